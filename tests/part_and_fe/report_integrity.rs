//! Issue 50, cases 3 and 14: a report belongs to the set it was made of, and it renders only
//! files that are what the set's manifest says they are, of the shape flexopt writes.

use std::path::{Path, PathBuf};

use flexopt::report::folder::{fnv1a64, listed, OutputSet};
use serde_json::Value;

use crate::common::flexopt;

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-integrity-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A set of one file `name` holding `text`, written into `dir` as a command writes its set.
fn commit_one(dir: &Path, name: &str, text: &str) {
    let set = OutputSet::begin(dir).unwrap();
    set.write(|s| std::fs::write(s.path(name), text).map_err(|e| panic!("{e}")))
        .unwrap();
    set.commit(&[name]).unwrap();
}

/// Case 3, the race made certain: a report made of one set while another command replaces
/// it is not added to the new set (the manifest keeps the new set's files alone, and no
/// report lies in the folder); made of the set still there, it is added.
#[test]
fn a_report_never_joins_a_set_it_was_not_made_of() {
    let dir = fresh("race");
    commit_one(&dir, "optimum.json", "{\"seed\": 1}");
    let made_of = listed(&dir).unwrap();
    let report = OutputSet::begin(&dir).unwrap();
    report
        .write(|s| {
            std::fs::write(s.path("report.html"), "<p>seed 1</p>").map_err(|e| panic!("{e}"))
        })
        .unwrap();
    // meanwhile, a run replaces the set
    commit_one(&dir, "optimum.json", "{\"seed\": 2}");
    let e = report
        .commit_added_to(&["report.html"], &made_of)
        .unwrap_err();
    assert!(e.to_string().contains("another command replaced"), "{e}");
    let now = listed(&dir).unwrap();
    assert_eq!(
        now.iter().map(|e| e.name.as_str()).collect::<Vec<_>>(),
        ["optimum.json"]
    );
    assert!(!dir.join("report.html").exists());
    assert_eq!(
        std::fs::read_to_string(dir.join("optimum.json")).unwrap(),
        "{\"seed\": 2}"
    );
    // made of the set that is there: added beside it
    let made_of = listed(&dir).unwrap();
    let report = OutputSet::begin(&dir).unwrap();
    report
        .write(|s| {
            std::fs::write(s.path("report.html"), "<p>seed 2</p>").map_err(|e| panic!("{e}"))
        })
        .unwrap();
    report.commit_added_to(&["report.html"], &made_of).unwrap();
    let names: Vec<String> = listed(&dir).unwrap().into_iter().map(|e| e.name).collect();
    assert!(names.contains(&"report.html".into()) && names.contains(&"optimum.json".into()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `manifest.json` of `dir` with the entry of `name` made to match the file as it is now.
fn reseal(dir: &Path, name: &str) {
    let path = dir.join("manifest.json");
    let mut manifest: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let bytes = std::fs::read(dir.join(name)).unwrap();
    for e in manifest["files"].as_array_mut().unwrap() {
        if e["name"] == name {
            e["bytes"] = bytes.len().into();
            e["fnv1a64"] = format!("{:016x}", fnv1a64(&bytes)).into();
        }
    }
    std::fs::write(&path, serde_json::to_string_pretty(&manifest).unwrap()).unwrap();
}

/// `flexopt report dir` refused (exit 2, no report written) with each of `words` said.
fn report_refused(dir: &Path, words: &[&str]) {
    let o = flexopt(&["report", dir.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for w in words {
        assert!(stderr.contains(w), "{w:?} missing from: {stderr}");
    }
    assert!(!dir.join("report.html").exists());
}

/// Case 14: an `optimum.json` edited by hand is refused as not the file the manifest lists
/// (its size and hash told); one whose manifest was edited to match but whose `objective`
/// is a string is refused by that key, not shown as "no start ended feasible".
#[test]
fn a_report_renders_only_the_files_its_manifest_lists() {
    let dir = fresh("edited");
    let out = dir.join("set");
    let o = flexopt(&[
        "run",
        "problems/wei2017.toml",
        "--starts",
        "4",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let optimum = out.join("optimum.json");
    let text = std::fs::read_to_string(&optimum).unwrap();
    let mut json: Value = serde_json::from_str(&text).unwrap();
    json["seed"] = 77.into();
    std::fs::write(&optimum, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    report_refused(
        &out,
        &[
            "optimum.json",
            "not the file",
            "manifest.json",
            "changed after",
        ],
    );
    json["objective"] = "abc".into();
    std::fs::write(&optimum, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    reseal(&out, "optimum.json");
    report_refused(&out, &["optimum.json", "key `objective`"]);
    // as written, it renders
    std::fs::write(&optimum, text).unwrap();
    reseal(&out, "optimum.json");
    let o = flexopt(&["report", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The shape the report checks is the one flexopt writes: every committed set's
/// `optimum.json` passes it (a field renamed in the writer fails here first).
#[test]
fn every_committed_optimum_has_the_shape_the_report_reads() {
    let mut seen = 0;
    for entry in std::fs::read_dir("results").unwrap().flatten() {
        let file = entry.path().join("optimum.json");
        if let Ok(text) = std::fs::read_to_string(&file) {
            flexopt::report::html::check_optimum(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            seen += 1;
        }
    }
    assert!(seen >= 10, "{seen} sets");
}
