//! `refined.json` and the summary of a refinement ([`crate::refine`]): the refined design
//! and the analytic optimum, each as the model gives it and as measured, with every
//! constraint's measured margin and the iterations.

use std::fmt::{self, Display};

use indexmap::IndexMap;
use serde::Serialize;

use super::ConstraintReport;
use crate::problem::nlp::ACTIVE_TOLERANCE;
use crate::problem::refine::RefineSettings;
use crate::problem::units::Unit;
use crate::problem::Problem;
use crate::refine::{Check, RefineStatus, Refinement};

/// One output the objective or constraints use, at one design.
#[derive(Debug, Clone, Serialize)]
pub struct OutputRow {
    pub output: String,
    /// The file's unit of its constraint, else SI.
    pub unit: String,
    pub analytic: f64,
    /// As measured; `null` for an output measured by the model only (geometry).
    pub measured: Option<f64>,
    /// The measurement's estimated relative error.
    pub error: Option<f64>,
    /// The relative margin by which the measured value must meet its limits for the part
    /// to meet them: the error plus the difference from the fidelity used to the next one
    /// up (`null` where not measured).
    pub required_margin: Option<f64>,
    /// `(analytic - measured) / measured`.
    pub deviation: Option<f64>,
    /// Where the analytic value only stands in for the measured quantity
    /// ([`crate::model::OutputInfo::stand_in`]): what it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stand_in: Option<&'static str>,
}

/// A measured design.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredDesign {
    /// Variable -> value in the file's unit, and SI.
    pub design: IndexMap<String, f64>,
    pub design_si: IndexMap<String, f64>,
    /// The objective as the problem states it, measured where measured (SI).
    pub objective: f64,
    /// Every constraint met as measured, each by its output's required margin.
    pub feasible: bool,
    pub outputs: Vec<OutputRow>,
    /// Each constraint with the value that counts (measured where measured).
    pub constraints: Vec<ConstraintReport>,
    /// The measurement's other figures (the FE's outputs in both idealizations).
    pub measurement: serde_json::Value,
    pub seconds: f64,
}

impl MeasuredDesign {
    pub fn new(problem: &Problem, r: &Refinement, c: &Check) -> Self {
        let model = problem.model();
        let unit_of = |o: usize| {
            problem
                .constraints
                .iter()
                .find(|c| c.index == o)
                .map(|c| c.unit.clone())
        };
        let outputs = r
            .outputs
            .iter()
            .enumerate()
            .map(|(k, &o)| {
                let unit = unit_of(o).unwrap_or_else(|| Unit::si(model.outputs()[o].dimension));
                let (name, si) = (unit.name.clone(), unit);
                OutputRow {
                    output: model.outputs()[o].name.to_string(),
                    unit: name,
                    analytic: si.from_si(c.analytic[k]),
                    measured: c.measured[k].map(|m| si.from_si(m)),
                    error: c.errors[k],
                    required_margin: c.measured[k].map(|_| c.margins[k]),
                    deviation: c.measured[k].map(|m| (c.analytic[k] - m) / m),
                    stand_in: model.outputs()[o].stand_in,
                }
            })
            .collect();
        MeasuredDesign {
            design: problem.design_in_file_units(&c.x),
            design_si: problem
                .variables
                .iter()
                .zip(&c.x)
                .map(|(v, &x)| (v.name.clone(), x))
                .collect(),
            objective: c.objective,
            feasible: c.feasible,
            outputs,
            constraints: problem
                .constraints
                .iter()
                .map(|con| {
                    let k = r.outputs.iter().position(|&o| o == con.index).unwrap_or(0);
                    ConstraintReport::new(con, c.value(k), ACTIVE_TOLERANCE)
                })
                .collect(),
            measurement: c.detail.clone(),
            seconds: c.seconds,
        }
    }
}

