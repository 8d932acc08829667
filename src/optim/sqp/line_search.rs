//! The line search of the SQP: backtracking along the QP step on the l1 exact-penalty merit
//! function `phi(x) = f(x) + sum_i mu_i viol_i(x)`, with one second-order correction of a
//! rejected full step against the Maratos effect (Nocedal and Wright, Sec. 15.5 and 18.3).

use super::subproblem::{QpKind, Step};
use super::{Iterate, Sqp};
use crate::optim::dense::{dot, inf_norm, violation_l1, weighted_violation};

/// The shortest backtracked step tried, relative to the size of the iterate.
const MIN_STEP: f64 = 1e-10;

/// How a line search ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Outcome {
    /// The trial point at this step length (1 for a full or corrected step) is the new
    /// iterate, and the model has been updated.
    Accepted { alpha: f64 },
    /// No step length decreased the merit function enough.
    NoDecrease,
}

/// The line search's own arrays: the trial point, the step saved while a correction is
/// tried, and the correction's shifted constraint values.
pub(super) struct LineSearch {
    pub trial: Iterate,
    saved: Step,
    shifted: Vec<f64>,
}

impl LineSearch {
    pub fn new(n: usize, m: usize) -> Self {
        LineSearch {
            trial: Iterate::new(&vec![0.0; n], m),
            saved: Step::new(n, m),
            shifted: vec![0.0; m],
        }
    }
}

/// Backtracks along the step of `sqp` (from the elastic QP where `elastic`) with penalty
/// weights `mu`; on acceptance the trial point becomes the iterate and the BFGS update is
/// made.
pub(super) fn search(sqp: &mut Sqp, mu: &[f64], elastic: bool) -> Outcome {
    let meq = sqp.shape.meq;
    let viol = weighted_violation(&sqp.point.c, meq, mu);
    let phi = sqp.point.f + viol;
    let slope = (dot(&sqp.point.g, &sqp.step.d) - viol).min(0.0);
    // Armijo, with room for the rounding of phi itself: near a solution the predicted
    // decrease falls below what phi can resolve, and the full steps of the local
    // (superlinear) convergence must not be cut on noise
    let noise = 100.0 * f64::EPSILON * phi.abs().max(1.0);
    let accept_at = |phit: f64, alpha: f64| phit <= phi + 1e-4 * alpha * slope + noise;
    let step_size = inf_norm(&sqp.step.d);
    let x_size = 1.0 + inf_norm(&sqp.point.x);
    let mut alpha = 1.0;
    for k in 0..40 {
        set_trial(sqp, alpha);
        if !evaluate_trial_values(sqp) {
            alpha *= 0.25;
            continue;
        }
        let trial = &sqp.line_search.trial;
        let phit = trial.f + weighted_violation(&trial.c, meq, mu);
        if accept_at(phit, alpha) {
            if !evaluate_trial(sqp) {
                alpha *= 0.25;
                continue;
            }
            accept(sqp);
            return Outcome::Accepted { alpha };
        }
        if k == 0 && second_order_correction(sqp) {
            let trial = &sqp.line_search.trial;
            let phis = trial.f + weighted_violation(&trial.c, meq, mu);
            if accept_at(phis, 1.0) && evaluate_trial(sqp) {
                accept(sqp);
                return Outcome::Accepted { alpha: 1.0 };
            }
            restore_step(sqp);
        }
        // minimizer of the quadratic through phi(0), phi'(0) and phi(alpha), safeguarded
        let curvature = 2.0 * (phit - phi - slope * alpha);
        let next = if curvature > 0.0 {
            -slope * alpha * alpha / curvature
        } else {
            0.5 * alpha
        };
        alpha = next.clamp(0.1 * alpha, 0.5 * alpha);
        // an elastic step this short does not move the design: were it accepted, it would be
        // on the merit function's rounding alone, and the solver would stay where it is
        // (measured: 330 evaluations per start stuck at a kink of a clearance's violation).
        // The plain QP's short steps are kept: near a solution they still make progress.
        if elastic && alpha * step_size <= MIN_STEP * x_size {
            break;
        }
    }
    Outcome::NoDecrease
}

/// Replaces the rejected full step `d` by the solution of the QP whose constraints are
/// shifted by the curvature seen at `x + d`: `c(x+d) - J d + J d' >= 0`. Leaves the
/// corrected trial point evaluated; false (with the step restored) if the correction failed.
fn second_order_correction(sqp: &mut Sqp) -> bool {
    let meq = sqp.shape.meq;
    if violation_l1(&sqp.line_search.trial.c, meq) <= 0.5 * violation_l1(&sqp.point.c, meq) {
        return false;
    }
    let ls = &mut sqp.line_search;
    ls.saved.d.copy_from_slice(&sqp.step.d);
    ls.saved.lambda.copy_from_slice(&sqp.step.lambda);
    let n = sqp.shape.n;
    for i in 0..sqp.shape.m {
        ls.shifted[i] = ls.trial.c[i] - dot(&sqp.point.jac[i * n..(i + 1) * n], &ls.saved.d);
    }
    let kind = sqp.subproblem.solve(
        &sqp.shape,
        &sqp.point,
        &sqp.line_search.shifted,
        &mut sqp.curvature,
        &mut sqp.step,
    );
    if kind != Some(QpKind::Regular) {
        restore_step(sqp);
        return false;
    }
    set_trial(sqp, 1.0);
    if evaluate_trial_values(sqp) {
        return true;
    }
    restore_step(sqp);
    false
}

/// The step and multipliers as they were before a correction was tried.
fn restore_step(sqp: &mut Sqp) {
    sqp.step.d.copy_from_slice(&sqp.line_search.saved.d);
    sqp.step
        .lambda
        .copy_from_slice(&sqp.line_search.saved.lambda);
}

/// `x + alpha d`, kept inside the bounds.
fn set_trial(sqp: &mut Sqp, alpha: f64) {
    let (lower, upper) = (sqp.shape.lower, sqp.shape.upper);
    let trial = &mut sqp.line_search.trial.x;
    for j in 0..sqp.shape.n {
        trial[j] = (sqp.point.x[j] + alpha * sqp.step.d[j]).clamp(lower[j], upper[j]);
    }
}

fn evaluate_trial_values(sqp: &mut Sqp) -> bool {
    sqp.evaluations += 1;
    sqp.line_search.trial.evaluate_values(&sqp.problem)
}

/// The trial point with gradients, once it is accepted.
fn evaluate_trial(sqp: &mut Sqp) -> bool {
    sqp.evaluations += 1;
    sqp.line_search.trial.evaluate(&sqp.problem)
}

/// Moves to the trial point, updating the model.
fn accept(sqp: &mut Sqp) {
    sqp.curvature
        .update(&sqp.point, &sqp.line_search.trial, &sqp.step.lambda);
    std::mem::swap(&mut sqp.point, &mut sqp.line_search.trial);
}
