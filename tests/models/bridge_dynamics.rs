//! The dynamic outputs of the general bridge (src/model/bridge_dynamics.rs): the chain's
//! stiffness against the closed form of paper 004, the equivalent mass against limits and
//! scaling laws, the settling time against Runge-Kutta, gradients against differences.

use crate::common;

use common::{random_design, rel, rng, table1_optimum, wei2017_settings};
use flexopt::dynamics::{step_response, Oscillator};
use flexopt::model::bridge::dynamics::{DynamicsSettings, QuarterMode, SETTLING_BAND};
use flexopt::model::bridge::{Bridge, BridgeOutput, BridgeSettings, Geometry, QuarterBridge};
use flexopt::model::Model;
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};
use std::path::Path;

const K_OUT_ACTUATED: usize = BridgeOutput::KOutActuated as usize;
const MASS: usize = BridgeOutput::EquivalentMass as usize;
const FREQUENCY: usize = BridgeOutput::NaturalFrequency as usize;
const SETTLING: usize = BridgeOutput::SettlingTime as usize;

/// The masses of problems/wei2017_dynamic.toml.
fn stage() -> DynamicsSettings {
    DynamicsSettings::new(10e-3, 3e-3, 3e-3, 3e-3, 0.02)
}

fn bridge(dynamics: DynamicsSettings, k_pzt: Option<f64>) -> Bridge {
    let mut s = wei2017_settings();
    s.actuator.stiffness = k_pzt;
    s.dynamics = Some(dynamics);
    Bridge::new(s)
}

fn outputs(b: &dyn Model, x: &[f64], wanted: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; wanted.len()];
    b.evaluate(x, wanted, &mut out);
    out
}

fn mode(s: &BridgeSettings, x: [f64; 8], k_pzt: Option<f64>) -> QuarterMode<f64> {
    let g = Geometry::from_array(x);
    let b = g.b.compliance(s.width, &s.material);
    let d = g.d.compliance(s.width, &s.material);
    QuarterMode::new(&g, &g.trig(), &b, &d, k_pzt)
}

#[test]
fn the_chain_compliance_is_the_closed_form_of_appendix_a() {
    // the chain shares only the hinge compliances with Eq. 3-9: its node-5 compliance must
    // be [[a11, a12], [-a21, -a22]] (the sign convention of bridge.rs)
    let s = wei2017_settings();
    let mut r = rng(11);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let x = random_design(&mut r);
        let g = Geometry::from_array(x);
        let q = QuarterBridge::new(&g, s.width, &s.material);
        let c = mode(&s, x, None).compliance;
        let scale = q.a11().abs().max(q.a22().abs());
        for (got, want) in [
            (c[0][0], q.a11()),
            (c[0][1], q.a12()),
            (c[1][0], -q.a21()),
            (c[1][1], -q.a22()),
        ] {
            worst = worst.max((got - want).abs() / scale);
        }
    }
    assert!(worst < 1e-11, "chain vs closed form: {worst:e}");
}

#[test]
fn the_actuated_stiffness_condenses_eq8_with_the_actuator() {
    let mut r = rng(12);
    let actuators = [None, Some(1e5), Some(5e7)];
    let bridges = actuators.map(|k| bridge(stage(), k));
    let (soft_bridge, rigid_bridge) = (bridge(stage(), Some(1e-12)), bridge(stage(), None));
    for _ in 0..500 {
        let x = random_design(&mut r);
        let g = Geometry::from_array(x);
        let s = wei2017_settings();
        let q = QuarterBridge::new(&g, s.width, &s.material);
        let (a11, a21, a22) = (q.a11(), q.a21(), q.a22());
        for (k, b) in actuators.into_iter().zip(&bridges) {
            let got = outputs(b, &x, &[K_OUT_ACTUATED])[0];
            let want = match k {
                None => 1.0 / (-a22 - a21 * a21 / a11),
                Some(k) => 1.0 / (-a22 - a21 * a21 * k / (1.0 + a11 * k)),
            };
            assert!(rel(got, want, 0.0) < 1e-9, "k_pzt {k:?}: {got} vs {want}");
        }
        // a free input gives Eq. 11's k_out; a soft actuator tends to it
        let k_out = -1.0 / a22;
        let soft = outputs(&soft_bridge, &x, &[K_OUT_ACTUATED])[0];
        assert!(rel(soft, k_out, 0.0) < 1e-8, "{soft} vs {k_out}");
        // holding the input can only stiffen the output
        let rigid = outputs(&rigid_bridge, &x, &[K_OUT_ACTUATED])[0];
        assert!(rigid >= k_out * (1.0 - 1e-12));
    }
}

