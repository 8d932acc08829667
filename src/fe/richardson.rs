//! The discretization error of an output from its values on a sequence of uniformly refined
//! meshes (element size halved each time), by Richardson extrapolation with the observed
//! order: with `f0, f1, f2` the last three values, `p = log2(|f1 - f0| / |f2 - f1|)` and the
//! error of `f2` estimated as `|f2 - f1| / (2^p - 1)` (Roache, "Quantification of
//! uncertainty in computational fluid dynamics", Annu. Rev. Fluid Mech. 29, 1997, Eq. 4-6;
//! the grid convergence index without its safety factor).
//!
//! An output converges when its differences shrink by at least `sqrt(2)` a level (observed
//! order above 1/2): the stress at a sharp re-entrant corner, singular in elasticity, grows
//! as the mesh is refined and is reported as not converging, never extrapolated.

use serde::Serialize;

/// What the sequence says of an output's finest value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The value on the finest mesh.
    pub value: f64,
    /// The extrapolated value (the finest plus its estimated error), where it converges.
    pub extrapolated: Option<f64>,
    /// The estimated relative error of `value`, where it converges.
    pub relative_error: Option<f64>,
    /// The observed order of convergence, where it converges.
    pub order: Option<f64>,
    pub converging: bool,
}

/// The order is capped: differences at rounding level give absurd orders.
const MAX_ORDER: f64 = 8.0;

/// The estimate from `values`, coarsest first (at least three for an error estimate).
pub fn estimate(values: &[f64]) -> Estimate {
    let n = values.len();
    let value = values[n - 1];
    let none = Estimate {
        value,
        extrapolated: None,
        relative_error: None,
        order: None,
        converging: false,
    };
    if n < 3 || values.iter().any(|v| !v.is_finite()) {
        return none;
    }
    let (d1, d2) = (values[n - 2] - values[n - 3], value - values[n - 2]);
    let scale = value.abs().max(f64::MIN_POSITIVE);
    if d2.abs() <= 1e-13 * scale {
        // settled to rounding
        return Estimate {
            extrapolated: Some(value),
            relative_error: Some(d2.abs() / scale),
            order: Some(MAX_ORDER),
            converging: true,
            ..none
        };
    }
    let ratio = d1.abs() / d2.abs();
    if ratio < std::f64::consts::SQRT_2 {
        return none;
    }
    let p = ratio.log2().min(MAX_ORDER);
    let error = d2 / (2f64.powf(p) - 1.0);
    Estimate {
        value,
        extrapolated: Some(value + error),
        relative_error: Some(error.abs() / scale),
        order: Some(p),
        converging: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sequence_of_known_order_is_extrapolated_to_its_limit() {
        // f(h) = 2 + 3 h^3 at h = 1, 1/2, 1/4
        let f = |h: f64| 2.0 + 3.0 * h.powi(3);
        let e = estimate(&[f(1.0), f(0.5), f(0.25)]);
        assert!((e.order.unwrap() - 3.0).abs() < 1e-12);
        assert!((e.extrapolated.unwrap() - 2.0).abs() < 1e-12);
        assert!((e.relative_error.unwrap() - 3.0 * 0.25f64.powi(3) / f(0.25)).abs() < 1e-12);
    }

    #[test]
    fn a_growing_peak_does_not_converge() {
        // a singular stress: f(h) = h^-0.45
        let f = |h: f64| h.powf(-0.45);
        let e = estimate(&[f(1.0), f(0.5), f(0.25)]);
        assert!(!e.converging && e.relative_error.is_none());
    }
}
