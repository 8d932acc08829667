//! The frequencies at stroke on the shipped networks: unloaded the linear model's, at
//! stroke wei2017's part stiffer.

use std::path::Path;

use super::super::stroke::{build, Drive};
use super::*;
use crate::model::actuator::{Actuator, RawActuator};
use crate::model::large::solve::{continuation, Options};
use crate::model::material::{Material, RawMaterial};
use crate::model::network::file::describe;
use crate::model::network::raw::RawNetwork;
use crate::model::Model;
use crate::vocab::error::Locator;
use crate::vocab::sections::Sections;

const NETWORKS: [&str; 6] = [
    "bridge_lever",
    "guide",
    "lever",
    "rhombus",
    "scott_russell",
    "wei2017",
];

/// The network model a problem file's text `text` describes (its `[material]`,
/// `[network]` and `[actuator]`), `file` naming it.
fn model_of(file: &str, text: &str) -> NetworkModel {
    let loc = Locator::new(Path::new(file), text);
    let s = Sections::new(&loc, text, "network");
    let m: RawMaterial = s.required("material").unwrap();
    let n: RawNetwork = s.required("network").unwrap();
    let a: RawActuator = s.required("actuator").unwrap();
    NetworkModel::new(
        describe(&s, &n).unwrap(),
        Material::from_section(&s, &m).unwrap(),
        Actuator::read(&s, &a).unwrap(),
    )
}

/// The shipped network `name`'s model and the design of its `optimum.json`.
fn shipped(name: &str) -> (NetworkModel, Vec<f64>) {
    let file = format!("problems/{name}_network.toml");
    let model = model_of(&file, &std::fs::read_to_string(&file).unwrap());
    // the optimum's design (SI) by parameter, read as its file writes it
    let optimum = format!("results/{name}_network/optimum.json");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(optimum).unwrap()).unwrap();
    let x = model
        .parameters()
        .iter()
        .map(|p| json["design_si"][p.name.as_ref()].as_f64().unwrap())
        .collect();
    (model, x)
}

fn linear(model: &NetworkModel, x: &[f64], name: &str) -> f64 {
    let i = model.output_index(name).unwrap();
    let mut out = [0.0];
    model.evaluate(x, &[i], &mut out);
    out[0]
}

/// The first `count` frequencies at the unloaded state and at the full stroke, with
/// `elements` a flexure.
fn unloaded_and_stroke(name: &str, elements: usize, count: usize) -> [Vec<f64>; 2] {
    let (model, x) = shipped(name);
    let built = build(&model, &x, elements, Drive::Stack).unwrap();
    let zero = vec![0.0; 3 * built.driven.nodes.len()];
    let unloaded = frequencies_at(&model, &x, &built, &zero, 0.0, count).unwrap();
    let opts = Options {
        steps: 8,
        ..Options::default()
    };
    let path = continuation(&built.driven, 1.0, &opts).unwrap();
    let end = path.points.last().unwrap();
    let at = frequencies_at(&model, &x, &built, &end.displacement, end.lambda, count);
    [unloaded, at.unwrap()]
}

/// Unloaded, the frequencies are the linear model's `f1` and `f2` on every shipped
/// network that has them, with 1 and 4 elements a flexure (the structure's unloaded
/// stiffness is the linear network's for any number).
#[test]
fn unloaded_they_are_the_linear_models() {
    let mut compared = 0;
    for name in NETWORKS {
        let (model, x) = shipped(name);
        let f1 = model.output_index("f1").unwrap();
        if model.unavailable(f1).is_some() {
            continue;
        }
        let expected = [linear(&model, &x, "f1"), linear(&model, &x, "f2")];
        for elements in [1, 4] {
            let built = build(&model, &x, elements, Drive::Stack).unwrap();
            let zero = vec![0.0; 3 * built.driven.nodes.len()];
            let got = frequencies_at(&model, &x, &built, &zero, 0.0, 2).unwrap();
            for (g, e) in got.iter().zip(expected) {
                let rel = (g - e).abs() / e;
                eprintln!("{name} n {elements}: {g} Hz against {e} Hz, {rel:.1e}");
                assert!(rel < 1e-8, "{name} n {elements}: {g} against {e}");
            }
        }
        compared += 1;
    }
    assert_eq!(compared, 3, "bridge_lever, lever and scott_russell have f1");
}

/// wei2017's network at its optimum, its stack rigid (the file gives it no stiffness):
/// the first frequency rises at the full stroke, the part stiffer there; 8 and 16
/// elements a flexure agree.
#[test]
fn wei2017_stiffens_at_its_stroke() {
    let [unloaded, at] = unloaded_and_stroke("wei2017", 8, 2);
    let [_, finer] = unloaded_and_stroke("wei2017", 16, 2);
    let ratio = at[0] / unloaded[0];
    let n_2n = (finer[0] - at[0]).abs() / finer[0];
    eprintln!(
        "wei2017: f1 {} Hz unloaded, {} Hz at stroke ({ratio}), {} Hz with 16 elements \
         ({n_2n:.1e}); f2 {} -> {}",
        unloaded[0], at[0], finer[0], unloaded[1], at[1]
    );
    assert!(ratio > 1.0, "{ratio}");
    assert!(n_2n < 1e-3, "{n_2n}");
}

/// A strip cantilevered from the ground carrying a square block, its stack pushing the block
/// away from the root along the strip (a tension in it), the block's side motion read.
const CANTILEVER: &str = r#"
[material]
preset = "al7075-t6"

[network]
width = "10 mm"
unit = "mm"
parameters = [["t", "length"]]

