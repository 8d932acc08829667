//! Every output file and summary: JSON reports of designs, the study's, sweep's and
//! front's files and plots, and the text the command line prints.
//!
//! Every file is written whole or not at all: it is written beside its target under a
//! temporary name and renamed into place.

// how quantities read where a person reads them: since it moved below the study, kept
// reachable here for the writers
pub use crate::problem::display;
mod configurations;
pub mod folder;
pub mod hinge;
pub mod html;
pub mod pareto;
pub mod part;
pub mod plot;
pub mod refine;
pub mod stroke;
pub mod study;
mod study_plots;
pub mod summary;
pub mod sweep;
pub mod table;
pub mod tolerance;
pub mod verify;

use indexmap::IndexMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::model::Drawing;
use crate::problem::nlp::{ACTIVE_TOLERANCE, FEASIBILITY_TOLERANCE};
use crate::problem::{Constraint, Problem};

/// An error while writing results.
#[derive(Debug)]
pub struct WriteError {
    pub path: PathBuf,
    pub message: String,
}

impl std::fmt::Display for WriteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for WriteError {}

/// The temporary name a file is written under before it is renamed into place: hidden,
/// and with the same extension, which some encoders go by.
pub fn temporary_path(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|n| n.to_string_lossy())
        .unwrap_or_default();
    match path.extension() {
        Some(ext) => path.with_file_name(format!(".{stem}.partial.{}", ext.to_string_lossy())),
        None => path.with_file_name(format!(".{stem}.partial")),
    }
}

/// The file [`check_writable`] writes, followed by its process id.
const PROBE: &str = ".flexopt-probe-";

/// Checks, before any computation, that `dir` can be created and written: a run whose
/// results cannot be stored is bad input, not a failure found after the work is done.
pub fn check_writable(dir: &Path) -> Result<(), WriteError> {
    let fail = |e: &dyn std::fmt::Display| WriteError {
        path: dir.to_path_buf(),
        message: format!("cannot write results there: {e}"),
    };
    if dir.exists() && !dir.is_dir() {
        return Err(fail(&"it is not a folder"));
    }
    std::fs::create_dir_all(dir).map_err(|e| fail(&e))?;
    let probe = dir.join(format!("{PROBE}{}", std::process::id()));
    std::fs::File::create(&probe).map_err(|e| fail(&e))?;
    std::fs::remove_file(&probe).map_err(|e| fail(&e))
}

/// Writes `path` whole or not at all, creating its folder.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_with(path, |tmp| {
        let mut f = std::fs::File::create(tmp)?;
        f.write_all(bytes)?;
        f.sync_all()
    })
}

/// Lets `render` write the file under a temporary name, then renames it into place; on
/// failure the temporary file is removed and `path` is left as it was.
pub fn write_with(
    path: &Path,
    render: impl FnOnce(&Path) -> std::io::Result<()>,
) -> Result<(), WriteError> {
    let fail = |e: &dyn std::fmt::Display| WriteError {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| fail(&e))?;
    }
    let tmp = temporary_path(path);
    let result = render(&tmp).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(fail(&e));
    }
    Ok(())
}

