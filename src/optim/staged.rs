//! A solve in two stages: a start solved first in a relaxation of the problem (some of its
//! constraints left out), then, where that end breaks a constraint left out, in the whole
//! problem from there. Constraints that are costly, or kinked and inconsistent far from
//! where they hold, need then only be met near an end the relaxation has found, which is
//! where they hold or nearly. A start the relaxation does not end feasibly is not taken
//! further: the whole problem, stricter, would not either.
//!
//! The two problems must have the same variables and objective, and the whole problem's
//! constraints must include the relaxation's: the relaxation's end is judged by the whole
//! problem's constraints, and the result always carries them.

use super::problem::{max_violation, Problem, Solution, Status};

/// The solution of `whole` from `x0`: `relaxed`, the relaxation solved from `x0` (itself
/// in stages, where it has its own relaxation), then, where its end meets the relaxation's
/// constraints within `tolerance` but not `whole`'s, `solve` on `whole` from that end. The
/// iterations and evaluations of both stages are counted.
pub fn solve<R, S>(
    whole: &dyn Problem,
    x0: &[f64],
    tolerance: f64,
    relaxed: R,
    solve: S,
) -> Solution
where
    R: FnOnce(&[f64]) -> Solution,
    S: FnOnce(&dyn Problem, &[f64]) -> Solution,
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
    let mut s = solve(whole, &relaxed.x);
    if let Status::Failed(reason) = &s.status {
        s.status = Status::Failed(format!(
            "from the end of the relaxed problem, the whole one: {reason}"
        ));
    }
    s.iterations += relaxed.iterations;
    s.evaluations += relaxed.evaluations + 1;
    s
}
