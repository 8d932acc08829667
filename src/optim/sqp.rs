//! A dense sequential quadratic programming (SQP) solver.
//!
//! Each iteration solves the quadratic model
//!
//! ```text
//! minimize    1/2 d^T B d + grad f(x)^T d
//! subject to  c_i(x) + grad c_i(x)^T d  = 0   (equalities)
//!             c_i(x) + grad c_i(x)^T d >= 0   (inequalities)
//!             lower - x <= d <= upper - x
//! ```
//!
//! exactly with the dual active-set method of [`super::qp`], and steps along `d` with a
//! backtracking line search on the l1 exact-penalty merit function
//! `phi(x) = f(x) + mu sum_i viol_i(x)`. `B` is a BFGS approximation of the Hessian of the
//! Lagrangian with Powell's damping, which keeps it positive definite. Where the
//! linearised constraints have no common point, the step comes from the elastic QP, which
//! adds one slack `s >= 0` to every constraint and `rho s` to the objective (l-infinity
//! elastic mode). A full step the merit function rejects gets one second-order correction
//! (against the Maratos effect) before backtracking. Iterates never leave the bounds: the
//! QP keeps `x + d` inside, and the line search moves between two points inside.
//! After a step the line search had to cut back, the next QP step is kept within a box a few
//! times that step's size, lifted again near a KKT point (a line-search SQP with a trust-region
//! flavoured safeguard: the cut says how far the quadratic model holds).
//! A trial point where the problem cannot be evaluated is a failed step.
//!
//! The solve stops when the KKT residual, the largest of the scaled stationarity,
//! complementarity and feasibility errors, falls below the tolerance.
//!
//! References: J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Springer 2006,
//! Ch. 18 (SQP, merit functions, second-order correction, damped BFGS, Procedure 18.2);
//! M. J. D. Powell, "A fast algorithm for nonlinearly constrained optimization
//! calculations", Lecture Notes in Mathematics 630 (1978).

use super::hessian;
use super::problem::{clamp_into, max_violation, Problem, Solution, Status};
use super::qp::{self, QpStatus, QpWorkspace};

/// Settings of the SQP solver.
#[derive(Debug, Clone)]
pub struct SqpSettings {
    /// Stop when the KKT residual is below this.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Every this many iterations, replace the BFGS matrix by the Hessian of the Lagrangian
    /// from differences of the exact gradients, its negative curvature flipped
    /// ([`super::hessian`]), until the KKT residual falls below 1e-4; 0 for BFGS alone.
    pub hessian_refresh: usize,
}

impl Default for SqpSettings {
    fn default() -> Self {
        SqpSettings {
            tolerance: 1e-10,
            max_iterations: 500,
            hessian_refresh: HESSIAN_REFRESH,
        }
    }
}

/// The default of [`SqpSettings::hessian_refresh`].
pub const HESSIAN_REFRESH: usize = 5;

/// After a step cut to `alpha` of a QP step of size `|d|`, the next QP step is limited to
/// this times `alpha |d|` ([`Work::limit_next_step`]).
const STEP_LIMIT_RATIO: f64 = 4.0;

/// The Hessian refresh and the step limit stop once the KKT residual is below this.
const REFRESH_UNTIL_KKT: f64 = 1e-4;

/// Solves `problem` from `x0` (moved into the bounds first).
pub fn solve(problem: &dyn Problem, x0: &[f64], settings: &SqpSettings) -> Solution {
    let mut w = Work::new(problem, x0);
    w.run(problem, settings)
}

