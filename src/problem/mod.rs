//! Problem files: the TOML schema, its validation, units, and the binding of a model's
//! named outputs to an objective and constraints.
//!
//! The format is documented in the README ("Problem files"); `problems/wei2017.toml` is
//! a complete example.

pub mod design;
pub mod display;
pub mod elastic;
pub mod epigraph;
pub mod fit;
pub mod init;
pub mod json_schema;
pub mod nlp;
pub mod optimum_file;
pub mod part_rules;
pub mod refine;
pub mod schema;
mod strength;
pub mod tolerances;
mod validate;

// the vocabulary of the file, kept reachable where it was read before it moved below the
// models
pub use crate::vocab::{error, reader, sections, units};

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::model::registry::{ModelEntry, MODELS};
use crate::model::{Depiction, Mechanism, Model};
use crate::vocab::values::Choices;
pub use error::ProblemError;
use error::{Locator, Segment};
use units::Unit;

/// The largest problem file [`Problem::load`] reads (1 MiB).
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// A design variable: one model parameter, free within bounds or fixed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Variable {
    pub name: String,
    /// Index among the model's parameters.
    pub parameter: usize,
    /// The unit the file uses for this variable.
    #[serde(skip)]
    pub unit: Unit,
    /// SI bounds, or the SI value twice for a fixed variable.
    pub lower: f64,
    pub upper: f64,
    pub fixed: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    Maximize,
    Minimize,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Objective {
    pub output: String,
    /// Index among the model's outputs.
    #[serde(skip)]
    pub index: usize,
    pub sense: Sense,
    /// Optimize the absolute value of the output.
    pub absolute: bool,
}

/// `lower <= output <= upper`, SI; at least one limit is present.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Constraint {
    pub output: String,
    #[serde(skip)]
    pub index: usize,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    /// The unit the file uses, for reports.
    #[serde(skip)]
    pub unit: Unit,
    /// Whether the yield counts it (`[tolerances] yield_of`, every constraint by default):
    /// the Monte Carlo's yield and a robust study's margins.
    #[serde(skip)]
    pub in_yield: bool,
}

/// The size a limit's relative margins and violations are measured against: the limit's
/// own, or 1 for a limit of zero.
pub fn limit_scale(limit: f64) -> f64 {
    if limit == 0.0 {
        1.0
    } else {
        limit.abs()
    }
}

impl Constraint {
    /// The distance from `value` to the nearest limit (positive inside) and that limit's
    /// [`limit_scale`].
    pub fn nearest_limit(&self, value: f64) -> Option<(f64, f64)> {
        [
            self.lower.map(|lo| (value - lo, lo)),
            self.upper.map(|hi| (hi - value, hi)),
        ]
        .into_iter()
        .flatten()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(margin, limit)| (margin, limit_scale(limit)))
    }

    /// The distance from `value` to the nearest limit in standard deviations `std` of the
    /// output (infinite, of the margin's sign, for an output nothing moves).
    pub fn margin_in_sigma(&self, value: f64, std: f64) -> f64 {
        let margin = self.nearest_limit(value).map_or(f64::INFINITY, |(m, _)| m);
        if std > 0.0 {
            margin / std
        } else {
            margin.signum() * f64::INFINITY
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Solver {
    Sqp,
    NelderMead,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sampling {
    Uniform,
    LatinHypercube,
}

/// `search.solver` and `--solver`; the first is the default.
pub const SOLVERS: Choices<Solver> =
    Choices(&[("sqp", Solver::Sqp), ("nelder-mead", Solver::NelderMead)]);

/// `search.sampling`; the first is the default.
pub const SAMPLINGS: Choices<Sampling> = Choices(&[
    ("uniform", Sampling::Uniform),
    ("latin-hypercube", Sampling::LatinHypercube),
]);

/// What the study does with designs outside the ranges where the model's formulas hold
/// (a notch hinge's t/r at most 1, say; the guide's Hinges chapter lists them).
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum FitRanges {
    /// The ranges are constraints of the study; eval and run warn of a design outside them
    /// (the default).
    #[default]
    Constraint,
    /// The study may leave the ranges; eval and run warn of a design outside them.
    Warn,
    /// The study may leave the ranges, and nothing warns of it.
    Allow,
}

/// How the multistart search runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SearchSettings {
    pub starts: usize,
    pub seed: u64,
    pub solver: Solver,
    pub sampling: Sampling,
    /// Stopping tolerance of the local solver (KKT residual, scaled).
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
    /// Designs outside the model's ranges of fit: constraints, warnings or neither.
    pub fit_ranges: FitRanges,
    /// `robust`: each constraint kept this many first-order standard deviations inside its
    /// limits ([`tolerances`]); `None` for the nominal study.
    pub robust: Option<Robust>,
}

/// A robust study's margins: `k_sigma` standard deviations on every limit, given or made
/// from a target yield.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Robust {
    pub k_sigma: f64,
    /// The yield the file asked for, where it asked for one.
    #[serde(rename = "yield", skip_serializing_if = "Option::is_none")]
    pub target_yield: Option<f64>,
}

/// How optima are merged and sorted into zones.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZoneSettings {
    /// Objective thresholds between zones, descending; empty: zones from gaps.
    pub thresholds: Vec<f64>,
    /// Optima closer than this in design space scaled to the bounds are one optimum.
    pub x_tolerance: f64,
    /// ... and whose objectives differ by less than this, relative.
    pub objective_tolerance: f64,
    /// Count a design and its mirror image (all angles negated) as one geometry.
    pub merge_mirror_images: bool,
}

