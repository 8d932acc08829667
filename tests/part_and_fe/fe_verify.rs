//! The finite-element check of paper 004's printed design: every output converges to the
//! tolerance, the hinges are meshed finely enough, the deviations from the analytic model
//! fall as Table 2's do (or where they do not, the reason holds as a measurement), and a
//! sharp hinge root's peak stress is reported as not converging.

use crate::common;

use common::{table1_optimum, wei2017_settings};
use flexopt::fe::stress::Locator;
use flexopt::fe::verify::{verify_design, Verification, VerifySettings};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::{Mechanism, Model};

fn bridge(part: PartSettings) -> Bridge {
    let mut s = wei2017_settings();
    s.part = part;
    // no payload: the part's own mass, as paper 004's analysis has it
    s.dynamics = None;
    Bridge::new(s)
}

fn output<'a>(v: &'a Verification, k: usize, name: &str) -> &'a flexopt::fe::verify::Output {
    v.results[k]
        .outputs
        .iter()
        .find(|o| o.name == name)
        .unwrap()
}

/// The check of `model`'s part at `x` with the default settings.
fn checked(model: &Bridge, x: &[f64]) -> Verification {
    verify_design(
        &Mechanism::complete(model.clone()),
        x,
        &VerifySettings::default(),
    )
    .unwrap()
}

fn analytic(model: &Bridge, x: &[f64], name: &str) -> f64 {
    let i = model.output_index(name).unwrap();
    let mut v = [0.0];
    Model::evaluate(model, x, &[i], &mut v);
    v[0]
}

#[test]
fn the_printed_design_converges_and_deviates_as_table_2_does() {
    let model = bridge(PartSettings::default());
    let x = table1_optimum();
    let v = checked(&model, &x);
    assert!(v.converged);
    assert!(v.levels.len() >= 3);
    for r in &v.results {
        for o in &r.outputs {
            let e = &o.estimate;
            // the peak at a 0.2 mm fillet too: the first mesh is graded there (it turned by
            // 2 % on meshes sized for the hinges alone)
            assert!(
                e.within(0.005),
                "{:?} {}: {e:?} {:?}",
                r.idealization,
                o.name,
                o.values
            );
        }
    }
    // in 3D: every output within the tolerance, the stiffnesses by Richardson through the
    // layers (the quadratic wedges' observed order 2 to 4); and a direct 3D solve of the
    // second in-plane mesh at the same 4 layers lands on the 3D values within their stated
    // error plus that mesh's own plane-strain error (which the 3D values do not carry)
    let solid = &v.solid.as_ref().unwrap().outputs;
    // the five static outputs, the peak stress and the five under the stack
    assert_eq!(solid.len(), 11);
    let direct = v.solid_direct(1, 4).unwrap();
    for o in solid {
        let e = &o.estimate;
        assert!(e.within(0.005), "3D {}: {e:?} {:?}", o.name, o.values);
        if o.name.starts_with("fe_k_") {
            let order = e.order.unwrap();
            assert!(
                e.converging && (2.0..=4.0).contains(&order),
                "3D {}: {e:?}",
                o.name
            );
        }
        let strain = output(&v, 1, o.name);
        let level_error = (strain.values[1] - strain.estimate.value).abs() / strain.estimate.value;
        let (_, d) = direct.iter().find(|(n, _)| *n == o.name).unwrap();
        let off = (d - e.value).abs() / e.value;
        assert!(
            off <= e.relative_error.unwrap() + level_error,
            "3D {}: direct {d} against {} +- {:?}, level error {level_error}",
            o.name,
            e.value,
            e.relative_error
        );
    }
    // at least four elements through every hinge's thickness on the first mesh: the
    // elements a line across its middle passes through
    let m = &v.meshes[0];
    let locator = Locator::new(m);
    let domain = flexopt::fe::geometry::Domain::of_part(&v.half);
    for h in &domain.hinges {
        let c = [0.5 * (h.start[0] + h.end[0]), 0.5 * (h.start[1] + h.end[1])];
        let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
        let n = [
            -(h.end[1] - h.start[1]) / len,
            (h.end[0] - h.start[0]) / len,
        ];
        let mut crossed: Vec<usize> = (0..1000)
            .filter_map(|k| {
                let s = (k as f64 + 0.5) / 1000.0 - 0.5;
                locator.find(
                    m,
                    [c[0] + s * h.thickness * n[0], c[1] + s * h.thickness * n[1]],
                )
            })
            .map(|(e, _)| e)
            .collect();
        crossed.dedup();
        assert!(
            crossed.len() >= 4,
            "{}: {} elements through its thickness",
            h.name,
            crossed.len()
        );
    }
    let af = analytic(&model, &x, "force_in_max");
    for (k, r) in v.results.iter().enumerate() {
        let fe = |name: &str| output(&v, k, name).estimate.value;
        // Table 2: the FE amplification and input stiffness below the analytic ones
        assert!(
            fe("fe_amplification") < analytic(&model, &x, "amplification"),
            "{:?}",
            r.idealization
        );
        assert!(
            fe("fe_k_in") < analytic(&model, &x, "k_in"),
            "{:?}",
            r.idealization
        );
        // the stress: at equal force the hinges' section stress is Eq. 12-17's to 1 %, and
        // the peak at the fillets above it (Table 2's FE stress above the analytic); at the
        // FE's own actuation force, lower by the FE's lower k_in, the section stress falls
        // below the analytic (the README's comparison)
        let own = v.actuation_force[k];
        let stress = analytic(&model, &x, "stress_max");
        let section = fe("fe_stress_section") * af / own;
        assert!(
            (section - stress).abs() < 0.01 * stress,
            "{:?}: {section} against {stress}",
            r.idealization
        );
        assert!(fe("fe_stress_max") * af / own > 1.1 * stress);
        assert!(fe("fe_stress_section") < stress);
        // the first mode is a sideways one, below the output mode
        assert!(fe("fe_natural_frequency") < fe("fe_output_frequency"));
    }
    // plane strain is the stiffer bound
    assert!(output(&v, 1, "fe_k_in").estimate.value > output(&v, 0, "fe_k_in").estimate.value);
}

