//! A solve in two stages: a start solved first in a relaxation of the problem (some of its
//! constraints left out), then, where that end breaks a constraint left out, in the whole
//! problem from there. Constraints that are costly, or kinked and inconsistent far from
//! where they hold, need then only be met near an end the relaxation has found, which is
//! where they hold or nearly. A start the relaxation does not end feasibly is not taken
//! further: the whole problem, stricter, would not either.
//!
//! Where the relaxation's end breaks a constraint left out, `alternative` may offer another
//! point of the same worth (the caller's: the same design reflected, for a model whose
//! mirror image has the same outputs): where it meets the whole problem's constraints and
//! has the same objective, it is taken as the end with no second stage. The relaxation's
//! stationarity holds there as at the end it reflects, and the constraints left out are
//! met, so it is a KKT point of the whole problem too.
//!
//! A caller solving many starts may share the whole problem's solves between the starts
//! whose relaxations end at one point ([`HandOvers`]).
//!
//! The two problems must have the same variables and objective, and the whole problem's
//! constraints must include the relaxation's: the relaxation's end is judged by the whole
//! problem's constraints, and the result always carries them.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use super::problem::{max_violation, Problem, Solution, Status};

/// The solution of `whole` from `x0`: `relaxed`, the relaxation solved from `x0` (itself
/// in stages, where it has its own relaxation), then, where its end meets the relaxation's
/// constraints within `tolerance` but not `whole`'s, `alternative`'s point for that end
/// where it meets them all with the same objective (relative `1e-12`), else `solve` on
/// `whole` from that end. The iterations and evaluations of both stages are counted.
pub fn solve<R, S, A>(
    whole: &dyn Problem,
    x0: &[f64],
    tolerance: f64,
    relaxed: R,
    solve: S,
    alternative: A,
) -> Solution
where
    R: FnOnce(&[f64]) -> Solution,
    S: FnOnce(&dyn Problem, &[f64]) -> Solution,
    A: FnOnce(&[f64]) -> Option<Vec<f64>>,
{
    let relaxed = relaxed(x0);
    let mut c = vec![0.0; whole.constraint_count()];
    let objective = whole.evaluate(&relaxed.x, &mut c);
    let violation = max_violation(&c, whole.equality_count());
    let ended_feasibly = relaxed.max_violation <= tolerance
        && !matches!(relaxed.status, Status::Failed(_) | Status::Infeasible);
    if violation <= tolerance || !ended_feasibly || !violation.is_finite() {
        return Solution {
            objective,
            constraints: c,
            max_violation: violation,
            evaluations: relaxed.evaluations + 1,
            ..relaxed
        };
    }
    let mut evaluations = relaxed.evaluations + 1;
    if let Some(y) = alternative(&relaxed.x) {
        evaluations += 1;
        let mut cy = vec![0.0; whole.constraint_count()];
        let fy = whole.evaluate(&y, &mut cy);
        let same = (fy - objective).abs() <= 1e-12 * objective.abs().max(1e-300);
        let violation = max_violation(&cy, whole.equality_count());
        if same && violation <= tolerance {
            return Solution {
                x: y,
                objective: fy,
                constraints: cy,
                max_violation: violation,
                evaluations,
                ..relaxed
            };
        }
    }
    let mut s = solve(whole, &relaxed.x);
    if let Status::Failed(reason) = &s.status {
        s.status = Status::Failed(format!(
            "from the end of the relaxed problem, the whole one: {reason}"
        ));
    }
    s.iterations += relaxed.iterations;
    s.evaluations += evaluations;
    s
}

/// The whole problem's solves from the relaxation's ends, shared by the starts of a study.
///
/// Many starts end their relaxation at the same local optimum (wei2017: 79 of the 300
/// starts end at one optimum of the relaxation, its four images under the model's
/// symmetries, that breaks a clearance; wei2017_min_stress: 300 ends at some 30 optima), to
/// within the relaxation's tolerance, and each then went on alone from its own end, an
/// SQP's path from nearly the same point. Each end is now rounded to a grid of
/// [`GRID`] of its variable's range (of its size, rounded down to a power of two, where
/// the variable is unbounded), and the whole problem solved from the rounded point: ends
/// that round alike hand over the same point, and its solve, a function of that point
/// alone, is done once and its solution shared. Whichever thread solves it first, every
/// start gets the same solution, and with it the same iteration and evaluation counts, so
/// that a study's results do not depend on its threads.
#[derive(Default)]
pub struct HandOvers {
    solved: Mutex<HashMap<Vec<u64>, Arc<OnceLock<Solution>>>>,
}

/// The hand-over grid's spacing relative to a variable's range: fine beside the distances
/// a second stage moves (tenths of the range, where a constraint left out is broken), and
/// coarse beside the spread of a relaxation's ends at one optimum (1e-8 in wei2017's).
pub const GRID: f64 = 1.0 / (1u64 << 20) as f64;

impl HandOvers {
    pub fn new() -> Self {
        Self::default()
    }

    /// `solve` from `x` rounded to the grid within the bounds `lower`, `upper`; a solve from
    /// the same rounded point, done before or under way on another thread, is taken as it
    /// is.
    pub fn solve(
        &self,
        x: &[f64],
        lower: &[f64],
        upper: &[f64],
        solve: impl FnOnce(&[f64]) -> Solution,
    ) -> Solution {
        let y = round_to_grid(x, lower, upper);
        let key: Vec<u64> = y.iter().map(|v| v.to_bits()).collect();
        let cell = {
            let mut solved = self.solved.lock().unwrap_or_else(|e| e.into_inner());
            Arc::clone(solved.entry(key).or_default())
        };
        cell.get_or_init(|| solve(&y)).clone()
    }
}

/// `x` rounded to a grid of [`GRID`] of each variable's range (of its size, a power of two
/// at least 1, where the range is not finite), kept within the bounds.
fn round_to_grid(x: &[f64], lower: &[f64], upper: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(lower.iter().zip(upper))
        .map(|(&v, (&lo, &hi))| {
            let size = if (hi - lo).is_finite() {
                hi - lo
            } else {
                v.abs().max(1.0).log2().floor().exp2()
            };
            let q = GRID * size;
            if q > 0.0 && v.is_finite() {
                ((v / q).round() * q).clamp(lo, hi)
            } else {
                v
            }
        })
        .collect()
}
