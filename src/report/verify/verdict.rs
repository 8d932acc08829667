//! The verdict on a design from the highest fidelity of its FE check that ran: each
//! constraint read on the part, the ones it fails listed with their value, limit and
//! fidelity, the ones the part's check does not measure marked "model only".

use serde::Serialize;

use super::{fidelities, significant};
use crate::fe::verify::Verification;
use crate::fe::Fidelity;
use crate::part::analysis::FeCounterpart;
use crate::problem::Problem;

/// A constraint the part fails.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PartFailure {
    pub constraint: String,
    /// The value on the part, in the model's (SI) units.
    pub value: f64,
    /// The limit it breaks, in the same units.
    pub limit: f64,
    pub fidelity: Fidelity,
    /// The same in the file's units: `stroke_out = 142.8 µm on the part (3D), limit >= 150 µm`.
    pub shown: String,
}

/// How the check judges the design.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// The fidelity the constraints are read in: 3D where it ran, else the one the plate's
    /// width over its thinnest hinge calls for.
    pub fidelity: Fidelity,
    /// The constraints the part fails in that fidelity.
    pub fails: Vec<PartFailure>,
    /// The constraints the part's check does not measure: judged by the model only.
    pub model_only: Vec<String>,
}

impl Verdict {
    pub fn new(problem: &Problem, v: &Verification, read: Fidelity) -> Self {
        let ran = fidelities(v);
        let fidelity = [Fidelity::Solid, read]
            .into_iter()
            .find(|f| ran.iter().any(|(g, _, _)| g == f))
            .or_else(|| ran.first().map(|(f, _, _)| *f))
            .unwrap_or(read);
        let mechanism = problem.mechanism();
        let value = |output: usize| match mechanism.fe_counterpart(output)? {
            FeCounterpart::ActuationForce => v.actuation_force_of(fidelity),
            FeCounterpart::Output(id) => v
                .outputs(fidelity)?
                .iter()
                .find(|o| o.id == id)
                .map(|o| o.estimate.value),
        };
        let mut fails = Vec::new();
        let mut model_only: Vec<String> = Vec::new();
        for c in &problem.constraints {
            let Some(x) = value(c.index) else {
                if !model_only.contains(&c.output) {
                    model_only.push(c.output.clone());
                }
                continue;
            };
            let broken = [c.lower.filter(|&lo| x < lo), c.upper.filter(|&hi| x > hi)];
            if let Some(limit) = broken.into_iter().flatten().next() {
                let scale = c.unit.to_si;
                let sense = if x < limit { ">=" } else { "<=" };
                fails.push(PartFailure {
                    constraint: c.output.clone(),
                    value: x,
                    limit,
                    fidelity,
                    shown: format!(
                        "{} = {} {unit} on the part ({}), limit {sense} {} {unit}",
                        c.output,
                        significant(x / scale, 4),
                        fidelity.name(),
                        significant(limit / scale, 4),
                        unit = c.unit.name
                    ),
                });
            }
        }
        Verdict {
            fidelity,
            fails,
            model_only,
        }
    }
}
