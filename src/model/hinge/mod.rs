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
//! dimensions ([`HingeKind::dimensions`]). A hinge kind is a [`HingeKind`] variant here, with
//! its dimension table and its arms of the functions below ([`integrals`] for the notches'
//! compliances, [`profile`] for their shapes and stresses), and nothing else: the bridge
//! names a kind's dimensions after the hinge (`l2`, `t2` for a strip at b, `r4`, `t4` for a
//! circular notch at d) and lays them out by itself.
//!
//! The kinds: `strip` (`l`, `t`), `circular` (`r`, `t`), `elliptical` (`a`, `b`, `t`) and
//! `corner-filleted` (`l`, `t`, `r`).

pub mod calculator;
pub mod integrals;
pub mod profile;

use serde::Serialize;

use super::material::Material;
use super::scalar::{max, Scalar};
use super::Dimension;
use integrals::Span;

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

const fn dim(stem: &'static str, description: &'static str) -> HingeDimension {
    HingeDimension {
        stem,
        dimension: Dimension::Length,
        description,
    }
}

/// The dimensions of each kind. The first of every kind is the one that sets its length
/// along the centre line (a strip's length, a circular notch's radius).
const STRIP: [HingeDimension; 2] = [dim("l", "length"), dim("t", "thickness")];
const CIRCULAR: [HingeDimension; 2] = [dim("r", "notch radius"), dim("t", "least thickness")];
const ELLIPTICAL: [HingeDimension; 3] = [
    dim("a", "notch semi-axis along the hinge"),
    dim("b", "notch semi-axis across the hinge"),
    dim("t", "least thickness"),
];
const CORNER_FILLETED: [HingeDimension; 3] = [
    dim("l", "length, fillets included"),
    dim("t", "thickness"),
    dim("r", "fillet radius"),
];

/// The compliance coefficients of one hinge (paper 004, Eq. 1), SI units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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
    /// A right-circular notch of radius `r` from both sides, least thickness `t`: a bar
    /// `t + 2 r` thick with two half circles cut out, `2 r` long.
    Circular,
    /// A right-elliptical notch of semi-axes `a` (along) and `b` (across), least thickness
    /// `t`: `2 a` long, `t + 2 b` thick at its ends.
    Elliptical,
    /// A leaf of thickness `t` whose ends widen by quarter circles of radius `r` to
    /// `t + 2 r`: `l` long fillets included.
    CornerFilleted,
}

