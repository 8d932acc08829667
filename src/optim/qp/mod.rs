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
//! The files: this one holds the dual method; [`direct`] the solve on a hinted active set;
//! [`factor`] the factorization and its updates as constraints enter and leave.
//!
//! Reference: D. Goldfarb and A. Idnani, "A numerically stable dual method for solving
//! strictly convex quadratic programs", Mathematical Programming 27 (1983) 1-33.

/// `body` with the const `N` the length `n` where it is one of the studies' (2 to 12 free
/// variables, a minimized maximum's bound among them), `fallback` otherwise.
macro_rules! for_length {
    ($n:expr, |$N:ident| $body:expr, $fallback:expr) => {
        for_length!(@each $n, $N, $body, $fallback, 2 3 4 5 6 7 8 9 10 11 12)
    };
    (@each $n:expr, $N:ident, $body:expr, $fallback:expr, $($k:literal)*) => {
        match $n {
            $($k => {
                const $N: usize = $k;
                $body
            })*
            _ => $fallback,
        }
    };
}

mod direct;
mod factor;
#[cfg(test)]
mod tests;

use super::dense::{dot, norm};
use direct::solve_on_active_set;
use factor::{add_constraint, drop_constraint, factor};

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
    /// Per general row: the reciprocal of its size, for comparing violations; NaN until the
    /// row is first violated in a solve ([`Rows::inv_scale`]).
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

/// A QP: `g` is `n x n` row-major (only its lower triangle is read), `c` is `m x n`
/// row-major (one constraint per row), the first `meq` rows equalities; `lower`, `upper`
/// are simple bounds (empty for none, infinite entries for free sides).
#[derive(Debug, Clone, Copy)]
pub struct QpProblem<'a> {
    pub g: &'a [f64],
    pub a: &'a [f64],
    pub c: &'a [f64],
    pub b: &'a [f64],
    pub meq: usize,
    pub lower: &'a [f64],
    pub upper: &'a [f64],
}

