//! The elastic form of a design problem, for the least violating design of an infeasible one.
//!
//! Each constraint is treated one of four ways ([`Treatment`]): kept as it is, made elastic
//! with a slack of its own, relaxed by a fixed amount, or dropped. A row `c_i(u) >= 0` of an
//! elastic constraint `k` becomes
//!
//! ```text
//! c_i(u) + s_k >= 0,   s_k >= 0
//! ```
//!
//! and the goal ([`Goal::Violation`]) is `sum_k s_k`: the sum of the relative violations
//! (rows are relative margins, [`super::nlp`]), the l1 phase-one objective of elastic
//! programming (Brown and Graves, 1975; Chinneck, Feasibility and Infeasibility in
//! Optimization, Springer 2008, ch. 6 "the elastic filter"). An l1 sum, unlike the largest
//! violation, is zero on every constraint it can be, so the ones it leaves violated are the
//! ones to name. A relaxed constraint `c_i(u) + r_k >= 0` keeps a reached violation `r_k`
//! while [`Goal::Objective`] improves the design's own objective.
//!
//! Variables: the problem's scaled design `u`, then one slack per elastic constraint, each
//! from 0 up (unbounded above).

use super::nlp::DesignNlp;
use crate::optim::Problem;

/// How the elastic form treats one constraint of the problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Treatment {
    /// Kept as stated.
    Hard,
    /// Given a slack that the goal [`Goal::Violation`] minimizes.
    Elastic,
    /// Its rows moved by this relative amount (a violation allowed).
    Relaxed(f64),
    /// Left out.
    Dropped,
}

/// What the elastic form minimizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Goal {
    /// The sum of the slacks.
    Violation,
    /// The problem's own objective (the solver's merit).
    Objective,
}

/// A design problem in elastic form.
pub struct Elastic<'a, 'p> {
    nlp: &'a DesignNlp<'p>,
    goal: Goal,
    /// Per row of `nlp`: its slack (an index among the slacks), its fixed relaxation, or
    /// `None` when the row is dropped.
    rows: Vec<Option<(Option<usize>, f64)>>,
    /// Per constraint: its slack, if elastic.
    slack_of: Vec<Option<usize>>,
    kept: usize,
    slacks: usize,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

impl<'a, 'p> Elastic<'a, 'p> {
    /// `treatment` holds one entry per constraint of the problem.
    pub fn new(nlp: &'a DesignNlp<'p>, treatment: &[Treatment], goal: Goal) -> Self {
        let mut slack_of = vec![None; treatment.len()];
        let mut slacks = 0;
        for (k, t) in treatment.iter().enumerate() {
            if *t == Treatment::Elastic {
                slack_of[k] = Some(slacks);
                slacks += 1;
            }
        }
        // the ranges of fit, counted after the problem's constraints, stay hard: a least
        // violating design is still one the model can answer for
        let rows: Vec<_> = nlp
            .row_constraints()
            .map(
                |k| match treatment.get(k).copied().unwrap_or(Treatment::Hard) {
                    Treatment::Hard => Some((None, 0.0)),
                    Treatment::Elastic => Some((slack_of[k], 0.0)),
                    Treatment::Relaxed(r) => Some((None, r)),
                    Treatment::Dropped => None,
                },
            )
            .collect();
        let n = nlp.dimension();
        let (mut lower, mut upper) = (vec![0.0; n], vec![1.0; n]);
        lower.resize(n + slacks, 0.0);
        upper.resize(n + slacks, f64::INFINITY);
        Elastic {
            nlp,
            goal,
            kept: rows.iter().flatten().count(),
            rows,
            slack_of,
            slacks,
            lower,
            upper,
        }
    }

    /// A start from a scaled design: each slack just large enough for its rows.
    pub fn start(&self, u: &[f64]) -> Vec<f64> {
        let mut c = vec![0.0; self.nlp.constraint_count()];
        self.nlp.evaluate(u, &mut c);
        let mut v = u.to_vec();
        v.resize(u.len() + self.slacks, 0.0);
        for (ci, row) in c.iter().zip(&self.rows) {
            if let Some((Some(j), _)) = row {
                let need = -ci;
                if need.is_finite() && need > v[u.len() + j] {
                    v[u.len() + j] = need;
                }
            }
        }
        v
    }

