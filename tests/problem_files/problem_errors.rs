//! Every rejection rule of the problem-file format: the message names the file, the key
//! path and the bad value; the CLI exits with code 2. The refused files are one table,
//! `refused.toml` ([`crate::rejected`]), which the JSON Schema's test reads too.

use crate::common;
use crate::rejected::{refused, Refused};

use std::path::Path;

use common::flexopt;
use flexopt::problem::design::parse_design;
use flexopt::problem::{Problem, ProblemError};

const FILE: &str = "problems/wei2017.toml";

fn original() -> String {
    std::fs::read_to_string(FILE).unwrap()
}

/// Parses the problem file with `from` replaced by `to` (which must occur).
fn mutated(from: &str, to: &str) -> Result<Problem, ProblemError> {
    let text = original();
    assert!(text.contains(from), "fixture text {from:?} not in {FILE}");
    Problem::parse(Path::new("mutated.toml"), &text.replacen(from, to, 1))
}

/// The refused case `id`, parsed: its error, whose key and words are checked.
fn refused_case(id: &str) -> ProblemError {
    let cases = refused();
    rejects(
        cases
            .iter()
            .find(|c| c.id == id)
            .expect("a case of the table"),
    )
}

/// Asserts that the reader refuses `case`, naming the file, its key and its words.
fn rejects(case: &Refused) -> ProblemError {
    let e = Problem::parse(Path::new("mutated.toml"), &case.text())
        .err()
        .unwrap_or_else(|| panic!("{}: the file must be rejected", case.id));
    assert_eq!(e.key, case.key, "{}: {e}", case.id);
    let shown = e.to_string();
    assert!(
        shown.starts_with("mutated.toml:"),
        "{}: the file is named: {shown}",
        case.id
    );
    assert!(
        shown.contains(&format!("`{}`", case.key)),
        "{}: the key is named: {shown}",
        case.id
    );
    for w in &case.words {
        assert!(
            shown.contains(w.as_str()),
            "{}: {w:?} missing from: {shown}",
            case.id
        );
    }
    e
}

#[test]
fn every_refused_file_names_its_key_and_what_is_wrong() {
    let cases = refused();
    for case in &cases {
        rejects(case);
    }
    assert!(cases.len() > 80, "{}", cases.len());
}

#[test]
fn the_shipped_problem_is_accepted() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    assert_eq!(p.variables.len(), 8);
    assert_eq!(p.constraints.len(), 5);
    assert_eq!(p.free_variables().count(), 8);
}

#[test]
fn errors_in_the_file_give_their_line() {
    for id in [
        "unknown key",
        "a variable's bounds crossed",
        "a name that is a number",
    ] {
        let e = refused_case(id);
        assert!(e.position.is_some(), "TOML gives a line: {e}");
    }
}

#[test]
fn a_yield_fraction_is_a_stress_limit() {
    // with a preset, a yield fraction is a stress limit: 1/3 of 503 MPa
    let text = original().replace("unit = \"ultimate\"", "unit = \"yield\"");
    let p = Problem::parse(Path::new("yield.toml"), &text).unwrap();
    let c = p
        .constraints
        .iter()
        .find(|c| c.output == "stress_max")
        .unwrap();
    assert!((c.upper.unwrap() - 503e6 / 3.0).abs() < 1e-3);
}

#[test]
fn design_missing_a_variable_is_an_error() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    let e = parse_design(
        &p,
        "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07",
    )
    .unwrap_err();
    assert!(e.to_string().contains("problems/wei2017.toml"), "{e}");
    assert_eq!(e.key, "--design t4");
    let e = parse_design(&p, "l2=1.96,delta2=x").unwrap_err();
    assert_eq!(e.key, "--design delta2");
    assert!(e.message.contains("\"x\""));
    let e = parse_design(&p, "l9=1").unwrap_err();
    assert_eq!(e.key, "--design l9");
}

#[test]
fn design_outside_bounds_is_a_warning() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    let d = parse_design(
        &p,
        "l2=25,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
    )
    .unwrap();
    assert_eq!(d.warnings.len(), 1);
    assert!(
        d.warnings[0].contains("l2 = 25 mm") && d.warnings[0].contains("[0.5, 20]"),
        "{:?}",
        d.warnings
    );
    assert!((d.x[0] - 0.025).abs() < 1e-15);
}

#[test]
fn the_command_line_exits_2_and_names_file_and_key() {
    let dir = std::env::temp_dir().join(format!("flexopt-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, original().replacen("upper = 45", "upper = -50", 1)).unwrap();
    let out = flexopt(&["eval", bad.to_str().unwrap(), "--design", "l2=1"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:") && err.contains("`variables[1].lower`"),
        "{err}"
    );
    assert!(
        out.stdout.is_empty(),
        "nothing on stdout for a rejected file"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_fillet_of_zero_is_allowed() {
    // the part says what it costs when it is drawn
    let height = "height = \"5 mm\"";
    let p = mutated(
        height,
        &format!("{height}\n\n[part]\nfillet_radius = \"0 mm\""),
    )
    .unwrap();
    let x = parse_design(
        &p,
        "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
    )
    .unwrap()
    .x;
    let part = p.mechanism().part_or_error(&x).unwrap();
    assert!(part.warnings[0].contains("fillet_radius is 0"));
}
