//! Dense strictly convex quadratic programs, solved exactly by the dual active-set method of
//! Goldfarb and Idnani.
//!
//! ```text
//! minimize    1/2 x^T G x + a^T x
//! subject to  c_i^T x  = b_i   (i < meq)
//!             c_i^T x >= b_i   (meq <= i < m)
//! ```
//!
//! with `G` symmetric positive definite, and optionally simple bounds `lower <= x <= upper`,
//! which are handled as implicit rows (row `m + 2j` is `x_j >= lower_j`, row `m + 2j + 1` is
//! `-x_j >= -upper_j`) without building them. The method starts from the unconstrained minimum
//! and adds violated constraints one at a time, keeping the iterate dual feasible; each step
//! either makes the new constraint active (a full step) or drops an active constraint whose
//! multiplier would turn negative (a partial step). It keeps `J = L^-T Q` (with `G = L L^T`)
//! and an upper triangular `R` of the active constraints, updated by Givens rotations.
//!
//! Reference: D. Goldfarb and A. Idnani, "A numerically stable dual method for solving
//! strictly convex quadratic programs", Mathematical Programming 27 (1983) 1-33.

/// How a QP solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QpStatus {
    Optimal,
    /// The constraints have no common point (the dual is unbounded).
    Infeasible,
    /// `G` is not positive definite.
    NotConvex,
    /// More active-set changes than the limit: a degenerate, cycling problem.
    IterationLimit,
}

/// Scratch space for QPs of up to `n` variables; reused across solves, so a solve does not
/// allocate.
#[derive(Debug, Clone)]
pub struct QpWorkspace {
    n: usize,
    /// `J`, column-major: column `k` is `j[k*n..(k+1)*n]`.
    j: Vec<f64>,
    /// `R`, column-major, upper triangular in its first `q` columns.
    r: Vec<f64>,
    active: Vec<usize>,
    /// Multipliers of the active constraints.
    u: Vec<f64>,
    d: Vec<f64>,
    z: Vec<f64>,
    rv: Vec<f64>,
    /// Normal of the constraint being added (its sign flipped for an equality approached
    /// from above).
    np: Vec<f64>,
    in_active: Vec<bool>,
    /// Equalities added with their normal negated: their multiplier changes sign.
    flipped: Vec<bool>,
    /// The Cholesky factor, row-major lower triangle.
    l: Vec<f64>,
    /// Per general row: the reciprocal of its size, for comparing violations.
    inv_scale: Vec<f64>,
}

impl QpWorkspace {
    pub fn new(n: usize) -> Self {
        QpWorkspace {
            n,
            j: vec![0.0; n * n],
            r: vec![0.0; n * n],
            active: Vec::with_capacity(n),
            u: Vec::with_capacity(n),
            d: vec![0.0; n],
            z: vec![0.0; n],
            rv: vec![0.0; n],
            np: vec![0.0; n],
            in_active: Vec::new(),
            flipped: Vec::new(),
            l: vec![0.0; n * n],
            inv_scale: Vec::new(),
        }
    }
}

/// Solves the QP. `g` is `n x n` row-major (only its lower triangle is read), `c` is `m x n`
/// row-major (one constraint per row). On `Optimal`, `x` holds the solution and `lambda`
/// the multipliers (zero for inactive constraints, `>= 0` for inequalities).
#[allow(clippy::too_many_arguments)]
pub fn solve(
    g: &[f64],
    a: &[f64],
    c: &[f64],
    b: &[f64],
    meq: usize,
    x: &mut [f64],
    lambda: &mut [f64],
    ws: &mut QpWorkspace,
) -> QpStatus {
    solve_with_hint(g, a, c, b, meq, &[], &[], &[], x, lambda, ws)
}

/// The rows active at the last solve, after [`solve`] or [`solve_with_hint`].
pub fn active_rows(ws: &QpWorkspace) -> &[usize] {
    &ws.active
}

