//! `flexopt tolerance`'s set: `tolerance.json`, a histogram `histogram_<output>.png` per
//! constrained output with its limits marked, and the terminal's table. Every value is in
//! the unit the file uses for the output ([`output_unit`]).

use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plotters::prelude::*;
use serde::Serialize;

use super::folder::OutputSet;
use super::plot::{axis_tick, range, render_png, FAMILY};
use super::{write_json, WriteError};
use crate::problem::display::output_unit;
use crate::problem::tolerances::{Input, Tolerance};
use crate::problem::Problem;
use crate::refine::spread::FeSpread;
use crate::tolerance::monte_carlo::{Spread, CONFIDENCE};
use crate::tolerance::robust::Comparison;
use crate::tolerance::{normal_within, Analysis};

mod table;
use table::pc;
pub use table::{RobustTable, ToleranceTable};

/// One tolerance as the report shows it.
#[derive(Debug, Clone, Serialize)]
pub struct ToleranceLine {
    pub name: String,
    /// The band, in `unit` (a fraction for the modulus), `coverage` standard deviations.
    pub plus_minus: f64,
    pub coverage: f64,
    /// The standard deviation, in `unit`.
    pub sigma: f64,
    pub unit: String,
    pub distribution: crate::problem::tolerances::Distribution,
    pub origin: crate::problem::tolerances::Origin,
}

/// One output the problem uses, under the tolerances.
#[derive(Debug, Clone, Serialize)]
pub struct OutputLine {
    pub name: String,
    pub unit: String,
    /// `objective`, `constraint`, or both.
    pub role: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
    pub nominal: f64,
    /// The first-order standard deviation.
    pub std: f64,
    pub worst_case: [f64; 2],
    /// Tolerance -> share of the first-order variance.
    pub shares: IndexMap<String, f64>,
    /// The constraint's yield if the output were normal with the first-order spread.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_order_yield: Option<f64>,
    pub monte_carlo: Spread,
    /// The fraction of samples meeting the constraint.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub monte_carlo_yield: Option<f64>,
}

/// `tolerance.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ToleranceReport {
    pub problem: String,
    pub model: String,
    /// Variable -> value in the file's unit.
    pub design: IndexMap<String, f64>,
    pub tolerances: Vec<ToleranceLine>,
    pub outputs: Vec<OutputLine>,
    pub samples: usize,
    pub seed: u64,
    /// The fraction of samples whose part can be made and that meet every constraint of
    /// `yield_of`.
    #[serde(rename = "yield")]
    pub yield_fraction: f64,
    pub yield_of: Vec<String>,
    /// The fraction of samples whose part breaks one of the part's rules or more (failed
    /// parts), and per rule the fraction that breaks it (every rule the part states).
    pub unmakeable: f64,
    pub rules_broken: IndexMap<String, f64>,
    pub yield_interval: [f64; 2],
    pub yield_confidence: f64,
    pub interval_method: &'static str,
    /// With `--fe`: the part's own spread from a few samples checked by FE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fe: Option<FeReport>,
}

/// One output's measured spread ([`MeasuredSpread`]), in the output's unit.
#[derive(Debug, Clone, Serialize)]
pub struct FeLine {
    pub name: String,
    pub unit: String,
    /// At the design: the model's value, the FE's and its estimated relative error.
    pub model: f64,
    pub fe: f64,
    pub fe_error: Option<f64>,
    /// The FE over the model.
    pub factor: f64,
    /// The FE's deviations over the model's on the samples, its standard error, and over
    /// the factor (1: the model's spread scaled by the factor is the FE's).
    pub beta: f64,
    pub beta_error: f64,
    pub beta_over_factor: f64,
    /// The FE's standard deviation (`|beta|` times the model's first-order one), the
    /// model's, and the samples' own with its 95 % interval.
    pub std: f64,
    pub model_std: f64,
    pub sample_std: f64,
    pub sample_std_interval: [f64; 2],
}

