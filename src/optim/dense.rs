//! Dense vector and matrix helpers shared by the solvers: products, norms, the Cholesky
//! factorization with its triangular solves, and the measures of constraint violation.
//!
//! Matrices are row-major slices; a triangular factor is the lower triangle of an `n x n`
//! row-major array whose diagonal holds the reciprocals of the pivots, which is all the
//! solves need and spares them a division per row.

/// `a . b`
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm.
pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Largest absolute entry.
pub fn inf_norm(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// `L L^T` of the `k x k` symmetric matrix whose lower triangle is `entry(r, c)` (`r >= c`),
/// into `l` (row-major lower triangle with stride `n`), the diagonal holding the reciprocal
/// pivots; false when a pivot is not above `min_pivot` or not finite.
pub fn cholesky(
    l: &mut [f64],
    n: usize,
    k: usize,
    min_pivot: f64,
    entry: impl Fn(usize, usize) -> f64,
) -> bool {
    for r in 0..k {
        for c in 0..=r {
            let s = entry(r, c) - dot(&l[r * n..r * n + c], &l[c * n..c * n + c]);
            if r == c {
                if !(s > min_pivot && s < f64::INFINITY) {
                    return false;
                }
                l[r * n + r] = 1.0 / s.sqrt();
            } else {
                l[r * n + c] = s * l[c * n + c];
            }
        }
    }
    true
}

/// `v <- L^-1 v`, `L` the first `k x k` of a factor of [`cholesky`] with stride `n`.
pub fn forward_substitute(l: &[f64], n: usize, k: usize, v: &mut [f64]) {
    for i in 0..k {
        let s = v[i] - dot(&l[i * n..i * n + i], &v[..i]);
        v[i] = s * l[i * n + i];
    }
}

/// `v <- L^-T v`, `L` as in [`forward_substitute`].
pub fn back_substitute(l: &[f64], n: usize, k: usize, v: &mut [f64]) {
    for i in (0..k).rev() {
        let s = v[i] - (i + 1..k).map(|p| l[p * n + i] * v[p]).sum::<f64>();
        v[i] = s * l[i * n + i];
    }
}

/// The violation of constraint `i` of value `v`: `|v|` for an equality (`i < meq`),
/// `max(0, -v)` for an inequality `v >= 0`.
#[inline]
pub fn violation(i: usize, v: f64, meq: usize) -> f64 {
    if i < meq {
        v.abs()
    } else {
        (-v).max(0.0)
    }
}

/// The largest violation of the constraints `c`; infinite where a value is NaN.
pub fn max_violation(c: &[f64], meq: usize) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, &v)| violation(i, v, meq))
        .fold(
            0.0,
            |m: f64, v| if v.is_nan() { f64::INFINITY } else { m.max(v) },
        )
}

/// Whether every entry of `a` is finite: `v - v` is `0` for a finite `v` and NaN for an
/// infinite or NaN one, summed in four independent lanes (the sum is `0` or NaN whatever the
/// order), which the compiler turns into packed arithmetic. `all(is_finite)` stops at the
/// first failure and so is a branch an entry: on the part's rules' Jacobians (197 entries
/// in wei2017's first stage, tested at every evaluation with gradients) it was 3.5 % of the
/// study's instructions.
#[allow(clippy::eq_op)] // `v - v` is the test
pub fn all_finite(a: &[f64]) -> bool {
    let mut lanes = [0.0; 4];
    let chunks = a.chunks_exact(4);
    let rest = chunks.remainder();
    for chunk in chunks {
        for (l, &v) in lanes.iter_mut().zip(chunk) {
            *l += v - v;
        }
    }
    let tail: f64 = rest.iter().map(|&v| v - v).sum();
    lanes.iter().sum::<f64>() + tail == 0.0
}

/// `sum_i viol_i`.
pub fn violation_l1(c: &[f64], meq: usize) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, &v)| violation(i, v, meq))
        .sum()
}

/// `sum_i w_i viol_i`: the penalty term of an l1 merit function.
pub fn weighted_violation(c: &[f64], meq: usize, w: &[f64]) -> f64 {
    c.iter()
        .zip(w)
        .enumerate()
        .map(|(i, (&v, &wi))| wi * violation(i, v, meq))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_a_known_system() {
        // G = [[4, 2], [2, 3]] = L L^T with L = [[2, 0], [1, sqrt 2]]
        let g = [4.0, 2.0, 2.0, 3.0];
        let mut l = [0.0; 4];
        assert!(cholesky(&mut l, 2, 2, 0.0, |r, c| g[r * 2 + c]));
        assert!((l[0] - 0.5).abs() < 1e-15 && (l[2] - 1.0).abs() < 1e-15);
        // G x = b for b = G [1, -2] = [0, -4]
        let mut v = [0.0, -4.0];
        forward_substitute(&l, 2, 2, &mut v);
        back_substitute(&l, 2, 2, &mut v);
        assert!(
            (v[0] - 1.0).abs() < 1e-14 && (v[1] + 2.0).abs() < 1e-14,
            "{v:?}"
        );
        // indefinite: fails
        assert!(!cholesky(&mut l, 2, 2, 0.0, |r, c| [1.0, 2.0, 2.0, 1.0][r * 2 + c]));
    }

    #[test]
    fn all_finite_is_every_entry_finite() {
        for len in 0..11 {
            let finite: Vec<f64> = (0..len).map(|k| 1e300 * (k as f64 - 4.5)).collect();
            assert!(all_finite(&finite), "{len}");
            for k in 0..len {
                for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
                    let mut v = finite.clone();
                    v[k] = bad;
                    assert!(!all_finite(&v), "{len} {k} {bad}");
                }
            }
        }
        assert!(all_finite(&[f64::MAX, -f64::MAX, f64::MIN_POSITIVE, -0.0]));
    }

    #[test]
    fn violations_of_equalities_and_inequalities() {
        let c = [-0.5, 0.25, -2.0, 3.0];
        assert_eq!(max_violation(&c, 1), 2.0);
        assert_eq!(violation_l1(&c, 1), 0.5 + 2.0);
        assert_eq!(
            weighted_violation(&c, 2, &[2.0, 1.0, 0.5, 9.0]),
            1.0 + 0.25 + 1.0
        );
        assert_eq!(max_violation(&[f64::NAN], 1), f64::INFINITY);
    }
}
