//! Issue 27, item 5: what a command prints on standard output is checked like a file it
//! writes. Into a full device (`/dev/full`: every write fails with ENOSPC, as a full disk's
//! do), every command that prints exits 1 and says so, never 0 and never with a panic.

use std::fs::File;
use std::process::{Command, Output, Stdio};

const FILE: &str = "problems/wei2017.toml";
const OPTIMUM: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

/// Runs flexopt with `args`, its standard output a full device.
fn into_full_device(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexopt"))
        .args(args)
        .stdout(File::create("/dev/full").expect("/dev/full"))
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

fn assert_write_failure(args: &[&str]) {
    let out = into_full_device(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(
        err.contains("error: cannot write to standard output") && !err.contains("panicked"),
        "{args:?}: {err}"
    );
}

#[test]
fn every_command_that_prints_exits_1_into_a_full_device() {
    for args in [
        &["init"][..],
        &["init", "--model", "pss3"],
        &["schema"],
        &["outputs"],
        &["completions", "bash"],
        &["completions", "fish"],
        &["eval", FILE, "--design", OPTIMUM],
        &["eval", FILE, "--design", OPTIMUM, "--format", "table"],
        &[
            "hinge", "--kind", "strip", "--l", "5", "--t", "0.5", "--width", "10",
        ],
    ] {
        assert_write_failure(args);
    }
}

#[test]
fn a_command_that_writes_files_then_prints_exits_1_too() {
    let dir = std::env::temp_dir().join(format!("flexopt-stdout-{}", std::process::id()));
    let out_dir = dir.to_str().unwrap();
    assert_write_failure(&["export", FILE, "--design", OPTIMUM, "--out", out_dir]);
    assert_write_failure(&[
        "sweep", FILE, "--param", "l2", "--from", "1", "--to", "2", "--steps", "3", "--out",
        out_dir,
    ]);
    assert_write_failure(&["run", FILE, "--starts", "8", "--quiet", "--out", out_dir]);
    std::fs::remove_dir_all(&dir).unwrap();
}