/// One sample checked by FE, in the file's units.
#[derive(Debug, Clone, Serialize)]
pub struct FeSampleLine {
    /// Its index among the Monte Carlo's samples (the same draw).
    pub index: usize,
    pub design: IndexMap<String, f64>,
    pub youngs_modulus_factor: f64,
    /// Output -> [model, FE].
    pub outputs: IndexMap<String, [f64; 2]>,
}

/// `tolerance.json`'s `fe`: the measured spread.
#[derive(Debug, Clone, Serialize)]
pub struct FeReport {
    pub fidelity: String,
    pub samples: usize,
    pub method: &'static str,
    pub outputs: Vec<FeLine>,
    /// The Monte Carlo's samples mapped onto the FE: the fraction meeting every constraint,
    /// its Wilson interval (the Monte Carlo's count alone), and per constraint.
    #[serde(rename = "yield")]
    pub yield_fraction: f64,
    pub yield_interval: [f64; 2],
    pub constraint_yields: IndexMap<String, f64>,
    pub sample_records: Vec<FeSampleLine>,
    /// The samples passed over because their part cannot be made.
    pub unmade: Vec<UnmadeLine>,
    pub seconds: f64,
}

/// A sample whose part cannot be made, in the file's units.
#[derive(Debug, Clone, Serialize)]
pub struct UnmadeLine {
    pub index: usize,
    pub design: IndexMap<String, f64>,
    pub youngs_modulus_factor: f64,
    pub why: String,
}

impl FeReport {
    pub fn new(problem: &Problem, spread: &FeSpread) -> Self {
        let index = |name: &str| problem.model().output_index(name).unwrap_or(0);
        let units: Vec<_> = spread
            .outputs
            .iter()
            .map(|o| output_unit(problem, index(&o.output)))
            .collect();
        let outputs = spread
            .outputs
            .iter()
            .zip(&units)
            .map(|(o, unit)| {
                let s = |v: f64| unit.from_si(v);
                FeLine {
                    name: o.output.clone(),
                    unit: unit.name.clone(),
                    model: s(o.analytic),
                    fe: s(o.measured),
                    fe_error: o.measured_error,
                    factor: o.factor,
                    beta: o.beta,
                    beta_error: o.beta_error,
                    beta_over_factor: o.beta_over_factor,
                    std: s(o.std).abs(),
                    model_std: s(o.analytic_std).abs(),
                    sample_std: s(o.sample_std).abs(),
                    sample_std_interval: o.sample_std_interval.map(|v| s(v).abs()),
                }
            })
            .collect();
        let sample_records = spread
            .sample_records
            .iter()
            .map(|r| FeSampleLine {
                index: r.index,
                design: problem.design_in_file_units(&r.design),
                youngs_modulus_factor: r.modulus,
                outputs: spread
                    .outputs
                    .iter()
                    .zip(&units)
                    .enumerate()
                    .map(|(k, (o, unit))| {
                        (
                            o.output.clone(),
                            [unit.from_si(r.analytic[k]), unit.from_si(r.measured[k])],
                        )
                    })
                    .collect(),
            })
            .collect();
        FeReport {
            fidelity: spread.fidelity.clone(),
            samples: spread.samples,
            method: "the Monte Carlo's first samples whose part can be made checked by FE; \
                     the FE's deviations regressed on the model's (the model as control \
                     variate)",
            outputs,
            yield_fraction: spread.yield_fraction,
            yield_interval: spread.yield_interval,
            constraint_yields: problem
                .constraints
                .iter()
                .zip(&spread.constraint_yields)
                .map(|(c, &y)| (c.output.clone(), y))
                .collect(),
            sample_records,
            unmade: spread
                .unmade
                .iter()
                .map(|u| UnmadeLine {
                    index: u.index,
                    design: problem.design_in_file_units(&u.design),
                    youngs_modulus_factor: u.modulus,
                    why: u.why.clone(),
                })
                .collect(),
            seconds: spread.seconds,
        }
    }
}

