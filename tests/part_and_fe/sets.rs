//! Issue 27: a folder with a manifest holds exactly the set it lists, whatever set was there
//! before and however the write ends: a run that writes fewer files, a full disk, a folder in
//! a file's place, a kill at any moment.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rand::Rng;

use flexopt::report::part::PART_FILES;
use flexopt::report::study::STUDY_FILES;

use crate::common::{assert_whole_set, flexopt, flexopt_ok, flexopt_on_full_disk, rng, snapshot};

const WEI2017: &str = "problems/wei2017.toml";
const TABLE1: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";
const OTHER: &str = "l2=2.2,delta2=5,t2=0.45,l3=8,delta3=4,l4=2,delta4=5,t4=0.45";
/// The part's files other than its pictures, and `verify.json`, fit in a file this long (40 kB);
/// `part.png` and `stress.png` do not.
const FULL_DISK: u32 = 80;
/// The edit of wei2017.toml that leaves no design feasible.
const INFEASIBLE: (&str, &str) = ("lower = 3.8e4", "lower = 3.8e9");
/// The edits that leave its optimum without a part that can be made: the pocket is short,
/// and the part's rules are checked on the optimum only, not kept to by the study.
const UNMAKEABLE: [(&str, &str); 2] = [
    ("length = \"20 mm\"", "length = \"200 mm\""),
    (
        "height = \"5 mm\"\n",
        "height = \"5 mm\"\n\n[part]\nenforce = false\n",
    ),
];

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-sets-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `dir/s.toml`: wei2017's problem with its refinement on (at most 2 FE checks) and
/// the edits `(from, to)`; returns its path.
fn problem(dir: &Path, edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(WEI2017).unwrap();
    let refine = [
        (
            "# [refine]\n# fidelity = \"fe\"",
            "[refine]\nfidelity = \"fe\"",
        ),
        ("# max_fe = 12", "max_fe = 2"),
    ];
    for (from, to) in refine.iter().chain(edits) {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let file = dir.join("s.toml");
    std::fs::write(&file, text).unwrap();
    file.to_str().unwrap().to_string()
}

/// `flexopt run` of `file` into `out` with 8 starts and `extra` options.
fn run(file: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "run",
        file,
        "--starts",
        "8",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    flexopt(&args)
}

fn code(out: &std::process::Output) -> Option<i32> {
    out.status.code()
}

/// Issue 27, item 1: a run after a run that wrote more leaves none of the earlier set's
/// files that it does not write itself (the part's on exit 3 and 5, the refinement's
/// without it, the FE check's folder without --verify), and none of the user's own.
#[test]
fn a_run_leaves_no_file_of_the_earlier_set_it_does_not_write() {
    let dir = fresh("stale");
    let out = dir.join("out");
    let file = problem(&dir, &[]);
    // the refinement may end unconverged (exit 3) within 2 FE checks: its files are written
    let first = run(&file, &out, &["--refine", "fe", "--verify"]);
    assert!(matches!(code(&first), Some(0 | 3)), "{first:?}");
    let user = ["notes.txt", "fig"];
    std::fs::write(out.join("notes.txt"), "the user's").unwrap();
    std::fs::create_dir(out.join("fig")).unwrap();
    std::fs::write(out.join("fig/mine.txt"), "the user's").unwrap();
    let listed = assert_whole_set(&out, &user);
    for f in ["part.png", "refined.json", "refined_part.dxf", "verify"] {
        assert!(listed.iter().any(|n| n == f), "{f} not in {listed:?}");
    }
    let plain: Vec<&str> = STUDY_FILES.iter().chain(&PART_FILES).copied().collect();
    // without the refinement and the check: their files and folder are gone
    let second = run(&file, &out, &["--refine", "none"]);
    assert_eq!(code(&second), Some(0), "{second:?}");
    assert_eq!(assert_whole_set(&out, &user), plain);
    // infeasible (exit 3) and without a part that can be made (exit 5): no part files
    for (edits, exit) in [(&[INFEASIBLE][..], 3), (&UNMAKEABLE[..], 5)] {
        let file = problem(&dir, edits);
        let o = run(&file, &out, &["--refine", "none"]);
        assert_eq!(code(&o), Some(exit), "{o:?}");
        assert_eq!(assert_whole_set(&out, &user), plain[..6]);
        // the part's files come back with a feasible run, for the next case to remove
        let o = run(&problem(&dir, &[]), &out, &["--refine", "none"]);
        assert_eq!(assert_whole_set(&out, &user), plain, "{o:?}");
    }
    assert_eq!(
        std::fs::read_to_string(out.join("fig/mine.txt")).unwrap(),
        "the user's"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 27, item 4: `export` and `verify` over an earlier set on a full disk, and a run
/// whose move into place finds a folder where a file goes, exit 1 and leave the earlier set
/// as it was, whole, with the user's folder untouched.
#[test]
fn a_write_that_fails_leaves_the_earlier_set_whole() {
    let dir = fresh("failed");
    for (what, extra) in [("export", &[][..]), ("verify", &["--tolerance", "0.1"][..])] {
        let out = dir.join(what);
        let args = |design: &'static str| {
            let mut a = vec![what, WEI2017, "--design", design, "--out"];
            a.push(out.to_str().unwrap());
            a.extend(extra);
            a
        };
        flexopt_ok(&args(TABLE1));
        let before = snapshot(&out);
        let o = flexopt_on_full_disk(FULL_DISK, true, &args(OTHER));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(code(&o), Some(1), "{what}: {stderr}");
        // told of the file in place, not of the staging folder
        let png = if what == "export" {
            "part.png"
        } else {
            "stress.png"
        };
        assert!(
            stderr.contains(&format!("{}: ", out.join(png).display()))
                && stderr.contains("nothing was written"),
            "{what}: {stderr}"
        );
        assert_eq!(snapshot(&out), before, "{what}");
        assert_whole_set(&out, &[]);
    }

    // the earlier set has no part (infeasible); the user's folder stands where part.png goes
    let out = dir.join("run");
    let o = run(&problem(&dir, &[INFEASIBLE]), &out, &["--refine", "none"]);
    assert_eq!(code(&o), Some(3), "{o:?}");
    std::fs::create_dir(out.join("part.png")).unwrap();
    std::fs::write(out.join("part.png/mine.txt"), "the user's").unwrap();
    let before = snapshot(&out);
    let o = run(&problem(&dir, &[]), &out, &["--refine", "none"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(code(&o), Some(1), "{stderr}");
    assert!(
        stderr.contains(&out.join("part.png").display().to_string())
            && stderr.contains("holds its earlier files again"),
        "{stderr}"
    );
    assert_eq!(snapshot(&out), before);
    assert_whole_set(&out, &["part.png"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Done-when of issue 27: `export`, `verify` and `run --refine fe` killed (SIGKILL) at
/// moments drawn from a seeded schedule over the command's own duration leave, once the
/// next command into the folder has recovered it ([`flexopt::report::folder::recover`]),
/// one whole set: the earlier one as it was, or (a kill during the move, after its journal,
/// or after the command finished) the new one whole, and nothing else.
#[test]
fn a_command_killed_at_any_moment_leaves_one_whole_set() {
    let dir = fresh("killed");
    let file = problem(&dir, &[]);
    let mut schedule = rng(27);
    let cases: [(&str, Vec<&str>, usize); 3] = [
        ("export", vec!["export", WEI2017, "--design"], 6),
        (
            "verify",
            vec!["verify", WEI2017, "--tolerance", "0.1", "--design"],
            5,
        ),
        (
            "run",
            vec!["run", &file, "--refine", "fe", "--starts", "8", "--seed"],
            4,
        ),
    ];
    for (what, command, kills) in cases {
        let out = dir.join(what);
        let args = |last: &str| {
            let mut a: Vec<String> = command.iter().map(|s| s.to_string()).collect();
            a.extend([last.to_string(), "--out".into(), out.display().to_string()]);
            a
        };
        // the earlier set, and how long the command takes
        let variant = |k: usize| match what {
            "run" => format!("{}", 100 + k),
            _ if k.is_multiple_of(2) => TABLE1.to_string(),
            _ => OTHER.to_string(),
        };
        let start = Instant::now();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_flexopt"))
            .args(args(&variant(0)))
            .output()
            .unwrap();
        let took = start.elapsed();
        assert!(o.status.code().is_some_and(|c| c == 0 || c == 3), "{o:?}");
        let mut earlier = snapshot(&out);
        let names = assert_whole_set(&out, &[]);
        let (mut kept, mut replaced) = (0, 0);
        for k in 1..=kills {
            let delay = took.mul_f64(schedule.random_range(0.0..0.9));
            let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_flexopt"))
                .args(args(&variant(k)))
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .unwrap();
            std::thread::sleep(delay.max(Duration::from_micros(200)));
            child.kill().unwrap_or(()); // SIGKILL; an error only if it had ended
            child.wait().unwrap();
            flexopt::report::folder::recover(&out).unwrap();
            // the same command's set: the same names, never a mixture of two sets
            assert_eq!(assert_whole_set(&out, &[]), names, "{what}, kill {k}");
            let now = snapshot(&out);
            if now == earlier {
                kept += 1;
            } else {
                replaced += 1;
                earlier = now;
            }
        }
        eprintln!(
            "{what} ({took:?} uncut): {kept} kills left the earlier set, {replaced} the new one"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