#[test]
fn a_sharp_roots_peak_stress_is_reported_as_not_converging() {
    let model = bridge(PartSettings {
        fillet_radius: 0.0,
        ..PartSettings::default()
    });
    let x = table1_optimum();
    let v = checked(&model, &x);
    // the peak never stops the refinement and is never extrapolated; the rest converge
    assert!(v.converged);
    for k in 0..2 {
        let peak = &output(&v, k, "fe_stress_max").estimate;
        // its spread is quoted, never an extrapolation, and it is far beyond any tolerance
        assert!(
            !peak.converging
                && !peak.oscillating
                && peak.extrapolated.is_none()
                && peak.relative_error.is_some_and(|r| r > 0.1),
            "{peak:?}"
        );
        let values = &output(&v, k, "fe_stress_max").values;
        assert!(
            values.windows(2).all(|w| w[1] > w[0]),
            "the peak grows: {values:?}"
        );
        assert!(output(&v, k, "fe_stress_section").estimate.converging);
    }
    // the fillets stand beyond the model's hinge, where it has rigid bodies: the bodies'
    // faces move out by the radius and the fillets' zones, thicker than the hinge but far
    // from rigid, add compliance, so the filleted part is the softer one
    let filleted = checked(&bridge(PartSettings::default()), &x);
    assert!(
        output(&filleted, 1, "fe_k_in").estimate.value < output(&v, 1, "fe_k_in").estimate.value
    );
}