/// One iteration in `refined.json`.
#[derive(Debug, Clone, Serialize)]
pub struct IterationRow {
    pub trust_radius: f64,
    pub step: f64,
    pub surrogate: crate::optim::problem::Status,
    pub predicted: f64,
    pub actual: Option<f64>,
    pub accepted: bool,
    /// The measured design (SI) and its objective, feasibility and largest violation.
    pub design_si: Option<Vec<f64>>,
    pub objective: Option<f64>,
    pub feasible: Option<bool>,
    pub max_violation: Option<f64>,
    pub seconds: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// `refined.json`.
#[derive(Debug, Clone, Serialize)]
pub struct RefinedReport {
    pub problem: String,
    pub fidelity: String,
    pub settings: RefineSettings,
    #[serde(flatten)]
    pub status: RefineStatus,
    pub converged: bool,
    pub feasible: bool,
    /// Measurements (FE checks) made, over every refinement run.
    pub measurements: usize,
    pub seconds: f64,
    /// The refined design, measured.
    pub refined: Option<MeasuredDesign>,
    /// The analytic optimum it started from, measured.
    pub analytic_optimum: Option<MeasuredDesign>,
    pub iterations: Vec<IterationRow>,
    /// With `from = "zones"`: each zone's refinement, the chosen one included.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub zones: Vec<ZoneRefinement>,
}

/// One zone's refinement, in brief.
#[derive(Debug, Clone, Serialize)]
pub struct ZoneRefinement {
    pub zone: usize,
    #[serde(flatten)]
    pub status: RefineStatus,
    pub feasible: bool,
    pub objective: Option<f64>,
    pub measurements: usize,
    pub design_si: Option<Vec<f64>>,
}

impl RefinedReport {
    /// `chosen` among `all` (each with its zone's rank).
    pub fn new(
        problem: &Problem,
        settings: &RefineSettings,
        all: &[(usize, Refinement)],
        chosen: usize,
    ) -> Self {
        let r = &all[chosen].1;
        let measured = |c: &Option<Check>| c.as_ref().map(|c| MeasuredDesign::new(problem, r, c));
        RefinedReport {
            problem: problem.name.clone(),
            fidelity: r.fidelity.clone(),
            settings: settings.clone(),
            status: r.status.clone(),
            converged: r.status == RefineStatus::Converged,
            feasible: r.feasible(),
            measurements: all.iter().map(|(_, r)| r.measurements).sum(),
            seconds: all.iter().map(|(_, r)| r.seconds).sum(),
            refined: measured(&r.result),
            analytic_optimum: measured(&r.start),
            iterations: r
                .iterations
                .iter()
                .map(|it| IterationRow {
                    trust_radius: it.trust_radius,
                    step: it.step,
                    surrogate: it.surrogate.clone(),
                    predicted: it.predicted,
                    actual: it.actual,
                    accepted: it.accepted,
                    design_si: it.check.as_ref().map(|c| c.x.clone()),
                    objective: it.check.as_ref().map(|c| c.objective),
                    feasible: it.check.as_ref().map(|c| c.feasible),
                    max_violation: it
                        .check
                        .as_ref()
                        .map(|c| c.violations.iter().fold(0.0, |a: f64, &b| a.max(b))),
                    seconds: it.check.as_ref().map(|c| c.seconds),
                    note: it.note.clone(),
                })
                .collect(),
            zones: if all.len() > 1 {
                all.iter()
                    .map(|(zone, r)| ZoneRefinement {
                        zone: *zone,
                        status: r.status.clone(),
                        feasible: r.feasible(),
                        objective: r.result.as_ref().map(|c| c.objective),
                        measurements: r.measurements,
                        design_si: r.result.as_ref().map(|c| c.x.clone()),
                    })
                    .collect()
            } else {
                Vec::new()
            },
        }
    }
}

/// `v` to seven significant digits.
fn significant(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (6 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.decimals$}")
}

/// A limit as a file would write it: seven significant digits, no trailing zeros.
fn limit(v: f64) -> String {
    let s = significant(v);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The refinement's lines of the `run` summary: the analytic optimum against the refined
/// design, each by the model and as measured.
pub struct RefineSummary<'a>(pub &'a RefinedReport);

impl Display for RefineSummary<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = self.0;
        let how = match &r.status {
            RefineStatus::Converged => "converged".to_string(),
            RefineStatus::Budget => "NOT CONVERGED within refine.max_fe".to_string(),
            RefineStatus::Stalled => "STALLED: no better measured design nearby".to_string(),
            RefineStatus::Failed(e) => format!("FAILED: {e}"),
        };
        writeln!(
            s,
            "refined against {}: {how}, {} FE checks in {:.2} s",
            r.fidelity, r.measurements, r.seconds
        )?;
        let (Some(a), Some(b)) = (&r.analytic_optimum, &r.refined) else {
            return Ok(());
        };
        writeln!(
            s,
            "{:<24} {:>13} {:>13}   {:>13} {:>13}   limits",
            "", "optimum", "its FE", "refined", "its FE"
        )?;
        let num = |v: Option<f64>| v.map_or("-".to_string(), significant);
        for (ra, rb) in a.outputs.iter().zip(&b.outputs) {
            let limits =
                a.constraints
                    .iter()
                    .find(|c| c.output == ra.output)
                    .map_or(String::new(), |c| {
                        format!(
                            "{} .. {}",
                            c.lower.map_or(String::new(), limit),
                            c.upper.map_or(String::new(), limit)
                        )
                    });
            writeln!(
                s,
                "{:<24} {:>13} {:>13}   {:>13} {:>13}   {limits}",
                format!("{} ({})", ra.output, ra.unit),
                num(Some(ra.analytic)),
                num(ra.measured),
                num(Some(rb.analytic)),
                num(rb.measured)
            )?;
        }
        for r in &a.outputs {
            if let Some(what) = r.stand_in {
                writeln!(s, "{}: the model's value is {what}", r.output)?;
            }
        }
        let met = |m: &MeasuredDesign| if m.feasible { "meets" } else { "VIOLATES" };
        writeln!(
            s,
            "as FE: the analytic optimum {} its constraints, the refined design {} them",
            met(a),
            met(b)
        )?;
        let design: Vec<String> = b
            .design
            .iter()
            .map(|(k, v)| format!("{k}={v:.6}"))
            .collect();
        writeln!(s, "  refined design {}", design.join(","))
    }
}
