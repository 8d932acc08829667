//! The constrained problems the solvers accept.

/// ```text
/// minimize    f(x)
/// subject to  c_i(x)  = 0    for i < equality_count()
///             c_i(x) >= 0    for equality_count() <= i < constraint_count()
///             lower <= x <= upper
/// ```
///
/// An evaluation may fail (the model has no value there): it then returns a non-finite
/// objective, and the solvers treat the point as a failed step, never as a result.
pub trait Problem: Sync {
    fn dimension(&self) -> usize;
    /// Lower and upper bounds; infinite where a variable is unbounded.
    fn bounds(&self) -> (&[f64], &[f64]);
    fn equality_count(&self) -> usize;
    fn constraint_count(&self) -> usize;
    /// `f(x)`, with the constraint values written into `c`.
    fn evaluate(&self, x: &[f64], c: &mut [f64]) -> f64;
    /// `f(x)` with its gradient, the constraints and their Jacobian (row-major,
    /// `jacobian[i * n + j] = d c_i / d x_j`).
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64;
    /// [`Problem::evaluate_with_gradient`] where only the rows `i` with `needed[i]` are
    /// read: the others' values and gradients may be left at any finite numbers (the
    /// default works them out as well). The Hessian's refresh forms the Lagrangian's
    /// gradient from the last QP's multipliers, most of them zero, at each of its shifted
    /// points, and a problem whose rows cost more than its objective (the part's rules)
    /// can leave out those with none.
    fn evaluate_with_gradient_of(
        &self,
        x: &[f64],
        needed: &[bool],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let _ = needed;
        self.evaluate_with_gradient(x, c, gradient, jacobian)
    }
}

/// How a local solve ended.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case", tag = "status", content = "reason")]
pub enum Status {
    /// The KKT conditions hold to the tolerance.
    Converged,
    IterationLimit,
    /// The solver stopped at a point that minimizes the constraint violation but violates
    /// the constraints.
    Infeasible,
    /// The solve could not go on; the reason says why.
    Failed(String),
}

/// The result of a local solve.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Solution {
    pub status: Status,
    pub x: Vec<f64>,
    pub objective: f64,
    pub constraints: Vec<f64>,
    /// Largest violation of a constraint (bounds are never violated).
    pub max_violation: f64,
    /// Largest KKT residual (stationarity, complementarity, feasibility), where the solver
    /// has multipliers.
    pub kkt_residual: Option<f64>,
    pub iterations: usize,
    /// Evaluations of the problem, with or without gradients.
    pub evaluations: usize,
}

pub use super::dense::max_violation;

/// Moves `x` into the bounds.
pub fn clamp_into(x: &mut [f64], lower: &[f64], upper: &[f64]) {
    for ((xi, &lo), &hi) in x.iter_mut().zip(lower).zip(upper) {
        *xi = xi.max(lo).min(hi);
    }
}
