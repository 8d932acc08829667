//! A QP solved directly on a hinted active set, as an equality-constrained problem.

use super::{dot_of, QpWorkspace, Rows};
use crate::optim::dense::{back_substitute, cholesky, dot, forward_substitute};

/// The QP solved as an equality-constrained one on the hinted active set `A` (the
/// equalities and the hinted inequalities): its bound rows fix their variables, and on the
/// free ones `F`, with `G_FF = L L^T`, `y = -L^-1 a_F`, `W = L^-1 C_AF^T`,
///
/// ```text
/// (W^T W) lambda = b_A - W^T y,     L^T x_F = y + W lambda,
/// ```
///
/// (`a_F` and `b_A` shifted by the fixed variables), the bound multipliers being the
/// components `G x + a - C_A^T lambda` of the fixed variables. The result is the QP's
/// optimum, and is accepted, only when it is a KKT point: every inequality multiplier
/// `>= 0` and every other row satisfied as closely as the dual method's own stop asks.
/// False (with `x`, `lambda` and the workspace to be reset by the caller) otherwise, or when
/// the rows of `A` are dependent or `G_FF` is not positive definite.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_on_active_set(
    rows: &Rows,
    g: &[f64],
    a: &[f64],
    meq: usize,
    hint: &[usize],
    x: &mut [f64],
    lambda: &mut [f64],
    ws: &mut QpWorkspace,
) -> bool {
    let (n, mg, m) = (rows.n, rows.mg, rows.count());
    // the active set: the equalities, then the hinted inequalities, each once; a bound row
    // fixes its variable in x
    ws.in_active.clear();
    ws.in_active.resize(m, false);
    ws.fixed.clear();
    ws.fixed.resize(n, false);
    ws.active.clear();
    ws.general.clear();
    ws.bound_vars.clear();
    for i in (0..meq).chain(hint.iter().copied().filter(|&i| i >= meq)) {
        if i >= m || ws.in_active[i] {
            continue;
        }
        match rows.unit(i) {
            None => ws.general.push(i),
            Some((j, v)) => {
                let bound = if v > 0.0 {
                    rows.lower[j]
                } else {
                    rows.upper[j]
                };
                if ws.fixed[j] || !bound.is_finite() {
                    return false;
                }
                ws.fixed[j] = true;
                ws.bound_vars.push(j);
                x[j] = bound;
            }
        }
        ws.in_active[i] = true;
        ws.active.push(i);
    }
    ws.free.clear();
    ws.free.extend((0..n).filter(|&j| !ws.fixed[j]));
    let (free, general, bound_vars) = (&ws.free, &ws.general, &ws.bound_vars);
    let (nf, na) = (free.len(), general.len());
    if na > nf {
        return false;
    }
    // G's lower triangle; free is ascending, so G_FF's lower triangle is in it
    let gl = |i: usize, j: usize| g[i.max(j) * n + i.min(j)];
    // G_FF = L L^T into ws.l
    if !cholesky(&mut ws.l, n, nf, 0.0, |r, k| g[free[r] * n + free[k]]) {
        return false;
    }
    let l = &ws.l;
    // y = -L^-1 (a_F + G_FB x_B) into ws.d
    let y = &mut ws.d[..nf];
    for (yr, &i) in y.iter_mut().zip(free) {
        *yr = -(a[i] + bound_vars.iter().map(|&j| gl(i, j) * x[j]).sum::<f64>());
    }
    forward_substitute(l, n, nf, y);
    // column k of W = L^-1 C_AF^T into ws.j[k*n..], and the right side b_A - C_AB x_B - W^T y
    // into ws.rv
    let mut w_scale: f64 = 0.0;
    for (k, &i) in general.iter().enumerate() {
        let row = &rows.c[i * n..(i + 1) * n];
        let w = &mut ws.j[k * n..k * n + nf];
        for (wr, &j) in w.iter_mut().zip(free) {
            *wr = row[j];
        }
        forward_substitute(l, n, nf, w);
        w_scale = w_scale.max(dot(w, w));
        let fixed: f64 = bound_vars.iter().map(|&j| row[j] * x[j]).sum();
        ws.rv[k] = rows.b[i] - fixed - dot(w, y);
    }
    // W^T W = R R^T into ws.r (as L), then the multipliers into ws.rv; dependent or nearly
    // dependent rows (an angle below about 1e-7) are left to the dual method, which never
    // makes a dependent row active
    let (wm, r) = (&ws.j, &mut ws.r);
    let wtw = |p: usize, k: usize| dot(&wm[p * n..p * n + nf], &wm[k * n..k * n + nf]);
    if !cholesky(r, n, na, 1e-14 * w_scale, wtw) {
        return false;
    }
    let u = &mut ws.rv[..na];
    forward_substitute(r, n, na, u);
    back_substitute(r, n, na, u);
    if general
        .iter()
        .zip(u.iter())
        .any(|(&i, &ui)| i >= meq && !at_least(ui, 0.0))
    {
        return false;
    }
    // x_F = L^-T (y + W lambda)
    let z = &mut ws.z[..nf];
    for (rr, zr) in z.iter_mut().enumerate() {
        *zr = y[rr] + (0..na).map(|k| wm[k * n + rr] * u[k]).sum::<f64>();
    }
    back_substitute(l, n, nf, z);
    for (&j, &zj) in free.iter().zip(z.iter()) {
        x[j] = zj;
    }
    let in_active = &ws.in_active;
    let others_met = for_length!(
        n,
        |N| others_met::<N>(rows, meq, in_active, x),
        others_met::<0>(rows, meq, in_active, x)
    );
    if !others_met {
        return false;
    }
    if !rows.lower.is_empty() {
        for &j in free {
            let (lo, hi) = (rows.lower[j], rows.upper[j]);
            if (lo.is_finite() && !at_least((x[j] - lo) / (2.0 + lo.abs()), -1e-14))
                || (hi.is_finite() && !at_least((hi - x[j]) / (2.0 + hi.abs()), -1e-14))
            {
                return false;
            }
        }
    }
    // the bound multipliers: G x + a - C_A^T lambda on the fixed variables
    for &j in bound_vars {
        let mut res = a[j] + (0..n).map(|k| gl(j, k) * x[k]).sum::<f64>();
        for (&i, &ui) in general.iter().zip(u.iter()) {
            res -= ui * rows.c[i * n + j];
        }
        let (row, multiplier) = if ws.in_active[mg + 2 * j] {
            (mg + 2 * j, res)
        } else {
            (mg + 2 * j + 1, -res)
        };
        if !at_least(multiplier, 0.0) {
            return false;
        }
        lambda[row] = multiplier;
    }
    for (&i, &ui) in general.iter().zip(u.iter()) {
        lambda[i] = ui;
    }
    true
}

/// Whether every general inequality not in `in_active` is satisfied at `x`, as closely as
/// the dual method's stop asks; a finite slack `>= 0` passes whatever the row's size,
/// which is worked out only below zero. Rows of `N` entries ([`dot_of`]).
#[inline(always)]
#[allow(clippy::needless_range_loop)] // `i` indexes the rows, `b` and `in_active`
fn others_met<const N: usize>(rows: &Rows, meq: usize, in_active: &[bool], x: &[f64]) -> bool {
    let n = rows.n;
    for i in meq..rows.mg {
        if !in_active[i] {
            let row = &rows.c[i * n..(i + 1) * n];
            let slack = dot_of::<N>(row, x) - rows.b[i];
            if (0.0..f64::INFINITY).contains(&slack) {
                continue;
            }
            let scaled = slack / rows.size(i);
            if !at_least(scaled, -1e-14) {
                return false;
            }
        }
    }
    true
}

/// `v >= floor`, false for a NaN.
fn at_least(v: f64, floor: f64) -> bool {
    v >= floor
}
