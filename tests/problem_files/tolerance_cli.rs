//! `flexopt tolerance` end to end: the set it writes, its yield, and the bad input it
//! refuses without writing anything.

use std::path::{Path, PathBuf};

use crate::common;

use common::{flexopt, flexopt_ok};
use serde_json::Value;

/// wei2017's nominal optimum, rounded in the file's units.
const OPTIMUM: &str = "l2=1.98403217,delta2=4.05060614,t2=0.4,l3=8.0614441,delta3=3.99583492,\
                       l4=1.98403217,delta4=4.05060612,t4=0.4";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-tol-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// wei2017.toml with `tolerances` appended, written into `dir`.
fn wei2017_with(dir: &Path, tolerances: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let text = std::fs::read_to_string("problems/wei2017.toml").unwrap();
    let file = dir.join("wei2017.toml");
    std::fs::write(&file, format!("{text}\n[tolerances]\n{tolerances}\n")).unwrap();
    file
}

#[test]
fn tolerance_writes_its_set_and_the_nominal_yield() {
    let dir = scratch("set");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let stdout = flexopt_ok(&[
        "tolerance",
        "problems/wei2017.toml",
        "--design",
        OPTIMUM,
        "--samples",
        "20000",
        "--out",
        o,
    ])
    .stdout;
    let text = String::from_utf8(stdout).unwrap();
    assert!(
        text.contains("yield: ") && text.contains("Wilson"),
        "{text}"
    );
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("tolerance.json")).unwrap())
            .unwrap();
    let y = json["yield"].as_f64().unwrap();
    assert!(y < 0.05, "yield {y}");
    assert_eq!(json["samples"].as_u64(), Some(20000));
    assert_eq!(json["seed"].as_u64(), Some(2017), "the file's search.seed");
    let names: Vec<&str> = json["tolerances"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["l2", "t2", "l3", "l4", "t4", "youngs_modulus"]);
    for name in ["span_x", "span_y", "stress_max", "k_in", "k_out"] {
        assert!(
            out.join(format!("histogram_{name}.png")).is_file(),
            "{name}"
        );
    }
    assert!(
        !out.join("histogram_amplification.png").exists(),
        "no limits, no histogram"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexopt tolerance` on wei2017 with `tolerance` in its `[tolerances]`, which must fail
/// with exit 2 and write nothing: its standard error.
fn refused(name: &str, tolerance: &str) -> String {
    let dir = scratch(name);
    let file = wei2017_with(&dir, tolerance);
    let out = dir.join("out");
    let o = flexopt(&[
        "tolerance",
        file.to_str().unwrap(),
        "--design",
        OPTIMUM,
        "--samples",
        "1000",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{tolerance}");
    assert!(!out.join("tolerance.json").exists(), "nothing written");
    assert!(!out.join("histogram_k_in.png").exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn tolerance_refuses_a_sample_out_of_the_domain_and_writes_nothing() {
    let err = refused("domain", "t2 = { plus_minus = 1.5 }");
    assert!(
        err.contains("wei2017.toml") && err.contains("key `tolerances`"),
        "{err}"
    );
    assert!(
        err.contains("leaves the model's domain") && err.contains("t2 = -"),
        "{err}"
    );
}

#[test]
fn tolerance_refuses_bad_tolerances_naming_the_key() {
    for (tolerance, key, words) in [
        (
            "t2 = { plus_minus = -0.005 }",
            "tolerances.t2.plus_minus",
            "must be positive",
        ),
        (
            "t9 = { sigma = 0.01 }",
            "tolerances.t9",
            "no design variable",
        ),
        (
            "yield_of = [\"k_in\", \"stroke\"]",
            "tolerances.yield_of[1]",
            "\"stroke\" is no constrained output of this problem; expected one of",
        ),
    ] {
        let err = refused("bad", tolerance);
        assert!(
            err.contains("wei2017.toml")
                && err.contains(&format!("key `{key}`"))
                && err.contains(words),
            "{err}"
        );
    }
}

#[test]
fn tolerance_refuses_too_few_samples() {
    let o = flexopt(&[
        "tolerance",
        "problems/wei2017.toml",
        "--design",
        OPTIMUM,
        "--samples",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("key `--samples`") && err.contains("got 1"),
        "{err}"
    );
}

/// `tolerance --fe` on a plane-stress part (a second a check): the FE section of
/// `tolerance.json` holds one record per sample, each sample's FE over model near the
/// design's own factor, and the same figures for 1 and 2 threads.
#[test]
fn tolerance_fe_checks_samples_of_the_part_reproducibly() {
    let dir = scratch("fe");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string("problems/wei2017.toml").unwrap();
    let file = dir.join("wei2017.toml");
    std::fs::write(
        &file,
        format!("{text}\n[refine]\nfidelity = \"none\"\nidealization = \"plane-stress\"\n"),
    )
    .unwrap();
    let fe_section = |threads: &str| {
        let out = dir.join(format!("out{threads}"));
        flexopt_ok(&[
            "tolerance",
            file.to_str().unwrap(),
            "--design",
            OPTIMUM,
            "--samples",
            "2000",
            "--fe",
            "--fe-samples",
            "3",
            "--threads",
            threads,
            "--out",
            out.to_str().unwrap(),
        ]);
        let json: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("tolerance.json")).unwrap())
                .unwrap();
        let mut fe = json["fe"].clone();
        fe.as_object_mut().unwrap().remove("seconds");
        fe
    };
    let one = fe_section("1");
    assert_eq!(one["samples"].as_u64(), Some(3));
    assert!(
        one["fidelity"].as_str().unwrap().contains("plane stress"),
        "{}",
        one["fidelity"]
    );
    let records = one["sample_records"].as_array().unwrap();
    assert_eq!(records.len(), 3);
    let k_in = one["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["name"] == "k_in")
        .unwrap();
    let factor = k_in["factor"].as_f64().unwrap();
    assert!(factor > 0.5 && factor < 1.5, "k_in's factor {factor}");
    for r in records {
        let [model, fe] = [0, 1].map(|i| r["outputs"]["k_in"][i].as_f64().unwrap());
        // tolerances move the hinge by a few per cent; the FE's ratio to the model moves
        // far less
        assert!(
            ((fe / model) / factor - 1.0).abs() < 0.01,
            "sample {}: {} against {factor}",
            r["index"],
            fe / model
        );
    }
    let y = one["yield"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&y));
    assert_eq!(one, fe_section("2"), "the same for 1 and 2 threads");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn tolerance_fe_refuses_too_few_fe_samples() {
    let o = flexopt(&[
        "tolerance",
        "problems/wei2017.toml",
        "--design",
        OPTIMUM,
        "--fe",
        "--fe-samples",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--fe-samples") && err.contains('2'), "{err}");
}

/// `tolerance --fe` on an optimum that stands on a rule (wei2017_min_stress's middle link as
/// wide as its thickest hinge): about half its parts break the rule. The run finishes, counts
/// them as failed parts beside the yield, and checks by FE the first samples that can be
/// made, naming those passed over.
#[test]
fn tolerance_fe_on_an_active_rule_counts_the_parts_that_cannot_be_made() {
    let dir = scratch("unmade");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string("problems/wei2017_min_stress.toml").unwrap();
    let file = dir.join("wei2017_min_stress.toml");
    std::fs::write(
        &file,
        format!("{text}\n[refine]\nfidelity = \"none\"\nidealization = \"plane-stress\"\n"),
    )
    .unwrap();
    let optimum: Value = serde_json::from_str(
        &std::fs::read_to_string("results/wei2017_min_stress/optimum.json").unwrap(),
    )
    .unwrap();
    let design: Vec<String> = optimum["design"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| format!("{k}={}", v.as_f64().unwrap()))
        .collect();
    let out = dir.join("out");
    let o = flexopt_ok(&[
        "tolerance",
        file.to_str().unwrap(),
        "--design",
        &design.join(","),
        "--samples",
        "4000",
        "--fe",
        "--fe-samples",
        "3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("cannot be made: "), "{text}");
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("tolerance.json")).unwrap())
            .unwrap();
    let unmakeable = json["unmakeable"].as_f64().unwrap();
    assert!((0.2..0.8).contains(&unmakeable), "{unmakeable}");
    let link = json["rules_broken"]["link_width"].as_f64().unwrap();
    assert!(link > 0.0 && link <= unmakeable, "{link} {unmakeable}");
    let y = json["yield"].as_f64().unwrap();
    assert!(y <= 1.0 - unmakeable, "{y} {unmakeable}");
    let fe = &json["fe"];
    assert_eq!(fe["samples"].as_u64(), Some(3));
    assert!(fe["yield"].as_f64().unwrap() <= 1.0 - unmakeable);
    // the samples checked and those passed over are the Monte Carlo's first ones, each once
    let mut seen: Vec<u64> = fe["sample_records"]
        .as_array()
        .unwrap()
        .iter()
        .chain(fe["unmade"].as_array().unwrap())
        .map(|r| r["index"].as_u64().unwrap())
        .collect();
    seen.sort_unstable();
    assert_eq!(seen, (0..seen.len() as u64).collect::<Vec<_>>());
    for u in fe["unmade"].as_array().unwrap() {
        let why = u["why"].as_str().unwrap();
        assert!(!why.is_empty(), "{u}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