#[test]
fn the_command_line_checks_a_design_and_a_runs_optimum() {
    use common::{flexopt, flexopt_ok};
    let dir = std::env::temp_dir().join(format!("flexopt-verify-{}", std::process::id()));
    let out = flexopt_ok(&[
        "verify",
        "problems/wei2017.toml",
        "--design",
        "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("FE plane stress") && text.contains("amplification"),
        "{text}"
    );
    for f in [
        "verify.json",
        "stress.png",
        "deformed.png",
        "part.inp",
        "part3d.inp",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("verify.json")).unwrap()).unwrap();
    let amp = &json["outputs"]["plane_strain"]["fe_amplification"];
    assert!(amp["converging"].as_bool().unwrap());
    assert!(amp["relative_error"].as_f64().unwrap() < 0.005);
    assert!((amp["analytic"].as_f64().unwrap() - 12.86).abs() < 0.01);
    // 10 mm over 0.4 mm hinges: the 3D column, and the line saying to read it
    assert_eq!(json["read"], "3d");
    let k_out = |f: &str| json["outputs"][f]["fe_k_out"]["value"].as_f64().unwrap();
    assert!(k_out("plane_stress") < k_out("3d") && k_out("3d") < k_out("plane_strain"));
    assert!(text.contains("FE 3D") && text.contains("read 3D"), "{text}");
    // --no-3d: the two 2D idealizations only, and the reason said
    let out = flexopt_ok(&[
        "verify",
        "problems/wei2017.toml",
        "--optimum",
        "results/wei2017/optimum.json",
        "--out",
        dir.to_str().unwrap(),
        "--no-3d",
    ]);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("verify.json")).unwrap()).unwrap();
    assert!(json["outputs"].get("3d").is_none() && json["solid_solves"].is_null());
    assert!(String::from_utf8_lossy(&out.stdout).contains("no 3D check: left out"));
    std::fs::remove_dir_all(&dir).unwrap();

    // a model without a part, and a tolerance out of range: bad input
    let out = flexopt(&[
        "verify",
        "problems/prr3_frequency.toml",
        "--optimum",
        "results/prr3_frequency/optimum.json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no part"));
    let out = flexopt(&[
        "verify",
        "problems/wei2017.toml",
        "--optimum",
        "results/wei2017/optimum.json",
        "--tolerance",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--tolerance"));
    let _ = std::fs::remove_dir_all(&dir);

    // run --verify checks the optimum into DIR/verify; the optimum meets k_out >= 38 N/mm in
    // the model, its part gives 33.6 N/mm in 3D: exit 3, the failure named everywhere
    let out = flexopt(&[
        "run",
        "problems/wei2017.toml",
        "--starts",
        "10",
        "--verify",
        "--report",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("k_out = ") && stderr.contains("(3D), limit >= 38"),
        "{stderr}"
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("verdict by the 3D FE: the part FAILS"),
        "{stdout}"
    );
    assert!(
        stdout.contains("judged by the part's 3D FE: the part FAILS k_out = "),
        "{stdout}"
    );
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(optimum["feasible"], true);
    assert_eq!(optimum["verdict"]["fails"][0]["constraint"], "k_out");
    let verify: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("verify/verify.json")).unwrap())
            .unwrap();
    let fails = verify["verdict"]["fails"].as_array().unwrap();
    assert_eq!(fails.len(), 1);
    assert_eq!(fails[0]["constraint"], "k_out");
    assert_eq!(fails[0]["fidelity"], "3d");
    assert!(fails[0]["value"].as_f64().unwrap() < fails[0]["limit"].as_f64().unwrap());
    // the model's gaps beyond 5 % and the FE's error are named (k_in +23.5 %, k_out +13.1 %,
    // the ratio +8.7 % in 3D); the peak stress, 1.9 % off, is not
    let off: Vec<&str> = verify["verdict"]["model_off"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["output"].as_str().unwrap())
        .collect();
    for name in ["fe_k_in", "fe_k_out", "fe_amplification"] {
        assert!(off.contains(&name), "{off:?}");
    }
    assert!(!off.contains(&"fe_stress_max"), "{off:?}");
    for g in verify["verdict"]["model_off"].as_array().unwrap() {
        let d = g["deviation_percent"].as_f64().unwrap();
        let name = g["output"].as_str().unwrap();
        let listed = verify["outputs"]["3d"][name]["deviation_percent"].as_f64();
        assert_eq!(Some(d), listed, "{name}");
        assert!(d.abs() > 5.0 + g["fe_error_percent"].as_f64().unwrap());
    }
    assert!(
        stdout.contains("the model is off its part by more than 5 % beyond the FE's error"),
        "{stdout}"
    );
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert!(html.contains("The model does not hold on this part"));
    assert!(html.contains("its part fails by the 3D finite elements"));
    assert!(html.contains("k_out = "));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn with_rigid_bodies_the_part_in_plane_stress_is_the_analytic_model() {
    // everything outside the hinges' thin sections a thousand times stiffer: the links,
    // blocks and fillets rigid, as paper 004's model has them; in plane stress (the narrow
    // beam of Eq. 2) the FE then lands on the analytic outputs, so the whole analytic-FE gap
    // of the real part is the compliance of those bodies at the hinges' roots
    let model = bridge(PartSettings::default());
    let x = table1_optimum();
    let settings = VerifySettings {
        body_stiffening: 1000.0,
        max_levels: 3,
        ..VerifySettings::default()
    };
    let v = verify_design(&Mechanism::complete(model.clone()), &x, &settings).unwrap();
    for name in ["amplification", "k_in", "k_out"] {
        let fe = output(&v, 0, &format!("fe_{name}")).estimate.value;
        let an = analytic(&model, &x, name);
        assert!((fe - an).abs() < 0.015 * an, "{name}: FE {fe} against {an}");
    }
}

/// `value` without the times a check took ("seconds", at any depth), which vary by run.
fn without_seconds(value: serde_json::Value) -> serde_json::Value {
    match value {
        serde_json::Value::Object(map) => map
            .into_iter()
            .filter(|(k, _)| k != "seconds")
            .map(|(k, v)| (k, without_seconds(v)))
            .collect(),
        serde_json::Value::Array(items) => items.into_iter().map(without_seconds).collect(),
        other => other,
    }
}

/// The committed `results/wei2017/verify/verify.json` is what the check of the committed
/// optimum gives today, to the last digit of every value: the check a part states, solved
/// by the verifier that knows no mechanism, is the bridge's check as it was written before
/// the bridge stated it (scripts/check_results.sh checks every other committed file).
#[test]
fn the_committed_check_of_the_optimum_is_reproduced_to_the_last_digit() {
    let problem =
        flexopt::problem::Problem::load(std::path::Path::new("problems/wei2017.toml")).unwrap();
    let x = flexopt::problem::design::design_from_optimum(
        &problem,
        std::path::Path::new("results/wei2017/optimum.json"),
    )
    .unwrap()
    .x;
    let v = verify_design(problem.mechanism(), &x, &VerifySettings::default()).unwrap();
    let report = flexopt::report::verify::VerifyReport::new(&problem, &x, &v);
    let now = without_seconds(serde_json::to_value(&report).unwrap());
    let committed: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string("results/wei2017/verify/verify.json").unwrap(),
    )
    .unwrap();
    let committed = without_seconds(committed);
    assert!(
        now == committed,
        "verify.json of the wei2017 optimum differs from the committed one"
    );
}

