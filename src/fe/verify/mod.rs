//! Paper 004's finite-element check (Sec. 4.1) on a part: the lower output block's clamping
//! face held, 10 N on each input face along the actuator's axis, 10 N on the output face
//! with the input faces free, and the stress under the actuation `nominal_stroke * k_in +
//! preload`; with a density, the lowest in-plane natural modes. Both 2D idealizations, each
//! on a sequence of uniformly refined meshes until every output's estimated error is below
//! the tolerance.
//!
//! The part is symmetric about the output axis, so the half at `x >= 0` is solved: its cut
//! held in x (the symmetric response, which every load case is), or in y for the
//! antisymmetric modes. Definitions, each comparable with the analytic output of the same
//! meaning:
//!
//! - `x_in`: the increase of the distance between the input faces' mean positions under the
//!   test force on each; `k_in = force / x_in` (the analytic `k_in` is the same face-to-face
//!   stiffness, `1 / a11`).
//! - `y_out`: the output face's mean displacement towards the actuator's axis under the same
//!   load; `amplification = y_out / x_in` (positive when the output face moves inward as the
//!   input faces move apart, the sign of the analytic `amplification` of a bridge whose arms
//!   rise towards the output blocks).
//! - `k_out = force / (mean displacement of the output face)` under the test force on it,
//!   the input faces free (the analytic `k_out`).
//! - `stress_section`: the largest `|N| / (w t) + 6 |M| / (w t^2)` over the hinges' root
//!   sections (the ends of their thin sections), from the section resultants of the FE
//!   stresses under the actuation: what Eq. 12-17 predict (`stress_max`). The resultants are
//!   integrated across two inner sections, at a quarter and three quarters of the thin
//!   section, and carried to its ends by statics (`N` constant, `M` linear along a strip
//!   without loads): integrated across a sharp root itself they would meet its singular
//!   stress.
//! - `stress_peak`: the largest von Mises stress at a node under the actuation; at filleted
//!   roots it converges, at sharp ones it grows without bound and is reported as not
//!   converging.
//! - `frequency_output`: the lowest symmetric mode (the output mode, the analytic
//!   `natural_frequency`), the actuator holding the input faces (as springs of its stiffness,
//!   or fixed in x for an actuator much stiffer than the part), the payload on the output
//!   face; `frequency_first`: the lowest mode of either symmetry.

mod level;
mod whole;

pub use whole::FullModel;

use serde::Serialize;

use super::element::{Elastic, Idealization};
use super::geometry::Domain;
use super::loads;
use super::mesh::{mesh, Mesh};
use super::richardson::{estimate, Estimate};
use super::FeError;
use crate::part::{Part, PartSpec};
use level::{face_edges, holds, size_function, solve_level, LevelResult, Setup};

/// How a verification runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerifySettings {
    /// Every converging output's estimated relative error must fall below this.
    pub tolerance: f64,
    /// The most meshes in the sequence (at least three).
    pub max_levels: usize,
    /// The test force on each input face and on the output face (N).
    pub test_force: f64,
    /// Elements through a hinge's thickness on the first mesh (element size `t / n` at the
    /// hinges).
    pub per_thickness: f64,
    /// The stiffness of every element outside the hinges' thin sections is multiplied by
    /// this: 1 for the part as it is, large to make its links, blocks and fillets nearly
    /// rigid, as the analytic model has them (a measurement of what that assumption costs).
    pub body_stiffening: f64,
    /// Compute the natural modes too (where the material has a density).
    pub modal: bool,
}

impl Default for VerifySettings {
    fn default() -> Self {
        VerifySettings {
            tolerance: 0.005,
            max_levels: 4,
            test_force: 10.0,
            per_thickness: 4.0,
            body_stiffening: 1.0,
            modal: true,
        }
    }
}

/// The outputs, in the order of every level's values.
pub const OUTPUTS: [(&str, &str, &str); 9] = [
    ("fe_x_in", "m", "increase of the distance between the input faces under the test force"),
    ("fe_y_out", "m", "output face's displacement towards the axis under the same load"),
    ("fe_amplification", "1", "y_out / x_in"),
    ("fe_k_in", "N/m", "test force / x_in"),
    ("fe_k_out", "N/m", "test force on the output face / its displacement, inputs free"),
    ("fe_stress_section", "Pa", "largest beam stress |N|/(w t) + 6|M|/(w t^2) at the hinges' root sections under the actuation"),
    ("fe_stress_max", "Pa", "largest nodal von Mises stress under the actuation"),
    ("fe_output_frequency", "Hz", "lowest symmetric (output) mode"),
    ("fe_natural_frequency", "Hz", "lowest mode of either symmetry"),
];

