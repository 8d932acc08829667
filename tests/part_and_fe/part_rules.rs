//! The part's rules as constraints of the design (issue 23): each smooth rule of the
//! bridge changes sign where the part's own check flips, its gradient is exact, and the
//! study keeps to the rules unless the file says `[part] enforce = false`.

use crate::common;

use common::{flexopt, random_design, rng, table1_bounds, table1_optimum, wei2017_settings, MM};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::part_rules::TOLERANCE;
use flexopt::model::PartMaker;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

fn bridge(part: PartSettings) -> Bridge {
    let mut s = wei2017_settings();
    s.part = part;
    Bridge::new(s)
}

/// Sizes drawn so that every rule is met on some designs and broken on others.
fn random_settings(r: &mut ChaCha8Rng) -> PartSettings {
    PartSettings {
        link_thickness: r.random_range(0.3..4.0) * MM,
        fillet_radius: r.random_range(0.0..0.4) * MM,
        input_block_width: r.random_range(0.3..3.0) * MM,
        input_block_height: r.random_range(1.0..8.0) * MM,
        output_block_width: r.random_range(0.2..6.0) * MM,
        output_block_height: r.random_range(0.3..6.0) * MM,
        min_slot: r.random_range(0.0..1.0) * MM,
        actuator_length: Some(r.random_range(5.0..45.0) * MM),
        actuator_height: None,
        enforce: true,
    }
}

/// The rules that model a check, and whether a problem the spec reports is the check's.
type Check = (&'static [&'static str], fn(&str) -> bool);

/// Each check the spec makes before building solids: the rules that model it (the check
/// trips where the least of their margins is below `-TOLERANCE`) and how its message is
/// told apart from the others.
const CHECKS: [Check; 7] = [
    (&["link_thickness_b", "link_thickness_d"], |p| {
        p.starts_with("part.link_thickness (")
    }),
    (&["input_block_width_b", "input_block_width_d"], |p| {
        p.starts_with("part.input_block_width (")
    }),
    (&["output_block_height_b", "output_block_height_d"], |p| {
        p.starts_with("part.output_block_height (") && p.contains("thinner than the hinges")
    }),
    (&["input_block_faces"], |p| {
        p.starts_with("part.input_block_height (")
    }),
    (&["output_block_faces"], |p| {
        p.contains("does not hold the faces of hinges d")
    }),
    (&["output_slot_bottom", "output_slot_top"], |p| {
        p.contains("sides")
    }),
    (&["actuator_pocket"], |p| p.contains("actuator's pocket")),
];

/// The least margin of the rules `names` at `x`, and whether the check that they model
/// trips there.
fn margin_and_check(
    model: &Bridge,
    names: &[&str],
    tripped: fn(&str) -> bool,
    x: &[f64],
) -> (f64, bool) {
    let rules = model.rules();
    let mut m = vec![0.0; rules.len()];
    model.rule_margins(x, &mut m);
    let least = rules
        .iter()
        .zip(&m)
        .filter(|(r, _)| names.contains(&r.name))
        .map(|(_, &v)| v)
        .fold(f64::INFINITY, f64::min);
    let trips = match model.part(x) {
        Ok(_) => false,
        Err(problems) => problems.iter().any(|p| tripped(p)),
    };
    (least, trips)
}

