//! The right-circular notch: radius `r` from both sides, least thickness `t`; a bar
//! `t + 2 r` thick with two half circles cut out, `2 r` long.

use super::{dim, elliptical, from_moments, positive, FitRatio, Kind};
use crate::model::fit::FitRange;
use crate::model::hinge::integrals::{self, Span};
use crate::model::hinge::{Compliance, HingeDimension};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

/// A right-circular notch hinge.
#[derive(Debug, Clone, Copy)]
pub struct Circular;

impl Kind for Circular {
    const NAME: &'static str = "circular";
    const DIMENSIONS: &'static [HingeDimension] =
        &[dim("r", "notch radius"), dim("t", "least thickness")];
    /// A notch thin against its radius, as the literature's circular hinges are: beyond
    /// `t/r = 1` the notch is a shallow dent in a bar, the bar beside it bends as much as
    /// the notch does, and the mechanism's rigid links no longer hold.
    const FIT: &'static [FitRatio] = &[FitRatio {
        numerator: 1,
        denominator: 0,
        range: FitRange {
            lower: None,
            upper: Some(1.0),
            holds: "the notch's beam model and Smith's K_t fit",
            source: "Paros and Weisbord, Machine Design 37 (1965) 151, notches thin against \
                     their radius; K_t of S. T. Smith, Flexures (2000), fitted to Peterson's \
                     charts; the accuracy table's t/r from 0.05 to 1",
        },
    }];
    /// `t/r` at most 0.5 / 0.5 = 1 over the whole box; radii up to 3 mm keep the notch's
    /// root (`2 r + t`) within the default input block beside the actuator.
    const START: &'static [(f64, f64)] = &[(0.5, 3.0), (0.1, 0.5)];

    fn length<D: Scalar>(&self, dims: &[D]) -> D {
        dims[0] * 2.0
    }

    fn least_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1]
    }

    fn root_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1] + dims[0] * 2.0
    }

    fn area<D: Scalar>(&self, dims: &[D]) -> D {
        let pi = std::f64::consts::PI;
        let (r, t) = (dims[0], dims[1]);
        r * 2.0 * (t + r * 2.0) - r * r * pi
    }

    fn domain_error(&self, dims: &[f64], names: &[&str]) -> Option<String> {
        positive(dims, names, 0).or_else(|| positive(dims, names, 1))
    }

    /// The exact integrals of [`integrals`]: an elliptical notch with `a = b = r`.
    fn compliance<D: Scalar>(&self, dims: &[D], width: f64, material: &Material) -> Compliance<D> {
        let (r, t) = (dims[0], dims[1]);
        from_moments(integrals::arc(t, r, r, r, Span::Whole), width, material)
    }

    /// The fit to Peterson's charts that Smith gives for the right-circular notch hinge in
    /// bending (S. T. Smith, *Flexures: Elements of Elastic Mechanisms*, Gordon and Breach,
    /// 2000, its chapter on notch hinges): `K_t = (1 + t / (2 r))^(9/20)`.
    fn stress_concentration<D: Scalar>(&self, dims: &[D]) -> D {
        let (r, t) = (dims[0], dims[1]);
        (t / (r * 2.0) + 1.0).powf(0.45)
    }

    fn thickness_along<D: Scalar>(&self, dims: &[D], xi: D) -> D {
        elliptical::notch_thickness(dims[1], dims[0], xi)
    }

    /// A half circle below the chord, counterclockwise seen from its centre.
    fn outline(&self, dims: &[f64]) -> Vec<[f64; 3]> {
        let root = 0.5 * self.root_thickness(dims);
        vec![[0.0, root, 1.0], [2.0 * dims[0], root, 0.0]]
    }

    fn length_label(&self, first: String) -> String {
        format!("2 {first}")
    }
}
