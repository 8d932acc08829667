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
//! 6. stop when the surrogate's optimum, inside the trust region, promises less than a
//!    quarter of the tolerance (of the objective) beyond a centre that meets every constraint by its
//!    margin, or when an accepted step changes
//!    every measured output by less than the tolerance (relative) beyond the
//!    measurements' own error estimates, and the design meets every constraint as measured by its margin (the output's error estimate plus
//!    the difference from the fidelity used to the next one up, [`Measurement::margins`]:
//!    a measured value within its error of a limit may lie on either side of it); or when
//!    the budget of measurements is spent.
//!
//! Every design reported is a measured one, never the surrogate's word: the converged
//! centre, or else the best measured design that meets every constraint, or else the least
//! violating measured design. Outputs the high fidelity does not measure (the bridge's
//! spans, which are geometry) stay analytic.

mod context;
pub mod corrected;
pub mod fe;
pub mod spread;
pub mod study;

use std::time::Instant;

use serde::Serialize;

use crate::optim::problem::Status;
use crate::optim::sqp::SqpSettings;
use crate::problem::refine::RefineSettings;
use crate::problem::Problem;
use context::Context;

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
    /// Whether it measures the model's output `output` at designs like `x` (SI): the FE
    /// check's outputs are stated by the part, which only a design gives.
    fn measures(&self, x: &[f64], output: usize) -> bool;
    /// Measures `outputs` (model output indices it measures) at the design `x` (SI).
    fn measure(&self, x: &[f64], outputs: &[usize]) -> Result<Measurement, String>;

    /// As [`HighFidelity::measure`], the material's moduli `modulus` times the nominal
    /// ones (a tolerance on `E`); a high fidelity that cannot vary them says so.
    fn measure_at_modulus(
        &self,
        x: &[f64],
        modulus: f64,
        outputs: &[usize],
    ) -> Result<Measurement, String> {
        if modulus == 1.0 {
            self.measure(x, outputs)
        } else {
            Err(format!(
                "{} cannot vary the material's modulus",
                self.describe()
            ))
        }
    }
}

/// What one measurement gives.
#[derive(Debug, Clone, Serialize)]
pub struct Measurement {
    /// Each output's value, in the order asked.
    pub values: Vec<f64>,
    /// Each value's estimated relative error, where the high fidelity estimates it.
    pub errors: Vec<Option<f64>>,
    /// The relative margin by which each value must meet its limits for the part to meet
    /// them: its estimated error plus the difference from the fidelity used to the next one
    /// up (none above the highest).
    pub margins: Vec<f64>,
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
    /// ... the relative margin it must meet its limits by ([`Measurement::margins`]; 0
    /// for an output not measured).
    pub margins: Vec<f64>,
    /// ... in a robust problem, each output's first-order standard deviation under the
    /// tolerances, the model's scaled by the measurement's ratio to it, of which each limit
    /// keeps `k` inside (empty otherwise).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spreads: Vec<f64>,
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
    let corrected: Vec<bool> = outputs.iter().map(|&o| high.measures(x0, o)).collect();
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
        robust_k: problem
            .search
            .robust
            .filter(|_| problem.mechanism.modulus.is_some())
            .map_or(0.0, |r| r.k_sigma),
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
        let surrogate = ctx.surrogate(&corrections, &centre, delta);
        let (x_new, status) = surrogate.solve(&centre.x, &sqp_settings);
        let step = ctx.step(&centre.x, &x_new);
        let phi_c = ctx.surrogate_merit(&corrections, &centre.x, &centre.margins);
        let predicted = phi_c - ctx.surrogate_merit(&corrections, &x_new, &centre.margins);
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
        if centre.feasible && predicted <= MARGIN * settings.tolerance && step < 0.99 * delta {
            // a measured design that meets every constraint by its margin, and the surrogate's
            // optimum, inside the trust region (not held by its bound), promises less than a
            // quarter of the tolerance (of the objective) beyond it: a measurement would not
            // resolve the gain
            it.note = Some(
                "the surrogate promises less than a quarter of the tolerance beyond a design \
                 that meets every constraint"
                    .into(),
            );
            r.iterations.push(it);
            converged = true;
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
        // the fall of the merit with the centre's margins, as the surrogate predicted it:
        // an error estimate moves by steps with the design (a peak stress's sequence that
        // turns or not), which would otherwise pass for a change of the outputs
        let actual = centre.merit - ctx.merit_with(&check, &centre.margins);
        // the secants learn from every measurement, accepted or not
        for (k, c) in corrections.iter_mut().enumerate() {
            if let (Some(c), Some(m)) = (c, check.measured[k]) {
                c.update(&x_new, m / check.analytic[k], &ctx.range);
            }
        }
        let ratio = actual / predicted;
        it.actual = Some(actual);
        // never from a design that meets every constraint by its own margins to one that
        // does not (the merit compares them with the centre's margins)
        it.accepted = ratio >= ACCEPT && (check.feasible || !centre.feasible);
        if ctx.better(&check, &best) {
            best = check.clone();
        }
        if it.accepted {
            let change = ctx.change(&centre, &check);
            // an error estimate above the tolerance (a peak stress whose sequence turns)
            // does not hold the refinement: it widens that output's margin instead, and a
            // change within it is not resolved
            let settled = change <= settings.tolerance;
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
