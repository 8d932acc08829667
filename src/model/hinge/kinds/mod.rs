//! The rooms of the hinge kinds: each kind a unit struct implementing [`Kind`] in a file of
//! its own, with its name, its dimensions, its formulas and what the part asks of it, so that
//! everything a kind is sits in one place and [`super::HingeKind`] only dispatches to it.

mod circular;
mod corner_filleted;
mod elliptical;
mod strip;

pub use circular::Circular;
pub use corner_filleted::CornerFilleted;
pub use elliptical::Elliptical;
pub use strip::Strip;

use super::integrals::Moments;
use super::profile::beam_stress_max;
use super::{Compliance, HingeDimension, HingeLoads};
use crate::model::fit::FitRange;
use crate::model::material::Material;
use crate::model::scalar::Scalar;
use crate::model::Dimension;

/// A compliance and its partial derivatives by each of the hinge's dimensions
/// ([`Kind::compliance_partials`]).
pub type CompliancePartials = (
    Compliance<f64>,
    [Compliance<f64>; super::MAX_HINGE_DIMENSIONS],
);

/// A dimension of a kind, a length: `stem` names it (after the hinge in a mechanism, as a
/// flag of `flexopt hinge`), `description` says what it is in both places.
pub(super) const fn dim(stem: &'static str, description: &'static str) -> HingeDimension {
    HingeDimension {
        stem,
        dimension: Dimension::Length,
        description,
    }
}

/// A ratio of two of a kind's dimensions, `numerator / denominator` (indices into
/// [`Kind::DIMENSIONS`]), and the range within which the kind's formulas hold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitRatio {
    pub numerator: usize,
    pub denominator: usize,
    pub range: FitRange,
}

/// What a hinge kind is. Dimensions are SI (m) unless said otherwise, in the order of
/// [`Kind::DIMENSIONS`]; the methods are generic over the scalar so that the optimizer's
/// gradients run through the very formulas the reports print.
pub trait Kind: Sized {
    /// The name problem files and the command line use.
    const NAME: &'static str;
    /// The kind's dimensions, in the order its functions take them; the first is the one
    /// that sets its length along the centre line (a strip's length, a circular notch's
    /// radius), which the bridge lays out as paper 004 lays out a strip's length.
    const DIMENSIONS: &'static [HingeDimension];
    /// Where the kind's formulas hold: ranges of ratios of its dimensions, each with the
    /// source that fitted or checked the formula. The guide's table of them is made from
    /// these (`flexopt::model::hinge::fit_table`), and the study keeps a design inside them
    /// unless the problem file says otherwise.
    const FIT: &'static [FitRatio];
    /// The bounds (mm) `flexopt init --hinge` gives each dimension, in the order of
    /// [`Kind::DIMENSIONS`]: sizes a wire-EDM part of a few centimetres has, with the box
    /// inside [`Kind::FIT`] wherever the kind's ranges allow it (a test holds them to it).
    const START: &'static [(f64, f64)];

    /// The length of the hinge along its centre line (m).
    fn length<D: Scalar>(&self, dims: &[D]) -> D;

    /// The least thickness (m), where the hinge bends most.
    fn least_thickness<D: Scalar>(&self, dims: &[D]) -> D;

    /// The hinge's thickness where it meets the rigid bodies (m): the width of the faces
    /// its part's outline attaches to.
    fn root_thickness<D: Scalar>(&self, dims: &[D]) -> D;

    /// The hinge's area in the plane of the mechanism (m^2), for its mass.
    fn area<D: Scalar>(&self, dims: &[D]) -> D;

    /// Why `dims` make no hinge of this kind, if they do not; `names` are the dimensions'
    /// names in the mechanism (`l2`, `t2`) or on the command line (`--l`).
    fn domain_error(&self, dims: &[f64], names: &[&str]) -> Option<String>;

    /// Why some dimensions between `lower` and `upper` make no hinge of this kind though
    /// each bound is valid: the index of the dimension to blame and the reason. Only a kind
    /// whose dimensions constrain each other has one.
    fn box_error(
        &self,
        _lower: &[f64],
        _upper: &[f64],
        _names: &[&str],
    ) -> Option<(usize, String)> {
        None
    }

