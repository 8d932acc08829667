//! Exact rational arithmetic as a `Scalar`, for reference values.
//!
//! Every operation of the bridge's closed form is rational once the sines and cosines are
//! fixed. Evaluated on `Exact`, with the f64 sines and cosines taken as exact inputs, the
//! closed form gives the exact value of the formula for the very inputs the f64 evaluation
//! sees, so the f64 result's error is measured, not estimated.
//!
//! `Scalar` values are `Copy`; an `Exact` is a handle into a per-thread arena of rationals.

use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

use flexopt::model::scalar::Scalar;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

thread_local! {
    static ARENA: RefCell<Vec<BigRational>> = const { RefCell::new(Vec::new()) };
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exact(usize);

fn push(v: BigRational) -> Exact {
    ARENA.with(|a| {
        let mut a = a.borrow_mut();
        a.push(v);
        Exact(a.len() - 1)
    })
}

fn get(e: Exact) -> BigRational {
    ARENA.with(|a| a.borrow()[e.0].clone())
}

fn rational(v: f64) -> BigRational {
    BigRational::from_float(v).expect("a finite f64")
}

impl Exact {
    pub fn to_f64(self) -> f64 {
        get(self).to_f64().unwrap_or(f64::NAN)
    }

    /// Frees the arena (handles made before become invalid).
    pub fn reset() {
        ARENA.with(|a| a.borrow_mut().clear());
    }
}

impl From<f64> for Exact {
    fn from(v: f64) -> Self {
        push(rational(v))
    }
}

macro_rules! binary {
    ($tr:ident, $m:ident, $op:tt) => {
        impl $tr for Exact {
            type Output = Exact;
            fn $m(self, o: Exact) -> Exact {
                push(get(self) $op get(o))
            }
        }
        impl $tr<f64> for Exact {
            type Output = Exact;
            fn $m(self, o: f64) -> Exact {
                push(get(self) $op rational(o))
            }
        }
    };
}

binary!(Add, add, +);
binary!(Sub, sub, -);
binary!(Mul, mul, *);
binary!(Div, div, /);

impl Neg for Exact {
    type Output = Exact;
    fn neg(self) -> Exact {
        push(-get(self))
    }
}

impl Scalar for Exact {
    fn re(&self) -> f64 {
        self.to_f64()
    }
    fn recip(self) -> Self {
        push(get(self).recip())
    }
    /// The f64 sine and cosine of the (rounded) angle, taken as exact.
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = flexopt::model::scalar::sin_cos(self.to_f64());
        (Exact::from(s), Exact::from(c))
    }
    fn abs(self) -> Self {
        push(get(self).abs())
    }
    fn sqrt(self) -> Self {
        Exact::from(self.to_f64().sqrt())
    }
    /// The f64 arc tangent of the (rounded) value, taken as exact (the strip bridge, which
    /// this reference checks, uses none).
    fn atan(self) -> Self {
        Exact::from(self.to_f64().atan())
    }
    /// The f64 power of the (rounded) value, taken as exact (likewise unused by the strip).
    fn powf(self, n: f64) -> Self {
        Exact::from(self.to_f64().powf(n))
    }
    fn powi(self, n: i32) -> Self {
        let v = get(self);
        let mut r = BigRational::from_integer(1.into());
        for _ in 0..n.unsigned_abs() {
            r *= &v;
        }
        push(if n < 0 && !r.is_zero() { r.recip() } else { r })
    }
}
