//! Step responses of single-degree-of-freedom systems `m x'' + c x' + k x = F`, integrated
//! with the classical fourth-order Runge-Kutta method as paper 001 does (Sec. 4.2), with the
//! measures it reports: the step displacement `Sp`, the settling time `ts` into a +-2 % band
//! and the maximum overshoot `Mp`.
//!
//! The step is chosen from the natural frequency and the requested accuracy, so that a user
//! never tunes it: RK4's global error on an oscillator grows like `(omega h)^4` per unit of
//! `omega t`, so `h = tol^(1/4) / omega` (with a margin) keeps the relative error near `tol`.
//! Crossings of the band are located within a step by the cubic Hermite interpolant of the
//! computed positions and velocities.

use serde::Serialize;

/// Table 4 of paper 001: the platform's natural frequencies (theory, Hz) with their
/// identified damping ratios. The table prints the ratios in percent (0.28 %...); they are
/// stored here as fractions.
pub const PAPER001_TABLE4: [(f64, f64); 6] = [
    (46.637, 0.0028),
    (52.421, 0.0073),
    (52.420, 0.0086),
    (79.246, 0.0016),
    (88.598, 0.0079),
    (88.598, 0.0034),
];

/// `m x'' + c x' + k x = F` for `t >= 0`, at rest at `x = 0` before.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Oscillator {
    pub mass: f64,
    pub damping: f64,
    pub stiffness: f64,
}

impl Oscillator {
    /// The oscillator of natural frequency `f` (Hz) and damping ratio `zeta`, of unit mass:
    /// `C = 2 zeta sqrt(M K)` (paper 001, Sec. 2.2).
    pub fn from_frequency(f: f64, zeta: f64) -> Self {
        let omega = 2.0 * std::f64::consts::PI * f;
        Oscillator {
            mass: 1.0,
            damping: 2.0 * zeta * omega,
            stiffness: omega * omega,
        }
    }

    /// Natural angular frequency (rad/s).
    pub fn omega(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }

    pub fn damping_ratio(&self) -> f64 {
        self.damping / (2.0 * (self.stiffness * self.mass).sqrt())
    }

    fn acceleration(&self, force: f64, x: f64, v: f64) -> f64 {
        (force - self.damping * v - self.stiffness * x) / self.mass
    }