/// No estimate in a committed check claims more than its sequence shows: an output called
/// converging has its last differences of one sign and an observed order between 1/2 and 6;
/// any other quotes at least the spread of its last three values (the optimum's plane-stress
/// peak stress, 153.1 -> 156.2 -> 155.7 MPa, was once quoted +-0.07 %).
#[test]
fn every_committed_estimate_covers_what_its_sequence_shows() {
    let mut checked = 0;
    for file in [
        "results/wei2017/verify/verify.json",
        "results/wei2017/verify_printed/verify.json",
        "results/bridge_circular/verify/verify.json",
    ] {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
        for (idealization, outputs) in v["outputs"].as_object().unwrap() {
            for (name, o) in outputs.as_object().unwrap() {
                let values: Vec<f64> = o["values"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_f64().unwrap())
                    .collect();
                let n = values.len();
                let last = &values[n - 3..];
                let (d1, d2) = (last[1] - last[0], last[2] - last[1]);
                let value = values[n - 1];
                // a 3D output's values are its layer sequence (1, 2, 4 layers): one that turns
                // quotes the spread of 2 and 4 layers, one layer having no zone at the free
                // face where a stress peaks
                let spread_of = if idealization == "3d" {
                    &last[1..]
                } else {
                    last
                };
                let spread = spread_of.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
                    - spread_of.iter().fold(f64::INFINITY, |a, &b| a.min(b));
                let at = format!("{file} {idealization} {name}: {values:?}");
                if o["converging"] == true {
                    assert!(d1 * d2 >= 0.0, "{at}: called converging, turns");
                    let order = o["order"].as_f64().unwrap();
                    assert!((0.5..=8.0).contains(&order), "{at}: order {order}");
                } else if let Some(e) = o["relative_error"].as_f64() {
                    assert!(
                        e * value.abs() >= spread * (1.0 - 1e-12),
                        "{at}: error {e} below the spread"
                    );
                }
                checked += 1;
            }
        }
    }
    // each file: 14 outputs in each 2D idealization (9, and 5 under the stack), 11 in 3D
    // (no section stress, no modes)
    assert_eq!(checked, 3 * (2 * 14 + 11));
}
