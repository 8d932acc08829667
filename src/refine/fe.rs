//! The finite elements of the part as the high fidelity: [`crate::fe::verify`] at each
//! design, the model's outputs read from their FE counterparts
//! ([`crate::model::Model::fe_counterpart`]) in the chosen idealization.

use serde_json::json;

use super::{HighFidelity, Measurement};
use crate::fe::verify::{verify_design, Verification, VerifySettings};
use crate::fe::Idealization;
use crate::model::Mechanism;
use crate::problem::refine::{RefineSettings, StressMeasure};

/// The FE check of a model's part.
pub struct FeFidelity<'a> {
    pub mechanism: &'a Mechanism,
    pub idealization: Idealization,
    pub stress: StressMeasure,
    pub settings: VerifySettings,
}

impl<'a> FeFidelity<'a> {
    /// The FE check `refine` asks for, its meshes refined until every output's estimated
    /// error is below the refinement's tolerance; the modes only when a frequency is asked.
    pub fn new(mechanism: &'a Mechanism, refine: &RefineSettings, modal: bool) -> Self {
        FeFidelity {
            mechanism,
            idealization: refine.idealization,
            stress: refine.stress,
            settings: VerifySettings {
                tolerance: refine.tolerance,
                modal,
                ..VerifySettings::default()
            },
        }
    }

    /// The FE output that stands for the model's output `output`.
    pub fn counterpart(&self, output: usize) -> Option<&'static str> {
        match self.mechanism.fe_counterpart(output)? {
            "fe_stress_max" if self.stress == StressMeasure::Section => Some("fe_stress_section"),
            name => Some(name),
        }
    }
}

/// The value and estimated relative error of the FE output `name` in `result` (the
/// idealization's index in `v.results`).
fn read(v: &Verification, result: usize, name: &str) -> Option<(f64, Option<f64>)> {
    if name == "fe_actuation_force" {
        // from k_in, whose error it carries
        let (_, e) = read(v, result, "fe_k_in")?;
        return Some((v.actuation_force[result], e));
    }
    let o = v.results[result].outputs.iter().find(|o| o.name == name)?;
    let e = &o.estimate;
    if e.converging {
        return Some((e.value, e.relative_error));
    }
    // a peak stress whose last two refinements did not shrink its change by the order
    // expected: its last change is the error to quote (a sharp root's peak grows by a
    // third a refinement, which the caller refuses)
    let n = o.values.len();
    let change = (n >= 2).then(|| ((o.values[n - 1] - o.values[n - 2]) / e.value).abs());
    Some((e.value, change))
}

/// The largest last change of a non-converging peak stress the refinement accepts as its
/// error: beyond it the peak is a sharp root's, which grows without bound.
const PEAK_CHANGE_LIMIT: f64 = 0.02;

impl HighFidelity for FeFidelity<'_> {
    fn describe(&self) -> String {
        format!("finite elements, {}", self.idealization.name())
    }

    fn measures(&self, output: usize) -> bool {
        let Some(name) = self.counterpart(output) else {
            return false;
        };
        self.settings.modal || !name.contains("frequency")
    }

    fn measure(&self, x: &[f64], outputs: &[usize]) -> Result<Measurement, String> {
        let v = verify_design(self.mechanism, x, &self.settings).map_err(|e| e.to_string())?;
        let which = v
            .results
            .iter()
            .position(|r| r.idealization == self.idealization)
            .ok_or("the FE check gave no result in the idealization asked for")?;
        let mut values = Vec::new();
        let mut errors = Vec::new();
        for &o in outputs {
            let name = self
                .counterpart(o)
                .ok_or("an output without an FE counterpart")?;
            let (value, error) =
                read(&v, which, name).ok_or_else(|| format!("the FE check gave no {name}"))?;
            if name == "fe_stress_max" && error.is_none_or(|e| e > PEAK_CHANGE_LIMIT) {
                return Err(
                    "the FE peak stress does not converge (a sharp root: give the part \
                            fillets, or set [refine] stress = \"section\")"
                        .to_string(),
                );
            }
            values.push(value);
            errors.push(error);
        }
        let detail = json!({
            "levels": v.levels.len(),
            "elements": v.levels.last().map_or(0, |l| l.elements),
            "converged": v.converged,
            "seconds": v.seconds,
            "outputs": v.results.iter().enumerate().map(|(i, r)| {
                let mut map = serde_json::Map::new();
                for o in &r.outputs {
                    map.insert(o.name.to_string(), json!(o.estimate.value));
                }
                map.insert("fe_actuation_force".into(), json!(v.actuation_force[i]));
                (r.idealization.name().to_string(), serde_json::Value::Object(map))
            }).collect::<serde_json::Map<_, _>>(),
        });
        Ok(Measurement {
            values,
            errors,
            detail,
        })
    }
}
