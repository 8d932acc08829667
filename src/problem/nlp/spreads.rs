//! A robust study's spreads: each wanted output's first-order standard deviation under the
//! tolerances and its gradient, from the model's exact second derivatives.

use super::{DesignProblem, Row};
use crate::model::mechanism::{ModulusScaling, PartMaker};
use crate::problem::tolerances::Input;

/// A robust study's rows pointed at their spreads among the values, which begin at `first`:
/// the wanted outputs' (`wanted` of them, the constraints `yield_of` names keep theirs),
/// then those of the first `rule_spreads` rules, whose rows are the constraints from
/// `first_rule` on (a part that cannot be made fails whatever `yield_of` names).
pub(super) fn point_to_spreads(
    problem: &DesignProblem,
    rows: &mut [Row],
    (first, wanted): (usize, usize),
    first_rule: usize,
    rule_spreads: usize,
) {
    for r in rows.iter_mut() {
        if r.constraint >= first_rule {
            let i = r.constraint - first_rule;
            r.spread = (i < rule_spreads).then_some(first + wanted + i);
        } else if problem
            .constraints
            .get(r.constraint)
            .is_some_and(|c| c.in_yield)
        {
            r.spread = Some(first + r.value);
        }
    }
}

/// What a robust study needs to know of the tolerances.
pub(super) struct Spreads<'p> {
    /// Standard deviations of margin each constraint keeps.
    pub(super) k: f64,
    pub(super) model: &'p dyn ModulusScaling,
    /// The standard deviation of each input: the parameters, then the modulus's factor.
    pub(super) sigma: Vec<f64>,
}

/// A robust study's spreads, where `problem` asks for one and its model gives second
/// derivatives (the problem file's validation refuses a robust study otherwise).
pub(super) fn spreads(problem: &DesignProblem) -> Option<Spreads<'_>> {
    let robust = problem.search.robust?;
    let model = problem.mechanism.modulus.as_deref()?;
    let n = problem.variables.len();
    let mut sigma = vec![0.0; n + 1];
    for t in &problem.tolerances {
        match t.input {
            Input::Parameter(i) => sigma[i] = t.sigma,
            Input::Modulus => sigma[n] = t.sigma,
        }
    }
    Some(Spreads {
        k: robust.k_sigma,
        model,
        sigma,
    })
}

impl Spreads<'_> {
    /// The first-order standard deviation of each wanted output at `x` into `spreads`, and
    /// its gradient over the parameters into `jacobian` (rows of `x.len()`):
    /// `d sigma / dx_p = sum_j (dy/dp_j) s_j^2 (d^2 y / dp_j dx_p) / sigma`.
    pub(super) fn spreads_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        spreads: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let (w, n, np) = (wanted.len(), self.sigma.len(), x.len());
        let mut values = vec![0.0; w];
        let mut gradient = vec![0.0; w * n];
        let mut hessian = vec![0.0; w * n * n];
        self.model
            .evaluate_with_hessian(x, wanted, &mut values, &mut gradient, &mut hessian);
        for (i, (spread, row)) in spreads
            .iter_mut()
            .zip(jacobian.chunks_exact_mut(np))
            .enumerate()
        {
            let g = &gradient[i * n..(i + 1) * n];
            let h = &hessian[i * n * n..(i + 1) * n * n];
            *spread = spread_with_gradient(g, h, &self.sigma, row);
        }
    }

    /// The first-order standard deviation of each of the part's first `spreads.len()`
    /// rules' margins at `x`: the tolerances on the parameters move them, the modulus's
    /// does not.
    pub(super) fn rule_spreads(&self, part: &dyn PartMaker, x: &[f64], spreads: &mut [f64]) {
        let (r, np) = (spreads.len(), x.len());
        let mut margins = vec![0.0; r];
        let mut gradient = vec![0.0; r * np];
        part.rule_margins_with_gradient(x, &mut margins, &mut gradient);
        for (spread, g) in spreads.iter_mut().zip(gradient.chunks_exact(np)) {
            *spread = g
                .iter()
                .zip(&self.sigma)
                .map(|(d, s)| (d * s).powi(2))
                .sum::<f64>()
                .sqrt();
        }
    }

    /// As [`Spreads::rule_spreads`], with their gradients over the parameters into
    /// `jacobian` (rows of `x.len()`), from the rules' exact Hessians.
    pub(super) fn rule_spreads_with_gradient(
        &self,
        part: &dyn PartMaker,
        x: &[f64],
        spreads: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let (r, np) = (spreads.len(), x.len());
        let mut margins = vec![0.0; r];
        let mut gradient = vec![0.0; r * np];
        let mut hessian = vec![0.0; r * np * np];
        part.rule_margins_with_hessian(x, &mut margins, &mut gradient, &mut hessian);
        for (i, (spread, row)) in spreads
            .iter_mut()
            .zip(jacobian.chunks_exact_mut(np))
            .enumerate()
        {
            let g = &gradient[i * np..(i + 1) * np];
            let h = &hessian[i * np * np..(i + 1) * np * np];
            *spread = spread_with_gradient(g, h, &self.sigma[..np], row);
        }
    }
}

/// The first-order standard deviation `sigma = sqrt(sum_j (g_j s_j)^2)` of a value of
/// gradient `g` and Hessian `h` (`g.len()` square, row-major) over inputs of standard
/// deviations `s`, and its gradient over the first `row.len()` inputs (the parameters):
/// `d sigma / dx_p = sum_j g_j s_j^2 h_jp / sigma` (zero where `sigma` is).
fn spread_with_gradient(g: &[f64], h: &[f64], s: &[f64], row: &mut [f64]) -> f64 {
    let n = g.len();
    let sigma = g
        .iter()
        .zip(s)
        .map(|(d, s)| (d * s).powi(2))
        .sum::<f64>()
        .sqrt();
    for (p, o) in row.iter_mut().enumerate() {
        *o = if sigma > 0.0 {
            (0..n)
                .map(|j| g[j] * s[j].powi(2) * h[j * n + p])
                .sum::<f64>()
                / sigma
        } else {
            0.0
        };
    }
    sigma
}