impl ToleranceReport {
    pub fn new(problem: &Problem, x: &[f64], a: &Analysis) -> Self {
        let params = problem.model().parameters().len();
        let tolerances = problem
            .tolerances
            .iter()
            .map(|t| line(problem, t, params))
            .collect();
        let mc = &a.monte_carlo;
        let outputs = a
            .outputs
            .wanted
            .iter()
            .enumerate()
            .map(|(j, &index)| {
                let unit = output_unit(problem, index);
                let s = |v: f64| unit.from_si(v);
                let f = &a.first_order[j];
                let constraint = problem.constraints.iter().position(|c| c.index == index);
                let c = constraint.map(|k| &problem.constraints[k]);
                let objective = problem.objective.index == index;
                let spread = &mc.outputs[j];
                OutputLine {
                    name: problem.model().outputs()[index].name.to_string(),
                    unit: unit.name.clone(),
                    role: match (objective, c.is_some()) {
                        (true, true) => "objective, constraint",
                        (true, false) => "objective",
                        _ => "constraint",
                    }
                    .into(),
                    lower: c.and_then(|c| c.lower).map(s),
                    upper: c.and_then(|c| c.upper).map(s),
                    nominal: s(f.nominal),
                    std: s(f.std).abs(),
                    worst_case: {
                        let [a, b] = f.worst_case.map(s);
                        [a.min(b), a.max(b)]
                    },
                    shares: problem
                        .tolerances
                        .iter()
                        .zip(&f.shares)
                        .map(|(t, &v)| (t.name.clone(), v))
                        .collect(),
                    first_order_yield: c.map(|c| normal_within(f.nominal, f.std, c.lower, c.upper)),
                    monte_carlo: Spread {
                        mean: s(spread.mean),
                        std: s(spread.std).abs(),
                        quantiles: spread.quantiles.iter().map(|&[q, v]| [q, s(v)]).collect(),
                        min: s(spread.min),
                        max: s(spread.max),
                    },
                    monte_carlo_yield: constraint.map(|k| mc.constraint_yields[k]),
                }
            })
            .collect();
        ToleranceReport {
            problem: problem.name.clone(),
            model: problem.model().name().to_string(),
            design: problem.design_in_file_units(x),
            tolerances,
            outputs,
            samples: mc.samples,
            seed: mc.seed,
            yield_fraction: mc.yield_fraction,
            yield_of: problem
                .constraints
                .iter()
                .filter(|c| c.in_yield)
                .map(|c| c.output.clone())
                .collect(),
            unmakeable: mc.unmakeable,
            rules_broken: crate::tolerance::makeable::Rules::of(problem)
                .names()
                .into_iter()
                .zip(mc.rule_breaks.iter().copied())
                .collect(),
            yield_interval: mc.yield_interval,
            yield_confidence: CONFIDENCE,
            interval_method: mc.interval_method,
            fe: None,
        }
    }
}

fn line(problem: &Problem, t: &Tolerance, params: usize) -> ToleranceLine {
    let sigma = match t.input {
        Input::Parameter(i) if i < params => problem.variables[i].unit.from_si(t.sigma),
        _ => t.sigma,
    };
    ToleranceLine {
        name: t.name.clone(),
        plus_minus: t.plus_minus,
        coverage: t.coverage,
        sigma,
        unit: t.unit.clone(),
        distribution: t.distribution,
        origin: t.origin,
    }
}

/// The file name of an output's histogram.
pub fn histogram_name(output: &str) -> String {
    format!("histogram_{output}.png")
}

