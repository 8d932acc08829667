//! `flexopt stroke` end to end: wei2017's network over its stroke with large deflection,
//! its set of files against each other and the linear model, and the input it refuses.

use std::path::PathBuf;

use crate::common::{flexopt, flexopt_ok};
use serde_json::Value;

/// Table 1's optimum in the file's units (mm, degrees).
const TABLE1: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";
const NETWORK: &str = "problems/wei2017_network.toml";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-stroke-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The CSV's rows, each a map from its header's names.
fn rows(text: &str) -> Vec<std::collections::HashMap<String, f64>> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            header
                .iter()
                .zip(l.split(','))
                .map(|(h, v)| (h.to_string(), v.parse::<f64>().unwrap()))
                .collect()
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn stroke_writes_the_curves_beside_the_linear_model() {
    let dir = scratch("set");
    let o = dir.to_str().unwrap();
    let out = flexopt_ok(&[
        "stroke", NETWORK, "--design", TABLE1, "--steps", "2", "--out", o,
    ]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("model, large deflection, 8 elements a flexure")
            && stdout.contains("critical load factor"),
        "{stdout}"
    );
    for f in ["stroke.csv", "stroke.svg", "stroke.json", "manifest.json"] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let rows = rows(&std::fs::read_to_string(dir.join("stroke.csv")).unwrap());
    assert_eq!(rows.len(), 3, "the unloaded point and two steps");
    let (first, last) = (&rows[0], &rows[2]);
    assert_eq!(first["fraction"], 0.0);
    for c in ["stroke_in_um", "stroke_out_um"] {
        assert_eq!(first[c], 0.0, "{c}");
        assert_eq!(first[&format!("linear_{c}")], 0.0, "{c}");
    }
    let k = first["k_in_N_per_um"];
    assert!(rel(k, first["linear_k_in_N_per_um"]) < 1e-9, "{k}");
    assert_eq!(last["fraction"], 1.0);
    for c in [
        "stress_b_MPa",
        "stress_d_MPa",
        "parasitic_rotation_out_mrad",
    ] {
        assert!(
            last.contains_key(c) && last.contains_key(&format!("linear_{c}")),
            "{c}"
        );
    }
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stroke.json")).unwrap()).unwrap();
    let end = json["at_stroke"]["stroke_out"].as_f64().unwrap();
    assert!(rel(last["stroke_out_um"], end * 1e6) < 1e-12, "{end}");
    assert_eq!(json["elements"].as_u64(), Some(8));
    assert!(json["finer"]["k_in"].as_f64().is_some());
    assert!(json.get("critical_load_factor").is_some());
    // the stack's full stroke stiffens the input (the strips stretch)
    let ratio = last["k_in_N_per_um"] / last["linear_k_in_N_per_um"];
    assert!(ratio > 1.3, "{ratio}");
    let svg = std::fs::read_to_string(dir.join("stroke.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("stroke_out (um)"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Under the force that opens the input 17.4 um in a linear solve (122 N), the tangent
/// `k_in` at the stroke is 1.44 times the linear (docs/guide/src/networks.md).
#[test]
fn stroke_by_a_force_stiffens_the_input_as_documented() {
    let dir = scratch("force");
    let o = dir.to_str().unwrap();
    let args = ["stroke", NETWORK, "--design", TABLE1, "--steps", "4"];
    flexopt_ok(&[&args[..], &["--force", "122", "--out", o]].concat());
    let rows = rows(&std::fs::read_to_string(dir.join("stroke.csv")).unwrap());
    let last = rows.last().unwrap();
    let ratio = last["k_in_N_per_um"] / last["linear_k_in_N_per_um"];
    assert!((1.42..1.46).contains(&ratio), "{ratio}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexopt stroke` with `args`, which must fail with exit 2, writing nothing: its
/// standard error.
fn refused(file: &str, args: &[&str]) -> String {
    let dir = scratch("refused");
    let o = dir.to_str().unwrap();
    let out = flexopt(&[&["stroke", file, "--out", o], args].concat());
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    assert!(!dir.exists(), "{args:?}: nothing written");
    String::from_utf8(out.stderr).unwrap()
}

#[test]
fn stroke_refuses_a_model_without_a_large_deflection_solve() {
    let design = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";
    let err = refused("problems/wei2017.toml", &["--design", design]);
    assert!(
        err.contains("problems/wei2017.toml")
            && err.contains("the large-deflection solve is for networks"),
        "{err}"
    );
}

#[test]
fn stroke_refuses_bad_options_naming_them() {
    for (args, key) in [
        (&["--elements", "0"][..], "`--elements`"),
        (&["--steps", "0"][..], "`--steps`"),
        (&["--force", "0"][..], "`--force`"),
        (&["--force", "nan"][..], "`--force`"),
    ] {
        let err = refused(NETWORK, &[&["--design", TABLE1], args].concat());
        assert!(
            err.contains(NETWORK) && err.contains(key),
            "{args:?}: {err}"
        );
    }
}
