//! Issue 12, first part: a design that did not converge is never reported as converged,
//! tolerances outside a sensible range are refused, counts have limits, and messages show
//! the bad value.

mod common;

use std::path::Path;

use common::flexopt;
use flexopt::optim::Status;
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};

const FILE: &str = "problems/wei2017.toml";

fn wei2017_with(from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(FILE).unwrap();
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("flexopt-honest-{}-{name}", std::process::id()))
}

#[test]
fn tolerances_outside_the_sensible_range_are_refused() {
    for bad in ["10", "1e-300", "0.01", "1e-15"] {
        let text = wei2017_with("tolerance = 1e-10", &format!("tolerance = {bad}"));
        let e = Problem::parse(Path::new("t.toml"), &text).unwrap_err();
        assert_eq!(e.key, "search.tolerance", "{e}");
        assert!(
            e.to_string().contains("must lie between 1e-14 and 1e-3"),
            "{e}"
        );
    }
    for good in ["1e-14", "1e-3", "1e-8"] {
        let text = wei2017_with("tolerance = 1e-10", &format!("tolerance = {good}"));
        assert!(Problem::parse(Path::new("t.toml"), &text).is_ok(), "{good}");
    }
}

#[test]
fn the_optimum_comes_from_a_converged_start_when_one_exists() {
    // 15 iterations: 8 starts converge, 292 stop at the limit (some of them feasible)
    let text = wei2017_with("max_iterations = 500", "max_iterations = 15");
    let problem = Problem::parse(Path::new("t.toml"), &text).unwrap();
    let s = study::run(&problem, &StudyOptions::from_problem(&problem));
    let e = s.ends;
    assert!(e.converged > 0 && e.iteration_limit > 0, "{e:?}");
    assert_eq!(
        e.converged + e.iteration_limit + e.infeasible + e.failed,
        300
    );
    assert!(s.best_converged);
    let best = &s.runs[s.best];
    assert_eq!(best.solution.status, Status::Converged);
    assert!(best.feasible);
    for r in s.runs.iter().filter(|r| r.feasible) {
        if r.solution.status == Status::Converged {
            assert!(
                r.objective <= best.objective,
                "{} > {}",
                r.objective,
                best.objective
            );
        }
    }
}

#[test]
fn a_run_without_a_converged_start_says_so_and_exits_4() {
    let file = temp("limit.toml");
    std::fs::write(
        &file,
        wei2017_with("max_iterations = 500", "max_iterations = 6"),
    )
    .unwrap();
    let out_dir = temp("limit-out");
    let out = flexopt(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(out.status.code(), Some(4));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stdout.contains("ends: 0 converged, 300 at the iteration limit"),
        "{stdout}"
    );
    assert!(stdout.contains("NOT CONVERGED"), "{stdout}");
    assert!(stderr.contains("no feasible start converged"), "{stderr}");
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("optimum.json")).unwrap())
            .unwrap();
    assert_eq!(optimum["converged"], false);
    assert_eq!(optimum["ends"]["iteration_limit"], 300);
    std::fs::remove_dir_all(&out_dir).unwrap();
    std::fs::remove_file(&file).unwrap();
}

#[test]
fn the_summary_counts_every_end() {
    let out_dir = temp("summary-out");
    let out = flexopt(&["run", FILE, "--out", out_dir.to_str().unwrap(), "--quiet"]);
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("ends: 300 converged, 0 at the iteration limit, 0 infeasible, 0 failed"),
        "{stdout}"
    );
    std::fs::remove_dir_all(&out_dir).unwrap();
}

#[test]
fn a_huge_file_is_refused_before_it_is_read() {
    let file = temp("huge.toml");
    std::fs::write(&file, "x".repeat(2 << 20)).unwrap();
    let out = flexopt(&["eval", file.to_str().unwrap(), "--design", "l2=1"]);
    std::fs::remove_file(&file).unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("huge.toml"), "{stderr}");
    assert!(
        stderr.contains("2097152 bytes") && stderr.contains("1 MiB"),
        "{stderr}"
    );
}

#[test]
fn a_sweep_has_a_limit_on_its_points() {
    let out = flexopt(&[
        "sweep",
        FILE,
        "--param",
        "l2",
        "--from",
        "1",
        "--to",
        "2",
        "--steps",
        "2000000000",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("`--steps`") && stderr.contains("at most 100000"),
        "{stderr}"
    );
    assert!(stderr.contains("2000000000"), "{stderr}");
}

#[test]
fn messages_show_the_bad_value() {
    let out = flexopt(&["run", FILE, "--threads", "1025", "--quiet"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("`--threads`") && stderr.contains("got 1025"),
        "{stderr}"
    );
    let text = wei2017_with("upper = 7e6", "upper = \"7e6 N/m\"");
    let e = Problem::parse(Path::new("t.toml"), &text).unwrap_err();
    assert_eq!(e.key, "constraints[3].upper", "{e}");
    assert!(
        e.to_string().contains("expected a number, got \"7e6 N/m\""),
        "{e}"
    );
}
