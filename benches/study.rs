//! The 300-start study of wei2017: flexopt's SQP against the `slsqp` crate (Kraft's SLSQP)
//! as the peer, from the same starts, with the same exact gradients, on two threads each.
//! Before timing, both are checked to reach the same best objective.

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, Criterion};
use flexopt::optim::multistart::{self, Sampling};
use flexopt::optim::nelder_mead::{self, NelderMeadSettings};
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem;
use flexopt::study::{self, StudyOptions};
use rayon::prelude::*;

#[path = "support/peer.rs"]
mod peer;
use peer::slsqp_solve;

fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

/// The study's 300 starts, as `flexopt run` draws them.
fn study_starts(problem: &Problem, nlp: &DesignNlp) -> Vec<Vec<f64>> {
    let n = nlp.dimension();
    multistart::start_points(
        &vec![0.0; n],
        &vec![1.0; n],
        300,
        problem.search.seed,
        Sampling::Uniform,
    )
}

/// The problem each start is solved in: the study's first stage where the part keeps some
/// of its rules for the end (its clearances, `flexopt::optim::staged`), which is what the
/// solvers are compared on; [`rules`] times the whole study, both stages.
fn relaxed(problem: &Problem) -> DesignNlp<'_> {
    DesignNlp::first_stage(problem).unwrap_or_else(|| DesignNlp::new(problem))
}

/// The SQP settings of the problem file.
fn sqp_settings(problem: &Problem) -> SqpSettings {
    SqpSettings {
        tolerance: problem.search.tolerance,
        max_iterations: problem.search.max_iterations,
        ..SqpSettings::default()
    }
}

fn bench(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let nlp = relaxed(&problem);
    let starts = study_starts(&problem, &nlp);
    let settings = sqp_settings(&problem);
    let pool = pool();
    let flexopt_study = || {
        pool.install(|| {
            starts
                .par_iter()
                .map(|x0| sqp::solve(&nlp, x0, &settings))
                .collect::<Vec<_>>()
        })
    };
    let best_feasible = |runs: &[(f64, f64, usize)]| {
        runs.iter()
            .filter(|s| s.1 <= 1e-8)
            .map(|s| s.0)
            .fold(f64::INFINITY, f64::min)
    };
    let peer_runs = |ftol: f64| {
        pool.install(|| {
            starts
                .par_iter()
                .map(|x0| slsqp_solve(&nlp, x0, ftol))
                .collect::<Vec<_>>()
        })
    };
    // the peer at the loosest tolerance that reaches its best accuracy: a looser one stops
    // short (1e-4 gave a best objective 7.5e-10 off, 1e-6 4e-11), a tighter one only costs
    let tolerances = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12];
    let bests: Vec<f64> = tolerances
        .iter()
        .map(|&t| best_feasible(&peer_runs(t)))
        .collect();
    let floor = bests.iter().copied().fold(f64::INFINITY, f64::min);
    let chosen = tolerances
        .iter()
        .zip(&bests)
        .find(|(_, &b)| (b - floor).abs() <= 1e-12 * floor.abs())
        .map(|(&t, _)| t)
        .unwrap();
    let peer_study = || peer_runs(chosen);

    // accuracy: the best feasible objective of each, against flexopt's KKT-checked one
    let ours = flexopt_study();
    let best_ours = ours
        .iter()
        .filter(|s| s.max_violation <= 1e-8)
        .map(|s| s.objective)
        .fold(f64::INFINITY, f64::min);
    for (t, b) in tolerances.iter().zip(&bests) {
        eprintln!(
            "slsqp at ftol {t:e}: best objective {b:.12}, {:.1e} from flexopt's",
            ((b - best_ours) / best_ours).abs()
        );
    }
    let peer = peer_study();
    let best_peer = best_feasible(&peer);
    let global = |f: f64| (f - best_ours).abs() <= 1e-6 * best_ours.abs();
    eprintln!(
        "best objective: flexopt {best_ours:.12} ({} of 300 in the global optimum), slsqp at ftol {chosen:e} {best_peer:.12} ({} of 300); relative difference {:.1e}",
        ours.iter().filter(|s| s.max_violation <= 1e-8 && global(s.objective)).count(),
        peer.iter().filter(|s| s.1 <= 1e-8 && global(s.0)).count(),
        ((best_peer - best_ours) / best_ours).abs()
    );

    let mut group = c.benchmark_group("wei2017_300_starts");
    group.sample_size(20);
    group.bench_function("flexopt_sqp", |b| b.iter(|| black_box(flexopt_study())));
    group.bench_function("slsqp_crate", |b| b.iter(|| black_box(peer_study())));
    group.finish();
}

