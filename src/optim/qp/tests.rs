//! The QP against enumeration of active sets on random problems.

use super::*;
use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};

/// The optimum by enumeration: every set of active inequalities whose KKT point is
/// primal and dual feasible.
fn brute_force(
    g: &DMatrix<f64>,
    a: &DVector<f64>,
    c: &DMatrix<f64>,
    b: &DVector<f64>,
    meq: usize,
) -> Option<(DVector<f64>, f64)> {
    let (n, m) = (a.len(), b.len());
    let mut best: Option<(DVector<f64>, f64)> = None;
    for mask in 0u32..(1 << (m - meq)) {
        let act: Vec<usize> = (0..meq)
            .chain((meq..m).filter(|i| mask >> (i - meq) & 1 == 1))
            .collect();
        let k = act.len();
        let mut kkt = DMatrix::zeros(n + k, n + k);
        let mut rhs = DVector::zeros(n + k);
        kkt.view_mut((0, 0), (n, n)).copy_from(g);
        for (r, &i) in act.iter().enumerate() {
            for j in 0..n {
                kkt[(j, n + r)] = -c[(i, j)];
                kkt[(n + r, j)] = c[(i, j)];
            }
            rhs[n + r] = b[i];
        }
        rhs.rows_mut(0, n).copy_from(&(-a));
        let Some(sol) = kkt.lu().solve(&rhs) else {
            continue;
        };
        let x = sol.rows(0, n).into_owned();
        let feasible = (0..m).all(|i| {
            let s = (c.row(i) * &x)[0] - b[i];
            if i < meq {
                s.abs() < 1e-9
            } else {
                s > -1e-9
            }
        });
        let dual_ok = act
            .iter()
            .enumerate()
            .all(|(r, &i)| i < meq || sol[n + r] > -1e-9);
        if feasible && dual_ok {
            let f = 0.5 * (x.transpose() * g * &x)[0] + a.dot(&x);
            if best.as_ref().is_none_or(|(_, bf)| f < *bf) {
                best = Some((x, f));
            }
        }
    }
    best
}

/// A random `n x n` positive definite `G`, and a random `m x n` `C`, each with its
/// row-major copy.
fn random_g_and_c(
    rng: &mut impl Rng,
    n: usize,
    m: usize,
) -> (DMatrix<f64>, Vec<f64>, DMatrix<f64>, Vec<f64>) {
    let h = DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0));
    let g = &h * h.transpose() + DMatrix::identity(n, n) * 0.1;
    let c = DMatrix::from_fn(m, n, |_, _| rng.random_range(-1.0..1.0));
    let row_major = |mat: &DMatrix<f64>| -> Vec<f64> {
        let (r, k) = mat.shape();
        (0..r * k).map(|i| mat[(i / k, i % k)]).collect()
    };
    let (gr, cr) = (row_major(&g), row_major(&c));
    (g, gr, c, cr)
}

/// `x` is the enumerated optimum `xb` and `lambda` its multipliers (the rows of `c`).
fn assert_optimal(
    (g, a, c): (&DMatrix<f64>, &DVector<f64>, &DMatrix<f64>),
    x: &[f64],
    lambda: &[f64],
    meq: usize,
    xb: &DVector<f64>,
) {
    let x = DVector::from_column_slice(x);
    assert!((&x - xb).norm() < 1e-8 * (1.0 + xb.norm()), "{x} vs {xb}");
    // stationarity: G x + a = C^T lambda
    let res = g * &x + a - c.transpose() * DVector::from_column_slice(lambda);
    assert!(res.norm() < 1e-8, "stationarity {}", res.norm());
    assert!(lambda[meq..].iter().all(|&l| l >= -1e-12));
}

#[test]
fn agrees_with_enumeration_on_random_problems() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let (mut solved, mut infeasible) = (0, 0);
    for _ in 0..400 {
        let n = rng.random_range(1..=4);
        let m = rng.random_range(1..=7);
        let meq = rng.random_range(0..=m.min(n).min(2));
        let (g, gr, c, cr) = random_g_and_c(&mut rng, n, m);
        let a = DVector::from_fn(n, |_, _| rng.random_range(-3.0..3.0));
        let b = DVector::from_fn(m, |_, _| rng.random_range(-1.0..1.0));
        let mut ws = QpWorkspace::new(n);
        let (mut x, mut lambda) = (vec![0.0; n], vec![0.0; m]);
        let problem = QpProblem {
            g: &gr,
            a: a.as_slice(),
            c: &cr,
            b: b.as_slice(),
            meq,
            lower: &[],
            upper: &[],
        };
        let status = solve(&problem, &mut x, &mut lambda, &mut ws);
        match brute_force(&g, &a, &c, &b, meq) {
            Some((xb, _)) => {
                assert_eq!(status, QpStatus::Optimal);
                assert_optimal((&g, &a, &c), &x, &lambda, meq, &xb);
                solved += 1;
            }
            None => {
                assert_eq!(status, QpStatus::Infeasible);
                infeasible += 1;
            }
        }
    }
    assert!(
        solved > 250 && infeasible > 5,
        "{solved} solved, {infeasible} infeasible"
    );
}

