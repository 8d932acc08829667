//! The finite-element check a part's model states ([`crate::part::analysis`]): the clamped
//! faces held, each load case at the test force, the measures read from the mean
//! displacements of faces, the stresses under the actuation case scaled to the actuator's
//! largest force; with a density, the lowest in-plane natural modes. Both 2D idealizations,
//! each on a sequence of uniformly refined meshes until every output meant to converge has
//! an estimated error below the tolerance.
//!
//! Where the part is symmetric about the y axis, and every load case too, the half at
//! `x >= 0` is solved, its cut held in x (the symmetric response), or in y for the
//! antisymmetric modes; `statement.rs` derives the half's loads and measures from the
//! whole part's statement. Any other part is solved whole, its statement as it stands: its
//! natural modes are one family, computed where its actuator stands on the held faces (a
//! spring from its face to the ground) or it has none; otherwise the modal outputs are left
//! out, and the verification says so. What the quantities mean:
//!
//! - a stiffness is `test force / measure`, a ratio one measure over another.
//! - the section stress: the largest `|N| / (w t) + 6 |M| / (w t^2)` over the hinges' root
//!   sections (the ends of their thin sections), from the section resultants of the FE
//!   stresses under the actuation: what a beam model of the hinges predicts. The
//!   resultants are integrated across two inner sections, at a quarter and three quarters
//!   of the thin section, and carried to its ends by statics (`N` constant, `M` linear
//!   along a strip without loads): integrated across a sharp root itself they would meet
//!   its singular stress.
//! - the peak stress: the largest von Mises stress at a node under the actuation; at
//!   filleted roots it converges, at sharp ones it grows without bound and is reported as
//!   not converging.
//! - the symmetric frequency: the lowest symmetric mode, the actuator holding its faces (as
//!   springs of its stiffness, or fixed along its axis for an actuator much stiffer than
//!   the part), the payload on its face; the lowest frequency: the lowest mode of either
//!   symmetry.

mod grading;
mod level;
mod settings;
mod solid;
mod statement;
mod whole;

pub use settings::{BudgetStop, VerifySettings, MAX_DOFS};
pub use solid::{Solid3d, SolidSolve, SOLID_LAYERS};
pub use whole::FullModel;

use serde::Serialize;

use super::element::{Elastic, Fidelity, Idealization};
use super::geometry::Domain;
use super::mesh::{mesh_within, Mesh};
use super::richardson::{estimate, Estimate};
use super::FeError;
use crate::part::analysis::{Analysis, FeOutputId, Quantity};
use crate::part::{Part, PartSpec};
pub use grading::PER_RADIUS;
pub use level::size_function;
use level::{face_edges, face_masses, holds, solve_level, LevelResult, Setup};

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
    /// Which of the part's analysis's outputs it is.
    #[serde(skip)]
    pub id: FeOutputId,
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
    /// The check the part's model stated.
    pub analysis: Analysis,
    /// The part solved: its half at `x >= 0`, or the whole part ([`Verification::whole_part`]).
    pub half: Part,
    /// The whole part was solved, not its half: the part or its statement is not symmetric
    /// about the y axis.
    pub whole_part: bool,
    /// Why the modal outputs the part states were not computed.
    pub modal_note: Option<String>,
    pub levels: Vec<Level>,
    /// The solved part's mesh at each level (the half's, or the whole part's).
    pub meshes: Vec<Mesh>,
    pub material: Elastic,
    pub width: f64,
    pub results: Vec<Result2d>,
    /// Every output meant to converge did, within the tolerance.
    pub converged: bool,
    pub tolerance: f64,
    pub test_force: f64,
    /// The actuation force on each loaded face of the actuation case, for the stresses,
    /// from each idealization's finest value of the stiffness it is stated with (N).
    pub actuation_force: Vec<f64>,
    pub seconds: f64,
    /// The modal outputs were computed (the material has a density).
    pub modal: bool,
    /// The sequence stopped at the budget before converging.
    pub budget_stop: Option<BudgetStop>,
    /// The 3D check, where it was asked for and the budget allowed it.
    pub solid: Option<Solid3d>,
    /// Why the 3D check asked for was not made.
    pub solid_note: Option<String>,
    /// What the part gave the analysis, for further solves of its meshes.
    setup: Setup,
}

impl Verification {
    /// The outputs of `fidelity`, where the check made it.
    pub fn outputs(&self, fidelity: Fidelity) -> Option<&[Output]> {
        match fidelity.plane() {
            Some(i) => self
                .results
                .iter()
                .find(|r| r.idealization == i)
                .map(|r| r.outputs.as_slice()),
            None => self.solid.as_ref().map(|s| s.outputs.as_slice()),
        }
    }

    /// The fidelity the part calls for by its width over its thinnest hinge
    /// ([`Fidelity::for_plate`]).
    pub fn fidelity_for_part(&self) -> Fidelity {
        Fidelity::for_plate(self.width, self.thinnest_hinge())
    }

    /// The thinnest hinge's thickness (m).
    pub fn thinnest_hinge(&self) -> f64 {
        self.setup.domain.thinnest_hinge()
    }

