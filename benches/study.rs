//! The 300-start study of wei2017: flexopt's SQP against the `slsqp` crate (Kraft's SLSQP)
//! as the peer, from the same starts, with the same exact gradients, on two threads each.
//! Before timing, both are checked to reach the same best objective.

use std::cell::RefCell;
use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use flexopt::optim::multistart::{self, Sampling};
use flexopt::optim::sqp::{self, SqpSettings};
use flexopt::optim::Problem as _;
use flexopt::problem::nlp::DesignNlp;
use flexopt::problem::Problem;
use rayon::prelude::*;

/// The last evaluation of the problem, so that the peer's separate objective and
/// constraint callbacks cost one model evaluation per point, as flexopt's do.
#[derive(Default)]
struct Cache {
    x: Vec<f64>,
    f: f64,
    c: Vec<f64>,
    g: Vec<f64>,
    jac: Vec<f64>,
}

fn cached<'a>(
    nlp: &'a DesignNlp,
    cache: &'a RefCell<Cache>,
    x: &[f64],
) -> std::cell::RefMut<'a, Cache> {
    let mut c = cache.borrow_mut();
    if c.x != x {
        let (n, m) = (nlp.dimension(), nlp.constraint_count());
        c.c.resize(m, 0.0);
        c.g.resize(n, 0.0);
        c.jac.resize(m * n, 0.0);
        let Cache { c: cv, g, jac, .. } = &mut *c;
        let f = nlp.evaluate_with_gradient(x, cv, g, jac);
        c.f = f;
        c.x = x.to_vec();
    }
    c
}

/// A callback of the peer: value, and gradient when asked.
type PeerCallback<'a> = dyn Fn(&[f64], Option<&mut [f64]>, &mut ()) -> f64 + 'a;

/// One SLSQP solve; returns the objective and the largest constraint violation.
fn slsqp_solve(nlp: &DesignNlp, x0: &[f64], ftol: f64) -> (f64, f64) {
    let n = nlp.dimension();
    let m = nlp.constraint_count();
    let cache = RefCell::new(Cache::default());
    let objective = |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
        let c = cached(nlp, &cache, x);
        if let Some(g) = grad {
            g.copy_from_slice(&c.g);
        }
        c.f
    };
    // flexopt's constraints are c >= 0; the peer's are c <= 0
    let constraints: Vec<Box<PeerCallback>> = (0..m)
        .map(|i| {
            let cache = &cache;
            Box::new(move |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
                let c = cached(nlp, cache, x);
                if let Some(g) = grad {
                    for (gj, jac) in g.iter_mut().zip(&c.jac[i * n..(i + 1) * n]) {
                        *gj = -jac;
                    }
                }
                -c.c[i]
            }) as Box<PeerCallback>
        })
        .collect();
    let refs: Vec<&PeerCallback> = constraints.iter().map(|c| c.as_ref()).collect();
    let tol = slsqp::StopTols {
        ftol_rel: ftol,
        ..slsqp::StopTols::default()
    };
    let (x, f) = match slsqp::minimize(
        objective,
        x0,
        &vec![(0.0, 1.0); n],
        &refs,
        (),
        2000,
        Some(tol),
    ) {
        Ok((_, x, f)) | Err((_, x, f)) => (x, f),
    };
    let mut c = vec![0.0; m];
    let f_check = nlp.evaluate(&x, &mut c);
    let violation = c.iter().fold(0.0f64, |v, ci| v.max(-ci));
    (if f.is_finite() { f_check } else { f64::NAN }, violation)
}

fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

fn bench(c: &mut Criterion) {
    let problem = Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let nlp = DesignNlp::new(&problem);
    let n = nlp.dimension();
    let starts = multistart::start_points(
        &vec![0.0; n],
        &vec![1.0; n],
        300,
        problem.search.seed,
        Sampling::Uniform,
    );
    let settings = SqpSettings {
        tolerance: problem.search.tolerance,
        max_iterations: problem.search.max_iterations,
    };
    let pool = pool();
    let flexopt_study = || {
        pool.install(|| {
            starts
                .par_iter()
                .map(|x0| sqp::solve(&nlp, x0, &settings))
                .collect::<Vec<_>>()
        })
    };
    let peer_ftol = 1e-14;
    let peer_study = || {
        pool.install(|| {
            starts
                .par_iter()
                .map(|x0| slsqp_solve(&nlp, x0, peer_ftol))
                .collect::<Vec<_>>()
        })
    };

    // accuracy first: the best feasible objective of each, against flexopt's KKT-checked one
    let ours = flexopt_study();
    let best_ours = ours
        .iter()
        .filter(|s| s.max_violation <= 1e-8)
        .map(|s| s.objective)
        .fold(f64::INFINITY, f64::min);
    let peer = peer_study();
    let best_peer = peer
        .iter()
        .filter(|s| s.1 <= 1e-8)
        .map(|s| s.0)
        .fold(f64::INFINITY, f64::min);
    let global = |f: f64| (f - best_ours).abs() <= 1e-6 * best_ours.abs();
    eprintln!(
        "best objective: flexopt {best_ours:.12} ({} of 300 in the global optimum), slsqp {best_peer:.12} ({} of 300); relative difference {:.1e}",
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

criterion_group!(benches, bench);
criterion_main!(benches);
