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
//! The two problems must have the same variables and objective, and the whole problem's
//! constraints must include the relaxation's: the relaxation's end is judged by the whole
//! problem's constraints, and the result always carries them.

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
