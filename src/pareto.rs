//! Trade-off fronts by the epsilon-constraint method: the problem is solved again and again
//! with the limit of one of its constraints stepped over a range, each time with the full
//! multistart study, and the best objective is recorded against the output's value.
//!
//! The constraint to step must be one-sided in the problem file: its only limit is the one
//! that moves (`natural_frequency >= f` for a bandwidth floor). Each step's best design is
//! kept with the value the output actually takes there, so a floor that the unconstrained
//! optimum already clears shows up as a repeated point, not as a fake trade.

use std::time::{Duration, Instant};

use indexmap::IndexMap;
use serde::Serialize;

use crate::problem::nlp::ACTIVE_TOLERANCE;
use crate::problem::{Problem, ProblemError, Sense};
use crate::study::{self, StudyOptions};
use crate::sweep::check_range;

/// Which constraint to step, and over what, in the constraint's unit.
#[derive(Debug, Clone)]
pub struct ParetoSpec {
    pub output: String,
    pub from: f64,
    pub to: f64,
    pub steps: usize,
}

/// One step of the sweep.
#[derive(Debug, Clone, Serialize)]
pub struct ParetoPoint {
    /// The constraint's limit at this step, in the constraint's unit.
    pub limit: f64,
    /// Whether any start ended feasible.
    pub feasible: bool,
    /// Best objective found (as the problem states it); `null` when none is feasible.
    pub objective: Option<f64>,
    /// The stepped output's value at that design, in the constraint's unit.
    pub value: Option<f64>,
    /// Whether the stepped limit is active there.
    pub active: bool,
    /// Whether no other point is better in both the objective and the output.
    pub on_front: bool,
    /// The limit of an earlier point with the same result (objective and output equal to
    /// within [`SAME`]): a limit that does not bind gives the same optimum again.
    pub same_as: Option<f64>,
    /// The best design, variable -> value in the problem file's units.
    pub design: IndexMap<String, f64>,
    /// Configuration type of the best design (`-` for a model whose topology is fixed).
    pub configuration: String,
    pub feasible_starts: usize,
}

/// A trade-off front.
#[derive(Debug, Clone, Serialize)]
pub struct Pareto {
    pub problem: String,
    pub objective: String,
    pub sense: Sense,
    pub output: String,
    pub unit: String,
    /// `"lower"` or `"upper"`: the limit that was stepped.
    pub bound: &'static str,
    pub starts: usize,
    pub seed: u64,
    pub points: Vec<ParetoPoint>,
    #[serde(skip)]
    pub elapsed: Duration,
}

