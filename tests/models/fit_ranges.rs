//! The ranges where each hinge kind's formulas hold (issue 27, item 6): each kind declares
//! them, the docs show them as the code has them (with the FE figures at their edges),
//! `flexopt hinge` and `flexopt eval` warn of a hinge outside one and of no other, and a
//! study keeps to them as constraints with exact gradients unless the file says otherwise.

use std::path::{Path, PathBuf};

use crate::common::{flexopt, flexopt_ok, rng};
use flexopt::model::hinge::{fit_table, HingeKind};
use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};
use rand::Rng;

/// A ratio as a warning shows it: five significant digits.
fn shown(v: f64) -> String {
    flexopt::problem::units::short(format!("{v:.4e}").parse().unwrap())
}

/// One kind: dimensions (mm, the kind's order) inside every range, and for each range
/// dimensions outside it alone.
struct Case {
    kind: HingeKind,
    inside: Vec<f64>,
    outside: Vec<Vec<f64>>,
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            kind: HingeKind::Strip,
            inside: vec![2.0, 0.4],
            outside: vec![vec![0.4, 0.4]],
        },
        Case {
            kind: HingeKind::Circular,
            inside: vec![1.0, 0.4],
            // the notch: r = 0.25 mm, t = 2 mm
            outside: vec![vec![0.25, 2.0]],
        },
        Case {
            kind: HingeKind::Elliptical,
            inside: vec![2.0, 1.0, 0.4],
            outside: vec![vec![1.0, 2.0, 0.4], vec![2.0, 0.5, 1.0]],
        },
        Case {
            kind: HingeKind::CornerFilleted,
            inside: vec![4.0, 0.4, 0.1],
            // the fillet: r = 0.001 mm
            outside: vec![vec![4.0, 0.4, 0.001], vec![2.0, 1.6, 0.2]],
        },
    ]
}

/// The ratio of range `k` of `kind` at `dims`, its name and the range's words.
fn ratio(kind: HingeKind, k: usize, dims: &[f64]) -> (f64, String, String) {
    let f = kind.fit()[k];
    let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
    (
        dims[f.numerator] / dims[f.denominator],
        format!("{}/{}", stems[f.numerator], stems[f.denominator]),
        f.range.text(),
    )
}

#[test]
fn the_cases_lie_where_they_say() {
    for c in cases() {
        assert_eq!(c.outside.len(), c.kind.fit().len(), "{:?}", c.kind);
        for (k, f) in c.kind.fit().iter().enumerate() {
            assert!(f.range.contains(ratio(c.kind, k, &c.inside).0));
            for (j, dims) in c.outside.iter().enumerate() {
                assert_eq!(f.range.contains(ratio(c.kind, k, dims).0), j != k);
            }
        }
    }
}

#[test]
fn the_docs_show_every_kinds_ranges_as_the_code_declares_them() {
    // the table of ranges is made from the kinds' declarations: both docs show it whole
    let table = fit_table();
    for doc in ["docs/hinges.md", "docs/guide/src/hinges.md"] {
        let text = std::fs::read_to_string(doc).unwrap();
        assert!(
            text.contains(table.trim()),
            "{doc} does not show the ranges the hinge kinds declare:\n{table}"
        );
    }
    // and the FE figures at each range's edge and beyond it, written by `cargo run
    // --release --example hinge_accuracy` (checked byte for byte in CI), measure the same
    // ranges
    let measured = std::fs::read_to_string("results/hinges/fit_ranges.md").unwrap();
    let doc = std::fs::read_to_string("docs/hinges.md").unwrap();
    assert!(
        doc.contains(measured.trim()),
        "docs/hinges.md does not show results/hinges/fit_ranges.md"
    );
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("results/hinges/fit_ranges.json").unwrap())
            .unwrap();
    let rows = rows.as_array().unwrap();
    for &kind in HingeKind::ALL {
        assert!(!kind.fit().is_empty(), "{kind:?} declares no range");
        for (k, f) in kind.fit().iter().enumerate() {
            let (_, name, text) = ratio(kind, k, &[1.0; 3]);
            let of_it: Vec<&serde_json::Value> = rows
                .iter()
                .filter(|r| r["kind"] == kind.name() && r["ratio"] == name.as_str())
                .collect();
            assert!(
                of_it.iter().all(|r| r["range"] == text.as_str()),
                "{kind:?} {name}: the committed measurements are of another range"
            );
            let bound = f.range.lower.or(f.range.upper).unwrap();
            assert!(
                of_it
                    .iter()
                    .any(|r| r["value"].as_f64() == Some(bound) && r["inside"] == true),
                "{kind:?} {name}: no measurement at the edge {bound}"
            );
            assert!(
                of_it.iter().any(|r| r["inside"] == false),
                "{kind:?} {name}: no measurement outside the range"
            );
        }
    }
}

