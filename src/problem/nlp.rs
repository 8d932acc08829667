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
//! Gradients are the model's exact ones, through the chain rule of the scaling.

use super::bind::{merit, scratch, Evaluator};
use super::{Problem as DesignProblem, Sense};
use crate::model::{Dimension, MAX_PARAMETERS, MAX_WANTED};
use crate::optim::Problem;

/// One inequality: `sign * (value - limit) / scale >= 0`, `value` the evaluator's
/// `value`-th output.
#[derive(Debug, Clone, Copy)]
struct Row {
    value: usize,
    sign: f64,
    limit: f64,
    scale: f64,
}

/// The design problem in the solvers' form.
pub struct DesignNlp<'p> {
    pub problem: &'p DesignProblem,
    evaluator: Evaluator<'p>,
    /// Number of outputs the evaluator gives besides the objective.
    values: usize,
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
    pub fn new(problem: &'p DesignProblem) -> Self {
        let free: Vec<_> = problem.free_variables().collect();
        let model = problem.model();
        let mut rows = Vec::new();
        let mut outputs: Vec<usize> = Vec::new();
        let mut value_of = |index: usize| {
            outputs.iter().position(|&o| o == index).unwrap_or_else(|| {
                outputs.push(index);
                outputs.len() - 1
            })
        };
        for c in &problem.constraints {
            let scale = |l: f64| if l == 0.0 { 1.0 } else { l.abs() };
            if let Some(lo) = c.lower {
                rows.push(Row {
                    value: value_of(c.index),
                    sign: 1.0,
                    limit: lo,
                    scale: scale(lo),
                });
            }
            if let Some(hi) = c.upper {
                let parts = model
                    .max_of(c.index)
                    .map(<[usize]>::to_vec)
                    .unwrap_or_else(|| vec![c.index]);
                for part in parts {
                    rows.push(Row {
                        value: value_of(part),
                        sign: -1.0,
                        limit: hi,
                        scale: scale(hi),
                    });
                }
            }
        }
        let range: Vec<f64> = free.iter().map(|v| v.upper - v.lower).collect();
        let jacobian_factor = rows
            .iter()
            .flat_map(|r| range.iter().map(move |rj| r.sign * rj / r.scale))
            .collect();
        DesignNlp {
            problem,
            evaluator: Evaluator::for_outputs(problem, &outputs),
            values: outputs.len(),
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
        self.evaluator.full_design(&self.unscale(u))
    }

    /// The objective as the problem states it (absolute value taken if asked) from the
    /// solver's objective.
    pub fn stated_objective(&self, solver_objective: f64) -> f64 {
        match self.problem.objective.sense {
            Sense::Maximize => -solver_objective,
            Sense::Minimize => solver_objective,
        }
    }

    /// The mirror image of a scaled design (every angle negated), if it lies within the
    /// bounds; `None` for models without that symmetry.
    pub fn mirror(&self, u: &[f64]) -> Option<Vec<f64>> {
        let params = self.problem.model().parameters();
        let free: Vec<_> = self.problem.free_variables().collect();
        if !free
            .iter()
            .any(|v| params[v.parameter].dimension == Dimension::Angle)
        {
            return None;
        }
        let x = self.unscale(u);
        let mirrored: Vec<f64> = x
            .iter()
            .zip(&free)
            .map(|(&xi, v)| {
                if params[v.parameter].dimension == Dimension::Angle {
                    -xi
                } else {
                    xi
                }
            })
            .collect();
        let m = self.scale(&mirrored);
        m.iter()
            .all(|v| (-1e-12..=1.0 + 1e-12).contains(v))
            .then_some(m)
    }

    fn constraint_values(&self, values: &[f64], c: &mut [f64]) {
        for (ci, r) in c.iter_mut().zip(&self.rows) {
            *ci = r.sign * (values[r.value] - r.limit) / r.scale;
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
        let mut values = [0.0; MAX_WANTED];
        let values = &mut values[..self.values];
        let mut f = 0.0;
        self.evaluator.evaluate(x, &mut f, values);
        self.constraint_values(values, c);
        merit(
            self.problem.objective.sense,
            self.problem.objective.absolute,
            f,
        )
    }

    fn evaluate_with_gradient(
        &self,
        u: &[f64],
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let n = u.len();
        let nc = self.values;
        let mut buf = [0.0; MAX_PARAMETERS];
        let x = self.unscale_into(u, &mut buf);
        let mut values = [0.0; MAX_WANTED];
        let values = &mut values[..nc];
        let (mut small, mut large) = ([0.0; 96], Vec::new());
        let value_grad = scratch(&mut small, &mut large, nc * n);
        let mut f = 0.0;
        self.evaluator
            .evaluate_with_gradient(x, &mut f, gradient, values, value_grad);
        let o = &self.problem.objective;
        // d merit / d value: -1 or +1, times sign(value) for an absolute value
        let mut df = if o.sense == Sense::Maximize {
            -1.0
        } else {
            1.0
        };
        if o.absolute && f < 0.0 {
            df = -df;
        }
        for (gj, rj) in gradient.iter_mut().zip(&self.range) {
            *gj *= df * rj;
        }
        self.constraint_values(values, c);
        let rows = jacobian
            .chunks_exact_mut(n)
            .zip(self.jacobian_factor.chunks_exact(n));
        for ((out, factor), r) in rows.zip(&self.rows) {
            let grad = &value_grad[r.value * n..(r.value + 1) * n];
            for ((o, g), f) in out.iter_mut().zip(grad).zip(factor) {
                *o = g * f;
            }
        }
        merit(o.sense, o.absolute, f)
    }
}
