//! The QP subproblem of an SQP iteration: the quadratic model of the Lagrangian with the
//! linearised constraints, solved by [`crate::optim::qp`], and, where the linearised
//! constraints have no common point, the elastic QP that minimizes their largest violation.

use super::curvature::Curvature;
use super::screening::Screen;
use super::{Iterate, Shape};
use crate::optim::dense::inf_norm;
use crate::optim::qp::{self, QpProblem, QpStatus, QpWorkspace};

/// Which QP gave the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum QpKind {
    /// The plain QP: the linearised constraints are consistent.
    Regular,
    /// The elastic QP: one slack on every constraint, priced in the objective.
    Elastic,
}

/// A QP's step and multipliers.
#[derive(Debug, Clone)]
pub(super) struct Step {
    pub d: Vec<f64>,
    /// Constraint multipliers.
    pub lambda: Vec<f64>,
    /// Bound multipliers: positive at a lower bound, negative at an upper one.
    pub nu: Vec<f64>,
}

impl Step {
    pub fn new(n: usize, m: usize) -> Self {
        Step {
            d: vec![0.0; n],
            lambda: vec![0.0; m],
            nu: vec![0.0; n],
        }
    }
}

/// The arrays of the QP and the workspaces of the plain and the elastic QP.
pub(super) struct Subproblem {
    n: usize,
    g: Vec<f64>,
    a: Vec<f64>,
    c: Vec<f64>,
    b: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    x: Vec<f64>,
    l: Vec<f64>,
    ws: QpWorkspace,
    ws_elastic: QpWorkspace,
    /// Which constraints the plain QP holds ([`screening`]); all of them where screening is
    /// off, and in the elastic QP.
    screen: Screen,
    /// The constraints active at the last plain solve, by their index; the bounds as
    /// `m + 2j` (lower) and `m + 2j + 1` (upper).
    active_hint: Vec<usize>,
    /// `active_hint` as rows of the QP being solved.
    hint: Vec<usize>,
    /// The plain QP's rows are the iterate's Jacobian as it is (every constraint, in order):
    /// `c` is not filled, the QP reads the Jacobian.
    rows_are_jacobian: bool,
}

impl Subproblem {
    pub fn new(n: usize, screening: bool) -> Self {
        Subproblem {
            n,
            g: Vec::new(),
            a: Vec::new(),
            c: Vec::new(),
            b: Vec::new(),
            lo: Vec::new(),
            hi: Vec::new(),
            x: Vec::new(),
            l: Vec::new(),
            ws: QpWorkspace::new(n),
            ws_elastic: QpWorkspace::new(n + 1),
            screen: Screen::new(screening),
            active_hint: Vec::new(),
            hint: Vec::new(),
            rows_are_jacobian: false,
        }
    }

    /// The slack of the last elastic solve: the least largest violation the linearised
    /// constraints allow.
    pub fn slack(&self) -> f64 {
        self.x[self.n]
    }

    /// Solves the QP at `point` with constraint values `rhs` into `step`; the elastic QP
    /// when the plain one has no solution. `None` when even that fails. A model that has
    /// lost its definiteness is restarted (`curvature`) and the QP solved again. `step`
    /// comes in with the last step, whose length screening takes as the next one's reach.
    pub fn solve(
        &mut self,
        shape: &Shape,
        point: &Iterate,
        rhs: &[f64],
        curvature: &mut Curvature,
        step: &mut Step,
    ) -> Option<QpKind> {
        let limit = curvature.step_limit();
        self.screen.select(
            shape,
            point,
            rhs,
            limit,
            inf_norm(&step.d),
            &self.active_hint,
        );
        loop {
            self.build(shape, point, rhs, curvature, false);
            self.x.resize(shape.n, 0.0);
            self.l.resize(self.b.len() + 2 * shape.n, 0.0);
            self.hint.clear();
            self.hint.extend(
                self.active_hint
                    .iter()
                    .filter_map(|&i| self.screen.qp_row(i, shape.m)),
            );
            let c = if self.rows_are_jacobian {
                &point.jac[..shape.m * shape.n]
            } else {
                &self.c
            };
            let problem = QpProblem {
                g: &self.g,
                a: &self.a,
                c,
                b: &self.b,
                meq: shape.meq,
                lower: &self.lo,
                upper: &self.hi,
            };
            // the rows of the plain QP keep their meaning between iterations: start from the
            // last active set
            let status =
                qp::solve_with_hint(&problem, &self.hint, &mut self.x, &mut self.l, &mut self.ws);
            match status {
                QpStatus::Optimal => {
                    self.active_hint.clear();
                    let active = qp::active_rows(&self.ws);
                    self.active_hint
                        .extend(active.iter().map(|&k| self.screen.constraint(k, shape.m)));
                    // a row left out that the step breaks: in with it, and solve again
                    let d = &self.x[..shape.n];
                    if self
                        .screen
                        .admit_broken(shape, point, rhs, d, &mut self.active_hint)
                    {
                        continue;
                    }
                    self.read(shape, step, false);
                    return Some(QpKind::Regular);
                }
                QpStatus::NotConvex if !curvature.is_identity() => {
                    // rounding in the BFGS updates cost B its definiteness: start it afresh
                    curvature.reset();
                    return self.solve(shape, point, rhs, curvature, step);
                }
                _ => break,
            }
        }
        self.screen.take_all(shape.m);
        self.build(shape, point, rhs, curvature, true);
        let nv = shape.n + 1;
        self.x.resize(nv, 0.0);
        self.l.resize(self.b.len() + 2 * nv, 0.0);
        let problem = QpProblem {
            g: &self.g,
            a: &self.a,
            c: &self.c,
            b: &self.b,
            meq: 0,
            lower: &self.lo,
            upper: &self.hi,
        };
        match qp::solve(&problem, &mut self.x, &mut self.l, &mut self.ws_elastic) {
            QpStatus::Optimal => {
                self.read(shape, step, true);
                Some(QpKind::Elastic)
            }
            _ if !curvature.is_identity() => {
                // the elastic QP always has a solution (d = 0 with the slack at the worst
                // violation): the dual method lost it to B's conditioning, as after a
                // refresh across a clearance's kink, or B lost its definiteness. Start B
                // afresh.
                curvature.reset();
                self.solve(shape, point, rhs, curvature, step)
            }
            _ => None,
        }
    }