#[test]
fn flexopt_hinge_warns_of_each_range_it_is_outside_and_of_no_other() {
    for c in cases() {
        let run = |dims: &[f64]| {
            let mut args = vec![
                "hinge".to_string(),
                "--kind".into(),
                c.kind.name().into(),
                "--width".into(),
                "10".into(),
            ];
            for (d, v) in c.kind.dimensions().iter().zip(dims) {
                args.push(format!("--{}", d.stem));
                args.push(v.to_string());
            }
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let out = flexopt_ok(&args);
            let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            (String::from_utf8_lossy(&out.stderr).to_string(), json)
        };
        let (err, json) = run(&c.inside);
        assert!(!err.contains("warning"), "{:?} inside: {err}", c.kind);
        let checks = json["fit_ranges"].as_array().unwrap();
        assert_eq!(checks.len(), c.kind.fit().len());
        assert!(checks.iter().all(|k| k["inside"] == true), "{json}");
        for (k, dims) in c.outside.iter().enumerate() {
            let (err, json) = run(dims);
            let (value, name, text) = ratio(c.kind, k, dims);
            let value = shown(value);
            let wanted = format!(
                "warning: the {} hinge: {name} = {value} lies outside {name} {text}, the range \
                 of ",
                c.kind.name()
            );
            assert!(err.contains(&wanted), "{wanted:?} not in {err}");
            assert_eq!(err.matches("warning").count(), 1, "{err}");
            let checks = json["fit_ranges"].as_array().unwrap();
            for (j, check) in checks.iter().enumerate() {
                assert_eq!(check["inside"] == true, j != k, "{json}");
            }
        }
    }
}

/// A bridge problem whose hinges are both of `kind`: hinge b's dimensions free within
/// `b_bounds` (mm), hinge d's fixed at `d` (mm), the link and angles fixed; `tail` adds
/// keys at the end (`[search]`).
fn bridge_problem(kind: HingeKind, b_bounds: &[(f64, f64)], d: &[f64], tail: &str) -> String {
    let mut text = format!(
        "name = \"fit_{}\"\nmodel = \"bridge\"\n\n[material]\npreset = \"al7075-t6\"\n\n\
         [hinge]\nkind = \"{}\"\nwidth = \"10 mm\"\n\n[actuator]\nnominal_stroke = \"17.4 um\"\n\
         preload = \"40 N\"\n",
        kind.name().replace('-', "_"),
        kind.name()
    );
    let mut var = |name: String, unit: &str, bounds: (f64, f64)| {
        text += &format!("\n[[variables]]\nname = \"{name}\"\nunit = \"{unit}\"\n");
        text += &if bounds.0 == bounds.1 {
            format!("value = {}\n", bounds.0)
        } else {
            format!("lower = {}\nupper = {}\n", bounds.0, bounds.1)
        };
    };
    for (k, dim) in kind.dimensions().iter().enumerate() {
        var(format!("{}2", dim.stem), "mm", b_bounds[k]);
        var(format!("{}4", dim.stem), "mm", (d[k], d[k]));
    }
    var("delta2".into(), "deg", (10.0, 10.0));
    var("l3".into(), "mm", (8.0, 8.0));
    var("delta3".into(), "deg", (5.0, 5.0));
    var("delta4".into(), "deg", (10.0, 10.0));
    text + "\n[objective]\nmaximize = \"k_in\"\n" + tail
}

