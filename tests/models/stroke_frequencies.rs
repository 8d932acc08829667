//! The natural frequencies at the working stroke (`nl_f1`, `nl_f2`, ...): listed where the
//! linear model has its `f1`, `f2`, ... and unavailable where it has not, for the same
//! reason; the solve over the stroke's at its end, its unloaded point the linear model's
//! (and columns of its curves beside the linear ones); and their gradients, the eigenvalue's
//! derivative at the equilibrium, against central differences of the values on every
//! shipped network that has frequencies.

use std::path::Path;

use crate::common::{design_within_bounds, rng};
use flexopt::model::large::report::StrokeOptions;
use flexopt::problem::Problem;
use flexopt::report::stroke::stroke_csv;

use super::stroke_gradients::central;

/// The shipped networks whose linear model has natural frequencies (a stack with its
/// stiffness, every body a mass, no support).
const WITH_FREQUENCIES: [&str; 3] = [
    "problems/bridge_lever_network.toml",
    "problems/lever_network.toml",
    "problems/scott_russell_network.toml",
];

/// Those without: no stack's stiffness.
const WITHOUT: [&str; 3] = [
    "problems/guide_network.toml",
    "problems/rhombus_network.toml",
    "problems/wei2017_network.toml",
];

/// `file`'s text, each line starting with a key of `replace` in its place, with the
/// outputs at stroke (`elements` a flexure, `steps` load steps).
fn large_with(file: &str, replace: &[(&str, &str)], elements: usize, steps: usize) -> Problem {
    let text = std::fs::read_to_string(file).unwrap();
    let text: Vec<String> = text
        .lines()
        .map(|line| {
            let key = line.split('=').next().unwrap_or("").trim();
            match replace.iter().find(|(k, _)| *k == key) {
                Some((k, v)) => format!("{k} = {v}"),
                None => line.to_string(),
            }
        })
        .collect();
    let text = format!(
        "{}\n[analysis]\ndeflection = \"large\"\nelements = {elements}\nsteps = {steps}\n",
        text.join("\n")
    );
    Problem::parse(Path::new(file), &text).unwrap()
}

/// The indices of `names` among `p`'s outputs.
fn indices(p: &Problem, names: &[String]) -> Vec<usize> {
    let m = &p.mechanism.physics;
    names.iter().map(|n| m.output_index(n).unwrap()).collect()
}

/// `nl_f1` .. `nl_f3` are listed on every network; where the linear model has no `f_i`,
/// `nl_f_i` has none either and says the same; where it has, it has a value.
#[test]
fn the_frequencies_at_stroke_are_where_the_linear_models_are() {
    for file in WITH_FREQUENCIES.iter().chain(&WITHOUT) {
        let p = large_with(file, &[], 4, 4);
        let m = &p.mechanism.physics;
        for i in 1..=3 {
            let (f, nl) = (format!("f{i}"), format!("nl_f{i}"));
            let (f, nl) = (m.output_index(&f).unwrap(), m.output_index(&nl).unwrap());
            let (why_f, why_nl) = (m.unavailable(f), m.unavailable(nl));
            assert_eq!(why_f.is_some(), why_nl.is_some(), "{file} f{i}");
            if let (Some(a), Some(b)) = (why_f, why_nl) {
                assert_eq!(a.replace("\"f", "\"nl_f"), b, "{file}");
            }
        }
        let has = m.unavailable(m.output_index("nl_f1").unwrap()).is_none();
        assert_eq!(has, WITH_FREQUENCIES.contains(file), "{file}");
    }
}

