//! Parts that cannot be made under the tolerances: a Monte Carlo sample whose part breaks
//! one of the part's rules is a failed part. The share of them against the rule's
//! first-order probability, the yield that leaves them out, thread-count invariance, and a
//! robust optimum that keeps its binding rule `k` deviations inside, with exact gradients.

use std::path::Path;

use flexopt::model::part_rules::TOLERANCE;
use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::tolerances::{normal_cdf, Input};
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};
use flexopt::tolerance::analyze;
use flexopt::tolerance::monte_carlo::Settings;

fn shipped(name: &str) -> (Problem, Vec<f64>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let file = root.join(format!("problems/{name}.toml"));
    let p = Problem::load(&file).unwrap();
    let optimum: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join(format!("results/{name}/optimum.json"))).unwrap(),
    )
    .unwrap();
    let x = p
        .model()
        .parameters()
        .iter()
        .map(|q| optimum["design_si"][q.name.as_ref()].as_f64().unwrap())
        .collect();
    (p, x)
}

fn settings(samples: usize, threads: usize) -> Settings {
    Settings {
        samples,
        seed: 5,
        threads,
    }
}

/// wei2017_min_stress's optimum stands on `link_width` (the middle link as wide as its
/// thickest hinge): the rule's margin is close to linear in the parameters over a few
/// micrometres, so the share of samples that break it is its first-order probability
/// `Phi(-(m + TOLERANCE) / sigma_m)`, within the Monte Carlo's binomial error.
#[test]
fn the_share_breaking_an_active_rule_is_its_first_order_probability() {
    let (p, x) = shipped("wei2017_min_stress");
    let part = p.mechanism().part_maker.as_deref().unwrap();
    let names: Vec<String> = part.rules().iter().map(|r| r.name.to_string()).collect();
    let k = names.iter().position(|n| n == "link_width").unwrap();
    let (r, n) = (names.len(), x.len());
    let mut margins = vec![0.0; r];
    let mut jacobian = vec![0.0; r * n];
    part.rule_margins_with_gradient(&x, &mut margins, &mut jacobian);
    let variance: f64 = p
        .tolerances
        .iter()
        .filter_map(|t| match t.input {
            Input::Parameter(j) => Some((jacobian[k * n + j] * t.sigma).powi(2)),
            Input::Modulus => None,
        })
        .sum();
    let first_order = normal_cdf(-(margins[k] + TOLERANCE) / variance.sqrt());
    assert!(
        (0.2..0.8).contains(&first_order),
        "the rule is active: {first_order}"
    );
    let samples = 100_000;
    let mc = analyze(&p, &x, settings(samples, 2)).unwrap().monte_carlo;
    let share = mc.rule_breaks[k];
    let binomial = (first_order * (1.0 - first_order) / samples as f64).sqrt();
    assert!(
        (share - first_order).abs() < 4.0 * binomial,
        "link_width broken in {share} of the samples, {first_order} to first order"
    );
    // every sample that breaks a rule is unmakeable, and no other
    let most = mc.rule_breaks.iter().cloned().fold(0.0, f64::max);
    let sum: f64 = mc.rule_breaks.iter().sum();
    assert!(mc.unmakeable >= most && mc.unmakeable <= sum + 1e-12);
    assert_eq!(
        mc.makeable.iter().filter(|&&m| !m).count() as f64 / samples as f64,
        mc.unmakeable
    );
    // the yield counts them as failed: at most the makeable share, and each constraint's
    // own yield (the performance alone) is at least the yield
    assert!(mc.yield_fraction <= 1.0 - mc.unmakeable);
    assert!(mc.constraint_yields.iter().all(|&y| y >= mc.yield_fraction));
    // one thread or two: the same counts
    let one = analyze(&p, &x, settings(samples, 1)).unwrap().monte_carlo;
    assert_eq!(one.unmakeable.to_bits(), mc.unmakeable.to_bits());
    assert_eq!(one.rule_breaks, mc.rule_breaks);
    assert_eq!(one.yield_fraction.to_bits(), mc.yield_fraction.to_bits());
}

/// wei2017's optimum keeps every rule by a tenth of a millimetre or more, tens of the
/// tolerances' standard deviations: every sample can be made.
#[test]
fn a_design_well_inside_its_rules_makes_every_sample() {
    let (p, x) = shipped("wei2017");
    let mc = analyze(&p, &x, settings(20_000, 2)).unwrap().monte_carlo;
    assert!(
        !mc.rule_breaks.is_empty(),
        "wei2017's part states its rules"
    );
    assert_eq!(mc.unmakeable, 0.0);
    assert!(mc.rule_breaks.iter().all(|&f| f == 0.0));
    assert!(mc.makeable.iter().all(|&m| m));
}