#[test]
fn each_rule_changes_sign_where_the_parts_check_flips_to_1e_9_mm() {
    let mut r = rng(23);
    let mut met = [0usize; CHECKS.len()];
    let mut broken = [0usize; CHECKS.len()];
    let mut flips = [0usize; CHECKS.len()];
    for _ in 0..1000 {
        let model = bridge(random_settings(&mut r));
        let (a, b) = (random_design(&mut r), random_design(&mut r));
        for (k, (names, tripped)) in CHECKS.iter().enumerate() {
            let (ma, ta) = margin_and_check(&model, names, *tripped, &a);
            if ma.abs() > TOLERANCE {
                assert_eq!(ta, ma < 0.0, "{names:?}: margin {ma} m at {a:?}");
                if ta {
                    broken[k] += 1
                } else {
                    met[k] += 1
                }
            }
            let (_, tb) = margin_and_check(&model, names, *tripped, &b);
            if ta == tb {
                continue;
            }
            // between a design that passes the check and one that does not, the check
            // flips where the least margin is zero: bisect on the check alone
            let at =
                |t: f64| -> Vec<f64> { a.iter().zip(&b).map(|(p, q)| p + t * (q - p)).collect() };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if margin_and_check(&model, names, *tripped, &at(mid)).1 == ta {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            for t in [lo, hi] {
                let (m, _) = margin_and_check(&model, names, *tripped, &at(t));
                assert!(
                    (m + TOLERANCE).abs() <= 1e-12,
                    "{names:?}: the check flips at a margin of {m} m, not 1e-9 mm from the \
                     rule's zero"
                );
            }
            flips[k] += 1;
        }
    }
    for (k, (names, _)) in CHECKS.iter().enumerate() {
        assert!(
            met[k] >= 20 && broken[k] >= 20 && flips[k] >= 20,
            "{names:?}: {} met, {} broken, {} flips: the draws do not exercise it",
            met[k],
            broken[k],
            flips[k]
        );
    }
}

#[test]
fn each_rules_gradient_agrees_with_central_differences() {
    let mut r = rng(2023);
    let mut compared = 0;
    for _ in 0..200 {
        let settings = random_settings(&mut r);
        let model = bridge(settings.clone());
        let x = random_design(&mut r);
        let n = model.rules().len();
        let (mut m, mut jac) = (vec![0.0; n], vec![0.0; n * 8]);
        model.rule_margins_with_gradient(&x, &mut m, &mut jac);
        let mut plain = vec![0.0; n];
        model.rule_margins(&x, &mut plain);
        assert_eq!(m, plain, "the values with and without gradients differ");
        // the faces' half widths switch from the link's to the hinge's: no derivative there
        let near_kink = [x[2], x[7]].iter().any(|t| {
            (0.5 * settings.link_thickness - (0.5 * t + settings.fillet_radius)).abs() < 1e-6
        });
        if near_kink {
            continue;
        }
        for p in 0..8 {
            // a step of the parameter's range: rules are sums of terms much larger than
            // some of their derivatives
            let (lo, hi) = table1_bounds()[p];
            let h = 1e-6 * (hi - lo);
            let (mut up, mut down) = (x, x);
            up[p] += h;
            down[p] -= h;
            let (mut mu, mut md) = (vec![0.0; n], vec![0.0; n]);
            model.rule_margins(&up, &mut mu);
            model.rule_margins(&down, &mut md);
            for i in 0..n {
                let fd = (mu[i] - md[i]) / (2.0 * h);
                let exact = jac[i * 8 + p];
                assert!(
                    (fd - exact).abs() <= 1e-6 * exact.abs() + 1e-9,
                    "rule {}: d/dx{p} exact {exact}, differences {fd}",
                    model.rules()[i].name
                );
                compared += 1;
            }
        }
    }
    assert!(compared > 10_000, "{compared}");
}

#[test]
fn table_1s_optimum_meets_every_rule_and_its_part_is_made() {
    let model = bridge(PartSettings {
        actuator_length: Some(20.0 * MM),
        ..PartSettings::default()
    });
    let x = table1_optimum();
    let mut m = vec![0.0; model.rules().len()];
    model.rule_margins(&x, &mut m);
    assert_eq!(m.len(), 11);
    assert!(m.iter().all(|&v| v > 0.1 * MM), "{m:?}");
    assert!(flexopt::model::build_part(&model, &x).is_ok());
}

/// wei2017 with `part` as its `[part]` section, in a fresh `dir`; the file's path.
fn with_part(dir: &std::path::Path, part: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string("problems/wei2017.toml")
        .unwrap()
        .replace("[search]", &format!("[part]\n{part}\n\n[search]"));
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("s.toml");
    std::fs::write(&file, text).unwrap();
    file
}

/// Output blocks too low for the faces of hinges d at the angles of Table 1's optimum.
const LOW: &str = "output_block_height = \"2.5 mm\"";

/// `flexopt run` of `file` into `out`, quiet, with `extra` options.
fn run(file: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["run", file.to_str().unwrap(), "--quiet", "--out"];
    args.push(out.to_str().unwrap());
    args.extend(extra);
    flexopt(&args)
}

/// The `optimum.json` in `out`.
fn optimum(out: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("optimum.json")).unwrap()).unwrap()
}

