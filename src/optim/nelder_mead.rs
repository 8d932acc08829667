//! Derivative-free constrained minimization: argmin's Nelder-Mead simplex inside an
//! augmented-Lagrangian outer loop.
//!
//! Bounds are removed by a smooth change of variables, so the simplex never collapses onto
//! a bound: `x = l + (u - l)(1 + sin z)/2` for a variable with both bounds,
//! `x = l - 1 + sqrt(1 + z^2)` or `x = u + 1 - sqrt(1 + z^2)` with one bound, `x = z` with
//! none. Constraints enter through the Powell-Hestenes-Rockafellar augmented Lagrangian
//!
//! ```text
//! L(x) = f(x) - sum_eq (mu_j h_j - rho/2 h_j^2)
//!             + 1/(2 rho) sum_ineq (max(0, lambda_i - rho g_i)^2 - lambda_i^2)
//! ```
//!
//! minimized by Nelder-Mead from the best point so far with a fresh simplex; then
//! `lambda_i <- max(0, lambda_i - rho g_i)`, `mu_j <- mu_j - rho h_j`, and `rho` grows
//! tenfold whenever the violation did not fall to a quarter.
//!
//! Reference: J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Ch. 17.

use std::cell::Cell;

use argmin::core::{CostFunction, Error, Executor, State};
use argmin::solver::neldermead::NelderMead;

use super::problem::{clamp_into, max_violation, Problem, Solution, Status};

/// Settings of the constrained Nelder-Mead solver.
#[derive(Debug, Clone)]
pub struct NelderMeadSettings {
    /// Target constraint violation, and the relative change of the objective between
    /// outer iterations below which the solve has converged.
    pub tolerance: f64,
    /// Largest number of outer (multiplier) iterations.
    pub max_iterations: usize,
    /// Largest number of simplex iterations per outer iteration, per variable.
    pub inner_iterations_per_variable: u64,
}

impl Default for NelderMeadSettings {
    fn default() -> Self {
        NelderMeadSettings {
            tolerance: 1e-10,
            max_iterations: 40,
            inner_iterations_per_variable: 400,
        }
    }
}

/// The map from unconstrained `z` to `x` within the bounds.
struct Transform<'a> {
    lower: &'a [f64],
    upper: &'a [f64],
}

impl Transform<'_> {
    fn to_x(&self, z: &[f64], x: &mut [f64]) {
        for j in 0..z.len() {
            let (l, u) = (self.lower[j], self.upper[j]);
            x[j] = match (l.is_finite(), u.is_finite()) {
                (true, true) => (l + (u - l) * 0.5 * (1.0 + z[j].sin())).clamp(l, u),
                (true, false) => l - 1.0 + (1.0 + z[j] * z[j]).sqrt(),
                (false, true) => u + 1.0 - (1.0 + z[j] * z[j]).sqrt(),
                (false, false) => z[j],
            };
        }
    }

    fn to_z(&self, x: &[f64]) -> Vec<f64> {
        (0..x.len())
            .map(|j| {
                let (l, u) = (self.lower[j], self.upper[j]);
                match (l.is_finite(), u.is_finite()) {
                    (true, true) => (2.0 * (x[j] - l) / (u - l) - 1.0).clamp(-1.0, 1.0).asin(),
                    (true, false) => ((x[j] - l + 1.0).powi(2) - 1.0).max(0.0).sqrt(),
                    (false, true) => ((u - x[j] + 1.0).powi(2) - 1.0).max(0.0).sqrt(),
                    (false, false) => x[j],
                }
            })
            .collect()
    }
}

/// The augmented Lagrangian as a function of `z`.
struct Merit<'a> {
    problem: &'a dyn Problem,
    transform: &'a Transform<'a>,
    lambda: &'a [f64],
    rho: f64,
    evaluations: &'a Cell<usize>,
}

impl Merit<'_> {
    fn value_at_x(&self, x: &[f64], c: &mut [f64]) -> f64 {
        let f = self.problem.evaluate(x, c);
        self.evaluations.set(self.evaluations.get() + 1);
        if !f.is_finite() || c.iter().any(|v| !v.is_finite()) {
            return f64::INFINITY;
        }
        let meq = self.problem.equality_count();
        let rho = self.rho;
        let mut l = f;
        for (i, (&ci, &li)) in c.iter().zip(self.lambda).enumerate() {
            l += if i < meq {
                -li * ci + 0.5 * rho * ci * ci
            } else {
                ((li - rho * ci).max(0.0).powi(2) - li * li) / (2.0 * rho)
            };
        }
        l
    }
}