/// The state and work arrays of one solve, sized once.
struct Work<'p> {
    n: usize,
    m: usize,
    meq: usize,
    lower: &'p [f64],
    upper: &'p [f64],
    x: Vec<f64>,
    f: f64,
    c: Vec<f64>,
    g: Vec<f64>,
    jac: Vec<f64>,
    /// BFGS approximation of the Hessian of the Lagrangian, row-major.
    hess: Vec<f64>,
    hess_scratch: Vec<f64>,
    eigen_scratch: Vec<f64>,
    /// The variables inside their bounds, at a Hessian refresh.
    refresh_free: Vec<usize>,
    xt: Vec<f64>,
    ft: f64,
    ct: Vec<f64>,
    gt: Vec<f64>,
    jact: Vec<f64>,
    d: Vec<f64>,
    d_saved: Vec<f64>,
    lambda: Vec<f64>,
    lambda_saved: Vec<f64>,
    /// Bound multipliers: positive at a lower bound, negative at an upper one.
    nu: Vec<f64>,
    rhs: Vec<f64>,
    /// The rows of the plain QP active at its last solve.
    active_hint: Vec<usize>,
    bfgs_s: Vec<f64>,
    bfgs_y: Vec<f64>,
    bfgs_bs: Vec<f64>,
    qp: QpData,
    ws: QpWorkspace,
    ws_elastic: QpWorkspace,
    evaluations: usize,
    /// The largest step component the next QP may take (infinite: no limit).
    step_limit: f64,
}

/// The arrays of one QP subproblem.
#[derive(Default)]
struct QpData {
    g: Vec<f64>,
    a: Vec<f64>,
    c: Vec<f64>,
    b: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    x: Vec<f64>,
    l: Vec<f64>,
}

impl<'p> Work<'p> {
    fn new(problem: &'p dyn Problem, x0: &[f64]) -> Self {
        let n = problem.dimension();
        let m = problem.constraint_count();
        let (lower, upper) = problem.bounds();
        Work {
            n,
            m,
            meq: problem.equality_count(),
            lower,
            upper,
            x: x0.to_vec(),
            f: f64::NAN,
            c: vec![0.0; m],
            g: vec![0.0; n],
            jac: vec![0.0; m * n],
            hess: identity(n),
            hess_scratch: vec![0.0; n * n],
            eigen_scratch: vec![0.0; n * n],
            refresh_free: Vec::with_capacity(n),
            xt: vec![0.0; n],
            ft: f64::NAN,
            ct: vec![0.0; m],
            gt: vec![0.0; n],
            jact: vec![0.0; m * n],
            d: vec![0.0; n],
            d_saved: vec![0.0; n],
            lambda: vec![0.0; m],
            lambda_saved: vec![0.0; m],
            nu: vec![0.0; n],
            rhs: vec![0.0; m],
            active_hint: Vec::new(),
            bfgs_s: vec![0.0; n],
            bfgs_y: vec![0.0; n],
            bfgs_bs: vec![0.0; n],
            qp: QpData::default(),
            ws: QpWorkspace::new(n),
            ws_elastic: QpWorkspace::new(n + 1),
            evaluations: 0,
            step_limit: f64::INFINITY,
        }
    }

