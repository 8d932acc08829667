//! A design problem as the solvers see it.
//!
//! - Variables: the free design variables scaled to `[0, 1]` by their bounds.
//! - Objective: the objective output, negated for a maximization, its absolute value if
//!   the problem asks for it.
//! - Constraints: one inequality per limit, `(value - lower) / |lower| >= 0` or
//!   `(upper - value) / |upper| >= 0` (divided by 1 SI unit where the limit is 0), so that
//!   a constraint's value is its relative margin. An upper limit on an output the model
//!   defines as a maximum (`Model::max_of`) becomes one such row per part: the same
//!   feasible set, without the kinks of the max.
//!
//! - The ranges where the model's fits hold ([`super::fit`]), unless the file says
//!   otherwise: each ratio's bounds are rows of the same form, after the problem's own
//!   constraints, counted as constraints `constraints.len() + j` (the `j`-th range).
//! - The part's rules ([`crate::model::part_rules`]), where the model's part states them
//!   and enforces them (`[part] enforce`, the default): one row `margin / SCALE >= 0` each,
//!   after the ranges, counted as constraints `constraints.len() + ranges + i`.
//!
//! - A robust study (`[search] robust`): each row of a problem constraint keeps `k` times
//!   its output's first-order standard deviation under the tolerances
//!   ([`super::tolerances`]) inside its limit, `sign * (value - limit) - k sigma >= 0`
//!   (scaled alike): the first-order second-moment method (Parkinson, Sorensen and
//!   Pourhassan, J. Mech. Des. 115 (1993) 74-80). The spreads follow the rules' margins
//!   among the values, one per wanted output; their gradients come from the model's exact
//!   second derivatives ([`crate::model::mechanism::ModulusScaling::evaluate_with_hessian`]).
//!
//! The model is asked for exactly the outputs the objective and constraints name, once
//! each (the objective first), at the full parameter vector: the free variables in place
//! among the fixed values; the ranges' ratios, then the rules' margins, follow them among
//! the values the rows read.
//! Gradients are the model's exact ones, through the chain rule of the scaling.

use super::{Problem as DesignProblem, Sense};
use crate::model::fit::FitLimit;
use crate::model::mechanism::PartMaker;
use crate::model::scalar::Jet;
use crate::model::{Model, MAX_PARAMETERS};
use crate::optim::Problem;

mod rows;
mod spreads;
pub(crate) use rows::with_scratch;
use spreads::{point_to_spreads, spreads, Spreads};

/// Relative violation up to which a constraint counts as met: a constraint's value here is
/// its relative margin, so this is the one place where the rule can be stated.
pub const FEASIBILITY_TOLERANCE: f64 = 1e-8;

// a design the study leaves on a range of fit's bound is inside it for the reports too
const _: () = assert!(FEASIBILITY_TOLERANCE == crate::model::fit::TOLERANCE);

// a design the study leaves on a part's rule passes the part's check of it
const _: () = assert!(
    crate::model::part_rules::TOLERANCE == FEASIBILITY_TOLERANCE * crate::model::part_rules::SCALE
);

/// Whether a solve ended at a design that meets every constraint: finite, within
/// [`FEASIBILITY_TOLERANCE`] of each limit, and not a solve that failed or proved the
/// problem infeasible. The one test of a feasible end, wherever ends are sorted.
pub fn feasible_end(s: &crate::optim::Solution) -> bool {
    s.objective.is_finite()
        && s.x.iter().all(|x| x.is_finite())
        && s.max_violation <= FEASIBILITY_TOLERANCE
        && !matches!(
            s.status,
            crate::optim::Status::Failed(_) | crate::optim::Status::Infeasible
        )
}

/// Relative margin within which a constraint counts as active.
pub const ACTIVE_TOLERANCE: f64 = 1e-6;

/// One inequality: `sign * (value - limit) / scale >= 0`, `value` the position of its
/// output among the wanted ones.
#[derive(Debug, Clone, Copy)]
struct Row {
    /// The problem constraint the row belongs to.
    constraint: usize,
    value: usize,
    sign: f64,
    limit: f64,
    scale: f64,
    /// The slot of the output's spread among the values, in a robust study.
    spread: Option<usize>,
}