/// As [`solve`], with simple bounds (`lower`, `upper`: empty for none, infinite entries
/// for free sides) whose multipliers follow the general rows in `lambda` (length
/// `m + 2n` then), and trying the inequalities of `hint` first (in its order) while they
/// are violated: the dual method is correct whichever violated constraint it adds next,
/// and a good guess of the active set, such as the previous SQP iteration's, spares it the
/// constraints it would add and drop again.
#[allow(clippy::too_many_arguments)]
pub fn solve_with_hint(
    g: &[f64],
    a: &[f64],
    c: &[f64],
    b: &[f64],
    meq: usize,
    lower: &[f64],
    upper: &[f64],
    hint: &[usize],
    x: &mut [f64],
    lambda: &mut [f64],
    ws: &mut QpWorkspace,
) -> QpStatus {
    let n = a.len();
    let mg = b.len();
    let rows = Rows {
        c,
        b,
        n,
        mg,
        lower,
        upper,
    };
    let m = rows.count();
    assert!(
        ws.n == n && g.len() == n * n && c.len() == mg * n && x.len() == n && lambda.len() == m
    );
    assert!(lower.is_empty() || (lower.len() == n && upper.len() == n));
    lambda.fill(0.0);
    if !factor(g, n, &mut ws.l, &mut ws.j) {
        return QpStatus::NotConvex;
    }
    // unconstrained minimum x = -G^-1 a = -J J^T a
    for k in 0..n {
        ws.d[k] = dot(col(&ws.j, n, k), a);
    }
    for (i, xi) in x.iter_mut().enumerate() {
        *xi = -(0..n).map(|k| ws.j[k * n + i] * ws.d[k]).sum::<f64>();
    }
    ws.active.clear();
    ws.u.clear();
    ws.in_active.clear();
    ws.in_active.resize(m, false);
    ws.flipped.clear();
    ws.flipped.resize(m, false);
    ws.inv_scale.clear();
    ws.inv_scale
        .extend((0..mg).map(|i| 1.0 / (1.0 + b[i].abs() + norm(&c[i * n..(i + 1) * n]))));
    let max_changes = 10 * (n + m) + 20;
    let mut changes = 0;
    let mut next_eq = 0;
    let mut next_hint = 0;
    loop {
        // choose the constraint to add: the next equality, else the most violated inequality
        let mut p = usize::MAX;
        let mut sign = 1.0;
        if next_eq < meq {
            p = next_eq;
            next_eq += 1;
            if rows.slack(p, x) > 0.0 {
                // approach the equality from above: add it as -c^T x >= -b
                sign = -1.0;
                ws.flipped[p] = true;
            }
        } else {
            while next_hint < hint.len() {
                let i = hint[next_hint];
                next_hint += 1;
                if i >= meq
                    && i < m
                    && !ws.in_active[i]
                    && rows.scaled_slack(i, x, &ws.inv_scale) < -1e-14
                {
                    p = i;
                    break;
                }
            }
        }
        if p == usize::MAX {
            // the most violated inequality, violations relative to the constraint's size so
            // that scaling a row does not change which is the worst; general rows, then the
            // bounds (lower, upper) of each variable
            let mut worst = 0.0;
            let general = c.chunks_exact(n).zip(b).zip(&ws.inv_scale).enumerate();
            for (i, ((row, &bi), &inv)) in general.skip(meq) {
                if !ws.in_active[i] {
                    let s = (dot(row, x) - bi) * inv;
                    if s < worst {
                        worst = s;
                        p = i;
                    }
                }
            }
            if !lower.is_empty() {
                for (j, ((&xj, &lo), &hi)) in x.iter().zip(lower).zip(upper).enumerate() {
                    let i = mg + 2 * j;
                    if lo.is_finite() && !ws.in_active[i] {
                        let s = (xj - lo) / (2.0 + lo.abs());
                        if s < worst {
                            worst = s;
                            p = i;
                        }
                    }
                    if hi.is_finite() && !ws.in_active[i + 1] {
                        let s = (hi - xj) / (2.0 + hi.abs());
                        if s < worst {
                            worst = s;
                            p = i + 1;
                        }
                    }
                }
            }
            if p == usize::MAX || worst > -1e-14 {
                break;
            }
        }
        let unit = rows.unit(p);
        match unit {
            Some(_) => ws.np.fill(0.0),
            None => {
                for (k, v) in ws.np.iter_mut().enumerate() {
                    *v = sign * c[p * n + k];
                }
            }
        }
        if let Some((j, v)) = unit {
            ws.np[j] = sign * v;
        }
        let mut up = 0.0;
        // add p, dropping active constraints on the way as needed
        loop {
            changes += 1;
            if changes > max_changes {
                return QpStatus::IterationLimit;
            }
            let q = ws.active.len();
            match unit {
                // d = J^T (sign' e_j): row j of J
                Some((j, v)) => {
                    for k in 0..n {
                        ws.d[k] = sign * v * ws.j[k * n + j];
                    }
                }
                None => {
                    for k in 0..n {
                        ws.d[k] = dot(col(&ws.j, n, k), &ws.np);
                    }
                }
            }
            // primal direction z = J2 d2, dual direction r = R^-1 d1
            ws.z.fill(0.0);
            for k in q..n {
                let dk = ws.d[k];
                for (zi, jk) in ws.z.iter_mut().zip(col(&ws.j, n, k)) {
                    *zi += jk * dk;
                }
            }
            for i in (0..q).rev() {
                let mut s = ws.d[i];
                for k in i + 1..q {
                    s -= ws.r[k * n + i] * ws.rv[k];
                }
                ws.rv[i] = s / ws.r[i * n + i];
            }
            // partial step: the largest step before an active inequality's multiplier hits zero
            let mut t1 = f64::INFINITY;
            let mut drop = usize::MAX;
            for k in 0..q {
                if ws.active[k] >= meq && ws.rv[k] > 0.0 {
                    let t = ws.u[k] / ws.rv[k];
                    if t < t1 {
                        t1 = t;
                        drop = k;
                    }
                }
            }
            // full step: the step that makes p active
            let zn = dot(&ws.z, &ws.np);
            let sp = sign * rows.slack(p, x);
            let dnorm = norm(&ws.d);
            let t2 = if zn.abs() <= 1e-14 * dnorm * dnorm.max(1.0) {
                f64::INFINITY
            } else {
                -sp / zn
            };
            let t = t1.min(t2);
            if t.is_infinite() {
                return QpStatus::Infeasible;
            }
            if t2.is_finite() {
                for (xi, zi) in x.iter_mut().zip(&ws.z) {
                    *xi += t * zi;
                }
            }
            for k in 0..q {
                ws.u[k] -= t * ws.rv[k];
            }
            up += t;
            if t2 <= t1 {
                add_constraint(ws, n, p, up);
                break;
            }
            drop_constraint(ws, n, drop);
        }
    }
    for (&i, &ui) in ws.active.iter().zip(&ws.u) {
        lambda[i] = if ws.flipped[i] { -ui } else { ui };
    }
    QpStatus::Optimal
}

