//! The check's size is bounded: a part whose meshes would outgrow the budget of degrees of
//! freedom stops (or is refused) with a message saying so, under a memory limit that the
//! unbounded check overran, and never aborts.

use std::process::Command;

use crate::common;

/// A wei2017 part with every length 100 mm (beyond the file's bounds: a warning), which took
/// 22 GB before it was killed when the meshes had no bound.
const LONG: &str = "l2=100,delta2=4,t2=0.4,l3=100,delta3=4,l4=100,delta4=4,t4=0.4";

fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("flexopt-budget-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn a_long_part_stops_at_the_budget_within_a_memory_limit() {
    let dir = scratch("long");
    // 1.5 GB of address space: the process's own needs at this budget, with room to spare
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 1500000; exec \"$0\" verify problems/wei2017.toml --design {LONG} \
             --tolerance 0.1 --max-dofs 100000 --out {}",
            dir.display()
        ))
        .arg(env!("CARGO_BIN_EXE_flexopt"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("stopped, the next mesh would have about")
            && stdout.contains("more than the budget of 100000 (--max-dofs)"),
        "{stdout}"
    );
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("verify.json")).unwrap()).unwrap();
    assert_eq!(v["converged"], false);
    assert!(v["budget_stop"].as_str().unwrap().contains("100000"));
    let dofs: Vec<u64> = v["levels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["dofs"].as_u64().unwrap())
        .collect();
    assert!(
        !dofs.is_empty() && dofs.iter().all(|&d| d <= 100_000),
        "{dofs:?}"
    );
    // the next mesh, about four times the last, would have been over it
    assert!(4 * dofs.last().unwrap() > 100_000);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `verify` of wei2017's committed optimum with `extra` arguments.
fn verify_optimum(extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "verify",
        "problems/wei2017.toml",
        "--optimum",
        "results/wei2017/optimum.json",
    ];
    args.extend_from_slice(extra);
    common::flexopt(&args)
}

#[test]
fn a_first_mesh_over_the_budget_is_refused() {
    // 1000 degrees of freedom: fewer than the outline's own points need; 5000: the outline
    // fits, the refinement inside it does not
    for budget in ["1000", "5000"] {
        let dir = scratch(budget);
        let out = verify_optimum(&["--max-dofs", budget, "--out", dir.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{budget}: {stderr}");
        assert!(
            stderr.contains("problems/wei2017.toml: cannot check this design: over the budget: the first mesh needs more than")
                && stderr.contains(&format!("more than the {} allowed", budget.parse::<usize>().unwrap() / 2)),
            "{budget}: {stderr}"
        );
        assert!(!dir.join("verify.json").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn a_budget_out_of_range_is_rejected() {
    let out = verify_optimum(&["--max-dofs", "10"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr.contains("key `--max-dofs`: must lie between 1000 and 50000000, got 10"),
        "{stderr}"
    );
}
