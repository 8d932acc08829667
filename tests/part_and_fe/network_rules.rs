//! The flexure network's part rules as constraints of the design (issues 23 and 25): on
//! random designs of every shipped network, their least margin changes sign where the
//! part's check of its solids flips, and their gradients are exact (that the rules see the
//! spec's solids is the library's own test, `model::network::part::rules`).

use std::path::Path;

use crate::common::{self, rng};
use flexopt::model::part_rules::TOLERANCE;
use flexopt::model::PartMaker;
use flexopt::part::checks::before_union;
use flexopt::problem::Problem;

const NETWORKS: [&str; 6] = [
    "problems/lever_network.toml",
    "problems/rhombus_network.toml",
    "problems/scott_russell_network.toml",
    "problems/wei2017_network.toml",
    "problems/bridge_lever_network.toml",
    "problems/guide_network.toml",
];

fn load(file: &str) -> Problem {
    Problem::load(Path::new(file)).unwrap()
}

fn part(p: &Problem) -> &dyn PartMaker {
    p.mechanism()
        .part_maker
        .as_deref()
        .expect("a network with a part")
}

fn margins(part: &dyn PartMaker, x: &[f64]) -> Vec<f64> {
    let mut m = vec![0.0; part.rules().len()];
    part.rule_margins(x, &mut m);
    m
}

/// The least margin of the clearance rules at `x` and whether the part's check of its
/// placed solids finds a problem there; `None` where the spec refuses the design.
fn clearance_and_check(part: &dyn PartMaker, x: &[f64]) -> Option<(f64, bool)> {
    let spec = part.part(x).ok()?;
    let least = margins(part, x)[part.first_rules()..]
        .iter()
        .fold(f64::INFINITY, |a, &b| a.min(b));
    Some((least, !before_union(&spec).is_empty()))
}

#[test]
fn the_rules_change_sign_where_the_check_of_the_solids_flips_to_1e_9_mm() {
    let mut r = rng(2523);
    let mut totals = [0; 2];
    for file in NETWORKS {
        let p = load(file);
        let part = part(&p);
        assert!(part.enforces_rules() && !part.rules().is_empty(), "{file}");
        let (mut met, mut broken, mut flips) = (0, 0, 0);
        for _ in 0..1000 {
            let (a, b) = (
                common::design_within_bounds(&p, &mut r),
                common::design_within_bounds(&p, &mut r),
            );
            let Some((ma, ta)) = clearance_and_check(part, &a) else {
                continue;
            };
            if ma.abs() > TOLERANCE {
                assert_eq!(ta, ma < 0.0, "{file}: margin {ma} m at {a:?}");
                if ta {
                    broken += 1
                } else {
                    met += 1
                }
            }
            let Some((_, tb)) = clearance_and_check(part, &b) else {
                continue;
            };
            if ta == tb {
                continue;
            }
            let at =
                |t: f64| -> Vec<f64> { a.iter().zip(&b).map(|(p, q)| p + t * (q - p)).collect() };
            // bisect on the check alone, along a line on which every part can be placed
            let (mut lo, mut hi) = (0.0, 1.0);
            let mut placed = true;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                match clearance_and_check(part, &at(mid)) {
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
                let (m, _) = clearance_and_check(part, &at(t)).unwrap();
                assert!(
                    (m + TOLERANCE).abs() <= TOLERANCE,
                    "{file}: the check flips at a margin of {m} m, not within 1e-9 mm of the \
                     rules' -1e-9 mm"
                );
            }
            flips += 1;
        }
        println!("{file}: {met} met, {broken} broken, {flips} flips");
        assert!(met >= 20, "{file}: {met} met");
        totals = [totals[0] + broken, totals[1] + flips];
    }
    // the lever's parts are made everywhere in its bounds; the others' are not
    assert!(
        totals[0] >= 100 && totals[1] >= 50,
        "{totals:?} broken and flips: the draws do not exercise the rules"
    );
}