/// A folder of this test's own for its files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fit_ranges")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn flexopt_eval_warns_of_a_hinge_outside_its_range_naming_it() {
    let dir = scratch("eval");
    for c in cases() {
        for (tail, warns) in [
            ("", true),
            ("\n[search]\nfit_ranges = \"warn\"\n", true),
            ("\n[search]\nfit_ranges = \"allow\"\n", false),
        ] {
            // wide bounds, but a fillet at most half its leaf's least length
            let bounds = match c.kind {
                HingeKind::CornerFilleted => vec![(1.0, 20.0), (0.001, 20.0), (0.0005, 0.5)],
                _ => c.inside.iter().map(|_| (0.001, 20.0)).collect(),
            };
            let file = dir.join(format!("{}.toml", c.kind.name()));
            std::fs::write(&file, bridge_problem(c.kind, &bounds, &c.inside, tail)).unwrap();
            let file = file.to_str().unwrap();
            let eval = |dims: &[f64]| {
                let design: Vec<String> = c
                    .kind
                    .dimensions()
                    .iter()
                    .zip(dims)
                    .map(|(d, v)| format!("{}2={v}", d.stem))
                    .collect();
                let out = flexopt_ok(&[
                    "eval",
                    file,
                    "--design",
                    &design.join(","),
                    "--format",
                    "json",
                ]);
                let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
                (String::from_utf8_lossy(&out.stderr).to_string(), json)
            };
            let (err, json) = eval(&c.inside);
            assert!(!err.contains("range of"), "{:?} inside: {err}", c.kind);
            assert_eq!(json["feasible"], true, "{json}");
            for (k, dims) in c.outside.iter().enumerate() {
                let (err, json) = eval(dims);
                let (value, name, text) = ratio(c.kind, k, dims);
                let (num, den) = name.split_once('/').unwrap();
                let name = format!("{num}2/{den}2");
                let value = shown(value);
                let wanted = format!(
                    "warning: {file}: hinge b ({}): {name} = {value} lies outside {name} {text}",
                    c.kind.name()
                );
                assert_eq!(
                    err.contains(&wanted),
                    warns,
                    "{tail:?}: {wanted:?} in {err}?"
                );
                assert!(!err.contains("hinge d"), "{err}");
                let check = json["fit_ranges"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|r| r["ratio"] == name.as_str())
                    .unwrap();
                assert_eq!(check["inside"], false);
                assert_eq!(check["owner"], format!("hinge b ({})", c.kind.name()));
                // outside a range the file makes a constraint: not feasible
                assert_eq!(json["feasible"], !tail.is_empty(), "{tail:?}: {json}");
            }
        }
    }
}

/// Hinge b's bounds (mm) for the stiffest bridge, whose hinge b leaves a range of its kind
/// when nothing keeps it in: short, thick, shallow hinges.
fn stiff_bounds(kind: HingeKind) -> Vec<(f64, f64)> {
    match kind {
        HingeKind::Strip => vec![(0.5, 20.0), (0.4, 2.0)],
        HingeKind::Circular => vec![(0.25, 10.0), (0.4, 2.0)],
        HingeKind::Elliptical => vec![(0.25, 10.0), (0.25, 10.0), (0.4, 2.0)],
        HingeKind::CornerFilleted => vec![(1.0, 20.0), (0.4, 2.0), (0.02, 0.5)],
    }
}

fn study_of(text: &str) -> (Problem, Vec<f64>) {
    let problem = Problem::parse(Path::new("fit.toml"), text).unwrap();
    let mut options = StudyOptions::from_problem(&problem);
    options.starts = 12;
    options.threads = 1;
    let s = study::run(&problem, &options);
    assert!(s.any_feasible && s.best_converged, "{text}");
    let x = s.reported_design().to_vec();
    (problem, x)
}

#[test]
fn a_study_keeps_to_every_kinds_ranges_unless_the_file_lets_it_leave_them() {
    for c in cases() {
        let bounds = stiff_bounds(c.kind);
        // let out: the stiffest bridge's hinge b leaves a range
        let (p, x) = study_of(&bridge_problem(
            c.kind,
            &bounds,
            &c.inside,
            "\n[search]\nfit_ranges = \"warn\"\n",
        ));
        let free = flexopt::problem::fit::checks(&p, &x);
        assert!(free.iter().any(|k| !k.inside), "{:?}: {free:?}", c.kind);
        let k_free = flexopt::report::DesignReport::new(&p, &x)
            .objective
            .unwrap();
        // kept in (the default): the optimum inside every range, on the edge of one, and
        // less stiff than the one outside
        let (p, x) = study_of(&bridge_problem(c.kind, &bounds, &c.inside, ""));
        let kept = flexopt::problem::fit::checks(&p, &x);
        assert!(kept.iter().all(|k| k.inside), "{:?}: {kept:?}", c.kind);
        assert!(
            kept.iter().any(|k| [k.lower, k.upper]
                .iter()
                .flatten()
                .any(|b| (k.value - b).abs() <= 1e-6 * b)),
            "{:?}: no range active at the optimum: {kept:?}",
            c.kind
        );
        let report = flexopt::report::DesignReport::new(&p, &x);
        assert!(report.feasible);
        assert!(report.objective.unwrap() < k_free, "{:?}", c.kind);
    }
}

