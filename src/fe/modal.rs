//! The lowest natural modes of `K phi = omega^2 M phi` by the Lanczos method on the inverse
//! `K^-1 M`, in the M inner product, with full reorthogonalization (Ericsson and Ruhe, "The
//! spectral transformation Lanczos method for the numerical solution of large sparse
//! generalized symmetric eigenvalue problems", Math. Comp. 35, 1980, with shift zero): each
//! step one solve with the stiffness matrix's Cholesky factor, which the static load cases
//! have already computed. The Ritz values of the small tridiagonal matrix converge first at
//! the largest `1 / omega^2`, the lowest modes.

use faer::sparse::SparseColMat;
use faer::Mat;
use nalgebra::{DMatrix, SymmetricEigen};

use super::assembly::{symmetric_product, Factor};
use super::FeError;

/// A natural mode: its frequency (Hz) and its shape (free degrees of freedom), normalised
/// to `phi^T M phi = 1`.
#[derive(Debug, Clone)]
pub struct Mode {
    pub frequency: f64,
    pub shape: Vec<f64>,
}

/// The `count` lowest modes, each to a relative residual of its eigenvalue below
/// `tolerance`, the Lanczos vectors started from `start` (free degrees of freedom; a
/// static deflection close to the modes sought saves steps) or from a fixed smooth field.
pub fn lowest_modes(
    k: &Factor,
    m: &SparseColMat<usize, f64>,
    count: usize,
    tolerance: f64,
    start: Option<Vec<f64>>,
) -> Result<Vec<Mode>, FeError> {
    let n = m.ncols();
    let steps_max = (4 * count + 20).min(n);
    let mut q: Vec<Vec<f64>> = Vec::with_capacity(steps_max + 1);
    let mut mq: Vec<Vec<f64>> = Vec::with_capacity(steps_max + 1);
    let (mut alpha, mut beta) = (Vec::new(), Vec::new());
    // a fixed start, the same on every run: a smooth field with every component
    let mut v: Vec<f64> = start
        .filter(|s| s.len() == n && s.iter().any(|&x| x != 0.0))
        .unwrap_or_else(|| {
            (0..n)
                .map(|i| 1.0 + ((i as f64) * 0.618_033_988_75).fract())
                .collect()
        });
    let mut mv = vec![0.0; n];
    symmetric_product(m, &v, &mut mv);
    let norm = dot(&v, &mv).sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
    mv.iter_mut().for_each(|x| *x /= norm);
    q.push(v);
    mq.push(mv);
    let mut rhs = Mat::<f64>::zeros(n, 1);
    let mut last: Option<Vec<Mode>> = None;
    for j in 0..steps_max {
        for i in 0..n {
            rhs[(i, 0)] = mq[j][i];
        }
        k.solve(&mut rhs);
        let mut w: Vec<f64> = (0..n).map(|i| rhs[(i, 0)]).collect();
        let a = dot(&w, &mq[j]);
        alpha.push(a);
        // full reorthogonalization, twice, in the M inner product
        for _ in 0..2 {
            for (qi, mqi) in q.iter().zip(&mq) {
                let c = dot(&w, mqi);
                w.iter_mut().zip(qi).for_each(|(x, y)| *x -= c * y);
            }
        }
        let mut mw = vec![0.0; n];
        symmetric_product(m, &w, &mut mw);
        let b = dot(&w, &mw).max(0.0).sqrt();
        // the Ritz pairs so far
        let size = alpha.len();
        if size >= count {
            let mut t = DMatrix::<f64>::zeros(size, size);
            for i in 0..size {
                t[(i, i)] = alpha[i];
                if i + 1 < size {
                    t[(i, i + 1)] = beta[i];
                    t[(i + 1, i)] = beta[i];
                }
            }
            let eig = SymmetricEigen::new(t);
            let mut order: Vec<usize> = (0..size).collect();
            order.sort_by(|&x, &y| eig.eigenvalues[y].total_cmp(&eig.eigenvalues[x]));
            let converged = order[..count].iter().all(|&i| {
                let theta = eig.eigenvalues[i];
                theta > 0.0 && (b * eig.eigenvectors[(size - 1, i)]).abs() <= tolerance * theta
            });
            if std::env::var("FE_TIMING").is_ok() && (converged || b == 0.0) {
                eprintln!("lanczos steps {}", j + 1);
            }
            if converged || b == 0.0 || j + 1 == steps_max {
                let modes = order[..count]
                    .iter()
                    .map(|&i| {
                        let theta = eig.eigenvalues[i];
                        let mut shape = vec![0.0; n];
                        for (r, qr) in q.iter().enumerate().take(size) {
                            let s = eig.eigenvectors[(r, i)];
                            shape.iter_mut().zip(qr).for_each(|(x, y)| *x += s * y);
                        }
                        Mode {
                            frequency: (1.0 / theta).sqrt() / std::f64::consts::TAU,
                            shape,
                        }
                    })
                    .collect();
                if converged || b == 0.0 {
                    return Ok(modes);
                }
                last = Some(modes);
                break;
            }
        }
        beta.push(b);
        w.iter_mut().for_each(|x| *x /= b);
        mw.iter_mut().for_each(|x| *x /= b);
        q.push(w);
        mq.push(mw);
    }
    Err(FeError::Solve(format!(
        "the lowest {count} modes did not converge in {steps_max} Lanczos steps{}",
        if last.is_some() {
            ""
        } else {
            " (too few degrees of freedom)"
        }
    )))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
