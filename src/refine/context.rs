//! What every step of the refinement needs: measuring a design and scoring it, the
//! corrections, the surrogate within its trust region and its solve.

use std::sync::Arc;
use std::time::Instant;

use super::corrected::{Corrected, CorrectedScaling};
use super::{Check, Correction, HighFidelity, PENALTY};
use crate::optim::problem::{Problem as _, Status};
use crate::optim::sqp::{self, SqpSettings};
use crate::problem::epigraph::Epigraph;
use crate::problem::nlp::{merit, DesignNlp, FEASIBILITY_TOLERANCE};
use crate::problem::{limit_scale, Problem};
use crate::tolerance::{first_order, Outputs};

/// What every step needs.
pub(super) struct Context<'a> {
    pub(super) problem: &'a Problem,
    pub(super) high: &'a dyn HighFidelity,
    pub(super) outputs: Vec<usize>,
    pub(super) corrected: Vec<bool>,
    /// Each parameter's range (0 for a fixed one).
    pub(super) range: Vec<f64>,
    /// The objective's scale in the merit.
    pub(super) scale: f64,
    /// How far inside each measured limit the surrogate aims (relative).
    pub(super) margin: f64,
    /// A robust problem's standard deviations of margin (0: not robust).
    pub(super) robust_k: f64,
}