impl CostFunction for Merit<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, z: &Vec<f64>) -> Result<f64, Error> {
        let mut x = vec![0.0; z.len()];
        self.transform.to_x(z, &mut x);
        let mut c = vec![0.0; self.problem.constraint_count()];
        Ok(self.value_at_x(&x, &mut c))
    }
}

/// Solves `problem` from `x0` (moved into the bounds first).
pub fn solve(problem: &dyn Problem, x0: &[f64], settings: &NelderMeadSettings) -> Solution {
    let n = problem.dimension();
    let m = problem.constraint_count();
    let meq = problem.equality_count();
    let (lower, upper) = problem.bounds();
    let transform = Transform { lower, upper };
    let evaluations = Cell::new(0);
    let mut x = x0.to_vec();
    clamp_into(&mut x, lower, upper);
    let mut c = vec![0.0; m];
    let mut f = problem.evaluate(&x, &mut c);
    evaluations.set(1);
    if !f.is_finite() || c.iter().any(|v| !v.is_finite()) {
        return finish(
            Status::Failed("the problem cannot be evaluated at the start point".into()),
            x,
            f,
            c,
            meq,
            0,
            &evaluations,
        );
    }
    let mut lambda = vec![0.0; m];
    let mut rho = 10.0 * f.abs().max(1.0);
    let mut z = transform.to_z(&x);
    let mut last_violation = max_violation(&c, meq);
    for outer in 0..settings.max_iterations {
        let merit = Merit {
            problem,
            transform: &transform,
            lambda: &lambda,
            rho,
            evaluations: &evaluations,
        };
        z = match minimize(
            merit,
            &z,
            settings.tolerance,
            settings.inner_iterations_per_variable * n as u64,
        ) {
            Ok(z) => z,
            Err(e) => {
                return finish(
                    Status::Failed(format!("Nelder-Mead: {e}")),
                    x,
                    f,
                    c,
                    meq,
                    outer,
                    &evaluations,
                )
            }
        };
        let f_previous = f;
        let mut xn = vec![0.0; n];
        transform.to_x(&z, &mut xn);
        let fnew = problem.evaluate(&xn, &mut c);
        evaluations.set(evaluations.get() + 1);
        if !fnew.is_finite() || c.iter().any(|v| !v.is_finite()) {
            return finish(
                Status::Failed("the simplex ended where the problem cannot be evaluated".into()),
                x,
                f,
                c,
                meq,
                outer,
                &evaluations,
            );
        }
        x = xn;
        f = fnew;
        let violation = max_violation(&c, meq);
        for i in 0..m {
            lambda[i] = if i < meq {
                lambda[i] - rho * c[i]
            } else {
                (lambda[i] - rho * c[i]).max(0.0)
            };
        }
        let settled = (f - f_previous).abs() <= settings.tolerance * f.abs().max(1.0);
        if violation <= settings.tolerance && settled && outer > 0 {
            return finish(Status::Converged, x, f, c, meq, outer + 1, &evaluations);
        }
        if violation > 0.25 * last_violation && violation > settings.tolerance {
            rho *= 10.0;
        }
        last_violation = violation;
    }
    let status = if max_violation(&c, meq) > settings.tolerance.max(1e-8) {
        Status::Infeasible
    } else {
        Status::IterationLimit
    };
    finish(status, x, f, c, meq, settings.max_iterations, &evaluations)
}

/// One Nelder-Mead run from `z0` with a fresh simplex.
fn minimize(merit: Merit, z0: &[f64], tolerance: f64, max_iters: u64) -> Result<Vec<f64>, Error> {
    let n = z0.len();
    let mut simplex = vec![z0.to_vec()];
    for j in 0..n {
        let mut v = z0.to_vec();
        v[j] += if v[j].abs() > 1e-3 {
            0.1 * v[j].abs().max(0.1)
        } else {
            0.1
        };
        simplex.push(v);
    }
    let solver = NelderMead::new(simplex).with_sd_tolerance(tolerance * 1e-3)?;
    let result = Executor::new(merit, solver)
        .configure(|state| state.max_iters(max_iters))
        .run()?;
    Ok(result
        .state()
        .get_best_param()
        .cloned()
        .unwrap_or_else(|| z0.to_vec()))
}

fn finish(
    status: Status,
    x: Vec<f64>,
    f: f64,
    c: Vec<f64>,
    meq: usize,
    iterations: usize,
    evaluations: &Cell<usize>,
) -> Solution {
    Solution {
        status,
        max_violation: max_violation(&c, meq),
        x,
        objective: f,
        constraints: c,
        kkt_residual: None,
        iterations,
        evaluations: evaluations.get(),
    }
}
