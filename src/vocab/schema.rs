//! The JSON Schema of the vocabulary's values, made from the tables the reader checks them
//! against: numbers as Rust reads them, each dimension's units, the signs a key allows.
//! A raw section states what a quantity key takes by its type ([`Measured`]), and the
//! reader and the schema both read it from there.

use std::borrow::Cow;
use std::marker::PhantomData;

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Deserialize;

use super::error::Segment;
use super::reader::{Reader, Res};
use super::units;
use super::values::Quantity;
use super::Dimension;

/// What sign a quantity key allows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sign {
    Positive,
    NonNegative,
}

/// A quantity key's dimension and sign, as a type: see [`Measured`].
pub trait Measure {
    const DIMENSION: Dimension;
    const SIGN: Sign;
    /// Its name among the schema's definitions.
    const NAME: &'static str;
    /// How the schema describes it.
    const WHAT: &'static str;
}

/// A quantity as written (`"10 mm"`), of the dimension and sign that `M` states: the reader
/// converts it by them ([`Reader::measured`]), the schema gives their pattern.
#[derive(Debug, Clone, Deserialize)]
#[serde(transparent)]
pub struct Measured<M> {
    pub written: Quantity,
    #[serde(skip)]
    measure: PhantomData<M>,
}

impl<M: Measure> JsonSchema for Measured<M> {
    fn schema_name() -> Cow<'static, str> {
        M::NAME.into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        quantity_schema(M::DIMENSION, M::SIGN, M::WHAT)
    }
}

impl Reader<'_, '_> {
    /// A quantity key in SI, by the dimension and sign its type states.
    pub fn measured<M: Measure>(&self, path: &[Segment], q: &Measured<M>) -> Res<f64> {
        match M::SIGN {
            Sign::Positive => self.positive(path, &q.written, M::DIMENSION),
            Sign::NonNegative => self.non_negative(path, &q.written, M::DIMENSION),
        }
    }

    /// [`Sections::measured`] of an optional key, or `or` where the file leaves it out.
    pub fn measured_or<M: Measure>(
        &self,
        path: &[Segment],
        q: &Option<Measured<M>>,
        or: f64,
    ) -> Res<f64> {
        q.as_ref().map_or(Ok(or), |q| self.measured(path, q))
    }
}

macro_rules! measures {
    ($($name:ident = $dim:ident, $sign:ident, $what:literal;)*) => {$(
        #[doc = concat!("A ", $what, ".")]
        #[derive(Debug, Clone)]
        pub struct $name;

        impl Measure for $name {
            const DIMENSION: Dimension = Dimension::$dim;
            const SIGN: Sign = Sign::$sign;
            const NAME: &'static str = stringify!($name);
            const WHAT: &'static str = $what;
        }
    )*};
}

measures! {
    PositiveLength = Length, Positive, "length above zero with its unit, e.g. \"10 mm\"";
    NonNegativeLength = Length, NonNegative, "length of zero or more with its unit, e.g. \"0.5 mm\"";
    PositiveStress = Stress, Positive, "stress above zero with its unit, e.g. \"72 GPa\"";
    NonNegativeForce = Force, NonNegative, "force of zero or more with its unit, e.g. \"40 N\"";
    PositiveStiffness = Stiffness, Positive, "stiffness above zero with its unit, e.g. \"7 N/um\"";
    NonNegativeMass = Mass, NonNegative, "mass of zero or more with its unit, e.g. \"10 g\"";
}

/// A finite number as Rust reads one (`1`, `-2.5`, `.5`, `1e-3`), for patterns.
pub const NUMBER: &str = r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?";

/// A number above zero as written (its size in SI aside).
const POSITIVE: &str =
    r"\+?(?:[0-9]*[1-9][0-9]*\.?[0-9]*|[0-9]*\.[0-9]*[1-9][0-9]*)(?:[eE][+-]?[0-9]+)?";

/// A number of zero or more as written: `-0` is zero.
const NON_NEGATIVE: &str =
    r"(?:\+?(?:[0-9]+\.?[0-9]*|\.[0-9]+)|-(?:0+\.?0*|\.0+))(?:[eE][+-]?[0-9]+)?";

/// `text` with the characters a pattern gives a meaning escaped.
pub fn escaped(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let special = "\\^$.|?*+()[]{}/".contains(c);
            special.then_some('\\').into_iter().chain([c])
        })
        .collect()
}

/// The pattern of a quantity with `sign` written as [`units::parse_quantity`] reads it: a
/// number, white space, one of `units` (or none, where the empty unit of a plain ratio is
/// one of them).
pub fn quantity_pattern(sign: Sign, units: &[&str]) -> String {
    let number = match sign {
        Sign::Positive => POSITIVE,
        Sign::NonNegative => NON_NEGATIVE,
    };
    let names: Vec<String> = units
        .iter()
        .filter(|u| !u.is_empty())
        .map(|u| escaped(u))
        .collect();
    let unit = format!(r"\s+(?:{})", names.join("|"));
    let unit = if units.contains(&"") {
        format!("(?:{unit})?")
    } else {
        unit
    };
    format!(r"^\s*{number}{unit}\s*$")
}

fn quantity_schema(dimension: Dimension, sign: Sign, what: &str) -> Schema {
    json_schema!({
        "type": "string",
        "pattern": quantity_pattern(sign, &units::names(dimension)),
        "description": format!("A {what}; units: {}", units::accepted(dimension)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_accept_what_the_reader_accepts() {
        let re = |d, s| {
            let schema = serde_json::json!({"pattern": quantity_pattern(s, &units::names(d))});
            jsonschema::validator_for(&schema).unwrap()
        };
        let is = |v: &jsonschema::Validator, text: &str| v.is_valid(&serde_json::json!(text));
        let length = re(Dimension::Length, Sign::Positive);
        let non_negative = re(Dimension::Length, Sign::NonNegative);
        for text in ["10 mm", " 0.5  um ", "1e-3 m", ".5 mm", "5. mm", "+2 cm"] {
            assert!(is(&length, text), "{text}");
            assert!(
                units::parse_quantity(text, Dimension::Length).is_ok(),
                "{text}"
            );
        }
        for text in [
            "0 mm", "-1 mm", "10mm", "10 kg", "mm", "10", "inf mm", "0.0e5 mm",
        ] {
            assert!(!is(&length, text), "{text}");
        }
        assert!(is(&non_negative, "0 mm") && is(&non_negative, "-0 mm"));
        assert!(!is(&non_negative, "-0.1 mm"));
        let torque = re(Dimension::RotationalStiffness, Sign::Positive);
        assert!(is(&torque, "34.5 N*m/rad") && is(&torque, "3 N m/rad"));
        assert!(!is(&torque, "3 NXm/rad"));
    }
}
