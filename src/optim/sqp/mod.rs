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
//! The steps live in their own files, each with a typed result: [`subproblem`] (the QP
//! and its elastic fallback: [`subproblem::QpKind`]), [`line_search`] (backtracking with
//! the second-order correction: [`line_search::Outcome`]), [`curvature`] (the BFGS update,
//! the Hessian refresh and the step limit), [`termination`] (the KKT residual) and
//! [`screening`] (which inequalities a QP holds, where [`SqpSettings::screening`] asks).
//!
//! References: J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Springer 2006,
//! Ch. 18 (SQP, merit functions, second-order correction, damped BFGS, Procedure 18.2);
//! M. J. D. Powell, "A fast algorithm for nonlinearly constrained optimization
//! calculations", Lecture Notes in Mathematics 630 (1978).

mod curvature;
mod line_search;
mod scaling;
mod screening;
mod subproblem;
mod termination;

use super::dense::{all_finite, inf_norm, max_violation};
use super::problem::{clamp_into, Problem, Solution, Status};
use curvature::Curvature;
use line_search::{LineSearch, Outcome};
use scaling::ScaledObjective;
use subproblem::{QpKind, Step, Subproblem};

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
    /// Put into each QP only the inequalities its step could reach, the others once a step
    /// breaks them ([`screening`]): the same steps, from smaller QPs where most rows are far
    /// from their bounds.
    pub screening: bool,
}

impl Default for SqpSettings {
    fn default() -> Self {
        SqpSettings {
            tolerance: 1e-10,
            max_iterations: 500,
            hessian_refresh: HESSIAN_REFRESH,
            screening: false,
        }
    }
}

/// The default of [`SqpSettings::hessian_refresh`].
pub const HESSIAN_REFRESH: usize = 5;

/// The Hessian refresh and the step limit stop once the KKT residual is below this.
const REFRESH_UNTIL_KKT: f64 = 1e-4;

/// Solves `problem` from `x0` (moved into the bounds first), its objective scaled where
/// its gradient there is large ([`scaling`]).
pub fn solve(problem: &dyn Problem, x0: &[f64], settings: &SqpSettings) -> Solution {
    Sqp::new(problem, x0, settings.screening).run(settings)
}

/// A point with the problem's values and gradients there.
#[derive(Debug, Clone)]
struct Iterate {
    x: Vec<f64>,
    f: f64,
    c: Vec<f64>,
    g: Vec<f64>,
    /// Constraint Jacobian, row-major.
    jac: Vec<f64>,
}

impl Iterate {
    fn new(x: &[f64], m: usize) -> Self {
        let n = x.len();
        Iterate {
            x: x.to_vec(),
            f: f64::NAN,
            c: vec![0.0; m],
            g: vec![0.0; n],
            jac: vec![0.0; m * n],
        }
    }

    /// Values and gradients at `x`; false where any is not finite.
    fn evaluate(&mut self, problem: &dyn Problem) -> bool {
        self.f = problem.evaluate_with_gradient(&self.x, &mut self.c, &mut self.g, &mut self.jac);
        self.finite_with_gradient()
    }

    /// Whether the objective, the constraints and their gradients are all finite.
    fn finite_with_gradient(&self) -> bool {
        self.f.is_finite() && all_finite(&self.c) && all_finite(&self.g) && all_finite(&self.jac)
    }

    /// [`Iterate::evaluate`] where only the rows with `needed` are read afterwards
    /// ([`Problem::evaluate_with_gradient_of`]); false where any value is not finite.
    fn evaluate_rows(&mut self, problem: &dyn Problem, needed: &[bool]) -> bool {
        self.f = problem.evaluate_with_gradient_of(
            &self.x,
            needed,
            &mut self.c,
            &mut self.g,
            &mut self.jac,
        );
        self.finite_with_gradient()
    }

    /// The objective and constraints at `x` without gradients; false where any is not
    /// finite. Most trial points of a line search are rejected, and need no more.
    fn evaluate_values(&mut self, problem: &dyn Problem) -> bool {
        self.f = problem.evaluate(&self.x, &mut self.c);
        self.f.is_finite() && all_finite(&self.c)
    }
}

/// The bounds and counts of the problem being solved.
#[derive(Clone, Copy)]
struct Shape<'p> {
    n: usize,
    m: usize,
    meq: usize,
    lower: &'p [f64],
    upper: &'p [f64],
}

/// One solve: the iterate, the QP step and its multipliers, the quadratic model, the
/// subproblem's workspaces and the count of evaluations.
struct Sqp<'p> {
    /// The problem, its objective scaled once the start is evaluated ([`scaling`]).
    problem: ScaledObjective<'p>,
    shape: Shape<'p>,
    point: Iterate,
    step: Step,
    curvature: Curvature,
    subproblem: Subproblem,
    line_search: LineSearch,
    evaluations: usize,
}

impl<'p> Sqp<'p> {
    fn new(problem: &'p dyn Problem, x0: &[f64], screening: bool) -> Self {
        let n = problem.dimension();
        let m = problem.constraint_count();
        let (lower, upper) = problem.bounds();
        Sqp {
            problem: ScaledObjective {
                problem,
                scale: 1.0,
            },
            shape: Shape {
                n,
                m,
                meq: problem.equality_count(),
                lower,
                upper,
            },
            point: Iterate::new(x0, m),
            step: Step::new(n, m),
            curvature: Curvature::new(n),
            subproblem: Subproblem::new(n, screening),
            line_search: LineSearch::new(n, m),
            evaluations: 0,
        }
    }

