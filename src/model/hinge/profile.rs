//! What follows from a hinge's shape, whatever its kind: the compliances by numerical
//! integration of its thickness profile (the check of the closed forms), the largest beam
//! stress along it, and the bulges of the arcs its outline is drawn with.

use super::super::scalar::{Jet, Scalar};
use super::kinds::Kind;
use super::{Compliance, HingeKind, HingeLoads};
use crate::model::material::Material;

impl HingeKind {
    /// The thickness at the fraction `xi` of the hinge's length (0 and 1 its ends).
    pub fn thickness_at<D: Scalar>(self, dims: &[D], xi: f64) -> D {
        self.thickness_along(dims, D::from(xi))
    }

    /// The compliances by adaptive numerical integration of the thickness profile, for the
    /// tests and the accuracy table: independent of the closed forms' algebra.
    pub fn compliance_numerical(
        self,
        dims: &[f64],
        width: f64,
        material: &Material,
    ) -> Compliance<f64> {
        let l = self.length(dims);
        let t = |x: f64| self.thickness_at(dims, x / l);
        let i0 = integrate(&|x| 1.0 / t(x), 0.0, l);
        let i3: Vec<f64> = (0..3)
            .map(|k| integrate(&|x| x.powi(k) / t(x).powi(3), 0.0, l))
            .collect();
        let (e, g) = (material.youngs_modulus, material.shear_modulus());
        Compliance {
            c11: i0 / (e * width),
            c22: 12.0 * i3[2] / (e * width) + i0 / (g * width),
            c23: 12.0 * i3[1] / (e * width),
            c33: 12.0 * i3[0] / (e * width),
        }
    }
}

