//! The problem file as written, before validation. Unknown keys are rejected (those at
//! the top level once the model is known, [`RawProblem::sections`]).

use indexmap::IndexMap;
use serde::de::IgnoredAny;
use serde::Deserialize;

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
    /// The other top-level keys, in file order: the model's sections, checked against
    /// the model's list before it reads them.
    #[serde(flatten)]
    pub sections: IndexMap<String, IgnoredAny>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawVariable {
    pub name: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
    pub value: Option<Number>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawObjective {
    pub maximize: Option<String>,
    pub minimize: Option<String>,
    #[serde(default)]
    pub absolute: bool,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawConstraint {
    pub output: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawSearch {
    pub starts: Option<i64>,
    pub seed: Option<i64>,
    pub solver: Option<String>,
    pub sampling: Option<String>,
    pub tolerance: Option<Number>,
    pub max_iterations: Option<i64>,
    pub threads: Option<i64>,
    pub fit_ranges: Option<super::FitRanges>,
}

#[derive(Debug, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawZones {
    pub thresholds: Option<Vec<Number>>,
    pub x_tolerance: Option<Number>,
    pub objective_tolerance: Option<Number>,
    pub merge_mirror_images: Option<bool>,
}