/// Index of the peak stress among [`OUTPUTS`]: reported, never a reason to refine.
const PEAK: usize = 6;
const MODAL: [usize; 2] = [7, 8];

/// One mesh of the sequence.
#[derive(Debug, Clone, Serialize)]
pub struct Level {
    pub level: usize,
    pub elements: usize,
    pub nodes: usize,
    /// Free degrees of freedom of the static analysis.
    pub dofs: usize,
    pub seconds: f64,
}

/// An output of one idealization over the sequence.
#[derive(Debug, Clone, Serialize)]
pub struct Output {
    pub name: &'static str,
    pub unit: &'static str,
    pub values: Vec<f64>,
    pub estimate: Estimate,
    /// Where it occurs (mm, the whole part's frame), for the stresses.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub location_mm: Option<[f64; 2]>,
    /// Where, in words (the hinge and its end, for the section stress).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<String>,
}

/// The finest mesh's fields, for the pictures.
#[derive(Debug, Clone)]
pub struct Fields {
    /// The half mesh (m).
    pub mesh: Mesh,
    /// Displacements under the actuation (m, two a node).
    pub displacement: Vec<f64>,
    /// Nodal von Mises stress under the actuation (Pa).
    pub von_mises: Vec<f64>,
}

/// One idealization's results.
#[derive(Debug, Clone)]
pub struct Result2d {
    pub idealization: Idealization,
    pub outputs: Vec<Output>,
    pub fields: Fields,
}

/// A verification: the part, the sequence of meshes, both idealizations' results.
#[derive(Debug, Clone)]
pub struct Verification {
    pub part: Part,
    pub half: Part,
    pub levels: Vec<Level>,
    /// The half part's mesh at each level.
    pub meshes: Vec<Mesh>,
    pub material: Elastic,
    pub width: f64,
    pub results: Vec<Result2d>,
    /// Every output meant to converge did, within the tolerance.
    pub converged: bool,
    pub tolerance: f64,
    pub test_force: f64,
    /// The actuation force on each input face for the stresses, from each idealization's
    /// finest `k_in` (N).
    pub actuation_force: Vec<f64>,
    pub seconds: f64,
    /// The modal outputs were computed (the material has a density).
    pub modal: bool,
}

