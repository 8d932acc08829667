//! The finite elements of the part as the high fidelity: [`crate::fe::verify`] at each
//! design, the model's outputs read from their FE counterparts
//! ([`crate::model::PartMaker::fe_counterpart`]) in the chosen idealization.

use serde_json::json;

use super::{HighFidelity, Measurement};
use crate::fe::element::SOLID_RULE;
use crate::fe::verify::{verify_design_at_modulus, Verification, VerifySettings};
use crate::fe::Fidelity;
use crate::model::Mechanism;
use crate::part::analysis::{Analysis, FeCounterpart, Quantity};
use crate::problem::refine::{RefineSettings, StressMeasure};

/// The FE check of a model's part.
pub struct FeFidelity<'a> {
    pub mechanism: &'a Mechanism,
    /// The FE that counts; `None`: by the rule at each design ([`Fidelity::for_plate`]).
    pub idealization: Option<Fidelity>,
    pub stress: StressMeasure,
    pub settings: VerifySettings,
}

/// The check the part of `mechanism` at `x` states, where it has a part that can be made.
pub fn analysis_at(mechanism: &Mechanism, x: &[f64]) -> Option<Analysis> {
    mechanism.part_spec(x)?.ok()?.analysis
}

/// Whether the FE counterpart of the model's output `output` is a natural frequency.
pub fn is_modal(mechanism: &Mechanism, analysis: &Analysis, output: usize) -> bool {
    match mechanism.fe_counterpart(output) {
        Some(FeCounterpart::Output(id)) => analysis
            .outputs
            .get(id.0)
            .is_some_and(|o| o.quantity.is_modal()),
        _ => false,
    }
}

impl<'a> FeFidelity<'a> {
    /// The FE check `refine` asks for, its meshes refined until every output's estimated
    /// error is below the refinement's tolerance; the modes only when a frequency is asked.
    pub fn new(mechanism: &'a Mechanism, refine: &RefineSettings, modal: bool) -> Self {
        FeFidelity {
            mechanism,
            idealization: refine.idealization,
            stress: refine.stress,
            // the 3D check whatever counts: it is the next fidelity up from either 2D
            // idealization, whose difference from it is part of their margins
            // three meshes at every design, whether or not their outputs converged: a
            // fourth at some designs only would move the outputs by steps as the design
            // moves; an error above the tolerance widens the output's margin instead
            settings: VerifySettings {
                tolerance: refine.tolerance,
                max_levels: 3,
                modal,
                solid: true,
                ..VerifySettings::default()
            },
        }
    }

    /// What of the check `analysis` stands for the model's output `output`
    /// ([`counterpart`]).
    pub fn counterpart(&self, analysis: &Analysis, output: usize) -> Option<FeCounterpart> {
        counterpart(self.mechanism, analysis, self.stress, output)
    }
}

/// What of the check `analysis` stands for the model's output `output`, a stress read as
/// `stress` asks (`[refine] stress`): the peak or the section stress, whichever of the two
/// the mechanism names, when the check measures the other. The refinement and `verify`'s
/// verdict read the part through this one function, so both judge the same stress.
pub fn counterpart(
    mechanism: &Mechanism,
    analysis: &Analysis,
    stress: StressMeasure,
    output: usize,
) -> Option<FeCounterpart> {
    let named = mechanism.fe_counterpart(output)?;
    let FeCounterpart::Output(id) = named else {
        return Some(named);
    };
    let wanted = match (stress, analysis.outputs.get(id.0)?.quantity) {
        (StressMeasure::Section, Quantity::PeakStress) => Quantity::SectionStress,
        (StressMeasure::Peak, Quantity::SectionStress) => Quantity::PeakStress,
        _ => return Some(named),
    };
    Some(analysis.find(wanted).map_or(named, FeCounterpart::Output))
}

/// The value and estimated relative error of `what` in `fidelity`.
fn read(v: &Verification, fidelity: Fidelity, what: FeCounterpart) -> Option<(f64, Option<f64>)> {
    let id = match what {
        FeCounterpart::ActuationForce => {
            // from its stiffness, whose error it carries
            let stiffness = v.analysis.actuation?.stiffness;
            let (_, e) = read(v, fidelity, FeCounterpart::Output(stiffness))?;
            return Some((v.actuation_force_of(fidelity)?, e));
        }
        FeCounterpart::Output(id) => id,
    };
    let o = v.outputs(fidelity)?.iter().find(|o| o.id == id)?;
    // the verification's own estimate: the extrapolation's error where the output converges,
    // else the spread of its last values (a sharp root's peak grows by a third a refinement,
    // which the caller refuses)
    Some((o.estimate.value, o.estimate.relative_error))
}

/// The largest spread (over the last three meshes) of a non-converging peak stress the
/// refinement accepts as its error: beyond it the peak is a sharp root's, which grows
/// without bound. Measured: a 0.2 mm fillet's peak on uniformly refined meshes turns within
/// 1.8-1.9 % (wei2017's optimum and printed design), a sharp root's grows by more than 10 %
/// (tests/part_and_fe/fe_verify.rs).
const PEAK_SPREAD_LIMIT: f64 = 0.05;