/// stack_amplifier.toml robust for a yield of 95 %: `k = 1.96`.
fn robust_stack_amplifier() -> Problem {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("problems/stack_amplifier.toml")).unwrap();
    assert!(text.contains("threads = 0\n"));
    let text = text.replacen(
        "threads = 0\n",
        "threads = 0\nrobust = { yield = 0.95 }\n",
        1,
    );
    Problem::parse(Path::new("stack_amplifier.toml"), &text).unwrap()
}

/// The nominal optimum of stack_amplifier stands on the actuator's room (rule
/// `actuator/c_ul`) and loses half its parts to it. The robust optimum keeps that rule
/// `k` first-order deviations inside, as it keeps its performance limits: `Phi(-k)` of the
/// parts, 2.5 %, cannot be made, by Monte Carlo within its binomial error.
#[test]
fn a_robust_optimum_keeps_its_binding_rule_k_deviations_inside() {
    let p = robust_stack_amplifier();
    let k = p.search.robust.unwrap().k_sigma;
    let s = study::run(&p, &StudyOptions::from_problem(&p));
    assert!(s.any_feasible);
    let x = s.reported_design().to_vec();
    let part = p.mechanism().part_maker.as_deref().unwrap();
    let names: Vec<String> = part.rules().iter().map(|r| r.name.to_string()).collect();
    let (r, n) = (names.len(), x.len());
    let mut margins = vec![0.0; r];
    let mut jacobian = vec![0.0; r * n];
    part.rule_margins_with_gradient(&x, &mut margins, &mut jacobian);
    let mut sigma = vec![0.0; n];
    for t in &p.tolerances {
        if let Input::Parameter(j) = t.input {
            sigma[j] = t.sigma;
        }
    }
    let in_sigma: Vec<f64> = (0..r)
        .map(|i| {
            let s: f64 = (0..n)
                .map(|j| (jacobian[i * n + j] * sigma[j]).powi(2))
                .sum::<f64>()
                .sqrt();
            margins[i] / s
        })
        .collect();
    for (name, m) in names.iter().zip(&in_sigma) {
        assert!(*m >= k * (1.0 - 1e-6), "{name}: {m} deviations inside");
    }
    let room = names.iter().position(|n| n == "actuator/c_ul").unwrap();
    assert!(
        (in_sigma[room] / k - 1.0).abs() < 1e-4,
        "the actuator's room is binding: {} deviations",
        in_sigma[room]
    );
    let samples = 100_000;
    let mc = analyze(&p, &x, settings(samples, 2)).unwrap().monte_carlo;
    let expected = normal_cdf(-k);
    let binomial = (expected * (1.0 - expected) / samples as f64).sqrt();
    assert!(
        (mc.rule_breaks[room] - expected).abs() < 4.0 * binomial,
        "{} of the parts break the actuator's room, {expected} expected",
        mc.rule_breaks[room]
    );
    assert!(
        mc.unmakeable < expected + 4.0 * binomial,
        "{}",
        mc.unmakeable
    );
    assert!(mc.yield_fraction > 0.94, "yield {}", mc.yield_fraction);
}

/// The robust rows of the part's rules (each margin less `k` times its spread, the
/// spread's gradient from the rules' exact Hessians) against central differences, near
/// the robust optimum of stack_amplifier, where its rules are smooth.
#[test]
fn robust_rule_rows_have_exact_gradients() {
    let p = robust_stack_amplifier();
    let s = study::run(&p, &StudyOptions::from_problem(&p));
    let nlp = DesignNlp::new(&p);
    let u0 = nlp.scale(s.reported_design());
    let (m, n) = (nlp.constraint_count(), nlp.dimension());
    let first_rule = p.constraints.len();
    assert!(m > first_rule + 10, "the rules are rows: {m}");
    let (mut c, mut g, mut jac) = (vec![0.0; m], vec![0.0; n], vec![0.0; m * n]);
    let (mut cp, mut cm) = (vec![0.0; m], vec![0.0; m]);
    for t in [0.0, 1e-3, -2e-3] {
        let u: Vec<f64> = u0
            .iter()
            .enumerate()
            .map(|(i, v)| v + t * (i as f64 - 3.0))
            .collect();
        nlp.evaluate_with_gradient(&u, &mut c, &mut g, &mut jac);
        for j in 0..n {
            let h = 1e-7;
            let (mut up, mut um) = (u.clone(), u.clone());
            up[j] += h;
            um[j] -= h;
            nlp.evaluate(&up, &mut cp);
            nlp.evaluate(&um, &mut cm);
            for i in first_rule..m {
                let fd = (cp[i] - cm[i]) / (2.0 * h);
                let exact = jac[i * n + j];
                assert!(
                    (fd - exact).abs() <= 1e-5 * exact.abs().max(1.0),
                    "row {i}, variable {j} at {t}: {exact} exact, {fd} by differences"
                );
            }
        }
    }
}
