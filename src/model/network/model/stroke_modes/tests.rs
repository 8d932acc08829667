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
