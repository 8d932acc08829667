//! The part's first natural mode as a limit (issue 22, item 4): `first_frequency`, which
//! only the finite elements measure (the model's value stands in with the output mode's),
//! is met on the part by the refinement, and refused by every command that would meet it
//! with the model alone.

use crate::common;

use std::path::Path;

use common::flexopt;
use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::fe::Idealization;
use flexopt::problem::Problem;
use flexopt::refine::study::refine_study;
use flexopt::refine::RefineStatus;
use flexopt::study::{self, StudyOptions};

const FILE: &str = "problems/ti_first_mode.toml";
const LIMIT: f64 = 250.0;

/// The FE's first mode (plane strain, the refinement's idealization) at `x`, and its
/// estimated relative error, from a check of its own.
fn first_mode(p: &Problem, x: &[f64]) -> (f64, f64) {
    let v = verify_design(p.mechanism(), x, &VerifySettings::default()).unwrap();
    let r = v
        .results
        .iter()
        .find(|r| r.idealization == Idealization::PlaneStrain)
        .unwrap();
    let o = r
        .outputs
        .iter()
        .find(|o| o.name == "fe_natural_frequency")
        .unwrap();
    (o.estimate.value, o.estimate.relative_error.unwrap_or(0.0))
}

#[test]
fn the_refined_design_meets_the_first_mode_on_the_part_where_the_analytic_optimum_does_not() {
    let mut p = Problem::load(Path::new(FILE)).unwrap();
    // fewer starts and a looser refinement than the file's, to keep the test short: the
    // first mode converges on the first meshes, so the check below is as tight
    p.search.starts = 10;
    p.refine.tolerance = 0.05;
    let s = study::run(&p, &StudyOptions::from_problem(&p));
    let x0 = s.reported_design().to_vec();
    // the model meets the limit with the output mode's frequency; the part's sway is far below
    let model = p.model();
    let mut stand_in = [0.0];
    model.evaluate(
        &x0,
        &[model.output_index("first_frequency").unwrap()],
        &mut stand_in,
    );
    assert!(stand_in[0] >= LIMIT, "model {}", stand_in[0]);
    let (f0, _) = first_mode(&p, &x0);
    assert!(
        f0 < 0.7 * LIMIT,
        "the analytic optimum's first mode {f0} Hz"
    );
    let r = refine_study(&p, &s);
    let refinement = &r.all[r.chosen].1;
    assert_eq!(refinement.status, RefineStatus::Converged);
    let x = &refinement.result.as_ref().unwrap().x;
    let (f, e) = first_mode(&p, x);
    assert!(
        f >= LIMIT * (1.0 - e),
        "the refined design's first mode {f} Hz (+-{e})"
    );
    // and the output mode, above it, stays above the limit too
    let v = verify_design(p.mechanism(), x, &VerifySettings::default()).unwrap();
    let strain = v
        .results
        .iter()
        .find(|r| r.idealization == Idealization::PlaneStrain)
        .unwrap();
    let output_mode = strain
        .outputs
        .iter()
        .find(|o| o.name == "fe_output_frequency")
        .unwrap()
        .estimate
        .value;
    assert!(
        output_mode >= f,
        "output mode {output_mode} Hz under the first {f} Hz"
    );
}

#[test]
fn a_first_mode_limit_is_refused_without_the_refinement_and_marked_where_shown() {
    let dir = std::env::temp_dir().join(format!("flexopt-first-mode-{}", std::process::id()));
    let out_dir = dir.join("out");
    let out = flexopt(&[
        "run",
        FILE,
        "--refine",
        "none",
        "--quiet",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("{FILE}: key `constraints[5].output`"))
            && stderr
                .contains("\"first_frequency\" is measured by the part's finite elements only")
            && stderr.contains("run --refine fe"),
        "{stderr}"
    );
    assert!(
        !out_dir.exists(),
        "an unrefined run wrote {}",
        out_dir.display()
    );
    // a front is a set of analytic optima
    let out = flexopt(&[
        "pareto",
        FILE,
        "--vary",
        "k_in",
        "--from",
        "5e6",
        "--to",
        "7e6",
        "--steps",
        "2",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("a front would meet it"), "{stderr}");
    assert!(!out_dir.exists());
    // eval reports no analytic first mode; the limit on it says what the model's value is
    let design = "l2=3.68,delta2=4.37,t2=0.4,l3=4.67,delta3=4.25,l4=3.69,delta4=4.32,t4=0.4";
    let out = flexopt(&["eval", FILE, "--design", design, "--format", "json"]);
    assert_eq!(out.status.code(), Some(0));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(json["outputs"].get("first_frequency").is_none());
    assert!(json["outputs"]["output_frequency"].as_f64().unwrap() > 0.0);
    let limit = &json["constraints"][5];
    assert_eq!(limit["output"], "first_frequency");
    assert!(
        limit["stand_in"]
            .as_str()
            .unwrap()
            .starts_with("output_frequency"),
        "{limit}"
    );
    // a sweep neither
    let out = flexopt(&[
        "sweep",
        FILE,
        "--param",
        "t2",
        "--from",
        "0.4",
        "--to",
        "0.5",
        "--steps",
        "2",
        "--outputs",
        "first_frequency",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("`verify` measures it"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}
