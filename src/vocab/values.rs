//! The values a problem file writes: plain numbers and quantities with their units.

use serde::Deserialize;

/// The names a key may take, each with what it means: one table for the reader, the
/// schema's `enum` and the command line's choices.
pub struct Choices<T: 'static>(pub &'static [(&'static str, T)]);

impl<T: Copy> Choices<T> {
    /// What `name` means, if it is one of the names.
    pub fn get(&self, name: &str) -> Option<T> {
        self.0.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
    }

    pub fn names(&self) -> Vec<&'static str> {
        self.0.iter().map(|(n, _)| *n).collect()
    }

    /// The names for a message: `"a" or "b"`.
    pub fn expected(&self) -> String {
        self.0
            .iter()
            .map(|(n, _)| format!("\"{n}\""))
            .collect::<Vec<_>>()
            .join(" or ")
    }
}

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

// In the schema a number is a JSON number (TOML's nan and inf have no JSON form, and the
// reader refuses them), a quantity a string: the bare number is read only to be refused.
impl schemars::JsonSchema for Number {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Number".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({"type": "number", "description": "A finite number."})
    }
}

impl schemars::JsonSchema for Quantity {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Quantity".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "type": "string",
            "description": "A quantity with its unit, e.g. \"10 mm\"."
        })
    }
}
