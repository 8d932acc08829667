//! `refined.json` and the summary of a refinement ([`crate::refine`]): the refined design
//! and the analytic optimum, each as the model gives it and as measured, with every
//! constraint's measured margin and the iterations.

use std::fmt::{self, Display};

use indexmap::IndexMap;
use serde::Serialize;

use super::tolerance::FeReport;
use super::ConstraintReport;
use crate::problem::nlp::ACTIVE_TOLERANCE;
use crate::problem::refine::RefineSettings;
use crate::problem::Problem;
use crate::refine::spread::FeSpread;
use crate::refine::study::StudyRefinement;
use crate::refine::{Check, RefineStatus, Refinement};

/// One output the objective or constraints use, at one design.
#[derive(Debug, Clone, Serialize)]
pub struct OutputRow {
    pub output: String,
    /// The unit it is shown in ([`crate::problem::display::output_unit`]).
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
    /// Neither measured nor a size of the part as drawn: the part's check has no counterpart
    /// of it, and its value is the model's alone.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub not_measured_on_the_part: bool,
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
        let outputs = r
            .outputs
            .iter()
            .enumerate()
            .map(|(k, &o)| {
                let si = crate::problem::display::output_unit(problem, o);
                let name = si.name.clone();
                OutputRow {
                    output: model.outputs()[o].name.to_string(),
                    unit: name,
                    analytic: si.from_si(c.analytic[k]),
                    measured: c.measured[k].map(|m| si.from_si(m)),
                    error: c.errors[k],
                    required_margin: c.measured[k].map(|_| c.margins[k]),
                    deviation: c.measured[k].map(|m| (c.analytic[k] - m) / m),
                    stand_in: model.outputs()[o].stand_in,
                    not_measured_on_the_part: c.measured[k].is_none()
                        && !problem.mechanism().drawn(o),
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
    /// A robust problem's refined design under the tolerances, checked by FE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust_check: Option<RobustCheck>,
}

/// A robust refinement's design under the tolerances: the FE's spread on a few of the Monte
/// Carlo's samples ([`crate::refine::spread`]), the part's yield and each constraint's FE
/// margin in the FE's standard deviations.
#[derive(Debug, Clone, Serialize)]
pub struct RobustCheck {
    /// The standard deviations each limit keeps, and the yield they stand for.
    pub k_sigma: f64,
    pub target_yield: Option<f64>,
    /// Constraint output -> the FE value's distance to its nearest limit over the FE's
    /// standard deviation.
    pub margins_in_sigma: IndexMap<String, f64>,
    /// Whether the part's yield (the Monte Carlo mapped onto the FE) reaches the target (or
    /// every margin `k_sigma`, without a target).
    pub meets_target: bool,
    pub spread: Option<FeReport>,
    /// Why the spread could not be measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl RobustCheck {
    fn new(problem: &Problem, spread: &Result<FeSpread, String>) -> Option<Self> {
        let robust = problem.search.robust?;
        let mut check = RobustCheck {
            k_sigma: robust.k_sigma,
            target_yield: robust.target_yield,
            margins_in_sigma: IndexMap::new(),
            meets_target: false,
            spread: None,
            error: None,
        };
        let spread = match spread {
            Ok(s) => s,
            Err(e) => {
                check.error = Some(e.clone());
                return Some(check);
            }
        };
        let name =
            |c: &crate::problem::Constraint| problem.model().outputs()[c.index].name.to_string();
        for c in &problem.constraints {
            let Some(o) = spread.outputs.iter().find(|o| o.output == name(c)) else {
                continue;
            };
            check
                .margins_in_sigma
                .insert(c.output.clone(), c.margin_in_sigma(o.measured, o.std));
        }
        check.meets_target = match robust.target_yield {
            Some(y) => spread.yield_fraction >= y,
            None => check
                .margins_in_sigma
                .values()
                .all(|&m| m >= robust.k_sigma),
        };
        check.spread = Some(FeReport::new(problem, spread));
        Some(check)
    }
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
    /// The refinement `refinement` of a study's optimum (or of each zone's), its chosen one
    /// reported.
    pub fn new(problem: &Problem, settings: &RefineSettings, refinement: &StudyRefinement) -> Self {
        let (all, chosen) = (&refinement.all, refinement.chosen);
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
            robust_check: refinement
                .spread
                .as_ref()
                .and_then(|s| RobustCheck::new(problem, s)),
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
        let fe = |r: &OutputRow| {
            if r.not_measured_on_the_part {
                "not measured".to_string()
            } else {
                num(r.measured)
            }
        };
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
                fe(ra),
                num(Some(rb.analytic)),
                fe(rb)
            )?;
        }
        if b.outputs.iter().any(|r| r.not_measured_on_the_part) {
            writeln!(
                s,
                "not measured: on the part, whose check has no counterpart of it (the model's value \
                 alone)"
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
        writeln!(s, "  refined design {}", design.join(","))?;
        if let Some(c) = &r.robust_check {
            write!(s, "{}", RobustCheckSummary(c))?;
        }
        Ok(())
    }
}

/// A robust refinement's check under the tolerances, for the summary.
struct RobustCheckSummary<'a>(&'a RobustCheck);

impl Display for RobustCheckSummary<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.0;
        let Some(fe) = &c.spread else {
            return writeln!(
                s,
                "robust: the refined design's FE spread could not be measured: {}",
                c.error.as_deref().unwrap_or("")
            );
        };
        let target = c.target_yield.map_or(String::new(), |y| {
            format!(", target {} %", limit(100.0 * y))
        });
        writeln!(
            s,
            "robust: the refined design under the tolerances, its spread checked by FE on {} of \
             the Monte Carlo's samples: yield of the part {:.2} % ({:.2} .. {:.2} %){target}{}",
            fe.samples,
            100.0 * fe.yield_fraction,
            100.0 * fe.yield_interval[0],
            100.0 * fe.yield_interval[1],
            if c.meets_target {
                ""
            } else {
                ": BELOW THE TARGET"
            }
        )?;
        let margins: Vec<String> = c
            .margins_in_sigma
            .iter()
            .map(|(k, v)| format!("{k} {:.2}", v))
            .collect();
        writeln!(
            s,
            "  FE margins in FE standard deviations (each limit keeps {:.3}): {}",
            c.k_sigma,
            margins.join(", ")
        )?;
        let ratios: Vec<String> = fe
            .outputs
            .iter()
            .map(|o| {
                format!(
                    "{} {:.3} +-{:.3}",
                    o.name,
                    o.beta_over_factor,
                    o.beta_error / o.factor.abs()
                )
            })
            .collect();
        writeln!(
            s,
            "  FE spread over the corrected model's (1: as the refinement assumed): {}",
            ratios.join(", ")
        )
    }
}