    fn run(&mut self, problem: &dyn Problem, settings: &SqpSettings) -> Solution {
        clamp_into(&mut self.x, self.lower, self.upper);
        self.f = problem.evaluate_with_gradient(&self.x, &mut self.c, &mut self.g, &mut self.jac);
        self.evaluations += 1;
        if !finite(self.f, &self.c, &self.g, &self.jac) {
            return self.finish(
                Status::Failed("the problem cannot be evaluated at the start point".into()),
                0,
                None,
            );
        }
        // Powell's penalty weights, one per constraint: they follow the multipliers down as
        // well as up, so that the large multipliers of an elastic phase do not leave the
        // merit function all violation
        let mut mu = vec![0.0; self.m];
        let mut elastic_streak = 0;
        let mut kkt = f64::INFINITY;
        let (mut best_kkt, mut stalled) = (f64::INFINITY, 0);
        let mut stationary_violation = 0;
        for iteration in 0..settings.max_iterations {
            // near a KKT point the secant updates have the curvature they need: the refresh
            // is for the way there (measured: the same iterations, 6 % less time)
            if settings.hessian_refresh > 0
                && iteration % settings.hessian_refresh == 0
                && kkt > REFRESH_UNTIL_KKT
            {
                self.refresh_hessian(problem);
            }
            self.rhs.copy_from_slice(&self.c);
            let Some(elastic) = self.solve_qp() else {
                return self.finish(
                    Status::Failed("the QP subproblem could not be solved".into()),
                    iteration,
                    None,
                );
            };
            elastic_streak = if elastic { elastic_streak + 1 } else { 0 };
            kkt = self.kkt_residual();
            if kkt <= settings.tolerance {
                return self.finish(Status::Converged, iteration, Some(kkt));
            }
            // in elastic mode the slack is the least largest violation the linearised
            // constraints allow; when it is hardly below the violation now (the objective's
            // pull on a finite slack price moves it a little), no step reduces the violation
            // to first order: a stationary point of the violation
            if elastic {
                let violation = max_violation(&self.c, self.meq);
                let slack = self.qp.x[self.n];
                stationary_violation = if slack >= violation * (1.0 - 1e-4) - 1e-14 {
                    stationary_violation + 1
                } else {
                    0
                };
                if stationary_violation >= 3 {
                    return self.finish(Status::Infeasible, iteration, Some(kkt));
                }
            } else {
                stationary_violation = 0;
            }
            let step = inf_norm(&self.d);
            if kkt < 0.9 * best_kkt {
                best_kkt = kkt;
                stalled = 0;
            } else {
                stalled += 1;
            }
            if stalled >= 10 && !is_identity(&self.hess, self.n) {
                // no progress towards a KKT point for ten iterations: B has lost its scale
                // (an elastic phase or a run of tiny steps can do that); start it afresh
                self.reset_hessian();
                stalled = 0;
                continue;
            }
            if elastic_streak > 3 && step <= settings.tolerance * (1.0 + inf_norm(&self.x)) {
                // the linearised constraints stay inconsistent and the step has vanished:
                // a local minimizer of the violation
                return self.finish(Status::Infeasible, iteration, Some(kkt));
            }
            for (mi, li) in mu.iter_mut().zip(&self.lambda) {
                *mi = (1.01 * li.abs()).max(0.5 * (*mi + li.abs()));
            }
            let Some(alpha) = self.line_search(problem, &mu) else {
                if is_identity(&self.hess, self.n) {
                    return self.finish(
                        Status::Failed("the line search found no decrease".into()),
                        iteration + 1,
                        Some(kkt),
                    );
                }
                // restart the curvature model and try again from the same point
                self.reset_hessian();
                continue;
            };
            if !elastic {
                self.limit_next_step(alpha, step, kkt);
            }
        }
        self.rhs.copy_from_slice(&self.c);
        if self.solve_qp().is_some() {
            kkt = self.kkt_residual();
        }
        self.finish(Status::IterationLimit, settings.max_iterations, Some(kkt))
    }

    /// Backtracks along `d` on the l1 merit function; on success the trial point becomes the
    /// iterate, the Hessian is updated, and the step length taken is returned (1 for a full
    /// or second-order corrected step).
    fn line_search(&mut self, problem: &dyn Problem, mu: &[f64]) -> Option<f64> {
        let viol = weighted_violation(&self.c, self.meq, mu);
        let phi = self.f + viol;
        let slope = (dot(&self.g, &self.d) - viol).min(0.0);
        // Armijo, with room for the rounding of phi itself: near a solution the predicted
        // decrease falls below what phi can resolve, and the full steps of the local
        // (superlinear) convergence must not be cut on noise
        let noise = 100.0 * f64::EPSILON * phi.abs().max(1.0);
        let accept_at = |phit: f64, alpha: f64| phit <= phi + 1e-4 * alpha * slope + noise;
        let mut alpha = 1.0;
        for k in 0..40 {
            self.set_trial(alpha);
            if !self.evaluate_trial_values(problem) {
                alpha *= 0.25;
                continue;
            }
            let phit = self.ft + weighted_violation(&self.ct, self.meq, mu);
            if accept_at(phit, alpha) {
                if !self.evaluate_trial(problem) {
                    alpha *= 0.25;
                    continue;
                }
                self.accept();
                return Some(alpha);
            }
            if k == 0 && self.second_order_correction(problem) {
                let phis = self.ft + weighted_violation(&self.ct, self.meq, mu);
                if accept_at(phis, 1.0) && self.evaluate_trial(problem) {
                    self.accept();
                    return Some(1.0);
                }
                self.d.copy_from_slice(&self.d_saved);
                self.lambda.copy_from_slice(&self.lambda_saved);
            }
            // minimizer of the quadratic through phi(0), phi'(0) and phi(alpha), safeguarded
            let curvature = 2.0 * (phit - phi - slope * alpha);
            let next = if curvature > 0.0 {
                -slope * alpha * alpha / curvature
            } else {
                0.5 * alpha
            };
            alpha = next.clamp(0.1 * alpha, 0.5 * alpha);
        }
        None
    }

