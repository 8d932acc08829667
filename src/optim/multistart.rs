//! Multistart: many local solves from seeded start points, in parallel.
//!
//! Start `i` draws from its own random stream (ChaCha8 seeded with the run's seed, stream
//! `i`), and every solve is a pure function of its start, so the results are the same
//! whatever the number of threads and whatever order the solves finish in.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

use super::problem::{Problem, Solution};
use super::progress::Progress;

/// How start points fill the sampling box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sampling {
    /// Independent uniform points.
    Uniform,
    /// Latin hypercube: each variable's range cut into `count` equal strata, each stratum
    /// used by exactly one start.
    LatinHypercube,
}

/// `count` start points in the box `[lower, upper]` (finite bounds).
pub fn start_points(
    lower: &[f64],
    upper: &[f64],
    count: usize,
    seed: u64,
    sampling: Sampling,
) -> Vec<Vec<f64>> {
    let n = lower.len();
    // the strata of a Latin hypercube: one permutation per variable, from stream 2^63
    let strata: Vec<Vec<usize>> = match sampling {
        Sampling::Uniform => Vec::new(),
        Sampling::LatinHypercube => {
            let mut rng = stream(seed, 1 << 63);
            (0..n)
                .map(|_| {
                    let mut p: Vec<usize> = (0..count).collect();
                    for i in (1..count).rev() {
                        p.swap(i, rng.random_range(0..=i));
                    }
                    p
                })
                .collect()
        }
    };
    (0..count)
        .map(|i| {
            let mut rng = stream(seed, i as u64);
            (0..n)
                .map(|j| {
                    let u: f64 = rng.random();
                    let t = match sampling {
                        Sampling::Uniform => u,
                        Sampling::LatinHypercube => (strata[j][i] as f64 + u) / count as f64,
                    };
                    lower[j] + (upper[j] - lower[j]) * t
                })
                .collect()
        })
        .collect()
}

fn stream(seed: u64, index: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    rng
}

/// Solves `problem` from every start with `solve`, on `threads` threads (0: all cores),
/// keeping every result in the order of the starts, each reported to `progress`.
pub fn run<S>(
    problem: &dyn Problem,
    starts: &[Vec<f64>],
    solve: S,
    threads: usize,
    progress: Option<&Progress>,
) -> Vec<Solution>
where
    S: Fn(&dyn Problem, &[f64]) -> Solution + Sync,
{
    let never = AtomicBool::new(false);
    run_until(problem, starts, solve, threads, progress, &never)
        .into_iter()
        .flatten()
        .collect()
}

/// As [`run`], but a start not begun when `stop` is set is skipped: its entry is `None`.
/// Solves under way finish.
pub fn run_until<S>(
    problem: &dyn Problem,
    starts: &[Vec<f64>],
    solve: S,
    threads: usize,
    progress: Option<&Progress>,
    stop: &AtomicBool,
) -> Vec<Option<Solution>>
where
    S: Fn(&dyn Problem, &[f64]) -> Solution + Sync,
{
    let work = || {
        // every start a task of its own that an idle thread can take: rayon's adaptive
        // split (`bridge_producer_consumer`, its splits as many as the threads, halved at each
        // level unless stolen) leaves runs of starts solved in turn (75 of 300 on two
        // threads) that no other thread can share once begun, and a study whose starts
        // differ in cost (a second stage solved for many) ended with one thread idle beside
        // the other's last run (wei2017 with its part's rules, two threads: 25.8 -> 24.8 ms;
        // a task's cost, well under a microsecond, beside a start's 0.1 ms or more)
        starts
            .par_iter()
            .with_max_len(1)
            .map(|x0| {
                if stop.load(Ordering::Relaxed) {
                    return None;
                }
                let s = solve(problem, x0);
                if let Some(p) = progress {
                    p.record(&s);
                }
                Some(s)
            })
            .collect::<Vec<_>>()
    };
    let results = match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    };
    if let Some(p) = progress {
        p.finish();
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latin_hypercube_uses_every_stratum_once() {
        let pts = start_points(&[0.0, -1.0], &[1.0, 1.0], 50, 3, Sampling::LatinHypercube);
        for j in 0..2 {
            let (lo, hi) = ([0.0, -1.0][j], [1.0, 1.0][j]);
            let mut seen = [false; 50];
            for p in &pts {
                let k = (((p[j] - lo) / (hi - lo)) * 50.0).floor() as usize;
                assert!(!seen[k], "stratum {k} of variable {j} used twice");
                seen[k] = true;
            }
        }
    }

    #[test]
    fn start_points_depend_on_the_seed_only() {
        let a = start_points(&[0.0; 3], &[1.0; 3], 20, 9, Sampling::Uniform);
        let b = start_points(&[0.0; 3], &[1.0; 3], 20, 9, Sampling::Uniform);
        let c = start_points(&[0.0; 3], &[1.0; 3], 20, 10, Sampling::Uniform);
        assert_eq!(a, b);
        assert_ne!(a, c);
        // the first starts do not change when more are asked for
        let d = start_points(&[0.0; 3], &[1.0; 3], 40, 9, Sampling::Uniform);
        assert_eq!(a[..], d[..20]);
    }
}