[[network.bodies]]
name = "block"
outline = [["20", "-2"], ["24", "-2"], ["24", "2"], ["20", "2"]]

[[network.hinges]]
name = "leaf"
kind = "strip"
from = "ground"
to = "block"
start = ["0", "0"]
angle = "0"
l = "20"
t = "t"

[network.input]
body = "block"
at = ["20", "0"]
direction = ["1", "0"]

[[network.outputs]]
name = "side"
body = "block"
at = ["22", "0"]
direction = ["0", "1"]

[actuator]
nominal_stroke = "1 um"
preload = "5 N"
stiffness = "1 N/um"
"#;

/// The stiffness of a beam-column's free end `(v, theta)` (the other end clamped) under
/// an axial tension `p`: `EI v'''' - p v'' = 0`, `v = A + B x + C cosh(kx) + D sinh(kx)`,
/// `k^2 = p / EI`, its end force `-EI v''' + p v'` and moment `EI v''` (Timoshenko and
/// Gere, *Theory of Elastic Stability*, 2nd ed., McGraw-Hill 1961, sec. 1.10).
fn beam_column_end(ei: f64, p: f64, l: f64) -> [[f64; 2]; 2] {
    let k = (p / ei).sqrt();
    let (sh, ch) = ((k * l).sinh(), (k * l).cosh());
    // v(0) = v'(0) = 0: A = -C, B = -k D; the end's (v, v') from (C, D)
    let g = [[ch - 1.0, sh - k * l], [k * sh, k * (ch - 1.0)]];
    let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    let mut out = [[0.0; 2]; 2];
    for (col, end) in [[1.0, 0.0], [0.0, 1.0]].iter().enumerate() {
        let c = (end[0] * g[1][1] - g[0][1] * end[1]) / det;
        let d = (g[0][0] * end[1] - g[1][0] * end[0]) / det;
        let v2 = k * k * (c * ch + d * sh);
        let v3 = k * k * k * (c * sh + d * ch);
        out[0][col] = -ei * v3 + p * end[1];
        out[1][col] = ei * v2;
    }
    out
}

/// The lowest root of `det(K - w^2 M) = 0` of two degrees of freedom (Hz).
fn lowest_of_two(k: [[f64; 2]; 2], m: [[f64; 2]; 2]) -> f64 {
    let a = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let b = k[0][0] * m[1][1] + k[1][1] * m[0][0] - k[0][1] * m[1][0] - k[1][0] * m[0][1];
    let c = k[0][0] * k[1][1] - k[0][1] * k[1][0];
    let w2 = (b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    w2.sqrt() / (2.0 * std::f64::consts::PI)
}

/// The cantilever's first mode, the block swaying on the strip, at the stack's full stroke:
/// the beam-column's end stiffness under the strip's tension `P` (from the stack, `k_a (X -
/// delta) + F_pre` at the block's motion `delta`), less the stack's own sway `P / l` (a
/// pushing spring of length `l`, 1 m behind the input and stretched by `delta`), on the
/// block's mass and inertia carried to the strip's end. The corotational chain tends to the
/// beam-column as its elements shorten (Richardson's extrapolation of 16 and 32 elements);
/// the strip's shear compliance, which the beam-column leaves out, is `(1 + nu) t^2 / (2
/// L^2)` of its bending's, 7e-5.
#[test]
fn a_cantilever_in_tension_sways_as_the_beam_column() {
    let model = model_of("cantilever.toml", CANTILEVER);
    let t = 0.2e-3;
    let x = [t];
    let (material, _) = model.material_and_actuator();
    let (e, rho, w, l) = (material.youngs_modulus, material.density, 0.01, 0.02);
    let ei = e * w * t.powi(3) / 12.0;
    let sway = |elements: usize| {
        let built = build(&model, &x, elements, Drive::Stack).unwrap();
        let opts = Options {
            steps: 4,
            ..Options::default()
        };
        let path = continuation(&built.driven, 1.0, &opts).unwrap();
        let end = path.points.last().unwrap();
        let f = frequencies_at(&model, &x, &built, &end.displacement, end.lambda, 1);
        let delta = end.displacement[3 * built.ports[0].node];
        (f.unwrap()[0], delta)
    };
    let ((coarse, _), (fine, delta)) = (sway(16), sway(32));
    let extrapolated = (4.0 * fine - coarse) / 3.0;
    let p = 1e6 * (1e-6 - delta) + 5.0;
    let mut k = beam_column_end(ei, p, l);
    k[0][0] -= p / (1.0 + delta);
    // the block: 4 mm square, its centroid 2 mm beyond the strip's end
    let (mass, c) = (rho * w * 16e-6, 2e-3);
    let j = mass * 32e-6 / 12.0;
    let m = [[mass, mass * c], [mass * c, j + mass * c * c]];
    let exact = lowest_of_two(k, m);
    let cantilever = [
        [12.0 * ei / l.powi(3), -6.0 * ei / (l * l)],
        [-6.0 * ei / (l * l), 4.0 * ei / l],
    ];
    let unloaded = lowest_of_two(cantilever, m);
    let rel = (extrapolated - exact).abs() / exact;
    eprintln!(
        "cantilever: P {p} N (kL {}), f1 {coarse} / {fine} -> {extrapolated} Hz against the \
         beam-column's {exact} ({rel:.1e}); unloaded {unloaded} Hz",
        (p / ei).sqrt() * l
    );
    assert!(exact / unloaded > 1.05, "the tension stiffens it");
    assert!(rel < 2e-4, "{extrapolated} against {exact}");
}
