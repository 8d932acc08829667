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
//! dimensions ([`HingeKind::dimensions`]); its part asks for its outline and its part rules
//! (sharp roots to fillet, how the drawing names its length). The bridge names a kind's
//! dimensions after the hinge (`l2`, `t2` for a strip at b, `r4`, `t4` for a circular notch
//! at d) and lays them out by itself; `flexopt hinge` makes a flag of each dimension stem.
//!
//! The kinds: `strip` (`l`, `t`), `circular` (`r`, `t`), `elliptical` (`a`, `b`, `t`) and
//! `corner-filleted` (`l`, `t`, `r`), each in its room under [`kinds`].
//!
//! Adding a kind takes three places, and the rest of flexopt (problem files, the
//! `--kind` choices, the `hinge` command's flags, the bridge's layout, part, drawing and FE
//! check) follows from them:
//!
//! 1. its room, `kinds/<name>.rs`: a unit struct implementing [`kinds::Kind`] (its name,
//!    its dimension table, its formulas, its part rules), declared and re-exported in
//!    `kinds/mod.rs` (`mod <name>; pub use <name>::<Struct>;`);
//! 2. its variant of [`HingeKind`];
//! 3. its line `Variant => kinds::Struct` in the table of `for_each_kind!` (in this file),
//!    the one place that joins the two.
//!
//! A test holds each room's name to its variant's name in problem files (serde's
//! kebab-case of the variant).
//!
//! A kind with more than [`MAX_HINGE_DIMENSIONS`] dimensions raises that constant too.

pub mod calculator;
pub mod integrals;
pub mod kinds;
pub mod profile;

use serde::Serialize;

use super::fit::FitLimit;
use super::material::Material;
use super::scalar::{max, Scalar};
use super::Dimension;
use kinds::{CompliancePartials, FitRatio, Kind};

/// The most dimensions a hinge kind has.
pub const MAX_HINGE_DIMENSIONS: usize = 3;

/// One dimension of a hinge kind; a mechanism names it `stem` followed by the hinge's
/// number (`t` of hinge b is the bridge's `t2`), `flexopt hinge` takes it as `--stem`.
/// `description` serves both: the parameter's description and the flag's help.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HingeDimension {
    pub stem: &'static str,
    pub dimension: Dimension,
    pub description: &'static str,
}

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

impl<D: Scalar> Compliance<D> {
    /// The same hinge's compliances in a material whose Young's and shear moduli are both
    /// `modulus` times the nominal ones (Poisson's ratio kept): every coefficient of a
    /// linear-elastic hinge is a length integral over `E` or `G`, so each scales by
    /// `1 / modulus` exactly. The tolerance analysis varies `E` through it.
    pub fn with_modulus(self, modulus: D) -> Self {
        let inv = modulus.recip();
        Compliance {
            c11: self.c11 * inv,
            c22: self.c22 * inv,
            c23: self.c23 * inv,
            c33: self.c33 * inv,
        }
    }
}

/// The kinds of flexure hinge flexopt models; each variant's room is in [`kinds`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum HingeKind {
    /// A leaf (strip) hinge ([`kinds::Strip`]).
    Strip,
    /// A right-circular notch ([`kinds::Circular`]).
    Circular,
    /// A right-elliptical notch ([`kinds::Elliptical`]).
    Elliptical,
    /// A leaf with filleted corners ([`kinds::CornerFilleted`]).
    CornerFilleted,
}

/// The one table of the kinds, each variant of [`HingeKind`] with its room: hands the table
/// to the macro `$then` (with `$args` first), so that the dispatch of every method and the
/// list of kinds come from these lines alone.
macro_rules! for_each_kind {
    ($then:ident $args:tt) => {
        $then! { $args
            Strip => kinds::Strip,
            Circular => kinds::Circular,
            Elliptical => kinds::Elliptical,
            CornerFilleted => kinds::CornerFilleted,
        }
    };
}

/// `$body` with `$k` bound to the room of the kind `$kind`.
macro_rules! with_kind {
    ($kind:expr, $k:ident => $body:expr) => {
        for_each_kind!(dispatch($kind, $k, $body))
    };
}

