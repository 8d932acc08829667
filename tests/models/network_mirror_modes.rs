//! The natural frequencies of a network with mirror axes (issue 25): the rhombus described
//! as a quarter standing on its lower output block, which the model joins to its image
//! across the x axis, against the same rhombus described by hand as the half whose lower
//! block is the ground: the same modes, values and gradients, with and without a payload.

use std::path::Path;

use crate::common::{rel, rng};
use flexopt::model::Model;
use flexopt::problem::Problem;
use rand::Rng;

const ACTUATOR: &str = "stiffness = \"20 N/um\"\n";

/// The shipped rhombus with the actuator's stiffness and a payload on its output.
fn quarter(payload: &str) -> Problem {
    let text = std::fs::read_to_string("problems/rhombus_network.toml").unwrap();
    let text = text
        .replace(
            "preload = \"40 N\"\n",
            &format!("preload = \"40 N\"\n{ACTUATOR}"),
        )
        .replace(
            "across = \"x\"\n",
            &format!("across = \"x\"\npayload = \"{payload}\"\n"),
        );
    Problem::parse(Path::new("rhombus_quarter.toml"), &text).unwrap()
}

/// The same rhombus as its left half: the input block whole, the upper block cut by the y
/// axis, the lower block the ground, the lower arm its upper arm's mirror image.
fn half(payload: &str) -> Problem {
    let text = format!(
        r#"
name = "rhombus_half"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
unit = "mm"
parameters = [["L", "length"], ["delta", "angle"], ["t", "length"]]
mirror = ["y"]

[[network.bodies]]
name = "input"
outline = [["-L*cos(delta) - 11", "-4.5"], ["-L*cos(delta) - 5.5", "-4.5"], ["-L*cos(delta) - 5.5", "4.5"], ["-L*cos(delta) - 11", "4.5"]]

[[network.bodies]]
name = "output"
on_axis = ["y"]
outline = [["-4.5", "L*sin(delta) + 1.5"], ["0", "L*sin(delta) + 1.5"], ["0", "L*sin(delta) + 8"], ["-4.5", "L*sin(delta) + 8"]]

[[network.bodies]]
name = "ground"
outline = [["-4.5", "-L*sin(delta) - 8"], ["0", "-L*sin(delta) - 8"], ["0", "-L*sin(delta) - 1.5"], ["-4.5", "-L*sin(delta) - 1.5"]]

[[network.hinges]]
name = "arm"
kind = "strip"
from = "input"
to = "output"
start = ["-L*cos(delta) - 5", "3"]
angle = "delta"
l = "L"
t = "t"

[[network.hinges]]
name = "lower"
kind = "strip"
from = "input"
to = "ground"
start = ["-L*cos(delta) - 5", "-3"]
angle = "-delta"
l = "L"
t = "t"

[network.input]
body = "input"
at = ["-L*cos(delta) - 8", "0"]
direction = ["-1", "0"]
across = "y"

[[network.outputs]]
name = "out"
body = "output"
at = ["0", "L*sin(delta) + 6"]
direction = ["0", "-1"]
payload = "{payload}"

[actuator]
nominal_stroke = "17.4 um"
preload = "40 N"
{ACTUATOR}
[[variables]]
name = "L"
unit = "mm"
lower = 5
upper = 20

[[variables]]
name = "delta"
unit = "deg"
lower = 0.5
upper = 45

[[variables]]
name = "t"
unit = "mm"
value = 0.4

[objective]
maximize = "amplification"
"#
    );
    Problem::parse(Path::new("rhombus_half.toml"), &text).unwrap()
}

/// `f1` and `f2` with their gradients by the two variables.
fn frequencies(m: &dyn Model, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let wanted: Vec<usize> = ["f1", "f2"]
        .iter()
        .map(|n| m.output_index(n).unwrap())
        .collect();
    for &i in &wanted {
        assert_eq!(m.unavailable(i), None);
    }
    let (mut v, mut g) = (vec![0.0; 2], vec![0.0; 2 * x.len()]);
    m.evaluate_with_gradient(x, &wanted, &mut v, &mut g);
    (v, g)
}

#[test]
fn the_quarter_on_its_lower_block_is_the_half_on_its_ground() {
    let mut r = rng(25);
    let mut worst = 0.0f64;
    for payload in ["0 g", "10 g"] {
        let (q, h) = (quarter(payload), half(payload));
        for _ in 0..10 {
            let x = vec![
                r.random_range(5e-3..20e-3),
                r.random_range(0.5f64..45.0).to_radians(),
                0.4e-3,
            ];
            let (fq, gq) = frequencies(q.model(), &x);
            let (fh, gh) = frequencies(h.model(), &x);
            for (a, b) in fq.iter().zip(&fh) {
                worst = worst.max(rel(*a, *b, 0.0));
            }
            let n = x.len();
            for k in 0..2 {
                // each derivative against the frequency's change over the bounds
                let scale = gh[k * n].abs() * 15e-3 + gh[k * n + 1].abs() * 0.77;
                for j in 0..2 {
                    worst = worst.max((gq[k * n + j] - gh[k * n + j]).abs() / scale);
                }
            }
        }
    }
    eprintln!("quarter against half, worst relative difference {worst:e}");
    assert!(worst < 1e-10, "{worst:e}");
}
