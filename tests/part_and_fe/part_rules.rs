//! The part's rules as constraints of the design (issue 23): each smooth rule of the
//! bridge changes sign where the part's own check flips, its gradient is exact, and the
//! study keeps to the rules unless the file says `[part] enforce = false`.

use crate::common;

use common::{flexopt, random_design, rng, table1_bounds, table1_optimum, wei2017_settings, MM};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::part_rules::TOLERANCE;
use flexopt::model::PartMaker;
use flexopt::part::checks::before_union;
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
        actuator_height: Some(r.random_range(1.0..8.0) * MM),
        enforce: true,
    }
}

/// The least margin at `x` of the rules `keep` takes (by their index and name).
fn least_margin(model: &Bridge, x: &[f64], keep: impl Fn(usize, &str) -> bool) -> f64 {
    let rules = model.rules();
    let mut m = vec![0.0; rules.len()];
    model.rule_margins(x, &mut m);
    rules
        .iter()
        .zip(&m)
        .enumerate()
        .filter(|(i, (r, _))| keep(*i, &r.name))
        .map(|(_, (_, &v))| v)
        .fold(f64::INFINITY, f64::min)
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
    let least = least_margin(model, x, |_, name| names.contains(&name));
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

/// The least margin of the clearance rules (those after the first ones, but the link's
/// width) at `x`, and whether the part's check of its placed solids (keep-out bands, slots,
/// the actuator) finds a problem there; `None` where a size rule leaves no part to place.
fn clearance_and_check(model: &Bridge, x: &[f64]) -> Option<(f64, bool)> {
    let spec = model.part(x).ok()?;
    let first = model.first_rules();
    let least = least_margin(model, x, |i, name| i >= first && name != "link_width");
    Some((least, !before_union(&spec).is_empty()))
}

#[test]
fn the_clearance_rules_change_sign_where_the_check_of_the_solids_flips_to_1e_9_mm() {
    let mut r = rng(1023);
    let (mut met, mut broken, mut flips) = (0, 0, 0);
    for _ in 0..3000 {
        let model = bridge(random_settings(&mut r));
        let (a, b) = (random_design(&mut r), random_design(&mut r));
        let Some((ma, ta)) = clearance_and_check(&model, &a) else {
            continue;
        };
        if ma.abs() > TOLERANCE {
            assert_eq!(ta, ma < 0.0, "margin {ma} m at {a:?}");
            if ta {
                broken += 1
            } else {
                met += 1
            }
        }
        let Some((_, tb)) = clearance_and_check(&model, &b) else {
            continue;
        };
        if ta == tb {
            continue;
        }
        let at = |t: f64| -> Vec<f64> { a.iter().zip(&b).map(|(p, q)| p + t * (q - p)).collect() };
        // bisect on the check alone, along a line on which every part can be placed
        let (mut lo, mut hi) = (0.0, 1.0);
        let mut placed = true;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            match clearance_and_check(&model, &at(mid)) {
                Some((_, t)) if t == ta => lo = mid,
                Some(_) => hi = mid,
                None => {
                    placed = false;
                    break;
                }
            }
        }
        if !placed {
            continue;
        }
        for t in [lo, hi] {
            // the check tolerates what the study's feasibility tolerance lets a rule fall
            // short, 1e-9 mm: it flips there (an inset band's corner, up to twice that)
            let (m, _) = clearance_and_check(&model, &at(t)).unwrap();
            assert!(
                (m + TOLERANCE).abs() <= TOLERANCE,
                "the check flips at a margin of {m} m, not within 1e-9 mm of the rules' -1e-9 mm"
            );
        }
        flips += 1;
    }
    assert!(
        met >= 20 && broken >= 50 && flips >= 20,
        "{met} met, {broken} broken, {flips} flips: the draws do not exercise the rules"
    );
}