/// Verifies the part of `spec` (a whole part, symmetric about the y axis) with `material`.
pub fn verify(
    spec: &PartSpec,
    material: &Elastic,
    settings: &VerifySettings,
) -> Result<Verification, FeError> {
    let begin = std::time::Instant::now();
    let part =
        Part::build(spec).map_err(|e| FeError::Setup(format!("the part cannot be made: {e}")))?;
    let half_spec = spec
        .right_half()
        .ok_or_else(|| FeError::Setup("the part is not symmetric about its output axis".into()))?;
    let half = Part::build(&half_spec)
        .map_err(|e| FeError::Setup(format!("the half part cannot be built: {e}")))?;
    let actuation = spec
        .actuation
        .ok_or_else(|| FeError::Setup("the model gives no actuation for its part".into()))?;
    let setup = Setup {
        domain: Domain::of_part(&half),
        material: *material,
        width: spec.width,
        actuation,
        body_stiffening: settings.body_stiffening,
    };
    let modal = settings.modal && material.density > 0.0;
    let (size, coarse) = size_function(&setup.domain, settings.per_thickness);
    let mut m = mesh(&setup.domain, &size, coarse)?;
    let mut levels = Vec::new();
    let mut meshes = Vec::new();
    let mut per: Vec<Vec<LevelResult>> = vec![Vec::new(), Vec::new()];
    let max_levels = settings.max_levels.max(3);
    let converged = loop {
        let start = std::time::Instant::now();
        let h = holds(&m, &setup)?;
        // the mass does not depend on the idealization: the payload on the output face,
        // half of it on the half
        let mass = if modal {
            let output = face_edges(&m, &setup.domain, "output_top")?;
            let share = loads::uniform_force(
                &m,
                &output,
                setup.width,
                [0.5 * actuation.payload_mass, 0.0],
            );
            let points: Vec<(usize, f64)> = share
                .iter()
                .enumerate()
                .step_by(2)
                .filter(|(_, &v)| v != 0.0)
                .flat_map(|(dof, &v)| [(dof, v), (dof + 1, v)])
                .collect();
            Some(
                h.pattern
                    .mass_with(&m, &setup.material, setup.width, &points)?,
            )
        } else {
            None
        };
        let solve = |idealization| {
            solve_level(
                &m,
                &setup,
                &h,
                mass.as_ref(),
                idealization,
                settings.test_force,
            )
        };
        let (a, b) = rayon::join(
            || solve(Idealization::PlaneStress),
            || solve(Idealization::PlaneStrain),
        );
        levels.push(Level {
            level: m.level,
            elements: m.elements.len(),
            nodes: m.nodes.len(),
            dofs: h.pattern.dofs.count(),
            seconds: start.elapsed().as_secs_f64(),
        });
        per[0].push(a?);
        per[1].push(b?);
        meshes.push(m.clone());
        if levels.len() >= 3 {
            let done = per.iter().all(|results| {
                (0..OUTPUTS.len())
                    .filter(|&k| k != PEAK && (modal || !MODAL.contains(&k)))
                    .all(|k| {
                        let values: Vec<f64> = results.iter().map(|r| r.values[k]).collect();
                        let e = estimate(&values);
                        e.converging && e.relative_error.is_some_and(|r| r <= settings.tolerance)
                    })
            });
            if done || levels.len() >= max_levels {
                break done;
            }
        }
        m = m.refined(&setup.domain);
    };
    let results = Idealization::BOTH
        .iter()
        .zip(per)
        .map(|(&idealization, mut results)| {
            let last = results.last().expect("three levels at least");
            let mm = |p: [f64; 2]| [p[0] * 1e3, p[1] * 1e3];
            let outputs = OUTPUTS
                .iter()
                .enumerate()
                .filter(|(k, _)| modal || !MODAL.contains(k))
                .map(|(k, &(name, unit, _))| {
                    let values: Vec<f64> = results.iter().map(|r| r.values[k]).collect();
                    Output {
                        name,
                        unit,
                        estimate: estimate(&values),
                        values,
                        location_mm: match k {
                            5 => Some(mm(last.section_point)),
                            PEAK => Some(mm(last.peak_at)),
                            _ => None,
                        },
                        at: (k == 5).then(|| last.section_at.clone()),
                    }
                })
                .collect();
            let finest = results.pop().expect("three levels at least");
            Result2d {
                idealization,
                outputs,
                fields: Fields {
                    mesh: m.clone(),
                    displacement: finest.displacement,
                    von_mises: finest.von_mises,
                },
            }
        })
        .collect::<Vec<_>>();
    let actuation_force = results
        .iter()
        .map(|r| {
            let k_in = r
                .outputs
                .iter()
                .find(|o| o.name == "fe_k_in")
                .map_or(f64::NAN, |o| o.estimate.value);
            actuation.nominal_stroke * k_in + actuation.preload
        })
        .collect();
    Ok(Verification {
        part,
        half,
        levels,
        meshes,
        material: *material,
        width: spec.width,
        results,
        converged,
        tolerance: settings.tolerance,
        test_force: settings.test_force,
        actuation_force,
        seconds: begin.elapsed().as_secs_f64(),
        modal,
    })
}

/// Verifies the part of `mechanism` at the design `x` (SI): its part and material.
pub fn verify_design(
    mechanism: &crate::model::Mechanism,
    x: &[f64],
    settings: &VerifySettings,
) -> Result<Verification, FeError> {
    let model = mechanism.physics.as_ref();
    let spec = match mechanism.part_spec(x) {
        None => {
            return Err(FeError::Setup(format!(
                "the {} model has no part to check",
                model.name()
            )))
        }
        Some(Err(problems)) => {
            return Err(FeError::Setup(format!(
                "this design gives no part that can be made: {}",
                crate::part::PartError { problems }
            )))
        }
        Some(Ok(spec)) => spec,
    };
    let m = model
        .material()
        .ok_or_else(|| FeError::Setup(format!("the {} model has no material", model.name())))?;
    let material = Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
        density: m.density,
    };
    verify(&spec, &material, settings)
}
