//! The scalar type the models are written over.
//!
//! Every model function is generic over [`Scalar`]: with `f64` it gives values; with a
//! dual number it gives values and exact gradients from the same code. [`Scalar`] asks
//! only for the operations the models use, and is implemented for
//!
//! - `f64`, and num-dual's `Dual64` and `DualSVec64<N>`, and its second-order
//!   `Dual2SVec64<N>` (against which the tests check [`super::jet2::Jet2`], the Hessians a
//!   robust study's spreads need), and
//! - [`Jet<N>`], a first-order forward-mode number with a plain `[f64; N]` gradient.
//!
//! Why a type of our own beside num-dual: num-dual keeps each gradient as an
//! `Option<SVector>`, and that bookkeeping dominated the cost of the bridge model. On the
//! eight-parameter bridge the `Jet<8>` evaluation of wei2017's objective and constraints
//! with gradients ran about 2.5 times faster than `DualSVec64<8>` in the same criterion run
//! (see `benches/bridge.rs`). `tests/models/bridge_model.rs` checks that both give the same gradients.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_dual::DualNum;

/// A real number, or a dual number over `f64` that carries derivatives along.
pub trait Scalar:
    Copy
    + Debug
    + From<f64>
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// The real part.
    fn re(&self) -> f64;
    fn recip(self) -> Self;
    fn sin_cos(self) -> (Self, Self);
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    /// `-self` where the real part is negative: a forward-mode number's rule.
    #[inline(always)]
    fn abs(self) -> Self {
        if self.re() < 0.0 {
            -self
        } else {
            self
        }
    }
    fn sqrt(self) -> Self;
    fn powi(self, n: i32) -> Self;
    /// `self^n` for a real exponent (`self > 0`).
    fn powf(self, n: f64) -> Self;
    fn atan(self) -> Self;

    /// Whether [`Scalar::from_partials`] is how this number is best built from a function
    /// whose partial derivatives are known in closed form: for a number of first
    /// derivatives alone ([`Jet`]). Not for `f64` (no tangent: the function's own code is as
    /// cheap), the second-order numbers (the partials miss their second derivatives) or
    /// num-dual's first-order ones (the tests' independent path, kept the function's own).
    const FROM_PARTIALS: bool = false;

    /// Whether the number carries second derivatives (a robust study's Hessians): a value
    /// whose derivatives are built from first-order ones alone (an equilibrium's, through
    /// the implicit function theorem) refuses such a number rather than give it wrong ones.
    const SECOND_ORDER: bool = false;

    /// The value `re` of a function of `args` whose partial derivatives there are
    /// `partials` (one per argument), with the chain rule's first derivatives
    /// `sum_k partials[k] args[k]'`: the local preaccumulation of Griewank and Walther,
    /// "Evaluating Derivatives", 2nd ed., SIAM 2008 (its chapter on Jacobian accumulation),
    /// the local Jacobian written out. First order only: callers ask
    /// [`Scalar::FROM_PARTIALS`] first.
    fn from_partials(re: f64, args: &[Self], partials: &[f64]) -> Self {
        args.iter()
            .zip(partials)
            .fold(Self::from(re), |sum, (&a, &p)| sum + (a - a.re()) * p)
    }
}

