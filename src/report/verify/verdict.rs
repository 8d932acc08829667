//! The verdict on a design from the highest fidelity of its FE check that ran: each
//! constraint read on the part, the ones it fails listed with their value, limit and
//! fidelity, the ones the part's check does not measure marked "model only".

use std::fmt::{self, Display};

use indexmap::IndexMap;
use serde::Serialize;

use super::{fidelities, significant, value as model_value, OutputReport};
use crate::fe::verify::Verification;
use crate::fe::Fidelity;
use crate::part::analysis::FeCounterpart;
use crate::problem::Problem;
use crate::refine::fe::counterpart;

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

/// A constraint read on the part.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Judged {
    pub constraint: String,
    /// The value on the part (SI): measured, or for a drawn size the drawing's own.
    pub value: f64,
    pub fidelity: Fidelity,
    pub met: bool,
}

/// How the check judges the design.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// The fidelity the constraints are read in: 3D where it ran, else the one the plate's
    /// width over its thinnest hinge calls for.
    pub fidelity: Fidelity,
    /// Every constraint the part's check reads, in the problem's order.
    pub judged: Vec<Judged>,
    /// The constraints the part fails, each read in the highest fidelity that measures it
    /// (its own `fidelity`: a section stress, which 3D does not give, in 2D).
    pub fails: Vec<PartFailure>,
    /// The constraints the part's check does not measure: judged by the model only.
    pub model_only: Vec<String>,
    /// The outputs (in `fidelity`) whose model value is off the part's by more than
    /// [`MODEL_GAP`] beyond the FE's own error: where the model's idealization fails.
    pub model_off: Vec<ModelGap>,
}

/// How far beyond the FE's error a model output may be off its part before the check says
/// that the model does not hold there: 5 %, well above the FE's errors (below 0.1 % on the
/// shipped parts) and the hinge formulas' accuracy within their ranges of fit.
pub const MODEL_GAP: f64 = 0.05;

/// A model output off its part.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ModelGap {
    pub output: String,
    /// `(model - FE) / FE`, in percent.
    pub deviation_percent: f64,
    /// The FE value's estimated relative error, in percent.
    pub fe_error_percent: f64,
}

/// The outputs of one fidelity whose model value is off by more than [`MODEL_GAP`] beyond
/// their FE error.
pub fn model_gaps(outputs: Option<&IndexMap<&'static str, OutputReport>>) -> Vec<ModelGap> {
    let Some(outputs) = outputs else {
        return Vec::new();
    };
    outputs
        .iter()
        .filter_map(|(name, o)| {
            let d = o.deviation_percent?;
            let e = 100.0 * o.estimate.relative_error.unwrap_or(0.0);
            (d.abs() > 100.0 * MODEL_GAP + e).then(|| ModelGap {
                output: name.to_string(),
                deviation_percent: d,
                fe_error_percent: e,
            })
        })
        .collect()
}

/// The verdict's lines of `verify`'s table.
pub struct VerdictLines<'a>(pub &'a Verdict);

impl Display for VerdictLines<'_> {
    fn fmt(&self, s: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let fidelity = v.fidelity.name();
        match v.fails.as_slice() {
            [] => writeln!(
                s,
                "verdict by the {fidelity} FE: the part meets every constraint it measures"
            )?,
            fails => {
                writeln!(s, "verdict by the {fidelity} FE: the part FAILS")?;
                for f in fails {
                    writeln!(s, "  {}", f.shown)?;
                }
            }
        }
        if !v.model_off.is_empty() {
            let off: Vec<String> = v
                .model_off
                .iter()
                .map(|g| format!("{} {:+.1} %", g.output, g.deviation_percent))
                .collect();
            writeln!(
                s,
                "the model is off its part by more than {:.0} % beyond the FE's error ({fidelity}): \
                 {}; its idealization (rigid links and blocks, each hinge formula within its \
                 range of fit) does not hold here: judge by the FE, or refine against it \
                 (run --refine fe)",
                100.0 * MODEL_GAP,
                off.join(", ")
            )?;
        }
        Ok(())
    }
}

impl Verdict {
    /// The verdict on design `x` (SI) from check `v`; `read` is the idealization the plate
    /// calls for. A size of the part as drawn (`part_width`) is read from the model, which
    /// gives the drawn part's own size.
    pub fn new(problem: &Problem, x: &[f64], v: &Verification, read: Fidelity) -> Self {
        // highest first: 3D, the idealization the plate calls for, then the other one; an
        // output the higher ones do not measure (a section stress, which 3D has not) is
        // read in the highest that does
        let ran: Vec<Fidelity> = fidelities(v).iter().map(|(f, _, _)| *f).collect();
        let mut order: Vec<Fidelity> = [Fidelity::Solid, read]
            .into_iter()
            .filter(|f| ran.contains(f))
            .collect();
        let rest: Vec<Fidelity> = ran.into_iter().filter(|f| !order.contains(f)).collect();
        order.extend(rest);
        let fidelity = order.first().copied().unwrap_or(read);
        let mechanism = problem.mechanism();
        // the stress the refinement reads ([refine] stress), so that both judge the same
        let stress = problem.refine.stress;
        let measured =
            |output: usize, f: Fidelity| match counterpart(mechanism, &v.analysis, stress, output)?
            {
                FeCounterpart::ActuationForce => v.actuation_force_of(f),
                FeCounterpart::Output(id) => v
                    .outputs(f)?
                    .iter()
                    .find(|o| o.id == id)
                    .map(|o| o.estimate.value),
            };
        let value = |output: usize| {
            if mechanism.fe_counterpart(output).is_none() && mechanism.drawn(output) {
                return model_value(problem.model(), x, output).map(|x| (x, fidelity));
            }
            order
                .iter()
                .find_map(|&f| measured(output, f).map(|x| (x, f)))
        };
        let mut fails = Vec::new();
        let mut judged = Vec::new();
        let mut model_only: Vec<String> = Vec::new();
        for c in &problem.constraints {
            let Some((x, fidelity)) = value(c.index) else {
                if !model_only.contains(&c.output) {
                    model_only.push(c.output.clone());
                }
                continue;
            };
            let broken = [c.lower.filter(|&lo| x < lo), c.upper.filter(|&hi| x > hi)];
            judged.push(Judged {
                constraint: c.output.clone(),
                value: x,
                fidelity,
                met: broken.iter().all(Option::is_none),
            });
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
            judged,
            fails,
            model_only,
            model_off: Vec::new(),
        }
    }
}