/// The design problem in the solvers' form.
pub struct DesignNlp<'p> {
    pub problem: &'p DesignProblem,
    model: &'p dyn Model,
    /// The full parameter vector with the fixed values in place.
    base: Vec<f64>,
    /// Model parameter index of each free variable.
    free: Vec<usize>,
    /// Every parameter is free, in model order: designs pass through unchanged.
    all_free: bool,
    /// Output indices the model is asked for: no duplicates, objective first.
    wanted: Vec<usize>,
    /// The ranges of fit the study keeps to; their ratios follow the wanted outputs.
    fits: &'p [FitLimit],
    /// The part whose rules the study keeps to, and how many rules it has.
    part: Option<&'p dyn PartMaker>,
    rules: usize,
    /// Present in a robust study.
    spreads: Option<Spreads<'p>>,
    /// How many of the rules keep their spread too (all of them in a robust study whose
    /// part gives their Hessians; none otherwise): their spreads follow the outputs'.
    rule_spreads: usize,
    offset: Vec<f64>,
    range: Vec<f64>,
    zeros: Vec<f64>,
    ones: Vec<f64>,
    rows: Vec<Row>,
    /// `sign * range_j / scale` of each row and variable, row-major: the chain rule of the
    /// scalings, worked out once (the divisions showed in the solver's profile).
    jacobian_factor: Vec<f64>,
}

impl<'p> DesignNlp<'p> {
    /// The study's problem: every constraint, range of fit and part rule it keeps to.
    pub fn new(problem: &'p DesignProblem) -> Self {
        Self::with_rules(problem, usize::MAX)
    }

    /// The problem a start is solved in first where the part keeps some of its rules for
    /// the end ([`crate::model::PartMaker::first_rules`]): [`DesignNlp::new`]'s but for
    /// those. `None` where the part has no such rules.
    pub fn first_stage(problem: &'p DesignProblem) -> Option<Self> {
        let part = super::part_rules::enforced(problem)?;
        (part.first_rules() < part.rules().len())
            .then(|| Self::with_rules(problem, part.first_rules()))
    }

    /// The problems a start is solved in, in turn, each a relaxation of the next and the
    /// last [`DesignNlp::new`]'s ([`crate::optim::staged`]): where the part keeps some of
    /// its rules for the end, the problem without them first; in a robust study, the
    /// nominal problem before the robust ones, as its spreads' gradients cost second
    /// derivatives and they move its optimum only a little, so that most starts need few
    /// robust iterations from the nominal end. A nominal end that breaks a limit is
    /// robust-infeasible too, its margins being only stricter.
    pub fn stages(problem: &'p DesignProblem) -> Vec<Self> {
        let first = super::part_rules::enforced(problem)
            .map(|p| (p.first_rules(), p.rules().len()))
            .filter(|(first, all)| first < all)
            .map(|(first, _)| first);
        let mut stages = Vec::new();
        if problem.search.robust.is_some() {
            stages.push(Self::with_rules_robust(
                problem,
                first.unwrap_or(usize::MAX),
                false,
            ));
        }
        if let Some(f) = first {
            stages.push(Self::with_rules(problem, f));
        }
        stages.push(Self::new(problem));
        stages
    }

    /// The problem with the first `limit` of the part's rules (all, where fewer).
    fn with_rules(problem: &'p DesignProblem, limit: usize) -> Self {
        Self::with_rules_robust(problem, limit, true)
    }