    /// One classical RK4 step of `(x, v)` under the constant force.
    pub fn rk4_step(&self, force: f64, (x, v): (f64, f64), h: f64) -> (f64, f64) {
        let a = |x: f64, v: f64| self.acceleration(force, x, v);
        let (k1x, k1v) = (v, a(x, v));
        let (k2x, k2v) = (v + 0.5 * h * k1v, a(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, a(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, a(x + h * k3x, v + h * k3v));
        (
            x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
            v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
        )
    }

    /// The step of RK4 for a relative accuracy of about `tolerance`.
    pub fn step_for(&self, tolerance: f64) -> f64 {
        // the fastest time scale: the natural period, or the fast pole of an overdamped system
        let zeta = self.damping_ratio();
        let fast = self.omega()
            * if zeta > 1.0 {
                zeta + (zeta * zeta - 1.0).sqrt()
            } else {
                1.0
            };
        0.5 * tolerance.powf(0.25) / fast
    }

    /// Time by which the response has settled for certain: ten time constants of the slowest
    /// decay, and at least two natural periods.
    fn horizon(&self) -> f64 {
        let (omega, zeta) = (self.omega(), self.damping_ratio());
        let slow = if zeta >= 1.0 {
            omega * (zeta - (zeta * zeta - 1.0).sqrt())
        } else {
            zeta * omega
        };
        (10.0 / slow.max(1e-300)).max(4.0 * std::f64::consts::PI / omega)
    }
}

/// The measures of a step response.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepResponse {
    /// Final displacement `F / k` (Sp).
    pub step_displacement: f64,
    /// Time after which the response stays within `band` of the final value (ts).
    pub settling_time: f64,
    /// Largest excess over the final value, relative to it (Mp); 0 without overshoot.
    pub overshoot: f64,
    /// The integration step used.
    pub step: f64,
}

/// The response to a step force `force` from rest, with settling band `band` (0.02 for
/// +-2 %), integrated to relative accuracy about `tolerance`.
pub fn step_response(osc: &Oscillator, force: f64, band: f64, tolerance: f64) -> StepResponse {
    let h = osc.step_for(tolerance);
    let steps = (osc.horizon() / h).ceil() as usize;
    let xf = force / osc.stiffness;
    let limit = band * xf.abs();
    let (mut state, mut t) = ((0.0, 0.0), 0.0);
    let mut settling = 0.0;
    let mut peak = 0.0f64;
    for _ in 0..steps {
        let next = osc.rk4_step(force, state, h);
        let outside = |s: (f64, f64)| (s.0 - xf).abs() > limit;
        // the last step that ends inside the band after starting outside it holds ts
        if outside(state) && !outside(next) {
            settling = crossing(state, next, t, h, xf, limit);
        } else if outside(next) {
            settling = t + h;
        }
        // the peak: where the velocity changes sign from positive to negative
        if state.1 > 0.0 && next.1 <= 0.0 {
            peak = peak.max(hermite_max(state, next, h));
        }
        state = next;
        t += h;
    }
    StepResponse {
        step_displacement: xf,
        settling_time: settling,
        overshoot: ((peak - xf) / xf).max(0.0),
        step: h,
    }
}

/// The cubic Hermite interpolant of `x` over one step, from the positions and velocities at
/// its ends, at `s` in `[0, 1]`.
fn hermite(a: (f64, f64), b: (f64, f64), h: f64, s: f64) -> f64 {
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * a.0
        + (s3 - 2.0 * s2 + s) * h * a.1
        + (-2.0 * s3 + 3.0 * s2) * b.0
        + (s3 - s2) * h * b.1
}

/// Where within the step `[t, t + h]` the response enters the band, by bisection on the
/// Hermite interpolant.
fn crossing(a: (f64, f64), b: (f64, f64), t: f64, h: f64, xf: f64, limit: f64) -> f64 {
    let outside = |s: f64| (hermite(a, b, h, s) - xf).abs() > limit;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if outside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    t + hi * h
}

/// The derivative of the Hermite interpolant with respect to `s`.
fn hermite_slope(a: (f64, f64), b: (f64, f64), h: f64, s: f64) -> f64 {
    let s2 = s * s;
    (6.0 * s2 - 6.0 * s) * a.0
        + (3.0 * s2 - 4.0 * s + 1.0) * h * a.1
        + (-6.0 * s2 + 6.0 * s) * b.0
        + (3.0 * s2 - 2.0 * s) * h * b.1
}

/// The largest value of the Hermite interpolant over a step in which the velocity turns
/// from positive to negative, by bisection on its derivative.
fn hermite_max(a: (f64, f64), b: (f64, f64), h: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if hermite_slope(a, b, h, mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hermite(a, b, h, 0.5 * (lo + hi)).max(a.0).max(b.0)
}

/// The exact settling time into `band` (0.02 for +-2 %) of the step response, from the
/// exact solution: for an underdamped system the deviation from the final value has its
/// extremes `exp(-zeta omega t_k)` at `t_k = k pi / omega_d`, so the last extreme outside the
/// band is known in closed form and the band is entered before the next one, where the
/// deviation falls monotonically: bisection there. A system at or above critical damping
/// approaches monotonically: bisection from the start.
pub fn exact_settling_time(osc: &Oscillator, band: f64) -> f64 {
    let (omega, zeta) = (osc.omega(), osc.damping_ratio());
    let deviation = |t: f64| exact_step(osc, 1.0, t) * osc.stiffness - 1.0;
    let (lo, hi, sign) = if zeta < 1.0 {
        let period = std::f64::consts::PI / (omega * (1.0 - zeta * zeta).sqrt());
        // the largest k with exp(-zeta omega k period) > band
        let k = ((-band.ln()) / (zeta * omega * period)).ceil() - 1.0;
        let k = k.max(0.0);
        let sign = if (k as u64).is_multiple_of(2) {
            -1.0
        } else {
            1.0
        };
        (k * period, (k + 1.0) * period, sign)
    } else {
        (0.0, osc.horizon(), -1.0)
    };
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if deviation(mid) * sign > band {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= f64::EPSILON * hi {
            break;
        }
    }
    hi
}

/// The exact response `x(t)` to a step force from rest.
pub fn exact_step(osc: &Oscillator, force: f64, t: f64) -> f64 {
    let (omega, zeta) = (osc.omega(), osc.damping_ratio());
    let xf = force / osc.stiffness;
    if (zeta - 1.0).abs() < 1e-12 {
        return xf * (1.0 - (1.0 + omega * t) * (-omega * t).exp());
    }
    if zeta < 1.0 {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let decay = (-zeta * omega * t).exp();
        xf * (1.0 - decay * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin()))
    } else {
        let root = (zeta * zeta - 1.0).sqrt();
        let (s1, s2) = (-omega * (zeta - root), -omega * (zeta + root));
        xf * (1.0 + (s2 * (s1 * t).exp() - s1 * (s2 * t).exp()) / (s1 - s2))
    }
}

/// The largest error of the RK4 response with step `h` against [`exact_step`] over
/// `[0, t_end]`, relative to the final displacement.
pub fn max_relative_error(osc: &Oscillator, force: f64, h: f64, t_end: f64) -> f64 {
    let n = (t_end / h).ceil() as usize;
    let xf = force / osc.stiffness;
    let mut state = (0.0, 0.0);
    let mut worst = 0.0f64;
    for i in 1..=n {
        state = osc.rk4_step(force, state, h);
        worst = worst.max((state.0 - exact_step(osc, force, i as f64 * h)).abs());
    }
    worst / xf.abs()
}