    /// A direct 3D solve of the mesh at `level` in `layers` graded layers (no ratio to
    /// plane strain): each static output and the peak stress by name, as a check of the 3D
    /// values on a finer mesh than theirs.
    pub fn solid_direct(
        &self,
        level: usize,
        layers: usize,
    ) -> Result<Vec<(&'static str, f64)>, FeError> {
        let m = self
            .meshes
            .get(level)
            .ok_or_else(|| FeError::Setup(format!("the check has no mesh at level {level}")))?;
        let strain = &self.results[1];
        // the plane-strain peak's node on that mesh, through which the 3D peak is read
        let h = holds(m, &self.setup)?;
        let peak_node = solve_level(
            m,
            &self.setup,
            &h,
            None,
            Idealization::PlaneStrain,
            self.test_force,
        )?
        .peak_node;
        let layers = crate::fe::solid::Layers::graded(layers, self.width, self.thinnest_hinge());
        let r = solid::solve_solid(m, &self.setup, layers, self.test_force, peak_node)?;
        Ok(strain
            .outputs
            .iter()
            .map(|o| (o.name, r.values[o.id.0]))
            .filter(|(_, v)| v.is_finite())
            .collect())
    }

    /// The layers of the 3D check's finest solve (those of `part3d.inp`).
    pub fn solid_layers(&self) -> crate::fe::solid::Layers {
        crate::fe::solid::Layers::graded(SOLID_LAYERS, self.width, self.thinnest_hinge())
    }

    /// The actuation force of `fidelity` (N), where the check made it.
    pub fn actuation_force_of(&self, fidelity: Fidelity) -> Option<f64> {
        match fidelity.plane() {
            Some(i) => self
                .results
                .iter()
                .position(|r| r.idealization == i)
                .map(|k| self.actuation_force[k]),
            None => self.solid.as_ref().map(|s| s.actuation_force),
        }
    }
}