/// Random QPs with bounds, solved again and again with the last active set as the hint,
/// then perturbed, then with a wrong hint: the direct path must be taken where the hint
/// holds and must agree with enumeration every time, as the dual method's fallback must.
#[test]
fn hinted_solves_agree_with_enumeration() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let (mut checked, mut direct) = (0, 0);
    for _ in 0..300 {
        let n = rng.random_range(2..=4);
        let mg = rng.random_range(1..=3);
        let meq = rng.random_range(0..=1usize);
        let (g, gr, c, cr) = random_g_and_c(&mut rng, n, mg);
        let lower: Vec<f64> = (0..n).map(|_| rng.random_range(-1.5..-0.2)).collect();
        let upper: Vec<f64> = (0..n).map(|_| rng.random_range(0.2..1.5)).collect();
        // the bounds as general rows, for the enumeration
        let mut call = c.clone().resize_vertically(mg + 2 * n, 0.0);
        for j in 0..n {
            call[(mg + 2 * j, j)] = 1.0;
            call[(mg + 2 * j + 1, j)] = -1.0;
        }
        let mut ws = QpWorkspace::new(n);
        let mut hint: Vec<usize> = Vec::new();
        let mut a = DVector::from_fn(n, |_, _| rng.random_range(-3.0..3.0));
        let mut b = DVector::from_fn(mg, |_, _| rng.random_range(-0.5..0.5));
        for round in 0..6 {
            if round == 4 {
                // a small move of the problem, as between SQP iterations
                a += DVector::from_fn(n, |_, _| rng.random_range(-0.3..0.3));
                b += DVector::from_fn(mg, |_, _| rng.random_range(-0.1..0.1));
            }
            if round == 5 {
                // a wrong guess: one more row than was active
                if let Some(extra) = (meq..mg + 2 * n).find(|i| !hint.contains(i)) {
                    hint.push(extra);
                }
            }
            let mut bvec = b.clone().resize_vertically(mg + 2 * n, 0.0);
            for j in 0..n {
                bvec[mg + 2 * j] = lower[j];
                bvec[mg + 2 * j + 1] = -upper[j];
            }
            let (mut x, mut lambda) = (vec![0.0; n], vec![0.0; mg + 2 * n]);
            let before = direct_solves(&ws);
            let problem = QpProblem {
                g: &gr,
                a: a.as_slice(),
                c: &cr,
                b: b.as_slice(),
                meq,
                lower: &lower,
                upper: &upper,
            };
            let status = solve_with_hint(&problem, &hint, &mut x, &mut lambda, &mut ws);
            let took_direct = direct_solves(&ws) > before;
            match brute_force(&g, &a, &call, &bvec, meq) {
                Some((xb, _)) => {
                    assert_eq!(status, QpStatus::Optimal, "direct {took_direct}");
                    assert_optimal((&g, &a, &call), &x, &lambda, meq, &xb);
                    checked += 1;
                    direct += usize::from(took_direct);
                    hint = active_rows(&ws).to_vec();
                }
                None => {
                    assert_eq!(status, QpStatus::Infeasible);
                    break;
                }
            }
        }
    }
    assert!(
        checked > 1000 && direct > checked / 3,
        "{checked} solves checked, {direct} direct"
    );
}

#[test]
fn rejects_an_indefinite_hessian() {
    let mut ws = QpWorkspace::new(2);
    let (mut x, mut l) = (vec![0.0; 2], vec![]);
    let problem = QpProblem {
        g: &[1.0, 0.0, 0.0, -1.0],
        a: &[0.0, 0.0],
        c: &[],
        b: &[],
        meq: 0,
        lower: &[],
        upper: &[],
    };
    let st = solve(&problem, &mut x, &mut l, &mut ws);
    assert_eq!(st, QpStatus::NotConvex);
}

#[test]
fn the_rows_of_a_known_length_give_the_same_choice_to_the_bit() {
    // the most violated row and its scaled slack, over rows walked as arrays of the length
    // the compiler knows, against the loop over a length known at run time
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
    for n in 1..=14 {
        for _ in 0..50 {
            let mg = rng.random_range(1..30);
            let meq = rng.random_range(0..=mg.min(3));
            let c: Vec<f64> = (0..mg * n).map(|_| rng.random_range(-1e3..1e3)).collect();
            let b: Vec<f64> = (0..mg).map(|_| rng.random_range(-1e3..1e3)).collect();
            let x: Vec<f64> = (0..n).map(|_| rng.random_range(-2.0..2.0)).collect();
            let in_active: Vec<bool> = (0..mg).map(|_| rng.random_bool(0.2)).collect();
            let rows = Rows {
                c: &c,
                b: &b,
                n,
                mg,
                lower: &[],
                upper: &[],
            };
            let (mut known, mut any) = (vec![f64::NAN; mg], vec![f64::NAN; mg]);
            let (p, worst) = rows.most_violated(meq, &x, &in_active, &mut known);
            let (q, least) = rows.most_violated_of::<0>(meq, &x, &in_active, &mut any);
            assert_eq!((p, worst.to_bits()), (q, least.to_bits()), "n {n}");
            assert_eq!(
                known.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                any.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
        }
    }
}
