//! Issue 27, item 9: what the command line says, said where it applies: a skipped FE step
//! named, the key at fault blamed, echoed input cut short and escaped, a sweep's holes
//! named.

use crate::common;

use std::path::PathBuf;

use common::flexopt;

const FILE: &str = "problems/wei2017.toml";

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flexopt-messages-{}-{name}", std::process::id()))
}

/// The shipped problem with `from` replaced by `to`, written to a temporary file.
fn edited(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(FILE).unwrap();
    assert!(text.contains(from), "{from}");
    let path = temp(name);
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    path.to_str().unwrap().to_string()
}

/// Runs flexopt with `args`, asserts its exit code and that its standard error holds each
/// of `words`, and returns that.
fn says(args: &[&str], code: i32, words: &[&str]) -> String {
    let out = flexopt(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not in {err}");
    }
    err
}

const SLOT: &str = "height = \"5 mm\"\n\n[part]\nmin_slot = \"10 mm\"";
/// [`SLOT`] checked on the optimum only: a study whose optimum's part cannot be made.
const SLOT_CHECKED: &str = "height = \"5 mm\"\n\n[part]\nmin_slot = \"10 mm\"\nenforce = false";
const TABLE1: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

#[test]
fn a_skipped_refinement_or_check_is_said_whatever_the_exit_code() {
    let out = temp("skipped-out");
    let out = out.to_str().unwrap();
    // exit 3: no feasible optimum to refine or check
    let infeasible = edited("infeasible.toml", "lower = 3.8e4", "lower = 3.8e7");
    let run = [
        "run",
        &infeasible,
        "--starts",
        "12",
        "--quiet",
        "--out",
        out,
        "--refine",
        "fe",
    ];
    let words = [
        "warning:",
        "the optimum is not refined against finite elements: no start ended feasible",
        "--verify: the optimum's part is not checked",
    ];
    says(&[&run[..], &["--verify"]].concat(), 3, &words);
    // exit 5: an optimum without a part that can be made
    let no_part = edited("no-part.toml", "height = \"5 mm\"", SLOT_CHECKED);
    let run = [
        "run", &no_part, "--starts", "12", "--quiet", "--out", out, "--refine", "fe",
    ];
    let words = ["not refined against finite elements: the optimum gives no part that can be made"];
    says(&run, 5, &words);
    let _ = std::fs::remove_dir_all(out);
    for f in [infeasible, no_part] {
        std::fs::remove_file(f).unwrap();
    }
}

#[test]
fn a_slot_too_wide_is_blamed_on_min_slot() {
    let file = edited("slot.toml", "height = \"5 mm\"", SLOT);
    let out = temp("slot-out");
    let export = [
        "export",
        &file,
        "--design",
        TABLE1,
        "--out",
        out.to_str().unwrap(),
    ];
    let words =
        ["part.min_slot (10 mm) is wider than the slot between the sides of the output block"];
    let err = says(&export, 5, &words);
    assert!(
        !err.contains("output_block_width (10 mm) is too narrow"),
        "{err}"
    );
    std::fs::remove_file(&file).unwrap();
}

#[test]
fn echoed_input_is_cut_short_and_escaped() {
    let key = "k".repeat(900_000);
    let file = edited(
        "long.toml",
        "absolute = true",
        &format!("absolute = true\n{key} = 1"),
    );
    let cut = format!("unknown field `{}…`", "k".repeat(60));
    let err = says(&["eval", &file, "--design", "l2=1"], 2, &[&cut]);
    assert!(err.len() < 400, "{} bytes", err.len());
    // a NUL byte and an escape sequence, shown as escapes
    let file = edited(
        "nul.toml",
        "name = \"wei2017\"",
        "name = \"a\\u0000b\\u001b[31m\"",
    );
    let err = says(
        &["eval", &file, "--design", "l2=1"],
        2,
        &[r#""a\0b\u{1b}[31m" cannot name"#],
    );
    assert!(!err.contains('\0') && !err.contains('\u{1b}'), "{err:?}");
    for f in ["long.toml", "nul.toml"] {
        std::fs::remove_file(temp(f)).unwrap();
    }
}

#[test]
fn a_sweep_says_which_points_gave_no_output() {
    let out_dir = temp("sweep-out");
    let out = out_dir.to_str().unwrap();
    let sweep = |from: &'static str| {
        [
            "sweep", FILE, "--param", "t2", "--from", from, "--to", "1", "--steps", "5", "--out",
            out,
        ]
    };
    let words = [
        "warning: problems/wei2017.toml: the model gives no value of 18 of 24 outputs",
        "at 1 of 5 points, t2 = 1e-300 mm",
    ];
    says(&sweep("1e-300"), 0, &words);
    // a sweep with a value everywhere says nothing
    let err = says(&sweep("0.4"), 0, &[]);
    assert!(err.is_empty(), "{err}");
    std::fs::remove_dir_all(&out_dir).unwrap();
}

/// Issue 50, case 17: numbers at the limits of `f64` read in a short form in every message
/// (a value of 1e308 was 309 digits), and a key read into one of our tables says what it
/// holds, not the type's name.
#[test]
fn numbers_read_short_and_tables_say_what_they_hold() {
    let tolerances = "[tolerances]\nt2 = { sigma = 0.001 }\n\n[search]";
    let cases = [
        ("robust = { yield = 1e-300 }", "got 1e-300"),
        ("robust = { k_sigma = 1e300 }", "got 1e300"),
        (
            "robust = \"x\"",
            "expected a table, { yield = 0.99 } or { k_sigma = 3 }",
        ),
    ];
    for (i, (robust, word)) in cases.iter().enumerate() {
        let file = edited(
            &format!("robust{i}.toml"),
            "[search]",
            &format!("{tolerances}\n{robust}"),
        );
        let err = says(&["run", &file, "--starts", "4", "--quiet"], 2, &[word]);
        assert!(err.len() < 300, "{err}");
        assert!(!err.contains("Raw"), "{err}");
        std::fs::remove_file(file).unwrap();
    }
    let file = edited(
        "spread.toml",
        "[search]",
        "[tolerances]\nt2 = \"x\"\n\n[search]",
    );
    let err = says(
        &["eval", &file, "--design", TABLE1],
        2,
        &[
            "`tolerances.t2`",
            "expected a table of the variable's spread, e.g. { plus_minus",
        ],
    );
    assert!(!err.contains("RawTolerance"), "{err}");
    std::fs::remove_file(file).unwrap();
    // a huge spread: the sample outside the domain in short form
    let file = edited(
        "sigma.toml",
        "[search]",
        "[tolerances]\nt2 = { sigma = 1e300 }\n\n[search]",
    );
    let out = temp("sigma-out");
    let err = says(
        &[
            "tolerance",
            &file,
            "--design",
            TABLE1,
            "--out",
            out.to_str().unwrap(),
        ],
        2,
        &["leaves the model's domain: t2 = -7.270418e296 m is not positive"],
    );
    assert!(err.len() < 400, "{err}");
    std::fs::remove_file(file).unwrap();
    // a design value at either end of f64's range
    for (t2, shown) in [
        ("1e308", "t2 = 1e308 mm lies outside"),
        ("1e-300", "t2 = 1e-300 mm lies outside"),
    ] {
        let design = TABLE1.replace("t2=0.4", &format!("t2={t2}"));
        let err = says(&["eval", FILE, "--design", &design], 0, &[shown]);
        assert!(err.lines().all(|l| l.len() < 300), "{err}");
    }
}
