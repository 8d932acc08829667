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
//! A mechanism asks a hinge for these four coefficients, the largest stress under given end
//! loads, its length along the centre line and its area, each from the hinge's own
//! dimensions ([`HingeKind::dimensions`]). A new hinge kind (a circular or elliptical notch,
//! say) is therefore a new [`HingeKind`] variant here, with its dimension table and its arms
//! of the functions below, and nothing else: the bridge names a kind's dimensions after the
//! hinge (`l2`, `t2` for hinge b, `l4`, `t4` for hinge d) and lays them out by itself.

use serde::Serialize;

use super::material::Material;
use super::scalar::{max, Scalar};
use super::Dimension;

/// The most dimensions a hinge kind has.
pub const MAX_HINGE_DIMENSIONS: usize = 3;

/// One dimension of a hinge kind; a mechanism names it `stem` followed by the hinge's
/// number (`t` of hinge b is the bridge's `t2`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HingeDimension {
    pub stem: &'static str,
    pub dimension: Dimension,
    pub description: &'static str,
}

/// A strip hinge's dimensions. The first of every kind is the one that sets its length
/// along the centre line (a strip's length, a circular notch's radius).
const STRIP: [HingeDimension; 2] = [
    HingeDimension {
        stem: "l",
        dimension: Dimension::Length,
        description: "length",
    },
    HingeDimension {
        stem: "t",
        dimension: Dimension::Length,
        description: "thickness",
    },
];

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

    /// The kind's dimensions, in the order its functions take them; the first is the one
    /// that sets the length along the centre line.
    pub fn dimensions(self) -> &'static [HingeDimension] {
        match self {
            HingeKind::Strip => &STRIP,
        }
    }

    /// The length of the hinge along its centre line (m).
    pub fn length<D: Scalar>(self, dims: &[D]) -> D {
        match self {
            HingeKind::Strip => dims[0],
        }
    }

    /// The hinge's thickness where it meets the rigid bodies (m): the width of the faces
    /// its part's outline attaches to, and of the fillets' corners.
    pub fn root_thickness(self, dims: &[f64]) -> f64 {
        match self {
            HingeKind::Strip => dims[1],
        }
    }

    /// The hinge's area in the plane of the mechanism (m^2), for its mass.
    pub fn area<D: Scalar>(self, dims: &[D]) -> D {
        match self {
            HingeKind::Strip => dims[0] * dims[1],
        }
    }

    /// Why `dims` (SI) make no hinge of this kind, if they do not; `names` are the
    /// dimensions' names in the mechanism (`l2`, `t2`). A length of zero is allowed: the
    /// mechanism then has no hinge there.
    pub fn domain_error(self, dims: &[f64], names: &[&str]) -> Option<String> {
        match self {
            HingeKind::Strip => {
                if dims[0] < 0.0 {
                    Some(format!("{} = {} m is negative", names[0], dims[0]))
                } else if dims[1] <= 0.0 {
                    Some(format!("{} = {} m is not positive", names[1], dims[1]))
                } else {
                    None
                }
            }
        }
    }

    /// Compliance of a hinge of dimensions `dims` (SI, in the order of
    /// [`HingeKind::dimensions`]) and section width `width` (m).
    ///
    /// Strip hinge of length `l` and thickness `t`, paper 004 Eq. 2 (Timoshenko cantilever,
    /// shear factor taken as 1 as the paper does):
    ///
    /// ```text
    /// c11 = l / (E w t)
    /// c22 = 4 l^3 / (E w t^3) + l / (G w t)
    /// c23 = c32 = 6 l^2 / (E w t^3)
    /// c33 = 12 l / (E w t^3)
    /// ```
    pub fn compliance<D: Scalar>(
        self,
        dims: &[D],
        width: f64,
        material: &Material,
    ) -> Compliance<D> {
        match self {
            HingeKind::Strip => {
                let (length, thickness) = (dims[0], dims[1]);
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
    pub fn end_stresses<D: Scalar>(self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> (D, D) {
        match self {
            HingeKind::Strip => {
                let (length, thickness) = (dims[0], dims[1]);
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
    pub fn max_stress<D: Scalar>(self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> D {
        let (near, far) = self.end_stresses(dims, width, loads);
        max(near, far)
    }
}

/// One hinge of a mechanism: its kind and its dimensions (SI, in the order of
/// [`HingeKind::dimensions`]; the entries past the kind's count are unused).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hinge<D> {
    pub kind: HingeKind,
    pub dims: [D; MAX_HINGE_DIMENSIONS],
}

impl<D: Scalar> Hinge<D> {
    /// A hinge of `kind` with the dimensions `dims`, in the kind's order.
    pub fn new(kind: HingeKind, dims: &[D]) -> Self {
        let mut all = [D::from(0.0); MAX_HINGE_DIMENSIONS];
        all[..dims.len()].copy_from_slice(dims);
        Hinge { kind, dims: all }
    }

    /// A strip hinge of `length` and `thickness`.
    pub fn strip(length: D, thickness: D) -> Self {
        Self::new(HingeKind::Strip, &[length, thickness])
    }

    /// The kind's dimensions.
    #[inline]
    pub fn dims(&self) -> &[D] {
        &self.dims[..self.kind.dimensions().len()]
    }

    #[inline]
    pub fn length(&self) -> D {
        self.kind.length(self.dims())
    }

    #[inline]
    pub fn area(&self) -> D {
        self.kind.area(self.dims())
    }

    #[inline]
    pub fn compliance(&self, width: f64, material: &Material) -> Compliance<D> {
        self.kind.compliance(self.dims(), width, material)
    }

    #[inline]
    pub fn end_stresses(&self, width: f64, loads: &HingeLoads<D>) -> (D, D) {
        self.kind.end_stresses(self.dims(), width, loads)
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
        let c = HingeKind::Strip.compliance(&[l, t], w, &mat);
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
        let s = HingeKind::Strip.max_stress(&[l, t], w, &loads);
        assert!((s - 6.0 * 3.0 * l / (w * t * t)).abs() < 1e-6);
    }
}
