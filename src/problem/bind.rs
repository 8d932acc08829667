//! The binding of a problem's objective and constraints to its model's outputs.
//!
//! An [`Evaluator`] asks the model for exactly the outputs the objective and constraints
//! name, once each, and maps the free variables into the model's full parameter vector.

use super::{Problem, Sense};
use crate::model::{Model, MAX_PARAMETERS, MAX_WANTED};

/// Evaluates a problem's objective and constraint outputs at designs given by the free
/// variables (SI, model order).
pub struct Evaluator<'p> {
    model: &'p dyn Model,
    /// The full parameter vector with the fixed values in place.
    base: Vec<f64>,
    /// Model parameter index of each free variable.
    free: Vec<usize>,
    /// Output indices the model is asked for: no duplicates, objective first.
    wanted: Vec<usize>,
    /// Position in `wanted` of each constraint's output.
    constraint_slot: Vec<usize>,
    /// Every parameter is free, in model order: designs pass through unchanged.
    all_free: bool,
}

impl<'p> Evaluator<'p> {
    /// The objective and the outputs the problem's constraints name.
    pub fn new(problem: &'p Problem) -> Self {
        let outputs: Vec<usize> = problem.constraints.iter().map(|c| c.index).collect();
        Self::for_outputs(problem, &outputs)
    }

    /// The objective and the model outputs `outputs`, which then play the part of the
    /// constraint values in [`Evaluator::evaluate`].
    pub fn for_outputs(problem: &'p Problem, outputs: &[usize]) -> Self {
        let mut wanted = vec![problem.objective.index];
        let mut constraint_slot = Vec::new();
        for &index in outputs {
            let slot = wanted.iter().position(|&w| w == index).unwrap_or_else(|| {
                wanted.push(index);
                wanted.len() - 1
            });
            constraint_slot.push(slot);
        }
        assert!(
            wanted.len() <= MAX_WANTED,
            "a problem names at most {MAX_WANTED} outputs"
        );
        assert!(problem.variables.len() <= MAX_PARAMETERS);
        let free: Vec<usize> = problem.free_variables().map(|v| v.parameter).collect();
        Evaluator {
            all_free: free.iter().copied().eq(0..problem.variables.len()),
            model: problem.model(),
            base: problem.variables.iter().map(|v| v.lower).collect(),
            free,
            wanted,
            constraint_slot,
        }
    }

    /// Number of free variables.
    pub fn dimension(&self) -> usize {
        self.free.len()
    }

    /// The output indices the model computes for this problem.
    pub fn wanted(&self) -> &[usize] {
        &self.wanted
    }

    /// The full parameter vector (SI) of a design given by its free variables.
    pub fn full_design(&self, free: &[f64]) -> Vec<f64> {
        let mut x = self.base.clone();
        for (&p, &v) in self.free.iter().zip(free) {
            x[p] = v;
        }
        x
    }

    /// The objective's output and each constraint's output, SI.
    pub fn evaluate(&self, free: &[f64], objective: &mut f64, constraints: &mut [f64]) {
        let mut x = [0.0; MAX_PARAMETERS];
        let x = self.fill(free, &mut x);
        let (mut small, mut large) = ([0.0; 10], Vec::new());
        let out = scratch(&mut small, &mut large, self.wanted.len());
        self.model.evaluate(x, &self.wanted, out);
        *objective = out[0];
        for (c, &slot) in constraints.iter_mut().zip(&self.constraint_slot) {
            *c = out[slot];
        }
    }

    /// As [`Evaluator::evaluate`], with the gradients with respect to the free variables:
    /// `objective_grad[j]`, `constraint_grad[i * n + j]` with `n = self.dimension()`.
    pub fn evaluate_with_gradient(
        &self,
        free: &[f64],
        objective: &mut f64,
        objective_grad: &mut [f64],
        constraints: &mut [f64],
        constraint_grad: &mut [f64],
    ) {
        let mut x = [0.0; MAX_PARAMETERS];
        let x = self.fill(free, &mut x);
        let np = x.len();
        // sized for the wei2017 problems (9 outputs of 8 parameters): a heap buffer per
        // evaluation showed in the solver's profile
        let (mut small_out, mut large_out) = ([0.0; 16], Vec::new());
        let out = scratch(&mut small_out, &mut large_out, self.wanted.len());
        let (mut small_jac, mut large_jac) = ([0.0; 128], Vec::new());
        let jac = scratch(&mut small_jac, &mut large_jac, self.wanted.len() * np);
        self.model.evaluate_with_gradient(x, &self.wanted, out, jac);
        let n = self.free.len();
        *objective = out[0];
        for (i, &slot) in self.constraint_slot.iter().enumerate() {
            constraints[i] = out[slot];
        }
        if self.all_free {
            // the free variables are the parameters: whole rows copy over
            objective_grad.copy_from_slice(&jac[..np]);
            for (i, &slot) in self.constraint_slot.iter().enumerate() {
                constraint_grad[i * n..(i + 1) * n]
                    .copy_from_slice(&jac[slot * np..(slot + 1) * np]);
            }
            return;
        }
        for (j, &p) in self.free.iter().enumerate() {
            objective_grad[j] = jac[p];
        }
        for (i, &slot) in self.constraint_slot.iter().enumerate() {
            for (j, &p) in self.free.iter().enumerate() {
                constraint_grad[i * n + j] = jac[slot * np + p];
            }
        }
    }

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
}

/// A work buffer of `len` numbers: on the stack when `small` holds them, which spares
/// the zeroing of a large array on every evaluation.
pub(crate) fn scratch<'a, const N: usize>(
    small: &'a mut [f64; N],
    large: &'a mut Vec<f64>,
    len: usize,
) -> &'a mut [f64] {
    if len <= N {
        &mut small[..len]
    } else {
        large.resize(len, 0.0);
        large
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
