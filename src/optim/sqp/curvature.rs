//! The quadratic model of the SQP: `B`, an approximation of the Hessian of the Lagrangian
//! kept positive definite (damped BFGS updates, Nocedal and Wright Procedure 18.2, and a
//! periodic refresh from differences of exact gradients, [`crate::optim::hessian`]), and
//! the limit on the next step that says how far the model was last seen to hold.

use super::{Iterate, Shape};
use crate::optim::dense::dot;
use crate::optim::hessian;
use crate::optim::Problem;

/// After a step cut to `alpha` of a QP step of size `|d|`, the next QP step is limited to
/// this times `alpha |d|` ([`Curvature::limit_next_step`]).
const STEP_LIMIT_RATIO: f64 = 4.0;

pub(super) struct Curvature {
    n: usize,
    /// `B`, row-major.
    b: Vec<f64>,
    /// The largest step component the next QP may take (infinite: no limit).
    step_limit: f64,
    /// The BFGS pair and `B s`.
    s: Vec<f64>,
    y: Vec<f64>,
    bs: Vec<f64>,
    /// The refresh's difference Hessian and its eigenvector scratch, the variables inside
    /// their bounds, and the Lagrangian's gradients at the iterate and a shifted point.
    h: Vec<f64>,
    eigen: Vec<f64>,
    free: Vec<usize>,
    lagrangian: Vec<f64>,
    lagrangian_shifted: Vec<f64>,
    /// The rows with a multiplier: the only ones the refresh reads.
    needed: Vec<bool>,
}

impl Curvature {
    pub fn new(n: usize) -> Self {
        Curvature {
            n,
            b: identity(n),
            step_limit: f64::INFINITY,
            s: vec![0.0; n],
            y: vec![0.0; n],
            bs: vec![0.0; n],
            h: vec![0.0; n * n],
            eigen: vec![0.0; n * n],
            free: Vec::with_capacity(n),
            lagrangian: vec![0.0; n],
            lagrangian_shifted: vec![0.0; n],
            needed: Vec::new(),
        }
    }

    /// `B`, row-major.
    pub fn matrix(&self) -> &[f64] {
        &self.b
    }

    pub fn step_limit(&self) -> f64 {
        self.step_limit
    }

    pub fn is_identity(&self) -> bool {
        let n = self.n;
        (0..n * n).all(|k| self.b[k] == if k / n == k % n { 1.0 } else { 0.0 })
    }

    /// Starts the model afresh, and with it the step limit, which was set from steps of
    /// the old model.
    pub fn reset(&mut self) {
        self.b = identity(self.n);
        self.step_limit = f64::INFINITY;
    }

    /// The damped BFGS update for the move from `from` to `to` with the multipliers
    /// `lambda`: `s = x+ - x`, `y = grad L(x+) - grad L(x)`, `L = f - lambda^T c`; Powell's
    /// damping keeps `B` positive definite.
    pub fn update(&mut self, from: &Iterate, to: &Iterate, lambda: &[f64]) {
        let n = self.n;
        let (s, y, bs) = (&mut self.s, &mut self.y, &mut self.bs);
        for j in 0..n {
            s[j] = to.x[j] - from.x[j];
            y[j] = to.g[j] - from.g[j];
        }
        // the rows with a multiplier only (an inactive row's term is a zero), each component
        // subtracting them in the same order as before: the same numbers
        let rows = to.jac.chunks_exact(n).zip(from.jac.chunks_exact(n));
        for ((to_row, from_row), &l) in rows.zip(lambda) {
            if l != 0.0 {
                for ((yj, t), f) in y.iter_mut().zip(to_row).zip(from_row) {
                    *yj -= l * (t - f);
                }
            }
        }
        for (bi, row) in bs.iter_mut().zip(self.b.chunks_exact(n)) {
            *bi = dot(row, s);
        }
        let sbs = dot(s, bs);
        let sy = dot(s, y);
        if sbs > 1e-300 && s.iter().any(|&v| v != 0.0) {
            if sy < 0.2 * sbs {
                let theta = 0.8 * sbs / (sbs - sy);
                for j in 0..n {
                    y[j] = theta * y[j] + (1.0 - theta) * bs[j];
                }
            }
            let sy = dot(s, y);
            if sy > 0.0 {
                let (isy, isbs) = (1.0 / sy, 1.0 / sbs);
                for i in 0..n {
                    for j in 0..n {
                        self.b[i * n + j] += y[i] * y[j] * isy - bs[i] * bs[j] * isbs;
                    }
                }
            }
        }
    }

