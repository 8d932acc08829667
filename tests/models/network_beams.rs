//! Flexible beams in a flexure network (`[[network.beams]]`, issue 25): a body on one beam
//! against the Timoshenko cantilever's tip compliances, two parallel beams against the
//! guided beams' `24 E I / L^3` with shear, a beam against the strip hinge it is with
//! Cowper's shear coefficient for the strip's 1, the gradients against central
//! differences, and the description's faults named by key.

use std::path::Path;

use crate::common::{rel, rng};
use crate::network_shipped::worst_central_difference;
use flexopt::model::hinge::HingeKind;
use flexopt::model::material::Material;
use flexopt::model::network::structure::beam_compliance;
use flexopt::model::Model;
use flexopt::problem::Problem;
use rand::Rng;

const WIDTH: f64 = 0.01;

/// A network of parameters `L` and `t` (mm, bounds 10-40 and 0.5-2) whose bodies, members
/// and ports are `body`: the input at `input` across, the output there along x.
fn network(members: &str, input: [&str; 2]) -> String {
    format!(
        r#"
name = "beams"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
parameters = [["L", "length"], ["t", "length"]]

[[network.bodies]]
name = "tip"
outline = [["L", "-6"], ["L + 5", "-6"], ["L + 5", "6"], ["L", "6"]]

{members}

[network.input]
body = "tip"
at = ["{}", "{}"]
direction = ["0", "1"]

[[network.outputs]]
name = "along"
body = "tip"
at = ["{}", "{}"]
direction = ["1", "0"]

[actuator]
nominal_stroke = "0.1 mm"
preload = "1 N"
stiffness = "50 N/um"

[[variables]]
name = "L"
unit = "mm"
lower = 10
upper = 40

[[variables]]
name = "t"
unit = "mm"
lower = 0.5
upper = 2

[objective]
maximize = "amplification"
"#,
        input[0], input[1], input[0], input[1]
    )
}

fn beam(name: &str, y: &str) -> String {
    format!(
        "[[network.beams]]\nname = \"{name}\"\nfrom = \"ground\"\nto = \"tip\"\n\
         start = [\"0\", \"{y}\"]\nend = [\"L\", \"{y}\"]\nthickness = \"t\"\n"
    )
}

fn parse(text: &str) -> Problem {
    Problem::parse(Path::new("beams.toml"), text).unwrap()
}

fn values(m: &dyn Model, x: &[f64], names: &[&str]) -> Vec<f64> {
    let wanted: Vec<usize> = names.iter().map(|n| m.output_index(n).unwrap()).collect();
    let mut v = vec![0.0; names.len()];
    m.evaluate(x, &wanted, &mut v);
    v
}

fn designs(seed: u64) -> Vec<Vec<f64>> {
    let mut r = rng(seed);
    (0..20)
        .map(|_| vec![r.random_range(10e-3..40e-3), r.random_range(0.5e-3..2e-3)])
        .collect()
}

/// The file's actuator (0.1 mm free stroke, 50 N/um, 1 N preload) on an input of
/// stiffness `k_in`: its force at the stroke it makes there.
fn largest_force(k_in: f64) -> f64 {
    let (stroke, k_a, preload) = (1e-4, 50e6, 1.0);
    k_in * stroke * k_a / (k_in + k_a) + preload
}

/// Cowper's shear coefficient of a rectangle, J. Appl. Mech. 33 (1966) 335.
fn kappa(m: &Material) -> f64 {
    let nu = m.poisson_ratio;
    10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
}