/// [`with_kind!`]'s match, one arm per line of the table.
macro_rules! dispatch {
    (($kind:expr, $k:ident, $body:expr) $($variant:ident => $room:path,)*) => {
        match $kind {
            $(HingeKind::$variant => {
                let $k = &$room;
                $body
            })*
        }
    };
}

/// [`HingeKind::ALL`] and [`HingeKind::NAMES`] from the table: consts, because clap's
/// `PossibleValuesParser` and the problem files' messages take the names as a static list.
macro_rules! kind_list {
    (() $($variant:ident => $room:path,)*) => {
        impl HingeKind {
            /// Every kind, in the table's order.
            pub const ALL: &'static [HingeKind] = &[$(HingeKind::$variant),*];

            /// The names a problem file uses, in the order of [`HingeKind::ALL`].
            pub const NAMES: &'static [&'static str] = &[$(<$room as Kind>::NAME),*];
        }
    };
}

for_each_kind!(kind_list());

impl HingeKind {
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|k| k.name() == name)
    }

    pub fn name(self) -> &'static str {
        with_kind!(self, k => kind_name(k))
    }

    /// The kind's dimensions, in the order its functions take them; the first is the one
    /// that sets the length along the centre line.
    pub fn dimensions(self) -> &'static [HingeDimension] {
        with_kind!(self, k => kind_dimensions(k))
    }

    /// Where the kind's formulas hold ([`Kind::FIT`]).
    pub fn fit(self) -> &'static [FitRatio] {
        with_kind!(self, k => kind_fit(k))
    }

    /// The kind's ranges over a mechanism's parameters: `index[k]` is the parameter index of
    /// the kind's dimension `k` and `names[k]` its name (`t2`); `owner` names the hinge in
    /// warnings (`hinge b (circular)`).
    pub fn fit_limits(self, owner: &str, index: &[usize], names: &[&str]) -> Vec<FitLimit> {
        self.fit()
            .iter()
            .map(|f| FitLimit {
                owner: owner.to_string(),
                ratio: format!("{}/{}", names[f.numerator], names[f.denominator]),
                numerator: index[f.numerator],
                denominator: index[f.denominator],
                range: f.range,
            })
            .collect()
    }

    /// The bounds (mm) `flexopt init --hinge` gives each dimension ([`Kind::START`]).
    pub fn start_bounds(self) -> &'static [(f64, f64)] {
        with_kind!(self, k => kind_start(k))
    }

    /// The length of the hinge along its centre line (m).
    pub fn length<D: Scalar>(self, dims: &[D]) -> D {
        with_kind!(self, k => k.length(dims))
    }

    /// The least thickness (m), where the hinge bends most.
    pub fn least_thickness<D: Scalar>(self, dims: &[D]) -> D {
        with_kind!(self, k => k.least_thickness(dims))
    }

    /// The hinge's thickness where it meets the rigid bodies (m): the width of the faces
    /// its part's outline attaches to.
    pub fn root_thickness<D: Scalar>(self, dims: &[D]) -> D {
        with_kind!(self, k => k.root_thickness(dims))
    }

    /// The hinge's area in the plane of the mechanism (m^2), for its mass.
    pub fn area<D: Scalar>(self, dims: &[D]) -> D {
        with_kind!(self, k => k.area(dims))
    }

    /// Why `dims` (SI) make no hinge of this kind, if they do not; `names` are the
    /// dimensions' names in the mechanism (`l2`, `t2`).
    pub fn domain_error(self, dims: &[f64], names: &[&str]) -> Option<String> {
        with_kind!(self, k => k.domain_error(dims, names))
    }

    /// Why some dimensions between `lower` and `upper` make no hinge of this kind though
    /// each bound is valid: the index of the dimension to blame and the reason.
    pub fn box_error(
        self,
        lower: &[f64],
        upper: &[f64],
        names: &[&str],
    ) -> Option<(usize, String)> {
        with_kind!(self, k => k.box_error(lower, upper, names))
    }

    /// Compliance of a hinge of dimensions `dims` (SI, in the order of
    /// [`HingeKind::dimensions`]) and section width `width` (m): each kind's
    /// [`Kind::compliance`] (paper 004 Eq. 2 for the strip, the exact integrals of
    /// [`integrals`] for the notches).
    pub fn compliance<D: Scalar>(
        self,
        dims: &[D],
        width: f64,
        material: &Material,
    ) -> Compliance<D> {
        with_kind!(self, k => k.compliance(dims, width, material))
    }

    /// [`HingeKind::compliance`] over `f64` with its partial derivatives by each dimension,
    /// where the kind has them in closed form ([`Kind::compliance_partials`]; the strip).
    pub fn compliance_partials(
        self,
        dims: &[f64],
        width: f64,
        material: &Material,
    ) -> Option<CompliancePartials> {
        with_kind!(self, k => k.compliance_partials(dims, width, material))
    }

    /// The factor by which the largest surface stress of a notch exceeds the beam stress
    /// at its thinnest section in bending, `K_t`; 1 for the strip. Each kind's
    /// [`Kind::stress_concentration`] cites its source.
    pub fn stress_concentration<D: Scalar>(self, dims: &[D]) -> D {
        with_kind!(self, k => k.stress_concentration(dims))
    }

    /// The largest normal stress (Pa) at the two ends of the hinge, `(loaded end, clamped
    /// end)`, under the end loads that hold its free end: axial force `axial`, transverse
    /// force `shear` and moment `moment` there; for a notch, its one peak, twice
    /// ([`Kind::end_stresses`]).
    pub fn end_stresses<D: Scalar>(self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> (D, D) {
        with_kind!(self, k => k.end_stresses(dims, width, loads))
    }

    /// The largest normal stress in the hinge (Pa): the larger of [`HingeKind::end_stresses`].
    pub fn max_stress<D: Scalar>(self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> D {
        let (near, far) = self.end_stresses(dims, width, loads);
        max(near, far)
    }

    /// [`HingeKind::thickness_at`] with the place a scalar too (for its derivative along the
    /// hinge).
    pub fn thickness_along<D: Scalar>(self, dims: &[D], xi: D) -> D {
        with_kind!(self, k => k.thickness_along(dims, xi))
    }

    /// The hinge's outline above its centre line ([`Kind::outline`]), which the part, the
    /// FE and the drawing draw from.
    pub fn outline(self, dims: &[f64]) -> Vec<[f64; 3]> {
        with_kind!(self, k => k.outline(dims))
    }

    /// [`profile::beam_stress_max`] of this kind.
    pub fn beam_stress_max<D: Scalar>(
        self,
        dims: &[D],
        width: f64,
        loads: &HingeLoads<D>,
        lo: f64,
        hi: f64,
    ) -> D {
        with_kind!(self, k => profile::beam_stress_max(k, dims, width, loads, lo, hi))
    }

    /// Whether the hinge meets its bodies at sharp inner corners, which the part fillets.
    pub fn has_sharp_roots(self) -> bool {
        with_kind!(self, k => k.has_sharp_roots())
    }

    /// How the drawing names the hinge's length, `first` the name of its first dimension.
    pub fn length_label(self, first: String) -> String {
        with_kind!(self, k => k.length_label(first))
    }
}

fn kind_name<K: Kind>(_: &K) -> &'static str {
    K::NAME
}