    /// Replaces the rejected full step `d` by the solution of the QP whose constraints are
    /// shifted by the curvature seen at `x + d`: `c(x+d) - J d + J d' >= 0`. Leaves the
    /// corrected trial point evaluated; false if the correction failed.
    fn second_order_correction(&mut self, problem: &dyn Problem) -> bool {
        if violation_l1(&self.ct, self.meq) <= 0.5 * violation_l1(&self.c, self.meq) {
            return false;
        }
        self.d_saved.copy_from_slice(&self.d);
        self.lambda_saved.copy_from_slice(&self.lambda);
        let n = self.n;
        for i in 0..self.m {
            self.rhs[i] = self.ct[i] - dot(&self.jac[i * n..(i + 1) * n], &self.d_saved);
        }
        if self.solve_qp() != Some(false) {
            self.d.copy_from_slice(&self.d_saved);
            self.lambda.copy_from_slice(&self.lambda_saved);
            return false;
        }
        self.set_trial(1.0);
        if self.evaluate_trial_values(problem) {
            return true;
        }
        self.d.copy_from_slice(&self.d_saved);
        self.lambda.copy_from_slice(&self.lambda_saved);
        false
    }

    /// `B <- |H|`, `H` the Hessian of the Lagrangian at `x` with the current multipliers, by
    /// forward differences of the exact gradients (backward at an upper bound). Leaves `B`
    /// as it was where a difference cannot be evaluated.
    fn refresh_hessian(&mut self, problem: &dyn Problem) {
        let n = self.n;
        // only the variables strictly inside their bounds: a variable on a bound takes no
        // step while the bound stays active, and then its row of B does not enter the QP's
        // step; B keeps its diagonal for it (decoupled) in case the bound lets go
        self.refresh_free.clear();
        self.refresh_free
            .extend((0..n).filter(|&j| self.x[j] > self.lower[j] && self.x[j] < self.upper[j]));
        let nf = self.refresh_free.len();
        if nf == 0 {
            return;
        }
        // the Lagrangian's gradient at x into bfgs_y, at the shifted point into bfgs_bs
        lagrangian_gradient(&self.g, &self.jac, &self.lambda, &mut self.bfgs_y);
        let h = &mut self.hess_scratch[..nf * nf];
        for (b, &j) in self.refresh_free.iter().enumerate() {
            let step = 1e-7 * (1.0 + self.x[j].abs());
            let step = if self.x[j] + step <= self.upper[j] {
                step
            } else {
                -step
            };
            self.xt.copy_from_slice(&self.x);
            self.xt[j] += step;
            self.ft = problem.evaluate_with_gradient(
                &self.xt,
                &mut self.ct,
                &mut self.gt,
                &mut self.jact,
            );
            self.evaluations += 1;
            if !finite(self.ft, &self.ct, &self.gt, &self.jact) {
                return;
            }
            lagrangian_gradient(&self.gt, &self.jact, &self.lambda, &mut self.bfgs_bs);
            for (a, &i) in self.refresh_free.iter().enumerate() {
                h[a * nf + b] = (self.bfgs_bs[i] - self.bfgs_y[i]) / step;
            }
        }
        for a in 0..nf {
            for b in 0..a {
                let v = 0.5 * (h[a * nf + b] + h[b * nf + a]);
                h[a * nf + b] = v;
                h[b * nf + a] = v;
            }
        }
        if !hessian::make_positive_definite(h, &mut self.eigen_scratch[..nf * nf], nf, 1e-6) {
            return;
        }
        // B = |H| on the free variables, B's own diagonal on the others, no coupling
        for i in 0..n {
            for j in 0..n {
                if i != j {
                    self.hess[i * n + j] = 0.0;
                }
            }
        }
        for (a, &i) in self.refresh_free.iter().enumerate() {
            for (b, &j) in self.refresh_free.iter().enumerate() {
                self.hess[i * n + j] = h[a * nf + b];
            }
        }
    }

