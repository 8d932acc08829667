//! The leaf (strip) hinge: a straight beam of constant rectangular section, `l` long and
//! `t` thick, paper 004's hinge.

use super::{dim, positive, CompliancePartials, FitRatio, Kind};
use crate::model::fit::FitRange;
use crate::model::hinge::{Compliance, HingeDimension, HingeLoads};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

/// A leaf (strip) hinge.
#[derive(Debug, Clone, Copy)]
pub struct Strip;

impl Kind for Strip {
    const NAME: &'static str = "strip";
    const DIMENSIONS: &'static [HingeDimension] = &[dim("l", "length"), dim("t", "thickness")];
    /// A beam: at least twice as long as it is thick. Paper 004's own optimum has
    /// `l/t = 5`; below 2 the leaf is a stub whose rotation spreads into the bodies it
    /// joins, which the mechanism takes as rigid.
    const FIT: &'static [FitRatio] = &[FitRatio {
        numerator: 0,
        denominator: 1,
        range: FitRange {
            lower: Some(2.0),
            upper: None,
            holds: "the leaf's beam model",
            source: "Timoshenko beam of Wei et al., Micromachines 8 (2017) 238, Eq. 2 (its \
                     optimum: l/t = 5); the accuracy table's shortest leaf, l/t = 2",
        },
    }];
    /// Paper 004's Table 1 bounds, which the default template keeps: the short thick
    /// corner (`l/t` below 2) is left to the study, which keeps designs inside [`Strip::FIT`].
    const START: &'static [(f64, f64)] = &[(0.5, 20.0), (0.4, 2.0)];

    fn length<D: Scalar>(&self, dims: &[D]) -> D {
        dims[0]
    }

    fn least_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1]
    }

    fn root_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1]
    }

    fn area<D: Scalar>(&self, dims: &[D]) -> D {
        dims[0] * dims[1]
    }

    /// A length of zero is allowed: the mechanism then has no hinge there.
    fn domain_error(&self, dims: &[f64], names: &[&str]) -> Option<String> {
        if dims[0] < 0.0 {
            Some(format!(
                "{} = {} m is negative",
                names[0],
                crate::vocab::units::short(dims[0])
            ))
        } else {
            positive(dims, names, 1)
        }
    }

    /// Paper 004 Eq. 2 (Timoshenko cantilever, shear factor taken as 1 as the paper does):
    ///
    /// ```text
    /// c11 = l / (E w t)
    /// c22 = 4 l^3 / (E w t^3) + l / (G w t)
    /// c23 = c32 = 6 l^2 / (E w t^3)
    /// c33 = 12 l / (E w t^3)
    /// ```
    fn compliance<D: Scalar>(&self, dims: &[D], width: f64, material: &Material) -> Compliance<D> {
        let (length, thickness) = (dims[0], dims[1]);
        // one division: every coefficient is a multiple of 1 / (E w t^3)
        let e = material.youngs_modulus;
        let inv = (thickness * thickness * thickness * (e * width)).recip();
        let l_inv = length * inv;
        let t2 = thickness * thickness;
        Compliance {
            c11: l_inv * t2,
            // E / G = 2 (1 + nu)
            c22: l_inv * (length * length * 4.0 + t2 * (2.0 * (1.0 + material.poisson_ratio))),
            c23: l_inv * length * 6.0,
            c33: l_inv * 12.0,
        }
    }

    /// Eq. 2's derivatives: with `A = 1 / (E w)`, each coefficient is a monomial
    /// `l^p t^-q` times a constant (or two, `c22`), so `d/dl = p c / l` and `d/dt = -q c / t`,
    /// written without dividing by `l`, which may be zero.
    fn compliance_partials(
        &self,
        dims: &[f64],
        width: f64,
        material: &Material,
    ) -> Option<CompliancePartials> {
        let (length, thickness) = (dims[0], dims[1]);
        // the values are Eq. 2's own code's, bit for bit
        let c = self.compliance(dims, width, material);
        let inv = (thickness * thickness * thickness * (material.youngs_modulus * width)).recip();
        let t2 = thickness * thickness;
        let shear = t2 * (2.0 * (1.0 + material.poisson_ratio));
        // l A / t^4
        let over_t = length * inv / thickness;
        let zero = Compliance {
            c11: 0.0,
            c22: 0.0,
            c23: 0.0,
            c33: 0.0,
        };
        let by_length = Compliance {
            c11: inv * t2,
            c22: inv * (length * length * 12.0 + shear),
            c23: length * inv * 12.0,
            c33: inv * 12.0,
        };
        let by_thickness = Compliance {
            c11: -over_t * t2,
            c22: -over_t * (length * length * 12.0 + shear),
            c23: -over_t * length * 18.0,
            c33: -over_t * 36.0,
        };
        Some((c, [by_length, by_thickness, zero]))
    }

    /// 1: paper 004 takes its beam stress at the clamped ends, where a sharp corner has no
    /// finite factor.
    fn stress_concentration<D: Scalar>(&self, _dims: &[D]) -> D {
        D::from(1.0)
    }

    /// Paper 004 Eq. 15-16: the moment varies linearly along the hinge, `M(x) = M + V x`
    /// for `x` in `[0, l]` measured from the loaded end, so the extreme fibre stress
    /// `6 |M(x)| / (w t^2) + |N| / (w t)` is largest at one of the two ends.
    fn end_stresses<D: Scalar>(&self, dims: &[D], width: f64, loads: &HingeLoads<D>) -> (D, D) {
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

    fn thickness_along<D: Scalar>(&self, dims: &[D], _xi: D) -> D {
        dims[1]
    }

    /// One straight edge.
    fn outline(&self, dims: &[f64]) -> Vec<[f64; 3]> {
        let root = 0.5 * self.root_thickness(dims);
        vec![[0.0, root, 0.0], [dims[0], root, 0.0]]
    }

    fn has_sharp_roots(&self) -> bool {
        true
    }
}
