//! The natural frequencies of a flexure network (issue 25): the model's `f1` against the
//! finite elements' lowest mode of the exported part, solved whole with the actuator a
//! spring from its face to the ground, as the model has it; for a part with mirror axes, on
//! the right half, the lowest of the modes symmetric about the y axis (the actuator a spring
//! between its input faces) and antisymmetric about it, as the model's families of modes.

use std::path::Path;

use flexopt::fe::verify::{verify_design, VerifySettings};
use flexopt::fe::Fidelity;
use flexopt::problem::Problem;

/// The lever's optimum: the model's first frequency 25 to 35 % above the part's, in both
/// idealizations (docs/guide/src/networks.md, "Natural frequencies"). The model's lever is
/// rigid on a point spring; the part's lever gives under the stack's 2 mm face, and its
/// notch is 30 to 45 % softer than the formula's at t/r = 1 (the statics' band). Each FE
/// value's estimated error is below 0.1 %. A payload of 10 g on the tip, about the lever's
/// own mass, lowers the frequency by half and widens the gap to 30 to 45 %: the part's lever
/// bends under the tip's mass (its tip stiffness in bending, `3 E I / L^3`, about 2.3 N/um, is
/// of the stack's 1.35 N/um seen at the tip), which a rigid body has not.
#[test]
fn the_levers_first_frequency_lies_in_its_band_against_its_parts_modes() {
    let x = [1.174e-3, 1.174e-3, 6e-3, 40e-3];
    let bare = check(&load("problems/lever_network.toml"), &x, (0.25, 0.35));
    let text = std::fs::read_to_string("problems/lever_network.toml")
        .unwrap()
        .replacen("name = \"tip\"", "name = \"tip\"\npayload = \"10 g\"", 1);
    let p = Problem::parse(Path::new("lever_payload.toml"), &text).unwrap();
    let loaded = check(&p, &x, (0.30, 0.45));
    assert!(loaded < 0.8 * bare, "{loaded} against {bare}");
}

fn load(file: &str) -> Problem {
    Problem::load(Path::new(file)).unwrap()
}

/// The Scott-Russell mechanism's optimum (its stack pushing leftwards, a spring whichever
/// way it acts): the model 10 to 25 % above the part, whose notches are softer than the
/// formula's at t/r = 1 and whose blocks give under the stack and the leaves.
#[test]
fn the_scott_russells_first_frequency_lies_in_its_band_against_its_parts_modes() {
    let p = load("problems/scott_russell_network.toml");
    let text = std::fs::read_to_string("results/scott_russell_network/optimum.json").unwrap();
    let optimum: serde_json::Value = serde_json::from_str(&text).unwrap();
    let x: Vec<f64> = p
        .variables
        .iter()
        .map(|v| optimum["design_si"][v.name.as_str()].as_f64().unwrap())
        .collect();
    check(&p, &x, (0.10, 0.25));
}

/// The model's `f1` over the FE's `fe_f1` minus one lies in `band`, in plane stress and in
/// plane strain, each FE value within 0.1 % by its estimate. Returns the model's `f1`.
fn check(p: &Problem, x: &[f64], band: (f64, f64)) -> f64 {
    let whole = p.name == "lever_network" || p.name.contains("scott");
    let file = &p.name;
    let settings = VerifySettings {
        solid: false,
        ..VerifySettings::default()
    };
    let v = verify_design(p.mechanism(), x, &settings).unwrap();
    assert_eq!(v.whole_part, whole);
    let m = p.model();
    let mut f1 = [0.0];
    m.evaluate(x, &[m.output_index("f1").unwrap()], &mut f1);
    for fidelity in [Fidelity::PlaneStress, Fidelity::PlaneStrain] {
        let outputs = v.outputs(fidelity).unwrap();
        let fe = outputs.iter().find(|o| o.name == "fe_f1").unwrap();
        let over = f1[0] / fe.estimate.value - 1.0;
        eprintln!(
            "{file} {fidelity:?}: model {:.1} Hz, FE {:.1} Hz (+-{:?}), model over FE {over:+.4}",
            f1[0], fe.estimate.value, fe.estimate.relative_error
        );
        assert!(fe.estimate.within(1e-3), "{:?}", fe.estimate);
        assert!(
            (band.0..band.1).contains(&over),
            "{file} {fidelity:?}: {over}"
        );
    }
    f1[0]
}

/// The shipped two-stage amplifier's optimum (a half about the y axis on its ground frame,
/// the stack between the input blocks): its lowest mode is antisymmetric about the y axis
/// (1312.4 Hz in the model, below the symmetric 1445.1 Hz), and the model is 15 to 35 %
/// above the part's (measured +27.4 % in plane stress, +20.3 % in plane strain), as its
/// statics are stiffer than the part's (its short thick arms and its lever held rigid).
#[test]
fn the_two_stages_first_frequency_lies_in_its_band_against_its_parts_modes() {
    let p = load("problems/bridge_lever_network.toml");
    let x = optimum(&p, "results/bridge_lever_network/optimum.json");
    check(&p, &x, (0.15, 0.35));
}

/// The rhombus (a quarter standing on its lower output block, unfolded by the model into
/// the half on its ground) with a 20 N/um stack and a 10 g payload, at the middle of its
/// bounds: its lowest mode is the sway antisymmetric about the y axis, the upper block and
/// its payload moving sideways on the leaves' bending (113.7 Hz, where the lowest symmetric
/// mode is 1869.2 Hz), and the model is 1 to 12 % above the half part's (measured +8.3 % in
/// plane stress, +2.2 % in plane strain; the leaves' roots turn in the blocks, which the
/// rigid bodies do not).
#[test]
fn the_rhombus_first_frequency_lies_in_its_band_against_its_parts_modes() {
    let text = std::fs::read_to_string("problems/rhombus_network.toml")
        .unwrap()
        .replace(
            "preload = \"40 N\"\n",
            "preload = \"40 N\"\nstiffness = \"20 N/um\"\n",
        )
        .replace("across = \"x\"\n", "across = \"x\"\npayload = \"10 g\"\n");
    let p = Problem::parse(Path::new("rhombus_modes.toml"), &text).unwrap();
    check(&p, &[12.5e-3, 22.75f64.to_radians(), 0.4e-3], (0.01, 0.12));
}

fn optimum(p: &Problem, file: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(file).unwrap();
    let optimum: serde_json::Value = serde_json::from_str(&text).unwrap();
    p.variables
        .iter()
        .map(|v| optimum["design_si"][v.name.as_str()].as_f64().unwrap())
        .collect()
}
