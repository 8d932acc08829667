//! Curves of model outputs against one design variable, the others held at a base design.

use indexmap::IndexMap;

use serde::Serialize;

use crate::problem::display::human;
use crate::problem::{Problem, ProblemError};

/// The most points a sweep computes.
pub const MAX_STEPS: usize = 100_000;

/// What to sweep, in the problem file's units.
#[derive(Debug, Clone)]
pub struct SweepSpec {
    pub variable: String,
    pub from: f64,
    pub to: f64,
    pub steps: usize,
    /// Outputs to record; empty for all.
    pub outputs: Vec<String>,
}

/// The result of a sweep.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    pub problem: String,
    pub variable: String,
    pub unit: String,
    /// The swept values, in `unit`.
    pub values: Vec<f64>,
    /// The base design, variable -> value in the file's units.
    pub around: IndexMap<String, f64>,
    /// Output -> values (SI), `null` where the model gives no finite number.
    pub outputs: IndexMap<String, Vec<Option<f64>>>,
    /// Output -> SI unit.
    pub output_units: IndexMap<String, String>,
    /// Output -> the unit the plot shows it in (its constraint's, else the designer's
    /// usual one), and that unit's factor to SI.
    pub display_units: IndexMap<String, String>,
    #[serde(skip)]
    pub display_to_si: IndexMap<String, f64>,
    /// Output -> its constraint's limits (SI), where the problem constrains it.
    pub limits: IndexMap<String, [Option<f64>; 2]>,
    /// Output -> its value at the base design (SI).
    pub at_around: IndexMap<String, Option<f64>>,
    /// The part's rule -> its margin (mm) at each point, where the model's part states
    /// rules ([`crate::model::part_rules`]): negative where the part breaks it.
    #[serde(skip_serializing_if = "IndexMap::is_empty")]
    pub part_rules: IndexMap<String, Vec<Option<f64>>>,
    /// Order of the outputs as the model lists them.
    #[serde(skip)]
    pub order: Vec<String>,
}

impl Sweep {
    /// Which points gave no value of some output (the model gives no finite number there,
    /// or the point lies in a hole of its domain), as a sentence, if any did: those values
    /// are `null` in the JSON and gaps in the plot.
    pub fn gaps(&self) -> Option<String> {
        let missing = |i: usize| self.outputs.values().any(|c| c[i].is_none());
        let points: Vec<usize> = (0..self.values.len()).filter(|&i| missing(i)).collect();
        if points.is_empty() {
            return None;
        }
        let outputs: Vec<&str> = self
            .outputs
            .iter()
            .filter(|(_, c)| c.iter().any(Option::is_none))
            .map(|(name, _)| name.as_str())
            .collect();
        let list = |items: Vec<String>| {
            let more = items.len().saturating_sub(GAPS_LISTED);
            let mut text = items[..items.len() - more].join(", ");
            if more > 0 {
                text += &format!(" and {more} more");
            }
            text
        };
        let at = list(points.iter().map(|&i| human(self.values[i])).collect());
        Some(format!(
            "the model gives no value of {} of {} outputs ({}) at {} of {} points, {} = {at} \
             {}: they are null in the JSON and gaps in the plot",
            outputs.len(),
            self.outputs.len(),
            list(outputs.iter().map(|o| o.to_string()).collect()),
            points.len(),
            self.values.len(),
            self.variable,
            self.unit
        ))
    }
}

/// How many points or outputs [`Sweep::gaps`] names before it counts the rest.
const GAPS_LISTED: usize = 5;

