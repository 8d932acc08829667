//! [`Jet2<N>`]: a second-order forward-mode number, value, gradient and Hessian over `N`
//! independent variables, for the Hessians a robust study's spreads need
//! ([`super::mechanism::ModulusScaling::evaluate_with_hessian`]).
//!
//! Why beside num-dual's `Dual2SVec64<N>`, which gives the same derivatives: for the reason
//! [`super::scalar::Jet`] is beside its first-order numbers. num-dual keeps the gradient and
//! the Hessian as `Option`s of matrices and works the whole `N x N` Hessian; here they are
//! plain arrays and only the upper triangle is worked (the Hessian is symmetric), the lower
//! left at zero until [`Jet2::hessian`] mirrors it. The propagation rules are those of
//! second-order forward differentiation (Griewank and Walther, *Evaluating Derivatives*,
//! 2nd ed., SIAM 2008, Sec. 13.2): for `f(u)`, `f'' u' u'^T + f' u''`; for `u v`,
//! `u'' v + u v'' + u' v'^T + v' u'^T`.

use std::ops::{Add, Div, Mul, Sub};

use super::scalar::{sin_cos, Scalar};

/// Value, gradient and the upper triangle of the Hessian (`hess[i][j]`, `i <= j`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet2<const N: usize> {
    pub re: f64,
    pub grad: [f64; N],
    hess: [[f64; N]; N],
}

impl<const N: usize> Jet2<N> {
    /// The independent variable `i` with value `re`.
    pub fn variable(re: f64, i: usize) -> Self {
        let mut x = Self::from(re);
        x.grad[i] = 1.0;
        x
    }

    /// The whole Hessian, row-major, `N * N` entries into `out`.
    pub fn hessian(&self, out: &mut [f64]) {
        for i in 0..N {
            for j in i..N {
                out[i * N + j] = self.hess[i][j];
                out[j * N + i] = self.hess[i][j];
            }
        }
    }

    /// `f(self)` with value `re`, `f' = d1` and `f'' = d2`.
    #[inline(always)]
    fn chain(&self, re: f64, d1: f64, d2: f64) -> Self {
        let g = &self.grad;
        let mut hess = [[0.0; N]; N];
        for (i, row) in hess.iter_mut().enumerate() {
            let gi = d2 * g[i];
            for j in i..N {
                row[j] = d1 * self.hess[i][j] + gi * g[j];
            }
        }
        Jet2 {
            re,
            grad: g.map(|g| d1 * g),
            hess,
        }
    }

    /// `self * scale` for a constant `scale`, value `re`.
    #[inline(always)]
    fn scaled(&self, re: f64, scale: f64) -> Self {
        Jet2 {
            re,
            grad: self.grad.map(|g| g * scale),
            hess: self.hess.map(|row| row.map(|h| h * scale)),
        }
    }
}

impl<const N: usize> From<f64> for Jet2<N> {
    fn from(re: f64) -> Self {
        Jet2 {
            re,
            grad: [0.0; N],
            hess: [[0.0; N]; N],
        }
    }
}

/// The parameters `x` and the moduli's factor at one (the last of the `N`) as independent
/// variables: the inputs of a model's Hessians for its spreads.
pub(crate) fn seeded_with_modulus<const N: usize>(x: &[f64]) -> Vec<Jet2<N>> {
    (0..N)
        .map(|i| Jet2::variable(if i + 1 < N { x[i] } else { 1.0 }, i))
        .collect()
}

/// Values, gradients and Hessians (row-major, `N * N` per output) of `y`.
pub(crate) fn unseed2<const N: usize>(
    y: &[Jet2<N>],
    out: &mut [f64],
    jacobian: &mut [f64],
    hessian: &mut [f64],
) {
    for (i, yi) in y.iter().enumerate() {
        out[i] = yi.re;
        jacobian[i * N..(i + 1) * N].copy_from_slice(&yi.grad);
        yi.hessian(&mut hessian[i * N * N..(i + 1) * N * N]);
    }
}

impl<const N: usize> Add for Jet2<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Jet2 {
            re: self.re + o.re,
            grad: std::array::from_fn(|i| self.grad[i] + o.grad[i]),
            hess: std::array::from_fn(|i| std::array::from_fn(|j| self.hess[i][j] + o.hess[i][j])),
        }
    }
}

