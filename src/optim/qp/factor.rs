//! The factorization of the dual method: `J = L^-T Q` and the triangle `R` of the active
//! constraints, updated by Givens rotations as constraints enter and leave.

use super::QpWorkspace;
use crate::optim::dense::{back_substitute, cholesky};

/// `J = L^-T` with `G = L L^T`, column-major; false if `G` is not positive definite.
pub(super) fn factor(g: &[f64], n: usize, l: &mut [f64], j: &mut [f64]) -> bool {
    if !cholesky(l, n, n, 0.0, |i, k| g[i * n + k]) {
        return false;
    }
    // J = L^-T: column k solves L^T y = e_k (L^T upper triangular)
    j.fill(0.0);
    for k in 0..n {
        let y = &mut j[k * n..k * n + k + 1];
        y[k] = 1.0;
        back_substitute(l, n, k + 1, y);
    }
    true
}

/// Makes constraint `p` (with `d = J^T n_p` in `ws.d`) the last active one.
pub(super) fn add_constraint(ws: &mut QpWorkspace, n: usize, p: usize, up: f64) {
    let q = ws.active.len();
    // rotate d[q+1..n] into d[q], applying the rotations to the columns of J
    for i in (q + 1..n).rev() {
        let (a, b) = (ws.d[i - 1], ws.d[i]);
        if b == 0.0 {
            continue;
        }
        let h = (a * a + b * b).sqrt();
        let inv = 1.0 / h;
        let (cs, sn) = (a * inv, b * inv);
        ws.d[i - 1] = h;
        ws.d[i] = 0.0;
        rotate_columns(&mut ws.j, n, i - 1, cs, sn);
    }
    for i in 0..=q {
        ws.r[q * n + i] = ws.d[i];
    }
    ws.active.push(p);
    ws.u.push(up);
    ws.in_active[p] = true;
}

/// Removes the active constraint at position `k`, restoring the triangle of `R`.
pub(super) fn drop_constraint(ws: &mut QpWorkspace, n: usize, k: usize) {
    let q = ws.active.len();
    ws.in_active[ws.active[k]] = false;
    ws.active.remove(k);
    ws.u.remove(k);
    // shift the columns of R after k one to the left
    for colm in k..q - 1 {
        for i in 0..n {
            ws.r[colm * n + i] = ws.r[(colm + 1) * n + i];
        }
    }
    // the shifted part is upper Hessenberg: rotate rows i, i+1 to clear R[i+1][i]
    for i in k..q - 1 {
        let (a, b) = (ws.r[i * n + i], ws.r[i * n + i + 1]);
        if b == 0.0 {
            continue;
        }
        let h = (a * a + b * b).sqrt();
        let inv = 1.0 / h;
        let (cs, sn) = (a * inv, b * inv);
        for colm in i..q - 1 {
            let (x, y) = (ws.r[colm * n + i], ws.r[colm * n + i + 1]);
            ws.r[colm * n + i] = cs * x + sn * y;
            ws.r[colm * n + i + 1] = -sn * x + cs * y;
        }
        rotate_columns(&mut ws.j, n, i, cs, sn);
    }
}

/// `(J_k, J_k+1) <- (c J_k + s J_k+1, -s J_k + c J_k+1)`.
fn rotate_columns(j: &mut [f64], n: usize, k: usize, cs: f64, sn: f64) {
    let (left, right) = j.split_at_mut((k + 1) * n);
    let a = &mut left[k * n..];
    let b = &mut right[..n];
    for (x, y) in a.iter_mut().zip(b.iter_mut()) {
        let (xa, ya) = (*x, *y);
        *x = cs * xa + sn * ya;
        *y = -sn * xa + cs * ya;
    }
}