/// Sweeps `spec.variable` with every other variable at `base` (full design, SI).
/// Values outside the variable's bounds are allowed: a sweep explores the model.
pub fn sweep(problem: &Problem, spec: &SweepSpec, base: &[f64]) -> Result<Sweep, ProblemError> {
    let err = |key: &str, message: String| ProblemError {
        file: problem.file.clone(),
        key: key.into(),
        position: None,
        message,
    };
    let Some(vi) = problem
        .variables
        .iter()
        .position(|v| v.name == spec.variable)
    else {
        let names: Vec<_> = problem.variables.iter().map(|v| v.name.as_str()).collect();
        return Err(err(
            "--param",
            format!(
                "unknown variable \"{}\"; expected one of {}",
                spec.variable,
                names.join(", ")
            ),
        ));
    };
    let var = &problem.variables[vi];
    let model = problem.model();
    check_range(spec.from, spec.to, spec.steps, MAX_STEPS).map_err(|(k, m)| err(k, m))?;
    // one rule for every variable: each point of the range lies in the model's domain (a
    // length past zero and an angle past a right angle alike), else nothing is computed
    let mut x = base.to_vec();
    for (key, v) in [("--from", spec.from), ("--to", spec.to)] {
        x[var.parameter] = var.unit.to_si(v);
        if let Some(why) = model.domain_error(&x) {
            return Err(err(
                key,
                format!(
                    "{} = {} {} lies outside the model's domain around this design: {why}",
                    var.name,
                    crate::vocab::units::short(v),
                    var.unit.name
                ),
            ));
        }
    }
    let wanted: Vec<usize> = if spec.outputs.is_empty() {
        model.analytic_outputs()
    } else {
        spec.outputs
            .iter()
            .map(|name| {
                let i = model.output_index(name).ok_or_else(|| {
                    let names: Vec<_> = model.outputs().iter().map(|o| o.name.as_ref()).collect();
                    err(
                        "--outputs",
                        format!(
                            "unknown output \"{name}\"; expected one of {}",
                            names.join(", ")
                        ),
                    )
                })?;
                match (model.unavailable(i), model.outputs()[i].stand_in) {
                    (Some(why), _) => Err(err("--outputs", why)),
                    (None, Some(what)) => Err(err(
                        "--outputs",
                        format!(
                            "output \"{name}\" is measured by the part's finite elements \
                             only (the model's value is {what}); `verify` measures it"
                        ),
                    )),
                    (None, None) => Ok(i),
                }
            })
            .collect::<Result<_, _>>()?
    };
    let values: Vec<f64> = (0..spec.steps)
        .map(|i| spec.from + (spec.to - spec.from) * i as f64 / (spec.steps - 1) as f64)
        .collect();
    let mut curves = vec![Vec::with_capacity(values.len()); wanted.len()];
    let mut out = vec![0.0; wanted.len()];
    let part = problem.mechanism().part_maker.as_deref();
    let rules = part.map_or(&[][..], |p| p.rules());
    let mut margins = vec![Vec::with_capacity(values.len()); rules.len()];
    let mut m = vec![0.0; rules.len()];
    for &v in &values {
        x[var.parameter] = var.unit.to_si(v);
        if model.domain_error(&x).is_some() {
            // a hole in the domain between the ends (a singular configuration): a gap in
            // the curve, never a number
            out.fill(f64::NAN);
            m.fill(f64::NAN);
        } else {
            model.evaluate(&x, &wanted, &mut out);
            if let Some(part) = part {
                part.rule_margins(&x, &mut m);
            }
        }
        for (curve, &y) in curves.iter_mut().zip(&out) {
            curve.push(y.is_finite().then_some(y));
        }
        for (curve, &y) in margins.iter_mut().zip(&m) {
            curve.push(y.is_finite().then_some(y * crate::part::MM));
        }
    }
    let infos = model.outputs();
    let mut at = vec![f64::NAN; wanted.len()];
    if model.domain_error(base).is_none() {
        model.evaluate(base, &wanted, &mut at);
    }
    let display: Vec<crate::problem::units::Unit> = wanted
        .iter()
        .map(|&k| crate::problem::display::output_unit(problem, k))
        .collect();
    let name = |k: usize| infos[k].name.to_string();
    Ok(Sweep {
        display_units: wanted
            .iter()
            .zip(&display)
            .map(|(&k, u)| (name(k), u.name.clone()))
            .collect(),
        display_to_si: wanted
            .iter()
            .zip(&display)
            .map(|(&k, u)| (name(k), u.to_si))
            .collect(),
        limits: problem
            .constraints
            .iter()
            .filter(|c| wanted.contains(&c.index))
            .map(|c| (name(c.index), [c.lower, c.upper]))
            .collect(),
        at_around: wanted
            .iter()
            .zip(&at)
            .map(|(&k, &v)| (name(k), v.is_finite().then_some(v)))
            .collect(),
        problem: problem.name.clone(),
        variable: var.name.clone(),
        unit: var.unit.name.clone(),
        values,
        around: problem
            .variables
            .iter()
            .zip(base)
            .map(|(v, &b)| (v.name.clone(), v.unit.from_si(b)))
            .collect(),
        outputs: wanted
            .iter()
            .zip(curves)
            .map(|(&k, c)| (infos[k].name.to_string(), c))
            .collect(),
        output_units: wanted
            .iter()
            .map(|&k| {
                (
                    infos[k].name.to_string(),
                    infos[k].dimension.si_unit().to_string(),
                )
            })
            .collect(),
        part_rules: rules
            .iter()
            .zip(margins)
            .map(|(r, c)| (r.name.to_string(), c))
            .collect(),
        order: wanted.iter().map(|&k| infos[k].name.to_string()).collect(),
    })
}

/// Checks the stepped range of a command (`--from`, `--to`, `--steps`): at least 2 and at
/// most `max_steps` steps over a finite, non-empty range. On failure, the option at fault
/// and why.
pub fn check_range(
    from: f64,
    to: f64,
    steps: usize,
    max_steps: usize,
) -> Result<(), (&'static str, String)> {
    if steps < 2 || steps > max_steps {
        let most = if max_steps == usize::MAX {
            String::new()
        } else {
            format!(" and at most {max_steps}")
        };
        return Err((
            "--steps",
            format!("needs at least 2 steps{most}, got {steps}"),
        ));
    }
    if !(from.is_finite() && to.is_finite()) || from == to {
        return Err((
            "--from",
            format!("the range {from} to {to} is empty or not finite"),
        ));
    }
    Ok(())
}