/// Writes `tolerance.json` and the histograms into `dir` as one set; returns the paths.
pub fn write_tolerance_set(
    dir: &Path,
    report: &ToleranceReport,
    analysis: &Analysis,
    problem: &Problem,
) -> Result<Vec<PathBuf>, WriteError> {
    let m = analysis.outputs.wanted.len();
    let constrained: Vec<usize> = (0..m)
        .filter(|&j| report.outputs[j].lower.is_some() || report.outputs[j].upper.is_some())
        .collect();
    let mut names = vec!["tolerance.json".to_string()];
    names.extend(
        constrained
            .iter()
            .map(|&j| histogram_name(&report.outputs[j].name)),
    );
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    super::folder::check_names(dir, &refs)?;
    let set = OutputSet::begin(dir)?;
    set.write(|set| {
        write_json(&set.path(&names[0]), report)?;
        for (&j, name) in constrained.iter().zip(&names[1..]) {
            let unit = output_unit(problem, analysis.outputs.wanted[j]);
            let values: Vec<f64> = analysis
                .monte_carlo
                .values
                .iter()
                .skip(j)
                .step_by(m)
                .map(|&v| unit.from_si(v))
                .collect();
            histogram(
                &set.path(name),
                &report.problem,
                &report.outputs[j],
                &values,
            )?;
        }
        Ok(())
    })?;
    set.commit(&refs)
}

/// The bins of a histogram.
const BINS: usize = 60;

/// One output's samples as a histogram, its limits as red dashed lines and its nominal value
/// as a black one.
fn histogram(png: &Path, problem: &str, o: &OutputLine, values: &[f64]) -> Result<(), WriteError> {
    let limits: Vec<f64> = [o.lower, o.upper].into_iter().flatten().collect();
    let (lo, hi) = range(values.iter().copied());
    // a limit within reach of the samples widens the range; a far one would squash them
    let reach = 2.0 * (hi - lo);
    let near: Vec<f64> = limits
        .iter()
        .copied()
        .filter(|&l| l > lo - reach && l < hi + reach)
        .collect();
    let (x0, x1) = range(values.iter().copied().chain(near.iter().copied()));
    let width = (hi - lo) / BINS as f64;
    let mut counts = vec![0usize; BINS];
    for &v in values.iter().filter(|v| v.is_finite()) {
        let b = (((v - lo) / width) as usize).min(BINS - 1);
        counts[b] += 1;
    }
    let top = *counts.iter().max().unwrap_or(&1) as f64 * 1.08;
    let unit = if o.unit == "1" {
        String::new()
    } else {
        format!(" ({})", o.unit)
    };
    let title = format!(
        "{problem}: {} over {} samples, {} meet the constraint",
        o.name,
        values.len(),
        o.monte_carlo_yield.map_or("-".into(), pc)
    );
    render_png(png, (900, 520), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(&title, (FAMILY, 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, 0.0..top)?;
        chart
            .configure_mesh()
            .x_desc(format!("{}{unit}", o.name))
            .y_desc("samples")
            .label_style((FAMILY, 12))
            .axis_desc_style((FAMILY, 13))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .x_label_formatter(&|v| axis_tick(*v, (x0, x1), 10))
            .y_label_formatter(&|v| axis_tick(*v, (0.0, top), 10))
            .draw()?;
        chart.draw_series(counts.iter().enumerate().map(|(b, &c)| {
            let left = lo + width * b as f64;
            Rectangle::new(
                [(left, 0.0), (left + width, c as f64)],
                BLUE.mix(0.5).filled(),
            )
        }))?;
        for &l in &near {
            chart.draw_series(DashedLineSeries::new(
                [(l, 0.0), (l, top)],
                6,
                4,
                RED.mix(0.8).stroke_width(2),
            ))?;
        }
        chart.draw_series(LineSeries::new(
            [(o.nominal, 0.0), (o.nominal, top)],
            BLACK.stroke_width(1),
        ))?;
        Ok(())
    })
}

/// Writes `robust.json` into `dir`, added to the run's set; returns its path.
pub fn write_robust(dir: &Path, comparison: &Comparison) -> Result<Vec<PathBuf>, WriteError> {
    let set = OutputSet::begin(dir)?;
    set.write(|set| write_json(&set.path("robust.json"), comparison))?;
    set.commit_added(&["robust.json"])
}
