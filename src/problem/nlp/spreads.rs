//! A robust study's spreads: each wanted output's first-order standard deviation under the
//! tolerances and its gradient, from the model's exact second derivatives.

use super::DesignProblem;
use crate::model::mechanism::ModulusScaling;
use crate::problem::tolerances::Input;

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
        for i in 0..w {
            let g = &gradient[i * n..(i + 1) * n];
            let h = &hessian[i * n * n..(i + 1) * n * n];
            let sigma = g
                .iter()
                .zip(&self.sigma)
                .map(|(d, s)| (d * s).powi(2))
                .sum::<f64>()
                .sqrt();
            spreads[i] = sigma;
            let row = &mut jacobian[i * np..(i + 1) * np];
            for (p, o) in row.iter_mut().enumerate() {
                *o = if sigma > 0.0 {
                    (0..n)
                        .map(|j| g[j] * self.sigma[j].powi(2) * h[j * n + p])
                        .sum::<f64>()
                        / sigma
                } else {
                    0.0
                };
            }
        }
    }
}