impl Scalar for f64 {
    fn re(&self) -> f64 {
        *self
    }
    #[inline(always)]
    fn recip(self) -> Self {
        1.0 / self
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        sin_cos(self)
    }
    fn abs(self) -> Self {
        f64::abs(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn powi(self, n: i32) -> Self {
        f64::powi(self, n)
    }
    fn powf(self, n: f64) -> Self {
        f64::powf(self, n)
    }
    fn atan(self) -> Self {
        f64::atan(self)
    }
}

/// num-dual's numbers over `f64` are scalars too, so every model can be differentiated with
/// num-dual as well; the tests use this to check [`Jet`] against an independent
/// implementation.
macro_rules! num_dual_scalar {
    ($($t:ty $(, const $n:ident)? => $second:expr);*) => {$(
        impl$(<const $n: usize>)? Scalar for $t {
            const SECOND_ORDER: bool = $second;
            fn re(&self) -> f64 {
                num_dual::DualStruct::re(self)
            }
            fn recip(self) -> Self {
                DualNum::recip(&self)
            }
            fn sin_cos(self) -> (Self, Self) {
                DualNum::sin_cos(&self)
            }
            fn abs(self) -> Self {
                num_traits::Signed::abs(&self)
            }
            fn sqrt(self) -> Self {
                DualNum::sqrt(&self)
            }
            fn powi(self, n: i32) -> Self {
                DualNum::powi(&self, n)
            }
            fn powf(self, n: f64) -> Self {
                DualNum::powf(&self, n)
            }
            fn atan(self) -> Self {
                DualNum::atan(&self)
            }
        }
    )*};
}

num_dual_scalar!(
    num_dual::Dual64 => false;
    num_dual::DualSVec64<N>, const N => false;
    num_dual::Dual2SVec64<N>, const N => true
);

/// `sin` and `cos` of `x`: for `|x| <= pi/4`, where every angle of Table 1's bounds lies,
/// by the minimax polynomial kernels of fdlibm (no argument reduction needed, error within
/// one unit in the last place); elsewhere by the standard library. Three libm `sin_cos`
/// calls were a third of the bridge model's cost.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > std::f64::consts::FRAC_PI_4 {
        return x.sin_cos();
    }
    // the coefficients as fdlibm publishes them; the last digits round away in f64
    #[allow(clippy::excessive_precision)]
    const S: [f64; 6] = [
        -1.66666666666666324348e-01,
        8.33333333332248946124e-03,
        -1.98412698298579493134e-04,
        2.75573137070700676789e-06,
        -2.50507602534068634195e-08,
        1.58969099521155010221e-10,
    ];
    #[allow(clippy::excessive_precision)]
    const C: [f64; 6] = [
        4.16666666666666019037e-02,
        -1.38888888888741095749e-03,
        2.48015872894767294178e-05,
        -2.75573143513906633035e-07,
        2.08757232129817482790e-09,
        -1.13596475577881948265e-11,
    ];
    let z = x * x;
    let rs = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
    let sin = x + z * x * (S[0] + z * rs);
    let rc = z * (C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5])))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let cos = w + (((1.0 - w) - hz) + z * rc);
    (sin, cos)
}

/// The real part of a scalar.
#[inline]
pub fn re<D: Scalar>(x: D) -> f64 {
    x.re()
}

/// The larger of two scalars, carrying the derivatives of the one chosen.
#[inline]
pub fn max<D: Scalar>(a: D, b: D) -> D {
    if a.re() >= b.re() {
        a
    } else {
        b
    }
}

/// The angle of `(x, y)` in `(-pi, pi]`, from `atan` of the smaller ratio so that neither
/// division is by a number near zero; its derivatives are atan's, the branch constants
/// having none.
pub fn atan2<D: Scalar>(y: D, x: D) -> D {
    if x.re().abs() >= y.re().abs() {
        let a = (y / x).atan();
        if x.re() > 0.0 {
            a
        } else if y.re() >= 0.0 {
            a + PI
        } else {
            a - PI
        }
    } else {
        let half = if y.re() > 0.0 { FRAC_PI_2 } else { -FRAC_PI_2 };
        -(x / y).atan() + half
    }
}

/// The smaller of two scalars, carrying the derivatives of the one chosen.
#[inline]
pub fn min<D: Scalar>(a: D, b: D) -> D {
    if a.re() <= b.re() {
        a
    } else {
        b
    }
}

/// A first-order forward-mode dual number: a value and its gradient with respect to `N`
/// independent variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet<const N: usize> {
    pub re: f64,
    pub grad: [f64; N],
}

impl<const N: usize> Jet<N> {
    /// The independent variable `i` with value `re`.
    pub fn variable(re: f64, i: usize) -> Self {
        let mut grad = [0.0; N];
        grad[i] = 1.0;
        Jet { re, grad }
    }

    /// `re` with gradient `grad * scale`: the chain rule through a function of one argument
    /// whose derivative is `scale`.
    #[inline(always)]
    fn chain(self, re: f64, scale: f64) -> Self {
        Jet {
            re,
            grad: self.grad.map(|g| g * scale),
        }
    }
}

