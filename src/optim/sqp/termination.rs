//! When the SQP stops: the KKT residual of the iterate with the QP's multipliers.

use super::subproblem::Step;
use super::{Iterate, Shape};
use crate::optim::dense::{inf_norm, max_violation};

/// Variables up to which the residual's scratch is on the stack.
const MAX_STACK: usize = 32;

/// The largest of: stationarity `|grad f - J^T lambda - nu|` scaled by `max(1, |grad f|)`;
/// complementarity of the constraints and the bounds scaled by `max(1, |multipliers|)`; and
/// the constraint violation. The multipliers are the QP's at `x`, so that the measure needs
/// no guess of which bounds are active.
pub(super) fn kkt_residual(shape: &Shape, point: &Iterate, step: &Step) -> f64 {
    let Shape {
        n,
        m,
        meq,
        lower,
        upper,
    } = *shape;
    let (lambda, nu) = (&step.lambda, &step.nu);
    // the rows with a multiplier only, each read along its length: an inactive row's
    // product is a zero, and subtracting it leaves each sum as it was (its sign of zero
    // aside, which the absolute value drops); each component still subtracts its rows in
    // the same order, so the residual is the same number. The rules' rows doubled wei2017's
    // rows and with them this test's cost, though few are active at once.
    let mut r = [0.0; MAX_STACK];
    let mut heap = Vec::new();
    let r: &mut [f64] = if n <= MAX_STACK {
        &mut r[..n]
    } else {
        heap.resize(n, 0.0);
        &mut heap
    };
    for ((rj, &gj), &nuj) in r.iter_mut().zip(&point.g).zip(nu) {
        *rj = gj - nuj;
    }
    for (row, &l) in point.jac.chunks_exact(n).zip(lambda) {
        if l != 0.0 {
            for (rj, &d) in r.iter_mut().zip(row) {
                *rj -= l * d;
            }
        }
    }
    let stat = r.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    let stat = stat / inf_norm(&point.g).max(1.0);
    let mscale = inf_norm(lambda).max(inf_norm(nu)).max(1.0);
    let mut compl: f64 = (meq..m)
        .map(|i| (lambda[i] * point.c[i]).abs())
        .fold(0.0, f64::max);
    for j in 0..n {
        let gap = if nu[j] > 0.0 {
            point.x[j] - lower[j]
        } else {
            upper[j] - point.x[j]
        };
        if nu[j] != 0.0 {
            compl = compl.max(nu[j].abs() * gap);
        }
    }
    stat.max(compl / mscale).max(max_violation(&point.c, meq))
}