    /// [`DesignNlp::with_rules`], robust where the problem asks for it and `robust` is set.
    fn with_rules_robust(problem: &'p DesignProblem, limit: usize, robust: bool) -> Self {
        let free: Vec<_> = problem.free_variables().collect();
        let model = problem.model();
        let mut rows = Vec::new();
        let mut wanted = vec![problem.objective.index];
        let mut value_of = |index: usize| {
            wanted.iter().position(|&o| o == index).unwrap_or_else(|| {
                wanted.push(index);
                wanted.len() - 1
            })
        };
        // a minimized maximum reaches the SQP through its parts (super::epigraph)
        if let Some(parts) = super::epigraph::parts(problem) {
            for &part in parts {
                value_of(part);
            }
        }
        for (k, c) in problem.constraints.iter().enumerate() {
            let scale = super::limit_scale;
            if let Some(lo) = c.lower {
                rows.push(Row {
                    constraint: k,
                    value: value_of(c.index),
                    sign: 1.0,
                    limit: lo,
                    scale: scale(lo),
                    spread: None,
                });
            }
            if let Some(hi) = c.upper {
                let parts = model
                    .max_of(c.index)
                    .map(<[usize]>::to_vec)
                    .unwrap_or_else(|| vec![c.index]);
                for part in parts {
                    rows.push(Row {
                        constraint: k,
                        value: value_of(part),
                        sign: -1.0,
                        limit: hi,
                        scale: scale(hi),
                        spread: None,
                    });
                }
            }
        }
        let fits = super::fit::constrained(problem);
        for (j, f) in fits.iter().enumerate() {
            let constraint = problem.constraints.len() + j;
            let value = wanted.len() + j;
            let bounds = [(f.range.lower, 1.0), (f.range.upper, -1.0)];
            for (limit, sign) in bounds.into_iter().filter_map(|(l, s)| Some((l?, s))) {
                rows.push(Row {
                    constraint,
                    value,
                    sign,
                    limit,
                    scale: limit.abs(),
                    spread: None,
                });
            }
        }
        let part = super::part_rules::enforced(problem);
        let rules = part.map_or(0, |p| p.rules().len()).min(limit);
        for i in 0..rules {
            rows.push(Row {
                constraint: problem.constraints.len() + fits.len() + i,
                value: wanted.len() + fits.len() + i,
                sign: 1.0,
                limit: 0.0,
                scale: crate::model::part_rules::SCALE,
                spread: None,
            });
        }
        let spreads = spreads(problem).filter(|_| robust);
        let rule_spreads = match (&spreads, part) {
            (Some(_), Some(p)) if p.rule_hessians() => rules,
            _ => 0,
        };
        if spreads.is_some() {
            let first = wanted.len() + fits.len() + rules;
            let first_rule = problem.constraints.len() + fits.len();
            point_to_spreads(
                problem,
                &mut rows,
                (first, wanted.len()),
                first_rule,
                rule_spreads,
            );
        }
        let range: Vec<f64> = free.iter().map(|v| v.upper - v.lower).collect();
        let jacobian_factor = rows
            .iter()
            .flat_map(|r| range.iter().map(move |rj| r.sign * rj / r.scale))
            .collect();
        // bounded where the file is read (a network's `parameters`, a model's own count)
        assert!(problem.variables.len() <= MAX_PARAMETERS);
        let free_index: Vec<usize> = free.iter().map(|v| v.parameter).collect();
        DesignNlp {
            problem,
            model,
            base: problem.variables.iter().map(|v| v.lower).collect(),
            all_free: free_index.iter().copied().eq(0..problem.variables.len()),
            free: free_index,
            wanted,
            fits,
            part,
            rules,
            spreads,
            rule_spreads,
            offset: free.iter().map(|v| v.lower).collect(),
            range,
            zeros: vec![0.0; free.len()],
            ones: vec![1.0; free.len()],
            rows,
            jacobian_factor,
        }
    }

    /// The free variables (SI) of a scaled design.
    pub fn unscale(&self, u: &[f64]) -> Vec<f64> {
        self.unscale_into(u, &mut [0.0; MAX_PARAMETERS]).to_vec()
    }

