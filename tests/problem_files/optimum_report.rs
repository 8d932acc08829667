//! Issue 27, item 7: `--optimum` reads a report of `run` only for the problem and model it
//! was written for, refuses a key said twice, reads past a byte-order mark, and warns of a
//! design the report marks infeasible and of a problem file changed since.

use crate::common;

use std::path::{Path, PathBuf};

use common::{flexopt, flexopt_ok};

const FILE: &str = "problems/wei2017.toml";

/// A fresh `optimum.json` of wei2017, and a folder for its variants.
struct Fixture {
    dir: PathBuf,
    report: String,
}

impl Fixture {
    fn new(tag: &str) -> Fixture {
        let dir =
            std::env::temp_dir().join(format!("flexopt-optimum-{tag}-{}", std::process::id()));
        let run = dir.join("run");
        flexopt_ok(&[
            "run",
            FILE,
            "--starts",
            "12",
            "--quiet",
            "--out",
            run.to_str().unwrap(),
        ]);
        let report = std::fs::read_to_string(run.join("optimum.json")).unwrap();
        Fixture { dir, report }
    }

    /// The report with `from` replaced by `to` (which must occur).
    fn edited(&self, from: &str, to: &str) -> String {
        assert!(self.report.contains(from), "{from}");
        self.report.replacen(from, to, 1)
    }

    /// Exports `problem` with `report` (written as `name`): the exit code and what it said.
    fn export(&self, problem: &Path, name: &str, report: &str) -> (Option<i32>, String) {
        let path = self.dir.join(name);
        std::fs::write(&path, report).unwrap();
        let out_dir = self.dir.join("export");
        let [problem, path, out_dir] =
            [problem, path.as_path(), out_dir.as_path()].map(|p| p.to_str().unwrap());
        let out = flexopt(&["export", problem, "--optimum", path, "--out", out_dir]);
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    }

    /// Asserts that exporting `problem` with `report` exits with `code` and says `words`.
    fn says(&self, problem: &Path, report: &str, code: i32, words: &[&str]) {
        let (got, err) = self.export(problem, "report.json", report);
        assert_eq!(got, Some(code), "{err}");
        for w in words {
            assert!(err.contains(w), "{w:?} not in {err}");
        }
        if words.is_empty() {
            assert!(err.is_empty(), "{err}");
        }
    }

    /// The shipped problem with `from` replaced by `to`, written beside the reports.
    fn problem(&self, from: &str, to: &str) -> PathBuf {
        let text = std::fs::read_to_string(FILE).unwrap();
        assert!(text.contains(from), "{from}");
        let path = self.dir.join("edited.toml");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        path
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

const DESIGN: &str = "\"design_si\": {";

#[test]
fn a_report_of_another_model_or_problem_is_refused() {
    let f = Fixture::new("other");
    let prr3 = Path::new("problems/prr3_frequency.toml");
    f.says(
        prr3,
        &f.report,
        2,
        &["key `model`: the report is of the bridge model"],
    );
    let renamed = f.problem("name = \"wei2017\"", "name = \"stage\"");
    let words = [
        "key `problem`: the report is of the problem \"wei2017\"",
        "\"stage\"",
    ];
    f.says(&renamed, &f.report, 2, &words);
    // a design of another parameterization: a variable the problem does not have
    let extra = f.edited(DESIGN, "\"design_si\": {\n    \"r2\": 0.001,");
    f.says(Path::new(FILE), &extra, 2, &["key `design_si.r2`"]);
    assert!(!f.dir.join("export").join("part.dxf").exists());
}

#[test]
fn a_key_given_twice_is_refused_and_a_byte_order_mark_read_past() {
    let f = Fixture::new("twice");
    let file = Path::new(FILE);
    let twice = f.edited(DESIGN, "\"design_si\": {\n    \"l2\": 0.005,");
    f.says(file, &twice, 2, &["the key `design_si.l2` is given twice"]);
    let twice = f.edited(
        "\"model\": \"bridge\",",
        "\"model\": \"prr3\",\n  \"model\": \"bridge\",",
    );
    f.says(file, &twice, 2, &["the key `model` is given twice"]);
    f.says(file, &format!("\u{feff}{}", f.report), 0, &[]);
}

#[test]
fn an_infeasible_design_and_a_changed_problem_are_said() {
    let f = Fixture::new("warn");
    let infeasible = f
        .edited("\"feasible\": true", "\"feasible\": false")
        .replacen("\"satisfied\": true", "\"satisfied\": false", 1);
    let words = [
        "warning:",
        "the report's design is not feasible",
        "breaks the constraint on span_x",
    ];
    f.says(Path::new(FILE), &infeasible, 0, &words);
    let changed = f.problem("upper = 7e6", "upper = 7.1e6");
    f.says(
        &changed,
        &f.report,
        0,
        &["has changed since the report was written"],
    );
    // a comment changes nothing the problem says
    let commented = f.problem("upper = 7e6", "upper = 7e6   # the piezo's limit");
    f.says(&commented, &f.report, 0, &[]);
}
