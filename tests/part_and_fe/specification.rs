//! The guide's chapter "From a specification to a part" (issue 51, item 7): its problem file,
//! `problems/stack_amplifier.toml`, run end to end as the chapter runs it, and the figures the
//! chapter quotes are what the commands give: the model's optimum on the stroke's limit, the
//! part within its footprint, the FE under the stack falling short of the model, the
//! refinement saying what it could not meet, and the yield of a design on its limit.

use std::path::{Path, PathBuf};

use crate::common::{flexopt, flexopt_ok};

const FILE: &str = "problems/stack_amplifier.toml";

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-spec-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn within(value: f64, expected: f64, relative: f64, what: &str) {
    assert!(
        (value - expected).abs() <= relative * expected.abs(),
        "{what}: {value}, the chapter says {expected} (to {relative})"
    );
}

#[test]
fn the_chapters_amplifier_from_its_specification_to_its_part() {
    let out = folder("run");
    let o = out.to_str().unwrap();
    // the model's optimum meets every limit; its part, under the stack by 3D FE, does not:
    // exit 3, and the verdict names the part's shortfalls with the fidelity that found them
    let ran = flexopt(&["run", FILE, "--quiet", "--out", o, "--verify"]);
    assert_eq!(ran.status.code(), Some(3), "{ran:?}");
    let err = String::from_utf8_lossy(&ran.stderr);
    assert!(
        err.contains("its part fails by the 3D finite elements") && err.contains("stroke_out = "),
        "{err}"
    );
    let optimum = json(&out.join("optimum.json"));
    assert_eq!(optimum["feasible"], true);
    let verdict = &optimum["verdict"];
    assert_eq!(verdict["fidelity"], "3d");
    let failed: Vec<&str> = verdict["fails"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["constraint"].as_str().unwrap())
        .collect();
    for short in ["stroke_out", "k_out_actuated"] {
        assert!(failed.contains(&short), "{failed:?}");
    }
    // the footprint is a size of the drawn part: judged on it, met
    assert!(!failed.contains(&"part_width"), "{failed:?}");
    assert!(verdict["model_only"]
        .as_array()
        .unwrap()
        .iter()
        .all(|n| n != "part_width" && n != "part_height"));
    // the stroke and the stiffness are lower limits (SI in the verdict): the part's value
    // under them
    for f in verdict["fails"].as_array().unwrap() {
        if f["constraint"] == "stroke_out" || f["constraint"] == "k_out_actuated" {
            let (value, limit) = (f["value"].as_f64().unwrap(), f["limit"].as_f64().unwrap());
            assert!(value < limit, "{f}");
        }
    }
    let outputs = &optimum["outputs"];
    // the stress at full stroke is under the force the stack exerts at the stroke it makes
    // against the part (Eq. 13: 15 um free, 120 N/um), not at its free stroke: in the model
    // and on the part alike
    let (free, k_a, preload) = (15e-6, 120e6, 50.0);
    let value = |name: &str| outputs[name].as_f64().unwrap();
    let true_stroke = |k: f64| free * k_a / (k + k_a);
    assert!((value("stroke_in") - true_stroke(value("k_in"))).abs() < 1e-12 * free);
    assert!(value("stroke_in") < 0.98 * free, "{}", value("stroke_in"));
    within(
        value("force_in_max"),
        value("k_in") * value("stroke_in") + preload,
        1e-12,
        "force_in_max",
    );
    let check = json(&out.join("verify/verify.json"));
    let fe_k_in = check["outputs"]["3d"]["fe_k_in"]["value"].as_f64().unwrap();
    within(
        check["actuation_force"]["3d"].as_f64().unwrap(),
        fe_k_in * true_stroke(fe_k_in) + preload,
        1e-12,
        "the 3D FE's force at full stroke",
    );
    // the model's optimum: 713.3 Hz, on the stroke's limit, inside 60 x 40 mm
    within(
        outputs["output_frequency"].as_f64().unwrap(),
        713.33,
        1e-4,
        "output_frequency",
    );
    within(
        outputs["stroke_out"].as_f64().unwrap(),
        150e-6,
        1e-6,
        "stroke_out",
    );
    within(
        outputs["k_out_actuated"].as_f64().unwrap(),
        0.5186e6,
        1e-3,
        "k_out_actuated",
    );
    within(
        outputs["part_width"].as_f64().unwrap(),
        59.03e-3,
        1e-3,
        "part_width",
    );
    within(
        outputs["part_height"].as_f64().unwrap(),
        22.60e-3,
        1e-3,
        "part_height",
    );
    // the exported outline has the footprint the optimum reports
    let part = json(&out.join("part.json"));
    assert_eq!(part["units"], "mm");
    let b: Vec<f64> = part["bounding_box"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap() * 1e-3)
        .collect();
    within(
        b[2] - b[0],
        outputs["part_width"].as_f64().unwrap(),
        1e-9,
        "outline width",
    );
    within(
        b[3] - b[1],
        outputs["part_height"].as_f64().unwrap(),
        1e-9,
        "outline height",
    );
    // the part under its stack (3D FE) falls short of the model: stroke 138.8 um, k 0.200 N/um
    let verify = json(&out.join("verify/verify.json"));
    let fe = |id: &str| verify["outputs"]["3d"][id]["value"].as_f64().unwrap();
    within(fe("fe_stroke_out"), 138.82e-6, 2e-3, "3D stroke_out");
    within(fe("fe_k_out_actuated"), 199.64e3, 2e-3, "3D k_out_actuated");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_chapters_refinement_meets_the_specification_or_names_what_it_cannot() {
    let out = folder("refine");
    let o = out.to_str().unwrap();
    let run = flexopt(&[
        "run", FILE, "--quiet", "--out", o, "--refine", "fe", "--report",
    ]);
    let err = String::from_utf8_lossy(&run.stderr);
    let refined = json(&out.join("refined.json"));
    // the report's headline says what refined.json says
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let headline = &html[html.find("class=\"lead\"").unwrap()..];
    let headline = &headline[..headline.find("</p>").unwrap()];
    let fails = "no design the refinement checked meets every constraint on the part";
    assert_eq!(
        headline.contains(fails),
        refined["feasible"] == false,
        "{headline}"
    );
    match run.status.code() {
        Some(0) => assert_eq!(refined["feasible"], true, "{err}"),
        Some(3) => {
            assert_eq!(refined["feasible"], false);
            assert!(headline.contains("stroke_out = "), "{headline}");
            assert!(err.contains("finite elements"), "{err}");
            // what it could not meet is measured on the part: below its limit there
            let short: Vec<&str> = refined["refined"]["outputs"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|o| o["output"] == "stroke_out" || o["output"] == "k_out_actuated")
                .filter(|o| {
                    o["measured"].as_f64().is_some_and(|m| {
                        m < if o["output"] == "stroke_out" {
                            150.0
                        } else {
                            0.5
                        }
                    })
                })
                .map(|o| o["output"].as_str().unwrap())
                .collect();
            assert!(
                !short.is_empty(),
                "refined.json names no output short of its limit"
            );
        }
        code => panic!("exit {code:?}: {err}"),
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// The chapter's optimum stands on `stroke_out`'s limit and on the actuator's room beside
/// body c (rule `actuator/c_ul`): each loses about half the parts, and the yield counts
/// only the parts that can be made and meet the stroke (21.72 % of 100,000).
#[test]
fn the_chapters_optimum_loses_half_its_parts_to_the_stroke_and_half_to_the_actuators_room() {
    let run = folder("yield-run");
    let r = run.to_str().unwrap();
    flexopt_ok(&["run", FILE, "--quiet", "--out", r]);
    let out = folder("yield");
    let optimum = run.join("optimum.json");
    flexopt_ok(&[
        "tolerance",
        FILE,
        "--optimum",
        optimum.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let t = json(&out.join("tolerance.json"));
    let stroke = t["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["name"] == "stroke_out")
        .unwrap()["monte_carlo_yield"]
        .as_f64()
        .unwrap();
    assert!((0.48..0.52).contains(&stroke), "stroke_out met by {stroke}");
    let unmakeable = t["unmakeable"].as_f64().unwrap();
    let room = t["rules_broken"]["actuator/c_ul"].as_f64().unwrap();
    assert!(
        (0.48..0.52).contains(&room),
        "actuator/c_ul broken by {room}"
    );
    assert!(unmakeable >= room && unmakeable < 0.52, "{unmakeable}");
    let y = t["yield"].as_f64().unwrap();
    assert!(y <= stroke.min(1.0 - unmakeable), "yield {y}");
    within(y, 0.2172, 0.01, "yield");
    let _ = std::fs::remove_dir_all(&run);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_chapters_robust_optimum_keeps_the_stroke_two_deviations_inside() {
    let text = std::fs::read_to_string(FILE).unwrap();
    assert!(text.contains("threads = 0\n"));
    let dir = folder("robust");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("robust.toml");
    let robust = text.replacen(
        "threads = 0\n",
        "threads = 0\nrobust = { yield = 0.95 }\n",
        1,
    );
    std::fs::write(&file, robust).unwrap();
    let out = dir.join("run");
    flexopt_ok(&[
        "run",
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let outputs = &json(&out.join("optimum.json"))["outputs"];
    within(
        outputs["output_frequency"].as_f64().unwrap(),
        711.124,
        1e-4,
        "robust output_frequency",
    );
    within(
        outputs["stroke_out"].as_f64().unwrap(),
        150.198e-6,
        1e-5,
        "robust stroke_out",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 47 item 6, measured: where the chapter's part departs from the model (plane
/// stress, the model's narrow beams). With every element outside the hinges' thin sections a
/// thousand times stiffer (links, blocks, fillets and the material at the hinges' roots rigid,
/// as the model has them) the FE lands on the model within 1 %: the hinge formula holds at
/// l/t = 2 when its ends are truly clamped. Thicker links, sharp roots or wider blocks each
/// move k_in by under 10 %, while the rigid bodies raise it by 75 %: most of the gap is the
/// bodies giving way where the short hinges enter them (docs/guide/src/specification.md).
#[test]
fn the_chapters_model_gap_is_the_bodies_at_the_hinges_roots_not_the_hinge_formula() {
    use flexopt::fe::verify::{verify_design, VerifySettings};
    use flexopt::fe::Fidelity;
    use flexopt::study::{self, StudyOptions};
    let p = flexopt::problem::Problem::load(Path::new(FILE)).unwrap();
    let s = study::run(&p, &StudyOptions::from_problem(&p));
    let x = s.reported_design().to_vec();
    let settings = |stiffening: f64| VerifySettings {
        body_stiffening: stiffening,
        max_levels: 3,
        modal: false,
        solid: false,
        ..VerifySettings::default()
    };
    let measured = |q: &flexopt::problem::Problem, stiffening: f64| {
        let v = verify_design(q.mechanism(), &x, &settings(stiffening)).unwrap();
        let o = v.outputs(Fidelity::PlaneStress).unwrap();
        let get = |n: &str| o.iter().find(|o| o.name == n).unwrap().estimate.value;
        [get("fe_k_in"), get("fe_k_out"), get("fe_amplification")]
    };
    let m = p.model();
    let model: Vec<f64> = ["k_in", "k_out", "amplification"]
        .iter()
        .map(|name| {
            let i = m.outputs().iter().position(|o| o.name == *name).unwrap();
            let mut out = [0.0];
            m.evaluate(&x, &[i], &mut out);
            out[0]
        })
        .collect();
    let (part, rigid) = (measured(&p, 1.0), measured(&p, 1000.0));
    for k in 0..3 {
        let off = (model[k] - rigid[k]) / rigid[k];
        eprintln!(
            "model {:.5e}, rigid bodies {:.5e} ({:+.2} %), part {:.5e}",
            model[k],
            rigid[k],
            100.0 * off,
            part[k]
        );
        assert!(off.abs() < 0.015, "{k}: {off}");
    }
    let rigid_gain = rigid[0] / part[0] - 1.0;
    assert!(rigid_gain > 0.6, "{rigid_gain}");
    // the same design with other [part] sizes, the stack's room left out (the variants'
    // links and roots would cross it)
    let text = std::fs::read_to_string(FILE)
        .unwrap()
        .replace("length = \"18 mm\"", "")
        .replace("height = \"10 mm\"", "");
    let dir = folder("variants");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("v.toml");
    let variant = |from: &str, to: &str| {
        std::fs::write(&file, text.replace(from, to)).unwrap();
        measured(&flexopt::problem::Problem::load(&file).unwrap(), 1.0)[0] / part[0] - 1.0
    };
    let blocks = "input_block_width = \"4 mm\"";
    for (name, gain, band) in [
        (
            "links 6 mm thick",
            variant(blocks, &format!("{blocks}\nlink_thickness = \"6 mm\"")),
            (0.0, 0.06),
        ),
        (
            "sharp roots",
            variant(blocks, &format!("{blocks}\nfillet_radius = \"0 mm\"")),
            (0.05, 0.12),
        ),
        (
            "input blocks 8 mm wide",
            variant(blocks, "input_block_width = \"8 mm\""),
            (0.0, 0.06),
        ),
    ] {
        eprintln!("{name}: k_in {:+.2} %", 100.0 * gain);
        assert!(gain > band.0 && gain < band.1, "{name}: {gain}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
