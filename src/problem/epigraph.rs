//! A minimized maximum as a smooth problem: the epigraph form.
//!
//! An objective that is the largest of several outputs (`Model::max_of`: `stress_max` of the
//! four node stresses) has kinks where two of them cross, and a minimum usually sits on such
//! a kink; an SQP that sees the max stalls there without converging. The standard remedy
//! (e.g. Nocedal and Wright, Numerical Optimization, 2nd ed., 2006, Sec. 12.1, the
//! reformulation of minimax problems) adds one variable `t` and minimizes it with one smooth
//! constraint per part:
//!
//! ```text
//! minimize t   subject to   t - part_i(x) >= 0 for every part,  and the problem's own
//! ```
//!
//! The same optimum, with no kink. `t` is scaled by the size of the objective at the centre
//! of the box (`t_scaled = t / scale`), unbounded, and starts at the largest part of each
//! start design, so every start is feasible for the new rows.

use super::nlp::with_scratch;
use super::nlp::DesignNlp;
use super::{Problem as DesignProblem, Sense};
use crate::optim::Problem;

/// The parts of the problem's objective when it is a maximum to be minimized (as stated:
/// not its absolute value); `None` otherwise.
pub fn parts(problem: &DesignProblem) -> Option<&[usize]> {
    let o = &problem.objective;
    if o.sense != Sense::Minimize || o.absolute {
        return None;
    }
    problem.model().max_of(o.index)
}

/// The problem `nlp` in epigraph form; variables: `nlp`'s, then `t`.
pub struct Epigraph<'a, 'p> {
    nlp: &'a DesignNlp<'p>,
    /// Slots of the objective's parts among the wanted outputs.
    slots: Vec<usize>,
    scale: f64,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

impl<'a, 'p> Epigraph<'a, 'p> {
    /// `None` when the problem's objective is no minimized maximum.
    pub fn new(nlp: &'a DesignNlp<'p>) -> Option<Self> {
        let slots = nlp.slots_of(parts(nlp.problem)?)?;
        let n = nlp.dimension();
        let mut ep = Epigraph {
            nlp,
            slots,
            scale: 1.0,
            lower: vec![0.0; n],
            upper: vec![1.0; n],
        };
        ep.lower.push(f64::NEG_INFINITY);
        ep.upper.push(f64::INFINITY);
        let centre = ep.largest_part(&vec![0.5; n]).abs();
        if centre.is_finite() && centre > 0.0 {
            ep.scale = centre;
        }
        Some(ep)
    }

    /// The largest part (SI) at the scaled design `u`.
    fn largest_part(&self, u: &[f64]) -> f64 {
        let mut out = vec![0.0; self.nlp.values()];
        self.nlp.outputs(&self.nlp.unscale(u), &mut out);
        self.slots
            .iter()
            .map(|&s| out[s])
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// A start of the epigraph problem from a scaled design: `t` at its largest part.
    pub fn start(&self, u: &[f64]) -> Vec<f64> {
        let mut v = u.to_vec();
        let t = self.largest_part(u) / self.scale;
        v.push(if t.is_finite() { t } else { 0.0 });
        v
    }

    fn rows(&self) -> usize {
        self.nlp.constraint_count()
    }
}

impl Problem for Epigraph<'_, '_> {
    fn dimension(&self) -> usize {
        self.nlp.dimension() + 1
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    fn equality_count(&self) -> usize {
        0
    }

    fn constraint_count(&self) -> usize {
        self.rows() + self.slots.len()
    }

    fn evaluate(&self, v: &[f64], c: &mut [f64]) -> f64 {
        let n = self.nlp.dimension();
        with_scratch(self.nlp.values(), 0, |out, _| {
            // one model evaluation: the design rows from it, then one row per part
            self.nlp.outputs(&self.nlp.unscale(&v[..n]), out);
            self.nlp.constraint_values(out, &mut c[..self.rows()]);
            let t = v[n];
            for (ci, &s) in c[self.rows()..].iter_mut().zip(&self.slots) {
                *ci = t - out[s] / self.scale;
            }
            t * self.scale
        })
    }

    fn evaluate_with_gradient(
        &self,
        v: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        self.evaluate_gradient(v, true, c, gradient, jacobian)
    }

    /// The design's rows first, the part's rules last among them ([`DesignNlp`]'s), then
    /// the parts': the rules are worked out only where one of their rows is needed, as
    /// [`DesignNlp`] does.
    fn evaluate_with_gradient_of(
        &self,
        v: &[f64],
        needed: &[bool],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let rules = self.nlp.rules_needed(&needed[..self.rows()]);
        self.evaluate_gradient(v, rules, c, gradient, jacobian)
    }
}

impl Epigraph<'_, '_> {
    /// [`Problem::evaluate_with_gradient`], the part's rules and their rows worked out
    /// only where `rules` (their rows zero otherwise).
    fn evaluate_gradient(
        &self,
        v: &[f64],
        rules: bool,
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let n = self.nlp.dimension();
        let stride = n + 1;
        let np = self.nlp.parameter_count();
        let values = self.nlp.values();
        with_scratch(values, values * np, |out, model_jac| {
            self.nlp
                .outputs_with_gradient_of(&self.nlp.unscale(&v[..n]), rules, out, model_jac);
            let m = self.rows();
            let (design_rows, part_rows) = jacobian.split_at_mut(m * stride);
            // without the rules their rows are not read: zeros
            let written = if rules {
                m
            } else {
                self.nlp.rows_without_rules()
            };
            let (written_rows, unread_rows) = design_rows.split_at_mut(written * stride);
            self.nlp
                .rows_from(out, model_jac, &mut c[..written], written_rows, stride);
            c[written..m].fill(0.0);
            unread_rows.fill(0.0);
            for row in written_rows.chunks_exact_mut(stride) {
                row[n] = 0.0;
            }
            let (free, range) = self.nlp.free_and_range();
            let t = v[n];
            for ((ci, row), &s) in c[m..]
                .iter_mut()
                .zip(part_rows.chunks_exact_mut(stride))
                .zip(&self.slots)
            {
                *ci = t - out[s] / self.scale;
                for ((o, &p), r) in row.iter_mut().zip(free).zip(range) {
                    *o = -model_jac[s * np + p] * r / self.scale;
                }
                row[n] = 1.0;
            }
            gradient[..n].fill(0.0);
            gradient[n] = self.scale;
            t * self.scale
        })
    }
}
