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
//! In a sequence of related QPs (an SQP's) the last active set is usually the next one's:
//! given as a hint, it is first solved directly, as an equality-constrained QP, and the dual
//! method runs only when that is not a KKT point.
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
    /// The direct solve on a hinted active set: per variable whether a bound row fixes it,
    /// the free variables, the active general rows, the fixed variables.
    fixed: Vec<bool>,
    free: Vec<usize>,
    general: Vec<usize>,
    bound_vars: Vec<usize>,
    /// Whether the last solve ended on its hint's active set: a guess that held once is
    /// tried directly the next time (measured on the wei2017 study: it then holds 4 times in
    /// 5, against 1 in 5 after a guess that failed).
    hint_held: bool,
    /// Solves answered by the direct path, for tests and statistics.
    direct_solves: usize,
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
            fixed: Vec::with_capacity(n),
            free: Vec::with_capacity(n),
            general: Vec::with_capacity(n),
            bound_vars: Vec::with_capacity(n),
            hint_held: false,
            direct_solves: 0,
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

/// How many solves with this workspace were answered on the hinted active set directly,
/// without the dual method.
pub fn direct_solves(ws: &QpWorkspace) -> usize {
    ws.direct_solves
}

/// As [`solve`], with simple bounds (`lower`, `upper`: empty for none, infinite entries
/// for free sides) whose multipliers follow the general rows in `lambda` (length
/// `m + 2n` then), and trying the inequalities of `hint` first (in its order) while they
/// are violated: the dual method is correct whichever violated constraint it adds next,
/// and a good guess of the active set, such as the previous SQP iteration's, spares it the
/// constraints it would add and drop again. When the hint (with the equalities) is the
/// optimal active set, as it is in most late SQP iterations, the QP is solved directly on it
/// ([`solve_on_active_set`]) and the dual method is not run at all.
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
    if ws.hint_held && !hint.is_empty() {
        if solve_on_active_set(&rows, g, a, meq, hint, x, lambda, ws) {
            ws.direct_solves += 1;
            return QpStatus::Optimal;
        }
        lambda.fill(0.0);
    }
    ws.hint_held = false;
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
    ws.hint_held = !hint.is_empty()
        && ws.active.len() == hint.len()
        && hint.iter().all(|&i| i < m && ws.in_active[i]);
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
fn solve_on_active_set(
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
    // every other row satisfied, as closely as the dual method's stop asks
    for i in meq..mg {
        if !ws.in_active[i] {
            let row = &rows.c[i * n..(i + 1) * n];
            let scaled = (dot(row, x) - rows.b[i]) / (1.0 + rows.b[i].abs() + norm(row));
            if !at_least(scaled, -1e-14) {
                return false;
            }
        }
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

/// `v >= floor`, false for a NaN.
fn at_least(v: f64, floor: f64) -> bool {
    v >= floor
}

/// `v <- L^-1 v`, `L` the first `k x k` of a row-major lower triangle with stride `n` and
/// reciprocal pivots on its diagonal.
fn forward_substitute(l: &[f64], n: usize, k: usize, v: &mut [f64]) {
    for i in 0..k {
        let s = v[i] - dot(&l[i * n..i * n + i], &v[..i]);
        v[i] = s * l[i * n + i];
    }
}

/// `v <- L^-T v`, `L` as in [`forward_substitute`].
fn back_substitute(l: &[f64], n: usize, k: usize, v: &mut [f64]) {
    for i in (0..k).rev() {
        let s = v[i] - (i + 1..k).map(|p| l[p * n + i] * v[p]).sum::<f64>();
        v[i] = s * l[i * n + i];
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

/// `L L^T` of the `k x k` symmetric matrix whose lower triangle is `entry(r, c)` (`r >= c`),
/// into `l` (row-major lower triangle with stride `n`), the diagonal holding the reciprocal
/// pivots, which is all the solves need; false when a pivot is not above `min_pivot` or not
/// finite.
fn cholesky(
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
                let status = solve_with_hint(
                    &gr,
                    a.as_slice(),
                    &cr,
                    b.as_slice(),
                    meq,
                    &lower,
                    &upper,
                    &hint,
                    &mut x,
                    &mut lambda,
                    &mut ws,
                );
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