impl<const N: usize> Sub for Jet2<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Jet2 {
            re: self.re - o.re,
            grad: std::array::from_fn(|i| self.grad[i] - o.grad[i]),
            hess: std::array::from_fn(|i| std::array::from_fn(|j| self.hess[i][j] - o.hess[i][j])),
        }
    }
}

impl<const N: usize> Mul for Jet2<N> {
    type Output = Self;
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let (a, b) = (&self.grad, &o.grad);
        let mut hess = [[0.0; N]; N];
        for (i, row) in hess.iter_mut().enumerate() {
            for j in i..N {
                row[j] =
                    self.hess[i][j] * o.re + o.hess[i][j] * self.re + a[i] * b[j] + b[i] * a[j];
            }
        }
        Jet2 {
            re: self.re * o.re,
            grad: std::array::from_fn(|i| a[i] * o.re + b[i] * self.re),
            hess,
        }
    }
}

impl<const N: usize> Div for Jet2<N> {
    type Output = Self;
    // q = u / v from u = q v: q' = (u' - q v') / v, q'' = (u'' - q v'' - q' v'^T - v' q'^T) / v
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let q = self.re * inv;
        let gq: [f64; N] = std::array::from_fn(|i| (self.grad[i] - q * o.grad[i]) * inv);
        let gv = &o.grad;
        let mut hess = [[0.0; N]; N];
        for (i, row) in hess.iter_mut().enumerate() {
            for j in i..N {
                row[j] = (self.hess[i][j] - q * o.hess[i][j] - gq[i] * gv[j] - gv[i] * gq[j]) * inv;
            }
        }
        Jet2 {
            re: q,
            grad: gq,
            hess,
        }
    }
}

super::scalar::constant_ops!(Jet2, scaled);

impl<const N: usize> Scalar for Jet2<N> {
    const SECOND_ORDER: bool = true;

    fn re(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn recip(self) -> Self {
        let r = 1.0 / self.re;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = sin_cos(self.re);
        (self.chain(s, c, -s), self.chain(c, -s, -c))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let r = self.re.sqrt();
        let d1 = 0.5 / r;
        self.chain(r, d1, -0.5 * d1 / self.re)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        match n {
            0 => Self::from(1.0),
            1 => self,
            _ => {
                let p = self.re.powi(n - 2);
                let nf = n as f64;
                self.chain(p * self.re * self.re, nf * p * self.re, nf * (nf - 1.0) * p)
            }
        }
    }
    #[inline(always)]
    fn powf(self, n: f64) -> Self {
        let p = self.re.powf(n - 2.0);
        self.chain(p * self.re * self.re, n * p * self.re, n * (n - 1.0) * p)
    }
    #[inline(always)]
    fn atan(self) -> Self {
        let d1 = 1.0 / (1.0 + self.re * self.re);
        self.chain(self.re.atan(), d1, -2.0 * self.re * d1 * d1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scalar::tests::f;
    use num_dual::Dual2SVec64;

    #[test]
    fn jet2_derivatives_match_num_dual() {
        use nalgebra::{Const, U1};
        for &(x, y) in &[(0.3, -1.7), (2.0, 0.5), (-1.1, 3.3)] {
            let j = f(Jet2::<2>::variable(x, 0), Jet2::variable(y, 1));
            let d = f(
                Dual2SVec64::<2>::from_re(x).derivative(0),
                Dual2SVec64::from_re(y).derivative(1),
            );
            let g = d.v1.unwrap_generic(U1, Const::<2>);
            let h = d.v2.unwrap_generic(Const::<2>, Const::<2>);
            let mut jh = [0.0; 4];
            j.hessian(&mut jh);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs().max(1.0);
            assert!(close(j.re, d.re), "{} vs {}", j.re, d.re);
            for i in 0..2 {
                assert!(close(j.grad[i], g[i]), "{i}: {} vs {}", j.grad[i], g[i]);
                for l in 0..2 {
                    assert!(
                        close(jh[i * 2 + l], h[(i, l)]),
                        "({i}, {l}): {} vs {}",
                        jh[i * 2 + l],
                        h[(i, l)]
                    );
                }
            }
        }
    }
}
