//! Issue 27, item 4: a sweep and a front are sets too, added to the folder's set: both
//! files of a sweep or none, the sweeps of other variables and a run's files kept.

use std::path::PathBuf;

use crate::common::{assert_whole_set, flexopt, flexopt_ok, flexopt_on_full_disk, snapshot};

/// `pareto.json` fits in a file this long (20 kB), `pareto.png` does not.
const FULL_DISK: u32 = 40;

/// `l2.json` of a 20-point sweep (31 kB with the part's rules' margins) fits in a file
/// this long (50 kB), `l2.png` (310 kB) does not.
const FULL_DISK_SWEEP: u32 = 100;

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-sets-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn sweeps_into_one_folder_are_one_set_and_a_failed_one_leaves_it_whole() {
    let out = fresh("sweeps");
    let sweep = |param: &str, to: &str| {
        [
            "sweep",
            "problems/wei2017.toml",
            "--param",
            param,
            "--from",
            "1",
            "--to",
            to,
            "--steps",
            "20",
            "--out",
            out.to_str().unwrap(),
        ]
        .map(String::from)
    };
    fn args(a: &[String; 12]) -> Vec<&str> {
        a.iter().map(String::as_str).collect()
    }
    flexopt_ok(&args(&sweep("l2", "3")));
    flexopt_ok(&args(&sweep("l3", "12")));
    assert_eq!(
        assert_whole_set(&out, &[]),
        ["l2.json", "l2.png", "l3.json", "l3.png"]
    );
    let before = snapshot(&out);
    let o = flexopt_on_full_disk(FULL_DISK_SWEEP, true, &args(&sweep("l2", "4")));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("{}: ", out.join("l2.png").display())),
        "{stderr}"
    );
    // not the new l2.json beside the old l2.png: the earlier set as it was
    assert_eq!(snapshot(&out), before);
    // a sweep of a variable swept before replaces that sweep's two files
    flexopt_ok(&args(&sweep("l2", "4")));
    assert_eq!(
        assert_whole_set(&out, &[]),
        ["l2.json", "l2.png", "l3.json", "l3.png"]
    );
    assert_ne!(snapshot(&out)["l2.json"], before["l2.json"]);
    assert_eq!(snapshot(&out)["l3.json"], before["l3.json"]);
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn a_front_joins_the_runs_set_and_a_failed_one_leaves_it_whole() {
    let out = fresh("front");
    let file = "problems/wei2017_dynamic.toml";
    let dir = out.to_str().unwrap();
    let pareto = [
        "pareto",
        file,
        "--vary",
        "natural_frequency",
        "--from",
        "400",
        "--to",
        "2000",
        "--steps",
        "3",
        "--starts",
        "4",
        "--quiet",
        "--out",
        dir,
    ];
    flexopt_ok(&["run", file, "--starts", "4", "--quiet", "--out", dir]);
    let run = assert_whole_set(&out, &[]);
    flexopt_ok(&pareto);
    let with_front = assert_whole_set(&out, &[]);
    assert_eq!(with_front[..run.len()], run);
    assert_eq!(with_front[run.len()..], ["pareto.json", "pareto.png"]);
    let before = snapshot(&out);
    let mut other = pareto;
    other[9] = "5";
    let o = flexopt_on_full_disk(FULL_DISK, true, &other);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    assert_eq!(snapshot(&out), before);
    // a run replaces the folder's set: the front of the earlier one goes with it
    let o = flexopt(&["run", file, "--starts", "5", "--quiet", "--out", dir]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(assert_whole_set(&out, &[]), run);
    std::fs::remove_dir_all(&out).unwrap();
}