fn kind_dimensions<K: Kind>(_: &K) -> &'static [HingeDimension] {
    K::DIMENSIONS
}

fn kind_fit<K: Kind>(_: &K) -> &'static [FitRatio] {
    K::FIT
}

fn kind_start<K: Kind>(_: &K) -> &'static [(f64, f64)] {
    K::START
}

/// The table of every kind's ranges ([`HingeKind::fit`]), as the guide and
/// `docs/hinges.md` show it (a test holds them to it).
pub fn fit_table() -> String {
    let mut md = String::from(
        "| kind | ratio | range | what holds within it | source |\n|---|---|---|---|---|\n",
    );
    for &kind in HingeKind::ALL {
        let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
        for f in kind.fit() {
            md += &format!(
                "| {} | {}/{} | {} | {} | {} |\n",
                kind.name(),
                stems[f.numerator],
                stems[f.denominator],
                f.range.text(),
                f.range.holds,
                f.range.source
            );
        }
    }
    md
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
    fn each_rooms_name_is_its_variants_name_in_problem_files() {
        assert_eq!(HingeKind::ALL.len(), HingeKind::NAMES.len());
        for (&kind, &name) in HingeKind::ALL.iter().zip(HingeKind::NAMES) {
            let serde_name = serde_json::to_value(kind).unwrap();
            assert_eq!(serde_name.as_str(), Some(name));
            assert_eq!(HingeKind::from_name(name), Some(kind));
            assert!(kind.dimensions().len() <= MAX_HINGE_DIMENSIONS, "{name}");
        }
    }

    #[test]
    fn inits_bounds_make_hinges_inside_the_range_of_fit() {
        for &kind in HingeKind::ALL {
            let start = kind.start_bounds();
            let names: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
            assert_eq!(start.len(), names.len(), "{}", kind.name());
            let lower: Vec<f64> = start.iter().map(|b| b.0 * 1e-3).collect();
            let upper: Vec<f64> = start.iter().map(|b| b.1 * 1e-3).collect();
            assert!(start.iter().all(|&(lo, hi)| 0.0 < lo && lo < hi));
            assert_eq!(kind.box_error(&lower, &upper, &names), None);
            // every corner of a notch's or a filleted leaf's box, and the strip's centre
            // (the study keeps its short thick corner out), is a hinge the formulas hold for
            let corners: Vec<Vec<f64>> = (0..1 << start.len())
                .map(|bits: usize| {
                    (0..start.len())
                        .map(|i| {
                            if bits >> i & 1 == 1 {
                                upper[i]
                            } else {
                                lower[i]
                            }
                        })
                        .collect()
                })
                .collect();
            let centre: Vec<f64> = lower
                .iter()
                .zip(&upper)
                .map(|(a, b)| (a + b) / 2.0)
                .collect();
            let designs = if kind == HingeKind::Strip {
                vec![centre]
            } else {
                corners
            };
            for dims in &designs {
                assert_eq!(kind.domain_error(dims, &names), None, "{}", kind.name());
                for f in kind.fit() {
                    let ratio = dims[f.numerator] / dims[f.denominator];
                    assert!(f.range.contains(ratio), "{} {dims:?}", kind.name());
                }
            }
        }
    }

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
    fn strip_partials_are_the_formulas_derivatives() {
        use crate::model::scalar::Jet;
        let mat = Material::al7075_t6();
        let w = 10e-3;
        for dims in [
            [2e-3, 0.4e-3],
            [0.5e-3, 2e-3],
            [20e-3, 0.7e-3],
            [0.0, 0.5e-3],
        ] {
            let (c, by) = HingeKind::Strip
                .compliance_partials(&dims, w, &mat)
                .unwrap();
            // the values are the formula's over f64, bit for bit
            assert_eq!(c, HingeKind::Strip.compliance(&dims, w, &mat));
            // the partials are its forward-mode derivatives, to rounding
            let jets = [Jet::<2>::variable(dims[0], 0), Jet::variable(dims[1], 1)];
            let j = HingeKind::Strip.compliance(&jets, w, &mat);
            let pick = |c: &Compliance<f64>| [c.c11, c.c22, c.c23, c.c33];
            let dual = [j.c11, j.c22, j.c23, j.c33];
            for (k, by_k) in by.iter().take(2).enumerate() {
                for (exact, jet) in pick(by_k).iter().zip(&dual) {
                    let d = jet.grad[k];
                    assert!(
                        (exact - d).abs() <= 1e-14 * d.abs().max(1e-300),
                        "{dims:?} d/d{k}: {exact} vs {d}"
                    );
                }
            }
        }
        assert_eq!(
            HingeKind::Circular.compliance_partials(&[1e-3, 0.3e-3], w, &mat),
            None
        );
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
