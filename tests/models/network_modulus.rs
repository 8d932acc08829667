//! The networks at other moduli (`ModulusScaling`): at the factor one the plain outputs; at
//! another factor the plain network on a stack softer by that factor (every flexure stiffer
//! by it, or the stack softer, is the same eigenproblem and the same statics up to the
//! factor); and the Hessians a robust study reads against central differences of the exact
//! gradients.

use std::path::Path;

use rand::Rng;

use crate::common::{rel, rng};
use flexopt::model::mechanism::ModulusScaling;
use flexopt::problem::Problem;

const SHIPPED: [&str; 6] = [
    "lever_network",
    "guide_network",
    "rhombus_network",
    "wei2017_network",
    "scott_russell_network",
    "bridge_lever_network",
];

fn load(name: &str) -> Problem {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    Problem::load(&root.join(format!("problems/{name}.toml"))).unwrap()
}

fn scaling(p: &Problem) -> &dyn ModulusScaling {
    p.mechanism
        .modulus
        .as_deref()
        .expect("a network varies its modulus")
}

/// Designs drawn uniformly within the file's bounds (fixed variables at their values).
fn designs(p: &Problem, count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut r = rng(seed);
    (0..count)
        .map(|_| {
            p.variables
                .iter()
                .map(|v| {
                    if v.upper > v.lower {
                        r.random_range(v.lower..v.upper)
                    } else {
                        v.lower
                    }
                })
                .collect()
        })
        .collect()
}

/// Below this an output is zero by the part's symmetry (a rotation of a hinge that does not
/// turn: 1e-18 rad of round-off), its value and gradient round-off alone; every other output
/// of these networks is above 1e-7 in SI.
const ZERO: f64 = 1e-15;

#[test]
fn every_shipped_network_at_the_factor_one_is_the_plain_network() {
    let mut worst = [0.0f64; 3];
    for name in SHIPPED {
        let p = load(name);
        let (model, scaled) = (p.model(), scaling(&p));
        let all = model.available_outputs();
        let (m, n) = (all.len(), model.parameters().len());
        for x in designs(&p, 10, 3) {
            let (mut plain, mut plain_jac) = (vec![0.0; m], vec![0.0; m * n]);
            model.evaluate_with_gradient(&x, &all, &mut plain, &mut plain_jac);
            let mut f64_plain = vec![0.0; m];
            model.evaluate(&x, &all, &mut f64_plain);
            let mut values = vec![0.0; m];
            scaled.evaluate_scaled(&x, 1.0, &all, &mut values);
            let (mut v1, mut j1) = (vec![0.0; m], vec![0.0; m * (n + 1)]);
            scaled.evaluate_scaled_with_gradient(&x, 1.0, &all, &mut v1, &mut j1);
            let (mut v2, mut j2, mut h2) = (
                vec![0.0; m],
                vec![0.0; m * (n + 1)],
                vec![0.0; m * (n + 1) * (n + 1)],
            );
            scaled.evaluate_with_hessian(&x, &all, &mut v2, &mut j2, &mut h2);
            for i in 0..m {
                assert!(plain[i].is_finite(), "{name}: output {i} at {x:?}");
                if plain[i].abs() < ZERO {
                    assert!([values[i], v1[i], v2[i]].iter().all(|v| v.abs() < ZERO));
                    continue;
                }
                worst[0] = worst[0].max(rel(values[i], f64_plain[i], 1e-300));
                for v in [v1[i], v2[i]] {
                    worst[1] = worst[1].max(rel(v, plain[i], 1e-300));
                }
                let row = &plain_jac[i * n..(i + 1) * n];
                let scale = row.iter().fold(1e-300f64, |s, g| s.max(g.abs()));
                for (j, g) in row.iter().enumerate() {
                    for jac in [&j1, &j2] {
                        worst[2] = worst[2].max((jac[i * (n + 1) + j] - g).abs() / scale);
                    }
                }
            }
        }
    }
    eprintln!(
        "scaled at 1 against plain, worst relative difference of values, of the dual numbers' \
         values, of gradients: {:e} {:e} {:e}",
        worst[0], worst[1], worst[2]
    );
    // each scalar against its own kind (the plain and the dual numbers' values differ by
    // round-off where a difference cancels: the lever's k_out_blocked by 2e-12); the
    // gradients by round-off (5e-13), the dual numbers' operations in another order
    assert!(
        worst[0] <= 1e-12 && worst[1] <= 1e-12,
        "{:e} {:e}",
        worst[0],
        worst[1]
    );
    assert!(worst[2] <= 1e-11, "{:e}", worst[2]);
}

