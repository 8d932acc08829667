//! The refinement of an analytic optimum against a higher fidelity (the finite elements of
//! the part): find the design whose *measured* outputs meet the constraints and optimize
//! the *measured* objective, at the cost of a handful of measurements.
//!
//! The method is trust-region model management with output space mapping:
//!
//! 1. measure the outputs the objective and constraints use at the centre `x_c` (the
//!    analytic optimum first);
//! 2. correct each measured output of the analytic model by its ratio to the measurement
//!    there, with a first-order term ([`corrected`]): the surrogate agrees with the
//!    measurement at `x_c` exactly;
//! 3. optimize the surrogate with the SQP within a box of half-width `delta` (a fraction of
//!    each variable's range) around `x_c`;
//! 4. measure the surrogate's optimum `x_n`, and compare the decrease of the merit
//!    `phi = f / |f_0| + mu sum(v_i)` (objective scaled, `v_i` the constraints' relative
//!    violations, `mu = 100`) that the measurement shows with the one the surrogate
//!    predicted: accept `x_n` as the new centre when it shows at least a hundredth of it,
//!    and widen or narrow the box by the ratio (the classic rule: Conn, Gould and Toint,
//!    *Trust-Region Methods*, SIAM 2000, Alg. 6.1.1; for corrected surrogates Alexandrov,
//!    Dennis, Lewis and Torczon, "A trust-region framework for managing the use of
//!    approximation models in optimization", Structural Optimization 15, 1998);
//! 5. update each correction's slope by Broyden's secant rule from the ratio measured at
//!    `x_n`, accepted or not (Broyden, Math. Comp. 19, 1965; so aggressive space mapping
//!    does: Bandler et al., IEEE Trans. Microwave Theory Tech. 43(12), 1995);
//! 6. stop when an accepted step changes every measured output by less than the tolerance
//!    (relative), the measurement's own error estimates are below it too, and the design
//!    meets every constraint as measured (each to the error estimate of its output); or
//!    when the budget of measurements is spent.
//!
//! Every design reported is a measured one, never the surrogate's word: the converged
//! centre, or else the best measured design that meets every constraint, or else the least
//! violating measured design. Outputs the high fidelity does not measure (the bridge's
//! spans, which are geometry) stay analytic.

pub mod corrected;
pub mod fe;
pub mod study;

use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;

use crate::optim::problem::{Problem as _, Status};
use crate::optim::sqp::{self, SqpSettings};
use crate::problem::epigraph::Epigraph;
use crate::problem::nlp::{merit, DesignNlp, FEASIBILITY_TOLERANCE};
use crate::problem::refine::RefineSettings;
use crate::problem::Problem;
use corrected::Corrected;

/// The weight of the constraints' violations in the merit against the scaled objective.
const PENALTY: f64 = 100.0;
/// The surrogate aims this fraction of the tolerance inside each measured limit.
const MARGIN: f64 = 0.25;
/// A step is accepted when the measured merit falls by at least this fraction of the
/// predicted fall.
const ACCEPT: f64 = 0.01;

/// A source of measured outputs: the finite elements of the part ([`fe::FeFidelity`]), or
/// in tests any function with a known answer.
pub trait HighFidelity: Sync {
    /// What it is, for the reports.
    fn describe(&self) -> String;
    /// Whether it measures the model's output `output`.
    fn measures(&self, output: usize) -> bool;
    /// Measures `outputs` (model output indices it measures) at the design `x` (SI).
    fn measure(&self, x: &[f64], outputs: &[usize]) -> Result<Measurement, String>;
}

/// What one measurement gives.
#[derive(Debug, Clone, Serialize)]
pub struct Measurement {
    /// Each output's value, in the order asked.
    pub values: Vec<f64>,
    /// Each value's estimated relative error, where the high fidelity estimates it.
    pub errors: Vec<Option<f64>>,
    /// Anything else worth reporting (the FE's outputs of both idealizations).
    pub detail: serde_json::Value,
}