#[test]
fn the_ranges_reach_the_solver_as_rows_with_exact_gradients() {
    let mut r = rng(27);
    for c in cases() {
        let p = Problem::parse(
            Path::new("fit.toml"),
            &bridge_problem(c.kind, &stiff_bounds(c.kind), &c.inside, ""),
        )
        .unwrap();
        // the study's first stage: no constraint in the file, so every row is a bound of a
        // range of hinge b's or d's, then the part's size rules, whose rows' gradients are
        // checked here too (the clearances, kept for each start's end, are checked with
        // their kinks in tests/part_and_fe/part_rules.rs)
        let nlp = DesignNlp::first_stage(&p).unwrap();
        let rules = p.mechanism().part_maker.as_ref().unwrap().first_rules();
        assert_eq!(rules, 10, "{:?}", c.kind);
        let bounds: usize = c
            .kind
            .fit()
            .iter()
            .map(|f| f.range.lower.is_some() as usize + f.range.upper.is_some() as usize)
            .sum();
        assert_eq!(nlp.constraint_count(), 2 * bounds + rules, "{:?}", c.kind);
        let n = nlp.dimension();
        let m = nlp.constraint_count();
        for _ in 0..20 {
            let u: Vec<f64> = (0..n).map(|_| r.random_range(0.1..0.9)).collect();
            let (mut cv, mut g, mut jac) = (vec![0.0; m], vec![0.0; n], vec![0.0; m * n]);
            nlp.evaluate_with_gradient(&u, &mut cv, &mut g, &mut jac);
            for j in 0..n {
                let h = 1e-6;
                let at = |s: f64| {
                    let mut v = u.clone();
                    v[j] += s * h;
                    let mut out = vec![0.0; m];
                    nlp.evaluate(&v, &mut out);
                    out
                };
                let (lo, hi) = (at(-1.0), at(1.0));
                for i in 0..m {
                    let fd = (hi[i] - lo[i]) / (2.0 * h);
                    let exact = jac[i * n + j];
                    assert!(
                        (fd - exact).abs() <= 1e-6 * exact.abs().max(1.0),
                        "{:?} row {i}, variable {j}: exact {exact}, differences {fd}",
                        c.kind
                    );
                }
            }
        }
    }
}

#[test]
fn a_study_whose_bounds_cannot_reach_a_range_is_refused_naming_it() {
    let dir = scratch("unreachable");
    // the notch, r and t fixed: t/r = 8
    let file = dir.join("notch.toml");
    let text = bridge_problem(
        HingeKind::Circular,
        &[(0.25, 0.25), (2.0, 2.0)],
        &[1.0, 0.4],
        "",
    )
    .replace(
        "name = \"l3\"\nunit = \"mm\"\nvalue = 8",
        "name = \"l3\"\nunit = \"mm\"\nlower = 4\nupper = 10",
    );
    std::fs::write(&file, &text).unwrap();
    let out_dir = dir.join("out");
    let (f, o) = (file.to_str().unwrap(), out_dir.to_str().unwrap());
    let out = flexopt(&["run", f, "--quiet", "--out", o]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("variables `t2` and `r2`: hinge b (circular): t2/r2 is 8 at their fixed values, never at most 1")
            && err.contains("fit_ranges = \"warn\""),
        "{err}"
    );
    assert!(
        !out_dir.exists(),
        "a refused run wrote {}",
        out_dir.display()
    );
    // let out, the same study runs, and warns of its optimum
    std::fs::write(
        &file,
        text + "\n[search]\nfit_ranges = \"warn\"\nstarts = 4\n",
    )
    .unwrap();
    let out = flexopt_ok(&["run", f, "--quiet", "--out", o]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("hinge b (circular): t2/r2 = 8 lies outside t2/r2 at most 1"),
        "{err}"
    );
    // an unknown treatment is named with its key and the three there are
    std::fs::write(
        &file,
        bridge_problem(
            HingeKind::Circular,
            &[(0.25, 2.0), (0.4, 2.0)],
            &[1.0, 0.4],
            "",
        ) + "\n[search]\nfit_ranges = \"sometimes\"\n",
    )
    .unwrap();
    let out = flexopt(&["eval", file.to_str().unwrap(), "--design", "r2=1,t2=0.4"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("search.fit_ranges")
            && err.contains("constraint")
            && err.contains("warn")
            && err.contains("allow"),
        "{err}"
    );
}

#[test]
fn the_schema_offers_the_three_treatments() {
    let out = flexopt_ok(&["schema"]);
    let text = String::from_utf8_lossy(&out.stdout);
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let all = schema.to_string();
    for value in ["\"constraint\"", "\"warn\"", "\"allow\""] {
        assert!(all.contains(value), "{value} not in the schema");
    }
    assert!(all.contains("\"fit_ranges\""));
}
