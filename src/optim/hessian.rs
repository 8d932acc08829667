//! Second derivatives for the SQP from first ones: the Hessian of the Lagrangian by forward
//! differences of exact gradients, made positive definite by flipping its negative
//! curvature (an eigen-decomposition: Householder tridiagonalization and implicit QL).
//!
//! The flip `|H| = V |Lambda| V^T` keeps the size of every curvature, so that a step along a
//! direction of negative curvature is as long as along a positive one of the same size; a
//! shift `H + tau I` instead inflates the small curvatures along the valley floors that the
//! SQP must cross, and was measured to stall it.
//!
//! Reference: J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Springer 2006,
//! Sec. 3.4 (modified Hessians) and Sec. 8.1 (Hessians by differences of gradients);
//! G. H. Golub and C. F. Van Loan, Matrix Computations, 4th ed., 2013, Sec. 8.3
//! (tridiagonalization and the symmetric QR/QL algorithm), as in EISPACK's tred2 and tql2.

use super::dense::cholesky;

/// `|H|` of the symmetric `n x n` matrix `h` (row-major, overwritten), every eigenvalue's
/// magnitude floored at `floor_ratio` times the largest; `v` is scratch of the same size.
/// False, with `h` undefined, when `H` has no curvature to speak of (every eigenvalue below
/// `1e-12`: a linear Lagrangian), which leaves nothing to model, or when `n > MAX_N`.
pub fn make_positive_definite(h: &mut [f64], v: &mut [f64], n: usize, floor_ratio: f64) -> bool {
    // a matrix positive definite with every eigenvalue above the floor is its own |H|; a
    // Cholesky factorization of H - floor I (into v) tells, at a fraction of the cost
    let largest_diag = (0..n).map(|i| h[i * n + i].abs()).fold(0.0, f64::max);
    let shift = floor_ratio * largest_diag;
    let shifted = |r: usize, c: usize| h[r * n + c] - if r == c { shift } else { 0.0 };
    if largest_diag > 1e-12 && cholesky(v, n, n, 0.0, shifted) {
        return true;
    }
    if n > MAX_N {
        return false;
    }
    // eigenvalues into d, eigenvectors into the columns of v
    let (mut d, mut e) = ([0.0; MAX_N], [0.0; MAX_N]);
    let (d, e) = (&mut d[..n], &mut e[..n]);
    v.copy_from_slice(&h[..n * n]);
    tridiagonalize(v, n, d, e);
    diagonalize(v, n, d, e);
    let largest = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest <= 1e-12 {
        return false;
    }
    let floor = floor_ratio * largest;
    for l in d.iter_mut() {
        *l = l.abs().max(floor);
    }
    // H <- V |Lambda| V^T
    for i in 0..n {
        for j in 0..=i {
            let s: f64 = (0..n).map(|k| v[i * n + k] * d[k] * v[j * n + k]).sum();
            h[i * n + j] = s;
            h[j * n + i] = s;
        }
    }
    true
}

/// Largest dimension [`make_positive_definite`] handles.
pub const MAX_N: usize = 32;

/// Householder reduction of the symmetric matrix in `v` (row-major) to tridiagonal form:
/// the diagonal into `d`, the subdiagonal into `e[1..]`, and `v` overwritten by the
/// orthogonal transformation (the EISPACK `tred2` scheme).
fn tridiagonalize(v: &mut [f64], n: usize, d: &mut [f64], e: &mut [f64]) {
    let at = |i: usize, j: usize| i * n + j;
    for j in 0..n {
        d[j] = v[at(n - 1, j)];
    }
    for i in (1..n).rev() {
        let scale: f64 = d[..i].iter().map(|x| x.abs()).sum();
        let mut h = 0.0;
        if scale == 0.0 {
            e[i] = d[i - 1];
            for j in 0..i {
                d[j] = v[at(i - 1, j)];
                v[at(i, j)] = 0.0;
                v[at(j, i)] = 0.0;
            }
        } else {
            for dk in &mut d[..i] {
                *dk /= scale;
                h += *dk * *dk;
            }
            let f = d[i - 1];
            let g = if f > 0.0 { -h.sqrt() } else { h.sqrt() };
            e[i] = scale * g;
            h -= f * g;
            d[i - 1] = f - g;
            e[..i].fill(0.0);
            for j in 0..i {
                let f = d[j];
                v[at(j, i)] = f;
                let mut g = e[j] + v[at(j, j)] * f;
                for k in j + 1..i {
                    g += v[at(k, j)] * d[k];
                    e[k] += v[at(k, j)] * f;
                }
                e[j] = g;
            }
            let mut f = 0.0;
            for j in 0..i {
                e[j] /= h;
                f += e[j] * d[j];
            }
            let hh = f / (h + h);
            for j in 0..i {
                e[j] -= hh * d[j];
            }
            for j in 0..i {
                let (f, g) = (d[j], e[j]);
                for k in j..i {
                    v[at(k, j)] -= f * e[k] + g * d[k];
                }
                d[j] = v[at(i - 1, j)];
                v[at(i, j)] = 0.0;
            }
        }
        d[i] = h;
    }
    // accumulate the transformations
    for i in 0..n - 1 {
        v[at(n - 1, i)] = v[at(i, i)];
        v[at(i, i)] = 1.0;
        let h = d[i + 1];
        if h != 0.0 {
            for k in 0..=i {
                d[k] = v[at(k, i + 1)] / h;
            }
            for j in 0..=i {
                let g: f64 = (0..=i).map(|k| v[at(k, i + 1)] * v[at(k, j)]).sum();
                for k in 0..=i {
                    v[at(k, j)] -= g * d[k];
                }
            }
        }
        for k in 0..=i {
            v[at(k, i + 1)] = 0.0;
        }
    }
    for j in 0..n {
        d[j] = v[at(n - 1, j)];
        v[at(n - 1, j)] = 0.0;
    }
    v[at(n - 1, n - 1)] = 1.0;
    e[0] = 0.0;
}

