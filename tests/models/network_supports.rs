//! Supports in one direction (`[[network.supports]]`, issue 51): a lever on a strip pivot
//! whose input face is held in x (a guide: free along y, free to turn), against the
//! compliance-matrix result written out here, the guide's reaction found from the pivot's
//! compliance at the lever alone; the same with the guide tilted, and a guide that also
//! holds the rotation; the gradients against central differences.

use std::path::Path;

use crate::common::{rel, rng};
use crate::network_shipped::worst_central_difference;
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use flexopt::model::Model;
use flexopt::problem::Problem;
use rand::Rng;

const WIDTH: f64 = 0.01;
const ARM: f64 = 0.03;

/// A lever from (0, 0) to (30 mm, 0) on a strip of length `l` and thickness `t` from the
/// ground at (0, -l) up to (0, 0); pushed up at (a, 0), read up at its tip; held at the
/// input's point along `direction`, its rotation held too where `hold` says so. The stack
/// has a stiffness: a rigid one on a lever held in x and in rotation would hold it whole, and
/// its output stiffness with the stack in place would be infinite.
fn lever_text(direction: [&str; 2], hold: bool) -> String {
    format!(
        r#"
name = "guided"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
parameters = [["l", "length"], ["t", "length"], ["a", "length"]]

[[network.bodies]]
name = "lever"
link = {{ from = ["0", "0"], to = ["30", "0"], width = "3" }}

[[network.hinges]]
name = "pivot"
kind = "strip"
from = "ground"
to = "lever"
start = ["0", "-l"]
angle = "90*deg"
l = "l"
t = "t"

[[network.supports]]
body = "lever"
at = ["a", "0"]
direction = ["{}", "{}"]
hold_rotation = {hold}

[network.input]
body = "lever"
at = ["a", "0"]
direction = ["0", "1"]

[[network.outputs]]
name = "tip"
body = "lever"
at = ["30", "0"]
direction = ["0", "1"]

[actuator]
nominal_stroke = "10 um"
preload = "1 N"
stiffness = "50 N/um"

[[variables]]
name = "l"
unit = "mm"
lower = 0.5
upper = 3

[[variables]]
name = "t"
unit = "mm"
lower = 0.2
upper = 1

[[variables]]
name = "a"
unit = "mm"
lower = 2
upper = 8

[objective]
maximize = "amplification"
"#,
        direction[0], direction[1]
    )
}

fn lever(direction: [&str; 2], hold: bool) -> Problem {
    Problem::parse(Path::new("guided.toml"), &lever_text(direction, hold)).unwrap()
}

fn designs(seed: u64) -> Vec<Vec<f64>> {
    let mut r = rng(seed);
    (0..20)
        .map(|_| {
            vec![
                r.random_range(0.5e-3..3e-3),
                r.random_range(0.2e-3..1e-3),
                r.random_range(2e-3..8e-3),
            ]
        })
        .collect()
}

fn mat_vec(c: &[[f64; 3]; 3], f: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| c[i][0] * f[0] + c[i][1] * f[1] + c[i][2] * f[2])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The compliance-matrix answer, `(amplification, k_in)`: the lever's motion `(u, v,
/// theta)` at the pivot's end `Q = (0, 0)` is `C F_Q`, `C` the strip's compliance
/// `[c11 0 0; 0 c22 c23; 0 c23 c33]` turned from its frame (x up) to the plane's, `F_Q` the
/// loads carried to `Q` (a force `F` at `p` gives `(F_x, F_y, p_x F_y - p_y F_x)`). The
/// guide's reaction `R` along `n` at the input's point gives `b = (n_x, n_y, p_x n_y - p_y
/// n_x)` and holds `b . u = 0`, so `R = -b.C f / b.C b` under the unit input force `f`;
/// with the rotation held too, the reactions are a force along `n` and a moment, two
/// unknowns of the 2x2 system. The motion of a point `p` along y is `v + theta p_x`.
fn by_hand(x: &[f64], n: [f64; 2], hold: bool) -> (f64, f64) {
    let (l, t, a) = (x[0], x[1], x[2]);
    let c = HingeKind::Strip.compliance(&[l, t], WIDTH, &Material::al7075_t6());
    // the strip's frame: x along (0, 1), y along (-1, 0): u_local = (v, -u, theta)
    let cl = [[c.c11, 0.0, 0.0], [0.0, c.c22, c.c23], [0.0, c.c23, c.c33]];
    let turn = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let cg: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3)
                .flat_map(|p| (0..3).map(move |q| (p, q)))
                .map(|(p, q)| turn[p][i] * cl[p][q] * turn[q][j])
                .sum()
        })
    });
    let f = [0.0, 1.0, a];
    let b = [n[0], n[1], a * n[1]];
    let u = if n == [0.0, 0.0] {
        mat_vec(&cg, f)
    } else if hold {
        let m = [0.0, 0.0, 1.0];
        let (cb, cm, cf) = (mat_vec(&cg, b), mat_vec(&cg, m), mat_vec(&cg, f));
        // [b.Cb b.Cm; m.Cb m.Cm] [R; M] = -[b.Cf; m.Cf]
        let (g11, g12, g22) = (dot(b, cb), dot(b, cm), dot(m, cm));
        let (r1, r2) = (-dot(b, cf), -dot(m, cf));
        let det = g11 * g22 - g12 * g12;
        let (r, mo) = ((r1 * g22 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det);
        mat_vec(&cg, std::array::from_fn(|i| f[i] + r * b[i] + mo * m[i]))
    } else {
        let cb = mat_vec(&cg, b);
        let r = -dot(b, mat_vec(&cg, f)) / dot(b, cb);
        mat_vec(&cg, std::array::from_fn(|i| f[i] + r * b[i]))
    };
    let along_y = |px: f64| u[1] + u[2] * px;
    (along_y(ARM) / along_y(a), along_y(a).recip())
}