    /// A step cut back by the line search says the quadratic model holds only over a shorter
    /// distance: the next QP step is kept within `STEP_LIMIT_RATIO` times the step taken,
    /// in every variable, instead of going as far and being cut back again (each cut costs
    /// trial evaluations, and the longer QP step points where the model is worst). A full
    /// step that reached the limit doubles it; near a KKT point the limit is lifted, so as
    /// not to hold back the fast local convergence. Measured on the wei2017 study: 5 %
    /// fewer iterations, 9 % fewer evaluations.
    fn limit_next_step(&mut self, alpha: f64, step: f64, kkt: f64) {
        if kkt < REFRESH_UNTIL_KKT {
            self.step_limit = f64::INFINITY;
        } else if alpha < 1.0 {
            self.step_limit = STEP_LIMIT_RATIO * alpha * step;
        } else if step >= 0.99 * self.step_limit {
            self.step_limit *= 2.0;
        }
    }

    /// Starts the curvature model afresh, and with it the step limit, which was set from
    /// steps of the old model.
    fn reset_hessian(&mut self) {
        self.hess = identity(self.n);
        self.step_limit = f64::INFINITY;
    }

    fn set_trial(&mut self, alpha: f64) {
        for j in 0..self.n {
            self.xt[j] = (self.x[j] + alpha * self.d[j]).clamp(self.lower[j], self.upper[j]);
        }
    }

    /// The objective and constraints at the trial point, without gradients: most trial
    /// points of a line search are rejected.
    fn evaluate_trial_values(&mut self, problem: &dyn Problem) -> bool {
        self.ft = problem.evaluate(&self.xt, &mut self.ct);
        self.evaluations += 1;
        self.ft.is_finite() && self.ct.iter().all(|v| v.is_finite())
    }

    /// The trial point with gradients, once it is accepted.
    fn evaluate_trial(&mut self, problem: &dyn Problem) -> bool {
        self.ft =
            problem.evaluate_with_gradient(&self.xt, &mut self.ct, &mut self.gt, &mut self.jact);
        self.evaluations += 1;
        finite(self.ft, &self.ct, &self.gt, &self.jact)
    }