/// The outputs equal the solve over the stroke at its end, whose curves have a column a
/// frequency beside the linear model's (the same over the stroke): the unloaded point's the
/// linear model's, to 1e-9.
#[test]
fn the_solve_over_the_stroke_has_the_frequencies_in_its_curves() {
    let file = WITH_FREQUENCIES[1];
    let p = large_with(file, &[], 8, 10);
    let m = &p.mechanism.physics;
    let x = design_within_bounds(&p, &mut rng(48));
    let options = StrokeOptions {
        critical_up_to: 0.0,
        ..StrokeOptions::default()
    };
    let report = p.mechanism.large.as_ref().unwrap();
    let report = report.at_stroke(&x, &options).unwrap();
    let names = ["f1", "f2", "f3", "nl_f1", "nl_f2", "nl_f3"].map(String::from);
    let wanted = indices(&p, &names);
    let mut out = vec![0.0; wanted.len()];
    m.evaluate(&x, &wanted, &mut out);
    let (linear, at) = out.split_at(3);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    let end = &report.at_stroke().frequencies;
    let unloaded = &report.curve[0].frequencies;
    assert_eq!((end.len(), report.linear.frequencies.len()), (3, 3));
    for i in 0..3 {
        assert!(
            close(end[i], at[i]),
            "f{}: {} against {}",
            i + 1,
            end[i],
            at[i]
        );
        assert!(close(report.linear.frequencies[i], linear[i]), "f{}", i + 1);
        assert!(close(unloaded[i], linear[i]), "f{}", i + 1);
    }
    let csv = stroke_csv(&report);
    let header = csv.lines().next().unwrap();
    assert!(header.ends_with(",f3_Hz,linear_f3_Hz"), "{header}");
    let last: Vec<f64> = (csv.lines().last().unwrap().split(','))
        .map(|v| v.parse().unwrap())
        .collect();
    let n = last.len();
    assert!(
        close(last[n - 2], at[2]) && close(last[n - 1], linear[2]),
        "{last:?}"
    );
    // a force in the stack's place has no stack to stand on: no frequencies
    let forced = StrokeOptions {
        force: Some(10.0),
        ..options
    };
    let forced = p.mechanism.large.as_ref().unwrap().at_stroke(&x, &forced);
    assert!(forced.unwrap().linear.frequencies.is_empty());
}

/// Each frequency's gradient at stroke against differences of its value, at two designs
/// within each shipped network's bounds that has frequencies (4 elements a flexure, 4 load
/// steps: the derivatives are exact for any discretisation). The differences take a step of
/// 1e-3 of the parameter's range with Richardson's extrapolation of two central differences
/// (`(4 D(h/2) - D(h)) / 3`, its error of order `h^4`), against the path's noise of about
/// 1e-10 of the values. Each error is the frequency's change over the parameter's range,
/// relative to the largest such change of its gradient.
#[test]
fn frequency_gradients_at_stroke_equal_differences() {
    let mut r = rng(4850);
    let (mut compared, mut worst) = (0usize, 0.0f64);
    for file in WITH_FREQUENCIES {
        let p = large_with(file, &[], 4, 4);
        let m = &p.mechanism.physics;
        let wanted = indices(&p, &["nl_f1", "nl_f2", "nl_f3"].map(String::from));
        let n = m.parameters().len();
        for _ in 0..2 {
            let x = design_within_bounds(&p, &mut r);
            let (mut out, mut jac) = (vec![0.0; wanted.len()], vec![0.0; wanted.len() * n]);
            m.evaluate_with_gradient(&x, &wanted, &mut out, &mut jac);
            assert!(out.iter().all(|v| v.is_finite()), "{file}: {out:?}");
            let mut diff = vec![vec![0.0; n]; wanted.len()];
            for v in p.free_variables() {
                let (j, h) = (v.parameter, 1e-3 * (v.upper - v.lower));
                let (coarse, fine) = (
                    central(&p, &x, j, h, &wanted),
                    central(&p, &x, j, h / 2.0, &wanted),
                );
                for i in 0..wanted.len() {
                    diff[i][j] = (4.0 * fine[i] - coarse[i]) / 3.0;
                }
            }
            for (i, &w) in wanted.iter().enumerate() {
                let change =
                    |g: f64, u: &flexopt::problem::Variable| (g * (u.upper - u.lower)).abs();
                let scale = p
                    .free_variables()
                    .map(|u| change(jac[i * n + u.parameter], u))
                    .fold(f64::MIN_POSITIVE, f64::max);
                for v in p.free_variables() {
                    let j = v.parameter;
                    let error = change(diff[i][j] - jac[i * n + j], v) / scale;
                    worst = worst.max(error);
                    assert!(
                        error < 1e-6,
                        "{file} {} by {}: exact {} differences {} (error {error:e})",
                        m.outputs()[w].name,
                        m.parameters()[j].name,
                        jac[i * n + j],
                        diff[i][j]
                    );
                    compared += 1;
                }
            }
        }
    }
    eprintln!("frequency gradients at stroke: {compared} compared, worst {worst:e}");
    assert!(compared > 50, "{compared}");
}