impl<const N: usize> From<f64> for Jet<N> {
    fn from(re: f64) -> Self {
        Jet { re, grad: [0.0; N] }
    }
}

impl<const N: usize> Add for Jet<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Jet {
            re: self.re + o.re,
            grad: std::array::from_fn(|i| self.grad[i] + o.grad[i]),
        }
    }
}

impl<const N: usize> Sub for Jet<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Jet {
            re: self.re - o.re,
            grad: std::array::from_fn(|i| self.grad[i] - o.grad[i]),
        }
    }
}

impl<const N: usize> Mul for Jet<N> {
    type Output = Self;
    // the product rule: (uv)' = u'v + uv'
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Jet {
            re: self.re * o.re,
            grad: std::array::from_fn(|i| self.grad[i] * o.re + o.grad[i] * self.re),
        }
    }
}

impl<const N: usize> Div for Jet<N> {
    type Output = Self;
    // the quotient rule: (u/v)' = (u' - (u/v) v') / v
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let re = self.re * inv;
        Jet {
            re,
            grad: std::array::from_fn(|i| (self.grad[i] - o.grad[i] * re) * inv),
        }
    }
}

/// A forward-mode number's negation and its operations with a constant, by its method
/// `$scaled(re, scale)`: value `re`, every derivative times `scale`.
macro_rules! constant_ops {
    ($t:ident, $scaled:ident) => {
        impl<const N: usize> std::ops::Neg for $t<N> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                self.$scaled(-self.re, -1.0)
            }
        }

        impl<const N: usize> std::ops::Add<f64> for $t<N> {
            type Output = Self;
            #[inline(always)]
            fn add(mut self, o: f64) -> Self {
                self.re += o;
                self
            }
        }

        impl<const N: usize> std::ops::Sub<f64> for $t<N> {
            type Output = Self;
            #[inline(always)]
            fn sub(mut self, o: f64) -> Self {
                self.re -= o;
                self
            }
        }

        impl<const N: usize> std::ops::Mul<f64> for $t<N> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: f64) -> Self {
                self.$scaled(self.re * o, o)
            }
        }

        impl<const N: usize> std::ops::Div<f64> for $t<N> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: f64) -> Self {
                let inv = 1.0 / o;
                self.$scaled(self.re * inv, inv)
            }
        }
    };
}
pub(crate) use constant_ops;

constant_ops!(Jet, chain);

