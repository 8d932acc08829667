//! The 3-PRR mechanism of paper 002 against the paper's example (Sec. 2, 4.3, Fig. 6) and
//! trends (Sec. 4.2, Fig. 5).

use flexopt::model::prr3::{frequencies, mass_and_stiffness, modes, Prr3};
use flexopt::model::scalar::Jet;
use nalgebra::Matrix3;

const MODEL: [f64; 3] = [1201.6, 1201.7, 1520.6];
const FEA: [f64; 3] = [1106.4, 1106.7, 1446.3];

fn freqs(p: &Prr3<f64>) -> [f64; 3] {
    frequencies(p).expect("a positive definite mass matrix")
}

#[test]
fn the_paper_example_within_ten_percent_of_both_and_closest_to_the_fea() {
    let f = freqs(&Prr3::paper002());
    eprintln!("3-PRR example: {f:?} Hz (paper model {MODEL:?}, FEA {FEA:?})");
    for i in 0..3 {
        assert!(
            (f[i] / MODEL[i] - 1.0).abs() < 0.10,
            "mode {i}: {} vs model {}",
            f[i],
            MODEL[i]
        );
        assert!(
            (f[i] / FEA[i] - 1.0).abs() < 0.10,
            "mode {i}: {} vs FEA {}",
            f[i],
            FEA[i]
        );
        // the printed model reproduces the paper's FEA, not its analytical values
        assert!(
            (f[i] / FEA[i] - 1.0).abs() < 0.005,
            "mode {i}: {} vs FEA {}",
            f[i],
            FEA[i]
        );
    }
    assert!(
        ((f[0] - f[1]) / f[0]).abs() < 1e-9,
        "the symmetric pair: {} {}",
        f[0],
        f[1]
    );
}

#[test]
fn mode_shapes_are_mass_orthonormal() {
    let (m, k) = mass_and_stiffness(&Prr3::paper002());
    let (f, v) = modes(&m, &k).unwrap();
    let (m, k) = (
        Matrix3::from_fn(|r, c| m[r][c]),
        Matrix3::from_fn(|r, c| k[r][c]),
    );
    let vmv = v.transpose() * m * v;
    let vkv = v.transpose() * k * v;
    for r in 0..3 {
        for c in 0..3 {
            let w2 = (2.0 * std::f64::consts::PI * f[r]).powi(2);
            let (em, ek) = if r == c { (1.0, w2) } else { (0.0, 0.0) };
            assert!((vmv[(r, c)] - em).abs() < 1e-12, "V'MV");
            assert!((vkv[(r, c)] - ek).abs() < 1e-9 * w2.max(1.0), "V'KV");
        }
    }
    // the third mode is the platform's rotation
    assert!(v[(2, 2)].abs() > 10.0 * v[(0, 2)].abs().max(v[(1, 2)].abs()));
}

/// Coefficient of determination of a straight-line fit.
fn r_squared(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let syy: f64 = y.iter().map(|b| (b - my).powi(2)).sum();
    sxy * sxy / (sxx * syy)
}

#[test]
fn frequencies_rise_nearly_linearly_with_hinge_stiffness() {
    // Sec. 4.2, Fig. 5a
    let ks: Vec<f64> = (0..=20).map(|i| 10.0 + 5.0 * i as f64).collect();
    for mode in 0..3 {
        let f: Vec<f64> = ks
            .iter()
            .map(|&k| {
                freqs(&Prr3 {
                    hinge_stiffness: k,
                    ..Prr3::paper002()
                })[mode]
            })
            .collect();
        assert!(f.windows(2).all(|w| w[1] > w[0]), "mode {mode} rises");
        let r2 = r_squared(&ks, &f);
        assert!(r2 > 0.99, "mode {mode}: R^2 = {r2}");
    }
}

#[test]
fn frequencies_rise_with_drive_stiffness_but_not_linearly() {
    // Sec. 4.2, Fig. 5b: rising, concave (negative second differences on a uniform grid),
    // and far below proportional: a hundredfold drive stiffness does not multiply them by 10
    let k1s: Vec<f64> = (0..=40).map(|i| 1e5 + 2.5e5 * i as f64).collect();
    for mode in 0..3 {
        let f: Vec<f64> = k1s
            .iter()
            .map(|&k1| {
                freqs(&Prr3 {
                    drive_stiffness: k1,
                    ..Prr3::paper002()
                })[mode]
            })
            .collect();
        assert!(f.windows(2).all(|w| w[1] > w[0]), "mode {mode} rises");
        assert!(
            f.windows(3).all(|w| w[2] - 2.0 * w[1] + w[0] < 0.0),
            "mode {mode} is concave in k1"
        );
        let (first, last) = (f[0], f[f.len() - 1]);
        assert!(
            last / first < (k1s[k1s.len() - 1] / k1s[0]).sqrt(),
            "mode {mode}: {first} -> {last}"
        );
    }
}