/// The constraints: `mg` general rows, then (with bounds) two implicit rows per variable.
struct Rows<'a> {
    c: &'a [f64],
    b: &'a [f64],
    n: usize,
    mg: usize,
    lower: &'a [f64],
    upper: &'a [f64],
}

impl Rows<'_> {
    fn count(&self) -> usize {
        self.mg + if self.lower.is_empty() { 0 } else { 2 * self.n }
    }

    /// `Some((j, sign))` for a bound row `sign * x_j >= ...`.
    fn unit(&self, i: usize) -> Option<(usize, f64)> {
        (i >= self.mg).then(|| {
            let k = i - self.mg;
            (k / 2, if k.is_multiple_of(2) { 1.0 } else { -1.0 })
        })
    }

    /// `c_i^T x - b_i`; `+inf` for an infinite bound.
    fn slack(&self, i: usize, x: &[f64]) -> f64 {
        match self.unit(i) {
            None => dot(&self.c[i * self.n..(i + 1) * self.n], x) - self.b[i],
            Some((j, v)) => {
                let bound = if v > 0.0 {
                    self.lower[j]
                } else {
                    self.upper[j]
                };
                if bound.is_finite() {
                    v * (x[j] - bound)
                } else {
                    f64::INFINITY
                }
            }
        }
    }

    /// The slack relative to the row's size.
    fn scaled_slack(&self, i: usize, x: &[f64], inv_scale: &[f64]) -> f64 {
        match self.unit(i) {
            None => self.slack(i, x) * inv_scale[i],
            Some((j, v)) => {
                let bound = if v > 0.0 {
                    self.lower[j]
                } else {
                    self.upper[j]
                };
                self.slack(i, x) / (2.0 + bound.abs())
            }
        }
    }
}

