//! A robust study's optimum beside the nominal one: the nominal study run on the same
//! problem without `[search] robust`, and each optimum's objective, Monte Carlo yield and
//! margins, for the summary of `run`.

use indexmap::IndexMap;
use serde::Serialize;

use super::analyze;
use super::monte_carlo::Settings;
use crate::problem::Problem;
use crate::study::{self, StudyOptions};

/// One optimum under the tolerances.
#[derive(Debug, Clone, Serialize)]
pub struct Side {
    /// The objective as the problem states it.
    pub objective: f64,
    /// Variable -> value in the file's unit.
    pub design: IndexMap<String, f64>,
    #[serde(rename = "yield")]
    pub yield_fraction: f64,
    pub yield_interval: [f64; 2],
    /// The fraction of samples whose part breaks one of the part's rules (failed parts,
    /// outside the yield).
    pub unmakeable: f64,
    /// Constraint output -> its margin to the nearest limit in first-order standard
    /// deviations (positive inside).
    pub margins_in_sigma: IndexMap<String, f64>,
}

/// `robust.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    pub problem: String,
    pub k_sigma: f64,
    #[serde(rename = "target_yield", skip_serializing_if = "Option::is_none")]
    pub target_yield: Option<f64>,
    pub samples: usize,
    pub seed: u64,
    pub nominal: Option<Side>,
    pub robust: Side,
}

/// The robust optimum `x` (objective `objective`) of `problem` beside the nominal study's,
/// each checked by `settings.samples` Monte Carlo samples.
pub fn compare(
    problem: &Problem,
    options: &StudyOptions,
    x: &[f64],
    objective: f64,
    settings: Settings,
) -> Result<Comparison, String> {
    let robust = problem
        .search
        .robust
        .ok_or("the problem asks for no robust study")?;
    let mut nominal = problem.clone();
    nominal.search.robust = None;
    let quiet = StudyOptions {
        progress: false,
        explain_infeasible: false,
        ..options.clone()
    };
    let study = study::run(&nominal, &quiet);
    let nominal_side = if study.any_feasible {
        let xn = study.reported_design().to_vec();
        Some(side(problem, &xn, study.reported_objective(), settings)?)
    } else {
        None
    };
    Ok(Comparison {
        problem: problem.name.clone(),
        k_sigma: robust.k_sigma,
        target_yield: robust.target_yield,
        samples: settings.samples,
        seed: settings.seed,
        nominal: nominal_side,
        robust: side(problem, x, objective, settings)?,
    })
}

fn side(problem: &Problem, x: &[f64], objective: f64, settings: Settings) -> Result<Side, String> {
    let a = analyze(problem, x, settings)?;
    let margins = problem
        .constraints
        .iter()
        .map(|c| {
            let j = a
                .outputs
                .wanted
                .iter()
                .position(|&w| w == c.index)
                .unwrap_or(0);
            (
                c.output.clone(),
                c.margin_in_sigma(a.first_order[j].nominal, a.first_order[j].std),
            )
        })
        .collect();
    Ok(Side {
        objective,
        design: problem.design_in_file_units(x),
        yield_fraction: a.monte_carlo.yield_fraction,
        yield_interval: a.monte_carlo.yield_interval,
        unmakeable: a.monte_carlo.unmakeable,
        margins_in_sigma: margins,
    })
}