    /// The compliance coefficients (paper 004, Eq. 1) at section width `width` (m).
    fn compliance<D: Scalar>(&self, dims: &[D], width: f64, material: &Material) -> Compliance<D>;

    /// [`Kind::compliance`] over `f64` and its partial derivatives by each dimension (the
    /// entries past the kind's count unused), where the kind has them in closed form: a
    /// dual number's tangent is then the chain rule over them ([`Scalar::from_partials`]),
    /// not the formula's every operation over the dual number. `None`: the caller takes
    /// [`Kind::compliance`] over its own scalar.
    fn compliance_partials(
        &self,
        _dims: &[f64],
        _width: f64,
        _material: &Material,
    ) -> Option<CompliancePartials> {
        None
    }

    /// The factor by which the largest surface stress exceeds the beam stress at the
    /// thinnest section in bending, `K_t`.
    fn stress_concentration<D: Scalar>(&self, dims: &[D]) -> D;

    /// The largest normal stress (Pa) at the two ends of the hinge, `(loaded end, clamped
    /// end)`, under the end loads that hold its free end.
    ///
    /// A notch: the beam stress, largest near its thinnest section, found along it
    /// ([`beam_stress_max`]), times the notch's stress concentration
    /// ([`Kind::stress_concentration`]), which the finite-element check of the single hinge
    /// measures (the README's accuracy table).
    fn end_stresses<D: Scalar>(&self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> (D, D) {
        // one peak, near the thinnest section: the same value for both ends, so that
        // an optimizer bounding both sees one constraint twice rather than two
        // nearly equal ones where the peak crosses the middle
        let peak =
            beam_stress_max(self, dims, width, loads, 0.0, 1.0) * self.stress_concentration(dims);
        (peak, peak)
    }

    /// The thickness at the fraction `xi` of the hinge's length (0 and 1 its ends), the
    /// place a scalar too (for its derivative along the hinge).
    fn thickness_along<D: Scalar>(&self, dims: &[D], xi: D) -> D;

    /// The hinge's outline above its centre line, in its own frame (x along the hinge from
    /// its start, y across, mm or m as `dims`): vertices `(x, y, bulge)` from `(0, root/2)`
    /// to `(length, root/2)`, each arc to the next vertex as a bulge (the tangent of a
    /// quarter of its angle, positive counterclockwise).
    fn outline(&self, dims: &[f64]) -> Vec<[f64; 3]>;

    /// Part rule: the hinge meets its bodies at sharp inner corners, which the part's
    /// fillets round (and which wire EDM cannot cut without them); a notch meets them
    /// smoothly.
    fn has_sharp_roots(&self) -> bool {
        false
    }

    /// Part rule: how the drawing names the hinge's length, given the name of its first
    /// dimension (`l2`); a notch's length is twice its first dimension.
    fn length_label(&self, first: String) -> String {
        first
    }
}

/// Why dimension `k` is not positive, if it is not.
pub(super) fn positive(dims: &[f64], names: &[&str], k: usize) -> Option<String> {
    (dims[k] <= 0.0).then(|| {
        format!(
            "{} = {} m is not positive",
            names[k],
            crate::vocab::units::short(dims[k])
        )
    })
}

/// The compliances of a hinge of varying thickness from its profile's moments
/// ([`super::integrals`]), Castigliano's integrals with paper 004's shear factor 1.
pub(super) fn from_moments<D: Scalar>(
    moments: Moments<D>,
    width: f64,
    material: &Material,
) -> Compliance<D> {
    let e = material.youngs_modulus;
    let ew = e * width;
    // E / G = 2 (1 + nu)
    let shear = 2.0 * (1.0 + material.poisson_ratio);
    Compliance {
        c11: moments.i0 / ew,
        c22: (moments.i3[2] * 12.0 + moments.i0 * shear) / ew,
        c23: moments.i3[1] * 12.0 / ew,
        c33: moments.i3[0] * 12.0 / ew,
    }
}
