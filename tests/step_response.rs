//! Fourth-order Runge-Kutta step responses (paper 001, Sec. 4.2) against the exact solution
//! of the damped single-degree-of-freedom oscillator.

use flexopt::dynamics::{exact_step, step_response, Oscillator, PAPER001_TABLE4};

/// The largest error over `[0, t_end]` for step `h` (at one instant the error may pass
/// near zero for some step, which would spoil the fit).
fn error_at(osc: &Oscillator, t_end: f64, h: f64) -> f64 {
    let n = (t_end / h).round() as usize;
    let mut state = (0.0, 0.0);
    let mut worst = 0.0f64;
    for i in 1..=n {
        state = osc.rk4_step(1.0, state, h);
        worst = worst.max((state.0 - exact_step(osc, 1.0, i as f64 * h)).abs());
    }
    worst
}

#[test]
fn runge_kutta_is_fourth_order() {
    for &(f, zeta) in &[(50.0, 0.05), (50.0, 0.3), (50.0, 1.0), (50.0, 2.5)] {
        let osc = Oscillator::from_frequency(f, zeta);
        let t_end = 3.0 / f;
        // steps from the one for 1e-2 accuracy down by halves: inside RK4's stability region
        // (an overdamped system's fast pole sets it) and coarse enough that rounding does not
        // reach the error
        let h0 = osc.step_for(1e-2);
        let hs: Vec<f64> = (0..5).map(|i| h0 / 2f64.powi(i)).collect();
        let errs: Vec<f64> = hs.iter().map(|&h| error_at(&osc, t_end, h)).collect();
        assert!(errs.iter().all(|&e| e > 1e-12 / osc.stiffness), "{errs:?}");
        // least-squares slope of log(error) against log(h)
        let (lx, ly): (Vec<f64>, Vec<f64>) =
            hs.iter().zip(&errs).map(|(h, e)| (h.ln(), e.ln())).unzip();
        let n = lx.len() as f64;
        let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
        let slope = lx
            .iter()
            .zip(&ly)
            .map(|(x, y)| (x - mx) * (y - my))
            .sum::<f64>()
            / lx.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
        eprintln!("zeta {zeta}: errors {errs:?}, order {slope:.3}");
        assert!(slope >= 3.9, "order {slope} for zeta {zeta}");
    }
}

/// The exact settling time: the last time the exact response is outside the band, found by
/// scanning finely and bisecting.
fn exact_settling(osc: &Oscillator, band: f64) -> f64 {
    let xf = 1.0 / osc.stiffness;
    let outside = |t: f64| (exact_step(osc, 1.0, t) - xf).abs() > band * xf;
    let dt = 1e-4 / (osc.omega() / (2.0 * std::f64::consts::PI));
    let mut t = 40.0 / (osc.damping_ratio() * osc.omega()).min(osc.omega());
    while !outside(t) && t > 0.0 {
        t -= dt;
    }
    let (mut lo, mut hi) = (t, t + dt);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if outside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

#[test]
fn settling_time_agrees_with_the_exact_one_to_within_a_step() {
    for &(f, zeta) in PAPER001_TABLE4
        .iter()
        .chain(&[(10.0, 0.02), (10.0, 1.0), (10.0, 3.0)])
    {
        let osc = Oscillator::from_frequency(f, zeta);
        let r = step_response(&osc, 1.0, 0.02, 1e-6);
        let exact = exact_settling(&osc, 0.02);
        assert!(
            (r.settling_time - exact).abs() <= r.step,
            "f {f} zeta {zeta}: {} vs {exact} (step {})",
            r.settling_time,
            r.step
        );
        // overshoot: exp(-pi zeta / sqrt(1 - zeta^2)) for an underdamped system
        if zeta < 1.0 {
            let mp = (-std::f64::consts::PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
            assert!(
                (r.overshoot - mp).abs() <= 1e-6,
                "f {f} zeta {zeta}: Mp {} vs {mp}",
                r.overshoot
            );
        } else {
            assert_eq!(r.overshoot, 0.0);
        }
    }
}

#[test]
fn the_default_step_gives_the_requested_accuracy() {
    for &(f, zeta) in &PAPER001_TABLE4 {
        let osc = Oscillator::from_frequency(f, zeta);
        for tol in [1e-4, 1e-6, 1e-8] {
            let h = osc.step_for(tol);
            let err = error_at(&osc, 10.0 / f, h) * osc.stiffness;
            assert!(
                err <= tol,
                "f {f} zeta {zeta} tol {tol}: relative error {err:e}"
            );
        }
    }
}

#[test]
fn table4_settling_times_lie_where_the_envelope_puts_them() {
    // ts = 4 / (zeta omega_n) (paper 001, Sec. 4.2) is the envelope estimate of the 2 %
    // settling time. The response leaves the band for the last time at a peak, so the true
    // settling time lies within half a damped period before the time at which the envelope
    // exp(-zeta w t) / sqrt(1 - zeta^2) falls to 2 %: that bound is what this test holds the
    // integrated response to. Against 4 / (zeta omega_n) itself the ratios are printed (and
    // quoted in the README): the 3 % does not hold for every pair of Table 4.
    for &(f, zeta) in &PAPER001_TABLE4 {
        let osc = Oscillator::from_frequency(f, zeta);
        let r = step_response(&osc, 1.0, 0.02, 1e-6);
        let w = osc.omega();
        let envelope = ((1.0f64 / 0.02).ln() - (1.0 - zeta * zeta).sqrt().ln()) / (zeta * w);
        let half_period = std::f64::consts::PI / (w * (1.0 - zeta * zeta).sqrt());
        assert!(
            r.settling_time <= envelope + r.step
                && r.settling_time >= envelope - half_period - r.step,
            "zeta {zeta}: ts {} outside [{}, {}]",
            r.settling_time,
            envelope - half_period,
            envelope
        );
        let estimate = 4.0 / (zeta * w);
        eprintln!(
            "Table 4: f {f} Hz, zeta {zeta}: ts {:.6} s, 4/(zeta wn) {estimate:.6} s, ratio {:.4}",
            r.settling_time,
            r.settling_time / estimate
        );
    }
}