#[test]
fn the_study_keeps_to_the_rules_and_names_the_binding_one_unless_told_not_to() {
    let dir = std::env::temp_dir().join(format!("flexopt-rules-{}", std::process::id()));
    let out = dir.join("enforced");
    let o = run(&with_part(&dir, LOW), &out, &[]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        text.contains("active: ") && text.contains("part rule output_block_faces"),
        "{text}"
    );
    for f in ["part.dxf", "part.svg", "part.json", "part.png"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let json = optimum(&out);
    let rules = json["part_rules"].as_array().unwrap();
    assert_eq!(rules.len(), 11);
    let active: Vec<&str> = rules
        .iter()
        .filter(|r| r["active"] == true)
        .map(|r| r["rule"].as_str().unwrap())
        .collect();
    assert_eq!(active, ["output_block_faces"]);
    assert!(rules.iter().all(|r| r["met"] == true));
    assert_eq!(json["feasible"], true);
    // the faces tilted until they fit: 2 h_d cos(delta4) = 2.5 mm with h_d = 1.5 mm
    let delta4 = json["design_si"]["delta4"].as_f64().unwrap();
    assert!(
        (3.0 * MM * delta4.cos() - 2.5 * MM).abs() < 1e-12,
        "{delta4}"
    );

    // not enforced: today's study, whose optimum's part cannot be made
    let out = dir.join("checked");
    let o = run(
        &with_part(&dir, &format!("{LOW}\nenforce = false")),
        &out,
        &[],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(5), "{err}");
    assert!(
        err.contains("part.output_block_height (2.5 mm) does not hold the faces of hinges d"),
        "{err}"
    );
    assert!(!out.join("part.dxf").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn eval_lists_each_rules_margin_and_marks_the_broken_one() {
    let dir = std::env::temp_dir().join(format!("flexopt-rules-eval-{}", std::process::id()));
    let file = with_part(&dir, LOW);
    let design = "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4";
    let file = file.to_str().unwrap();
    let out = flexopt(&["eval", file, "--format", "table", "--design", design]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().filter(|l| l.contains("BROKEN")).collect();
    // 2.5 mm - 2 (1.5 mm) cos(4.07 deg)
    let margin = 2.5 - 3.0 * (4.07_f64).to_radians().cos();
    assert_eq!(lines.len(), 1, "{text}");
    let fields: Vec<&str> = lines[0].split_whitespace().collect();
    assert_eq!(fields[0], "output_block_faces", "{text}");
    assert!(
        (fields[1].parse::<f64>().unwrap() - margin).abs() < 1e-5,
        "{text}"
    );
    assert!(text.contains("feasible: NO"), "{text}");
    assert_eq!(text.matches("  link_thickness_").count(), 2, "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_study_no_start_of_which_meets_the_rules_exits_5_naming_the_part_size() {
    let dir = std::env::temp_dir().join(format!("flexopt-rules-thin-{}", std::process::id()));
    // links thinner than the thinnest hinge the bounds allow (0.4 mm): no design is made
    let out = dir.join("out");
    let o = run(
        &with_part(&dir, "link_thickness = \"0.3 mm\""),
        &out,
        &["--starts", "8"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(5), "{err}");
    assert!(
        err.contains("no start ended at a design whose part can be made")
            && err.contains("part.link_thickness (0.3 mm) is thinner than the hinges"),
        "{err}"
    );
    assert_eq!(optimum(&out)["feasible"], false);
    assert!(!out.join("part.dxf").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