/// The largest beam stress `6 |M(x)| / (w t^2) + |N| / (w t)` over the half of the hinge
/// from `lo` to `hi` (fractions of its length), `M(x) = M + V x` from the loaded end. The
/// largest of 17 stations is refined to the zero of its slope and the stress evaluated there:
/// at an interior maximum its derivative along the hinge is zero, so the value's
/// gradient with respect to the dimensions and loads is that at the fixed point (the
/// envelope theorem), which the scalar type carries exactly.
pub fn beam_stress_max<K: Kind, D: Scalar>(
    kind: &K,
    dims: &[D],
    width: f64,
    loads: &HingeLoads<D>,
    lo: f64,
    hi: f64,
) -> D {
    let l = kind.length(dims);
    let at = |xi: f64| -> D {
        let t = kind.thickness_along(dims, D::from(xi));
        let m = (loads.moment + loads.shear * (l * xi)).abs();
        (m * 6.0 / (t * t) + loads.axial.abs() / t) / width
    };
    let f = |xi: f64| at(xi).re();
    const STATIONS: usize = 16;
    let xs: Vec<f64> = (0..=STATIONS)
        .map(|k| lo + (hi - lo) * k as f64 / STATIONS as f64)
        .collect();
    let fs: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
    let best = (0..=STATIONS)
        .max_by(|&a, &b| fs[a].total_cmp(&fs[b]))
        .unwrap_or(0);
    if best == 0 || best == STATIONS {
        return at(xs[best]);
    }
    // the stress's slope along the hinge, exact (a dual number in the place): a maximum
    // so flat that comparing values could place it only to 1e-8 is placed to rounding
    let (values, re) = (dims.iter().map(|d| d.re()).collect::<Vec<f64>>(), |d: D| {
        d.re()
    });
    let plain = HingeLoads {
        axial: re(loads.axial),
        shear: re(loads.shear),
        moment: re(loads.moment),
    };
    let length = kind.length(&values);
    let slope = |xi: f64| -> f64 {
        let x = Jet::<1>::variable(xi, 0);
        let t = kind.thickness_along(&values.iter().map(|&v| Jet::from(v)).collect::<Vec<_>>(), x);
        let m = (x * (plain.shear * length) + plain.moment).abs();
        ((m * 6.0 / (t * t) + t.recip() * plain.axial.abs()) / width).grad[0]
    };
    // the slope falls through zero between the best station's neighbours: the Illinois
    // variant of false position, which keeps the root bracketed (the profile may be
    // only once differentiable, where a fillet meets its leaf)
    let (mut a, mut b) = (xs[best - 1], xs[best + 1]);
    let (mut ga, mut gb) = (slope(a), slope(b));
    if !(ga > 0.0 && gb < 0.0) {
        return at(xs[best]);
    }
    let mut xi = xs[best];
    let mut side = 0;
    for _ in 0..100 {
        xi = (a * gb - b * ga) / (gb - ga);
        if !(xi > a && xi < b) {
            xi = 0.5 * (a + b);
        }
        let g = slope(xi);
        if g == 0.0 || (b - a) <= 1e-15 * (hi - lo) {
            break;
        }
        if g > 0.0 {
            a = xi;
            ga = g;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            b = xi;
            gb = g;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    at(xi)
}

/// The bulge of the arc from `p` through `m` to `q`.
pub fn bulge_through(p: [f64; 2], m: [f64; 2], q: [f64; 2]) -> f64 {
    // the inscribed angle at m is pi - sweep/2 for the arc p..q through m
    let cross = (m[0] - p[0]) * (q[1] - p[1]) - (m[1] - p[1]) * (q[0] - p[0]);
    let (a, b) = ([p[0] - m[0], p[1] - m[1]], [q[0] - m[0], q[1] - m[1]]);
    let angle = (a[0] * b[1] - a[1] * b[0])
        .abs()
        .atan2(a[0] * b[0] + a[1] * b[1]);
    let sweep = 2.0 * (std::f64::consts::PI - angle);
    // counterclockwise when m lies to the right of p -> q: (m - p) x (q - p) > 0
    let sign = if cross > 0.0 { 1.0 } else { -1.0 };
    sign * (sweep / 4.0).tan()
}

/// Adaptive Gauss-Kronrod (7-15) integration of `f` on `[a, b]` to a relative 1e-13.
pub fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    integrate_over(f, a, b)
}

/// [`integrate`] of a function into any scalar: the subdivision follows the real part, and
/// a dual number's derivatives are integrated by the same rule on the same intervals (the
/// derivative of the quadrature, which converges with it).
pub fn integrate_over<D: Scalar>(f: &dyn Fn(f64) -> D, a: f64, b: f64) -> D {
    const XK: [f64; 8] = [
        0.991_455_371_120_812_6,
        0.949_107_912_342_758_5,
        0.864_864_423_359_769_1,
        0.741_531_185_599_394_4,
        0.586_087_235_467_691_1,
        0.405_845_151_377_397_2,
        0.207_784_955_007_898_5,
        0.0,
    ];
    const WK: [f64; 8] = [
        0.022_935_322_010_529_22,
        0.063_092_092_629_978_55,
        0.104_790_010_322_250_2,
        0.140_653_259_715_525_9,
        0.169_004_726_639_267_9,
        0.190_350_578_064_785_4,
        0.204_432_940_075_298_9,
        0.209_482_141_084_728,
    ];
    const WG: [f64; 4] = [
        0.129_484_966_168_869_7,
        0.279_705_391_489_276_7,
        0.381_830_050_505_118_9,
        0.417_959_183_673_469_4,
    ];
    fn rule<D: Scalar>(f: &dyn Fn(f64) -> D, a: f64, b: f64) -> (D, f64) {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let fc = f(c);
        let (mut k, mut g) = (fc * WK[7], fc * WG[3]);
        for i in 0..7 {
            let (y1, y2) = (f(c - h * XK[i]), f(c + h * XK[i]));
            k = k + (y1 + y2) * WK[i];
            if i % 2 == 1 {
                g = g + (y1 + y2) * WG[i / 2];
            }
        }
        (k * h, (k.re() - g.re()).abs() * h)
    }
    fn go<D: Scalar>(f: &dyn Fn(f64) -> D, a: f64, b: f64, whole: f64, depth: u32) -> D {
        let (k, err) = rule(f, a, b);
        if depth == 0 || err <= 1e-14 * whole.abs().max(k.re().abs()) {
            return k;
        }
        let m = 0.5 * (a + b);
        go(f, a, m, whole, depth - 1) + go(f, m, b, whole, depth - 1)
    }
    let whole = rule(f, a, b).0.re();
    go(f, a, b, whole, 40)
}