/// Implicit QL iterations on the tridiagonal matrix `(d, e)` with the transformation in `v`
/// (the EISPACK `tql2` scheme): eigenvalues into `d`, eigenvectors into the columns of `v`.
fn diagonalize(v: &mut [f64], n: usize, d: &mut [f64], e: &mut [f64]) {
    let at = |i: usize, j: usize| i * n + j;
    for i in 1..n {
        e[i - 1] = e[i];
    }
    e[n - 1] = 0.0;
    let (mut f, mut tst1) = (0.0f64, 0.0f64);
    let eps = f64::EPSILON;
    for l in 0..n {
        tst1 = tst1.max(d[l].abs() + e[l].abs());
        let mut m = l;
        while m < n - 1 && e[m].abs() > eps * tst1 {
            m += 1;
        }
        if m > l {
            for _ in 0..60 {
                let g = d[l];
                let p = (d[l + 1] - g) / (2.0 * e[l]);
                let r = pythag(p, 1.0).copysign(p);
                d[l] = e[l] / (p + r);
                d[l + 1] = e[l] * (p + r);
                let dl1 = d[l + 1];
                let h = g - d[l];
                for di in &mut d[l + 2..n] {
                    *di -= h;
                }
                f += h;
                let mut p = d[m];
                let (mut c, mut c2, mut c3) = (1.0, 1.0, 1.0);
                let el1 = e[l + 1];
                let (mut s, mut s2) = (0.0, 0.0);
                for i in (l..m).rev() {
                    c3 = c2;
                    c2 = c;
                    s2 = s;
                    let g = c * e[i];
                    let h = c * p;
                    let r = pythag(p, e[i]);
                    e[i + 1] = s * r;
                    s = e[i] / r;
                    c = p / r;
                    p = c * d[i] - s * g;
                    d[i + 1] = h + s * (c * g + s * d[i]);
                    for k in 0..n {
                        let h = v[at(k, i + 1)];
                        v[at(k, i + 1)] = s * v[at(k, i)] + c * h;
                        v[at(k, i)] = c * v[at(k, i)] - s * h;
                    }
                }
                let p = -s * s2 * c3 * el1 * e[l] / dl1;
                e[l] = s * p;
                d[l] = c * p;
                if e[l].abs() <= eps * tst1 {
                    break;
                }
            }
        }
        d[l] += f;
        e[l] = 0.0;
    }
}

/// `sqrt(a^2 + b^2)` without overflow or underflow of the squares; libm's `hypot` also
/// rounds its result correctly, which the iterations do not need and which showed in the
/// profile.
fn pythag(a: f64, b: f64) -> f64 {
    let (a, b) = (a.abs(), b.abs());
    if a > b {
        a * (1.0 + (b / a) * (b / a)).sqrt()
    } else if b == 0.0 {
        0.0
    } else {
        b * (1.0 + (a / b) * (a / b)).sqrt()
    }
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
    fn the_square_of_the_flip_is_the_square() {
        // |H|^2 = H^2 for any symmetric H: a check of the eigen-decomposition that does not
        // depend on how it is computed
        let n = 8;
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..50 {
            let mut h = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..=i {
                    let x = next();
                    h[i * n + j] = x;
                    h[j * n + i] = x;
                }
            }
            let square = |a: &[f64]| -> Vec<f64> {
                (0..n * n)
                    .map(|k| (0..n).map(|p| a[(k / n) * n + p] * a[p * n + k % n]).sum())
                    .collect()
            };
            let want = square(&h);
            let mut flipped = h.clone();
            let mut v = vec![0.0; n * n];
            assert!(make_positive_definite(&mut flipped, &mut v, n, 0.0));
            let got = square(&flipped);
            let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in got.iter().zip(&want) {
                assert!((a - b).abs() < 1e-13 * scale, "{a} vs {b}");
            }
            // and |H| is positive semidefinite: x^T |H| x >= 0
            let x: Vec<f64> = (0..n).map(|_| next()).collect();
            let q: f64 = (0..n * n).map(|k| x[k / n] * flipped[k] * x[k % n]).sum();
            assert!(q >= -1e-14);
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