/// A multiplicative correction `rho + slope . (x - centre)` of one output (SI `x`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Correction {
    pub rho: f64,
    pub slope: Vec<f64>,
    pub centre: Vec<f64>,
}

impl Correction {
    pub fn factor(&self, x: &[f64]) -> f64 {
        self.rho
            + self
                .slope
                .iter()
                .zip(x.iter().zip(&self.centre))
                .map(|(h, (xi, ci))| h * (xi - ci))
                .sum::<f64>()
    }

    /// Broyden's update from the ratio `ratio` measured at `x`: the slope changes least (in
    /// the design space scaled by `range`, the variables' ranges, 0 for fixed ones) such
    /// that the factor at `x` is `ratio`.
    pub fn update(&mut self, x: &[f64], ratio: f64, range: &[f64]) {
        let s: Vec<f64> = x
            .iter()
            .zip(&self.centre)
            .zip(range)
            .map(|((xi, ci), r)| if *r > 0.0 { (xi - ci) / r } else { 0.0 })
            .collect();
        let ss: f64 = s.iter().map(|v| v * v).sum();
        if ss <= 0.0 {
            return;
        }
        let miss = ratio - self.factor(x);
        for ((h, sj), r) in self.slope.iter_mut().zip(&s).zip(range) {
            if *r > 0.0 {
                *h += miss * sj / ss / r;
            }
        }
    }
}

/// One design measured, with its analytic values beside.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    /// The design, every parameter (SI).
    pub x: Vec<f64>,
    /// The outputs the objective and constraints use ([`Refinement::outputs`]): analytic.
    pub analytic: Vec<f64>,
    /// ... as measured, where measured (else the analytic value stands).
    pub measured: Vec<Option<f64>>,
    /// ... each measurement's estimated relative error.
    pub errors: Vec<Option<f64>>,
    /// The objective as the problem states it, measured where measured.
    pub objective: f64,
    /// Each constraint's relative violation (0 when met), measured where measured.
    pub violations: Vec<f64>,
    pub feasible: bool,
    pub merit: f64,
    pub seconds: f64,
    pub detail: serde_json::Value,
}

impl Check {
    /// The value that counts for output slot `k`: measured, else analytic.
    pub fn value(&self, k: usize) -> f64 {
        self.measured[k].unwrap_or(self.analytic[k])
    }
}

/// One step of the refinement.
#[derive(Debug, Clone, Serialize)]
pub struct Iteration {
    /// The trust region's half-width the step was taken in (scaled to the bounds).
    pub trust_radius: f64,
    /// The step's length (largest scaled change of a variable).
    pub step: f64,
    /// The surrogate's solve: how it ended.
    pub surrogate: Status,
    /// The fall of the merit the surrogate predicted and the one measured.
    pub predicted: f64,
    pub actual: Option<f64>,
    pub accepted: bool,
    /// The measurement, when one was made; else why not.
    pub check: Option<Check>,
    pub note: Option<String>,
}

/// How a refinement ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "status", content = "reason")]
pub enum RefineStatus {
    /// The measured outputs settled within the tolerance at a design meeting every
    /// constraint as measured.
    Converged,
    /// The budget of measurements was spent first.
    Budget,
    /// The trust region shrank to nothing without a better measured design.
    Stalled,
    /// No measurement could be made at the start.
    Failed(String),
}

/// A refinement's record.
#[derive(Debug, Clone, Serialize)]
pub struct Refinement {
    pub fidelity: String,
    /// The model outputs the objective and constraints use, the objective's first.
    pub outputs: Vec<usize>,
    /// Which of them were corrected by measurement.
    pub corrected: Vec<bool>,
    /// The analytic optimum, measured.
    pub start: Option<Check>,
    pub iterations: Vec<Iteration>,
    /// The design reported: the converged centre, else the best feasible measured
    /// design, else the least violating one.
    pub result: Option<Check>,
    pub status: RefineStatus,
    /// Measurements made.
    pub measurements: usize,
    pub seconds: f64,
}

