//! The outputs at the working stroke as a problem file asks for them (`[analysis]
//! deflection = "large"`): listed beside the linear ones, equal to the solve over the
//! stroke, and with exact gradients through the equilibrium (the implicit function theorem)
//! that central differences of the solve confirm on every shipped network.

use std::path::Path;

use crate::common::{design_within_bounds, rng};
use flexopt::model::large::report::StrokeOptions;
use flexopt::problem::Problem;

const NETWORKS: [&str; 6] = [
    "problems/bridge_lever_network.toml",
    "problems/guide_network.toml",
    "problems/lever_network.toml",
    "problems/rhombus_network.toml",
    "problems/scott_russell_network.toml",
    "problems/wei2017_network.toml",
];

/// `file` with `analysis` appended as its `[analysis]` section.
fn with_analysis(file: &str, analysis: &str) -> Result<Problem, String> {
    let text = std::fs::read_to_string(file).unwrap();
    let text = format!("{text}\n[analysis]\n{analysis}\n");
    Problem::parse(Path::new(file), &text).map_err(|e| e.to_string())
}

fn large(file: &str, elements: usize, steps: usize) -> Problem {
    let analysis = format!("deflection = \"large\"\nelements = {elements}\nsteps = {steps}");
    with_analysis(file, &analysis).unwrap()
}

/// The indices and names of the outputs at stroke.
fn at_stroke_outputs(p: &Problem) -> Vec<(usize, String)> {
    let m = &p.mechanism.physics;
    let outputs = m.outputs().iter().enumerate();
    outputs
        .filter(|(_, o)| o.name.starts_with("nl_"))
        .map(|(i, o)| (i, o.name.to_string()))
        .collect()
}

/// Without the key a network lists no output at stroke; with it, each equals the solve over
/// the stroke (`LargeDeflection::at_stroke`) at its end.
#[test]
fn the_outputs_at_stroke_are_the_solve_at_its_end() {
    let plain = Problem::load(Path::new(NETWORKS[5])).unwrap();
    assert!(at_stroke_outputs(&plain).is_empty());
    let p = large(NETWORKS[5], 8, 10);
    let names: Vec<String> = at_stroke_outputs(&p).into_iter().map(|o| o.1).collect();
    for name in [
        "nl_stroke_out",
        "nl_k_in",
        "nl_amplification",
        "nl_stress_max",
    ] {
        assert!(names.iter().any(|n| n == name), "{name} in {names:?}");
    }
    let x = design_within_bounds(&p, &mut rng(48));
    let options = StrokeOptions {
        critical_up_to: 0.0,
        ..StrokeOptions::default()
    };
    let report = plain.mechanism.large.as_ref().unwrap();
    let end = report.at_stroke(&x, &options).unwrap();
    let end = end.at_stroke();
    let m = &p.mechanism.physics;
    let value = |name: &str| {
        let mut out = [0.0];
        m.evaluate(&x, &[m.output_index(name).unwrap()], &mut out);
        out[0]
    };
    for (name, expected) in [
        ("nl_stroke_in", end.stroke_in),
        ("nl_stroke_out", end.stroke_out),
        ("nl_amplification", end.amplification),
        ("nl_amplification_tangent", end.amplification_tangent),
        ("nl_k_in", end.k_in),
        ("nl_k_out", end.k_out),
        ("nl_stress_max", end.stress_max),
    ] {
        let got = value(name);
        assert!(
            (got - expected).abs() <= 1e-9 * expected.abs(),
            "{name}: {got} against the solve's {expected}"
        );
    }
}

/// Central differences of the outputs `wanted` along parameter `j` at `x` with step `h`.
pub(super) fn central(p: &Problem, x: &[f64], j: usize, h: f64, wanted: &[usize]) -> Vec<f64> {
    let m = &p.mechanism.physics;
    let (mut up, mut down) = (x.to_vec(), x.to_vec());
    up[j] += h;
    down[j] -= h;
    let (mut ou, mut od) = (vec![0.0; wanted.len()], vec![0.0; wanted.len()]);
    m.evaluate(&up, wanted, &mut ou);
    m.evaluate(&down, wanted, &mut od);
    ou.iter()
        .zip(&od)
        .map(|(u, d)| (u - d) / (2.0 * h))
        .collect()
}