/// The same 300-start study with strip hinges (wei2017) and with circular notches
/// (bridge_circular), side by side: what the notches' closed forms cost.
fn hinge_kinds(c: &mut Criterion) {
    let mut group = c.benchmark_group("hinge_kinds_300_starts");
    group.sample_size(20);
    let pool = pool();
    for (name, file) in [
        ("strip", "problems/wei2017.toml"),
        ("circular", "problems/bridge_circular.toml"),
    ] {
        let problem = Problem::load(Path::new(file)).unwrap();
        let nlp = relaxed(&problem);
        let starts = study_starts(&problem, &nlp);
        let settings = sqp_settings(&problem);
        group.bench_function(name, |b| {
            b.iter(|| {
                pool.install(|| {
                    black_box(
                        starts
                            .par_iter()
                            .map(|x0| sqp::solve(&nlp, x0, &settings))
                            .collect::<Vec<_>>(),
                    )
                })
            })
        });
    }
    group.finish();
}

/// The whole 300-start study of wei2017 (`flexopt::study::run`, two threads) with the
/// part's rules enforced (the default: size rules from every start, clearances from each
/// end that breaks one) and with `[part] enforce = false`; and the same for the
/// least-stress variant, whose ends break the clearances most.
fn rules(c: &mut Criterion) {
    let mut group = c.benchmark_group("part_rules_300_starts");
    group.sample_size(10);
    for (name, file) in [
        ("wei2017", "problems/wei2017.toml"),
        ("min_stress", "problems/wei2017_min_stress.toml"),
    ] {
        let text = std::fs::read_to_string(file).unwrap();
        let free = text.replace("[search]", "[part]\nenforce = false\n\n[search]");
        for (rules, text) in [("enforced", text.clone()), ("not_enforced", free)] {
            let problem = Problem::parse(Path::new(file), &text).unwrap();
            let options = StudyOptions {
                threads: 2,
                ..StudyOptions::from_problem(&problem)
            };
            group.bench_function(format!("{name}_{rules}"), |b| {
                b.iter(|| black_box(study::run(&problem, &options).runs.len()))
            });
        }
    }
    group.finish();
}

/// One local solve of each kind, the Nelder-Mead study, and the SQP study on one and two
/// threads.
fn pieces(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let nlp = relaxed(&problem);
    let starts = study_starts(&problem, &nlp);
    let sqp_settings = sqp_settings(&problem);
    let nm_settings = NelderMeadSettings {
        tolerance: problem.search.tolerance,
        ..NelderMeadSettings::default()
    };
    let mut group = c.benchmark_group("wei2017_pieces");
    group.sample_size(20);
    group.bench_function("one_sqp_solve", |b| {
        b.iter(|| sqp::solve(&nlp, black_box(&starts[0]), &sqp_settings))
    });
    group.bench_function("one_nelder_mead_solve", |b| {
        b.iter(|| nelder_mead::solve(&nlp, black_box(&starts[0]), &nm_settings))
    });
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        group.bench_function(format!("sqp_300_starts_{threads}_thread"), |b| {
            b.iter(|| {
                pool.install(|| {
                    starts
                        .par_iter()
                        .map(|x0| sqp::solve(&nlp, x0, &sqp_settings))
                        .collect::<Vec<_>>()
                })
            })
        });
    }
    group.sample_size(10);
    let pool = pool();
    group.bench_function("nelder_mead_300_starts_2_threads", |b| {
        b.iter(|| {
            pool.install(|| {
                starts
                    .par_iter()
                    .map(|x0| nelder_mead::solve(&nlp, x0, &nm_settings))
                    .collect::<Vec<_>>()
            })
        })
    });
    group.finish();
}

