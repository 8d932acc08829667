//! The networks at their working stroke (issue 48): the large-deflection structure built
//! from a network's description, against the linear model at a vanishing stroke, against the
//! nonlinear finite elements of wei2017's part at its stroke, and against the elastica of a
//! parallelogram's leaves.

use std::path::Path;
use std::time::Instant;

use crate::common::table1_optimum;
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

/// wei2017's network at Table 1's optimum under the force that opens its input 17.4 um in a
/// linear solve, and twice it, against CalculiX's geometrically nonlinear solve of the
/// part (issue 48: quadratic plane-stress triangles on the exported outline, two meshes
/// agreeing to 0.01 %): the part is 16.6 % stiffer at the input (17.40 / 14.92 um) and
/// amplifies 2.9 % more (12.321 / 11.970); at twice the force 32.8 % and 4.9 %.
#[test]
fn wei2017_at_its_stroke_against_the_nonlinear_finite_elements() {
    let p = load("problems/wei2017_network.toml");
    let x = table1_optimum();
    let force = 17.4e-6 * output(&p, &x, "k_in");
    let measured = |factor: f64| {
        let options = StrokeOptions {
            elements: 8,
            steps: 10,
            critical_up_to: 0.0,
            force: Some(factor * force),
        };
        let r = at_stroke(&p, &x, &options);
        let end = r.at_stroke();
        (
            r.linear.stroke_in / end.stroke_in,
            end.amplification / r.linear.amplification,
        )
    };
    // the network's effect overshoots the part's by 20 % (stiffness) and 60 % (amplification)
    // at the stroke: the finding this test keeps, measured to 1 % of the effect; the FE's
    // figures bound it below and the effect stays within twice theirs
    for (factor, fe_k, fe_amp, k_measured, amp_measured) in [
        (1.0, 17.40 / 14.92, 12.321 / 11.970, 1.1989, 1.0461),
        (2.0, 34.80 / 26.21, 12.553 / 11.970, 1.3968, 1.0809),
    ] {
        let (k, amp) = measured(factor);
        println!(
            "wei2017_network at {factor} x {force:.2} N: k_in x {k:.4} (FE {fe_k:.4}), \
             amplification x {amp:.4} (FE {fe_amp:.4})"
        );
        assert!((k - k_measured).abs() < 1e-2 * (k_measured - 1.0), "{k}");
        assert!(
            (amp - amp_measured).abs() < 1e-2 * (amp_measured - 1.0),
            "{amp}"
        );
        assert!(k - 1.0 > fe_k - 1.0 && k - 1.0 < 2.0 * (fe_k - 1.0));
        assert!(amp - 1.0 > fe_amp - 1.0 && amp - 1.0 < 2.0 * (fe_amp - 1.0));
    }
    // one solve at the stroke (8 and 16 elements a flexure, 10 steps each) against one
    // linear evaluation of every output
    let options = StrokeOptions {
        force: Some(force),
        ..StrokeOptions::default()
    };
    let start = Instant::now();
    let r = at_stroke(&p, &x, &options);
    let nonlinear = start.elapsed().as_secs_f64();
    let m = &p.mechanism.physics;
    let all: Vec<usize> = (0..m.outputs().len()).collect();
    let mut out = vec![0.0; all.len()];
    let start = Instant::now();
    for _ in 0..1000 {
        m.evaluate(&x, &all, &mut out);
    }
    let linear = start.elapsed().as_secs_f64() / 1000.0;
    let (end, finer) = (r.at_stroke(), r.finer.as_ref().unwrap());
    println!(
        "wei2017_network: at stroke {nonlinear:.2e} s, linear {linear:.2e} s; n = 8 / 16: \
         stroke_out {:e} / {:e}, k_in {:e} / {:e}, critical load factor {:?}",
        end.stroke_out, finer.stroke_out, end.k_in, finer.k_in, r.critical_load_factor
    );
    assert!(rel(end.stroke_out, finer.stroke_out) < 1e-4);
    assert!(rel(end.k_in, finer.k_in) < 1e-4);
}

/// A parallelogram guide: two parallel strips `L` long from the ground to a stage, the stage
/// pushed across them by `delta`.
const PARALLELOGRAM: &str = r#"
name = "parallelogram"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
unit = "mm"
parameters = [["L", "length"], ["t", "length"]]

[[network.bodies]]
name = "stage"
outline = [["-5", "L"], ["25", "L"], ["25", "L + 5"], ["-5", "L + 5"]]

[[network.hinges]]
name = "left"
kind = "strip"
from = "ground"
to = "stage"
start = ["0", "0"]
angle = "90*deg"
l = "L"
t = "t"

[[network.hinges]]
name = "right"
kind = "strip"
from = "ground"
to = "stage"
start = ["20", "0"]
angle = "90*deg"
l = "L"
t = "t"

[network.input]
body = "stage"
at = ["10", "L"]
direction = ["1", "0"]

[[network.outputs]]
name = "stage"
body = "stage"
at = ["10", "L"]
direction = ["1", "0"]

[actuator]
nominal_stroke = "1 mm"
preload = "0 N"

[[variables]]
name = "L"
unit = "mm"
value = 20

[[variables]]
name = "t"
unit = "mm"
value = 0.3

[objective]
minimize = "k_in"
"#;

/// The parallelogram's stage, pushed 1 mm across its 20 mm leaves, sinks by each leaf's
/// shortening, `3/5 delta^2 / L` to the first order in `delta / L` (the guided beam's
/// kinematic coefficient: Awtar, Slocum and Sevincer, "Characteristics of Beam-Based
/// Flexure Modules", J. Mech. Des. 129 (2007) 625-639, Eq. 11 with no axial load: 30 um
/// here), and does not turn; the linear model has it move across its direction not at
/// all. 8 and 16 elements a leaf agree.
#[test]
fn a_parallelograms_stage_sinks_by_its_leaves_shortening() {
    let dir = std::env::temp_dir().join(format!("flexopt-stroke-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("parallelogram.toml");
    std::fs::write(&file, PARALLELOGRAM).unwrap();
    let p = Problem::load(&file).unwrap();
    let x = middle(&p);
    let r = at_stroke(&p, &x, &StrokeOptions::default());
    std::fs::remove_dir_all(&dir).unwrap();
    let end = r.at_stroke();
    let (delta, l) = (1e-3, 20e-3);
    assert!(rel(end.stroke_in, delta) < 1e-12, "{}", end.stroke_in);
    let sink = -end.parasitic[0].across;
    let first_order = 0.6 * delta * delta / l;
    println!("parallelogram: sink {sink:e} m against 3/5 delta^2 / L = {first_order:e} m");
    assert!(rel(sink, first_order) < 0.01, "{sink} {first_order}");
    assert!(r.linear.parasitic[0].across.abs() < 1e-9 * delta);
    let finer = r.finer.as_ref().unwrap();
    assert!(rel(-finer.parasitic[0].across, sink) < 1e-4);
}