/// `$call` with the const `$N` the count `$n` of a design's parameters, one of 1 to
/// [`crate::model::MAX_PARAMETERS`]: a model's evaluation with gradients runs over
/// `Jet<N>` with as many derivatives as the design has parameters (a `Jet<16>` carried 16
/// through every operation whatever the count). Panics on another count.
macro_rules! with_count {
    ($n:expr, |$N:ident| $call:expr) => {
        $crate::model::scalar::with_count!(@each $n, $N, $call, 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
    };
    (@each $n:expr, $N:ident, $call:expr, $($k:literal)*) => {
        match $n {
            $($k => {
                const $N: usize = $k;
                $call
            })*
            n => panic!(
                "a design has 1 to {} parameters, got {n}",
                $crate::model::MAX_PARAMETERS
            ),
        }
    };
}
pub(crate) use with_count;

// `with_count!`'s arms are written out to the largest count
const _: () = assert!(crate::model::MAX_PARAMETERS == 16);

impl<const N: usize> Scalar for Jet<N> {
    fn re(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn recip(self) -> Self {
        let r = 1.0 / self.re;
        self.chain(r, -r * r)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = sin_cos(self.re);
        (self.chain(s, c), self.chain(c, -s))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let r = self.re.sqrt();
        self.chain(r, 0.5 / r)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        let p = self.re.powi(n - 1);
        self.chain(p * self.re, n as f64 * p)
    }
    #[inline(always)]
    fn powf(self, n: f64) -> Self {
        let p = self.re.powf(n - 1.0);
        self.chain(p * self.re, n * p)
    }
    #[inline(always)]
    fn atan(self) -> Self {
        self.chain(self.re.atan(), 1.0 / (1.0 + self.re * self.re))
    }

    const FROM_PARTIALS: bool = true;

    #[inline(always)]
    fn from_partials(re: f64, args: &[Self], partials: &[f64]) -> Self {
        let mut grad = [0.0; N];
        for (a, &p) in args.iter().zip(partials) {
            for (g, &d) in grad.iter_mut().zip(&a.grad) {
                *g += d * p;
            }
        }
        Jet { re, grad }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use num_dual::DualSVec64;

    /// A function that uses every operation of the trait.
    pub(crate) fn f<D: Scalar>(x: D, y: D) -> D {
        let (s, c) = (x * y).sin_cos();
        (s + c * 2.0 - 1.0) / (x.powi(3) + 3.0) * y.abs().sqrt() - (x / y).recip() / 2.0
            + -(x - y).cos()
            + (x * 0.5 - y).atan()
            + (x * x + 1.0).powf(0.45)
            + x.sin()
            + (y * 0.3).powi(2) * x.powi(-2)
            - x * 1.5
    }

    #[test]
    fn jet_gradients_match_num_dual() {
        for &(x, y) in &[(0.3, -1.7), (2.0, 0.5), (-1.1, 3.3)] {
            let j = f(Jet::<2>::variable(x, 0), Jet::variable(y, 1));
            let d = f(
                DualSVec64::<2>::from_re(x).derivative(0),
                DualSVec64::from_re(y).derivative(1),
            );
            let g = d.eps.0.unwrap();
            assert!((j.re - d.re).abs() <= 1e-15 * d.re.abs().max(1.0));
            for i in 0..2 {
                assert!(
                    (j.grad[i] - g[i]).abs() <= 1e-14 * g[i].abs().max(1.0),
                    "{i}: {} vs {}",
                    j.grad[i],
                    g[i]
                );
            }
        }
    }

    #[test]
    fn polynomial_sin_cos_is_within_one_ulp_of_libm() {
        let ulp = |a: f64, b: f64| ((a.to_bits() as i64) - (b.to_bits() as i64)).unsigned_abs();
        let n = 200_000;
        let mut worst = (0, 0);
        for i in 0..=n {
            // dense near zero too: both uniform and geometric spacing
            let u = -1.0 + 2.0 * i as f64 / n as f64;
            for x in [
                u * std::f64::consts::FRAC_PI_4,
                u.signum() * 1e-9f64.powf(1.0 - u.abs()) * 0.78,
            ] {
                let (s, c) = sin_cos(x);
                let (ls, lc) = x.sin_cos();
                worst = (worst.0.max(ulp(s, ls)), worst.1.max(ulp(c, lc)));
            }
        }
        assert!(
            worst.0 <= 1 && worst.1 <= 1,
            "sin {} ulp, cos {} ulp",
            worst.0,
            worst.1
        );
        // outside the kernel's range the library is used
        assert_eq!(sin_cos(2.0), 2.0f64.sin_cos());
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
    }

    #[test]
    fn from_partials_is_the_chain_rule() {
        // f(u, v) = u^2 v at (u, v) with u = x + y, v = x y
        let (x, y) = (Jet::<2>::variable(0.7, 0), Jet::<2>::variable(-1.3, 1));
        let (u, v) = (x + y, x * y);
        let direct = u * u * v;
        let (du, dv) = (2.0 * u.re * v.re, u.re * u.re);
        let chained = Jet::from_partials(direct.re, &[u, v], &[du, dv]);
        // the generic default, as num-dual's numbers would have it
        let generic = [u, v]
            .iter()
            .zip([du, dv])
            .fold(Jet::from(direct.re), |s, (&a, p)| s + (a - a.re) * p);
        const { assert!(<Jet<2> as Scalar>::FROM_PARTIALS && !<f64 as Scalar>::FROM_PARTIALS) };
        assert_eq!(chained.re, direct.re);
        for i in 0..2 {
            let g = direct.grad[i];
            assert!((chained.grad[i] - g).abs() <= 1e-15 * g.abs(), "{i}");
            assert!((generic.grad[i] - g).abs() <= 1e-15 * g.abs(), "{i}");
        }
    }

    #[test]
    fn jet_constants_carry_no_gradient() {
        let c = Jet::<3>::from(2.5);
        assert_eq!(c.grad, [0.0; 3]);
        assert_eq!((c * Jet::variable(1.0, 1)).grad, [0.0, 2.5, 0.0]);
    }
}