/// A body on one beam from the ground, loaded at the beam's end: across, the cantilever's
/// `L^3 / (3 E I) + L / (kappa G A)`; along, `L / (E A)`; the stress at the root `6 F L /
/// (w t^2)` under the actuator's largest force `F = k_in X_tr + F_preload`, `X_tr = X k_a /
/// (k_in + k_a)` the stroke the 50 N/um stack makes against the beam (paper 004, Eq. 13).
#[test]
fn a_body_on_one_beam_is_the_timoshenko_cantilever() {
    let p = parse(&network(&beam("leaf", "0"), ["L", "0"]));
    let m = p.model();
    let mat = Material::al7075_t6();
    let (e, g) = (mat.youngs_modulus, mat.shear_modulus());
    let mut worst = 0.0f64;
    for x in designs(381) {
        let [l, t] = [x[0], x[1]];
        let (a, i) = (WIDTH * t, WIDTH * t * t * t / 12.0);
        let across = l.powi(3) / (3.0 * e * i) + l / (kappa(&mat) * g * a);
        let v = values(m, &x, &["k_in", "k_out", "stress_leaf", "stress_max"]);
        let force = largest_force(v[0]);
        worst = worst
            .max(rel(v[0], across.recip(), 1e-300))
            .max(rel(v[1], e * a / l, 1e-300))
            .max(rel(v[2], 6.0 * force * l / (WIDTH * t * t), 1e-300))
            .max(rel(v[3], v[2], 1e-300));
    }
    eprintln!("one beam against the cantilever: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// Two parallel beams, `d = 8 mm` apart, loaded across on the line through their
/// mid-lengths: the body translates, each beam guided, `k = 2 / (L^3 / (12 E I) + L /
/// (kappa G A))`, `24 E I / L^3` with shear; along them, `2 E A / L`; no turn.
#[test]
fn two_parallel_beams_are_the_guided_pair() {
    let members = format!("{}\n{}", beam("top", "4"), beam("bottom", "-4"));
    let p = parse(&network(&members, ["L/2", "0"]));
    let m = p.model();
    let mat = Material::al7075_t6();
    let (e, g) = (mat.youngs_modulus, mat.shear_modulus());
    let mut worst = 0.0f64;
    let mut turn = 0.0f64;
    for x in designs(382) {
        let [l, t] = [x[0], x[1]];
        let (a, i) = (WIDTH * t, WIDTH * t * t * t / 12.0);
        let guided = l.powi(3) / (12.0 * e * i) + l / (kappa(&mat) * g * a);
        let v = values(m, &x, &["k_in", "k_out", "rotation_top", "rotation_bottom"]);
        worst = worst
            .max(rel(v[0], 2.0 / guided, 1e-300))
            .max(rel(v[1], 2.0 * e * a / l, 1e-300));
        turn = turn.max(v[2].abs()).max(v[3].abs());
    }
    eprintln!("two beams against the guided pair: {worst:e}, turn {turn:e}");
    assert!(worst < 1e-12, "{worst:e}");
    assert!(turn < 1e-12, "{turn:e}");
}

/// The beam's compliances are the strip's but for the shear term, Cowper's `kappa` for the
/// strip's 1; so a body on a strip hinge and on the same beam have the same stresses per
/// unit force (paper 004 Eq. 15-16, the same for both) and axial stiffness, and their transverse compliances differ by `L / (G A)
/// (1 / kappa - 1)`.
#[test]
fn a_beam_is_the_strip_hinge_with_cowpers_shear() {
    let mat = Material::al7075_t6();
    let g = mat.shear_modulus();
    let strip = "[[network.hinges]]\nname = \"leaf\"\nkind = \"strip\"\nfrom = \"ground\"\n\
                 to = \"tip\"\nstart = [\"0\", \"0\"]\nangle = \"0\"\nl = \"L\"\nt = \"t\"\n";
    let (hinge, beam) = (
        parse(&network(strip, ["L", "0"])),
        parse(&network(&beam("leaf", "0"), ["L", "0"])),
    );
    let names = ["k_in", "k_out", "stress_leaf_from", "stress_leaf_to"];
    let mut worst = 0.0f64;
    for x in designs(383) {
        let [l, t] = [x[0], x[1]];
        let c = beam_compliance(l, t, WIDTH, &mat);
        let s = HingeKind::Strip.compliance(&[l, t], WIDTH, &mat);
        let shear = l / (g * WIDTH * t) * (1.0 / kappa(&mat) - 1.0);
        worst = worst
            .max(rel(c.c11, s.c11, 1e-300))
            .max(rel(c.c23, s.c23, 1e-300))
            .max(rel(c.c33, s.c33, 1e-300))
            .max(rel(c.c22 - s.c22, shear, 1e-300));
        let (h, b) = (
            values(hinge.model(), &x, &names),
            values(beam.model(), &x, &names),
        );
        let per_force = |v: &[f64], i: usize| v[i] / largest_force(v[0]);
        worst = worst
            .max(rel(b[0].recip(), h[0].recip() + shear, 1e-300))
            .max(rel(b[1], h[1], 1e-300))
            .max(rel(per_force(&b, 2), per_force(&h, 2), 1e-300));
        // the loaded end carries no moment: its stress is rounding against the root's
        worst = worst.max((per_force(&b, 3) - per_force(&h, 3)).abs() / per_force(&h, 2));
    }
    eprintln!("beam against strip: {worst:e}");
    // the solve's rounding, on compliances that differ by a few 1e-3
    assert!(worst < 1e-11, "{worst:e}");
}

/// Every output of a body on two beams, the natural frequencies with the beams' lumped
/// masses among them, has its exact gradient, against central differences.
#[test]
fn a_beam_networks_outputs_have_their_central_difference_gradients() {
    let members = format!("{}\n{}", beam("top", "4"), beam("bottom", "-4"));
    // loaded off the beams' mid-lengths and off the axis: no output is zero by symmetry
    let p = parse(&network(&members, ["L", "2"]));
    let (worst, kinks, checks) = worst_central_difference(
        p.model(),
        &designs(384),
        &[(10e-3, 40e-3), (0.5e-3, 2e-3)],
        &[],
    );
    eprintln!(
        "beams: gradients vs central differences: worst {worst:?}, {kinks} kinks in {checks}"
    );
    assert!(kinks * 50 < checks, "{kinks} kinks in {checks}");
    assert!(worst.0 < 1e-6, "{worst:?}");
}

/// A beam's mass, lumped half at each end: a body on one slender beam has the f1 of the
/// body on the strip hinge (massless) with half the beam's mass as a payload at the beam's
/// end, but for the shear terms the two differ by (`(t/L)^2` of the bending, below 1e-3
/// here); without the payload the strip's f1 is higher by the mass's share.
#[test]
fn a_beams_mass_is_lumped_half_at_each_end() {
    let mat = Material::al7075_t6();
    let strip = "[[network.hinges]]\nname = \"leaf\"\nkind = \"strip\"\nfrom = \"ground\"\n\
                 to = \"tip\"\nstart = [\"0\", \"0\"]\nangle = \"0\"\nl = \"L\"\nt = \"t\"\n";
    // the actuator's spring at the plate's far edge: the first mode turns the plate about
    // it, moving the beam's end
    let far = ["L + 5", "0"];
    let beam = parse(&network(&beam("leaf", "0"), far));
    for x in [[40e-3, 0.5e-3], [30e-3, 0.6e-3], [20e-3, 0.5e-3]] {
        let half = 0.5 * mat.density * WIDTH * x[0] * x[1];
        let text = network(strip, far);
        let output = "at = [\"L + 5\", \"0\"]\ndirection = [\"1\", \"0\"]";
        assert!(text.contains(output));
        let loaded = text.replacen(
            output,
            &format!(
                "at = [\"L\", \"0\"]\ndirection = [\"1\", \"0\"]\npayload = \"{} g\"",
                half * 1e3
            ),
            1,
        );
        let f1 = |text: &str| values(parse(text).model(), &x, &["f1"])[0];
        let (b, with, without) = (values(beam.model(), &x, &["f1"])[0], f1(&loaded), f1(&text));
        eprintln!("f1 at {x:?}: beam {b}, strip with half its mass {with}, without {without}");
        assert!(rel(b, with, 1e-300) < 1e-3, "{b} vs {with}");
        assert!(without > b * 1.01, "{without} vs {b}");
    }
}

/// The faults of a beam's description, each named by its key.
#[test]
fn a_beams_faults_are_named_by_key() {
    let says = |members: &str, key: &str, words: &[&str]| {
        let Err(e) = Problem::parse(Path::new("beams.toml"), &network(members, ["L", "0"])) else {
            panic!("refused: {members}");
        };
        assert_eq!(e.key, key, "{e}");
        let shown = e.to_string();
        for w in words {
            assert!(shown.contains(w), "{w:?} missing from: {shown}");
        }
    };
    let leaf = beam("leaf", "0");
    says(
        &leaf.replace("from = \"ground\"", "from = \"tip\""),
        "network.beams[0].to",
        &["joins \"tip\" to itself"],
    );
    says(
        &leaf.replace("to = \"tip\"", "to = \"top\""),
        "network.beams[0].to",
        &["unknown body \"top\""],
    );
    says(
        &format!("{leaf}\n{leaf}"),
        "network.beams[1].name",
        &["\"leaf\" names another beam or hinge"],
    );
    says(
        &leaf.replace("thickness = \"t\"", "thickness = \"t +\""),
        "network.beams[0].thickness",
        &["in \"t +\""],
    );
    // at the middle of the bounds: the model's own checks, named by the beam's key
    for (edit, words) in [
        (
            leaf.replace("[\"L\", \"0\"]", "[\"0\", \"0\"]"),
            "same point",
        ),
        (
            leaf.replace("thickness = \"t\"", "thickness = \"t - 1.25\""),
            "not positive",
        ),
    ] {
        let Err(e) = Problem::parse(Path::new("beams.toml"), &network(&edit, ["L", "0"])) else {
            panic!("refused: {edit}");
        };
        let shown = e.to_string();
        assert!(
            shown.contains("network.beams[0]") && shown.contains(words),
            "{shown}"
        );
        assert!(shown.contains("middle of the bounds"), "{shown}");
    }
}