#[test]
fn the_link_width_rule_agrees_with_the_width_check_of_the_outline() {
    // the check erodes the outline's bodies (geo's buffer, round joins of 0.05 rad) and
    // bisects the widest disc to 1e-5 of its width, with a slack of 1e-4: it is as sharp as
    // that, 2e-4 mm on a 2 mm hinge
    let sharp = 2e-3 * MM;
    let mut r = rng(923);
    let (mut thin, mut wide) = (0, 0);
    for _ in 0..400 {
        // Table 1's bridge with its middle link swung and its hinges thickened: links
        // about as wide as their hinges
        let model = bridge(PartSettings {
            link_thickness: r.random_range(1.5..3.5) * MM,
            ..PartSettings::default()
        });
        let mut x = table1_optimum();
        x[2] = r.random_range(0.4..2.0) * MM;
        x[3] = r.random_range(3.0..12.0) * MM;
        x[4] = r.random_range(-45.0_f64..45.0).to_radians();
        x[7] = r.random_range(0.4..2.0) * MM;
        let Some((_, false)) = clearance_and_check(&model, &x) else {
            continue;
        };
        let rules = model.rules();
        let mut m = vec![0.0; rules.len()];
        model.rule_margins(&x, &mut m);
        let width = m[rules.iter().position(|r| r.name == "link_width").unwrap()];
        if width.abs() < sharp {
            continue;
        }
        let too_thin = match flexopt::model::build_part(&model, &x) {
            Ok(_) => false,
            Err(e) => e
                .problems
                .iter()
                .any(|p| p.starts_with("the middle link c") && p.contains(" across at ")),
        };
        assert_eq!(too_thin, width < 0.0, "link_width {width} m at {x:?}");
        if too_thin {
            thin += 1
        } else {
            wide += 1
        }
    }
    assert!(
        thin >= 10 && wide >= 10,
        "{thin} too thin, {wide} wide enough"
    );
}