#[test]
fn each_rules_gradient_agrees_with_central_differences() {
    let mut r = rng(2524);
    for file in NETWORKS {
        let p = load(file);
        let part = part(&p);
        let (n, rules) = (p.variables.len(), part.rules().len());
        let (mut compared, mut kinks) = (0, 0);
        for _ in 0..100 {
            let x = common::design_within_bounds(&p, &mut r);
            let (mut m, mut jac) = (vec![0.0; rules], vec![0.0; rules * n]);
            part.rule_margins_with_gradient(&x, &mut m, &mut jac);
            assert_eq!(
                m,
                margins(part, &x),
                "{file}: values with and without gradients"
            );
            for v in p.variables.iter().filter(|v| !v.fixed) {
                let k = v.parameter;
                let h = 1e-6 * (v.upper - v.lower);
                let (mut up, mut down) = (x.clone(), x.clone());
                up[k] += h;
                down[k] -= h;
                let (mu, md) = (margins(part, &up), margins(part, &down));
                for i in 0..rules {
                    let exact = jac[i * n + k];
                    let fd = (mu[i] - md[i]) / (2.0 * h);
                    // where the nearest pair changes within the step, there is no
                    // derivative to compare with
                    let (forward, backward) = ((mu[i] - m[i]) / h, (m[i] - md[i]) / h);
                    if (forward - backward).abs() > 1e-4 * exact.abs() + 1e-7 {
                        kinks += 1;
                        continue;
                    }
                    assert!(
                        (fd - exact).abs() <= 1e-6 * exact.abs() + 1e-7,
                        "{file}: rule {}: d/d{} exact {exact}, differences {fd} at {x:?}",
                        part.rules()[i].name,
                        v.name
                    );
                    compared += 1;
                }
            }
        }
        println!("{file}: {compared} compared, {kinks} at kinks");
        assert!(
            compared >= 500 && kinks * 20 < compared,
            "{file}: {compared} compared, {kinks} at kinks"
        );
    }
}

/// The lever with its arm free to 60 mm and a ground frame whose stop stands at 48 mm: left
/// to itself, the study lengthens the arm into the stop. In a fresh `dir`, with `part` as
/// its `[part]` section; the file's path.
fn long_lever(dir: &Path, part: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string("problems/lever_network.toml").unwrap();
    let replace = |text: String, from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        text.replacen(from, to, 1)
    };
    // the frame: a post up to the pivot's pad, a base, and the stop beyond the lever's end
    let ground = "[[network.bodies]]\nname = \"ground\"\noutline = [[\"-3\", \"-20\"], \
                  [\"60\", \"-20\"], [\"60\", \"10\"], [\"48\", \"10\"], [\"48\", \"-16\"], \
                  [\"3\", \"-16\"], [\"3\", \"-5 - 2*r\"], [\"-3\", \"-5 - 2*r\"]]\n\n\
                  [[network.bodies]]\nname = \"lever\"";
    let text = replace(text, "[[network.bodies]]\nname = \"lever\"", ground);
    let text = replace(text, "value = 40", "lower = 30\nupper = 60");
    // the tip's stiffness would hold the arm short of the stop
    let text = replace(
        text,
        "[[constraints]]\noutput = \"k_out\"             # the tip's stiffness, the stack free\n\
         unit = \"N/um\"\nlower = 0.05\n",
        "",
    );
    let text = replace(text, "[part]\n", &format!("[part]\n{part}\n"));
    let text = replace(text, "starts = 300", "starts = 40");
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("long_lever.toml");
    std::fs::write(&file, text).unwrap();
    file
}

/// `flexopt run` of `file` into `out`, quiet.
fn run(file: &Path, out: &Path) -> std::process::Output {
    crate::common::flexopt(&[
        "run",
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn a_network_study_keeps_to_its_parts_rules_and_names_the_binding_one_unless_told_not_to() {
    let dir = std::env::temp_dir().join(format!("flexopt-network-rules-{}", std::process::id()));
    // not enforced: the lever runs into the stop, and no part can be cut
    let out = dir.join("checked");
    let o = run(&long_lever(&dir, "enforce = false"), &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(5), "{err}");
    assert!(!out.join("part.dxf").exists());

    let out = dir.join("enforced");
    let o = run(&long_lever(&dir, ""), &out);
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for f in ["part.dxf", "part.svg", "part.json", "part.png"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(json["feasible"], true);
    let rules = json["part_rules"].as_array().unwrap();
    assert!(rules.iter().all(|r| r["met"] == true), "{rules:?}");
    let active: Vec<&str> = rules
        .iter()
        .filter(|r| r["active"] == true)
        .map(|r| r["rule"].as_str().unwrap())
        .collect();
    assert_eq!(active, ["slot, the ground, body lever"], "{rules:?}");
    assert!(
        active
            .iter()
            .all(|a| text.contains(&format!("part rule {a}"))),
        "{active:?}: {text}"
    );
    // the lever's end (arm + 2 mm) the narrowest slot short of the stop, and the part made
    let x: Vec<f64> = ["r", "t", "a", "arm"]
        .iter()
        .map(|k| json["design_si"][k].as_f64().unwrap())
        .collect();
    assert!((x[3] - 45.6e-3).abs() < 1e-11, "{x:?}");
    let p = load(dir.join("long_lever.toml").to_str().unwrap());
    assert!(p.mechanism().part(&x).unwrap().is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}
