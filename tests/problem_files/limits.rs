//! Input the size of which the file or the command line sets: a chain of many bodies, an
//! input file that never ends, a thread count, a file-size limit on the disk (issue 50,
//! cases 4, 6, 7, 8).

use std::path::{Path, PathBuf};

use crate::common::{flexopt, flexopt_on_full_disk};

#[path = "../../benches/support/chain.rs"]
mod chain_file;
use chain_file::chain_problem;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-limits-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The chain of [`chain_problem`] written into `dir` as `chain{n}.toml`.
fn chain(dir: &Path, n: usize, extra: &str) -> PathBuf {
    let file = dir.join(format!("chain{n}.toml"));
    std::fs::write(&file, chain_problem(n, extra)).unwrap();
    file
}

/// Case 4: a study of 70 bodies asks for more than 128 outputs, ranges of fit and rules
/// (each hinge's two ends under `stress_max`, each hinge's range of fit): it runs.
#[test]
fn a_study_of_a_long_chain_runs() {
    let dir = scratch("chain");
    let file = chain(&dir, 70, "[search]\nstarts = 2\nseed = 1\nthreads = 1");
    let out = dir.join("out");
    let o = flexopt(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(json["feasible"], true, "{json}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 19: the part of a chain of 200 bodies is exported, one piece with every hinge (the
/// checks before the union pair only solids whose boxes meet; the time is measured by
/// `cargo bench --bench network`).
#[test]
fn the_part_of_a_long_chain_is_exported() {
    let dir = scratch("export");
    let file = chain(&dir, 200, "[part]");
    let out = dir.join("out");
    let o = flexopt(&[
        "export",
        file.to_str().unwrap(),
        "--design",
        "l=2,t=0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let part: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("part.json")).unwrap()).unwrap();
    assert_eq!(part["loops"].as_array().unwrap().len(), 1);
    assert_eq!(part["hinges"].as_array().unwrap().len(), 200);
    // the last link's end, 10 mm a body from the first hinge's start
    let right = part["bounding_box"][2].as_f64().unwrap();
    assert!((right - 1999.5).abs() < 1e-9, "{right}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 4: a network's parameters are bounded where the file is read, not by a panic.
#[test]
fn a_network_of_too_many_parameters_is_refused_at_reading() {
    let dir = scratch("parameters");
    let file = chain(&dir, 2, "");
    let text = std::fs::read_to_string(&file).unwrap();
    let many: Vec<String> = (0..17).map(|i| format!("[\"p{i}\", \"length\"]")).collect();
    let text = text.replace(
        "parameters = [[\"l\", \"length\"], [\"t\", \"length\"]]",
        &format!(
            "parameters = [[\"l\", \"length\"], [\"t\", \"length\"], {}]",
            many.join(", ")
        ),
    );
    std::fs::write(&file, text).unwrap();
    let o = flexopt(&["outputs", file.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("chain2.toml")
            && stderr.contains("network.parameters")
            && stderr.contains("19 parameters; a network has at most 16"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 6: a device, a sparse file: refused after at most the limit's bytes, not read whole.
#[test]
fn every_input_is_read_through_its_size_limit() {
    let dir = scratch("unbounded");
    let refused = |args: &[&str], words: &str| {
        let o = flexopt(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(words), "{args:?}: {stderr}");
    };
    refused(
        &["run", "/dev/zero", "--quiet"],
        "/dev/zero: the file has more than 1048576 bytes; a problem file may have at most",
    );
    let report = dir.join("no-set");
    refused(
        &["report", report.to_str().unwrap(), "--problem", "/dev/zero"],
        "/dev/zero: key `--problem`: the file has more than 1048576 bytes",
    );
    let sparse = dir.join("optimum.json");
    std::fs::File::create(&sparse)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let out = dir.join("out");
    refused(
        &[
            "export",
            "problems/wei2017.toml",
            "--optimum",
            sparse.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        "the file has 1073741824 bytes; a report's file may have at most 67108864",
    );
    refused(
        &[
            "export",
            "problems/wei2017.toml",
            "--optimum",
            "/dev/zero",
            "--out",
            out.to_str().unwrap(),
        ],
        "the file has more than 67108864 bytes",
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 7: `tolerance --threads` in the range `run --threads` takes.
#[test]
fn every_threads_option_has_one_range() {
    for command in ["tolerance", "run"] {
        let mut args = vec![command, "problems/wei2017.toml", "--threads", "1025"];
        if command == "tolerance" {
            args.extend([
                "--design",
                "l2=2,delta2=4,t2=0.4,l3=8,delta3=4,l4=2,delta4=4,t4=0.4",
            ]);
        }
        let o = flexopt(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{command}: {stderr}");
        assert!(
            stderr.contains("wei2017.toml: key `--threads`: must lie between 0 and 1024, got 1025"),
            "{command}: {stderr}"
        );
    }
}

/// Case 8: past `ulimit -f` with SIGXFSZ at its default (death, exit 153), the write error
/// is told, naming the file, with exit 1.
#[test]
fn a_file_size_limit_is_a_write_error_not_a_signal() {
    let dir = scratch("ulimit");
    let out = dir.join("out");
    let o = flexopt_on_full_disk(
        40,
        false,
        &[
            "export",
            "problems/wei2017.toml",
            "--design",
            "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("{}: ", out.join("part.png").display())),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Case 5: expressions deep enough to overflow a recursion's stack (100,000 parentheses or
/// signs, a tower of powers, calls within calls) are refused with their key and the limit, not
/// an abort; long ones (a sum of 100,000 terms, a product of 50,000 factors) are read and
/// evaluated whatever their length, as the evaluation walks the tree without recursion.
#[test]
fn deep_expressions_are_refused_with_their_key() {
    let dir = scratch("deep");
    let n = 100_000;
    let deep = [
        format!("{}l{}", "(".repeat(n), ")".repeat(n)),
        format!("{}l", "-".repeat(n)),
        format!("l{}", "^1".repeat(n / 2)),
        format!("{}l{}", "sin(".repeat(n / 5), ")".repeat(n / 5)),
        format!("{}l{}", "(".repeat(101), ")".repeat(101)),
    ];
    let measure = |text: &str| {
        format!("[[network.measures]]\nname = \"m\"\ndimension = \"length\"\nvalue = \"{text}\"")
    };
    for (i, text) in deep.iter().enumerate() {
        let file = chain(&dir, 2, &measure(text));
        let o = flexopt(&["outputs", file.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{i}: {stderr}");
        assert!(
            stderr.contains("chain2.toml")
                && stderr.contains("network.measures[0].value")
                && stderr.contains("at most 100 parentheses"),
            "{i}: {stderr}"
        );
    }
    // at the limit, and long: read, and each value the sum's or the product's
    let long = [
        (format!("{}l{}", "(".repeat(100), ")".repeat(100)), 2e-3),
        (vec!["l"; n].join(" + "), 2e-3 * n as f64),
        (vec!["l"; n].join(" - ") + " + l", 2e-3 * (3.0 - n as f64)),
        (
            format!("{}l", "1.0001*".repeat(n / 2)),
            2e-3 * 1.0001f64.powi(n as i32 / 2),
        ),
    ];
    for (text, expected) in long {
        let file = chain(&dir, 2, &measure(&text));
        let o = flexopt(&[
            "eval",
            file.to_str().unwrap(),
            "--design",
            "l=2,t=0.5",
            "--format",
            "json",
        ]);
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let m = json["outputs"]["m"].as_f64().unwrap();
        assert!(
            ((m - expected) / expected).abs() < 1e-9,
            "{m} against {expected}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