/// Steps the one-sided constraint on `spec.output` from `spec.from` to `spec.to` and runs
/// the study of `problem` at each limit.
pub fn pareto(
    problem: &Problem,
    spec: &ParetoSpec,
    options: &StudyOptions,
) -> Result<Pareto, ProblemError> {
    let err = |key: &str, message: String| ProblemError {
        file: problem.file.clone(),
        key: key.into(),
        position: None,
        message,
    };
    let model = problem.model();
    if model.output_index(&spec.output).is_none() {
        let names: Vec<_> = model.outputs().iter().map(|o| o.name.as_ref()).collect();
        return Err(err(
            "--vary",
            format!(
                "unknown output \"{}\"; expected one of {}",
                spec.output,
                names.join(", ")
            ),
        ));
    }
    let on_output: Vec<usize> = (0..problem.constraints.len())
        .filter(|&i| problem.constraints[i].output == spec.output)
        .collect();
    let ci = match on_output[..] {
        [i] => i,
        [] => {
            return Err(err(
                "--vary",
                format!(
                    "the problem has no constraint on \"{}\": add one with the limit's unit and sense (lower or upper) to step",
                    spec.output
                ),
            ))
        }
        _ => {
            return Err(err(
                "--vary",
                format!(
                    "the problem has {} constraints on \"{}\": keep one to step",
                    on_output.len(),
                    spec.output
                ),
            ))
        }
    };
    let c = &problem.constraints[ci];
    let bound = match (c.lower, c.upper) {
        (Some(_), None) => "lower",
        (None, Some(_)) => "upper",
        _ => {
            return Err(err(
                "--vary",
                format!(
                    "the constraint on \"{}\" has two limits: give it only the one to step",
                    spec.output
                ),
            ))
        }
    };
    check_range(spec.from, spec.to, spec.steps, 1000).map_err(|(k, m)| err(k, m))?;
    let started = Instant::now();
    let unit = c.unit.clone();
    let mut points = Vec::with_capacity(spec.steps);
    let mut stepped = problem.clone();
    for i in 0..spec.steps {
        let limit = spec.from + (spec.to - spec.from) * i as f64 / (spec.steps - 1) as f64;
        let slot = if bound == "lower" {
            &mut stepped.constraints[ci].lower
        } else {
            &mut stepped.constraints[ci].upper
        };
        *slot = Some(unit.to_si(limit));
        let options = StudyOptions {
            explain_infeasible: false,
            ..options.clone()
        };
        let s = study::run(&stepped, &options);
        let best = &s.runs[s.best];
        let mut value = [0.0];
        problem
            .model()
            .evaluate(&best.x_end, &[c.index], &mut value);
        let value_si = value[0];
        let feasible = s.any_feasible && value_si.is_finite();
        let limit_si = unit.to_si(limit);
        points.push(ParetoPoint {
            limit,
            feasible,
            objective: feasible.then_some(best.objective),
            value: feasible.then(|| unit.from_si(value_si)),
            active: feasible
                && (value_si - limit_si).abs() <= ACTIVE_TOLERANCE * limit_si.abs().max(1e-300),
            on_front: false,
            same_as: None,
            design: problem.design_in_file_units(&best.x_end),
            configuration: problem.depiction().configuration(&best.x_end).into(),
            feasible_starts: s.feasible_runs.len(),
        });
    }
    mark_front(&mut points, problem.objective.sense, bound);
    Ok(Pareto {
        problem: problem.name.clone(),
        objective: problem.objective.output.clone(),
        sense: problem.objective.sense,
        output: spec.output.clone(),
        unit: unit.name.clone(),
        bound,
        starts: options.starts,
        seed: options.seed,
        points,
        elapsed: started.elapsed(),
    })
}

/// Marks the feasible points that no other point beats in both the objective and the
/// stepped output (higher is better for a lower limit, lower for an upper one). Points
/// equal to within [`SAME`] (relative) are all kept: repeated solves of one optimum differ
/// in their last digits.
fn mark_front(points: &mut [ParetoPoint], sense: Sense, bound: &str) {
    let oriented = |p: &ParetoPoint| -> Option<(f64, f64)> {
        let (o, v) = (p.objective?, p.value?);
        let o = if sense == Sense::Maximize { o } else { -o };
        let v = if bound == "lower" { v } else { -v };
        Some((o, v))
    };
    let all: Vec<Option<(f64, f64)>> = points.iter().map(oriented).collect();
    let better = |b: f64, a: f64| b > a + SAME * a.abs().max(b.abs());
    let worse = |b: f64, a: f64| better(a, b);
    for (i, p) in points.iter_mut().enumerate() {
        let Some(a) = all[i] else { continue };
        p.on_front = !all.iter().flatten().any(|b| {
            !worse(b.0, a.0) && !worse(b.1, a.1) && (better(b.0, a.0) || better(b.1, a.1))
        });
    }
    let limits: Vec<f64> = points.iter().map(|p| p.limit).collect();
    for i in 0..points.len() {
        let Some(a) = all[i] else { continue };
        points[i].same_as = (0..i)
            .find(|&j| {
                all[j].is_some_and(|b| {
                    !better(a.0, b.0) && !better(b.0, a.0) && !better(a.1, b.1) && !better(b.1, a.1)
                })
            })
            .map(|j| limits[j]);
    }
}

/// Relative difference below which two points of a front count as one.
pub const SAME: f64 = 1e-9;