#[test]
fn the_deflection_shape_moves_links_rigidly() {
    let s = wei2017_settings();
    let mut r = rng(13);
    for _ in 0..500 {
        let x = random_design(&mut r);
        let m = mode(&s, x, Some(2e7));
        let [n2, n3, n4, n5] = m.nodes;
        // the input link moves along x, the output link along y by one unit
        assert_eq!(n2[1], 0.0);
        assert!((n5[0]).abs() < 1e-9 && (n5[1] - 1.0).abs() < 1e-9, "{n5:?}");
        // the middle link c turns without stretching: (u4 - u3) is normal to it
        let g = Geometry::from_array(x);
        let p = g.nodes();
        let (dx, dy) = (p[2][0] - p[1][0], p[2][1] - p[1][1]);
        let along = (n4[0] - n3[0]) * dx + (n4[1] - n3[1]) * dy;
        assert!(along.abs() < 1e-9 * (dx * dx + dy * dy).sqrt(), "{along:e}");
        // and the turn is the rotation the shape reports
        let turn = ((n4[1] - n3[1]) * dx - (n4[0] - n3[0]) * dy) / (dx * dx + dy * dy);
        assert!(rel(turn, m.rotation, 1e-9) < 1e-9);
    }
}

#[test]
fn a_massless_bridge_carries_its_payload_and_one_output_link() {
    // with a weightless bridge, only the moving output link and the payload move: the
    // mass is theirs exactly, and f = sqrt(K / m) / 2 pi
    let x = table1_optimum();
    let mut s = wei2017_settings();
    s.material.density = 0.0;
    s.dynamics = Some(DynamicsSettings::new(7e-3, 0.0, 2e-3, 3e-3, 0.02));
    let b = Bridge::new(s);
    let [k, m, f] = outputs(&b, &x, &[K_OUT_ACTUATED, MASS, FREQUENCY])[..] else {
        unreachable!()
    };
    assert!(rel(m, 9e-3, 0.0) < 1e-15, "{m}");
    let expected = (k / 9e-3).sqrt() / (2.0 * std::f64::consts::PI);
    assert!(rel(f, expected, 0.0) < 1e-15);
}

#[test]
fn frequency_scales_with_the_square_root_of_e_over_rho() {
    // with only the bridge's own mass, f ~ sqrt(E / rho) at a fixed shape
    let mut r = rng(14);
    let own = DynamicsSettings::new(0.0, 0.0, 0.0, 3e-3, 0.02);
    for _ in 0..100 {
        let x = random_design(&mut r);
        let mut s = wei2017_settings();
        s.dynamics = Some(own.clone());
        let f0 = outputs(&Bridge::new(s.clone()), &x, &[FREQUENCY])[0];
        s.material.youngs_modulus *= 4.0;
        let f_stiff = outputs(&Bridge::new(s.clone()), &x, &[FREQUENCY])[0];
        s.material.density *= 9.0;
        let f_heavy = outputs(&Bridge::new(s), &x, &[FREQUENCY])[0];
        assert!(rel(f_stiff, 2.0 * f0, 0.0) < 1e-12);
        assert!(rel(f_heavy, 2.0 * f0 / 3.0, 0.0) < 1e-12);
    }
}