    /// Solves the QP at the iterate into `self.step` (the second-order correction solves
    /// its shifted QP through the subproblem directly).
    fn solve_qp(&mut self) -> Option<QpKind> {
        self.subproblem.solve(
            &self.shape,
            &self.point,
            &self.point.c,
            &mut self.curvature,
            &mut self.step,
        )
    }

    fn kkt_residual(&self) -> f64 {
        termination::kkt_residual(&self.shape, &self.point, &self.step)
    }

    fn run(mut self, settings: &SqpSettings) -> Solution {
        let Shape {
            m,
            meq,
            lower,
            upper,
            ..
        } = self.shape;
        clamp_into(&mut self.point.x, lower, upper);
        let start_ok = self.point.evaluate(&self.problem);
        self.evaluations += 1;
        if !start_ok {
            return self.finish(
                Status::Failed("the problem cannot be evaluated at the start point".into()),
                0,
                None,
            );
        }
        // the start's own evaluation sets the scale, and is scaled as the later ones will be
        let scale = scaling::objective_scale(&self.point.g);
        self.problem.scale = scale;
        self.point.f *= scale;
        self.point.g.iter_mut().for_each(|g| *g *= scale);
        // Powell's penalty weights, one per constraint: they follow the multipliers down as
        // well as up, so that the large multipliers of an elastic phase do not leave the
        // merit function all violation
        let mut mu = vec![0.0; m];
        let mut elastic_streak = 0;
        let mut kkt = f64::INFINITY;
        let (mut best_kkt, mut stalled) = (f64::INFINITY, 0);
        let mut stationary_violation = 0;
        // line searches failed in a row, from the same point
        let mut failed_searches = 0;
        for iteration in 0..settings.max_iterations {
            // near a KKT point the secant updates have the curvature they need: the refresh
            // is for the way there (measured: the same iterations, 6 % less time)
            if settings.hessian_refresh > 0
                && iteration % settings.hessian_refresh == 0
                && kkt > REFRESH_UNTIL_KKT
            {
                self.evaluations += self.curvature.refresh(
                    &self.problem,
                    &self.shape,
                    &self.point,
                    &self.step.lambda,
                    &mut self.line_search.trial,
                );
            }
            let Some(kind) = self.solve_qp() else {
                return self.finish(
                    Status::Failed("the QP subproblem could not be solved".into()),
                    iteration,
                    None,
                );
            };
            let elastic = kind == QpKind::Elastic;
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
                let violation = max_violation(&self.point.c, meq);
                let slack = self.subproblem.slack();
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
            let step = inf_norm(&self.step.d);
            if kkt < 0.9 * best_kkt {
                best_kkt = kkt;
                stalled = 0;
            } else {
                stalled += 1;
            }
            if stalled >= 10 && !self.curvature.is_identity() {
                // no progress towards a KKT point for ten iterations: B has lost its scale
                // (an elastic phase or a run of tiny steps can do that); start it afresh
                self.curvature.reset();
                stalled = 0;
                continue;
            }
            if elastic_streak > 3 && step <= settings.tolerance * (1.0 + inf_norm(&self.point.x)) {
                // the linearised constraints stay inconsistent and the step has vanished:
                // a local minimizer of the violation
                return self.finish(Status::Infeasible, iteration, Some(kkt));
            }
            for (mi, li) in mu.iter_mut().zip(&self.step.lambda) {
                *mi = (1.01 * li.abs()).max(0.5 * (*mi + li.abs()));
            }
            match line_search::search(&mut self, &mu, elastic) {
                Outcome::Accepted { alpha } => {
                    failed_searches = 0;
                    if !elastic {
                        self.curvature.limit_next_step(alpha, step, kkt);
                    }
                }
                Outcome::NoDecrease => {
                    // the second time at the same point: the curvature started afresh did
                    // not help either (the refresh may have rebuilt it in between)
                    if self.curvature.is_identity() || failed_searches > 0 {
                        if elastic {
                            // the linearisation promises less violation and no step gives
                            // it: a kink of the violation (a clearance changing its nearest
                            // features), a local minimizer of it
                            return self.finish(Status::Infeasible, iteration + 1, Some(kkt));
                        }
                        return self.finish(
                            Status::Failed("the line search found no decrease".into()),
                            iteration + 1,
                            Some(kkt),
                        );
                    }
                    failed_searches += 1;
                    // restart the curvature model and try again from the same point
                    self.curvature.reset();
                }
            }
        }
        if self.solve_qp().is_some() {
            kkt = self.kkt_residual();
        }
        self.finish(Status::IterationLimit, settings.max_iterations, Some(kkt))
    }

    fn finish(&self, status: Status, iterations: usize, kkt: Option<f64>) -> Solution {
        Solution {
            status,
            x: self.point.x.clone(),
            objective: self.point.f / self.problem.scale,
            constraints: self.point.c.clone(),
            max_violation: max_violation(&self.point.c, self.shape.meq),
            kkt_residual: kkt,
            iterations,
            evaluations: self.evaluations,
        }
    }
}
