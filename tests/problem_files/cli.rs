//! The command line end to end: `flexopt eval` and `flexopt sweep`.

use crate::common;

use common::{flexopt, flexopt_ok, printed};
use serde_json::Value;

const OPTIMUM: &str = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";

#[test]
fn eval_prints_table2_and_table3_at_the_published_optimum() {
    let out = flexopt_ok(&["eval", "problems/wei2017.toml", "--design", OPTIMUM]);
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
    flexopt_ok(&[
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
    // each rule of the part beside the outputs, its margin (mm) at every point as eval gives
    let rules = json["part_rules"].as_object().unwrap();
    assert_eq!(rules.len(), report.part_rules.len());
    for r in &report.part_rules {
        let curve = rules[&r.rule].as_array().unwrap();
        assert_eq!(curve.len(), 41);
        assert!(
            (curve[28].as_f64().unwrap() - r.margin_mm).abs() <= 1e-12,
            "{}",
            r.rule
        );
    }
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

#[test]
fn pareto_steps_the_frequency_floor_and_writes_the_front() {
    let dir = std::env::temp_dir().join(format!("flexopt-pareto-{}", std::process::id()));
    flexopt_ok(&[
        "pareto",
        "problems/wei2017_dynamic.toml",
        "--vary",
        "natural_frequency",
        "--from",
        "600",
        "--to",
        "1400",
        "--steps",
        "5",
        "--starts",
        "40",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("pareto.json")).unwrap()).unwrap();
    assert!(dir.join("pareto.png").is_file());
    let points = json["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    let get = |p: &Value, k: &str| p[k].as_f64().unwrap();
    for (i, p) in points.iter().enumerate() {
        let (limit, value) = (get(p, "limit"), get(p, "value"));
        assert!((limit - (600.0 + 200.0 * i as f64)).abs() < 1e-9);
        // every optimum meets its floor; the floors above the free optimum's 802 Hz bind
        assert!(value >= limit * (1.0 - 1e-8), "{value} < {limit}");
        assert_eq!(p["active"].as_bool().unwrap(), limit > 850.0, "{limit}");
        assert!(p["on_front"].as_bool().unwrap());
    }
    // a higher floor costs amplification
    for w in points.windows(2) {
        assert!(get(&w[1], "objective") <= get(&w[0], "objective") * (1.0 + 1e-9));
    }
    assert!(get(&points[4], "objective") < get(&points[1], "objective") - 1.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pareto_refuses_an_output_without_a_one_sided_constraint() {
    for (output, words) in [
        ("settling_time", "no constraint on \"settling_time\""),
        ("span_x", "has two limits"),
        ("bandwidth", "unknown output \"bandwidth\""),
    ] {
        let out = flexopt(&[
            "pareto",
            "problems/wei2017_dynamic.toml",
            "--vary",
            output,
            "--from",
            "1",
            "--to",
            "2",
        ]);
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("problems/wei2017_dynamic.toml")
                && err.contains("--vary")
                && err.contains(words),
            "{err}"
        );
    }
}

#[test]
fn dynamic_outputs_need_a_dynamics_section() {
    // wei2017.toml has no [dynamics]: eval leaves the dynamic outputs out, and a problem
    // that names one is refused at the key that does
    let out = flexopt(&["eval", "problems/wei2017.toml", "--design", OPTIMUM]);
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(json["outputs"]["k_out_actuated"].is_number());
    assert!(json["outputs"].get("natural_frequency").is_none());
    let text = std::fs::read_to_string("problems/wei2017.toml")
        .unwrap()
        .replacen("output = \"k_out\"", "output = \"natural_frequency\"", 1)
        .replacen(
            "unit = \"N/m\"\nlower = 3.8e4",
            "unit = \"Hz\"\nlower = 500",
            1,
        );
    let path = std::env::temp_dir().join(format!("flexopt-nodyn-{}.toml", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let out = flexopt(&["run", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("constraints[4].output") && err.contains("[dynamics]"),
        "{err}"
    );
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn run_and_pareto_reject_a_problem_without_free_variables() {
    // the sweep file fixes every variable: a clear error, not a panic
    for args in [
        &["run", "problems/wei2017_fig9.toml", "--out", "/nonexistent"][..],
        &[
            "pareto",
            "problems/wei2017_fig9.toml",
            "--vary",
            "k_out",
            "--from",
            "1",
            "--to",
            "2",
        ][..],
    ] {
        let out = flexopt(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("problems/wei2017_fig9.toml")
                && err.contains("`variables`")
                && err.contains("nothing to optimize")
                && !err.contains("panicked"),
            "{err}"
        );
    }
}

/// The issue's sliver links (issue 27, item 2): 40/-40/40 deg with 0.8 mm hinges, a link
/// about 0.5 mm across; 44/-44/44 deg with 20 mm lengths and 0.4 mm hinges, a needle.
const SLIVERS: [&str; 2] = [
    "l2=10,delta2=40,t2=0.8,l3=10,delta3=-40,l4=10,delta4=40,t4=0.8",
    "l2=20,delta2=44,t2=0.4,l3=20,delta3=-44,l4=20,delta4=44,t4=0.4",
];

/// What every refusal of a sliver says: the link, its width, the place and the rule.
fn assert_names_the_sliver(err: &str, rule: &str) {
    for quarter in ["upper left", "upper right", "lower left", "lower right"] {
        let at = err
            .find(&format!("the middle link c ({quarter}) is "))
            .unwrap_or_else(|| panic!("no {quarter} link in {err}"));
        let rest = &err[at..];
        let end = rest.find(";").unwrap_or(rest.len());
        let message = &rest[..end];
        assert!(
            message.contains(" mm across at (")
                && message.contains(&format!("thinner than the hinges it carries ({rule})")),
            "{message}"
        );
    }
}

#[test]
fn export_verify_and_run_refuse_a_sliver_link_with_exit_5() {
    let dir = std::env::temp_dir().join(format!("flexopt-sliver-{}", std::process::id()));
    let out_dir = dir.to_str().unwrap();
    for (design, rule) in SLIVERS.iter().zip(["0.8000 mm", "0.4000 mm"]) {
        for command in ["export", "verify"] {
            let out = flexopt(&[
                command,
                "problems/wei2017.toml",
                "--design",
                design,
                "--out",
                out_dir,
            ]);
            assert_eq!(out.status.code(), Some(5), "{command} {design}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(
                err.contains("problems/wei2017.toml")
                    && err.contains("this design gives no part that can be made"),
                "{err}"
            );
            assert_names_the_sliver(&err, rule);
            for file in ["part.dxf", "part.json", "verify.json", "stress.png"] {
                assert!(!dir.join(file).exists(), "{command} wrote {file}");
            }
        }
    }
    // a run whose optimum is the needle: the study is written, the part refused
    let problem = dir.join("sliver.toml");
    std::fs::write(&problem, SLIVER_PROBLEM).unwrap();
    let out = flexopt(&[
        "run",
        problem.to_str().unwrap(),
        "--quiet",
        "--out",
        out_dir,
    ]);
    assert_eq!(out.status.code(), Some(5));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("sliver.toml") && err.contains("no part that can be made"));
    assert_names_the_sliver(&err, "0.4000 mm");
    let optimum: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("optimum.json")).unwrap()).unwrap();
    let problems = optimum["part_problems"].as_array().unwrap();
    assert!(
        problems.len() == 4
            && problems
                .iter()
                .all(|p| p.as_str().unwrap().contains(" mm across at (")),
        "{problems:?}"
    );
    assert!(!dir.join("part.dxf").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A bridge whose lengths and angles are the needle's, only hinge b's thickness free.
const SLIVER_PROBLEM: &str = r#"
name = "sliver"
model = "bridge"

[material]
preset = "al7075-t6"

[hinge]
kind = "strip"
width = "10 mm"

[actuator]
nominal_stroke = "17.4 um"
preload = "40 N"

[[variables]]
name = "l2"
unit = "mm"
value = 20

[[variables]]
name = "delta2"
unit = "deg"
value = 44

[[variables]]
name = "t2"
unit = "mm"
lower = 0.4
upper = 0.5

[[variables]]
name = "l3"
unit = "mm"
value = 20

[[variables]]
name = "delta3"
unit = "deg"
value = -44

[[variables]]
name = "l4"
unit = "mm"
value = 20

[[variables]]
name = "delta4"
unit = "deg"
value = 44

[[variables]]
name = "t4"
unit = "mm"
value = 0.4

[objective]
maximize = "amplification"
absolute = true

# the part checked on the optimum only: the study's own rules would keep it from the sliver
[part]
enforce = false

[search]
starts = 4
seed = 1
"#;

#[test]
fn eval_takes_a_runs_optimum_and_run_takes_a_budget_of_fe_checks() {
    // eval --optimum: the run's design_si as it is, every output as the run reported it
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string("results/wei2017/optimum.json").unwrap())
            .unwrap();
    let out = flexopt_ok(&[
        "eval",
        "problems/wei2017.toml",
        "--optimum",
        "results/wei2017/optimum.json",
        "--format",
        "json",
    ]);
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["design"], report["design"]);
    for (name, v) in report["outputs"].as_object().unwrap() {
        let (a, b) = (v.as_f64().unwrap(), json["outputs"][name].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-12 * a.abs(), "{name}: {a} against {b}");
    }
    // one design source, not two
    let both = flexopt(&[
        "eval",
        "problems/wei2017.toml",
        "--design",
        OPTIMUM,
        "--optimum",
        "results/wei2017/optimum.json",
    ]);
    assert_eq!(both.status.code(), Some(2));
    // run --max-fe out of its range names the key and the range, before any work
    let out = flexopt(&[
        "run",
        "problems/wei2017.toml",
        "--max-fe",
        "1",
        "--out",
        "/nonexistent/x",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("wei2017.toml")
            && stderr.contains("`--max-fe`")
            && stderr.contains("between 2 and 200"),
        "{stderr}"
    );
}

#[test]
fn hinge_prints_a_table_with_units_or_json() {
    let args = [
        "hinge", "--kind", "circular", "--r", "1", "--t", "0.4", "--width", "10",
    ];
    let json: Value =
        serde_json::from_slice(&flexopt_ok(&[&args[..], &["--format", "json"]].concat()).stdout)
            .unwrap();
    let table = String::from_utf8(flexopt_ok(&[&args[..], &["--format", "table"]].concat()).stdout)
        .unwrap();
    // a row's value, read back, against the JSON's in the row's unit
    let row = |label: &str, unit: &str| -> f64 {
        let line = table
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap_or_else(|| panic!("no row {label}: {table}"));
        assert!(line.ends_with(unit), "{line}");
        line[label.len() + 2..line.len() - unit.len()]
            .trim()
            .parse()
            .unwrap()
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-4 * b.abs();
    assert!(table.starts_with("circular hinge, r = 1 mm, t = 0.4 mm, 10 mm wide, al7075-t6"));
    assert!(close(
        row("k33 (rotational)", "N m/rad"),
        json["stiffness"]["k33"].as_f64().unwrap()
    ));
    assert!(close(
        row("k11 (axial)", "N/um"),
        json["stiffness"]["k11"].as_f64().unwrap() * 1e-6
    ));
    assert!(close(
        row("c33 (slope per moment)", "rad/(N m)"),
        json["compliance"]["c33"].as_f64().unwrap()
    ));
    assert!(close(
        row("stress limit", "MPa"),
        json["stress_limit"].as_f64().unwrap() * 1e-6
    ));
    assert!(close(
        row("largest rotation", "deg"),
        json["max_rotation_deg"].as_f64().unwrap()
    ));
    assert!(close(
        row("length", "mm"),
        json["length_mm"].as_f64().unwrap()
    ));
    assert!(
        table.contains("t/r = 0.4000 (fitted for .. 1): inside"),
        "{table}"
    );
    // into a pipe without --format: JSON, what scripts read
    let piped: Value = serde_json::from_slice(&flexopt_ok(&args).stdout).unwrap();
    assert_eq!(piped["kind"], "circular");
}

#[test]
fn outputs_of_a_problem_file_list_its_own_hinge_kinds_parameters() {
    let params = |args: &[&str]| -> Vec<String> {
        let text = String::from_utf8(flexopt_ok(args).stdout).unwrap();
        text.lines()
            .skip(1)
            .take_while(|l| l.starts_with("  "))
            .map(|l| l.split_whitespace().next().unwrap().to_string())
            .collect()
    };
    // bridge_circular.toml's hinges are circular notches: radius and least thickness
    let circular = params(&["outputs", "problems/bridge_circular.toml"]);
    assert_eq!(
        circular,
        ["r2", "delta2", "t2", "l3", "delta3", "r4", "delta4", "t4"]
    );
    // the model as `init` writes it: strips
    let template = params(&["outputs", "--model", "bridge"]);
    assert_eq!(
        template,
        ["l2", "delta2", "t2", "l3", "delta3", "l4", "delta4", "t4"]
    );
    // a file that does not read: its name and exit 2
    let out = flexopt(&["outputs", "problems/none.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("problems/none.toml"));
}