#[test]
fn gradients_of_the_frequencies_agree_with_differences() {
    let p = Prr3::paper002();
    let v = |i: usize, x: f64| Jet::<10>::variable(x, i);
    let pj = Prr3 {
        base_radius: v(0, p.base_radius),
        platform_radius: v(1, p.platform_radius),
        link_length: v(2, p.link_length),
        alpha1: v(3, p.alpha1),
        beta1: v(4, p.beta1),
        theta1: v(5, p.theta1),
        platform_mass: v(6, p.platform_mass),
        link_mass: v(7, p.link_mass),
        hinge_stiffness: v(8, p.hinge_stiffness),
        drive_stiffness: v(9, p.drive_stiffness),
    };
    let fj = frequencies(&pj).unwrap();
    let fields: [fn(&mut Prr3<f64>) -> &mut f64; 10] = [
        |p| &mut p.base_radius,
        |p| &mut p.platform_radius,
        |p| &mut p.link_length,
        |p| &mut p.alpha1,
        |p| &mut p.beta1,
        |p| &mut p.theta1,
        |p| &mut p.platform_mass,
        |p| &mut p.link_mass,
        |p| &mut p.hinge_stiffness,
        |p| &mut p.drive_stiffness,
    ];
    // the parameters that keep the three-fold symmetry (all but the angles, which rotate
    // the whole mechanism or break nothing at first order) give a smooth pair
    for (j, field) in fields.iter().enumerate() {
        let mut q = p;
        let x = *field(&mut q);
        let h = 1e-6 * x.abs().max(1e-3);
        let at = |d: f64| {
            let mut q = p;
            *field(&mut q) = x + d;
            freqs(&q)
        };
        let (up, down) = (at(h), at(-h));
        for mode in 0..3 {
            let fd = (up[mode] - down[mode]) / (2.0 * h);
            let exact = fj[mode].grad[j];
            let scale = fj[mode].re / x.abs().max(1e-3);
            assert!(
                (fd - exact).abs() <= 1e-5 * scale.max(fd.abs()),
                "df{mode}/dp{j}: exact {exact:e}, differences {fd:e}"
            );
        }
    }
}

#[test]
fn maximizing_f1_from_the_problem_file_finds_a_checked_optimum() {
    use flexopt::problem::{Problem, Solver};
    use flexopt::study::{self, StudyOptions};
    let p = Problem::load(std::path::Path::new("problems/prr3_frequency.toml")).unwrap();
    let s = study::run(
        &p,
        &StudyOptions {
            solver: Solver::Sqp,
            ..StudyOptions::from_problem(&p)
        },
    );
    let best = &s.runs[s.best];
    assert!(s.any_feasible && best.feasible);
    assert!(
        best.solution.kkt_residual.unwrap() < 1e-8,
        "{:?}",
        best.solution
    );
    // an independent evaluation: the eigenvalues of M^-1 K by the general (non-symmetric)
    // solver instead of the Cholesky-reduced symmetric one
    let q = Prr3::from_slice(&best.x_end);
    let (m, k) = mass_and_stiffness(&q);
    let (m, k) = (
        Matrix3::from_fn(|r, c| m[r][c]),
        Matrix3::from_fn(|r, c| k[r][c]),
    );
    let mut w2: Vec<f64> = (m.try_inverse().unwrap() * k)
        .complex_eigenvalues()
        .iter()
        .map(|z| z.re)
        .collect();
    w2.sort_by(f64::total_cmp);
    let f1 = w2[0].sqrt() / (2.0 * std::f64::consts::PI);
    let f3 = w2[2].sqrt() / (2.0 * std::f64::consts::PI);
    assert!(
        (f1 / best.objective - 1.0).abs() < 1e-9,
        "{f1} vs {}",
        best.objective
    );
    assert!(f3 <= 1600.0 * (1.0 + 1e-8), "f3 = {f3}");
    // and no design of a grid over the bounds that meets the f3 limit does better
    let mut grid_best = 0.0f64;
    for i in 0..=20 {
        for j in 0..=20 {
            for kk in 0..=20 {
                let mut x = best.x_end.clone();
                x[1] = 0.020 + 0.020 * i as f64 / 20.0;
                x[2] = 0.010 + 0.020 * j as f64 / 20.0;
                x[8] = 20.0 + 30.0 * kk as f64 / 20.0;
                let f = freqs(&Prr3::from_slice(&x));
                if f[2] <= 1600.0 {
                    grid_best = grid_best.max(f[0]);
                }
            }
        }
    }
    eprintln!(
        "3-PRR maximum f1 {} Hz at {:?}; best of the grid {grid_best} Hz",
        best.objective, best.x_end
    );
    assert!(
        best.objective >= grid_best - 1e-6,
        "{} < {grid_best}",
        best.objective
    );
}

#[test]
fn the_third_frequency_turns_with_the_inertia_ratio_as_fig4_says() {
    // Fig. 4b: as the platform's inertia grows against the links', f3 first falls, then
    // rises again. Changing the ratio through rb at the example's masses gives the same
    // turn (at a ratio near 15, where the paper, whose masses also changed with rb and l by
    // rules it does not give, finds about 100); f1 and f2, the translations, do not depend
    // on rb here. The ratio at the example is 3 mp rb^2 / (4 mg l^2) = 25.3.
    let base = Prr3::paper002();
    let (ip, ig) = base.inertias();
    assert!((ip / ig - 25.3125).abs() < 1e-9, "{}", ip / ig);
    let f3: Vec<(f64, f64)> = (0..=50)
        .map(|k| {
            let mut p = base;
            p.platform_radius = (10.0 + k as f64) * 1e-3;
            let (ip, ig) = p.inertias();
            (ip / ig, freqs(&p)[2])
        })
        .collect();
    let (turn, _) = f3
        .iter()
        .enumerate()
        .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        .unwrap();
    assert!(turn > 5 && turn < 45, "the minimum lies inside: {turn}");
    assert!(f3[..=turn].windows(2).all(|w| w[1].1 < w[0].1));
    assert!(f3[turn..].windows(2).all(|w| w[1].1 > w[0].1));
    eprintln!("f3 turns at an inertia ratio of {:.1}", f3[turn].0);
    assert!(f3[turn].0 > 10.0 && f3[turn].0 < 25.0);
}
