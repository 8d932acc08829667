//! The problem file as written, before validation. Unknown keys are rejected.

use serde::Deserialize;

/// A number as TOML gives it: integer or float.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged)]
pub enum Number {
    Int(i64),
    Float(f64),
}

impl Number {
    pub fn get(self) -> f64 {
        match self {
            Number::Int(i) => i as f64,
            Number::Float(f) => f,
        }
    }
}

/// A dimensional value: `"72 GPa"`. A bare number is read so that the error can say
/// that a unit is missing.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum Quantity {
    Text(String),
    Bare(Number),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProblem {
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub model: String,
    /// Required by the bridge; the 3-PRR model takes none.
    pub material: Option<RawMaterial>,
    pub hinge: Option<RawHinge>,
    pub actuator: Option<RawActuator>,
    /// Masses and damping of the bridge, for its dynamic outputs.
    pub dynamics: Option<RawDynamics>,
    pub variables: Vec<RawVariable>,
    pub objective: RawObjective,
    #[serde(default)]
    pub constraints: Vec<RawConstraint>,
    #[serde(default)]
    pub search: RawSearch,
    #[serde(default)]
    pub zones: RawZones,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    pub preset: Option<String>,
    pub name: Option<String>,
    pub youngs_modulus: Option<Quantity>,
    pub poisson_ratio: Option<Number>,
    pub ultimate_strength: Option<Quantity>,
    pub density: Option<Quantity>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawHinge {
    pub kind: String,
    pub width: Quantity,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawActuator {
    pub nominal_stroke: Quantity,
    pub preload: Quantity,
    pub stiffness: Option<Quantity>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDynamics {
    pub payload_mass: Quantity,
    pub input_link_mass: Quantity,
    pub output_link_mass: Quantity,
    pub link_thickness: Quantity,
    pub damping_ratio: Number,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVariable {
    pub name: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
    pub value: Option<Number>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObjective {
    pub maximize: Option<String>,
    pub minimize: Option<String>,
    #[serde(default)]
    pub absolute: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawConstraint {
    pub output: String,
    pub unit: String,
    pub lower: Option<Number>,
    pub upper: Option<Number>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSearch {
    pub starts: Option<i64>,
    pub seed: Option<i64>,
    pub solver: Option<String>,
    pub sampling: Option<String>,
    pub tolerance: Option<Number>,
    pub max_iterations: Option<i64>,
    pub threads: Option<i64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawZones {
    pub thresholds: Option<Vec<Number>>,
    pub x_tolerance: Option<Number>,
    pub objective_tolerance: Option<Number>,
    pub merge_mirror_images: Option<bool>,
}