/// The largest relative difference of a stiffness between the 3D check and plane strain (0
/// without a 3D check): the gap to the next fidelity up of what only 2D gives.
fn stiffness_gap(v: &Verification) -> f64 {
    let (Some(solid), Some(strain)) =
        (v.outputs(Fidelity::Solid), v.outputs(Fidelity::PlaneStrain))
    else {
        return 0.0;
    };
    solid
        .iter()
        .filter(|o| matches!(v.analysis.outputs[o.id.0].quantity, Quantity::Stiffness(_)))
        .filter_map(|o| {
            let s = strain.iter().find(|p| p.id == o.id)?;
            Some(((o.estimate.value - s.estimate.value) / s.estimate.value).abs())
        })
        .fold(0.0, f64::max)
}

impl HighFidelity for FeFidelity<'_> {
    fn describe(&self) -> String {
        match self.idealization {
            Some(f) => format!("finite elements, {}", f.name()),
            None => format!(
                "finite elements, by the plate's width over its thinnest hinge (3D from {} to {}, \
                 a 2D idealization outside)",
                SOLID_RULE.0, SOLID_RULE.1
            ),
        }
    }

    fn measures(&self, x: &[f64], output: usize) -> bool {
        let Some(analysis) = analysis_at(self.mechanism, x) else {
            // no part here: the measurement will say why
            return self.mechanism.fe_counterpart(output).is_some();
        };
        match self.counterpart(&analysis, output) {
            None => false,
            Some(FeCounterpart::ActuationForce) => true,
            // a part may leave out an output its model has (a mode it cannot check)
            Some(FeCounterpart::Output(id)) => analysis
                .outputs
                .get(id.0)
                .is_some_and(|o| self.settings.modal || !o.quantity.is_modal()),
        }
    }

    fn measure(&self, x: &[f64], outputs: &[usize]) -> Result<Measurement, String> {
        self.measure_at_modulus(x, 1.0, outputs)
    }

    fn measure_at_modulus(
        &self,
        x: &[f64],
        modulus: f64,
        outputs: &[usize],
    ) -> Result<Measurement, String> {
        let v = verify_design_at_modulus(self.mechanism, x, &self.settings, modulus)
            .map_err(|e| e.to_string())?;
        let fidelity = self.idealization.unwrap_or_else(|| v.fidelity_for_part());
        if v.outputs(fidelity).is_none() {
            return Err(format!(
                "the FE check gave no {} result{}",
                fidelity.name(),
                v.solid_note
                    .as_ref()
                    .map_or(String::new(), |why| format!(": {why}"))
            ));
        }
        let mut values = Vec::new();
        let mut errors = Vec::new();
        let mut margins = Vec::new();
        for &o in outputs {
            let what = self
                .counterpart(&v.analysis, o)
                .ok_or("an output without an FE counterpart")?;
            // what the 3D check does not give (the modes, the section stress) is read in plane
            // strain, the nearer 2D bound of a part the rule sends to 3D, its margin widened
            // by the largest difference of a stiffness between 3D and plane strain
            let (used, widen) = match read(&v, fidelity, what) {
                None if fidelity == Fidelity::Solid => {
                    (Fidelity::PlaneStrain, Some(stiffness_gap(&v)))
                }
                _ => (fidelity, None),
            };
            let (value, error) = read(&v, used, what).ok_or_else(|| {
                let name = match what {
                    FeCounterpart::Output(id) => v.analysis.outputs[id.0].name,
                    FeCounterpart::ActuationForce => v.analysis.actuation.map_or("", |a| a.name),
                };
                format!("the FE check gave no {name}")
            })?;
            let peak = matches!(what, FeCounterpart::Output(id)
                if v.analysis.outputs[id.0].quantity == Quantity::PeakStress);
            if peak && error.is_none_or(|e| e > PEAK_SPREAD_LIMIT) {
                return Err(
                    "the FE peak stress does not converge (a sharp root: give the part \
                            fillets, or set [refine] stress = \"section\")"
                        .to_string(),
                );
            }
            // the next fidelity up from a 2D idealization is the 3D check; above 3D there is
            // none here, its error estimate covering its own discretization
            let gap = match (used, widen) {
                (_, Some(w)) => Some(w),
                (Fidelity::Solid, None) => Some(0.0),
                _ => read(&v, Fidelity::Solid, what)
                    .map(|(solid, _)| ((solid - value) / value).abs()),
            };
            margins.push(error.unwrap_or(0.0) + gap.unwrap_or(0.0));
            values.push(value);
            errors.push(error);
        }
        let outputs: serde_json::Map<_, _> = [
            Fidelity::PlaneStress,
            Fidelity::PlaneStrain,
            Fidelity::Solid,
        ]
        .into_iter()
        .filter_map(|f| {
            let mut map = serde_json::Map::new();
            for o in v.outputs(f)? {
                map.insert(o.name.to_string(), json!(o.estimate.value));
            }
            if let (Some(a), Some(force)) = (v.analysis.actuation, v.actuation_force_of(f)) {
                map.insert(a.name.into(), json!(force));
            }
            Some((f.name().to_string(), serde_json::Value::Object(map)))
        })
        .collect();
        let detail = json!({
            "fidelity": fidelity,
            "levels": v.levels.len(),
            "elements": v.levels.last().map_or(0, |l| l.elements),
            "converged": v.converged,
            "seconds": v.seconds,
            "outputs": outputs,
        });
        Ok(Measurement {
            values,
            errors,
            margins,
            detail,
        })
    }
}