    /// [`DesignNlp::unscale`] into a stack buffer, for the evaluation hot path.
    fn unscale_into<'b>(&self, u: &[f64], buf: &'b mut [f64; MAX_PARAMETERS]) -> &'b [f64] {
        let x = &mut buf[..u.len()];
        for ((xi, ui), (o, r)) in x.iter_mut().zip(u).zip(self.offset.iter().zip(&self.range)) {
            *xi = o + r * ui;
        }
        x
    }

    /// The scaled design of free variables given in SI.
    pub fn scale(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .zip(&self.offset)
            .zip(&self.range)
            .map(|((x, o), r)| (x - o) / r)
            .collect()
    }

    /// The full model design (SI) of a scaled design.
    pub fn full_design(&self, u: &[f64]) -> Vec<f64> {
        let mut x = self.base.clone();
        for (&p, v) in self.free.iter().zip(self.unscale(u)) {
            x[p] = v;
        }
        x
    }

    /// The output indices the model computes for this problem, the objective's first.
    pub fn wanted(&self) -> &[usize] {
        &self.wanted
    }

    /// The number of values the rows read: the wanted outputs, then the ratios of the
    /// ranges of fit the study keeps to, then the margins of the part's rules it keeps to.
    pub fn values(&self) -> usize {
        let spreads = if self.spreads.is_some() {
            self.wanted.len() + self.rule_spreads
        } else {
            0
        };
        self.wanted.len() + self.fits.len() + self.rules + spreads
    }

    /// The wanted outputs (SI) at the free variables `free` (SI, model order), then the
    /// ranges' ratios, then the rules' margins: [`DesignNlp::values`] of them.
    pub fn outputs(&self, free: &[f64], out: &mut [f64]) {
        let mut x = [0.0; MAX_PARAMETERS];
        let x = self.fill(free, &mut x);
        let (outputs, rest) = out.split_at_mut(self.wanted.len());
        let (ratios, rest) = rest.split_at_mut(self.fits.len());
        let (margins, spreads) = rest.split_at_mut(self.rules);
        self.model.evaluate(x, &self.wanted, outputs);
        for (r, f) in ratios.iter_mut().zip(self.fits) {
            *r = f.value(x);
        }
        if let Some(part) = self.part {
            part.rule_margins(x, margins);
        }
        if let Some(s) = &self.spreads {
            let (w, n) = (self.wanted.len(), s.sigma.len());
            let mut values = vec![0.0; w];
            let mut jacobian = vec![0.0; w * n];
            s.model
                .evaluate_scaled_with_gradient(x, 1.0, &self.wanted, &mut values, &mut jacobian);
            let (spreads, rule_spreads) = spreads.split_at_mut(w);
            for (spread, row) in spreads.iter_mut().zip(jacobian.chunks_exact(n)) {
                *spread = row
                    .iter()
                    .zip(&s.sigma)
                    .map(|(d, sj)| (d * sj).powi(2))
                    .sum::<f64>()
                    .sqrt();
            }
            if let (Some(part), false) = (self.part, rule_spreads.is_empty()) {
                s.rule_spreads(part, x, rule_spreads);
            }
        }
    }

    /// As [`DesignNlp::outputs`], with the Jacobian over all the model's parameters,
    /// row-major (`jacobian[i * np + p]`, `np` the number of parameters).
    pub fn outputs_with_gradient(&self, free: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        self.outputs_with_gradient_of(free, true, out, jacobian);
    }

    /// [`DesignNlp::outputs_with_gradient`], the part's rules' margins and gradients left
    /// as they come (zero on the evaluation's scratch) unless `rules`.
    pub(crate) fn outputs_with_gradient_of(
        &self,
        free: &[f64],
        rules: bool,
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let mut x = [0.0; MAX_PARAMETERS];
        let x = self.fill(free, &mut x);
        let w = self.wanted.len();
        let np = x.len();
        let (outputs, rest) = out.split_at_mut(w);
        let (ratios, rest) = rest.split_at_mut(self.fits.len());
        let (margins, spreads) = rest.split_at_mut(self.rules);
        let (model_jac, rest_jac) = jacobian.split_at_mut(w * np);
        let (ratio_jac, rest_jac) = rest_jac.split_at_mut(self.fits.len() * np);
        let (margin_jac, spread_jac) = rest_jac.split_at_mut(self.rules * np);
        if let Some(s) = &self.spreads {
            let (spreads, rule_spreads) = spreads.split_at_mut(w);
            let (spread_jac, rule_spread_jac) = spread_jac.split_at_mut(w * np);
            s.spreads_with_gradient(x, &self.wanted, spreads, spread_jac);
            if let (Some(part), true, false) = (self.part, rules, rule_spreads.is_empty()) {
                s.rule_spreads_with_gradient(part, x, rule_spreads, rule_spread_jac);
            }
        }
        if let (Some(part), true) = (self.part, rules) {
            part.rule_margins_with_gradient(x, margins, margin_jac);
        }
        self.model
            .evaluate_with_gradient(x, &self.wanted, outputs, model_jac);
        for ((r, row), f) in ratios
            .iter_mut()
            .zip(ratio_jac.chunks_exact_mut(np))
            .zip(self.fits)
        {
            // the ratio's two terms seeded: the same generic code the value comes from; the
            // value itself as `outputs` computes it, to the last digit
            let mut seeded = [Jet::<2>::from(0.0); MAX_PARAMETERS];
            seeded[f.numerator] = Jet::variable(x[f.numerator], 0);
            seeded[f.denominator] = Jet::variable(x[f.denominator], 1);
            let v = f.value(&seeded[..np]);
            *r = f.value(x);
            row.fill(0.0);
            row[f.numerator] += v.grad[0];
            row[f.denominator] += v.grad[1];
        }
    }

    /// The full parameter vector of the free variables `free`, in `buf` unless every
    /// parameter is free.
    fn fill<'a>(&self, free: &'a [f64], buf: &'a mut [f64; MAX_PARAMETERS]) -> &'a [f64] {
        if self.all_free {
            return free;
        }
        let x = &mut buf[..self.base.len()];
        x.copy_from_slice(&self.base);
        for (&p, &v) in self.free.iter().zip(free) {
            x[p] = v;
        }
        x
    }

    /// The objective as the problem states it (absolute value taken if asked) from the
    /// solver's objective.
    pub fn stated_objective(&self, solver_objective: f64) -> f64 {
        match self.problem.objective.sense {
            Sense::Maximize => -solver_objective,
            Sense::Minimize => solver_objective,
        }
    }

    /// The objective as the problem states it at the scaled design `u`, which the solver
    /// ended at with objective `solver_objective`: that objective, unless the solver saw
    /// the epigraph form ([`super::epigraph`]), whose `t` only bounds the objective until it
    /// converges; then the objective computed afresh.
    pub fn objective_at(&self, u: &[f64], solver_objective: f64) -> f64 {
        if super::epigraph::parts(self.problem).is_none() {
            return self.stated_objective(solver_objective);
        }
        with_scratch(self.values(), 0, |out, _| {
            self.outputs(&self.unscale(u), out);
            out[0]
        })
    }

    /// The mirror image of a scaled design by the model's own map ([`Model::mirror`]), if
    /// the model has one, it leaves the fixed variables as they are, the problem's outputs
    /// are the same there up to sign, and it lies within the bounds; `None` otherwise.
    ///
    /// The model's map is the mechanism's: a network's quarter drawn off the axes has a
    /// mirror image with every mechanical output the same but another part (wei2017's
    /// network: `part_height` 25.0 mm against 17.0 mm), which is no image for a problem that
    /// bounds the part's size.
    pub fn mirror(&self, u: &[f64]) -> Option<Vec<f64>> {
        let original = self.full_design(u);
        let mut x = original.clone();
        let fixed_moved = |x: &[f64]| {
            self.problem
                .variables
                .iter()
                .zip(x)
                .any(|(v, &xi)| v.fixed && xi != v.lower)
        };
        if !self.problem.model().mirror(&mut x) || fixed_moved(&x) {
            return None;
        }
        let free: Vec<f64> = self.free.iter().map(|&p| x[p]).collect();
        let m = self.scale(&free);
        // the outputs last: they cost two evaluations, the bounds nothing
        let within = m.iter().all(|v| (-1e-12..=1.0 + 1e-12).contains(v));
        (within && self.same_wanted(&original, &x)).then_some(m)
    }

    /// Whether the wanted outputs at `x` and at `y` are the same up to sign (relative
    /// 1e-10, the model's own test of a mirror image), or both have none.
    fn same_wanted(&self, x: &[f64], y: &[f64]) -> bool {
        let n = self.wanted.len();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        self.model.evaluate(x, &self.wanted, &mut a);
        self.model.evaluate(y, &self.wanted, &mut b);
        a.iter().zip(&b).all(|(&a, &b)| {
            let (a, b) = (a.abs(), b.abs());
            a == b || (a - b).abs() <= 1e-10 * a.max(b) || (a.is_nan() && b.is_nan())
        })
    }

    /// The constraint rows from the wanted outputs `values`.
    pub(crate) fn constraint_values(&self, values: &[f64], c: &mut [f64]) {
        let k = self.spreads.as_ref().map_or(0.0, |s| s.k);
        for (ci, r) in c.iter_mut().zip(&self.rows) {
            let margin = r.spread.map_or(0.0, |slot| k * values[slot]);
            *ci = (r.sign * (values[r.value] - r.limit) - margin) / r.scale;
        }
    }
}

