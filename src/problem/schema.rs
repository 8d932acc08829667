//! The problem file as written, before validation. Unknown keys are rejected (those at
//! the top level once the model is known, [`RawProblem::sections`]).

use indexmap::IndexMap;
use serde::de::IgnoredAny;
use serde::Deserialize;

use super::{SAMPLINGS, SOLVERS};
pub use crate::vocab::values::{Number, Quantity};

/// The keys every problem file may have; any other top-level key is a section of the
/// model's ([`crate::model::registry::ModelEntry::sections`]).
pub const COMMON_KEYS: &[&str] = &[
    "name",
    "description",
    "model",
    "variables",
    "objective",
    "constraints",
    "search",
    "zones",
    "refine",
    "tolerances",
];

/// The common part of a problem file; the model reads its own sections.
#[derive(Debug, Deserialize)]
pub struct RawProblem {
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub model: String,
    pub variables: Vec<RawVariable>,
    pub objective: RawObjective,
    #[serde(default)]
    pub constraints: Vec<RawConstraint>,
    #[serde(default)]
    pub search: RawSearch,
    #[serde(default)]
    pub zones: RawZones,
    pub refine: Option<super::refine::RawRefine>,
    #[serde(default)]
    pub tolerances: IndexMap<String, super::tolerances::RawEntry>,
    /// The other top-level keys, in file order: the model's sections, checked against
    /// the model's list before it reads them.
    #[serde(flatten)]
    pub sections: IndexMap<String, IgnoredAny>,
}

/// A variable is fixed (`value`) or free (`lower` and `upper`), never both.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("oneOf" = [
    {"required": ["value"], "not": {"anyOf": [{"required": ["lower"]}, {"required": ["upper"]}]}},
    {"required": ["lower", "upper"], "not": {"required": ["value"]}},
]))]
pub struct RawVariable {
    pub name: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
    pub value: Option<Number>,
}

/// One sense: `maximize` or `minimize`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("oneOf" = [
    {"required": ["maximize"], "not": {"required": ["minimize"]}},
    {"required": ["minimize"], "not": {"required": ["maximize"]}},
]))]
pub struct RawObjective {
    pub maximize: Option<String>,
    pub minimize: Option<String>,
    #[serde(default)]
    pub absolute: bool,
}

/// At least one limit.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("anyOf" = [{"required": ["lower"]}, {"required": ["upper"]}]))]
pub struct RawConstraint {
    pub output: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawSearch {
    #[schemars(extend("minimum" = STARTS.0, "maximum" = STARTS.1))]
    pub starts: Option<i64>,
    #[schemars(extend("minimum" = 0))]
    pub seed: Option<i64>,
    #[schemars(extend("enum" = SOLVERS.names()))]
    pub solver: Option<String>,
    #[schemars(extend("enum" = SAMPLINGS.names()))]
    pub sampling: Option<String>,
    #[schemars(extend("minimum" = TOLERANCE.0, "maximum" = TOLERANCE.1))]
    pub tolerance: Option<Number>,
    #[schemars(extend("minimum" = MAX_ITERATIONS.0, "maximum" = MAX_ITERATIONS.1))]
    pub max_iterations: Option<i64>,
    #[schemars(extend("minimum" = THREADS.0, "maximum" = THREADS.1))]
    pub threads: Option<i64>,
    pub fit_ranges: Option<super::FitRanges>,
    pub robust: Option<RawRobust>,
}

/// `[search] robust`: a yield to reach, or the standard deviations of margin each
/// constraint keeps; one of the two.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("oneOf" = [
    {"required": ["yield"], "not": {"required": ["k_sigma"]}},
    {"required": ["k_sigma"], "not": {"required": ["yield"]}},
]))]
pub struct RawRobust {
    #[serde(rename = "yield")]
    #[schemars(rename = "yield", extend("exclusiveMinimum" = ROBUST_YIELD.0, "exclusiveMaximum" = ROBUST_YIELD.1))]
    pub target_yield: Option<Number>,
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = K_SIGMA_MAX))]
    pub k_sigma: Option<Number>,
}

/// A robust study's yield lies strictly between these.
pub const ROBUST_YIELD: (f64, f64) = (0.5, 1.0);
/// More than 8 standard deviations of margin is a yield of 1 - 1e-15: rounding.
pub const K_SIGMA_MAX: f64 = 8.0;

/// The ranges of `[search]`'s keys (`--starts` and `--threads` take the same).
pub const STARTS: (i64, i64) = (1, 1_000_000);
pub const MAX_ITERATIONS: (i64, i64) = (1, 1_000_000);
pub const THREADS: (i64, i64) = (0, 1024);
/// Below 1e-14 a scaled KKT residual is rounding, which no solve can meet; above 1e-3 a
/// start "converges" where it stands.
pub const TOLERANCE: (f64, f64) = (1e-14, 1e-3);

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawZones {
    /// Each zone boundary once.
    #[schemars(extend("uniqueItems" = true))]
    pub thresholds: Option<Vec<Number>>,
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub x_tolerance: Option<Number>,
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub objective_tolerance: Option<Number>,
    pub merge_mirror_images: Option<bool>,
}