fn values(m: &dyn Model, x: &[f64]) -> [f64; 2] {
    let wanted = [
        m.output_index("amplification").unwrap(),
        m.output_index("k_in").unwrap(),
    ];
    let mut v = [0.0; 2];
    m.evaluate(x, &wanted, &mut v);
    v
}

fn worst_against_hand(direction: [&str; 2], n: [f64; 2], hold: bool, seed: u64) -> f64 {
    let p = lever(direction, hold);
    let mut worst = 0.0f64;
    for x in designs(seed) {
        let v = values(p.model(), &x);
        let (amplification, k_in) = by_hand(&x, n, hold);
        worst = worst
            .max(rel(v[0], amplification, 1e-300))
            .max(rel(v[1], k_in, 1e-300));
    }
    worst
}

/// The guided lever: the input's face held in x, free along y and to turn.
#[test]
fn a_lever_guided_in_x_is_its_compliance_matrix_answer() {
    let worst = worst_against_hand(["1", "0"], [1.0, 0.0], false, 511);
    eprintln!("lever guided in x against the compliance matrix: {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
    // the guide changes the answer: without it the pivot's end is free to sway
    let p = lever(["1", "0"], false);
    let x = [1e-3, 0.3e-3, 4e-3];
    let free = by_hand(&x, [0.0, 0.0], false);
    assert!(rel(values(p.model(), &x)[1], free.1, 1e-300) > 1e-6);
}

/// A guide along a tilted direction, and one that holds the rotation too.
#[test]
fn a_tilted_guide_and_a_held_rotation_are_their_compliance_matrix_answers() {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let tilted = worst_against_hand(["cos(30*deg)", "sin(30*deg)"], [c, s], false, 512);
    eprintln!("tilted guide {tilted:e}");
    assert!(tilted < 1e-9, "{tilted:e}");
    // a guide that holds the rotation too leaves the lever only its pivot's axial give: with
    // the stack blocked it is held whole, and the file is refused for its infinite output
    // stiffness (the model has no way yet to leave that output out)
    let refused = Problem::parse(Path::new("held.toml"), &lever_text(["1", "0"], true));
    let message = refused.expect_err("a lever held whole").to_string();
    assert!(
        message.contains("k_out_blocked") && message.contains("not finite"),
        "{message}"
    );
}

/// Every output's gradient of the guided lever against central differences.
#[test]
fn the_guided_levers_gradients_are_its_central_differences() {
    let p = lever(["1", "0"], false);
    let bounds = [(0.5e-3, 3e-3), (0.2e-3, 1e-3), (2e-3, 8e-3)];
    let ((worst, name), kinks, checks) =
        worst_central_difference(p.model(), &designs(514), &bounds, &[]);
    eprintln!("guided lever gradients: {worst:e} ({name}), {kinks} kinks in {checks} checks");
    assert!(
        checks > 0 && kinks * 50 < checks,
        "{kinks} kinks in {checks} checks"
    );
    assert!(worst < 1e-6, "{worst:e} ({name})");
}