impl Refinement {
    pub fn feasible(&self) -> bool {
        self.result.as_ref().is_some_and(|c| c.feasible)
    }
}

/// The problem's outputs, the objective's first, each once.
fn watched(problem: &Problem) -> Vec<usize> {
    let mut out = vec![problem.objective.index];
    for c in &problem.constraints {
        if !out.contains(&c.index) {
            out.push(c.index);
        }
    }
    out
}

/// Refines `x0` (SI, every parameter) of `problem` against `high`.
pub fn refine(
    problem: &Problem,
    x0: &[f64],
    high: &dyn HighFidelity,
    settings: &RefineSettings,
) -> Refinement {
    let begin = Instant::now();
    let outputs = watched(problem);
    let corrected: Vec<bool> = outputs.iter().map(|&o| high.measures(o)).collect();
    let mut r = Refinement {
        fidelity: high.describe(),
        outputs: outputs.clone(),
        corrected: corrected.clone(),
        start: None,
        iterations: Vec::new(),
        result: None,
        status: RefineStatus::Budget,
        measurements: 0,
        seconds: 0.0,
    };
    // the merit's objective is scaled by the start's, as the model gives it
    let mut start_objective = [0.0];
    problem
        .model()
        .evaluate(x0, &outputs[..1], &mut start_objective);
    let ctx = Context {
        problem,
        high,
        outputs,
        corrected,
        range: problem
            .variables
            .iter()
            .map(|v| if v.fixed { 0.0 } else { v.upper - v.lower })
            .collect(),
        scale: start_objective[0].abs().max(1e-300),
        margin: MARGIN * settings.tolerance,
    };
    let mut centre = match ctx.check(x0) {
        Ok(c) => c,
        Err(e) => {
            r.status = RefineStatus::Failed(e);
            r.seconds = begin.elapsed().as_secs_f64();
            return r;
        }
    };
    r.measurements = 1;
    r.start = Some(centre.clone());
    let mut corrections = match ctx.corrections(&centre) {
        Ok(c) => c,
        Err(e) => {
            r.status = RefineStatus::Failed(e);
            r.result = Some(centre);
            r.seconds = begin.elapsed().as_secs_f64();
            return r;
        }
    };
    let mut best = centre.clone();
    let mut delta = settings.trust_radius;
    let sqp_settings = SqpSettings {
        tolerance: problem.search.tolerance,
        max_iterations: problem.search.max_iterations,
        ..SqpSettings::default()
    };
    let mut converged = false;
    // a failed surrogate solve costs no measurement; bound them all the same
    let mut attempts = 0;
    while r.measurements < settings.max_fe && attempts < 4 * settings.max_fe {
        attempts += 1;
        let surrogate = ctx.surrogate(&corrections, &centre.x, delta);
        let (x_new, status) = surrogate.solve(&centre.x, &sqp_settings);
        let step = ctx.step(&centre.x, &x_new);
        let phi_c = ctx.surrogate_merit(&corrections, &centre.x);
        let predicted = phi_c - ctx.surrogate_merit(&corrections, &x_new);
        let mut it = Iteration {
            trust_radius: delta,
            step,
            surrogate: status.clone(),
            predicted,
            actual: None,
            accepted: false,
            check: None,
            note: None,
        };
        if !(predicted.is_finite()) || matches!(status, Status::Failed(_)) {
            it.note = Some("the surrogate's solve failed; the trust region narrowed".into());
            r.iterations.push(it);
            delta *= 0.25;
            if delta < 1e-9 {
                r.status = RefineStatus::Stalled;
                break;
            }
            continue;
        }
        if step <= 1e-9 || predicted <= 1e-12 * phi_c.abs().max(1.0) {
            // the surrogate, exact at the centre to first order as far as the secants
            // know, sees nothing better within the region
            it.note = Some("the surrogate's optimum is the centre".into());
            r.iterations.push(it);
            converged = centre.feasible;
            if !converged {
                r.status = RefineStatus::Stalled;
            }
            break;
        }
        let check = match ctx.check(&x_new) {
            Ok(c) => c,
            Err(e) => {
                r.measurements += 1;
                it.note = Some(format!("not measured: {e}; the trust region narrowed"));
                r.iterations.push(it);
                delta = 0.25 * step;
                continue;
            }
        };
        r.measurements += 1;
        let actual = centre.merit - check.merit;
        // the secants learn from every measurement, accepted or not
        for (k, c) in corrections.iter_mut().enumerate() {
            if let (Some(c), Some(m)) = (c, check.measured[k]) {
                c.update(&x_new, m / check.analytic[k], &ctx.range);
            }
        }
        let ratio = actual / predicted;
        it.actual = Some(actual);
        it.accepted = ratio >= ACCEPT;
        if ctx.better(&check, &best) {
            best = check.clone();
        }
        if it.accepted {
            let change = ctx.change(&centre, &check);
            let settled = change <= settings.tolerance
                && check
                    .errors
                    .iter()
                    .all(|e| e.is_none_or(|e| e <= settings.tolerance));
            centre = check.clone();
            for (k, c) in corrections.iter_mut().enumerate() {
                if let (Some(c), Some(m)) = (c, centre.measured[k]) {
                    c.rho = m / centre.analytic[k];
                    c.centre = centre.x.clone();
                }
            }
            if ratio > 0.75 && step >= 0.9 * delta {
                delta = (2.0 * delta).min(1.0);
            } else if ratio < 0.25 {
                delta = 0.5 * step;
            }
            it.check = Some(check);
            r.iterations.push(it);
            if settled && centre.feasible {
                converged = true;
                break;
            }
        } else {
            delta = 0.25 * step;
            it.check = Some(check);
            r.iterations.push(it);
        }
        if delta < 1e-9 {
            r.status = RefineStatus::Stalled;
            break;
        }
    }
    if converged {
        r.status = RefineStatus::Converged;
        r.result = Some(centre);
    } else {
        r.result = Some(best);
    }
    r.seconds = begin.elapsed().as_secs_f64();
    r
}