    /// Moves to the trial point, updating the BFGS Hessian with Powell's damping.
    fn accept(&mut self) {
        let n = self.n;
        let (s, y, bs) = (&mut self.bfgs_s, &mut self.bfgs_y, &mut self.bfgs_bs);
        for j in 0..n {
            s[j] = self.xt[j] - self.x[j];
            // y = grad L(xt) - grad L(x), L = f - lambda^T c
            let mut yj = self.gt[j] - self.g[j];
            for i in 0..self.m {
                yj -= self.lambda[i] * (self.jact[i * n + j] - self.jac[i * n + j]);
            }
            y[j] = yj;
        }
        for (bi, row) in bs.iter_mut().zip(self.hess.chunks_exact(n)) {
            *bi = dot(row, s);
        }
        let sbs = dot(s, bs);
        let sy = dot(s, y);
        if sbs > 1e-300 && s.iter().any(|&v| v != 0.0) {
            // Powell's damping keeps B positive definite
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
                        self.hess[i * n + j] += y[i] * y[j] * isy - bs[i] * bs[j] * isbs;
                    }
                }
            }
        }
        std::mem::swap(&mut self.x, &mut self.xt);
        std::mem::swap(&mut self.c, &mut self.ct);
        std::mem::swap(&mut self.g, &mut self.gt);
        std::mem::swap(&mut self.jac, &mut self.jact);
        self.f = self.ft;
    }

    /// Solves the QP at `x` with constraint values `rhs`, into `d` and `lambda`.
    /// `Some(true)` when it took elastic mode, `None` when even that failed.
    fn solve_qp(&mut self) -> Option<bool> {
        for elastic in [false, true] {
            self.build_qp(elastic);
            let nv = self.n + usize::from(elastic);
            let meq = if elastic { 0 } else { self.meq };
            self.qp.x.resize(nv, 0.0);
            self.qp.l.resize(self.qp.b.len() + 2 * nv, 0.0);
            let ws = if elastic {
                &mut self.ws_elastic
            } else {
                &mut self.ws
            };
            let q = &mut self.qp;
            // the rows of the plain QP keep their meaning between iterations: start from the
            // last active set
            let hint: &[usize] = if elastic { &[] } else { &self.active_hint };
            let status = qp::solve_with_hint(
                &q.g, &q.a, &q.c, &q.b, meq, &q.lo, &q.hi, hint, &mut q.x, &mut q.l, ws,
            );
            if status == QpStatus::Optimal && !elastic {
                self.active_hint.clear();
                self.active_hint
                    .extend_from_slice(qp::active_rows(&self.ws));
            }
            match status {
                QpStatus::Optimal => {
                    self.read_qp(elastic);
                    return Some(elastic);
                }
                QpStatus::NotConvex if !is_identity(&self.hess, self.n) => {
                    // rounding in the BFGS updates cost B its definiteness: start it afresh
                    self.reset_hessian();
                    return self.solve_qp();
                }
                _ => {}
            }
        }
        None
    }

    /// QP variables: `d` (and the slack in elastic mode), bounded by `lower - x <= d <=
    /// upper - x` (and `s >= 0`). Rows: the linearised constraints, both sides of each
    /// equality in elastic mode.
    fn build_qp(&mut self, elastic: bool) {
        let (n, m, meq) = (self.n, self.m, self.meq);
        let nv = n + usize::from(elastic);
        let q = &mut self.qp;
        q.g.clear();
        q.g.resize(nv * nv, 0.0);
        for i in 0..n {
            q.g[i * nv..i * nv + n].copy_from_slice(&self.hess[i * n..(i + 1) * n]);
        }
        // B inherits the near-zero curvature of the Lagrangian along the constraint
        // normals; the dual QP method inverts it through L^-T and would lose as many digits
        // as its condition number has. A floor of 1e-6 of the largest curvature bounds that
        // loss and barely moves the step in the directions that matter.
        let floor = 1e-6 * (0..n).map(|i| self.hess[i * n + i]).fold(0.0, f64::max);
        for i in 0..n {
            q.g[i * nv + i] += floor;
        }
        q.a.clear();
        q.a.extend_from_slice(&self.g);
        q.c.clear();
        q.b.clear();
        q.lo.clear();
        q.hi.clear();
        // the step limit is left out of the elastic QP, whose slack must be free to show
        // how far the linearised constraints can be met
        let limit = if elastic {
            f64::INFINITY
        } else {
            self.step_limit
        };
        q.lo.extend(
            self.lower
                .iter()
                .zip(&self.x)
                .map(|(l, x)| (l - x).max(-limit)),
        );
        q.hi.extend(
            self.upper
                .iter()
                .zip(&self.x)
                .map(|(u, x)| (u - x).min(limit)),
        );
        if elastic {
            // a large linear price on the slack, and a curvature of the size of B's so that
            // G stays well conditioned; priced from the gradient alone: the multipliers of
            // an elastic QP are bounded by this price, and feeding them back would make it
            // grow without end
            let scale = inf_norm(&self.g).max(1.0);
            let diag = (0..n).map(|i| self.hess[i * n + i]).sum::<f64>() / n as f64;
            q.g[n * nv + n] = diag.max(1e-8);
            q.a.push(1e4 * scale);
            q.lo.push(0.0);
            q.hi.push(f64::INFINITY);
        }
        let slack = if elastic { Some(1.0) } else { None };
        for i in 0..m {
            let row = &self.jac[i * n..(i + 1) * n];
            push_row(q, row, 1.0, slack, -self.rhs[i]);
            if elastic && i < meq {
                push_row(q, row, -1.0, slack, self.rhs[i]);
            }
        }
    }

    fn read_qp(&mut self, elastic: bool) {
        self.d.copy_from_slice(&self.qp.x[..self.n]);
        let mut row = 0;
        for i in 0..self.m {
            self.lambda[i] = self.qp.l[row];
            row += 1;
            if elastic && i < self.meq {
                self.lambda[i] -= self.qp.l[row];
                row += 1;
            }
        }
        // the bound rows follow: lower then upper for each variable
        for j in 0..self.n {
            self.nu[j] = self.qp.l[row + 2 * j] - self.qp.l[row + 2 * j + 1];
        }
    }

    /// The largest of: stationarity `|grad f - J^T lambda - nu|` scaled by
    /// `max(1, |grad f|)`; complementarity of the constraints and the bounds scaled by
    /// `max(1, |multipliers|)`; and the constraint violation. The multipliers are the QP's
    /// at `x`, so that the measure needs no guess of which bounds are active.
    fn kkt_residual(&self) -> f64 {
        let n = self.n;
        let mut stat: f64 = 0.0;
        for j in 0..n {
            let mut r = self.g[j] - self.nu[j];
            for i in 0..self.m {
                r -= self.lambda[i] * self.jac[i * n + j];
            }
            stat = stat.max(r.abs());
        }
        let stat = stat / inf_norm(&self.g).max(1.0);
        let mscale = inf_norm(&self.lambda).max(inf_norm(&self.nu)).max(1.0);
        let mut compl: f64 = (self.meq..self.m)
            .map(|i| (self.lambda[i] * self.c[i]).abs())
            .fold(0.0, f64::max);
        for j in 0..n {
            let gap = if self.nu[j] > 0.0 {
                self.x[j] - self.lower[j]
            } else {
                self.upper[j] - self.x[j]
            };
            if self.nu[j] != 0.0 {
                compl = compl.max(self.nu[j].abs() * gap);
            }
        }
        stat.max(compl / mscale)
            .max(max_violation(&self.c, self.meq))
    }

    fn finish(&self, status: Status, iterations: usize, kkt: Option<f64>) -> Solution {
        Solution {
            status,
            x: self.x.clone(),
            objective: self.f,
            constraints: self.c.clone(),
            max_violation: max_violation(&self.c, self.meq),
            kkt_residual: kkt,
            iterations,
            evaluations: self.evaluations,
        }
    }
}

