//! Designs written on the command line: `l2=1.96,delta2=4.07,...` in the file's units.

pub use super::optimum_file::design_from_optimum;
use super::{Problem, ProblemError};
use crate::vocab::units::short;

/// A full design (every model parameter, SI) read from `name=value` pairs, with a
/// warning for each value outside its variable's bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct ParsedDesign {
    pub x: Vec<f64>,
    pub warnings: Vec<String>,
}

/// Reads `text` (`--design`) against `problem`. Fixed variables may be left out; every free
/// one must be given. Values are in the units the problem file gives each variable.
pub fn parse_design(problem: &Problem, text: &str) -> Result<ParsedDesign, ProblemError> {
    parse_design_with(problem, text, "--design", None)
}

/// Reads the design a sweep holds the other variables at (`--around`): any variable left
/// out takes its value in [`default_design`].
pub fn parse_around(problem: &Problem, text: &str) -> Result<ParsedDesign, ProblemError> {
    let base = default_design(problem);
    parse_design_with(problem, text, "--around", Some(&base))
}

/// The design a sweep runs around when none is given: fixed variables at their values, free
/// ones at the middle of their bounds, except an angle whose bounds straddle zero, which
/// takes the middle of its positive part. The middle of a symmetric angle range is zero,
/// where a mechanism such as the bridge is flat and amplifies nothing.
pub fn default_design(problem: &Problem) -> Vec<f64> {
    let params = problem.model().parameters();
    problem
        .variables
        .iter()
        .map(|v| {
            let angle = params[v.parameter].dimension == crate::model::Dimension::Angle;
            if angle && v.lower < 0.0 && v.upper > 0.0 {
                0.5 * v.upper
            } else {
                0.5 * (v.lower + v.upper)
            }
        })
        .collect()
}

pub(super) fn parse_design_with(
    problem: &Problem,
    text: &str,
    option: &str,
    defaults: Option<&[f64]>,
) -> Result<ParsedDesign, ProblemError> {
    let err = |key: &str, message: String| ProblemError {
        file: problem.file.clone(),
        key: format!("{option} {key}").trim_end().to_string(),
        position: None,
        message,
    };
    let mut given: Vec<Option<f64>> = vec![None; problem.variables.len()];
    for pair in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let Some((name, value)) = pair.split_once('=') else {
            return Err(err("", format!("\"{pair}\" is not of the form name=value")));
        };
        let (name, value) = (name.trim(), value.trim());
        let Some(i) = problem.variables.iter().position(|v| v.name == name) else {
            let names: Vec<_> = problem.variables.iter().map(|v| v.name.as_str()).collect();
            return Err(err(
                name,
                format!(
                    "unknown variable \"{name}\"; expected one of {}",
                    names.join(", ")
                ),
            ));
        };
        let v: f64 = value
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| err(name, format!("\"{value}\" is not a finite number")))?;
        if given[i].is_some() {
            return Err(err(name, format!("\"{name}\" is given twice")));
        }
        given[i] = Some(problem.variables[i].unit.to_si(v));
    }
    let mut x = Vec::with_capacity(given.len());
    let mut warnings = Vec::new();
    for (i, (var, g)) in problem.variables.iter().zip(given).enumerate() {
        let value = match (g, var.fixed) {
            (Some(v), _) => v,
            (None, true) => var.lower,
            (None, false) if defaults.is_some() => defaults.map_or(var.lower, |d| d[i]),
            (None, false) => {
                return Err(err(
                    &var.name,
                    format!(
                        "missing: the design must give the free variable \"{}\"",
                        var.name
                    ),
                ))
            }
        };
        let tol = 1e-12 * var.upper.abs().max(var.lower.abs());
        if value < var.lower - tol || value > var.upper + tol {
            let u = &var.unit;
            warnings.push(if var.fixed {
                format!(
                    "{} = {} {} differs from its fixed value {} {}",
                    var.name,
                    short(u.from_si(value)),
                    u.name,
                    short(u.from_si(var.lower)),
                    u.name
                )
            } else {
                format!(
                    "{} = {} {} lies outside its bounds [{}, {}] {}",
                    var.name,
                    short(u.from_si(value)),
                    u.name,
                    short(u.from_si(var.lower)),
                    short(u.from_si(var.upper)),
                    u.name
                )
            });
        }
        x.push(value);
    }
    Ok(ParsedDesign { x, warnings })
}
