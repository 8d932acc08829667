//! When the SQP stops: the KKT residual of the iterate with the QP's multipliers.

use super::subproblem::Step;
use super::{Iterate, Shape};
use crate::optim::dense::{inf_norm, max_violation};

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
    let mut stat: f64 = 0.0;
    for (j, (&gj, &nuj)) in point.g.iter().zip(nu).enumerate() {
        let mut r = gj - nuj;
        for (i, &l) in lambda.iter().enumerate() {
            r -= l * point.jac[i * n + j];
        }
        stat = stat.max(r.abs());
    }
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
