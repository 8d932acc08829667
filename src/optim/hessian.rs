//! Second derivatives for the SQP from first ones: the Hessian of the Lagrangian by forward
//! differences of exact gradients, made positive definite by flipping its negative
//! curvature (an eigen-decomposition by cyclic Jacobi rotations).
//!
//! The flip `|H| = V |Lambda| V^T` keeps the size of every curvature, so that a step along a
//! direction of negative curvature is as long as along a positive one of the same size; a
//! shift `H + tau I` instead inflates the small curvatures along the valley floors that the
//! SQP must cross, and was measured to stall it.
//!
//! Reference: J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Springer 2006,
//! Sec. 3.4 (modified Hessians) and Sec. 8.1 (Hessians by differences of gradients).

/// `|H|` of the symmetric `n x n` matrix `h` (row-major, overwritten), every eigenvalue's
/// magnitude floored at `floor_ratio` times the largest; `v` is scratch of the same size.
/// False, with `h` undefined, when `H` has no curvature to speak of (every eigenvalue below
/// `1e-12`: a linear Lagrangian), which leaves nothing to model.
pub fn make_positive_definite(h: &mut [f64], v: &mut [f64], n: usize, floor_ratio: f64) -> bool {
    // a matrix positive definite with every eigenvalue above the floor is its own |H|; a
    // Cholesky factorization of H - floor I (into v) tells, at a fraction of the cost
    let largest_diag = (0..n).map(|i| h[i * n + i].abs()).fold(0.0, f64::max);
    if largest_diag > 1e-12 && cholesky_succeeds(h, v, n, floor_ratio * largest_diag) {
        return true;
    }
    // cyclic Jacobi: rotate away the off-diagonal entries, accumulating V
    v.fill(0.0);
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _sweep in 0..30 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..i).map(move |j| (i, j)))
            .map(|(i, j)| h[i * n + j] * h[i * n + j])
            .sum();
        let diag: f64 = (0..n).map(|i| h[i * n + i] * h[i * n + i]).sum();
        // |H| models the curvature for a QP: off-diagonal entries of 1e-3 of the diagonal
        // (squared norms 1e-6) change its steps less than the BFGS updates that follow
        if off <= 1e-6 * diag || off == 0.0 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = h[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let (app, aqq) = (h[p * n + p], h[q * n + q]);
                let theta = (aqq - app) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                // H <- J^T H J with the rotation J in the (p, q) plane
                for k in 0..n {
                    let (hkp, hkq) = (h[k * n + p], h[k * n + q]);
                    h[k * n + p] = c * hkp - s * hkq;
                    h[k * n + q] = s * hkp + c * hkq;
                }
                for k in 0..n {
                    let (hpk, hqk) = (h[p * n + k], h[q * n + k]);
                    h[p * n + k] = c * hpk - s * hqk;
                    h[q * n + k] = s * hpk + c * hqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let largest = (0..n).map(|i| h[i * n + i].abs()).fold(0.0, f64::max);
    if largest <= 1e-12 {
        return false;
    }
    let floor = floor_ratio * largest;
    let mut lam = [0.0; 32];
    let lam = &mut lam[..n];
    for (i, l) in lam.iter_mut().enumerate() {
        *l = h[i * n + i].abs().max(floor);
    }
    // H <- V |Lambda| V^T
    for i in 0..n {
        for j in 0..=i {
            let s: f64 = (0..n).map(|k| v[i * n + k] * lam[k] * v[j * n + k]).sum();
            h[i * n + j] = s;
            h[j * n + i] = s;
        }
    }
    true
}

/// Whether `h - shift I` has a Cholesky factor (computed into `l`).
fn cholesky_succeeds(h: &[f64], l: &mut [f64], n: usize, shift: f64) -> bool {
    for i in 0..n {
        for k in 0..=i {
            let mut s = h[i * n + k] - if i == k { shift } else { 0.0 };
            for p in 0..k {
                s -= l[i * n + p] * l[k * n + p];
            }
            if i == k {
                if s <= 0.0 || !s.is_finite() {
                    return false;
                }
                l[i * n + i] = s.sqrt();
            } else {
                l[i * n + k] = s / l[k * n + k];
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flips_negative_curvature_and_keeps_the_eigenvectors() {
        // H = Q diag(3, -2, 0.5) Q^T for a rotation Q: |H| = Q diag(3, 2, 0.5) Q^T
        let (c, s) = (0.6f64, 0.8f64);
        let q = [c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0];
        let build = |d: [f64; 3]| {
            let mut h = [0.0; 9];
            for i in 0..3 {
                for j in 0..3 {
                    h[i * 3 + j] = (0..3).map(|k| q[i * 3 + k] * d[k] * q[j * 3 + k]).sum();
                }
            }
            h
        };
        let mut h = build([3.0, -2.0, 0.5]);
        let mut v = [0.0; 9];
        assert!(make_positive_definite(&mut h, &mut v, 3, 1e-6));
        let want = build([3.0, 2.0, 0.5]);
        for (a, b) in h.iter().zip(&want) {
            assert!((a - b).abs() < 1e-12, "{h:?} vs {want:?}");
        }
    }

    #[test]
    fn floors_a_singular_direction() {
        let mut h = [1.0, 0.0, 0.0, 0.0];
        let mut v = [0.0; 4];
        assert!(make_positive_definite(&mut h, &mut v, 2, 1e-6));
        assert!((h[3] - 1e-6).abs() < 1e-18 && h[0] == 1.0);
        // no curvature at all: nothing to model
        let mut zero = [0.0; 4];
        assert!(!make_positive_definite(&mut zero, &mut v, 2, 1e-6));
    }
}