    /// QP variables: `d` (and the slack in elastic mode), bounded by `lower - x <= d <=
    /// upper - x` (and `s >= 0`). Rows: the linearised constraints, both sides of each
    /// equality in elastic mode.
    fn build(
        &mut self,
        shape: &Shape,
        point: &Iterate,
        rhs: &[f64],
        curvature: &Curvature,
        elastic: bool,
    ) {
        let Shape { n, m, meq, .. } = *shape;
        let nv = n + usize::from(elastic);
        let hess = curvature.matrix();
        self.g.clear();
        self.g.resize(nv * nv, 0.0);
        for i in 0..n {
            self.g[i * nv..i * nv + n].copy_from_slice(&hess[i * n..(i + 1) * n]);
        }
        // B inherits the near-zero curvature of the Lagrangian along the constraint
        // normals; the dual QP method inverts it through L^-T and would lose as many digits
        // as its condition number has. A floor of 1e-6 of the largest curvature bounds that
        // loss and barely moves the step in the directions that matter.
        let floor = 1e-6 * (0..n).map(|i| hess[i * n + i]).fold(0.0, f64::max);
        for i in 0..n {
            self.g[i * nv + i] += floor;
        }
        self.a.clear();
        self.a.extend_from_slice(&point.g);
        self.c.clear();
        self.b.clear();
        self.lo.clear();
        self.hi.clear();
        // the step limit is left out of the elastic QP, whose slack must be free to show
        // how far the linearised constraints can be met
        let limit = if elastic {
            f64::INFINITY
        } else {
            curvature.step_limit()
        };
        self.lo.extend(
            shape
                .lower
                .iter()
                .zip(&point.x)
                .map(|(l, x)| (l - x).max(-limit)),
        );
        self.hi.extend(
            shape
                .upper
                .iter()
                .zip(&point.x)
                .map(|(u, x)| (u - x).min(limit)),
        );
        if elastic {
            // a large linear price on the slack, priced from the gradient alone: the
            // multipliers of an elastic QP are bounded by this price, and feeding them back
            // would make it grow without end
            let price = 1e4 * inf_norm(&point.g).max(1.0);
            // the multipliers' sum is the price plus the slack's curvature times the slack:
            // with a curvature of B's size they followed B, and B, refreshed with them, grew
            // a hundredfold an iteration until the dual method lost the QP (measured on
            // wei2017_min_stress). Small beside the price over the slack's possible size
            // (the worst violation), it keeps them within a thousandth of the price.
            let worst = crate::optim::dense::max_violation(&rhs[..m], meq);
            self.g[n * nv + n] = 1e-3 * price / (1.0 + worst);
            self.a.push(price);
            self.lo.push(0.0);
            self.hi.push(f64::INFINITY);
        }
        // a copy of every row as it is would be the Jacobian itself (a tenth of the QP's
        // cost with the part's rules): the plain QP then reads the Jacobian, and only the
        // right sides are made
        self.rows_are_jacobian = !elastic && self.screen.rows().iter().copied().eq(0..m);
        if self.rows_are_jacobian {
            self.b.extend(rhs[..m].iter().map(|v| -v));
            return;
        }
        for k in 0..self.screen.rows().len() {
            let i = self.screen.rows()[k];
            let row = &point.jac[i * n..(i + 1) * n];
            self.push_row(row, 1.0, elastic, -rhs[i]);
            if elastic && i < meq {
                self.push_row(row, -1.0, elastic, rhs[i]);
            }
        }
    }

    fn push_row(&mut self, row: &[f64], sign: f64, slack: bool, b: f64) {
        self.c.extend(row.iter().map(|v| sign * v));
        if slack {
            self.c.push(1.0);
        }
        self.b.push(b);
    }

    /// The step and the multipliers of the constraints (an equality's two elastic rows
    /// folded into one; zero for a row screened out) and of the bounds.
    fn read(&self, shape: &Shape, step: &mut Step, elastic: bool) {
        let (n, meq) = (shape.n, shape.meq);
        step.d.copy_from_slice(&self.x[..n]);
        step.lambda.fill(0.0);
        let mut row = 0;
        for &i in self.screen.rows() {
            step.lambda[i] = self.l[row];
            row += 1;
            if elastic && i < meq {
                step.lambda[i] -= self.l[row];
                row += 1;
            }
        }
        // the bound rows follow: lower then upper for each variable
        for j in 0..n {
            step.nu[j] = self.l[row + 2 * j] - self.l[row + 2 * j + 1];
        }
    }
}
