//! The right-elliptical notch: semi-axes `a` (along) and `b` (across), least thickness
//! `t`; `2 a` long, `t + 2 b` thick at its ends.

use super::{dim, from_moments, positive, FitRatio, Kind};
use crate::model::fit::FitRange;
use crate::model::hinge::integrals::{self, Span};
use crate::model::hinge::profile::bulge_through;
use crate::model::hinge::{Compliance, HingeDimension};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

/// A right-elliptical notch hinge.
#[derive(Debug, Clone, Copy)]
pub struct Elliptical;

impl Kind for Elliptical {
    const NAME: &'static str = "elliptical";
    const DIMENSIONS: &'static [HingeDimension] = &[
        dim("a", "notch semi-axis along the hinge"),
        dim("b", "notch semi-axis across the hinge"),
        dim("t", "least thickness"),
    ];
    /// No deeper than long (`b/a <= 1`: beyond it plane sections fail and the beam model
    /// is 12 to 24 % too stiff against the single-hinge FE), and the circular notch's
    /// range of least thickness over depth.
    const FIT: &'static [FitRatio] = &[
        FitRatio {
            numerator: 1,
            denominator: 0,
            range: FitRange {
                lower: None,
                upper: Some(1.0),
                holds: "the notch's beam model",
                source: "S. T. Smith, V. G. Badami, J. S. Dale and Y. Xu, Rev. Sci. \
                         Instrum. 68 (1997) 1474, elliptical hinges; beyond b/a = 1 the \
                         single-hinge FE finds the beam model 18 to 36 % too stiff",
            },
        },
        FitRatio {
            numerator: 2,
            denominator: 1,
            range: FitRange {
                lower: None,
                upper: Some(1.0),
                holds: "the notch's beam model and its K_t fit",
                source: "the circular notch's t/r, which it is at a = b",
            },
        },
    ];
    /// `b/a` at most 2 / 2 = 1 and `t/b` at most 0.5 / 0.5 = 1 over the whole box.
    const START: &'static [(f64, f64)] = &[(2.0, 10.0), (0.5, 2.0), (0.1, 0.5)];

    fn length<D: Scalar>(&self, dims: &[D]) -> D {
        dims[0] * 2.0
    }

    fn least_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[2]
    }

    fn root_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[2] + dims[1] * 2.0
    }

    fn area<D: Scalar>(&self, dims: &[D]) -> D {
        let pi = std::f64::consts::PI;
        let (a, b, t) = (dims[0], dims[1], dims[2]);
        a * 2.0 * (t + b * 2.0) - a * b * pi
    }

    fn domain_error(&self, dims: &[f64], names: &[&str]) -> Option<String> {
        positive(dims, names, 0)
            .or_else(|| positive(dims, names, 1))
            .or_else(|| positive(dims, names, 2))
    }

    /// The exact integrals of [`integrals`].
    fn compliance<D: Scalar>(&self, dims: &[D], width: f64, material: &Material) -> Compliance<D> {
        let (a, b, t) = (dims[0], dims[1], dims[2]);
        from_moments(integrals::arc(t, b, a, a, Span::Whole), width, material)
    }

    /// The circular notch's fit (Smith's, [`super::Circular`]) with the radius of curvature
    /// at the notch's root, `rho = a^2 / b`, for `r`: `K_t = (1 + t b / (2 a^2))^(9/20)`;
    /// our extension, within 1 % of the FE of the single hinge over the table's grid.
    fn stress_concentration<D: Scalar>(&self, dims: &[D]) -> D {
        let (a, b, t) = (dims[0], dims[1], dims[2]);
        (t * b / (a * a * 2.0) + 1.0).powf(0.45)
    }

    fn thickness_along<D: Scalar>(&self, dims: &[D], xi: D) -> D {
        notch_thickness(dims[2], dims[1], xi)
    }

    /// An ellipse, which no circular arc draws: a chain of 12 arcs, each through three of
    /// 25 points of the ellipse: within 3e-4 of the larger semi-axis of it for aspect ratios
    /// from 1/4 to 4 (1.3 um on a notch 4 mm long), a tenth of a wire EDM's tolerance.
    fn outline(&self, dims: &[f64]) -> Vec<[f64; 3]> {
        let root = 0.5 * self.root_thickness(dims);
        let (a, b, t) = (dims[0], dims[1], dims[2]);
        let n = 24;
        let point = |k: usize| {
            let phi = std::f64::consts::PI * (1.0 + k as f64 / n as f64);
            [a + a * phi.cos(), 0.5 * t + b + b * phi.sin()]
        };
        let mut out = Vec::with_capacity(n / 2 + 1);
        for k in (0..n).step_by(2) {
            let (p, m, q) = (point(k), point(k + 1), point(k + 2));
            out.push([p[0], p[1], bulge_through(p, m, q)]);
        }
        out.push([2.0 * a, root, 0.0]);
        out
    }

    fn length_label(&self, first: String) -> String {
        format!("2 {first}")
    }
}

/// The thickness of a notch of least thickness `t` and depth `b` from each side (an
/// ellipse's semi-axis across, a circle's radius) at the fraction `xi` of its length.
pub(super) fn notch_thickness<D: Scalar>(t: D, b: D, xi: D) -> D {
    let u = xi * 2.0 - 1.0;
    // at u from the middle: 1 - sqrt(1 - u^2)
    let inside = (D::from(1.0) - u * u).re().max(0.0);
    let root = if inside > 0.0 {
        (D::from(1.0) - u * u).sqrt()
    } else {
        D::from(0.0)
    };
    t + b * (D::from(1.0) - root) * 2.0
}