/// Every output at stroke's gradient against differences of the solve, at three designs
/// within each shipped network's bounds (4 elements a flexure, 4 load steps, so the test
/// stays short: the derivatives are exact for any discretisation). The solve's values carry
/// a noise of about 1e-10 of themselves (the path's ends, polished by Newton, still differ
/// at that level from design to design), so the differences take a step of 1e-3 of the
/// parameter's range with Richardson's extrapolation of two central differences (`h` and
/// `h / 2`: `(4 D(h/2) - D(h)) / 3`, its error of order `h^4`). Each error is the output's
/// change over the parameter's range, against the larger of the gradient's largest such
/// change and 1e-5 of the largest output of its dimension.
#[test]
fn gradients_at_stroke_equal_differences_on_every_shipped_network() {
    let mut r = rng(4848);
    let (mut compared, mut worst) = (0usize, 0.0f64);
    for file in NETWORKS {
        let p = large(file, 4, 4);
        let m = &p.mechanism.physics;
        // the folded guide's first output is its lateral motion, 1e-7 of its stroke: the
        // difference of two leaves' shortenings, whose derivatives are round-off of theirs
        let cancels = |name: &str| {
            file.contains("guide")
                && [
                    "nl_stroke_out",
                    "nl_amplification",
                    "nl_amplification_tangent",
                ]
                .contains(&name)
        };
        let wanted: Vec<usize> = at_stroke_outputs(&p)
            .into_iter()
            .filter(|o| !cancels(&o.1))
            .map(|o| o.0)
            .collect();
        let n = m.parameters().len();
        for _ in 0..3 {
            let x = design_within_bounds(&p, &mut r);
            let (mut out, mut jac) = (vec![0.0; wanted.len()], vec![0.0; wanted.len() * n]);
            m.evaluate_with_gradient(&x, &wanted, &mut out, &mut jac);
            assert!(out.iter().all(|v| v.is_finite()), "{file}: {out:?}");
            // the largest output of each one's dimension: a motion against the strokes
            let dimension = |i: usize| m.outputs()[wanted[i]].dimension;
            let largest_of_kind = |i: usize| {
                (0..wanted.len())
                    .filter(|&k| dimension(k) == dimension(i))
                    .map(|k| out[k].abs())
                    .fold(0.0, f64::max)
            };
            for v in p.free_variables() {
                let (j, range) = (v.parameter, v.upper - v.lower);
                let h = 1e-3 * range;
                let (coarse, fine) = (
                    central(&p, &x, j, h, &wanted),
                    central(&p, &x, j, h / 2.0, &wanted),
                );
                for (i, &w) in wanted.iter().enumerate() {
                    let scale = p
                        .free_variables()
                        .map(|u| (jac[i * n + u.parameter] * (u.upper - u.lower)).abs())
                        .fold((1e-5 * largest_of_kind(i)).max(1e-300), f64::max);
                    let fd = (4.0 * fine[i] - coarse[i]) / 3.0;
                    let error = (fd - jac[i * n + j]).abs() * range / scale;
                    worst = worst.max(error);
                    assert!(
                        error < 1e-5,
                        "{file} {} by {}: exact {} differences {fd} (error {error:e} of the \
                         gradient's largest term)",
                        m.outputs()[w].name,
                        m.parameters()[j].name,
                        jac[i * n + j]
                    );
                    compared += 1;
                }
            }
        }
    }
    eprintln!("gradients at stroke: {compared} compared, worst {worst:e}");
    assert!(compared > 500, "{compared}");
}

/// The section's keys refused with the key named: an unknown deflection, a count out of
/// range, and the solve's settings without large deflection.
#[test]
fn the_analysis_section_refuses_what_it_cannot_do() {
    let file = NETWORKS[2];
    for (analysis, key, says) in [
        ("deflection = \"medium\"", "deflection", "medium"),
        (
            "deflection = \"large\"\nelements = 0",
            "elements",
            "from 1 to 64",
        ),
        (
            "deflection = \"large\"\nsteps = 1000",
            "steps",
            "from 1 to 200",
        ),
        ("elements = 16", "deflection", "deflection = \"large\""),
    ] {
        let Err(err) = with_analysis(file, analysis) else {
            panic!("{analysis}: accepted");
        };
        assert!(
            err.contains(&format!("analysis.{key}")) && err.contains(says),
            "{analysis}: {err}"
        );
    }
}

