//! A network's tolerance on Young's modulus: its stiffnesses spread as the factor does, a
//! stroke against a stack of finite stiffness as the stack's share says, the first order
//! against Monte Carlo; the default modulus tolerance of a network with a part; and the
//! robust lever's yield by Monte Carlo.

use std::path::Path;

use flexopt::problem::tolerances::Input;
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};
use flexopt::tolerance::analyze;
use flexopt::tolerance::monte_carlo::Settings;

/// problems/lever_network.toml with `edit` applied to its text.
fn lever_with(edit: impl Fn(String) -> String) -> Problem {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("problems/lever_network.toml")).unwrap();
    Problem::parse(Path::new("lever_network.toml"), &edit(text)).unwrap()
}

fn settings(samples: usize) -> Settings {
    Settings {
        samples,
        seed: 7,
        threads: 0,
    }
}

/// With the modulus's tolerance alone (no part, so no default of the process), of relative
/// standard deviation `s`: `k = factor k_0`, so the stiffnesses' relative spread is `s`; the
/// stroke on a stack of stiffness `k_a` is `X k_a / (k_in + k_a)` times the amplification,
/// which the factor does not move, so its relative spread is `s k_in / (k_in + k_a)`.
#[test]
fn a_networks_modulus_tolerance_spreads_its_stiffnesses_by_the_factor() {
    let s = 0.01;
    let p = lever_with(|t| {
        let t = t.replace("\n[part]\n", "\n");
        let extra = "[[constraints]]\noutput = \"k_in\"\nunit = \"N/um\"\nlower = 1\n\n\
                     [[constraints]]\noutput = \"stroke_out\"\nunit = \"um\"\nlower = 1\n\n";
        let t = t.replace("[search]\n", &format!("{extra}[search]\n"));
        format!("{t}\n[tolerances]\nyoungs_modulus = {{ sigma = {s} }}\n")
    });
    assert_eq!(p.tolerances.len(), 1);
    assert_eq!(p.tolerances[0].input, Input::Modulus);
    let x: Vec<f64> = p
        .variables
        .iter()
        .map(|v| 0.5 * (v.lower + v.upper))
        .collect();
    let n = 200_000;
    let a = analyze(&p, &x, settings(n)).unwrap();
    let slot = |name: &str| {
        let index = p.model().output_index(name).unwrap();
        a.outputs.wanted.iter().position(|&w| w == index).unwrap()
    };
    let k_in = a.first_order[slot("k_in")].nominal;
    let k_a = 60e6;
    for (name, relative) in [
        ("k_in", s),
        ("k_out", s),
        ("amplification", 0.0),
        ("stroke_out", s * k_in / (k_in + k_a)),
    ] {
        let (f, mc) = (
            &a.first_order[slot(name)],
            &a.monte_carlo.outputs[slot(name)],
        );
        assert!(
            (f.std - relative * f.nominal.abs()).abs() <= 1e-9 * f.nominal.abs(),
            "{name}: first-order std {} against {}",
            f.std,
            relative * f.nominal.abs()
        );
        // the output is linear in the factor (the stiffnesses) or nearly (the stroke, whose
        // curvature over 1 % moves its spread by far less than the sampling's error); the
        // amplification's samples differ by round-off alone (1.5e-12 of it)
        let se = f.std / (2.0 * n as f64).sqrt();
        assert!(
            (mc.std - f.std).abs() <= 4.0 * se + 1e-11 * f.nominal.abs(),
            "{name}: Monte Carlo std {} against first order {}",
            mc.std,
            f.std
        );
    }
}

/// The lever has a part, so the process's defaults apply, the modulus's among them; and the
/// robust study keeps 99 % of its parts within the limits, by Monte Carlo.
#[test]
fn the_robust_lever_network_meets_its_yield() {
    let p = lever_with(|t| t.replace("[search]\n", "[search]\nrobust = { yield = 0.99 }\n"));
    assert!(
        p.tolerances.iter().any(|t| t.input == Input::Modulus),
        "{:?}",
        p.tolerances
    );
    let s = study::run(&p, &StudyOptions::from_problem(&p));
    assert!(s.any_feasible);
    let x = s.reported_design().to_vec();
    let mc = analyze(&p, &x, settings(100_000)).unwrap().monte_carlo;
    assert!(
        mc.yield_interval[0] >= 0.99,
        "yield {} {:?}",
        mc.yield_fraction,
        mc.yield_interval
    );
    // the nominal optimum stands on its k_out limit and keeps about half its parts
    let mut nominal = p.clone();
    nominal.search.robust = None;
    let n = study::run(&nominal, &StudyOptions::from_problem(&nominal));
    let half = analyze(&nominal, n.reported_design(), settings(100_000))
        .unwrap()
        .monte_carlo;
    assert!(
        (half.yield_fraction - 0.5).abs() < 0.02,
        "{}",
        half.yield_fraction
    );
    assert!(s.reported_objective() < n.reported_objective());
}
