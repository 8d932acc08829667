//! The objective scaled so that its gradient at the start is at most [`MAX_GRADIENT`] in
//! size (the gradient-based scaling of A. Wächter and L. T. Biegler, "On the implementation
//! of an interior-point filter line-search algorithm for large-scale nonlinear
//! programming", Mathematical Programming 106 (2006) 25-57, Sec. 3.8).
//!
//! The SQP's quadratic model starts (and restarts) as the identity, and the elastic QP
//! prices its slack at a multiple of the gradient: with a stress objective in pascals
//! (gradients of 3e7), the identity's unconstrained step was 3e7 long and the elastic QP's
//! slack sat at -3e11 before the dual method moved it back, losing the digits that the
//! constraints' own values (of order 1 to 10) needed.
//!
//! The bound is 1e4 rather than Wächter and Biegler's 100, measured on the 300 starts of
//! wei2017_min_stress (one thread): unscaled, 225 starts converge in 0.53 s; bounded at
//! 1e4, 222 in 0.34 s; at 100, 200 in 0.39 s; at 1, 170. wei2017 (gradients below 1e3) is
//! not scaled.

use crate::optim::dense::inf_norm;
use crate::optim::Problem;

/// The largest objective gradient the SQP sees at its start.
pub(super) const MAX_GRADIENT: f64 = 1e4;

/// `problem` with its objective multiplied by `scale` (1 until the start is evaluated).
pub(super) struct ScaledObjective<'p> {
    pub problem: &'p dyn Problem,
    pub scale: f64,
}

/// The factor that brings an objective gradient `g` (the start's) down to
/// [`MAX_GRADIENT`]; 1 where it is already below.
pub(super) fn objective_scale(g: &[f64]) -> f64 {
    let size = inf_norm(g);
    if size > MAX_GRADIENT {
        MAX_GRADIENT / size
    } else {
        1.0
    }
}

impl ScaledObjective<'_> {
    /// The objective `f` and its `gradient` (in place) scaled.
    fn scaled(&self, f: f64, gradient: &mut [f64]) -> f64 {
        for g in gradient.iter_mut() {
            *g *= self.scale;
        }
        self.scale * f
    }
}

impl Problem for ScaledObjective<'_> {
    fn dimension(&self) -> usize {
        self.problem.dimension()
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        self.problem.bounds()
    }

    fn equality_count(&self) -> usize {
        self.problem.equality_count()
    }

    fn constraint_count(&self) -> usize {
        self.problem.constraint_count()
    }

    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64 {
        self.scale * self.problem.evaluate(x, c)
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let f = self
            .problem
            .evaluate_with_gradient(x, c, gradient, jacobian);
        self.scaled(f, gradient)
    }

    fn evaluate_with_gradient_of(
        &self,
        x: &[f64],
        needed: &[bool],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let f = self
            .problem
            .evaluate_with_gradient_of(x, needed, c, gradient, jacobian);
        self.scaled(f, gradient)
    }
}
