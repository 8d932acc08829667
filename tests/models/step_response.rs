//! Fourth-order Runge-Kutta step responses (paper 001, Sec. 4.2) against the exact solution
//! of the damped single-degree-of-freedom oscillator.

use flexopt::dynamics::{
    exact_settling_time, exact_step, step_response, Oscillator, PAPER001_TABLE4,
};

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
fn table4_settling_times_agree_with_the_papers_estimate() {
    // ts ~ 4 / (zeta omega_n) (paper 001, Sec. 4.2, Eq. 17) for the frequency and damping
    // ratio of every mode of Table 4 (ratios in percent there): within 3 %. The estimate
    // is the time at which the decay envelope falls to exp(-4) = 1.8 %; the response leaves
    // the 2 % band for the last time at a peak a little earlier, ln(50)/4 = 0.978 of it.
    for &(f, zeta) in &PAPER001_TABLE4 {
        let osc = Oscillator::from_frequency(f, zeta);
        let r = step_response(&osc, 1.0, 0.02, 1e-6);
        let estimate = 4.0 / (zeta * osc.omega());
        let ratio = r.settling_time / estimate;
        assert!(
            (ratio - 1.0).abs() < 0.03,
            "f {f} Hz, zeta {zeta}: ts {} s, 4/(zeta wn) {estimate} s",
            r.settling_time
        );
        eprintln!(
            "Table 4: f {f} Hz, zeta {zeta}: ts {:.4} s, 4/(zeta wn) {estimate:.4} s, ratio {ratio:.4}",
            r.settling_time
        );
    }
}

#[test]
fn the_closed_form_settling_time_is_the_scanned_one() {
    for &(f, zeta) in PAPER001_TABLE4.iter().chain(&[
        (10.0, 0.02),
        (10.0, 0.3),
        (10.0, 0.999),
        (10.0, 1.0),
        (10.0, 3.0),
    ]) {
        let osc = Oscillator::from_frequency(f, zeta);
        let closed = exact_settling_time(&osc, 0.02);
        let scanned = exact_settling(&osc, 0.02);
        assert!(
            (closed - scanned).abs() <= 1e-9 * scanned,
            "f {f} zeta {zeta}: {closed} vs {scanned}"
        );
    }
}

#[test]
fn table5_settling_times_against_table4() {
    // Table 5 gives the theoretical settling times 1.43 s (X/Y) and 1.31 s (Z). From
    // Table 4, the Y translation (52.420 Hz, 0.86 %) settles in 1.374 s (4/(zeta wn):
    // 1.412 s), 3.9 % below 1.43 s; the X translation (52.421 Hz, 0.73 %) in 1.622 s. The
    // Z translation (79.246 Hz, 0.16 %) would take 4.9 s, not 1.31 s: no mode of Table 4
    // gives 1.31 s at 79.246 Hz (it needs about 0.61 %). See the README.
    let ts =
        |(f, zeta): (f64, f64)| exact_settling_time(&Oscillator::from_frequency(f, zeta), 0.02);
    let y = ts(PAPER001_TABLE4[2]);
    assert!((y / 1.43 - 1.0).abs() < 0.04, "Y: {y}");
    let x = ts(PAPER001_TABLE4[1]);
    assert!(x / 1.43 - 1.0 > 0.1, "X: {x}");
    let z = ts(PAPER001_TABLE4[3]);
    assert!(z / 1.31 > 3.0, "Z: {z}");
    // the damping ratio that would give Z 1.31 s lies between Table 4's values
    let needed = 4.0 / (1.31 * 2.0 * std::f64::consts::PI * 79.246);
    assert!(needed > 0.0034 && needed < 0.0073, "{needed}");
}