impl Context<'_> {
    pub(super) fn analytic(&self, model: &dyn crate::model::Model, x: &[f64]) -> Vec<f64> {
        let mut v = vec![0.0; self.outputs.len()];
        model.evaluate(x, &self.outputs, &mut v);
        v
    }

    /// Measures `x` and scores it.
    pub(super) fn check(&self, x: &[f64]) -> Result<Check, String> {
        let begin = Instant::now();
        if let Some(e) = self.problem.model().domain_error(x) {
            return Err(e);
        }
        let analytic = self.analytic(self.problem.model(), x);
        let asked: Vec<usize> = self
            .outputs
            .iter()
            .zip(&self.corrected)
            .filter(|(_, &c)| c)
            .map(|(&o, _)| o)
            .collect();
        let m = self.high.measure(x, &asked)?;
        let mut measured = vec![None; self.outputs.len()];
        let mut errors = vec![None; self.outputs.len()];
        let mut margins = vec![0.0; self.outputs.len()];
        let mut next = m.values.iter().zip(&m.errors).zip(&m.margins);
        for (k, &c) in self.corrected.iter().enumerate() {
            if c {
                let ((v, e), margin) = next.next().expect("one value per output asked");
                if !v.is_finite() {
                    return Err(format!(
                        "the measured {} is not a number",
                        self.problem.model().outputs()[self.outputs[k]].name
                    ));
                }
                measured[k] = Some(*v);
                errors[k] = *e;
                margins[k] = *margin;
            }
        }
        let spreads = self
            .spreads(x)
            .into_iter()
            .enumerate()
            .map(|(k, s)| measured[k].map_or(s, |m| s * m / analytic[k]))
            .collect();
        let c = Check {
            x: x.to_vec(),
            analytic,
            measured,
            errors,
            margins,
            spreads,
            objective: 0.0,
            violations: Vec::new(),
            feasible: false,
            merit: 0.0,
            seconds: begin.elapsed().as_secs_f64(),
            detail: m.detail,
        };
        Ok(self.rescore(c))
    }

    /// The objective, violations, feasibility and merit of `c` from its values: each
    /// constraint met by its output's margin, or violated.
    pub(super) fn rescore(&self, mut c: Check) -> Check {
        let values: Vec<f64> = (0..self.outputs.len()).map(|k| c.value(k)).collect();
        let (objective, violations, phi) = self.score(&values, &c.margins, &c.spreads);
        c.feasible = violations.iter().all(|&v| v <= FEASIBILITY_TOLERANCE);
        c.objective = objective;
        c.violations = violations;
        c.merit = phi;
        c
    }

    /// The merit of `c`'s values with the margins `margins`.
    pub(super) fn merit_with(&self, c: &Check, margins: &[f64]) -> f64 {
        let values: Vec<f64> = (0..self.outputs.len()).map(|k| c.value(k)).collect();
        self.score(&values, margins, &c.spreads).2
    }

    /// The model's first-order standard deviation of each watched output at `x` in a
    /// robust problem (empty otherwise).
    pub(super) fn spreads(&self, x: &[f64]) -> Vec<f64> {
        if self.robust_k == 0.0 {
            return Vec::new();
        }
        let outputs = Outputs::new(self.problem);
        debug_assert_eq!(outputs.wanted, self.outputs);
        first_order(&outputs, &self.problem.tolerances, x)
            .iter()
            .map(|f| f.std)
            .collect()
    }

    pub(super) fn slot(&self, output: usize) -> usize {
        self.outputs
            .iter()
            .position(|&o| o == output)
            .expect("every constraint's output is watched")
    }

    /// The stated objective, each constraint's relative violation and the merit of
    /// output values in the order of `outputs`, each limit tightened by its output's
    /// relative margin `margins` (0 for none) and, in a robust problem, by `k` of its
    /// standard deviations `spreads` (empty otherwise).
    pub(super) fn score(
        &self,
        values: &[f64],
        margins: &[f64],
        spreads: &[f64],
    ) -> (f64, Vec<f64>, f64) {
        let o = &self.problem.objective;
        let objective = if o.absolute {
            values[0].abs()
        } else {
            values[0]
        };
        let scale = limit_scale;
        let violations: Vec<f64> = self
            .problem
            .constraints
            .iter()
            .map(|c| {
                let k = self.slot(c.index);
                let (v, m) = (values[k], margins[k]);
                let keep = self.robust_k * spreads.get(k).copied().unwrap_or(0.0);
                let below = c
                    .lower
                    .map_or(0.0, |lo| (lo + m * scale(lo) + keep - v) / scale(lo));
                let above = c
                    .upper
                    .map_or(0.0, |hi| (v - hi + m * scale(hi) + keep) / scale(hi));
                below.max(above).max(0.0)
            })
            .collect();
        let phi = merit(o.sense, o.absolute, values[0]) / self.scale
            + PENALTY * violations.iter().sum::<f64>();
        (objective, violations, phi)
    }

    /// The corrections at the start's measurement, with no slope yet.
    pub(super) fn corrections(&self, c: &Check) -> Result<Vec<Option<Correction>>, String> {
        (0..self.outputs.len())
            .map(|k| {
                let Some(m) = c.measured[k] else {
                    return Ok(None);
                };
                let a = c.analytic[k];
                let rho = m / a;
                if !rho.is_finite() || rho <= 0.0 {
                    return Err(format!(
                        "{} is {a} by the model and {m} measured: no factor maps one onto the \
                         other",
                        self.problem.model().outputs()[self.outputs[k]].name
                    ));
                }
                Ok(Some(Correction {
                    rho,
                    slope: vec![0.0; c.x.len()],
                    centre: c.x.clone(),
                }))
            })
            .collect()
    }

    /// The surrogate's merit at `x`, with the margins `margins`.
    pub(super) fn surrogate_merit(
        &self,
        corrections: &[Option<Correction>],
        x: &[f64],
        margins: &[f64],
    ) -> f64 {
        let mut values = self.analytic(self.problem.model(), x);
        let mut spreads = self.spreads(x);
        for (k, (v, c)) in values.iter_mut().zip(corrections).enumerate() {
            if let Some(c) = c {
                let f = c.factor(x);
                *v *= f;
                if let Some(s) = spreads.get_mut(k) {
                    *s *= f;
                }
            }
        }
        self.score(&values, margins, &spreads).2
    }

    /// The corrected problem within the trust region of half-width `delta` around the
    /// centre `centre`, each measured limit tightened by the centre's margin.
    pub(super) fn surrogate(
        &self,
        corrections: &[Option<Correction>],
        centre: &Check,
        delta: f64,
    ) -> Surrogate {
        let x = &centre.x;
        let pairs: Vec<(usize, Correction)> = self
            .outputs
            .iter()
            .zip(corrections)
            .filter_map(|(&o, c)| c.clone().map(|c| (o, c)))
            .collect();
        let mut p = self.problem.clone();
        let corrected = Corrected::new(self.problem.mechanism.physics.clone(), &pairs);
        // a robust problem's surrogate keeps its spreads, scaled by the corrections
        let scaling = match (&self.problem.search.robust, &self.problem.mechanism.modulus) {
            (Some(_), Some(m)) => Some(Arc::new(CorrectedScaling::new(m.clone(), &corrected))),
            _ => None,
        };
        p.mechanism = self.problem.mechanism.with_physics(Arc::new(corrected));
        if let Some(s) = scaling {
            p.mechanism = p.mechanism.with_modulus_scaling(s);
        }
        // aim inside each measured limit by its margin and a little more, so that a
        // measurement a little off the surrogate's prediction still meets it
        for c in &mut p.constraints {
            let k = self.slot(c.index);
            if self.corrected[k] {
                let m = self.margin + centre.margins[k];
                c.lower = c.lower.map(|lo| lo + m * limit_scale(lo));
                c.upper = c.upper.map(|hi| hi - m * limit_scale(hi));
            }
        }
        for (v, (&xi, &r)) in p.variables.iter_mut().zip(x.iter().zip(&self.range)) {
            if !v.fixed {
                v.lower = v.lower.max(xi - delta * r);
                v.upper = v.upper.min(xi + delta * r);
            }
        }
        Surrogate { problem: p }
    }

    /// The step's largest change of a variable, scaled to the problem's bounds.
    pub(super) fn step(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(&self.range)
            .filter(|(_, &r)| r > 0.0)
            .map(|((x, y), r)| (x - y).abs() / r)
            .fold(0.0, f64::max)
    }

    /// The largest relative change of a measured output from `a` to `b`, each less the
    /// larger of the two measurements' error estimates (a change within them is not
    /// resolved by the measurement), never below 0.
    pub(super) fn change(&self, a: &Check, b: &Check) -> f64 {
        (0..self.outputs.len())
            .filter_map(|k| {
                let (x, y) = (a.measured[k]?, b.measured[k]?);
                let noise = a.errors[k].unwrap_or(0.0).max(b.errors[k].unwrap_or(0.0));
                Some((((y - x) / y).abs() - noise).max(0.0))
            })
            .fold(0.0, f64::max)
    }

    /// Whether `a` is a better measured design than `b`: feasible beats infeasible, then
    /// the better objective among feasible ones and the smaller violation otherwise.
    pub(super) fn better(&self, a: &Check, b: &Check) -> bool {
        let total = |c: &Check| c.violations.iter().sum::<f64>();
        match (a.feasible, b.feasible) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => {
                let o = &self.problem.objective;
                let m = |c: &Check| merit(o.sense, false, c.objective);
                m(a) < m(b)
            }
            (false, false) => total(a) < total(b),
        }
    }
}

/// The corrected problem within a trust region.
pub(super) struct Surrogate {
    pub(super) problem: Problem,
}

impl Surrogate {
    /// The SQP's solution from `x` (SI): the full design it ends at and how it ended.
    pub(super) fn solve(&self, x: &[f64], settings: &SqpSettings) -> (Vec<f64>, Status) {
        let nlp = DesignNlp::new(&self.problem);
        let free: Vec<f64> = self
            .problem
            .free_variables()
            .map(|v| x[v.parameter])
            .collect();
        let u0: Vec<f64> = nlp.scale(&free).iter().map(|u| u.clamp(0.0, 1.0)).collect();
        let n = nlp.dimension();
        let solution = match Epigraph::new(&nlp) {
            Some(ep) => {
                let mut s = sqp::solve(&ep, &ep.start(&u0), settings);
                s.x.truncate(n);
                s
            }
            None => sqp::solve(&nlp, &u0, settings),
        };
        (nlp.full_design(&solution.x), solution.status)
    }
}
