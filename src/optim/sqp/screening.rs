//! Constraint screening: the plain QP of an iteration holds only the inequalities its step
//! could reach, the others being left out until a step breaks one.
//!
//! An inequality enters where its linearization could fall to zero within the step's reach:
//! `c_i + min_d grad c_i . d <= 0` over the box of the bounds' room cut to `|d_j| <= r`,
//! `r` a few times the last step's length (and within the step limit); every equality and
//! every row active at the last QP enter too. Once the QP is solved, a row left out that the
//! step breaks (by the dual method's own tolerance) is put in and the QP solved again,
//! starting from the active set found. The QP is convex, so a solution of the rows kept that
//! meets the rows left out is the solution of the whole QP: the step and the multipliers (zero
//! for the rows left out) are the whole QP's, and the SQP's merit function, line search and
//! KKT test, which read every row, see no difference but rounding.
//!
//! This is the potential constraint strategy of structural optimization (J. S. Arora,
//! Introduction to Optimum Design, 4th ed., Academic Press 2017, Sec. 13.2; K. Schittkowski,
//! "NLPQL: A FORTRAN subroutine solving constrained nonlinear programming problems", Annals
//! of Operations Research 5 (1986) 485-500, whose QP takes only the active and the nearly
//! active rows), with the step's reach as the margin and, as in an active-set method's warm
//! start, the last active set kept (J. Nocedal and S. J. Wright, Numerical Optimization,
//! 2nd ed., Springer 2006, Sec. 16.5 and 18.2).

use super::{Iterate, Shape};
use crate::optim::dense::{dot, norm};

/// The reach of a step: this many times the length of the last one. A row left out that a
/// step breaks costs one more QP solve.
const REACH_RATIO: f64 = 4.0;

/// The rows of the plain QP.
pub(super) struct Screen {
    on: bool,
    /// The constraints in the QP, ascending: its row `k` is constraint `rows[k]`.
    rows: Vec<usize>,
    /// The QP row of each constraint; `usize::MAX` where it is left out.
    qp_row: Vec<usize>,
}

impl Screen {
    pub fn new(on: bool) -> Self {
        Screen {
            on,
            rows: Vec::new(),
            qp_row: Vec::new(),
        }
    }

    /// The constraints of the QP, in its order.
    pub fn rows(&self) -> &[usize] {
        &self.rows
    }

    /// Every constraint in the QP.
    pub fn take_all(&mut self, m: usize) {
        self.rows.clear();
        self.rows.extend(0..m);
        self.qp_row.clear();
        self.qp_row.extend(0..m);
    }

    /// The QP row of `i`, a constraint (`i < m`) or a bound row (`m + t`, the QP's bound
    /// row `t` after its general rows); `None` for a constraint left out.
    pub fn qp_row(&self, i: usize, m: usize) -> Option<usize> {
        if i >= m {
            return Some(self.rows.len() + i - m);
        }
        let k = self.qp_row[i];
        (k != usize::MAX).then_some(k)
    }

    /// The constraint (or bound row, `m + t`) of the QP's row `k`.
    pub fn constraint(&self, k: usize, m: usize) -> usize {
        match self.rows.get(k) {
            Some(&i) => i,
            None => m + k - self.rows.len(),
        }
    }

    /// Chooses the rows of the QP at `point` with constraint values `rhs`, the step at most
    /// `limit` in each variable, the last step `last` long and `active` (by constraint) the
    /// last QP's active set. Every row when screening is off.
    pub fn select(
        &mut self,
        shape: &Shape,
        point: &Iterate,
        rhs: &[f64],
        limit: f64,
        last: f64,
        active: &[usize],
    ) {
        let Shape {
            n,
            m,
            meq,
            lower,
            upper,
        } = *shape;
        if !self.on {
            self.take_all(m);
            return;
        }
        let reach = (REACH_RATIO * last).min(limit);
        self.qp_row.clear();
        self.qp_row.resize(m, usize::MAX);
        for &i in active.iter().filter(|&&i| i < m) {
            self.qp_row[i] = 0;
        }
        let rows = point.jac.chunks_exact(n).zip(&rhs[..m]);
        for (i, (row, &value)) in rows.enumerate() {
            // the least the linearization can be within the box
            let mut least = value;
            for (j, &gj) in row.iter().enumerate() {
                let lo = (lower[j] - point.x[j]).max(-reach);
                let hi = (upper[j] - point.x[j]).min(reach);
                least += (gj * lo).min(gj * hi);
            }
            if i < meq || least <= 0.0 {
                self.qp_row[i] = 0;
            }
        }
        self.number();
    }

    /// Puts into the QP every row left out that the step `d` breaks, adding it to `hint`;
    /// whether there was any. The test is the dual method's: the row's value relative to
    /// its size below `-1e-14`.
    pub fn admit_broken(
        &mut self,
        shape: &Shape,
        point: &Iterate,
        rhs: &[f64],
        d: &[f64],
        hint: &mut Vec<usize>,
    ) -> bool {
        let (n, m) = (shape.n, shape.m);
        if self.rows.len() == m {
            return false;
        }
        let mut any = false;
        let rows = point.jac.chunks_exact(n).zip(&rhs[..m]);
        for (i, (row, &value)) in rows.enumerate() {
            if self.qp_row[i] != usize::MAX {
                continue;
            }
            let linear = value + dot(row, d);
            if linear / (1.0 + value.abs() + norm(row)) < -1e-14 {
                self.qp_row[i] = 0;
                hint.push(i);
                any = true;
            }
        }
        if any {
            self.number();
        }
        any
    }

    /// `rows` and `qp_row` from the rows marked in (`qp_row` not `usize::MAX`).
    fn number(&mut self) {
        self.rows.clear();
        for (i, k) in self.qp_row.iter_mut().enumerate() {
            if *k != usize::MAX {
                *k = self.rows.len();
                self.rows.push(i);
            }
        }
    }
}