    /// The slacks of an elastic design `v`.
    pub fn slacks<'v>(&self, v: &'v [f64]) -> &'v [f64] {
        &v[self.nlp.dimension()..]
    }

    /// The slack of constraint `k` in `v`; `None` unless `k` is elastic.
    pub fn slack(&self, v: &[f64], k: usize) -> Option<f64> {
        Some(v[self.nlp.dimension() + self.slack_of[k]?])
    }

    /// Writes the kept rows, elastic or relaxed, from the problem's rows `all`.
    fn kept_rows(&self, v: &[f64], all: &[f64], c: &mut [f64]) {
        let n = self.nlp.dimension();
        let kept = self
            .rows
            .iter()
            .zip(all)
            .filter_map(|(r, &ci)| Some((r.as_ref()?, ci)));
        for (out, (&(slack, relax), ci)) in c.iter_mut().zip(kept) {
            *out = ci + relax + slack.map_or(0.0, |j| v[n + j]);
        }
    }

    fn goal_value(&self, v: &[f64], merit: f64) -> f64 {
        match self.goal {
            Goal::Violation => self.slacks(v).iter().sum(),
            Goal::Objective => merit,
        }
    }
}

impl Problem for Elastic<'_, '_> {
    fn dimension(&self) -> usize {
        self.nlp.dimension() + self.slacks
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    fn equality_count(&self) -> usize {
        0
    }

    fn constraint_count(&self) -> usize {
        self.kept
    }

    fn evaluate(&self, v: &[f64], c: &mut [f64]) -> f64 {
        let n = self.nlp.dimension();
        let mut all = vec![0.0; self.nlp.constraint_count()];
        let merit = self.nlp.evaluate(&v[..n], &mut all);
        self.kept_rows(v, &all, c);
        self.goal_value(v, merit)
    }

    fn evaluate_with_gradient(
        &self,
        v: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let n = self.nlp.dimension();
        let stride = self.dimension();
        let m = self.nlp.constraint_count();
        let (mut all, mut all_jac) = (vec![0.0; m], vec![0.0; m * n]);
        let merit =
            self.nlp
                .evaluate_with_gradient(&v[..n], &mut all, &mut gradient[..n], &mut all_jac);
        self.kept_rows(v, &all, c);
        let kept = self
            .rows
            .iter()
            .zip(all_jac.chunks_exact(n))
            .filter_map(|(r, g)| Some((r.as_ref()?, g)));
        for (row, (&(slack, _), g)) in jacobian.chunks_exact_mut(stride).zip(kept) {
            row[..n].copy_from_slice(g);
            row[n..].fill(0.0);
            if let Some(j) = slack {
                row[n + j] = 1.0;
            }
        }
        match self.goal {
            Goal::Violation => {
                gradient[..n].fill(0.0);
                gradient[n..].fill(1.0);
            }
            Goal::Objective => gradient[n..].fill(0.0),
        }
        self.goal_value(v, merit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::Problem as DesignProblem;

    /// The elastic form's gradients against central differences, every treatment at once.
    #[test]
    fn gradients_match_differences() {
        let problem = DesignProblem::load("problems/wei2017.toml".as_ref()).unwrap();
        // without the part's clearances, whose kinks central differences may straddle
        let nlp = DesignNlp::first_stage(&problem).unwrap();
        let k = problem.constraints.len();
        assert!(k >= 4, "{k}");
        let mut treatment = vec![Treatment::Elastic; k];
        treatment[1] = Treatment::Hard;
        treatment[2] = Treatment::Dropped;
        treatment[3] = Treatment::Relaxed(0.3);
        for goal in [Goal::Violation, Goal::Objective] {
            let e = Elastic::new(&nlp, &treatment, goal);
            let v = e.start(&vec![0.4; nlp.dimension()]);
            let (d, m) = (e.dimension(), e.constraint_count());
            let (mut c, mut g, mut jac) = (vec![0.0; m], vec![0.0; d], vec![0.0; m * d]);
            let f = e.evaluate_with_gradient(&v, &mut c, &mut g, &mut jac);
            let mut c2 = vec![0.0; m];
            assert_eq!(f, e.evaluate(&v, &mut c2));
            assert_eq!(c, c2);
            for j in 0..d {
                let h = 1e-6;
                let (mut vp, mut vm) = (v.clone(), v.clone());
                vp[j] += h;
                vm[j] -= h;
                let (mut cp, mut cm) = (vec![0.0; m], vec![0.0; m]);
                let fd = (e.evaluate(&vp, &mut cp) - e.evaluate(&vm, &mut cm)) / (2.0 * h);
                assert!(
                    (fd - g[j]).abs() <= 1e-5 * (1.0 + g[j].abs()),
                    "{goal:?} f {j}"
                );
                for i in 0..m {
                    let cd = (cp[i] - cm[i]) / (2.0 * h);
                    let exact = jac[i * d + j];
                    assert!(
                        (cd - exact).abs() <= 1e-5 * (1.0 + exact.abs()),
                        "c {i} {j}"
                    );
                }
            }
        }
    }
}
