//! The rows as the solvers read them: the constraint rows and their Jacobian from the model's
//! outputs through the scalings, the gradient evaluation with or without the part's rules,
//! and the per-thread scratch one evaluation writes into.

use super::{merit, DesignNlp, Sense};
use crate::model::MAX_PARAMETERS;

impl DesignNlp<'_> {
    /// Whether a row of the part's rules (the last [`DesignNlp`]'s rows) is among the
    /// `needed` ([`Problem::evaluate_with_gradient_of`]; `needed` may go on past them).
    pub(crate) fn rules_needed(&self, needed: &[bool]) -> bool {
        let first_rule = self.rows.len() - self.rules;
        needed[first_rule..self.rows.len()].iter().any(|&k| k)
    }

    /// The rows before the part's rules': those worth writing where the rules are not
    /// worked out (their rows are not read then).
    pub(crate) fn rows_without_rules(&self) -> usize {
        self.rows.len() - self.rules
    }

    /// [`Problem::evaluate_with_gradient`], the part's rules worked out only where `rules`
    /// ([`DesignNlp::outputs_with_gradient_of`]).
    pub(super) fn evaluate_gradient(
        &self,
        u: &[f64],
        rules: bool,
        c: &mut [f64],
        gradient: &mut [f64],
        jacobian: &mut [f64],
    ) -> f64 {
        let n = u.len();
        let np = self.base.len();
        let mut buf = [0.0; MAX_PARAMETERS];
        let x = self.unscale_into(u, &mut buf);
        with_scratch(self.values(), self.values() * np, |out, model_jac| {
            self.outputs_with_gradient_of(x, rules, out, model_jac);
            let f = out[0];
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
            for ((gj, rj), &p) in gradient.iter_mut().zip(&self.range).zip(&self.free) {
                *gj = model_jac[p] * (df * rj);
            }
            // without the rules their rows are not read: zeros, not the chain rule's
            // products of zeros
            let m = if rules {
                self.rows.len()
            } else {
                self.rows_without_rules()
            };
            let (c, unread) = c.split_at_mut(m);
            let (jacobian, unread_rows) = jacobian.split_at_mut(m * n);
            self.rows_from(out, model_jac, c, jacobian, n);
            unread.fill(0.0);
            unread_rows.fill(0.0);
            merit(o.sense, o.absolute, f)
        })
    }
}

/// Runs `f` on zeroed scratch for one evaluation: `values` outputs and a Jacobian of
/// `jacobian` entries. Kept per thread and grown to the largest asked for, as a study
/// evaluates its problem tens of thousands of times: a stack buffer sized for the most
/// rows a problem may have (the part's rules among them) cost more to zero than a small
/// problem's evaluation, and a heap buffer per evaluation showed in the solver's profile.
pub(crate) fn with_scratch<R>(
    values: usize,
    jacobian: usize,
    f: impl FnOnce(&mut [f64], &mut [f64]) -> R,
) -> R {
    thread_local! {
        static SCRATCH: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    let len = values + jacobian;
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut v) => {
            if v.len() < len {
                v.resize(len, 0.0);
            }
            let used = &mut v[..len];
            used.fill(0.0);
            let (out, jac) = used.split_at_mut(values);
            f(out, jac)
        }
        // an evaluation within an evaluation: scratch of its own
        Err(_) => {
            let mut v = vec![0.0; len];
            let (out, jac) = v.split_at_mut(values);
            f(out, jac)
        }
    })
}

impl DesignNlp<'_> {
    /// The constraint rows and their Jacobian (rows of `stride` entries, the first
    /// `dimension()` of each written) from the wanted outputs and the model's Jacobian.
    pub(crate) fn rows_from(
        &self,
        out: &[f64],
        model_jac: &[f64],
        c: &mut [f64],
        jacobian: &mut [f64],
        stride: usize,
    ) {
        let (n, np) = (self.range.len(), self.base.len());
        self.constraint_values(out, c);
        if self.all_free && self.spreads.is_none() {
            // the same products with the row's length known to the compiler: a row's loop
            // over chunks of a length known only at run time cost 70 instructions a row
            // (callgrind), a tenth of them the products
            match n {
                8 => return self.scaled_rows::<8>(model_jac, np, jacobian, stride),
                9 => return self.scaled_rows::<9>(model_jac, np, jacobian, stride),
                10 => return self.scaled_rows::<10>(model_jac, np, jacobian, stride),
                _ => {}
            }
        }
        let rows = jacobian
            .chunks_exact_mut(stride)
            .zip(self.jacobian_factor.chunks_exact(n));
        for ((row, factor), r) in rows.zip(&self.rows) {
            let grad = &model_jac[r.value * np..(r.value + 1) * np];
            if self.all_free {
                // the variables are the parameters, in order: the same products, read
                // along the row (the gather through `free` cost as much as the rest of
                // the rows' work, and the part's rules doubled the rows)
                for ((o, &gp), f) in row[..n].iter_mut().zip(&grad[..n]).zip(factor) {
                    *o = gp * f;
                }
            } else {
                for ((o, &p), f) in row.iter_mut().zip(&self.free).zip(factor) {
                    *o = grad[p] * f;
                }
            }
            if let (Some(slot), Some(s)) = (r.spread, &self.spreads) {
                // the row is sign * (value - limit) - k sigma over its scale; the factor
                // carries the sign
                let spread = &model_jac[slot * np..(slot + 1) * np];
                for ((o, &p), f) in row.iter_mut().zip(&self.free).zip(factor) {
                    *o -= r.sign * s.k * spread[p] * f;
                }
            }
        }
    }

    /// [`DesignNlp::rows_from`]'s rows where every parameter is free, there are `N` of
    /// them and no spreads: each row the model's gradient of its value (rows of `np`)
    /// times the row's factor.
    fn scaled_rows<const N: usize>(
        &self,
        model_jac: &[f64],
        np: usize,
        jacobian: &mut [f64],
        stride: usize,
    ) {
        let rows = jacobian
            .chunks_exact_mut(stride)
            .zip(self.jacobian_factor.chunks_exact(N));
        for ((row, factor), r) in rows.zip(&self.rows) {
            let row: &mut [f64; N] = (&mut row[..N]).try_into().expect("a row of N");
            let grad: &[f64; N] = model_jac[r.value * np..][..N]
                .try_into()
                .expect("a gradient of N");
            let factor: &[f64; N] = factor.try_into().expect("a factor of N");
            for ((o, g), f) in row.iter_mut().zip(grad).zip(factor) {
                *o = g * f;
            }
        }
    }

    /// The slot among the wanted outputs of each of `outputs`.
    pub(crate) fn slots_of(&self, outputs: &[usize]) -> Option<Vec<usize>> {
        outputs
            .iter()
            .map(|o| self.wanted.iter().position(|w| w == o))
            .collect()
    }

    /// Model parameter index of each free variable, and the free variables' ranges.
    pub(crate) fn free_and_range(&self) -> (&[usize], &[f64]) {
        (&self.free, &self.range)
    }

    /// The problem constraint of each row.
    pub(crate) fn row_constraints(&self) -> impl Iterator<Item = usize> + '_ {
        self.rows.iter().map(|r| r.constraint)
    }

    /// Number of model parameters.
    pub(crate) fn parameter_count(&self) -> usize {
        self.base.len()
    }
}