impl HingeKind {
    /// The names a problem file uses.
    pub const NAMES: &'static [&'static str] =
        &["strip", "circular", "elliptical", "corner-filleted"];

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "strip" => Some(HingeKind::Strip),
            "circular" => Some(HingeKind::Circular),
            "elliptical" => Some(HingeKind::Elliptical),
            "corner-filleted" => Some(HingeKind::CornerFilleted),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            HingeKind::Strip => "strip",
            HingeKind::Circular => "circular",
            HingeKind::Elliptical => "elliptical",
            HingeKind::CornerFilleted => "corner-filleted",
        }
    }

    /// The kind's dimensions, in the order its functions take them; the first is the one
    /// that sets the length along the centre line.
    pub fn dimensions(self) -> &'static [HingeDimension] {
        match self {
            HingeKind::Strip => &STRIP,
            HingeKind::Circular => &CIRCULAR,
            HingeKind::Elliptical => &ELLIPTICAL,
            HingeKind::CornerFilleted => &CORNER_FILLETED,
        }
    }

    /// The length of the hinge along its centre line (m).
    pub fn length<D: Scalar>(self, dims: &[D]) -> D {
        match self {
            HingeKind::Strip | HingeKind::CornerFilleted => dims[0],
            HingeKind::Circular | HingeKind::Elliptical => dims[0] * 2.0,
        }
    }

    /// The least thickness (m), where the hinge bends most.
    pub fn least_thickness<D: Scalar>(self, dims: &[D]) -> D {
        match self {
            HingeKind::Strip | HingeKind::Circular | HingeKind::CornerFilleted => dims[1],
            HingeKind::Elliptical => dims[2],
        }
    }

    /// The hinge's thickness where it meets the rigid bodies (m): the width of the faces
    /// its part's outline attaches to.
    pub fn root_thickness(self, dims: &[f64]) -> f64 {
        match self {
            HingeKind::Strip => dims[1],
            HingeKind::Circular => dims[1] + 2.0 * dims[0],
            HingeKind::Elliptical => dims[2] + 2.0 * dims[1],
            HingeKind::CornerFilleted => dims[1] + 2.0 * dims[2],
        }
    }

    /// The hinge's area in the plane of the mechanism (m^2), for its mass.
    pub fn area<D: Scalar>(self, dims: &[D]) -> D {
        let pi = std::f64::consts::PI;
        match self {
            HingeKind::Strip => dims[0] * dims[1],
            HingeKind::Circular => {
                let (r, t) = (dims[0], dims[1]);
                r * 2.0 * (t + r * 2.0) - r * r * pi
            }
            HingeKind::Elliptical => {
                let (a, b, t) = (dims[0], dims[1], dims[2]);
                a * 2.0 * (t + b * 2.0) - a * b * pi
            }
            HingeKind::CornerFilleted => {
                let (l, t, r) = (dims[0], dims[1], dims[2]);
                l * t + r * r * (4.0 - pi)
            }
        }
    }

    /// Why `dims` (SI) make no hinge of this kind, if they do not; `names` are the
    /// dimensions' names in the mechanism (`l2`, `t2`). A strip's length of zero is
    /// allowed: the mechanism then has no hinge there.
    pub fn domain_error(self, dims: &[f64], names: &[&str]) -> Option<String> {
        let positive = |k: usize| {
            (dims[k] <= 0.0).then(|| format!("{} = {} m is not positive", names[k], dims[k]))
        };
        match self {
            HingeKind::Strip => {
                if dims[0] < 0.0 {
                    Some(format!("{} = {} m is negative", names[0], dims[0]))
                } else {
                    positive(1)
                }
            }
            HingeKind::Circular => positive(0).or_else(|| positive(1)),
            HingeKind::Elliptical => positive(0).or_else(|| positive(1)).or_else(|| positive(2)),
            HingeKind::CornerFilleted => positive(0)
                .or_else(|| positive(1))
                .or_else(|| positive(2))
                .or_else(|| {
                    (2.0 * dims[2] > dims[0]).then(|| {
                        format!(
                            "{} = {} m is longer than half {} = {} m: a fillet longer than \
                             half the leaf",
                            names[2], dims[2], names[0], dims[0]
                        )
                    })
                }),
        }
    }

    /// Why some dimensions between `lower` and `upper` make no hinge of this kind though
    /// each bound is valid: the index of the dimension to blame and the reason.
    pub fn box_error(
        self,
        lower: &[f64],
        upper: &[f64],
        names: &[&str],
    ) -> Option<(usize, String)> {
        match self {
            HingeKind::CornerFilleted if 2.0 * upper[2] > lower[0] => Some((
                2,
                format!(
                    "{} may reach {} mm, more than half of {}'s least {} mm: a fillet longer \
                     than half the leaf; keep {}'s upper bound at most half {}'s lower bound",
                    names[2],
                    upper[2] * 1e3,
                    names[0],
                    lower[0] * 1e3,
                    names[2],
                    names[0]
                ),
            )),
            _ => None,
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
    ///
    /// The notches: the same beam, its thickness varying, by the exact integrals of
    /// [`integrals`] (a circular notch is an elliptical one with `a = b = r`; a
    /// corner-filleted leaf a strip with a quarter-circle arc at each end).
    pub fn compliance<D: Scalar>(
        self,
        dims: &[D],
        width: f64,
        material: &Material,
    ) -> Compliance<D> {
        let moments = match self {
            HingeKind::Strip => {
                let (length, thickness) = (dims[0], dims[1]);
                // one division: every coefficient is a multiple of 1 / (E w t^3)
                let e = material.youngs_modulus;
                let inv = (thickness * thickness * thickness * (e * width)).recip();
                let l_inv = length * inv;
                let t2 = thickness * thickness;
                return Compliance {
                    c11: l_inv * t2,
                    // E / G = 2 (1 + nu)
                    c22: l_inv
                        * (length * length * 4.0 + t2 * (2.0 * (1.0 + material.poisson_ratio))),
                    c23: l_inv * length * 6.0,
                    c33: l_inv * 12.0,
                };
            }
            HingeKind::Circular => {
                let (r, t) = (dims[0], dims[1]);
                integrals::arc(t, r, r, r, Span::Whole)
            }
            HingeKind::Elliptical => {
                let (a, b, t) = (dims[0], dims[1], dims[2]);
                integrals::arc(t, b, a, a, Span::Whole)
            }
            HingeKind::CornerFilleted => {
                let (l, t, r) = (dims[0], dims[1], dims[2]);
                integrals::arc(t, r, r, r, Span::First)
                    .plus(integrals::strip(r, l - r, t))
                    .plus(integrals::arc(t, r, r, l - r, Span::Second))
            }
        };
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

    /// The factor by which the largest surface stress of a notch exceeds the beam stress
    /// at its thinnest section in bending, `K_t`; 1 for the strip (paper 004 takes its
    /// beam stress at the clamped ends, where a sharp corner has no finite factor).
    ///
    /// - circular, the fit to Peterson's charts that Smith gives for the right-circular
    ///   notch hinge in bending (S. T. Smith, *Flexures: Elements of Elastic Mechanisms*,
    ///   Gordon and Breach, 2000, its chapter on notch hinges):
    ///   `K_t = (1 + t / (2 r))^(9/20)`;
    /// - elliptical, the same fit with the radius of curvature at the notch's root,
    ///   `rho = a^2 / b`, for `r`: `K_t = (1 + t b / (2 a^2))^(9/20)`; our extension,
    ///   within 1 % of the FE of the single hinge over the table's grid;
    /// - corner-filleted, the flat bar with shoulder fillets in in-plane bending
    ///   (W. C. Young and R. G. Budynas, *Roark's Formulas for Stress and Strain*, 7th ed.,
    ///   McGraw-Hill, 2002, Table 17.1, case 2b) with shoulder height `h = r` (a quarter
    ///   circle from `t` to `D = t + 2 r`, so `h / r = 1`, inside the fit's 0.1..2):
    ///   `K_t = C1 + C2 x + C3 x^2 + C4 x^3`, `x = 2 h / D = 2 r / (t + 2 r)`, with
    ///   `C1 = 1.007 + 1.000 - 0.031`, `C2 = -0.270 - 2.404 + 0.749`,
    ///   `C3 = 0.677 + 1.133 - 0.904`, `C4 = -0.414 + 0.271 + 0.186` (each `Ci` at
    ///   `h / r = 1`).
    pub fn stress_concentration<D: Scalar>(self, dims: &[D]) -> D {
        match self {
            HingeKind::Strip => D::from(1.0),
            HingeKind::Circular => {
                let (r, t) = (dims[0], dims[1]);
                (t / (r * 2.0) + 1.0).powf(0.45)
            }
            HingeKind::Elliptical => {
                let (a, b, t) = (dims[0], dims[1], dims[2]);
                (t * b / (a * a * 2.0) + 1.0).powf(0.45)
            }
            HingeKind::CornerFilleted => {
                let (t, r) = (dims[1], dims[2]);
                let x = r * 2.0 / (t + r * 2.0);
                const C: [f64; 4] = [
                    1.007 + 1.000 - 0.031,
                    -0.270 - 2.404 + 0.749,
                    0.677 + 1.133 - 0.904,
                    -0.414 + 0.271 + 0.186,
                ];
                ((x * C[3] + C[2]) * x + C[1]) * x + C[0]
            }
        }
    }

    /// The largest normal stress (Pa) at the two ends of the hinge, `(loaded end, clamped
    /// end)`, under the end loads that hold its free end: axial force `axial`, transverse
    /// force `shear` and moment `moment` there; for a notch, its one peak, twice.
    ///
    /// Strip hinge, paper 004 Eq. 15-16: the moment varies linearly along the hinge,
    /// `M(x) = M + V x` for `x` in `[0, l]` measured from the loaded end, so the extreme
    /// fibre stress `6 |M(x)| / (w t^2) + |N| / (w t)` is largest at one of the two ends.
    /// A notch: the same beam stress, largest near its thinnest section, found along it
    /// ([`HingeKind::beam_stress_max`]), times the notch's stress concentration
    /// ([`HingeKind::stress_concentration`]), which the finite-element check of the single
    /// hinge measures (the README's accuracy table).
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
            _ => {
                // one peak, near the thinnest section: the same value for both ends, so that
                // an optimizer bounding both sees one constraint twice rather than two
                // nearly equal ones where the peak crosses the middle
                let peak = self.beam_stress_max(dims, width, loads, 0.0, 1.0)
                    * self.stress_concentration(dims);
                (peak, peak)
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