/// Verifies the part of `spec` (a whole part) with `material`: by its half where the part and
/// its statement are symmetric about the y axis, else whole.
pub fn verify(
    spec: &PartSpec,
    material: &Elastic,
    settings: &VerifySettings,
) -> Result<Verification, FeError> {
    let begin = std::time::Instant::now();
    let part =
        Part::build(spec).map_err(|e| FeError::Setup(format!("the part cannot be made: {e}")))?;
    let actuation = spec
        .actuation
        .ok_or_else(|| FeError::Setup("the model gives no actuation for its part".into()))?;
    let analysis = spec
        .analysis
        .clone()
        .ok_or_else(|| FeError::Setup("the model states no finite-element check".into()))?;
    statement::check(&analysis)?;
    let actuation_case = analysis
        .actuation
        .ok_or_else(|| FeError::Setup("the part's check states no actuation case".into()))?;
    statement::faces_exist(&analysis, &spec.faces)?;
    // the half where the part and its statement are symmetric, else the whole part
    let halved = spec.right_half().and_then(|h| {
        statement::half(&analysis, &spec.faces, settings.test_force)
            .ok()
            .map(|stated| (h, stated))
    });
    let whole_part = halved.is_none();
    let (half, stated) = match halved {
        Some((h, stated)) => (
            Part::build(&h)
                .map_err(|e| FeError::Setup(format!("the half part cannot be built: {e}")))?,
            stated,
        ),
        None => (
            part.clone(),
            statement::whole(&analysis, settings.test_force),
        ),
    };
    let setup = Setup {
        domain: Domain::of_part(&half),
        material: *material,
        width: spec.width,
        actuation,
        body_stiffening: settings.body_stiffening,
        analysis,
        actuation_case,
        stated,
    };
    let asked_modal = settings.modal && material.density > 0.0 && setup.analysis.modal.is_some();
    // a whole part's modes are one family; its actuator must stand on the ground (a
    // spring from one face to the held ones) for the statement to hold it in them
    let whole_modes = setup.stated.spring.is_some()
        || setup
            .analysis
            .modal
            .as_ref()
            .is_some_and(|m| m.actuator.is_none());
    let modal = asked_modal && (!whole_part || whole_modes);
    let modal_note = (asked_modal && !modal).then(|| {
        "left out: the part is not symmetric about the y axis, and its actuator does not \
         stand on its held faces: its modes are not yet computed on the whole part"
            .to_string()
    });
    let (base, coarse) = size_function(&setup.domain, settings.per_thickness);
    let budget = settings.max_dofs / 2;
    let first = mesh_within(&setup.domain, &base, coarse, budget)?;
    // graded at the fillets near the peak, unless that breaks the budget the ungraded keeps
    let arcs = grading::arcs_to_grade(&first, &setup, settings.test_force)?;
    let (mut m, arcs) = if arcs.is_empty() {
        (first, arcs)
    } else {
        match mesh_within(
            &setup.domain,
            &grading::graded(&base, arcs.clone()),
            coarse,
            budget,
        ) {
            Ok(graded) => (graded, arcs),
            Err(FeError::Budget(_)) => (first, Vec::new()),
            Err(e) => return Err(e),
        }
    };
    let size = grading::graded(&base, arcs);
    let values_of = |results: &[LevelResult], meshes: &[Mesh], k: usize| -> Vec<f64> {
        match setup.analysis.outputs[k].quantity {
            Quantity::PeakStress => {
                let at = results.last().expect("one level at least").peak_at;
                let levels = meshes.iter().zip(results.iter().map(|r| &r.von_mises[..]));
                grading::followed(levels, at, size(at))
            }
            _ => results.iter().map(|r| r.values[k]).collect(),
        }
    };
    let mut budget_stop = None;
    let mut levels = Vec::new();
    let mut meshes = Vec::new();
    let mut per: Vec<Vec<LevelResult>> = vec![Vec::new(), Vec::new()];
    let max_levels = settings.max_levels.max(3);
    let converged = loop {
        let start = std::time::Instant::now();
        let h = holds(&m, &setup)?;
        // the mass does not depend on the idealization: the payload on its face, half of
        // it on the half where the face crosses the axis
        let mass = match &setup.stated.payload {
            Some((face, share)) if modal => {
                let payload = face_edges(&m, &setup.domain, face)?;
                let each = share * actuation.payload_mass;
                let points = face_masses(&m, &payload, setup.width, [each, each]);
                Some(
                    h.pattern
                        .mass_with(&m, &setup.material, setup.width, &points)?,
                )
            }
            _ => None,
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
            let outputs = &setup.analysis.outputs;
            let done = per.iter().all(|results| {
                (0..outputs.len())
                    .filter(|&k| outputs[k].converges && (modal || !outputs[k].quantity.is_modal()))
                    .all(|k| estimate(&values_of(results, &meshes, k)).within(settings.tolerance))
            });
            if done || levels.len() >= max_levels {
                break done;
            }
        }
        // a uniform refinement has about four times the nodes
        let next_dofs = 4 * levels.last().map_or(0, |l: &Level| l.dofs);
        if next_dofs > settings.max_dofs {
            budget_stop = Some(BudgetStop {
                next_dofs,
                max_dofs: settings.max_dofs,
            });
            break false;
        }
        m = m.refined(&setup.domain);
    };
    let strain_levels: Vec<(Vec<f64>, usize)> = per[1]
        .iter()
        .map(|r| (r.values.clone(), r.peak_node))
        .collect();
    let results = Idealization::BOTH
        .iter()
        .zip(per)
        .map(|(&idealization, mut results)| {
            let last = results.last().expect("one level at least");
            let mm = |p: [f64; 2]| [p[0] * 1e3, p[1] * 1e3];
            let outputs = setup
                .analysis
                .outputs
                .iter()
                .enumerate()
                .filter(|(_, o)| modal || !o.quantity.is_modal())
                .map(|(k, o)| {
                    let values = values_of(&results, &meshes, k);
                    Output {
                        id: FeOutputId(k),
                        name: o.name,
                        unit: o.dimension.si_unit(),
                        estimate: estimate(&values),
                        values,
                        location_mm: match o.quantity {
                            Quantity::SectionStress => Some(mm(last.section_point)),
                            Quantity::PeakStress => Some(mm(last.peak_at)),
                            _ => None,
                        },
                        at: (o.quantity == Quantity::SectionStress)
                            .then(|| last.section_at.clone()),
                    }
                })
                .collect();
            let finest = results.pop().expect("one level at least");
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
            let k = r
                .outputs
                .iter()
                .find(|o| o.id == setup.actuation_case.stiffness)
                .map_or(f64::NAN, |o| o.estimate.value);
            actuation.largest_force(k)
        })
        .collect();
    let (solid, solid_note) = if settings.solid {
        match solid::check(
            &meshes,
            &setup,
            &strain_levels,
            &results[1].outputs,
            settings.test_force,
            settings.max_dofs,
        )? {
            Ok(s) => (Some(s), None),
            Err(why) => (None, Some(why)),
        }
    } else {
        (None, Some("left out, as asked (--no-3d)".to_string()))
    };
    Ok(Verification {
        part,
        solid,
        solid_note,
        analysis: setup.analysis.clone(),
        setup,
        half,
        whole_part,
        modal_note,
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
        budget_stop,
    })
}

/// Verifies the part of `mechanism` at the design `x` (SI): its part and material.
pub fn verify_design(
    mechanism: &crate::model::Mechanism,
    x: &[f64],
    settings: &VerifySettings,
) -> Result<Verification, FeError> {
    verify_design_at_modulus(mechanism, x, settings, 1.0)
}

/// As [`verify_design`], the material's Young's modulus `modulus` times its own (Poisson's
/// ratio and density kept): a part of a bar whose modulus lies off the handbook's figure.
pub fn verify_design_at_modulus(
    mechanism: &crate::model::Mechanism,
    x: &[f64],
    settings: &VerifySettings,
    modulus: f64,
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
        youngs_modulus: m.youngs_modulus * modulus,
        poisson_ratio: m.poisson_ratio,
        density: m.density,
    };
    verify(&spec, &material, settings)
}