/// Serializes `value` as pretty JSON into `path`, whole or not at all.
pub fn write_json(path: &Path, value: &impl Serialize) -> Result<(), WriteError> {
    let mut text = serde_json::to_string_pretty(value).map_err(|e| WriteError {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    text.push('\n');
    write_atomic(path, text.as_bytes())
}

/// One constraint at a design.
#[derive(Debug, Clone, Serialize)]
pub struct ConstraintReport {
    pub output: String,
    /// Value, limits and margin in the unit the problem file uses (`unit`).
    pub value: Option<f64>,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    pub unit: String,
    /// Distance to the nearest limit, positive inside; in `unit`.
    pub margin: Option<f64>,
    /// Relative margin: `margin` over the size of the nearest limit (or 1 when it is 0).
    pub relative_margin: Option<f64>,
    pub satisfied: bool,
    /// Within the activity tolerance of a limit; in a robust study, of the limit
    /// tightened by `k` standard deviations.
    pub active: bool,
    /// In a robust study: the margin in first-order standard deviations of the output
    /// under the tolerances (the robust rows keep `k` of them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub margin_in_sigma: Option<f64>,
    /// Where the model's value only stands in for what a higher fidelity measures
    /// ([`crate::model::OutputInfo::stand_in`]): what it is instead.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stand_in: Option<String>,
}

impl ConstraintReport {
    /// Reports constraint `c` whose output has SI value `value`; `active_tol` is relative.
    pub fn new(c: &Constraint, value: f64, active_tol: f64) -> Self {
        let u = &c.unit;
        let finite = value.is_finite();
        let (margin, relative) = match c.nearest_limit(value) {
            Some((m, scale)) if finite => (Some(u.from_si(m)), Some(m / scale)),
            _ => (None, None),
        };
        ConstraintReport {
            output: c.output.clone(),
            value: finite.then(|| u.from_si(value)),
            lower: c.lower.map(|v| u.from_si(v)),
            upper: c.upper.map(|v| u.from_si(v)),
            unit: u.name.clone(),
            margin,
            relative_margin: relative,
            satisfied: relative.is_some_and(|r| r >= -FEASIBILITY_TOLERANCE),
            active: relative.is_some_and(|r| r.abs() <= active_tol),
            margin_in_sigma: None,
            stand_in: None,
        }
    }
}

/// A design with every output of its model: what `flexopt eval` prints and what
/// `optimum.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct DesignReport {
    pub problem: String,
    pub model: String,
    /// The problem file's content hashed ([`crate::problem::fingerprint`], hexadecimal):
    /// `--optimum` compares it with the file it is given.
    pub problem_fnv1a64: String,
    /// Variable -> value in the file's unit.
    pub design: IndexMap<String, f64>,
    /// Variable -> the file's unit.
    pub design_units: IndexMap<String, String>,
    /// Variable -> SI value.
    pub design_si: IndexMap<String, f64>,
    /// Output -> SI value (`null` where the model gives no finite number).
    pub outputs: IndexMap<String, Option<f64>>,
    /// Output -> SI unit.
    pub output_units: IndexMap<String, String>,
    /// Output -> the unit a person reads it in: its constraint's in the file, else the
    /// designer's usual one (the summaries, tables and plots use it).
    pub display_units: IndexMap<String, String>,
    /// The objective as the problem states it (absolute value taken if asked), SI;
    /// `null` where the model gives no finite number.
    pub objective: Option<f64>,
    pub objective_output: String,
    pub sense: crate::problem::Sense,
    pub absolute: bool,
    pub constraints: Vec<ConstraintReport>,
    /// Each range where the model's fits hold, at this design: the ratio, its value and
    /// whether it lies inside ([`crate::model::Model::fit_limits`]).
    pub fit_ranges: Vec<crate::model::fit::FitCheck>,
    /// Each rule of the model's part at this design: its margin and whether it is active
    /// ([`crate::problem::part_rules`]); none for a model without a part.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub part_rules: Vec<crate::problem::part_rules::RuleCheck>,
    /// Every constraint met and, where the file makes the ranges of fit constraints (the
    /// default), every ratio inside its range, and where the part's rules are enforced (the
    /// default), every rule met.
    pub feasible: bool,
    /// The model's drawing data: nodes, mode shapes.
    #[serde(flatten)]
    pub drawing: Drawing,
}

impl DesignReport {
    /// Evaluates every output of `problem`'s model at the full design `x` (SI): those it
    /// gives itself, and the stand-ins the objective and constraints name, which only they
    /// report, marked.
    pub fn new(problem: &Problem, x: &[f64]) -> Self {
        let model = problem.model();
        let analytic = model.analytic_outputs();
        let mut all = analytic.clone();
        for i in std::iter::once(problem.objective.index)
            .chain(problem.constraints.iter().map(|c| c.index))
        {
            if !all.contains(&i) {
                all.push(i);
            }
        }
        let mut values = vec![0.0; all.len()];
        model.evaluate(x, &all, &mut values);
        // indexed like the model's outputs; the objective and constraints are available ones
        let mut out = vec![f64::NAN; model.outputs().len()];
        for (&i, &v) in all.iter().zip(&values) {
            out[i] = v;
        }
        let finite = |v: f64| v.is_finite().then_some(v);
        let mut report = DesignReport {
            problem: problem.name.clone(),
            model: model.name().into(),
            problem_fnv1a64: format!("{:016x}", problem.fingerprint),
            design: problem.design_in_file_units(x),
            design_units: IndexMap::new(),
            design_si: IndexMap::new(),
            outputs: IndexMap::new(),
            output_units: IndexMap::new(),
            display_units: IndexMap::new(),
            objective: finite(out[problem.objective.index]).map(|v| {
                if problem.objective.absolute {
                    v.abs()
                } else {
                    v
                }
            }),
            objective_output: problem.objective.output.clone(),
            sense: problem.objective.sense,
            absolute: problem.objective.absolute,
            constraints: problem
                .constraints
                .iter()
                .map(|c| ConstraintReport {
                    stand_in: model.outputs()[c.index].stand_in.map(str::to_string),
                    ..ConstraintReport::new(c, out[c.index], ACTIVE_TOLERANCE)
                })
                .collect(),
            fit_ranges: crate::problem::fit::checks(problem, x),
            part_rules: crate::problem::part_rules::checks(problem, x),
            feasible: false,
            drawing: problem.depiction().drawing(x),
        };
        robust_activity(problem, x, &mut report.constraints);
        for (v, &xi) in problem.variables.iter().zip(x) {
            report
                .design_units
                .insert(v.name.clone(), v.unit.name.clone());
            report.design_si.insert(v.name.clone(), xi);
        }
        for (&i, &v) in analytic.iter().zip(&values) {
            let info = &model.outputs()[i];
            report.outputs.insert(info.name.to_string(), finite(v));
            report
                .output_units
                .insert(info.name.to_string(), info.dimension.si_unit().into());
            report
                .display_units
                .insert(info.name.to_string(), display::output_unit(problem, i).name);
        }
        let fits_met = problem.search.fit_ranges != crate::problem::FitRanges::Constraint
            || report.fit_ranges.iter().all(|c| c.inside);
        report.feasible = report.objective.is_some()
            && report.constraints.iter().all(|c| c.satisfied)
            && fits_met
            && (crate::problem::part_rules::enforced(problem).is_none()
                || report.part_rules.iter().all(|r| r.met));
        report
    }

    /// Names of outputs without a finite value.
    pub fn non_finite_outputs(&self) -> Vec<&str> {
        self.outputs
            .iter()
            .filter(|(_, v)| v.is_none())
            .map(|(k, _)| k.as_str())
            .collect()
    }
}

/// In a robust study, each constraint's margin in its output's first-order standard
/// deviations, and active where it keeps just the `k` the robust rows ask: the nominal
/// limits of a robust optimum are not what it stands on.
fn robust_activity(problem: &Problem, x: &[f64], constraints: &mut [ConstraintReport]) {
    let Some(robust) = problem.search.robust else {
        return;
    };
    if problem.tolerances.is_empty() || problem.mechanism().modulus.is_none() {
        return;
    }
    let outputs = crate::tolerance::Outputs::new(problem);
    let spreads = crate::tolerance::first_order(&outputs, &problem.tolerances, x);
    for (report, c) in constraints.iter_mut().zip(&problem.constraints) {
        let Some(slot) = outputs.wanted.iter().position(|&w| w == c.index) else {
            continue;
        };
        let f = &spreads[slot];
        let Some((margin, scale)) = c.nearest_limit(f.nominal) else {
            continue;
        };
        if f.std.is_nan() || f.std <= 0.0 || !margin.is_finite() {
            continue;
        }
        report.margin_in_sigma = Some(margin / f.std);
        report.active = ((margin - robust.k_sigma * f.std) / scale).abs() <= ACTIVE_TOLERANCE;
    }
}
