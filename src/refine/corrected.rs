//! The analytic model with some outputs corrected towards a higher fidelity: the surrogate
//! the refinement optimizes.
//!
//! An output `a(x)` the high fidelity measures as `F(x)` is replaced by
//!
//! ```text
//! s(x) = a(x) (rho + h . (x - x_c))        rho = F(x_c) / a(x_c)
//! ```
//!
//! a multiplicative output space mapping (Koziel, Bandler and Madsen, "A space-mapping
//! framework for engineering optimization: theory and implementation", IEEE Trans.
//! Microwave Theory Tech. 54(10), 2006, Sec. II: the output correction) whose factor is
//! exact at the centre `x_c` and whose slope `h` is a Broyden secant estimate
//! ([`super::Correction::update`]). A multiplicative factor suits this model: the FE and
//! the beam model differ by a proportion that changes slowly over the design space (the
//! bridge's stiffnesses by 10-20 %, its amplification by 8 %), where an additive one would
//! change with every stiffness. The parts of a maximum ([`Model::max_of`]) take the
//! factor of the maximum, so a stress limit split into its places is corrected as a whole.
//!
//! It is physics alone: the refinement puts it in place of the analytic model's physics in
//! the same [`crate::model::Mechanism`], whose pictures and part stay the analytic model's.

use std::sync::Arc;

use super::Correction;
use crate::model::material::Material;
use crate::model::mechanism::ModulusScaling;
use crate::model::{Model, OutputInfo, ParameterInfo};

/// The analytic model `inner` with `corrections` (by output index) applied.
#[derive(Debug)]
pub struct Corrected {
    pub inner: Arc<dyn Model>,
    /// The correction of each output of `inner`, if it has one.
    pub by_output: Vec<Option<Correction>>,
}

impl Corrected {
    /// `inner` with `corrections` (output index, correction); each maximum's parts get its
    /// correction too.
    pub fn new(inner: Arc<dyn Model>, corrections: &[(usize, Correction)]) -> Self {
        let mut by_output: Vec<Option<Correction>> = vec![None; inner.outputs().len()];
        for (o, c) in corrections {
            by_output[*o] = Some(c.clone());
            for &part in inner.max_of(*o).unwrap_or(&[]) {
                by_output[part] = Some(c.clone());
            }
        }
        Corrected { inner, by_output }
    }
}

impl Model for Corrected {
    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn parameters(&self) -> &[ParameterInfo] {
        self.inner.parameters()
    }
    fn outputs(&self) -> &[OutputInfo] {
        self.inner.outputs()
    }

    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        self.inner.evaluate(x, wanted, out);
        for (v, &o) in out.iter_mut().zip(wanted) {
            if let Some(c) = &self.by_output[o] {
                *v *= c.factor(x);
            }
        }
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        self.inner.evaluate_with_gradient(x, wanted, out, jacobian);
        let n = x.len();
        for (k, (v, &o)) in out.iter_mut().zip(wanted).enumerate() {
            if let Some(c) = &self.by_output[o] {
                // d(a f)/dx = f da/dx + a df/dx, df/dx = h
                let f = c.factor(x);
                for (j, dj) in jacobian[k * n..(k + 1) * n].iter_mut().enumerate() {
                    *dj = f * *dj + *v * c.slope[j];
                }
                *v *= f;
            }
        }
    }

    fn domain_error(&self, x: &[f64]) -> Option<String> {
        self.inner.domain_error(x)
    }
    fn box_error(&self, lower: &[f64], upper: &[f64]) -> Option<(usize, String)> {
        self.inner.box_error(lower, upper)
    }
    fn max_of(&self, output: usize) -> Option<&[usize]> {
        self.inner.max_of(output)
    }
    fn unavailable(&self, output: usize) -> Option<String> {
        self.inner.unavailable(output)
    }
    fn material(&self) -> Option<&Material> {
        self.inner.material()
    }
    fn angle_limit(&self) -> Option<f64> {
        self.inner.angle_limit()
    }
    fn fit_limits(&self) -> &[crate::model::fit::FitLimit] {
        self.inner.fit_limits()
    }
    /// None: the correction's slope runs across the design space, so a design and its
    /// mirror image are corrected by different factors.
    fn mirror(&self, _x: &mut [f64]) -> bool {
        false
    }
}

/// A corrected model under the tolerances (a robust refinement's surrogate): the analytic
/// model's spread scaled by the correction's factor at the design. The factor is the
/// model's error on the part, which a machining error of microns does not move: it is held
/// at the nominal design's value while the tolerances vary the inputs, so an output's
/// first-order spread is `f(x) sigma_a(x)`, and the "Hessian" this gives is the derivative
/// by the design `x_p` of each input derivative `f g_j`, `f H_jp + g_j h_p` (`h` the
/// factor's slope), which is what the spreads' gradients read
/// ([`crate::problem::nlp`]'s `Spreads`).
#[derive(Debug)]
pub struct CorrectedScaling {
    pub inner: Arc<dyn ModulusScaling>,
    pub by_output: Vec<Option<Correction>>,
}

impl CorrectedScaling {
    /// The scaling of `corrected`'s outputs, `inner` its analytic model's.
    pub fn new(inner: Arc<dyn ModulusScaling>, corrected: &Corrected) -> Self {
        CorrectedScaling {
            inner,
            by_output: corrected.by_output.clone(),
        }
    }
}

impl ModulusScaling for CorrectedScaling {
    fn evaluate_scaled(&self, x: &[f64], modulus: f64, wanted: &[usize], out: &mut [f64]) {
        self.inner.evaluate_scaled(x, modulus, wanted, out);
        for (v, &o) in out.iter_mut().zip(wanted) {
            if let Some(c) = &self.by_output[o] {
                *v *= c.factor(x);
            }
        }
    }

    fn evaluate_scaled_with_gradient(
        &self,
        x: &[f64],
        modulus: f64,
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        self.inner
            .evaluate_scaled_with_gradient(x, modulus, wanted, out, jacobian);
        let n = x.len() + 1;
        for (k, (v, &o)) in out.iter_mut().zip(wanted).enumerate() {
            if let Some(c) = &self.by_output[o] {
                let f = c.factor(x);
                *v *= f;
                for d in &mut jacobian[k * n..(k + 1) * n] {
                    *d *= f;
                }
            }
        }
    }

    fn evaluate_with_hessian(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        self.inner
            .evaluate_with_hessian(x, wanted, out, jacobian, hessian);
        let (np, n) = (x.len(), x.len() + 1);
        for (k, (v, &o)) in out.iter_mut().zip(wanted).enumerate() {
            let Some(c) = &self.by_output[o] else {
                continue;
            };
            let f = c.factor(x);
            *v *= f;
            let g = &mut jacobian[k * n..(k + 1) * n];
            let h = &mut hessian[k * n * n..(k + 1) * n * n];
            for j in 0..n {
                for p in 0..n {
                    // the slope runs over the design's parameters, not the modulus's factor
                    let slope = if p < np { c.slope[p] } else { 0.0 };
                    h[j * n + p] = f * h[j * n + p] + g[j] * slope;
                }
            }
            for d in g.iter_mut() {
                *d *= f;
            }
        }
    }
}