/// `grad f - J^T lambda`.
fn lagrangian_gradient(g: &[f64], jac: &[f64], lambda: &[f64], out: &mut [f64]) {
    let n = g.len();
    out.copy_from_slice(g);
    for (i, &l) in lambda.iter().enumerate() {
        for (o, &d) in out.iter_mut().zip(&jac[i * n..(i + 1) * n]) {
            *o -= l * d;
        }
    }
}

fn push_row(q: &mut QpData, row: &[f64], sign: f64, slack: Option<f64>, b: f64) {
    q.c.extend(row.iter().map(|v| sign * v));
    if let Some(s) = slack {
        q.c.push(s);
    }
    q.b.push(b);
}

fn identity(n: usize) -> Vec<f64> {
    let mut h = vec![0.0; n * n];
    for i in 0..n {
        h[i * n + i] = 1.0;
    }
    h
}

fn is_identity(h: &[f64], n: usize) -> bool {
    (0..n * n).all(|k| h[k] == if k / n == k % n { 1.0 } else { 0.0 })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn inf_norm(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

fn finite(f: f64, c: &[f64], g: &[f64], jac: &[f64]) -> bool {
    f.is_finite() && c.iter().chain(g).chain(jac).all(|v| v.is_finite())
}

/// `sum mu_i viol_i`: the penalty term of the merit function.
fn weighted_violation(c: &[f64], meq: usize, mu: &[f64]) -> f64 {
    c.iter()
        .zip(mu)
        .enumerate()
        .map(|(i, (&v, &w))| w * if i < meq { v.abs() } else { (-v).max(0.0) })
        .sum()
}

/// `sum |c_eq| + sum max(0, -c_ineq)`.
fn violation_l1(c: &[f64], meq: usize) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, &v)| if i < meq { v.abs() } else { (-v).max(0.0) })
        .sum()
}