    /// `B <- |H|`, `H` the Hessian of the Lagrangian at `point` with the multipliers
    /// `lambda`, by forward differences of the exact gradients (backward at an upper bound),
    /// each shifted point evaluated in `probe`. Leaves `B` as it was where a difference
    /// cannot be evaluated. Returns the number of evaluations.
    pub fn refresh(
        &mut self,
        problem: &dyn Problem,
        shape: &Shape,
        point: &Iterate,
        lambda: &[f64],
        probe: &mut Iterate,
    ) -> usize {
        let n = self.n;
        let x = &point.x;
        // only the variables strictly inside their bounds: a variable on a bound takes no
        // step while the bound stays active, and then its row of B does not enter the QP's
        // step; B keeps its diagonal for it (decoupled) in case the bound lets go
        self.free.clear();
        self.free
            .extend((0..n).filter(|&j| x[j] > shape.lower[j] && x[j] < shape.upper[j]));
        let nf = self.free.len();
        if nf == 0 {
            return 0;
        }
        let mut evaluations = 0;
        lagrangian_gradient(&point.g, &point.jac, lambda, &mut self.lagrangian);
        self.needed.clear();
        self.needed.extend(lambda.iter().map(|&l| l != 0.0));
        let h = &mut self.h[..nf * nf];
        for (b, &j) in self.free.iter().enumerate() {
            let step = 1e-7 * (1.0 + x[j].abs());
            let step = if x[j] + step <= shape.upper[j] {
                step
            } else {
                -step
            };
            probe.x.copy_from_slice(x);
            probe.x[j] += step;
            evaluations += 1;
            if !probe.evaluate_rows(problem, &self.needed) {
                return evaluations;
            }
            lagrangian_gradient(&probe.g, &probe.jac, lambda, &mut self.lagrangian_shifted);
            for (a, &i) in self.free.iter().enumerate() {
                h[a * nf + b] = (self.lagrangian_shifted[i] - self.lagrangian[i]) / step;
            }
        }
        for a in 0..nf {
            for b in 0..a {
                let v = 0.5 * (h[a * nf + b] + h[b * nf + a]);
                h[a * nf + b] = v;
                h[b * nf + a] = v;
            }
        }
        if !hessian::make_positive_definite(h, &mut self.eigen[..nf * nf], nf, 1e-6) {
            return evaluations;
        }
        // B = |H| on the free variables, B's own diagonal on the others, no coupling
        for i in 0..n {
            for j in 0..n {
                if i != j {
                    self.b[i * n + j] = 0.0;
                }
            }
        }
        for (a, &i) in self.free.iter().enumerate() {
            for (b, &j) in self.free.iter().enumerate() {
                self.b[i * n + j] = h[a * nf + b];
            }
        }
        evaluations
    }

    /// A step cut back by the line search says the quadratic model holds only over a shorter
    /// distance: the next QP step is kept within `STEP_LIMIT_RATIO` times the step taken,
    /// in every variable, instead of going as far and being cut back again (each cut costs
    /// trial evaluations, and the longer QP step points where the model is worst). A full
    /// step that reached the limit doubles it; near a KKT point the limit is lifted, so as
    /// not to hold back the fast local convergence. Measured on the wei2017 study: 5 %
    /// fewer iterations, 9 % fewer evaluations.
    pub fn limit_next_step(&mut self, alpha: f64, step: f64, kkt: f64) {
        if kkt < super::REFRESH_UNTIL_KKT {
            self.step_limit = f64::INFINITY;
        } else if alpha < 1.0 {
            self.step_limit = STEP_LIMIT_RATIO * alpha * step;
        } else if step >= 0.99 * self.step_limit {
            self.step_limit *= 2.0;
        }
    }
}

/// `grad f - J^T lambda`.
fn lagrangian_gradient(g: &[f64], jac: &[f64], lambda: &[f64], out: &mut [f64]) {
    let n = g.len();
    out.copy_from_slice(g);
    // an inactive row's term is a zero: left out, the sums are the same
    for (i, &l) in lambda.iter().enumerate() {
        if l != 0.0 {
            for (o, &d) in out.iter_mut().zip(&jac[i * n..(i + 1) * n]) {
                *o -= l * d;
            }
        }
    }
}

fn identity(n: usize) -> Vec<f64> {
    let mut h = vec![0.0; n * n];
    for i in 0..n {
        h[i * n + i] = 1.0;
    }
    h
}