/// What every step needs.
struct Context<'a> {
    problem: &'a Problem,
    high: &'a dyn HighFidelity,
    outputs: Vec<usize>,
    corrected: Vec<bool>,
    /// Each parameter's range (0 for a fixed one).
    range: Vec<f64>,
    /// The objective's scale in the merit.
    scale: f64,
    /// How far inside each measured limit the surrogate aims (relative).
    margin: f64,
}

impl Context<'_> {
    fn analytic(&self, model: &dyn crate::model::Model, x: &[f64]) -> Vec<f64> {
        let mut v = vec![0.0; self.outputs.len()];
        model.evaluate(x, &self.outputs, &mut v);
        v
    }

    /// Measures `x` and scores it.
    fn check(&self, x: &[f64]) -> Result<Check, String> {
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
        let mut next = m.values.iter().zip(&m.errors);
        for (k, &c) in self.corrected.iter().enumerate() {
            if c {
                let (v, e) = next.next().expect("one value per output asked");
                if !v.is_finite() {
                    return Err(format!(
                        "the measured {} is not a number",
                        self.problem.model().outputs()[self.outputs[k]].name
                    ));
                }
                measured[k] = Some(*v);
                errors[k] = *e;
            }
        }
        let c = Check {
            x: x.to_vec(),
            analytic,
            measured,
            errors,
            objective: 0.0,
            violations: Vec::new(),
            feasible: false,
            merit: 0.0,
            seconds: begin.elapsed().as_secs_f64(),
            detail: m.detail,
        };
        Ok(self.rescore(c))
    }

    /// The objective, violations, feasibility and merit of `c` from its values.
    fn rescore(&self, mut c: Check) -> Check {
        let values: Vec<f64> = (0..self.outputs.len()).map(|k| c.value(k)).collect();
        let tolerance: Vec<f64> = c
            .errors
            .iter()
            .map(|e| e.unwrap_or(0.0).max(FEASIBILITY_TOLERANCE))
            .collect();
        let (objective, violations, phi) = self.score(&values);
        c.feasible = self
            .problem
            .constraints
            .iter()
            .zip(&violations)
            .all(|(con, v)| {
                let k = self.slot(con.index);
                *v <= tolerance[k]
            });
        c.objective = objective;
        c.violations = violations;
        c.merit = phi;
        c
    }

    fn slot(&self, output: usize) -> usize {
        self.outputs
            .iter()
            .position(|&o| o == output)
            .expect("every constraint's output is watched")
    }

    /// The stated objective, each constraint's relative violation and the merit of
    /// output values in the order of `outputs`.
    fn score(&self, values: &[f64]) -> (f64, Vec<f64>, f64) {
        let o = &self.problem.objective;
        let objective = if o.absolute {
            values[0].abs()
        } else {
            values[0]
        };
        let scale = |l: f64| if l == 0.0 { 1.0 } else { l.abs() };
        let violations: Vec<f64> = self
            .problem
            .constraints
            .iter()
            .map(|c| {
                let v = values[self.slot(c.index)];
                let below = c.lower.map_or(0.0, |lo| (lo - v) / scale(lo));
                let above = c.upper.map_or(0.0, |hi| (v - hi) / scale(hi));
                below.max(above).max(0.0)
            })
            .collect();
        let phi = merit(o.sense, o.absolute, values[0]) / self.scale
            + PENALTY * violations.iter().sum::<f64>();
        (objective, violations, phi)
    }

    /// The corrections at the start's measurement, with no slope yet.
    fn corrections(&self, c: &Check) -> Result<Vec<Option<Correction>>, String> {
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

    /// The surrogate's merit at `x`.
    fn surrogate_merit(&self, corrections: &[Option<Correction>], x: &[f64]) -> f64 {
        let mut values = self.analytic(self.problem.model(), x);
        for (v, c) in values.iter_mut().zip(corrections) {
            if let Some(c) = c {
                *v *= c.factor(x);
            }
        }
        self.score(&values).2
    }

    /// The corrected problem within the trust region of half-width `delta` around `x`.
    fn surrogate(&self, corrections: &[Option<Correction>], x: &[f64], delta: f64) -> Surrogate {
        let pairs: Vec<(usize, Correction)> = self
            .outputs
            .iter()
            .zip(corrections)
            .filter_map(|(&o, c)| c.clone().map(|c| (o, c)))
            .collect();
        let mut p = self.problem.clone();
        p.model = Arc::new(Corrected::new(self.problem.model.clone(), &pairs));
        // aim inside each measured limit by the margin, so that a measurement a little off
        // the surrogate's prediction still meets it
        for c in &mut p.constraints {
            if self.corrected[self.slot(c.index)] {
                let m = self.margin;
                c.lower = c
                    .lower
                    .map(|lo| lo + m * if lo == 0.0 { 1.0 } else { lo.abs() });
                c.upper = c
                    .upper
                    .map(|hi| hi - m * if hi == 0.0 { 1.0 } else { hi.abs() });
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
    fn step(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(&self.range)
            .filter(|(_, &r)| r > 0.0)
            .map(|((x, y), r)| (x - y).abs() / r)
            .fold(0.0, f64::max)
    }

    /// The largest relative change of a measured output from `a` to `b`.
    fn change(&self, a: &Check, b: &Check) -> f64 {
        (0..self.outputs.len())
            .filter_map(|k| Some((a.measured[k]?, b.measured[k]?)))
            .map(|(x, y)| ((y - x) / y).abs())
            .fold(0.0, f64::max)
    }

    /// Whether `a` is a better measured design than `b`: feasible beats infeasible, then
    /// the better objective among feasible ones and the smaller violation otherwise.
    fn better(&self, a: &Check, b: &Check) -> bool {
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
struct Surrogate {
    problem: Problem,
}

impl Surrogate {
    /// The SQP's solution from `x` (SI): the full design it ends at and how it ended.
    fn solve(&self, x: &[f64], settings: &SqpSettings) -> (Vec<f64>, Status) {
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