fn col(m: &[f64], n: usize, k: usize) -> &[f64] {
    &m[k * n..(k + 1) * n]
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// `J = L^-T` with `G = L L^T`, column-major; false if `G` is not positive definite.
fn factor(g: &[f64], n: usize, l: &mut [f64], j: &mut [f64]) -> bool {
    // Cholesky into a row-major lower triangle; the diagonal holds the reciprocal pivots,
    // which is all the solves below need
    for i in 0..n {
        for k in 0..=i {
            let s = g[i * n + k] - dot(&l[i * n..i * n + k], &l[k * n..k * n + k]);
            if i == k {
                if s <= 0.0 || !s.is_finite() {
                    return false;
                }
                l[i * n + i] = 1.0 / s.sqrt();
            } else {
                l[i * n + k] = s * l[k * n + k];
            }
        }
    }
    // J = L^-T: column k solves L^T y = e_k (L^T upper triangular)
    j.fill(0.0);
    for k in 0..n {
        let y = &mut j[k * n..(k + 1) * n];
        for i in (0..=k).rev() {
            let mut s = if i == k { 1.0 } else { 0.0 };
            for p in i + 1..=k {
                s -= l[p * n + i] * y[p];
            }
            y[i] = s * l[i * n + i];
        }
    }
    true
}

/// Makes constraint `p` (with `d = J^T n_p` in `ws.d`) the last active one.
fn add_constraint(ws: &mut QpWorkspace, n: usize, p: usize, up: f64) {
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
fn drop_constraint(ws: &mut QpWorkspace, n: usize, k: usize) {
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

#[cfg(test)]
mod tests {
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

    #[test]
    fn agrees_with_enumeration_on_random_problems() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let (mut solved, mut infeasible) = (0, 0);
        for _ in 0..400 {
            let n = rng.random_range(1..=4);
            let m = rng.random_range(1..=7);
            let meq = rng.random_range(0..=m.min(n).min(2));
            let h = DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0));
            let g = &h * h.transpose() + DMatrix::identity(n, n) * 0.1;
            let a = DVector::from_fn(n, |_, _| rng.random_range(-3.0..3.0));
            let c = DMatrix::from_fn(m, n, |_, _| rng.random_range(-1.0..1.0));
            let b = DVector::from_fn(m, |_, _| rng.random_range(-1.0..1.0));
            let mut ws = QpWorkspace::new(n);
            let (mut x, mut lambda) = (vec![0.0; n], vec![0.0; m]);
            let gr: Vec<f64> = (0..n * n).map(|k| g[(k / n, k % n)]).collect();
            let cr: Vec<f64> = (0..m * n).map(|k| c[(k / n, k % n)]).collect();
            let status = solve(
                &gr,
                a.as_slice(),
                &cr,
                b.as_slice(),
                meq,
                &mut x,
                &mut lambda,
                &mut ws,
            );
            match brute_force(&g, &a, &c, &b, meq) {
                Some((xb, _)) => {
                    assert_eq!(status, QpStatus::Optimal);
                    let x = DVector::from_vec(x);
                    assert!((&x - &xb).norm() < 1e-8 * (1.0 + xb.norm()), "{x} vs {xb}");
                    // stationarity: G x + a = C^T lambda
                    let res = &g * &x + &a - c.transpose() * DVector::from_column_slice(&lambda);
                    assert!(res.norm() < 1e-8, "stationarity {}", res.norm());
                    assert!(lambda[meq..].iter().all(|&l| l >= -1e-12));
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

    #[test]
    fn rejects_an_indefinite_hessian() {
        let mut ws = QpWorkspace::new(2);
        let (mut x, mut l) = (vec![0.0; 2], vec![]);
        let st = solve(
            &[1.0, 0.0, 0.0, -1.0],
            &[0.0, 0.0],
            &[],
            &[],
            0,
            &mut x,
            &mut l,
            &mut ws,
        );
        assert_eq!(st, QpStatus::NotConvex);
    }
}
