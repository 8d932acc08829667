//! The command line end to end: `flexopt eval` and `flexopt sweep`.

mod common;

use common::{flexopt, printed};
use serde_json::Value;

const OPTIMUM: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

#[test]
fn eval_prints_table2_and_table3_at_the_published_optimum() {
    let out = flexopt(&["eval", "problems/wei2017.toml", "--design", OPTIMUM]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).expect("one JSON object on stdout");
    let o = &json["outputs"];
    let get = |k: &str| o[k].as_f64().unwrap_or_else(|| panic!("output {k}"));
    assert_eq!(printed(get("a21") * 10.0 * 1e6, 3), 18.3);
    assert_eq!(printed(get("a11") * 10.0 * 1e6, 3), 1.42);
    assert_eq!(printed(get("k_in"), 3), 7.02e6);
    assert_eq!(printed(get("k_out"), 2), 3.8e4);
    assert_eq!(printed(get("amplification"), 4), 12.86);
    assert!((get("stress_max") / 148e6 - 1.0).abs() < 0.01);
    for name in [
        "amplification",
        "k_in",
        "k_out",
        "stress_max",
        "span_x",
        "span_y",
        "stroke_out",
        "a11",
        "a12",
        "a21",
        "a22",
    ] {
        assert!(o[name].is_number(), "output {name} is printed");
    }
    assert_eq!(
        json["design"]["l3"].as_f64(),
        Some(8.1),
        "the design echoes the file's units"
    );
    // Table 1 prints the optimum rounded (l2 = l4 = 1.984 mm as 1.96): the rounded design
    // exceeds the K_in <= 7e6 N/m limit by 0.31 % and meets every other constraint
    assert_eq!(json["feasible"].as_bool(), Some(false));
    for c in json["constraints"].as_array().unwrap() {
        let satisfied = c["satisfied"].as_bool().unwrap();
        if c["output"] == "k_in" {
            let margin = c["relative_margin"].as_f64().unwrap();
            assert!(
                !satisfied && (margin + 0.0031).abs() < 0.0001,
                "k_in margin {margin}"
            );
        } else {
            assert!(satisfied, "{}", c["output"]);
        }
    }
    assert_eq!(json["nodes_mm"].as_array().map(|a| a.len()), Some(4));
}

#[test]
fn sweep_writes_json_and_png_with_the_curve() {
    let dir = std::env::temp_dir().join(format!("flexopt-sweep-{}", std::process::id()));
    let out = flexopt(&[
        "sweep",
        "problems/wei2017.toml",
        "--param",
        "delta3",
        "--from",
        "-10",
        "--to",
        "10",
        "--steps",
        "41",
        "--around",
        OPTIMUM,
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value =
        serde_json::from_slice(&std::fs::read(dir.join("delta3.json")).unwrap()).unwrap();
    let values = json["values"].as_array().unwrap();
    assert_eq!(values.len(), 41);
    assert_eq!(values[0].as_f64(), Some(-10.0));
    assert_eq!(values[40].as_f64(), Some(10.0));
    let da = json["outputs"]["amplification"].as_array().unwrap();
    assert_eq!(da.len(), 41);
    // the point at delta3 = 4.0 deg matches an evaluation of that design
    let problem =
        flexopt::problem::Problem::load(std::path::Path::new("problems/wei2017.toml")).unwrap();
    let at = OPTIMUM.replace("delta3=4.01", "delta3=4.0");
    let x = flexopt::problem::design::parse_design(&problem, &at)
        .unwrap()
        .x;
    let report = flexopt::report::DesignReport::new(&problem, &x);
    let expect = report.outputs["amplification"].unwrap();
    assert_eq!(values[28].as_f64(), Some(4.0));
    assert!((da[28].as_f64().unwrap() / expect - 1.0).abs() < 1e-14);
    let png = std::fs::read(dir.join("delta3.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(!dir.join(".delta3.partial.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sweep_rejects_a_length_range_through_zero() {
    let out = flexopt(&[
        "sweep",
        "problems/wei2017.toml",
        "--param",
        "l2",
        "--from",
        "-1",
        "--to",
        "5",
        "--steps",
        "3",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("problems/wei2017.toml") && err.contains("`--from`"),
        "{err}"
    );
}