/// Solves the QP. On `Optimal`, `x` holds the solution and `lambda` the multipliers (zero
/// for inactive constraints, `>= 0` for inequalities), the general rows' then, with bounds,
/// two per variable (lower, upper).
pub fn solve(
    problem: &QpProblem,
    x: &mut [f64],
    lambda: &mut [f64],
    ws: &mut QpWorkspace,
) -> QpStatus {
    solve_with_hint(problem, &[], x, lambda, ws)
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

/// As [`solve`], trying the inequalities of `hint` first (in its order) while they
/// are violated: the dual method is correct whichever violated constraint it adds next,
/// and a good guess of the active set, such as the previous SQP iteration's, spares it the
/// constraints it would add and drop again. When the hint (with the equalities) is the
/// optimal active set, as it is in most late SQP iterations, the QP is solved directly on it
/// ([`direct::solve_on_active_set`]) and the dual method is not run at all.
pub fn solve_with_hint(
    problem: &QpProblem,
    hint: &[usize],
    x: &mut [f64],
    lambda: &mut [f64],
    ws: &mut QpWorkspace,
) -> QpStatus {
    let QpProblem {
        g,
        a,
        c,
        b,
        meq,
        lower,
        upper,
    } = *problem;
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
    ws.inv_scale.resize(mg, f64::NAN);
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
                    && rows.scaled_slack(i, x, &mut ws.inv_scale) < -1e-14
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
            let (row, mut worst) = rows.most_violated(meq, x, &ws.in_active, &mut ws.inv_scale);
            p = row;
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
pub(super) struct Rows<'a> {
    c: &'a [f64],
    b: &'a [f64],
    n: usize,
    mg: usize,
    lower: &'a [f64],
    upper: &'a [f64],
}

impl Rows<'_> {
    pub(super) fn count(&self) -> usize {
        self.mg + if self.lower.is_empty() { 0 } else { 2 * self.n }
    }

    /// `Some((j, sign))` for a bound row `sign * x_j >= ...`.
    pub(super) fn unit(&self, i: usize) -> Option<(usize, f64)> {
        (i >= self.mg).then(|| {
            let k = i - self.mg;
            (k / 2, if k.is_multiple_of(2) { 1.0 } else { -1.0 })
        })
    }

    /// `c_i^T x - b_i`; `+inf` for an infinite bound.
    pub(super) fn slack(&self, i: usize, x: &[f64]) -> f64 {
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

    /// The slack relative to the row's size where it is negative; a general row's slack
    /// as it is where not (only its sign is read then, and the size is not worked out).
    pub(super) fn scaled_slack(&self, i: usize, x: &[f64], inv_scale: &mut [f64]) -> f64 {
        match self.unit(i) {
            None => {
                let s = self.slack(i, x);
                if s < 0.0 {
                    s * self.inv_scale(i, inv_scale)
                } else {
                    s
                }
            }
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

    /// General row `i`'s size, `1 + |b_i| + |c_i|`: the rows' violations are compared as
    /// their slacks over their sizes.
    pub(super) fn size(&self, i: usize) -> f64 {
        1.0 + self.b[i].abs() + norm(&self.c[i * self.n..(i + 1) * self.n])
    }

    /// The reciprocal of general row `i`'s [size](Rows::size), worked out where
    /// `inv_scale[i]` does not hold it yet (NaN).
    fn inv_scale(&self, i: usize, inv_scale: &mut [f64]) -> f64 {
        let mut inv = inv_scale[i];
        if inv.is_nan() {
            inv = 1.0 / self.size(i);
            inv_scale[i] = inv;
        }
        inv
    }

    /// The general inequality not in `in_active` whose slack relative to its size is the
    /// lowest below zero, and that scaled slack; `(usize::MAX, 0.0)` where none is below.
    /// A row that meets its bound cannot be the lowest, whatever its size, so a row's size
    /// is worked out only once it is violated (most rows never are: the part's rules far
    /// from their limits); the rows are compared on the same numbers, in the same order.
    /// Kept out of line: inlined into the dual method, whose loop state fills the
    /// registers, the row loop kept its own state on the stack (about 90 instructions a row
    /// of 8 variables, the product's 30 among them; 64 out of line; callgrind, wei2017's
    /// study).
    ///
    /// The row's length is known to the compiler for the studies' sizes ([`for_length`]):
    /// a row's product of 8 then takes about 30 instructions, where the loop over a length
    /// known only at run time took 60 (callgrind, wei2017's study).
    #[inline(never)]
    fn most_violated(
        &self,
        meq: usize,
        x: &[f64],
        in_active: &[bool],
        inv_scale: &mut [f64],
    ) -> (usize, f64) {
        for_length!(
            self.n,
            |N| self.most_violated_of::<N>(meq, x, in_active, inv_scale),
            self.most_violated_of::<0>(meq, x, in_active, inv_scale)
        )
    }

    /// [`Rows::most_violated`] for rows of `N` entries (`N == self.n`), or of any length
    /// where `N` is 0.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // `i` indexes `b`, `in_active` and the sizes
    fn most_violated_of<const N: usize>(
        &self,
        meq: usize,
        x: &[f64],
        in_active: &[bool],
        inv_scale: &mut [f64],
    ) -> (usize, f64) {
        let (n, mg) = (self.n, self.mg);
        let mut worst = 0.0;
        let mut p = usize::MAX;
        let mut consider = |i: usize, r: f64| {
            if r < 0.0 {
                let s = r * self.inv_scale(i, inv_scale);
                if s < worst {
                    worst = s;
                    p = i;
                }
            }
        };
        if N == 0 {
            for i in meq..mg {
                if !in_active[i] {
                    consider(i, dot(&self.c[i * n..(i + 1) * n], x) - self.b[i]);
                }
            }
        } else {
            // the rows walked as arrays, no index worked out and checked for each
            let rows = (meq..mg)
                .zip(self.c[meq * N..mg * N].chunks_exact(N))
                .zip(&self.b[meq..mg])
                .zip(&in_active[meq..mg]);
            for (((i, row), &b), &active) in rows {
                if !active {
                    consider(i, dot_of::<N>(row, x) - b);
                }
            }
        }
        (p, worst)
    }
}

/// [`dot`] of `a` and `b` of length `N` (any length where `N` is 0): the same products
/// summed in the same order, so the same number to the bit, with the loop unrolled.
#[inline(always)]
pub(super) fn dot_of<const N: usize>(a: &[f64], b: &[f64]) -> f64 {
    if N == 0 {
        return dot(a, b);
    }
    let (a, b): (&[f64; N], &[f64; N]) = (a.try_into().unwrap(), b.try_into().unwrap());
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub(super) fn col(m: &[f64], n: usize, k: usize) -> &[f64] {
    &m[k * n..(k + 1) * n]
}
