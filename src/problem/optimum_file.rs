//! A report of `flexopt run` read back (`--optimum optimum.json`): its exact design, once the
//! report is known to be of this problem and model and to say each thing once.

use std::fmt;
use std::path::Path;

use serde::de::{DeserializeSeed, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};

use super::design::{parse_design_with, ParsedDesign};
use super::{Problem, ProblemError};

/// The design of a report written by `flexopt run` (`optimum.json`), read from its
/// `design_si`: the exact values, not their rounding in the file's units.
///
/// Refused: a report of another model or of another problem (by `name`), a key given twice
/// anywhere in it (JSON readers keep either one silently), a design that lacks a variable of
/// `problem` or names one it does not have, and a fixed variable away from its value. Said
/// in a warning: a design the report marks infeasible or unconverged, and a problem file
/// whose content differs from the one the report was written for. A UTF-8 byte-order mark
/// at its start is read past, as the TOML reader does for problem files.
pub fn design_from_optimum(problem: &Problem, path: &Path) -> Result<ParsedDesign, ProblemError> {
    let json = read_report(path)?;
    check_identity(problem, path, &json)?;
    let mut parsed = design_of(problem, path, &json)?;
    add_warnings(problem, path, &json, &mut parsed);
    Ok(parsed)
}

fn error(path: &Path, key: &str, message: String) -> ProblemError {
    ProblemError {
        file: path.to_path_buf(),
        key: key.to_string(),
        position: None,
        message,
    }
}

/// The report at `path` as JSON, each key once in each object.
fn read_report(path: &Path) -> Result<Value, ProblemError> {
    let err = |key: &str, message: String| error(path, key, message);
    let text = crate::vocab::input::read_text(
        path,
        crate::vocab::input::MAX_SET_FILE_BYTES,
        "a report's file",
    )
    .map_err(|e| err("", e))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let mut de = serde_json::Deserializer::from_str(text);
    let json = OnceEach {
        path: String::new(),
    }
    .deserialize(&mut de)
    .and_then(|v| de.end().map(|()| v))
    .map_err(|e| err("", format!("not a report of flexopt: {e}")))?;
    Ok(json)
}

/// Refuses a report of another model or problem.
fn check_identity(problem: &Problem, path: &Path, json: &Value) -> Result<(), ProblemError> {
    let err = |key: &str, message: String| error(path, key, message);
    let report = |key: &str| json.get(key);
    let text_of = |key: &str| -> Result<&str, ProblemError> {
        report(key).and_then(Value::as_str).ok_or_else(|| {
            err(
                key,
                "missing or not a string: not a report of `flexopt run` (optimum.json)".into(),
            )
        })
    };
    let model = problem.model().name();
    let (of_model, of_problem) = (text_of("model")?, text_of("problem")?);
    if of_model != model {
        return Err(err(
            "model",
            format!(
                "the report is of the {of_model} model, {} is of the {model} model",
                problem.file.display()
            ),
        ));
    }
    if of_problem != problem.name {
        return Err(err(
            "problem",
            format!(
                "the report is of the problem \"{of_problem}\", {} is \"{}\"; give its design \
                 with --design to take it for this problem",
                problem.file.display(),
                problem.name
            ),
        ));
    }
    Ok(())
}

/// The report's design, its exact SI values in place.
fn design_of(problem: &Problem, path: &Path, json: &Value) -> Result<ParsedDesign, ProblemError> {
    let err = |key: &str, message: String| error(path, key, message);
    let report = |key: &str| json.get(key);
    let Some(design) = report("design_si").and_then(Value::as_object) else {
        return Err(err(
            "design_si",
            "missing: not a design report of flexopt (optimum.json)".to_string(),
        ));
    };
    if let Some(name) = design
        .keys()
        .find(|name| !problem.variables.iter().any(|v| &v.name == *name))
    {
        return Err(err(
            &format!("design_si.{name}"),
            format!(
                "\"{name}\" is no variable of {}: the report holds a design of another problem",
                problem.file.display()
            ),
        ));
    }
    let mut pairs = Vec::new();
    for v in &problem.variables {
        let Some(value) = design.get(&v.name).and_then(Value::as_f64) else {
            return Err(err(
                &format!("design_si.{}", v.name),
                format!(
                    "missing or not a number: the report does not hold a design of {}",
                    problem.file.display()
                ),
            ));
        };
        pairs.push(format!("{}={}", v.name, v.unit.from_si(value)));
    }
    let mut parsed = parse_design_with(problem, &pairs.join(","), "--optimum", None)?;
    // the exact SI values, not their round trip through the file's units
    for (x, v) in parsed.x.iter_mut().zip(&problem.variables) {
        if let Some(value) = design.get(&v.name).and_then(Value::as_f64) {
            *x = value;
        }
    }
    Ok(parsed)
}

/// The warnings a report's design carries: a changed problem file, an infeasible or
/// unconverged design.
fn add_warnings(problem: &Problem, path: &Path, json: &Value, parsed: &mut ParsedDesign) {
    let report = |key: &str| json.get(key);
    let warning = |what: String| format!("{}: {what}", path.display());
    let hash = format!("{:016x}", problem.fingerprint);
    match report("problem_fnv1a64").and_then(Value::as_str) {
        Some(h) if h == hash => {}
        Some(h) => parsed.warnings.push(warning(format!(
            "{} has changed since the report was written (problem_fnv1a64 {h}, the file now \
             {hash}): the design is taken as it is, for the file as it is now",
            problem.file.display()
        ))),
        None => parsed.warnings.push(warning(format!(
            "the report does not say which content of {} it was written for \
             (problem_fnv1a64): the design is taken as it is",
            problem.file.display()
        ))),
    }
    if report("feasible") == Some(&Value::Bool(false)) {
        let broken: Vec<&str> = report("constraints")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter(|c| c.get("satisfied") == Some(&Value::Bool(false)))
            .filter_map(|c| c.get("output").and_then(Value::as_str))
            .collect();
        let which = if broken.is_empty() {
            String::new()
        } else {
            format!(": it breaks the constraint on {}", broken.join(", "))
        };
        parsed.warnings.push(warning(format!(
            "the report's design is not feasible (\"feasible\": false){which}"
        )));
    }
    if report("converged") == Some(&Value::Bool(false)) {
        parsed.warnings.push(warning(
            "the report's design did not converge (\"converged\": false): it is no optimum"
                .to_string(),
        ));
    }
}

/// A JSON value read so that each object holds each key once: a key given twice is an
/// error that names it, where serde_json's own map would keep the last silently.
struct OnceEach {
    /// Where the value is, `design_si.l2`, for the error.
    path: String,
}

impl OnceEach {
    fn child(&self, key: &str) -> OnceEach {
        let path = if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        };
        OnceEach { path }
    }
}

impl<'de> DeserializeSeed<'de> for OnceEach {
    type Value = Value;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for OnceEach {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }

    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }

    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }

    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(Value::from(v))
    }

    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_string()))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element_seed(OnceEach {
            path: format!("{}[{}]", self.path, items.len()),
        })? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            let child = self.child(&key);
            if object.contains_key(&key) {
                return Err(A::Error::custom(format!(
                    "the key `{}` is given twice",
                    child.path
                )));
            }
            let value = map.next_value_seed(child)?;
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}