impl Problem for DesignNlp<'_> {
    fn dimension(&self) -> usize {
        self.range.len()
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.zeros, &self.ones)
    }

    fn equality_count(&self) -> usize {
        0
    }

    fn constraint_count(&self) -> usize {
        self.rows.len()
    }

    fn evaluate(&self, u: &[f64], c: &mut [f64]) -> f64 {
        let mut buf = [0.0; MAX_PARAMETERS];
        let x = self.unscale_into(u, &mut buf);
        with_scratch(self.values(), 0, |out, _| {
            self.outputs(x, out);
            self.constraint_values(out, c);
            let o = &self.problem.objective;
            merit(o.sense, o.absolute, out[0])
        })
    }

    fn evaluate_with_gradient(
        &self,
        u: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        self.evaluate_gradient(u, true, c, gradient, jacobian)
    }

    /// The part's rules are the last rows: where none of them is needed, their margins
    /// are not worked out (the Hessian's refresh at a point where no rule has a multiplier:
    /// wei2017's first stages, where they were a fifth of an evaluation with gradients), and
    /// their rows are zero.
    fn evaluate_with_gradient_of(
        &self,
        u: &[f64],
        needed: &[bool],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let rules = self.rules_needed(needed);
        self.evaluate_gradient(u, rules, c, gradient, jacobian)
    }
}

/// The value an optimizer minimizes for an objective output `value`:
/// `-value` or `-|value|` for a maximization, `value` or `|value|` for a minimization.
pub fn merit(sense: Sense, absolute: bool, value: f64) -> f64 {
    let v = if absolute { value.abs() } else { value };
    match sense {
        Sense::Maximize => -v,
        Sense::Minimize => v,
    }
}
