//! The values a problem file writes: plain numbers and quantities with their units.

use serde::Deserialize;

/// A number as TOML gives it: integer or float.
#[derive(Debug, Clone, Copy, Deserialize, schemars::JsonSchema)]
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
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Quantity {
    Text(String),
    Bare(Number),
}
