//! Reading a problem file: deserialization with errors that name the key, and the checks
//! of single values (finite numbers, quantities with their units) that every section uses.

use serde::de::DeserializeSeed;

use super::error::{Locator, Segment};
use super::units::{self, parse_quantity};
use super::values::{Choices, Number, Quantity};
use super::Dimension;
use super::ProblemError;

pub(crate) type Res<T> = Result<T, ProblemError>;

/// A key path segment.
pub fn k(key: &str) -> Segment {
    Segment::Key(key.to_string())
}

/// Deserializes the whole text with `seed`, naming the key of any error.
pub(crate) fn deserialize<'de, S: DeserializeSeed<'de>>(
    loc: &Locator,
    text: &'de str,
    seed: S,
) -> Res<S::Value> {
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let key = e.span().map(|s| key_at(text, s.start)).unwrap_or_default();
        loc.error_at(key, e.span(), e.message().trim().to_string())
    })?;
    let mut track = serde_path_to_error::Track::new();
    let result = seed.deserialize(serde_path_to_error::Deserializer::new(de, &mut track));
    result.map_err(|inner| {
        let mut key = track.path().to_string();
        if key == "." {
            key.clear();
        }
        let message = inner.message().trim().to_string();
        // name the offending key itself, not only the table that holds it
        for prefix in ["unknown field `", "missing field `"] {
            if let Some(rest) = message.strip_prefix(prefix) {
                let field = rest
                    .split('`')
                    .next()
                    .filter(|f| !key.ends_with(&format!(".{f}")) && key != *f);
                if let Some(field) = field {
                    key = if key.is_empty() {
                        field.to_string()
                    } else {
                        format!("{key}.{field}")
                    };
                }
            }
        }
        // the value as written, where the parser says where it is
        let written = inner
            .span()
            .and_then(|sp| text.get(sp))
            .map(|w| format!(", got {}", w.trim()))
            .unwrap_or_default();
        let message = if message.contains("untagged enum Number") {
            format!("expected a number{written}")
        } else if message.contains("untagged enum Quantity") {
            "expected a quantity with its unit, e.g. \"10 mm\"".to_string()
        } else if let Some((head, name)) = message.split_once("expected struct ") {
            // the type's name is ours, not the file's: say what the key holds
            format!("{head}expected {}", table_expected(name.trim()))
        } else {
            message
        };
        loc.error_at(key, inner.span(), message)
    })
}

/// What a key read into the struct `name` holds, as the file writes it.
pub(crate) fn table_expected(name: &str) -> &'static str {
    match name {
        "RawTolerance" => {
            "a table of the variable's spread, e.g. { plus_minus = 0.005 } or { sigma = 0.004, \
             distribution = \"uniform\" }"
        }
        "RawRobust" => "a table, { yield = 0.99 } or { k_sigma = 3 }",
        _ => "a table of keys (`flexopt schema` lists them)",
    }
}

/// The key a syntax error at `offset` belongs to, read from the text: the last table
/// header before it and the key of its line (or the header itself, or `(top level)`).
fn key_at(text: &str, offset: usize) -> String {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let line = text[line_start..line_end].trim();
    let strip = |l: &str| l.trim_matches(|c| c == '[' || c == ']').trim().to_string();
    if line.starts_with('[') {
        let header = strip(line);
        return if header.is_empty() {
            "(table header)".to_string()
        } else {
            header
        };
    }
    let header = before[..line_start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .map(strip)
        .filter(|h| !h.is_empty());
    let key = line
        .split('=')
        .next()
        .map(str::trim)
        .filter(|k| !k.is_empty() && !k.starts_with('#'));
    match (header, key) {
        (Some(h), Some(k)) => format!("{h}.{k}"),
        (None, Some(k)) => k.to_string(),
        (Some(h), None) => h,
        (None, None) => "(top level)".to_string(),
    }
}

/// The checks of single values, each error naming the file and the key path.
pub struct Reader<'a, 'b> {
    pub(crate) loc: &'a Locator<'b>,
}

impl Reader<'_, '_> {
    /// An error at the key `path`.
    pub fn err(&self, path: &[Segment], message: impl Into<String>) -> ProblemError {
        self.loc.error(path, message)
    }

    /// What `name` means among `choices`, or an error that names the key and every choice.
    pub fn choice<T: Copy>(&self, path: &[Segment], name: &str, choices: &Choices<T>) -> Res<T> {
        choices.get(name).ok_or_else(|| {
            let what = match path.last() {
                Some(Segment::Key(key)) => key.as_str(),
                _ => "value",
            };
            self.err(
                path,
                format!("unknown {what} \"{name}\"; expected {}", choices.expected()),
            )
        })
    }

    /// A finite number.
    pub fn finite(&self, path: &[Segment], n: Number) -> Res<f64> {
        let v = n.get();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(path, format!("{} is not a finite number", units::short(v))))
        }
    }

    /// A quantity with its unit, in SI.
    pub fn quantity(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        match q {
            Quantity::Text(t) => parse_quantity(t, dim).map_err(|m| self.err(path, m)),
            Quantity::Bare(n) => Err(self.err(
                path,
                format!(
                    "{} has no unit: write it as a string with its unit, one of {}",
                    n.get(),
                    units::accepted(dim)
                ),
            )),
        }
    }

    /// A positive quantity, in SI.
    pub fn positive(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        let v = self.quantity(path, q, dim)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be positive, got {}", show(q))))
        }
    }

    /// A quantity not below zero, in SI.
    pub fn non_negative(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        let v = self.quantity(path, q, dim)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must not be negative, got {}", show(q))))
        }
    }
}

/// A quantity as the file wrote it.
pub fn show(q: &Quantity) -> String {
    match q {
        Quantity::Text(t) => format!("\"{t}\""),
        Quantity::Bare(n) => n.get().to_string(),
    }
}

/// Names in quotes, comma-separated, for messages.
pub fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}