#[test]
fn mass_grows_and_frequency_falls_with_every_added_mass() {
    let x = table1_optimum();
    let base = stage();
    let f = |d: DynamicsSettings| outputs(&bridge(d, Some(3e7)), &x, &[MASS, FREQUENCY]);
    let [m0, f0] = f(base.clone())[..] else {
        unreachable!()
    };
    let added = 1e-3;
    let mut gains = Vec::new();
    for d in [
        DynamicsSettings::new(base.payload_mass + added, 3e-3, 3e-3, 3e-3, 0.02),
        DynamicsSettings::new(base.payload_mass, 3e-3 + added, 3e-3, 3e-3, 0.02),
        DynamicsSettings::new(base.payload_mass, 3e-3, 3e-3 + added, 3e-3, 0.02),
        DynamicsSettings::new(base.payload_mass, 3e-3, 3e-3, 4e-3, 0.02),
        base.clone().with_stack_mass(added),
    ] {
        let [m, fr] = f(d)[..] else { unreachable!() };
        assert!(m > m0 && fr < f0, "{m} {fr} vs {m0} {f0}");
        gains.push(m - m0);
    }
    // a gram on the payload counts fully, so does a gram on each output link (one of the
    // two moves with q, the other rests); the input links sit half way up and move by
    // q/2 along y and by Xin along x: a gram on each counts (1 + (Xin/Yout)^2) / 2
    assert!((gains[0] - added).abs() < 1e-15);
    assert!((gains[2] - added).abs() < 1e-15);
    let xin = mode(&wei2017_settings(), x, Some(3e7)).nodes[0][0];
    assert!(xin.abs() > 0.01, "the actuator gives way: {xin}");
    assert!(
        rel(gains[1], added * (1.0 + xin * xin) / 2.0, 0.0) < 1e-9,
        "{}",
        gains[1]
    );
    // the stack is a rod between the input links: its ends move by +-Xin along x, its
    // middle stays, and it rides up by q/2 with them: a gram of it counts (1 + Xin^2/3) / 4
    assert!(
        rel(gains[4], added * (1.0 + xin * xin / 3.0) / 4.0, 0.0) < 1e-9,
        "{}",
        gains[4]
    );
    // the whole bridge is below its total mass plus the payload
    let s = wei2017_settings();
    let g = Geometry::from_array(x);
    let rho_w = s.material.density * s.width;
    let bridge_mass =
        4.0 * (g.l2() * g.b.dims[1] + g.l3 * 3e-3 + g.l4() * g.d.dims[1]) * rho_w + 12e-3;
    assert!(m0 > base.payload_mass + 3e-3 && m0 < base.payload_mass + bridge_mass);
}

#[test]
fn settling_time_is_that_of_the_runge_kutta_response() {
    let mut r = rng(15);
    for zeta in [0.005, 0.02, 0.3, 1.5] {
        let b = bridge(DynamicsSettings::new(10e-3, 3e-3, 3e-3, 3e-3, zeta), None);
        for _ in 0..3 {
            let x = random_design(&mut r);
            let [k, m, ts] = outputs(&b, &x, &[K_OUT_ACTUATED, MASS, SETTLING])[..] else {
                unreachable!()
            };
            let osc = Oscillator {
                mass: m,
                damping: 2.0 * zeta * (m * k).sqrt(),
                stiffness: k,
            };
            let direct = step_response(&osc, 1.0, SETTLING_BAND, 1e-10);
            assert!(
                (ts - direct.settling_time).abs() <= 2.0 * direct.step,
                "zeta {zeta}: {ts} vs {} (step {})",
                direct.settling_time,
                direct.step
            );
        }
    }
}

#[test]
fn gradients_of_the_dynamic_outputs_match_differences() {
    let b = bridge(stage(), Some(3e7));
    let wanted = [K_OUT_ACTUATED, MASS, FREQUENCY, SETTLING];
    let mut r = rng(16);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let x = random_design(&mut r);
        let mut val = [0.0; 4];
        let mut jac = [0.0; 32];
        b.evaluate_with_gradient(&x, &wanted, &mut val, &mut jac);
        for j in 0..8 {
            let h = 1e-6 * x[j].abs().max(1e-4);
            let at = |t: f64| {
                let mut y = x;
                y[j] += t;
                outputs(&b, &y, &wanted)
            };
            let (p, m, p2, m2) = (at(h), at(-h), at(2.0 * h), at(-2.0 * h));
            for i in 0..4 {
                let fd = (8.0 * (p[i] - m[i]) - (p2[i] - m2[i])) / (12.0 * h);
                let scale = val[i].abs() / x[j].abs().max(1e-4);
                worst = worst.max((jac[i * 8 + j] - fd).abs() / (fd.abs().max(scale)));
            }
        }
    }
    assert!(worst < 1e-6, "worst gradient error {worst:e}");
}

