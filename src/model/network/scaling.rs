//! The network at other moduli ([`ModulusScaling`]): every flexure's compliance divided by
//! the factor on `E` and `G` (its hinges' and beams' alike, each `Compliance::with_modulus`
//! where it is joined, [`NetworkModel::evaluate_generic`]'s `modulus`), the masses and the
//! actuator's stack kept. So the stiffnesses scale with the factor, the frequencies with its
//! square root, and an amplification, which is a ratio of compliances, not at all, but for
//! a stack of finite stiffness, against which the mechanism's share of the stroke moves.
//!
//! The plain evaluation passes no modulus, so it pays nothing for this one.

use super::model::NetworkModel;
use crate::model::jet2::{seeded_with_modulus, unseed2, Jet2};
use crate::model::mechanism::ModulusScaling;
use crate::model::scalar::{with_count, Jet};
use crate::model::{unseed, Model};

impl NetworkModel {
    /// Values and gradients of the outputs `wanted` at `x` and the moduli `modulus` times
    /// the nominal ones, with `N` = the number of parameters plus one, the modulus last.
    fn scaled_gradients<const N: usize>(
        &self,
        x: &[f64],
        modulus: f64,
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let seeded: [Jet<N>; N] =
            std::array::from_fn(|i| Jet::variable(if i + 1 < N { x[i] } else { modulus }, i));
        let mut y = vec![Jet::<N>::from(0.0); wanted.len()];
        let (x, m) = seeded.split_at(N - 1);
        if self.evaluate_generic(x, Some(m[0]), wanted, &mut y).is_ok() {
            unseed(&y, out, jacobian);
        } else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
        }
    }

    /// Values, gradients and Hessians of the outputs `wanted` at `x` and the nominal moduli,
    /// with `N` = the number of parameters plus one, the modulus last.
    fn hessians<const N: usize>(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        let seeded = seeded_with_modulus::<N>(x);
        let mut y = vec![Jet2::<N>::from(0.0); wanted.len()];
        let (x, m) = seeded.split_at(N - 1);
        if self.evaluate_generic(x, Some(m[0]), wanted, &mut y).is_ok() {
            unseed2(&y, out, jacobian, hessian);
        } else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
            hessian.fill(f64::NAN);
        }
    }
}

impl ModulusScaling for NetworkModel {
    fn first_order_only(&self, output: usize) -> Option<String> {
        self.at_stroke_output(output).then(|| {
            format!(
                "output \"{}\" is at the working stroke, whose solve gives first derivatives \
                 only: a robust study, which needs second derivatives, cannot use it",
                self.outputs()[output].name
            )
        })
    }

    fn evaluate_scaled(&self, x: &[f64], modulus: f64, wanted: &[usize], out: &mut [f64]) {
        if self
            .evaluate_generic(x, Some(modulus), wanted, out)
            .is_err()
        {
            out.fill(f64::NAN);
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
        with_count!(x.len(), |N| self
            .scaled_gradients::<{ N + 1 }>(x, modulus, wanted, out, jacobian))
    }

    fn evaluate_with_hessian(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        with_count!(x.len(), |N| self
            .hessians::<{ N + 1 }>(x, wanted, out, jacobian, hessian))
    }
}
