//! The compliance integrals of a hinge of varying thickness: by Castigliano's theorem a
//! cantilever of thickness `t(x)` (x from the loaded end) and width `w` has
//!
//! ```text
//! c11 = int dx / (E w t)                      c33 = 12 int dx / (E w t^3)
//! c23 = 12 int x dx / (E w t^3)                c22 = 12 int x^2 dx / (E w t^3) + int dx / (G w t)
//! ```
//!
//! (Euler-Bernoulli bending, Timoshenko shear with the factor 1 that paper 004 uses for the
//! strip, axial); Lobontiu, "Compliant Mechanisms: Design of Flexure Hinges", CRC Press 2003,
//! Ch. 2, derives the notch hinges' closed forms the same way. So a hinge is its four
//! moments `int dx / t` and `int x^k dx / t^3`, k = 0, 1, 2, summed over its segments: a
//! strip (constant t) or a circular arc of the profile.
//!
//! An arc segment: `t = t0 + 2 rho (1 - cos phi)` and `x = x0 + lambda sin phi` (a circular
//! notch or fillet: `rho = lambda = R`; an elliptical notch: `rho = b`, `lambda = a`), over
//! `phi` in `[-pi/2, pi/2]` (a whole notch) or a half of it (a fillet). With
//! `c = 1 + t0 / (2 rho)` and `D = c - cos phi` the moments reduce to
//!
//! ```text
//! A1 = int cos/D      A3 = int cos/D^3      B3 = int sin cos/D^3      C3 = int sin^2 cos/D^3
//! int dx/t       = lambda / (2 rho) A1
//! int x^k dx/t^3 = lambda / (8 rho^3) int (x0 + lambda sin)^k cos/D^3
//! ```
//!
//! which the recurrence of `K_n = int dphi / D^n`, derived for flexopt by differentiating
//! `sin / D^n`,
//!
//! ```text
//! K1 = 2 / sqrt(c^2 - 1) atan(sqrt((c + 1) / (c - 1)) tan(phi / 2))
//! K(n+1) = ([sin / D^n] + (2n - 1) c K(n) - (n - 1) K(n-1)) / (n (c^2 - 1))
//! A1 = c K1 - K0,   A3 = c K3 - K2,   C3 = c (1 - c^2) K3 + (3 c^2 - 1) K2 - 3 c K1 + K0
//! B3 = 1 / (2 c s^2) on [0, pi/2] (s = c - 1), its negative on [-pi/2, 0]
//! ```
//!
//! gives exactly. For a shallow arc (c > 8: the notch's depth under a fourteenth of the
//! thickness) the recurrence loses digits to cancellation (C3 about c^3 of them), and the
//! moments come from their series in `cos / c` instead (Wallis integrals), to rounding. The
//! tests hold both against a numerical integration of the profile.

use super::super::scalar::Scalar;

/// The four moments of a hinge's thickness profile: `int dx / t` and `int x^k dx / t^3`.
#[derive(Debug, Clone, Copy)]
pub struct Moments<D> {
    pub i0: D,
    pub i3: [D; 3],
}

impl<D: Scalar> Moments<D> {
    pub fn zero() -> Self {
        let z = D::from(0.0);
        Moments { i0: z, i3: [z; 3] }
    }

    pub fn plus(self, o: Self) -> Self {
        Moments {
            i0: self.i0 + o.i0,
            i3: [
                self.i3[0] + o.i3[0],
                self.i3[1] + o.i3[1],
                self.i3[2] + o.i3[2],
            ],
        }
    }
}

/// A segment of constant thickness `t` from `x1` to `x2`.
pub fn strip<D: Scalar>(x1: D, x2: D, t: D) -> Moments<D> {
    let inv = t.recip();
    let inv3 = inv * inv * inv;
    Moments {
        i0: (x2 - x1) * inv,
        i3: [
            (x2 - x1) * inv3,
            (x2 * x2 - x1 * x1) * inv3 * 0.5,
            (x2 * x2 * x2 - x1 * x1 * x1) * inv3 * (1.0 / 3.0),
        ],
    }
}