/// Medians of this many alternating runs for the tolerance figures.
const TOLERANCE_REPEATS: usize = 5;

/// The tolerance analysis and the robust study of wei2017 against the nominal 300-start
/// study, alternating, on the file's threads (every core): `flexopt tolerance` with 100,000
/// Monte Carlo samples (first order and Monte Carlo, no files), and the robust study for
/// `yield = 0.99`, each as a ratio to the nominal study's median. Writes
/// `results/bench/tolerance.json` and `results/bench/tolerance.txt`.
fn tolerance_ratios() {
    use flexopt::study::{self, StudyOptions};
    use flexopt::tolerance::{analyze, monte_carlo::Settings};
    use std::time::Instant;
    let nominal = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let mut robust = nominal.clone();
    robust.search.robust = Some(flexopt::problem::Robust {
        k_sigma: flexopt::problem::tolerances::normal_quantile(1.0 - 0.01 / 7.0),
        target_yield: Some(0.99),
    });
    let options = StudyOptions::from_problem(&nominal);
    let x = study::run(&nominal, &options).reported_design().to_vec();
    let settings = Settings {
        samples: 100_000,
        seed: nominal.search.seed,
        threads: nominal.search.threads,
    };
    let time = |f: &dyn Fn()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let mut seconds = [Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..TOLERANCE_REPEATS {
        seconds[0].push(time(&|| {
            black_box(study::run(&nominal, &options));
        }));
        seconds[1].push(time(&|| {
            black_box(study::run(&robust, &options));
        }));
        seconds[2].push(time(&|| {
            black_box(
                analyze(&nominal, &x, settings)
                    .unwrap()
                    .monte_carlo
                    .yield_fraction,
            );
        }));
    }
    let median = |v: &[f64]| {
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        s[s.len() / 2]
    };
    let [study_s, robust_s, tolerance_s] = [0, 1, 2].map(|i| median(&seconds[i]));
    let text = format!(
        "wei2017 on {} threads, medians of {TOLERANCE_REPEATS}, alternating\n\
         nominal study (300 starts)        {:>9.4} s\n\
         robust study (yield = 0.99)       {:>9.4} s   {:>6.2} x the nominal study\n\
         tolerance, 100,000 samples        {:>9.4} s   {:>6.2} x the nominal study\n",
        rayon::current_num_threads(),
        study_s,
        robust_s,
        robust_s / study_s,
        tolerance_s,
        tolerance_s / study_s,
    );
    print!("{text}");
    std::fs::create_dir_all("results/bench").unwrap();
    let json = serde_json::json!({
        "repeats": TOLERANCE_REPEATS,
        "nominal_study_seconds": seconds[0],
        "robust_study_seconds": seconds[1],
        "tolerance_100000_seconds": seconds[2],
        "robust_over_nominal": robust_s / study_s,
        "tolerance_over_nominal": tolerance_s / study_s,
    });
    flexopt::report::write_json(Path::new("results/bench/tolerance.json"), &json).unwrap();
    flexopt::report::write_atomic(Path::new("results/bench/tolerance.txt"), text.as_bytes())
        .unwrap();
}

criterion_group!(benches, bench, pieces, hinge_kinds, rules);

fn main() {
    tolerance_ratios();
    benches();
    Criterion::default().configure_from_args().final_summary();
}