/// At the factor `s` on the moduli, the lever's stiffnesses are `s` times the plain lever's
/// on a stack of `k_a / s`, its frequencies `sqrt(s)` times, its amplification and strokes
/// those: both solve `s K + k_a K_stack` (the second divided by `s`) with the same masses.
#[test]
fn the_lever_at_a_modulus_factor_is_the_lever_on_a_stack_softer_by_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("problems/lever_network.toml")).unwrap();
    let stack = "stiffness = \"60 N/um\"";
    assert!(text.contains(stack));
    let p = load("lever_network");
    let by_power = [
        ("k_in", 1.0),
        ("k_out", 1.0),
        ("k_out_actuated", 1.0),
        ("k_out_blocked", 1.0),
        ("blocked_force", 1.0),
        ("f1", 0.5),
        ("f2", 0.5),
        ("amplification", 0.0),
        ("stroke_in", 0.0),
        ("stroke_out", 0.0),
    ];
    let wanted: Vec<usize> = by_power
        .iter()
        .map(|(n, _)| p.model().output_index(n).unwrap())
        .collect();
    let mut worst = 0.0f64;
    for s in [0.6, 0.93, 1.07, 1.5] {
        let softer = text.replace(stack, &format!("stiffness = \"{} N/um\"", 60.0 / s));
        let q = Problem::parse(Path::new("lever_softer.toml"), &softer).unwrap();
        for x in designs(&p, 8, 5) {
            let (mut scaled, mut plain) = (vec![0.0; wanted.len()], vec![0.0; wanted.len()]);
            scaling(&p).evaluate_scaled(&x, s, &wanted, &mut scaled);
            q.model().evaluate(&x, &wanted, &mut plain);
            for ((a, b), (_, power)) in scaled.iter().zip(&plain).zip(&by_power) {
                worst = worst.max(rel(*a, b * f64::powf(s, *power), 1e-300));
            }
        }
    }
    eprintln!("scaled lever against a softer stack, worst relative difference: {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// Whether `name` is a natural frequency's (`f1`...): its derivatives come from the Rayleigh
/// quotient at the eigenvector found, exact to first order only (the networks' chapter of
/// the guide), so its Hessian is not compared.
fn frequency(name: &str) -> bool {
    name.strip_prefix('f')
        .is_some_and(|i| i.parse::<usize>().is_ok())
}

/// Each output's Hessian over the parameters and the factor against central differences of
/// its exact gradients, steps a millionth of each input's range (the factor's: one); the
/// differences' own error reaches 1.5e-5 of a block's largest entry (the lever's
/// `k_out_blocked`, by its thickness twice).
#[test]
fn the_networks_hessians_are_central_differences_of_their_gradients() {
    let mut worst = 0.0f64;
    for name in ["lever_network", "wei2017_network", "rhombus_network"] {
        let p = load(name);
        let scaled = scaling(&p);
        let all = p.model().available_outputs();
        let outputs = p.model().outputs();
        let (m, n) = (all.len(), p.model().parameters().len() + 1);
        let steps: Vec<f64> = p
            .variables
            .iter()
            .map(|v| 1e-6 * (v.upper - v.lower))
            .chain([1e-6])
            .collect();
        for x in designs(&p, 4, 11) {
            let (mut out, mut jac, mut hess) =
                (vec![0.0; m], vec![0.0; m * n], vec![0.0; m * n * n]);
            scaled.evaluate_with_hessian(&x, &all, &mut out, &mut jac, &mut hess);
            let gradient = |x: &[f64], modulus: f64| {
                let (mut v, mut j) = (vec![0.0; m], vec![0.0; m * n]);
                scaled.evaluate_scaled_with_gradient(x, modulus, &all, &mut v, &mut j);
                j
            };
            for (l, &h) in steps.iter().enumerate() {
                if h == 0.0 {
                    continue;
                }
                let (mut up, mut down) = (x.clone(), x.clone());
                let (mut mu, mut md) = (1.0, 1.0);
                if l + 1 < n {
                    up[l] += h;
                    down[l] -= h;
                } else {
                    mu += h;
                    md -= h;
                }
                let (gu, gd) = (gradient(&up, mu), gradient(&down, md));
                for i in (0..m).filter(|&i| !frequency(&outputs[all[i]].name)) {
                    let block = &hess[i * n * n..(i + 1) * n * n];
                    let scale = block.iter().fold(1e-300f64, |s, v| s.max(v.abs()));
                    for k in 0..n {
                        let fd = (gu[i * n + k] - gd[i * n + k]) / (2.0 * h);
                        worst = worst.max((fd - block[k * n + l]).abs() / scale);
                    }
                }
            }
        }
    }
    eprintln!("Hessians against differences of gradients, worst relative difference: {worst:e}");
    assert!(worst < 1e-4, "{worst:e}");
}