/// Which part of an arc segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Span {
    /// `phi` in `[-pi/2, pi/2]`: a whole notch.
    Whole,
    /// `[-pi/2, 0]`: the first half (a fillet at the start).
    First,
    /// `[0, pi/2]`: the second half (a fillet at the end).
    Second,
}

/// `A1, A3, B3, C3` over `[0, pi/2]` for `c = 1 + s`.
fn half_integrals<D: Scalar>(s: D) -> [D; 4] {
    let c = s + 1.0;
    if c.re() > 8.0 {
        return half_series(c);
    }
    let c2m1 = s * (s + 2.0);
    let k0 = D::from(std::f64::consts::FRAC_PI_2);
    let k1 = ((s + 2.0) / s).sqrt().atan() * 2.0 / c2m1.sqrt();
    let inv_c = c.recip();
    let k2 = (inv_c + c * k1) / c2m1;
    let k3 = (inv_c * inv_c + c * k2 * 3.0 - k1) / (c2m1 * 2.0);
    let a1 = c * k1 - k0;
    let a3 = c * k3 - k2;
    let b3 = (c * s * s * 2.0).recip();
    let c3 = -(c * c2m1 * k3) + (c * c * 3.0 - 1.0) * k2 - c * k1 * 3.0 + k0;
    [a1, a3, b3, c3]
}

/// `int_0^{pi/2} cos^m`.
fn wallis(m: usize) -> f64 {
    // W0 = pi/2, W1 = 1, W(m) = (m - 1) / m W(m - 2)
    let mut w = if m.is_multiple_of(2) {
        std::f64::consts::FRAC_PI_2
    } else {
        1.0
    };
    let mut k = if m.is_multiple_of(2) { 2 } else { 3 };
    while k <= m {
        w *= (k - 1) as f64 / k as f64;
        k += 2;
    }
    w
}

/// The same integrals from `1 / (c - cos)^n = c^-n sum_k binom(n + k - 1, k) (cos / c)^k`.
fn half_series<D: Scalar>(c: D) -> [D; 4] {
    let inv = c.recip();
    let (mut a1, mut a3, mut c3) = (D::from(0.0), D::from(0.0), D::from(0.0));
    let mut p = D::from(1.0); // c^-k
    for k in 0..48usize {
        let kf = k as f64;
        let binom3 = 0.5 * (kf + 1.0) * (kf + 2.0);
        a1 = a1 + p * wallis(k + 1);
        a3 = a3 + p * (binom3 * wallis(k + 1));
        c3 = c3 + p * (binom3 * (wallis(k + 1) - wallis(k + 3)));
        p = p * inv;
    }
    let s = c - 1.0;
    let inv3 = inv * inv * inv;
    [a1 * inv, a3 * inv3, (c * s * s * 2.0).recip(), c3 * inv3]
}

/// An arc segment of the profile: `t = t0 + 2 rho (1 - cos phi)`, `x = x0 + lambda sin phi`.
pub fn arc<D: Scalar>(t0: D, rho: D, lambda: D, x0: D, span: Span) -> Moments<D> {
    let s = t0 / (rho * 2.0);
    let [a1, a3, b3, c3] = half_integrals(s);
    let (a1, a3, b3, c3) = match span {
        Span::Whole => (a1 * 2.0, a3 * 2.0, D::from(0.0), c3 * 2.0),
        Span::First => (a1, a3, -b3, c3),
        Span::Second => (a1, a3, b3, c3),
    };
    let f = lambda / (rho * rho * rho * 8.0);
    Moments {
        i0: lambda / (rho * 2.0) * a1,
        i3: [
            f * a3,
            f * (x0 * a3 + lambda * b3),
            f * (x0 * x0 * a3 + x0 * lambda * b3 * 2.0 + lambda * lambda * c3),
        ],
    }
}
