//! The natural frequencies of a network with mirror axes (issue 25): the rhombus described
//! as a quarter standing on its lower output block, which the model joins to its image
//! across the x axis, against the same rhombus described by hand as the half whose lower
//! block is the ground: the same modes, values and gradients, with and without a payload;
//! and that half, whose modes the model finds family by family (symmetric and
//! antisymmetric about the y axis), against the whole rhombus described by hand with no
//! mirror axis at all.

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
    half_on(payload, ACTUATOR)
}

/// [`half`] on the stack `actuator` (its `[actuator]` stiffness line).
fn half_on(payload: &str, actuator: &str) -> Problem {
    let text = format!(
        r#"
name = "rhombus_half"
model = "network"
{HEAD}mirror = ["y"]

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
"#
    ) + &rest(payload, actuator);
    Problem::parse(Path::new("rhombus_half.toml"), &text).unwrap()
}

/// The whole rhombus on its lower block, no mirror axis: both input blocks, the whole upper
/// block, the four leaves (the right ones written from the blocks on the axis, so that
/// their angles are the left ones' without `pi`), the stack on the left block alone.
fn whole(payload: &str, actuator: &str) -> Problem {
    let text = format!(
        r#"
name = "rhombus_whole"
model = "network"
{HEAD}
[[network.bodies]]
name = "left"
outline = [["-L*cos(delta) - 11", "-4.5"], ["-L*cos(delta) - 5.5", "-4.5"], ["-L*cos(delta) - 5.5", "4.5"], ["-L*cos(delta) - 11", "4.5"]]

[[network.bodies]]
name = "right"
outline = [["L*cos(delta) + 5.5", "-4.5"], ["L*cos(delta) + 11", "-4.5"], ["L*cos(delta) + 11", "4.5"], ["L*cos(delta) + 5.5", "4.5"]]

[[network.bodies]]
name = "output"
outline = [["-4.5", "L*sin(delta) + 1.5"], ["4.5", "L*sin(delta) + 1.5"], ["4.5", "L*sin(delta) + 8"], ["-4.5", "L*sin(delta) + 8"]]

[[network.bodies]]
name = "ground"
outline = [["-4.5", "-L*sin(delta) - 8"], ["4.5", "-L*sin(delta) - 8"], ["4.5", "-L*sin(delta) - 1.5"], ["-4.5", "-L*sin(delta) - 1.5"]]

[[network.hinges]]
name = "left_arm"
kind = "strip"
from = "left"
to = "output"
start = ["-L*cos(delta) - 5", "3"]
angle = "delta"
l = "L"
t = "t"

[[network.hinges]]
name = "left_lower"
kind = "strip"
from = "left"
to = "ground"
start = ["-L*cos(delta) - 5", "-3"]
angle = "-delta"
l = "L"
t = "t"

[[network.hinges]]
name = "right_arm"
kind = "strip"
from = "output"
to = "right"
start = ["5", "L*sin(delta) + 3"]
angle = "-delta"
l = "L"
t = "t"

[[network.hinges]]
name = "right_lower"
kind = "strip"
from = "ground"
to = "right"
start = ["5", "-L*sin(delta) - 3"]
angle = "delta"
l = "L"
t = "t"

[network.input]
body = "left"
at = ["-L*cos(delta) - 8", "0"]
direction = ["-1", "0"]
"#
    ) + &rest(payload, actuator);
    Problem::parse(Path::new("rhombus_whole.toml"), &text).unwrap()
}

/// The start of both rhombi's `[network]`, after the name and the model.
const HEAD: &str = r#"
[material]
preset = "al7075-t6"

[network]
width = "10 mm"
unit = "mm"
parameters = [["L", "length"], ["delta", "angle"], ["t", "length"]]
"#;

/// What both rhombi share after their input: the output, the actuator, the variables.
fn rest(payload: &str, actuator: &str) -> String {
    format!(
        r#"
[[network.outputs]]
name = "out"
body = "output"
at = ["0", "L*sin(delta) + 6"]
direction = ["0", "-1"]
payload = "{payload}"

[actuator]
nominal_stroke = "17.4 um"
preload = "40 N"
{actuator}
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
    )
}

/// `f1` and `f2` with their gradients by the two variables.
fn frequencies(m: &dyn Model, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
    first_frequencies(m, x, 2)
}

/// `f1` to `f{count}` with their gradients.
fn first_frequencies(m: &dyn Model, x: &[f64], count: usize) -> (Vec<f64>, Vec<f64>) {
    let names: Vec<String> = (1..=count).map(|i| format!("f{i}")).collect();
    let wanted: Vec<usize> = names.iter().map(|n| m.output_index(n).unwrap()).collect();
    for &i in &wanted {
        assert_eq!(m.unavailable(i), None);
    }
    let (mut v, mut g) = (vec![0.0; count], vec![0.0; count * x.len()]);
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

/// The half's modes, family by family, are the whole rhombus's: `f1` to `f3` and their
/// gradients at 20 random designs, with and without a payload. The stack is made too soft to
/// count (1e-15 N/um, 1e-9 N/m, against the leaves' bending stiffness of some 1e4 N/m),
/// since the whole, with no mirror axis, can only put it between the left block and the
/// ground. Of the whole's nine modes, four are the half's symmetric ones and five its
/// antisymmetric ones (the upper block held from turning and moving sideways in the first,
/// from rising in the second), which a symmetric half alone would miss.
#[test]
fn the_halfs_families_of_modes_are_the_whole_rhombuss_modes() {
    let soft = "stiffness = \"1e-15 N/um\"\n";
    let mut r = rng(26);
    let mut worst = 0.0f64;
    for payload in ["0 g", "10 g"] {
        let (h, w) = (half_on(payload, soft), whole(payload, soft));
        for _ in 0..10 {
            let x = vec![
                r.random_range(5e-3..20e-3),
                r.random_range(0.5f64..45.0).to_radians(),
                0.4e-3,
            ];
            let (fh, gh) = first_frequencies(h.model(), &x, 3);
            let (fw, gw) = first_frequencies(w.model(), &x, 3);
            for (a, b) in fh.iter().zip(&fw) {
                worst = worst.max(rel(*a, *b, 0.0));
            }
            let n = x.len();
            for k in 0..3 {
                let scale = gw[k * n].abs() * 15e-3 + gw[k * n + 1].abs() * 0.77;
                for j in 0..2 {
                    worst = worst.max((gh[k * n + j] - gw[k * n + j]).abs() / scale);
                }
            }
        }
    }
    eprintln!("half against whole, worst relative difference {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
}
