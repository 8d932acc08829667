//! Flexure-hinge compliances and section stresses.
//!
//! A hinge is a short elastic beam clamped at one end. With a force `N` along its axis,
//! a transverse force `V` and a moment `M` at the free end (in the hinge's own frame,
//! `V` and `M` taken so that `c23 > 0`), the free end moves by
//!
//! ```text
//! u     = c11 N
//! v     = c22 V + c23 M
//! theta = c32 V + c33 M          (paper 004, Eq. 1; c32 = c23)
//! ```
//!
//! The bridge model only ever asks a hinge for these four coefficients and for the
//! largest stress under given end loads, so a new hinge kind (a circular or elliptical
//! notch, say) is a new [`HingeKind`] variant here and nothing else.

use serde::Serialize;

use super::material::Material;
use super::scalar::{max, Scalar};

/// The compliance coefficients of one hinge (paper 004, Eq. 1), SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compliance<D> {
    /// Axial compliance (m/N).
    pub c11: D,
    /// Transverse deflection per transverse force, bending and shear (m/N).
    pub c22: D,
    /// Deflection per moment, equal to slope per transverse force (1/N).
    pub c23: D,
    /// Slope per moment (1/(N m)).
    pub c33: D,
}

/// The kinds of flexure hinge flexopt models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum HingeKind {
    /// A leaf (strip) hinge: a straight beam of constant rectangular section.
    Strip,
}

impl HingeKind {
    /// The names a problem file uses.
    pub const NAMES: &'static [&'static str] = &["strip"];

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "strip" => Some(HingeKind::Strip),
            _ => None,
        }
    }

    /// Compliance of a hinge of `length` and `thickness` (m), of section width `width` (m).
    ///
    /// Strip hinge, paper 004 Eq. 2 (Timoshenko cantilever, shear factor taken as 1 as
    /// the paper does):
    ///
    /// ```text
    /// c11 = l / (E w t)
    /// c22 = 4 l^3 / (E w t^3) + l / (G w t)
    /// c23 = c32 = 6 l^2 / (E w t^3)
    /// c33 = 12 l / (E w t^3)
    /// ```
    pub fn compliance<D: Scalar>(
        self,
        length: D,
        thickness: D,
        width: f64,
        material: &Material,
    ) -> Compliance<D> {
        match self {
            HingeKind::Strip => {
                // one division: every coefficient is a multiple of 1 / (E w t^3)
                let e = material.youngs_modulus;
                let inv = (thickness * thickness * thickness * (e * width)).recip();
                let l_inv = length * inv;
                let t2 = thickness * thickness;
                Compliance {
                    c11: l_inv * t2,
                    // E / G = 2 (1 + nu)
                    c22: l_inv
                        * (length * length * 4.0 + t2 * (2.0 * (1.0 + material.poisson_ratio))),
                    c23: l_inv * length * 6.0,
                    c33: l_inv * 12.0,
                }
            }
        }
    }

    /// The largest normal stress (Pa) at the two ends of the hinge, `(loaded end, clamped
    /// end)`, under the end loads that hold its free end: axial force `axial`, transverse
    /// force `shear` and moment `moment` there.
    ///
    /// Strip hinge, paper 004 Eq. 15-16: the moment varies linearly along the hinge,
    /// `M(x) = M + V x` for `x` in `[0, l]` measured from the loaded end, so the extreme
    /// fibre stress `6 |M(x)| / (w t^2) + |N| / (w t)` is largest at one of the two ends.
    pub fn end_stresses<D: Scalar>(
        self,
        length: D,
        thickness: D,
        width: f64,
        loads: &HingeLoads<D>,
    ) -> (D, D) {
        match self {
            HingeKind::Strip => {
                let moment_far = loads.moment + loads.shear * length;
                let inv_wt = (thickness * width).recip();
                let bending = inv_wt * (6.0 * width);
                let axial = loads.axial.abs();
                (
                    (loads.moment.abs() * bending + axial) * inv_wt,
                    (moment_far.abs() * bending + axial) * inv_wt,
                )
            }
        }
    }

    /// The largest normal stress in the hinge (Pa): the larger of [`HingeKind::end_stresses`].
    pub fn max_stress<D: Scalar>(
        self,
        length: D,
        thickness: D,
        width: f64,
        loads: &HingeLoads<D>,
    ) -> D {
        let (near, far) = self.end_stresses(length, thickness, width, loads);
        max(near, far)
    }
}

/// The loads at the free end of a hinge (paper 004, Eq. 3-6), SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HingeLoads<D> {
    /// Axial force N (N).
    pub axial: D,
    /// Transverse force V (N).
    pub shear: D,
    /// Bending moment M (N m).
    pub moment: D,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_compliances_obey_beam_identities_without_shear() {
        // With the shear term removed, Euler-Bernoulli gives c33 = 3 c22 / l^2 and
        // c23 = 6 c22 / (4 l): the identities paper 004 uses to reach Eq. 25.
        let mat = Material::al7075_t6();
        let (l, t, w) = (2e-3, 0.4e-3, 10e-3);
        let c = HingeKind::Strip.compliance(l, t, w, &mat);
        let c22_bending = c.c22 - l / (mat.shear_modulus() * w * t);
        assert!((c.c33 - 3.0 * c22_bending / (l * l)).abs() <= 1e-12 * c.c33);
        assert!((c.c23 - 6.0 * c22_bending / (4.0 * l)).abs() <= 1e-12 * c.c23);
    }

    #[test]
    fn strip_stress_is_largest_at_the_clamped_end_of_a_cantilever() {
        // A cantilever with only a tip force V: M(0) = 0, M(l) = V l.
        let (l, t, w) = (2e-3, 0.5e-3, 10e-3);
        let loads = HingeLoads {
            axial: 0.0,
            shear: 3.0,
            moment: 0.0,
        };
        let s = HingeKind::Strip.max_stress(l, t, w, &loads);
        assert!((s - 6.0 * 3.0 * l / (w * t * t)).abs() < 1e-6);
    }
}