/// A validated problem, SI units inside.
#[derive(Debug, Clone)]
pub struct Problem {
    pub file: PathBuf,
    pub name: String,
    pub description: String,
    /// The mechanism (its physics and capabilities), configured by its sections of the file.
    pub mechanism: Mechanism,
    /// One per model parameter, in model order.
    pub variables: Vec<Variable>,
    pub objective: Objective,
    pub constraints: Vec<Constraint>,
    pub search: SearchSettings,
    pub zones: ZoneSettings,
    /// `[refine]`: the FE refinement of `run`'s optimum.
    pub refine: refine::RefineSettings,
    /// `[tolerances]`, with the process's defaults: what a made part's inputs scatter by.
    pub tolerances: Vec<tolerances::Tolerance>,
    /// The file's content as data, hashed ([`fingerprint`]): reports record it, so that a
    /// design read back from one can tell whether the file changed since.
    pub fingerprint: u64,
}

/// FNV-1a (64 bits) of the problem file's content as data: its keys sorted, its comments and
/// layout aside, so two files that say the same hash alike and a changed value shows.
pub fn fingerprint(text: &str) -> u64 {
    use std::hash::Hasher;
    let data = toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|t| serde_json::to_string(&t).ok())
        .unwrap_or_else(|| text.to_string());
    let mut h = fnv::FnvHasher::default();
    h.write(data.as_bytes());
    h.finish()
}

/// The text of the problem file at `path`, at most [`MAX_FILE_BYTES`] of it: the error a
/// sentence without the path.
pub fn read_problem_text(path: &Path) -> Result<String, String> {
    crate::vocab::input::read_text(path, MAX_FILE_BYTES, "a problem file")
}

impl Problem {
    /// Reads and validates a problem file.
    pub fn load(path: &Path) -> Result<Problem, ProblemError> {
        let fail = |message: String| ProblemError {
            file: path.to_path_buf(),
            key: String::new(),
            position: None,
            message,
        };
        // refused before it is parsed: a problem file is a few kilobytes, and parsing a huge
        // one takes seconds and gigabytes before its first error
        let text = read_problem_text(path).map_err(fail)?;
        Self::parse(path, &text)
    }

    /// Validates the text of a problem file; `path` names it in errors.
    pub fn parse(path: &Path, text: &str) -> Result<Problem, ProblemError> {
        Self::parse_with(MODELS, path, text)
    }

    /// As [`Problem::parse`], choosing the model among `models` instead of the registry's.
    pub fn parse_with(
        models: &[ModelEntry],
        path: &Path,
        text: &str,
    ) -> Result<Problem, ProblemError> {
        let loc = Locator::new(path, text);
        let raw: schema::RawProblem = reader::deserialize(&loc, text, std::marker::PhantomData)?;
        validate::Validator {
            reader: reader::Reader { loc: &loc },
            text,
            models,
        }
        .problem(raw)
    }

    /// The error of a command that would meet the objective or a constraint on an output
    /// only a higher fidelity gives ([`crate::model::OutputInfo::stand_in`]) by the model's
    /// stand-in alone, naming the first such key; `doing` is what the command does.
    pub fn stand_in_error(&self, doing: &str) -> Option<ProblemError> {
        let outputs = self.model().outputs();
        let key = match self.objective.sense {
            Sense::Maximize => "objective.maximize".to_string(),
            Sense::Minimize => "objective.minimize".to_string(),
        };
        std::iter::once((key, self.objective.index))
            .chain(
                self.constraints
                    .iter()
                    .enumerate()
                    .map(|(i, c)| (format!("constraints[{i}].output"), c.index)),
            )
            .find_map(|(key, i)| {
                let what = outputs[i].stand_in?;
                Some(ProblemError {
                    file: self.file.clone(),
                    key,
                    position: None,
                    message: format!(
                        "\"{}\" is measured by the part's finite elements only (the model's \
                         value is {what}): {doing} would meet it with the model's value alone; \
                         refine against the finite elements (run --refine fe, or [refine] \
                         fidelity = \"fe\")",
                        outputs[i].name
                    ),
                })
            })
    }

    /// The mechanism's physics.
    pub fn model(&self) -> &dyn Model {
        self.mechanism.physics.as_ref()
    }

    /// The mechanism: its physics, pictures and part.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// The pictures of the mechanism's designs (every default where it has none).
    pub fn depiction(&self) -> &dyn Depiction {
        self.mechanism.depiction()
    }

    /// The design `x` (SI, every parameter) in the file's units, by variable name: how
    /// every report writes a design.
    pub fn design_in_file_units(&self, x: &[f64]) -> indexmap::IndexMap<String, f64> {
        self.variables
            .iter()
            .zip(x)
            .map(|(v, &xi)| (v.name.clone(), v.unit.from_si(xi)))
            .collect()
    }

    /// The free variables, in model order.
    pub fn free_variables(&self) -> impl Iterator<Item = &Variable> {
        self.variables.iter().filter(|v| !v.fixed)
    }

    /// The folder a run writes to by default: `results/<name>/`.
    pub fn default_output_dir(&self) -> PathBuf {
        Path::new("results").join(&self.name)
    }
}