#[test]
fn the_frequency_floor_binds_and_costs_amplification() {
    // problems/wei2017_dynamic.toml: the floor of 1000 Hz lies above the 802 Hz of the
    // unconstrained optimum, so the study must end on it, below wei2017's 12.898
    let problem = Problem::load(Path::new("problems/wei2017_dynamic.toml")).unwrap();
    let mut options = StudyOptions::from_problem(&problem);
    options.starts = 60;
    let study = study::run(&problem, &options);
    assert!(study.any_feasible);
    let best = &study.runs[study.best];
    let [da, f] = outputs(
        problem.model(),
        &best.x_end,
        &[BridgeOutput::Amplification as usize, FREQUENCY],
    )[..] else {
        unreachable!()
    };
    assert!(rel(f, 1000.0, 0.0) < 1e-8, "the floor is active: {f} Hz");
    assert!(rel(da.abs(), best.objective, 0.0) < 1e-12);
    assert!(da.abs() > 11.0 && da.abs() < 12.8979, "{da}");
    // the unconstrained optimum of wei2017 violates the floor
    let free = outputs(problem.model(), &table1_optimum(), &[FREQUENCY])[0];
    assert!(free < 1000.0, "{free}");
}

#[test]
fn the_dynamics_section_is_validated() {
    let text = std::fs::read_to_string("problems/wei2017_dynamic.toml").unwrap();
    let parse = |from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        Problem::parse(Path::new("dyn.toml"), &text.replacen(from, to, 1))
    };
    for (from, to, key, words) in [
        (
            "damping_ratio = 0.02",
            "damping_ratio = 0",
            "dynamics.damping_ratio",
            "(0, 10]",
        ),
        (
            "damping_ratio = 0.02",
            "damping_ratio = -0.1",
            "dynamics.damping_ratio",
            "(0, 10]",
        ),
        (
            "payload_mass = \"10 g\"",
            "payload_mass = \"-1 g\"",
            "dynamics.payload_mass",
            "negative",
        ),
        (
            "payload_mass = \"10 g\"",
            "payload_mass = \"10 mm\"",
            "dynamics.payload_mass",
            "unit",
        ),
        (
            "link_thickness = \"3 mm\"",
            "link_thickness = 3",
            "part.link_thickness",
            "no unit",
        ),
        (
            "damping_ratio = 0.02",
            "damping_ratio = 0.02\nlink_thickness = \"3 mm\"",
            "dynamics.link_thickness",
            "[part] link_thickness",
        ),
        (
            "damping_ratio = 0.02",
            "damping_ratio = 0.02\nmode = 2",
            "dynamics.mode",
            "unknown",
        ),
    ] {
        let e = parse(from, to).expect_err(to);
        let shown = e.to_string();
        assert!(shown.starts_with("dyn.toml:"), "{shown}");
        assert_eq!(e.key, key, "{shown}");
        assert!(shown.contains(words), "{words:?} not in {shown}");
    }
    // the 3-PRR model takes no [dynamics]
    let prr3 = std::fs::read_to_string("problems/prr3_frequency.toml").unwrap()
        + "\n[dynamics]\npayload_mass = \"1 g\"\ninput_link_mass = \"1 g\"\noutput_link_mass = \"1 g\"\ndamping_ratio = 0.1\n";
    let e = Problem::parse(Path::new("p.toml"), &prr3).expect_err("refused");
    assert_eq!(e.key, "dynamics");
}