/// An output at stroke has first derivatives only: a robust study over it is refused,
/// naming the objective that uses it; a tolerance on E is not (it needs first derivatives).
#[test]
fn a_robust_study_refuses_an_output_at_stroke() {
    let file = NETWORKS[2];
    let text = std::fs::read_to_string(file).unwrap().replace(
        "maximize = \"amplification\"",
        "maximize = \"nl_amplification\"",
    );
    let text = format!("{text}\n[analysis]\ndeflection = \"large\"\n");
    let with_e = format!("{text}\n[tolerances]\nyoungs_modulus = {{ plus_minus = 0.03 }}\n");
    let p = Problem::parse(Path::new(file), &with_e).unwrap();
    assert!(p
        .tolerances
        .iter()
        .any(|t| t.input == flexopt::problem::tolerances::Input::Modulus));
    let robust = text.replace("[search]\n", "[search]\nrobust = { yield = 0.99 }\n");
    let err = Problem::parse(Path::new(file), &robust)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("objective") && err.contains("working stroke") && err.contains("robust"),
        "{err}"
    );
}

/// The outputs at stroke under the moduli scaled by `m` (a tolerance on E) are those of the
/// same network whose material's modulus is `m` times its own, and their derivative by `m`
/// is the difference of the scaled solve's.
#[test]
fn the_outputs_at_stroke_scale_with_the_modulus() {
    let file = NETWORKS[2];
    let p = large(file, 4, 4);
    let scaling = p.mechanism.modulus.as_ref().unwrap();
    let wanted: Vec<usize> = at_stroke_outputs(&p).iter().map(|o| o.0).collect();
    let x = design_within_bounds(&p, &mut rng(49));
    let (n, k) = (x.len(), wanted.len());
    let m = 1.1;
    let mut scaled = vec![0.0; k];
    scaling.evaluate_scaled(&x, m, &wanted, &mut scaled);
    // the same network of a material m times as stiff (Poisson's ratio kept)
    let e = flexopt::model::material::Material::preset("al7075-t6")
        .unwrap()
        .youngs_modulus;
    let text = std::fs::read_to_string(file).unwrap().replace(
        "preset = \"al7075-t6\"",
        &format!(
            "preset = \"al7075-t6\"\nyoungs_modulus = \"{:e} Pa\"",
            e * m
        ),
    );
    let text = format!("{text}\n[analysis]\ndeflection = \"large\"\nelements = 4\nsteps = 4\n");
    let stiffer = Problem::parse(Path::new(file), &text).unwrap();
    let mut direct = vec![0.0; k];
    stiffer.mechanism.physics.evaluate(&x, &wanted, &mut direct);
    for (i, (a, b)) in scaled.iter().zip(&direct).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * b.abs().max(1e-12),
            "output {}: {a} scaled against {b} of the stiffer material",
            wanted[i]
        );
    }
    // the derivative by the factor, the last of each row
    let (mut values, mut jacobian) = (vec![0.0; k], vec![0.0; k * (n + 1)]);
    scaling.evaluate_scaled_with_gradient(&x, 1.0, &wanted, &mut values, &mut jacobian);
    let differences = |h: f64| {
        let (mut up, mut down) = (vec![0.0; k], vec![0.0; k]);
        scaling.evaluate_scaled(&x, 1.0 + h, &wanted, &mut up);
        scaling.evaluate_scaled(&x, 1.0 - h, &wanted, &mut down);
        (up.iter().zip(&down))
            .map(|(u, d)| (u - d) / (2.0 * h))
            .collect::<Vec<_>>()
    };
    let (d1, d2) = (differences(1e-3), differences(5e-4));
    for i in 0..k {
        let richardson = (4.0 * d2[i] - d1[i]) / 3.0;
        let exact = jacobian[i * (n + 1) + n];
        let scale = values[i].abs().max(exact.abs());
        if scale == 0.0 {
            continue;
        }
        assert!(
            (exact - richardson).abs() <= 1e-6 * scale,
            "output {}: d/dm {exact} against differences {richardson}",
            wanted[i]
        );
    }
}