#[test]
fn each_rules_gradient_agrees_with_central_differences() {
    let mut r = rng(2023);
    let (mut compared, mut kinks) = (0, 0);
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
                // a clearance is the least over pairs of corners and sides: where the
                // nearest pair changes within the step, the one-sided differences disagree,
                // and there is no derivative to compare with
                let (forward, backward) = ((mu[i] - m[i]) / h, (m[i] - md[i]) / h);
                // the size rules are sums of a few terms; a clearance solves for its nearest
                // points, whose rounding the differences see at 1e-8
                let floor = if i < model.first_rules() { 1e-9 } else { 1e-7 };
                if (forward - backward).abs() > 1e-4 * exact.abs() + 1e-7 {
                    kinks += 1;
                    continue;
                }
                assert!(
                    (fd - exact).abs() <= 1e-6 * exact.abs() + floor,
                    "rule {}: d/dx{p} exact {exact}, differences {fd}",
                    model.rules()[i].name
                );
                compared += 1;
            }
        }
    }
    assert!(
        compared > 50_000 && kinks * 100 < compared,
        "{compared} compared, {kinks} at kinks"
    );
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
    // the size rules and the pocket's first, then the clearances
    assert_eq!(model.first_rules(), 11);
    assert!(m.len() > 40, "{}", m.len());
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
    for f in ["part.dxf", "part.svg", "part.json", "part.png", "part.step"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let json = optimum(&out);
    let rules = json["part_rules"].as_array().unwrap();
    assert!(rules.len() > 40, "{}", rules.len());
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
    // printed to 0.1 um
    assert!(
        (fields[1].parse::<f64>().unwrap() - margin).abs() <= 5e-5,
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

#[test]
fn the_least_stress_bridge_is_made_on_its_middle_links_width() {
    let dir = std::env::temp_dir().join(format!("flexopt-rules-stress-{}", std::process::id()));
    let file = std::path::Path::new("problems/wei2017_min_stress.toml");
    let out = dir.join("enforced");
    let o = run(file, &out, &[]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("part rule link_width"), "{text}");
    assert!(out.join("part.dxf").is_file());
    let json = optimum(&out);
    let rules = json["part_rules"].as_array().unwrap();
    assert!(rules.iter().all(|r| r["met"] == true));
    let active: Vec<&str> = rules
        .iter()
        .filter(|r| r["active"] == true)
        .map(|r| r["rule"].as_str().unwrap())
        .collect();
    assert_eq!(active, ["link_width"]);
    let made = json["objective"].as_f64().unwrap();

    // without the rules: a lower stress, on links thinner than their hinges
    let free = dir.join("free");
    let text = std::fs::read_to_string(file)
        .unwrap()
        .replace("[search]", "[part]\nenforce = false\n\n[search]");
    let free_file = dir.join("free.toml");
    std::fs::write(&free_file, text).unwrap();
    let o = run(&free_file, &free, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(5), "{err}");
    assert!(err.contains("the middle link c (upper left) is "), "{err}");
    let unmade = optimum(&free)["objective"].as_f64().unwrap();
    // measured: 38.96 MPa made, 38.82 MPa not (+0.38 %)
    assert!(
        made > unmade && made < 1.01 * unmade,
        "{made} against {unmade}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// The distance (m) from `p` to the part's outline, its arcs taken as chords.
fn to_outline(part: &flexopt::part::Part, p: [f64; 2]) -> f64 {
    let mut least = f64::INFINITY;
    for l in &part.loops {
        let pts = l.points(24);
        for (k, &a) in pts.iter().enumerate() {
            let b = pts[(k + 1) % pts.len()];
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            least = least.min(distance(p, [a[0] + t * d[0], a[1] + t * d[1]]));
        }
    }
    least
}

#[test]
fn each_rules_witness_points_stand_its_margin_plus_its_limit_apart_to_1e_9_mm() {
    use flexopt::model::bridge::part::clearances::CAP;
    let mut r = rng(523);
    let (mut apart, mut overlapping, mut link) = (0, 0, 0);
    for _ in 0..1000 {
        let model = bridge(random_settings(&mut r));
        let x = random_design(&mut r);
        let rules = model.rules();
        let n = rules.len();
        let mut m = vec![0.0; n];
        model.rule_margins(&x, &mut m);
        let mut w = vec![None; n];
        model.rule_witnesses(&x, &mut w);
        for (i, (rule, w)) in rules.iter().zip(&w).enumerate() {
            let Some(w) = w else {
                // a clearance is measured wherever a pair comes within CAP of its rule
                assert!(
                    i < model.first_rules() || m[i] == CAP || rule.name == "link_width",
                    "{}: margin {} m and no witness",
                    rule.name,
                    m[i]
                );
                continue;
            };
            // apart, the distance is the clearance; overlapping, the overlap's depth
            let d = distance(w.points[0], w.points[1]);
            assert!(
                (d - (m[i] + w.limit).abs()).abs() <= 1e-12,
                "{}: witness points {d} m apart, margin {} m, limit {} m",
                rule.name,
                m[i],
                w.limit
            );
            if rule.name == "link_width" {
                link += 1
            } else if m[i] + w.limit >= 0.0 {
                apart += 1
            } else {
                overlapping += 1
            }
        }
    }
    assert!(
        apart >= 1000 && overlapping >= 100 && link >= 500,
        "{apart} apart, {overlapping} overlapping, {link} link widths: the draws do not \
         exercise the witnesses"
    );
}

#[test]
fn the_least_stress_optimums_binding_rule_is_measured_on_the_part() {
    use flexopt::problem::Problem;
    use flexopt::study::{self, StudyOptions};
    let problem = Problem::load(std::path::Path::new("problems/wei2017_min_stress.toml")).unwrap();
    let s = study::run(&problem, &StudyOptions::from_problem(&problem));
    let x = s.reported_design().to_vec();
    // the rule the drawing marks, the nearest its limit, is the link's width, active
    let checks = flexopt::problem::part_rules::checks(&problem, &x);
    let nearest = checks
        .iter()
        .min_by(|a, b| a.margin_mm.total_cmp(&b.margin_mm))
        .unwrap();
    assert_eq!(nearest.rule, "link_width");
    assert!(nearest.active && nearest.witness_mm.is_some());
    let part = problem.mechanism().part_maker.as_deref().unwrap();
    let n = part.rules().len();
    let (mut m, mut w) = (vec![0.0; n], vec![None; n]);
    part.rule_margins(&x, &mut m);
    part.rule_witnesses(&x, &mut w);
    let k = part
        .rules()
        .iter()
        .position(|r| r.name == "link_width")
        .unwrap();
    let w = w[k].unwrap();
    let [centre, touch] = w.points;
    let d = distance(centre, touch);
    // the widest disc's radius: the thickest hinge's half thickness plus the margin
    assert!(
        (d - (m[k] + w.limit)).abs() <= 1e-12,
        "{d} m against {} + {} m",
        m[k],
        w.limit
    );
    // the disc touches the part's outline there, and nothing of it nearer its centre
    let built = problem.mechanism().part_or_error(&x).unwrap();
    assert!(
        to_outline(&built, touch) <= 1e-12,
        "{}",
        to_outline(&built, touch)
    );
    assert!(
        to_outline(&built, centre) >= d - 1e-12,
        "{} m to the outline, {d} m to the witness",
        to_outline(&built, centre)
    );
    let mm = nearest.witness_mm.unwrap();
    assert!((distance(mm[0], mm[1]) - d / MM).abs() <= 1e-9);
}
