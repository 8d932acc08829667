//! The discretization error of an output from its values on a sequence of uniformly refined
//! meshes (element size halved each time), by Richardson extrapolation with the observed
//! order: with `f0, f1, f2` the last three values, `p = log2(|f1 - f0| / |f2 - f1|)` and the
//! error of `f2` estimated as `|f2 - f1| / (2^p - 1)` (Roache, "Quantification of
//! uncertainty in computational fluid dynamics", Annu. Rev. Fluid Mech. 29, 1997, Eq. 4-6;
//! the grid convergence index without its safety factor).
//!
//! The extrapolation holds only in the asymptotic range, which the sequence must show before
//! it is believed (Roache 1997, Sec. 3.3: the observed order near the formal one, the
//! differences of one sign): an output converges when its last two differences have one sign
//! and shrink by a factor between `sqrt(2)` and `2^6` (observed order 1/2 to 6; the six-node
//! triangle's stiffnesses converge as h^4 at best, h^1 to h^2 near re-entrant corners).
//! Otherwise no extrapolation is made and the error quoted is the spread of the last three
//! values, relative:
//! - a sequence that turns (153.1 -> 156.2 -> 155.7) oscillates about its limit: its spread
//!   bounds the error, and an output within its tolerance by its spread is accepted;
//! - a sequence whose differences shrink too slowly (a stress at a sharp re-entrant corner,
//!   singular in elasticity, grows as the mesh is refined) or suspiciously fast (a difference
//!   that nearly vanished by chance, as a sequence crosses its limit) is not converging: its
//!   spread is quoted, as a lower bound, and never accepted.

use serde::Serialize;

/// What the sequence says of an output's finest value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The value on the finest mesh.
    pub value: f64,
    /// The extrapolated value (the finest plus its estimated error), where it converges.
    pub extrapolated: Option<f64>,
    /// The relative error to quote: the extrapolation's where the output converges, the
    /// spread of the last three values where it does not (none with fewer than two values).
    pub relative_error: Option<f64>,
    /// The observed order of convergence, where it converges.
    pub order: Option<f64>,
    pub converging: bool,
    /// The last differences change sign: the spread bounds the error.
    pub oscillating: bool,
}

impl Estimate {
    /// The error is known to lie within `tolerance` (relative): by the extrapolation, or by
    /// the spread of a sequence that oscillates.
    pub fn within(&self, tolerance: f64) -> bool {
        (self.converging || self.oscillating) && self.relative_error.is_some_and(|e| e <= tolerance)
    }
}

/// The order is capped: differences at rounding level give absurd orders.
const MAX_ORDER: f64 = 8.0;
/// The largest observed order believed: beyond it a difference vanished by chance.
const MAX_BELIEVED_ORDER: f64 = 6.0;

/// The estimate from `values`, coarsest first (at least three for an error estimate).
pub fn estimate(values: &[f64]) -> Estimate {
    let n = values.len();
    let value = values[n - 1];
    let scale = value.abs().max(f64::MIN_POSITIVE);
    let finite = values.iter().all(|v| v.is_finite());
    let last = &values[n.saturating_sub(3)..];
    let spread = (finite && n >= 2).then(|| {
        let (lo, hi) = last
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        (hi - lo) / scale
    });
    let none = Estimate {
        value,
        extrapolated: None,
        relative_error: spread,
        order: None,
        converging: false,
        oscillating: false,
    };
    if n < 3 || !finite {
        return none;
    }
    let (d1, d2) = (values[n - 2] - values[n - 3], value - values[n - 2]);
    if d2.abs() <= 1e-13 * scale && d1.abs() <= 1e-10 * scale {
        // settled to rounding
        return Estimate {
            extrapolated: Some(value),
            relative_error: Some(d2.abs() / scale),
            order: Some(MAX_ORDER),
            converging: true,
            ..none
        };
    }
    if d1 * d2 < 0.0 {
        return Estimate {
            oscillating: true,
            ..none
        };
    }
    let ratio = d1.abs() / d2.abs();
    if !(std::f64::consts::SQRT_2..=2f64.powf(MAX_BELIEVED_ORDER)).contains(&ratio) {
        return none;
    }
    let p = ratio.log2();
    let error = d2 / (2f64.powf(p) - 1.0);
    Estimate {
        value,
        extrapolated: Some(value + error),
        relative_error: Some(error.abs() / scale),
        order: Some(p),
        converging: true,
        oscillating: false,
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
        assert!(!e.converging && !e.oscillating && !e.within(1.0));
        // its spread is quoted, not an extrapolation
        let spread = (f(0.25) - f(1.0)) / f(0.25);
        assert!((e.relative_error.unwrap() - spread).abs() < 1e-15 && e.extrapolated.is_none());
    }

    #[test]
    fn a_sequence_that_turns_quotes_its_spread() {
        // the plane-stress peak stress of wei2017's optimum before the estimate was honest:
        // quoted then as +-0.07 %
        let e = estimate(&[153.1, 156.2, 155.7]);
        assert!(!e.converging && e.oscillating && e.extrapolated.is_none());
        assert!((e.relative_error.unwrap() - 3.1 / 155.7).abs() < 1e-15);
        assert!(!e.within(0.005) && e.within(0.02));
    }

    #[test]
    fn a_difference_vanishing_by_chance_is_not_believed() {
        // differences 1 then 1e-3 (order 10): the sequence crossed its limit, say
        let e = estimate(&[100.0, 101.0, 101.001]);
        assert!(!e.converging && !e.within(0.005));
        assert!((e.relative_error.unwrap() - 1.001 / 101.001).abs() < 1e-15);
        // order 6 still is
        let e = estimate(&[100.0, 101.0, 101.0 + 1.0 / 63.0]);
        assert!(e.converging && (e.order.unwrap() - 63f64.log2()).abs() < 1e-9);
    }
}
