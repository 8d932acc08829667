//! The corner-filleted leaf: a leaf of thickness `t` whose ends widen by quarter circles
//! of radius `r` to `t + 2 r`, `l` long fillets included.

use super::{dim, from_moments, positive, FitRatio, Kind};
use crate::model::fit::FitRange;
use crate::model::hinge::integrals::{self, Span};
use crate::model::hinge::{Compliance, HingeDimension};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

/// A corner-filleted leaf hinge.
#[derive(Debug, Clone, Copy)]
pub struct CornerFilleted;

impl Kind for CornerFilleted {
    const NAME: &'static str = "corner-filleted";
    const DIMENSIONS: &'static [HingeDimension] = &[
        dim("l", "length, fillets included"),
        dim("t", "thickness"),
        dim("r", "fillet radius"),
    ];
    /// A fillet the shoulder fit knows (`r/t >= 0.05`: below it the fit tends to its
    /// sharp-step limit, 1.98, while the stress at the leaf's root is set by whatever
    /// corner the part gives it), and a leaf that is a beam, as the strip's `l/t >= 2`.
    const FIT: &'static [FitRatio] = &[
        FitRatio {
            numerator: 2,
            denominator: 1,
            range: FitRange {
                lower: Some(0.05),
                upper: None,
                holds: "the shoulder fillet's K_t fit",
                source: "W. C. Young and R. G. Budynas, Roark's Formulas for Stress and \
                         Strain, 7th ed. (2002), Table 17.1 case 2b, for 0.1 <= h/r <= 2 (h/r \
                         = 1 here); the single-hinge FE resolves the fillet and confirms the \
                         fit from r/t = 0.05",
            },
        },
        FitRatio {
            numerator: 1,
            denominator: 0,
            range: FitRange {
                lower: None,
                upper: Some(0.5),
                holds: "the leaf's beam model",
                source: "N. Lobontiu, J. S. N. Paine, E. Garcia and M. Goldfarb, J. Mech. \
                         Des. 123 (2001) 346, corner-filleted hinges as beams; the strip's \
                         l/t >= 2",
            },
        },
    ];
    /// `r/t` at least 0.1 / 2 = 0.05 and `t/l` at most 2 / 4 = 0.5 over the whole box, and
    /// the two fillets (2 mm at most) shorter than the leaf (4 mm at least).
    const START: &'static [(f64, f64)] = &[(4.0, 20.0), (0.4, 2.0), (0.1, 1.0)];

    fn length<D: Scalar>(&self, dims: &[D]) -> D {
        dims[0]
    }

    fn least_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1]
    }

    fn root_thickness<D: Scalar>(&self, dims: &[D]) -> D {
        dims[1] + dims[2] * 2.0
    }

    fn area<D: Scalar>(&self, dims: &[D]) -> D {
        let pi = std::f64::consts::PI;
        let (l, t, r) = (dims[0], dims[1], dims[2]);
        l * t + r * r * (4.0 - pi)
    }

    fn domain_error(&self, dims: &[f64], names: &[&str]) -> Option<String> {
        positive(dims, names, 0)
            .or_else(|| positive(dims, names, 1))
            .or_else(|| positive(dims, names, 2))
            .or_else(|| {
                (2.0 * dims[2] > dims[0]).then(|| {
                    format!(
                        "{} = {} m is longer than half {} = {} m: a fillet longer than \
                         half the leaf",
                        names[2], dims[2], names[0], dims[0]
                    )
                })
            })
    }

    /// The fillets at most half the leaf's length, whatever values the bounds allow.
    fn box_error(&self, lower: &[f64], upper: &[f64], names: &[&str]) -> Option<(usize, String)> {
        (2.0 * upper[2] > lower[0]).then(|| {
            (
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
            )
        })
    }

    /// The exact integrals of [`integrals`]: a strip with a quarter-circle arc at each end.
    fn compliance<D: Scalar>(&self, dims: &[D], width: f64, material: &Material) -> Compliance<D> {
        let (l, t, r) = (dims[0], dims[1], dims[2]);
        let moments = integrals::arc(t, r, r, r, Span::First)
            .plus(integrals::strip(r, l - r, t))
            .plus(integrals::arc(t, r, r, l - r, Span::Second));
        from_moments(moments, width, material)
    }

    /// The flat bar with shoulder fillets in in-plane bending (W. C. Young and R. G.
    /// Budynas, *Roark's Formulas for Stress and Strain*, 7th ed., McGraw-Hill, 2002, Table
    /// 17.1, case 2b) with shoulder height `h = r` (a quarter circle from `t` to
    /// `D = t + 2 r`, so `h / r = 1`, inside the fit's 0.1..2):
    /// `K_t = C1 + C2 x + C3 x^2 + C4 x^3`, `x = 2 h / D = 2 r / (t + 2 r)`, with
    /// `C1 = 1.007 + 1.000 - 0.031`, `C2 = -0.270 - 2.404 + 0.749`,
    /// `C3 = 0.677 + 1.133 - 0.904`, `C4 = -0.414 + 0.271 + 0.186` (each `Ci` at
    /// `h / r = 1`).
    fn stress_concentration<D: Scalar>(&self, dims: &[D]) -> D {
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

    fn thickness_along<D: Scalar>(&self, dims: &[D], xi: D) -> D {
        let (l, t, r) = (dims[0], dims[1], dims[2]);
        let x = l * xi;
        let from_end = if xi.re() <= 0.5 { x } else { l - x };
        if from_end.re() >= r.re() {
            t
        } else {
            // a quarter circle: 1 at the root, 0 where the leaf begins
            let v = D::from(1.0) - from_end / r;
            let depth = D::from(1.0) - (D::from(1.0) - v * v).sqrt();
            t + r * depth * 2.0
        }
    }

    fn outline(&self, dims: &[f64]) -> Vec<[f64; 3]> {
        let root = 0.5 * self.root_thickness(dims);
        let (l, t, r) = (dims[0], dims[1], dims[2]);
        let quarter = std::f64::consts::FRAC_PI_8.tan();
        let mut out = vec![
            [0.0, root, quarter],
            [r, 0.5 * t, 0.0],
            [l - r, 0.5 * t, quarter],
            [l, root, 0.0],
        ];
        // fillets meeting in the middle leave no leaf between them
        if l - 2.0 * r <= 1e-12 * l {
            out.remove(1);
        }
        out
    }
}