/// `[dynamics]` without the links' masses takes the part's blocks: each block's rectangle of
/// `[part]`'s sizes through the plate, of the material's density. The dynamic outputs then
/// equal those of the file that states these masses, and the rectangles stand for the
/// blocks the part is cut with (their hinges' pads and tilted faces): at Table 1's optimum the
/// cut input block is 0.86 % larger than its rectangle, the output block 2.14 %.
#[test]
fn the_links_masses_default_to_the_parts_blocks() {
    let text = std::fs::read_to_string("problems/wei2017_dynamic.toml").unwrap();
    let stated = [
        "input_link_mass = \"3 g\"\n",
        "output_link_mass = \"3 g\"\n",
    ];
    let mut left_out = text.clone();
    for line in stated {
        assert!(left_out.contains(line), "{line}");
        left_out = left_out.replacen(line, "", 1);
    }
    // 7075-T6, 2810 kg/m^3, a 10 mm plate; blocks 6 x 12 mm and 10 x 6 mm (the defaults)
    let (rho_w, input, output) = (2810.0 * 10e-3, 6e-3 * 12e-3, 10e-3 * 6e-3);
    let masses = [rho_w * input, rho_w * output];
    let given = text
        .replacen(
            stated[0],
            &format!("input_link_mass = \"{} kg\"\n", masses[0]),
            1,
        )
        .replacen(
            stated[1],
            &format!("output_link_mass = \"{} kg\"\n", masses[1]),
            1,
        );
    let by_default = Problem::parse(Path::new("d.toml"), &left_out).unwrap();
    let by_hand = Problem::parse(Path::new("g.toml"), &given).unwrap();
    let x = table1_optimum();
    let wanted = [MASS, FREQUENCY, K_OUT_ACTUATED];
    let a = outputs(by_default.model(), &x, &wanted);
    let b = outputs(by_hand.model(), &x, &wanted);
    for (a, b) in a.iter().zip(&b) {
        assert!(rel(*a, *b, 0.0) < 1e-14, "{a} vs {b}");
    }
    // the blocks as cut: the left input block and the upper output block
    let spec = by_default
        .mechanism()
        .part_spec(&x)
        .expect("the bridge has a part")
        .expect("Table 1's optimum gives its part");
    let area = |k: usize| {
        let p = &spec.solids[k].points;
        let n = p.len();
        0.5 * (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum::<f64>()
            .abs()
    };
    let named = |name: &str| {
        let found = spec.solids.iter().position(|s| s.name.contains(name));
        found.unwrap_or_else(|| panic!("no solid {name}"))
    };
    let (left_input, upper_output) = (named("left input block"), named("upper output block"));
    for (k, rectangle) in [(left_input, input), (upper_output, output)] {
        let off = (area(k) - rectangle) / rectangle;
        println!(
            "{}: {:+.2} % of its rectangle",
            spec.solids[k].name,
            100.0 * off
        );
        assert!(off.abs() < 0.03, "{}: {off}", spec.solids[k].name);
    }
}

/// `[actuator] mass` is the stack's own mass: the file's bridge is the one built with
/// [`DynamicsSettings::with_stack_mass`], and a mass below zero is refused by its key.
#[test]
fn the_files_stack_mass_is_the_dynamics_stack_mass() {
    let text = std::fs::read_to_string("problems/wei2017_dynamic.toml").unwrap();
    let with = |mass: &str| {
        text.replacen(
            "[actuator]\n",
            &format!("[actuator]\nmass = \"{mass}\"\n"),
            1,
        )
    };
    let p = Problem::parse(Path::new("stack.toml"), &with("14 g")).unwrap();
    let x = table1_optimum();
    let from_file = outputs(p.model(), &x, &[MASS, FREQUENCY]);
    let by_hand = outputs(
        &bridge(stage().with_stack_mass(14e-3), None),
        &x,
        &[MASS, FREQUENCY],
    );
    let bare = outputs(&bridge(stage(), None), &x, &[MASS, FREQUENCY]);
    for (a, b) in from_file.iter().zip(&by_hand) {
        assert!(rel(*a, *b, 0.0) < 1e-14, "{a} vs {b}");
    }
    assert!(
        from_file[0] > bare[0] + 14e-3 / 4.0 * 0.999,
        "{from_file:?} {bare:?}"
    );
    let e = Problem::parse(Path::new("stack.toml"), &with("-1 g")).expect_err("refused");
    let message = e.to_string();
    assert!(
        message.contains("stack.toml") && message.contains("actuator.mass"),
        "{message}"
    );
}
