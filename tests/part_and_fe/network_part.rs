//! The part of a flexure network (problems/lever_network.toml, issue 25): drawn from the
//! description with the model's hinge where the model has it, its ports' faces on the
//! bodies' edges, solved whole by the finite elements through its ports, and its deck
//! solved by CalculiX as by flexopt.

use std::path::Path;

use flexopt::fe::verify::{verify_design, Verification, VerifySettings};
use flexopt::fe::{Elastic, Fidelity, Idealization};
use flexopt::part::Part;
use flexopt::problem::Problem;

fn lever() -> Problem {
    Problem::load(Path::new("problems/lever_network.toml")).unwrap()
}

/// The lever's design in SI: notch radius and web, the stack's offset, the lever's length.
fn design(r: f64, t: f64, a: f64) -> Vec<f64> {
    vec![r * 1e-3, t * 1e-3, a * 1e-3, 40e-3]
}

#[test]
fn the_levers_part_has_the_models_hinge_and_its_ports_faces_on_its_edges() {
    let p = lever();
    for (r, t, a) in [(1.2, 1.0, 6.0), (2.5, 0.5, 9.0), (0.8, 0.4, 14.0)] {
        let x = design(r, t, a);
        let spec = p.mechanism().part_spec(&x).unwrap().unwrap();
        let part = Part::build(&spec).unwrap_or_else(|e| panic!("r {r}, t {t}, a {a}: {e}"));
        assert_eq!(part.loops.iter().filter(|l| l.outer).count(), 1);
        // the model's notch: from the ground 2 r below the lever's lower edge to it
        let h = &part.hinges[0];
        let want = ([0.0, -4e-3 - 2.0 * r * 1e-3], [0.0, -4e-3]);
        for (got, want) in [(h.start, want.0), (h.end, want.1)] {
            assert!((got[0] - want[0]).abs() < 1e-15 && (got[1] - want[1]).abs() < 1e-15);
        }
        assert!((h.thickness - t * 1e-3).abs() < 1e-15);
        // the input face on the lever's lower edge, centred under the port, the tip's at
        // the tip
        let face = |name: &str| part.faces.iter().find(|f| f.name == name).unwrap();
        let input = face("input");
        assert!((input.a[1] + 4e-3).abs() < 1e-15 && (input.b[1] + 4e-3).abs() < 1e-15);
        assert!((0.5 * (input.a[0] + input.b[0]) - a * 1e-3).abs() < 1e-15);
        let tip = face("output_tip");
        assert!((0.5 * (tip.a[0] + tip.b[0]) - 40e-3).abs() < 1e-15);
        assert!(part.faces.iter().any(|f| f.name == "clamp"));
    }
}

#[test]
fn a_port_on_a_hinges_root_and_a_mirrored_network_give_no_part_and_say_why() {
    let p = lever();
    // the stack 2 mm from the pivot pushes on the notch's root, 3.2 mm to each side
    let problems = p
        .mechanism()
        .part_spec(&design(2.5, 0.7, 2.0))
        .unwrap()
        .unwrap_err();
    assert!(
        problems
            .iter()
            .any(|m| m.contains("port input") && m.contains("hinge pivot")),
        "{problems:?}"
    );
    let text = std::fs::read_to_string("problems/wei2017_network.toml").unwrap() + "\n[part]\n";
    let w = Problem::parse(Path::new("w.toml"), &text).unwrap();
    let x = [
        1.984e-3, 0.071, 0.4e-3, 8.1e-3, 0.07, 1.984e-3, 0.071, 0.4e-3,
    ];
    let problems = w.mechanism().part_spec(&x).unwrap().unwrap_err();
    assert!(problems[0].contains("mirror axes (x, y)"), "{problems:?}");
}

fn checked() -> Verification {
    let p = lever();
    let settings = VerifySettings {
        modal: false,
        ..VerifySettings::default()
    };
    verify_design(p.mechanism(), &design(1.174, 1.174, 6.0), &settings).unwrap()
}

fn fe(v: &Verification, f: Fidelity, name: &str) -> f64 {
    let o = v.outputs(f).unwrap();
    o.iter().find(|o| o.name == name).unwrap().estimate.value
}

/// The lever's optimum checked whole through its ports (the docs' band: the ratio within
/// 2 %, the notch's stiffnesses 30 to 45 % above the FE's at t/r = 1, the edge of the
/// notch formula's range of fit), and CalculiX on its deck: the same displacements as
/// flexopt's on the same mesh, its elements straightened as both integrate them exactly.
#[test]
fn the_levers_part_is_checked_whole_through_its_ports_and_ccx_agrees() {
    let v = checked();
    assert!(v.whole_part);
    let p = lever();
    let x = design(1.174, 1.174, 6.0);
    let m = p.model();
    let named = |n: &str| {
        let mut out = [0.0];
        m.evaluate(&x, &[m.output_index(n).unwrap()], &mut out);
        out[0]
    };
    let solid = Fidelity::Solid;
    let amplification = named("amplification") / fe(&v, solid, "fe_amplification") - 1.0;
    let k_in = named("k_in") / fe(&v, solid, "fe_k_in") - 1.0;
    let k_out = named("k_out") / fe(&v, solid, "fe_k_out") - 1.0;
    eprintln!("analytic over FE (3D): amplification {amplification:+.4}, k_in {k_in:+.4}, k_out {k_out:+.4}");
    assert!(amplification.abs() < 0.02, "{amplification}");
    assert!((0.30..0.45).contains(&k_in), "{k_in}");
    assert!((0.30..0.45).contains(&k_out), "{k_out}");

    if !crate::common::peer_present(
        std::process::Command::new("ccx").arg("-v").output().is_ok(),
        "ccx (Debian package calculix-ccx)",
        "the CalculiX comparison",
    ) {
        return;
    }
    let mut model = v.full_model(0).unwrap();
    crate::fe_calculix::straighten(&mut model);
    let ours = model.measures(
        &model
            .solve(&v.material, v.width, Idealization::PlaneStress)
            .unwrap(),
    );
    let (nu, e) = (v.material.poisson_ratio, v.material.youngs_modulus);
    // plane stress through the constants that make plane strain plane stress
    let exact = Elastic {
        youngs_modulus: e * (1.0 + 2.0 * nu) / ((1.0 + nu) * (1.0 + nu)),
        poisson_ratio: nu / (1.0 + nu),
        ..v.material
    };
    let deck = model
        .deck("lever", &exact, v.width, 1.0)
        .two_d(Idealization::PlaneStrain);
    let theirs = model.measures(&crate::fe_calculix::run_ccx("lever", &deck, &model, 0));
    eprintln!("lever, plane stress: flexopt {ours:?}, ccx {theirs:?}");
    for (o, t) in ours.iter().zip(&theirs) {
        assert!(
            (t / o - 1.0).abs() < 1e-6,
            "ccx {t:e} against flexopt {o:e}"
        );
    }
}
