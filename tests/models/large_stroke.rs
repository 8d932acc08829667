//! The networks at their working stroke (issue 48): the large-deflection structure built
//! from a network's description, against the linear model at a vanishing stroke, against the
//! nonlinear finite elements of wei2017's part at its stroke, and against the elastica of a
//! parallelogram's leaves.

use std::path::Path;

use flexopt::model::large::report::{StrokeOptions, StrokeReport};
use flexopt::problem::Problem;

/// Each shipped network and its stack's preload over its stiffness times its free stroke,
/// `P / (k_a X)`, from its `[actuator]` (0 for a stack without a stiffness, which prescribes
/// the input's motion).
const NETWORKS: [(&str, f64); 6] = [
    ("problems/bridge_lever_network.toml", 20.0 / 900.0),
    ("problems/guide_network.toml", 0.0),
    ("problems/lever_network.toml", 20.0 / 900.0),
    ("problems/rhombus_network.toml", 0.0),
    ("problems/scott_russell_network.toml", 20.0 / 900.0),
    ("problems/wei2017_network.toml", 0.0),
];

fn load(file: &str) -> Problem {
    Problem::load(Path::new(file)).unwrap()
}

/// The middle of each variable's range.
fn middle(p: &Problem) -> Vec<f64> {
    let mut x = vec![0.0; p.mechanism.physics.parameters().len()];
    for v in &p.variables {
        x[v.parameter] = 0.5 * (v.lower + v.upper);
    }
    x
}

fn output(p: &Problem, x: &[f64], name: &str) -> f64 {
    let m = &p.mechanism.physics;
    let i = m.output_index(name).unwrap_or_else(|| panic!("{name}"));
    let mut out = [0.0];
    m.evaluate(x, &[i], &mut out);
    out[0]
}

fn at_stroke(p: &Problem, x: &[f64], options: &StrokeOptions) -> StrokeReport {
    let large = p
        .mechanism
        .large
        .as_ref()
        .expect("a network solves at stroke");
    large.at_stroke(x, options).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// At the unloaded point the tangent stiffnesses and amplification are the linear model's,
/// and the linear solution of the stack's load is Eq. 13's stroke with the preload's share:
/// every shipped network, 1 and 3 elements a flexure.
#[test]
fn a_vanishing_stroke_is_the_linear_network() {
    for (file, p_over_kx) in NETWORKS {
        let p = load(file);
        let x = middle(&p);
        for elements in [1, 3] {
            let options = StrokeOptions {
                elements,
                steps: 2,
                critical_up_to: 0.0,
                force: None,
            };
            let r = at_stroke(&p, &x, &options);
            let start = &r.curve[0];
            let (k_in, amp) = (output(&p, &x, "k_in"), output(&p, &x, "amplification"));
            assert!(
                rel(start.k_in, k_in) < 1e-9,
                "{file} n {elements}: k_in {} {k_in}",
                start.k_in
            );
            assert!(
                // an output across the input's motion (the guide's lateral) moves by rounding
                (start.amplification_tangent - amp).abs() < 1e-9 * amp.abs().max(1.0),
                "{file} n {elements}: amplification {} {amp}",
                start.amplification_tangent
            );
            assert!(rel(r.linear.k_in, k_in) < 1e-9);
            let k_out = output(&p, &x, "k_out");
            assert!(
                rel(start.k_out, k_out) < 1e-9,
                "{file}: k_out {} {k_out}",
                start.k_out
            );
            // the linear solution: Eq. 13's true stroke, the preload's share added where the
            // stack has a stiffness (it pushes with it from the unloaded part)
            let stroke_in = output(&p, &x, "stroke_in");
            assert!(
                rel(r.linear.stroke_in, stroke_in * (1.0 + p_over_kx)) < 1e-9,
                "{file}: stroke_in {} {stroke_in}",
                r.linear.stroke_in
            );
            let stroke_out = output(&p, &x, "stroke_out");
            assert!(
                (r.linear.stroke_out - stroke_out * (1.0 + p_over_kx)).abs()
                    < 1e-9 * stroke_out.abs().max(stroke_in.abs()),
                "{file}: stroke_out {} {stroke_out}",
                r.linear.stroke_out
            );
        }
    }
}
