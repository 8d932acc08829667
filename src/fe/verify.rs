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

use serde::Serialize;

use super::assembly::Pattern;
use super::element::{Elastic, Idealization};
use super::geometry::Domain;
use super::mesh::{mesh, Mesh};
use super::richardson::{estimate, Estimate};
use super::stress::{nodal_stresses, peak_von_mises, section, Locator};
use super::{loads, modal, FeError};
use crate::part::half::SYMMETRY;
use crate::part::{Actuation, Part, PartSpec};

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
}

impl Default for VerifySettings {
    fn default() -> Self {
        VerifySettings {
            tolerance: 0.005,
            max_levels: 4,
            test_force: 10.0,
            per_thickness: 4.0,
            body_stiffening: 1.0,
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

/// What the part gives the analysis.
struct Setup {
    domain: Domain,
    material: Elastic,
    width: f64,
    actuation: Actuation,
    body_stiffening: f64,
}

/// The element size at `p`: `t / n` on and around each hinge's thin section, growing by 0.3
/// of the distance from it, never above a tenth of the part.
fn size_function(domain: &Domain, per_thickness: f64) -> (impl Fn([f64; 2]) -> f64, f64) {
    let hinges: Vec<(super::geometry::Edge, f64)> = domain
        .hinges
        .iter()
        .map(|h| {
            (
                super::geometry::Edge::Line {
                    a: h.start,
                    b: h.end,
                },
                h.thickness,
            )
        })
        .collect();
    let coarse = 0.1 * domain.size();
    (
        move |p: [f64; 2]| {
            hinges.iter().fold(coarse, |h, (line, t)| {
                let d = (line.nearest(p).0 - 0.5 * t).max(0.0);
                h.min(t / per_thickness + 0.3 * d)
            })
        },
        coarse,
    )
}

/// The degrees of freedom on the nodes of the faces called `name` (both directions).
fn face_nodes(m: &Mesh, domain: &Domain, name: &str) -> Vec<usize> {
    let tol = 1e-9 * domain.size();
    let mut nodes: Vec<usize> = domain
        .faces
        .iter()
        .filter(|f| f.name == name)
        .flat_map(|f| m.nodes_on(f.a, f.b, tol))
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

fn face_edges(m: &Mesh, domain: &Domain, name: &str) -> Result<Vec<[usize; 3]>, FeError> {
    let tol = 1e-9 * domain.size();
    let edges: Vec<[usize; 3]> = domain
        .faces
        .iter()
        .filter(|f| f.name == name)
        .flat_map(|f| m.edges_on(f.a, f.b, tol))
        .collect();
    if edges.is_empty() {
        return Err(FeError::Setup(format!("the part has no face `{name}`")));
    }
    Ok(edges)
}

/// A mesh's one pattern: the clamping face fixed, every other condition held by springs on
/// the diagonal (stiff ones, [`PENALTY`] times the stiffest diagonal entry, for conditions
/// that are exact), so that one ordering and one symbolic factorization serve the static
/// cases and both families of modes.
struct Holds {
    pattern: Pattern,
    /// The degrees of freedom of the cut, in x and in y, and of the input face in x.
    cut_x: Vec<usize>,
    cut_y: Vec<usize>,
    input_x: Vec<usize>,
}

/// The stiffness of a spring that stands for a fixed degree of freedom, relative to the
/// stiffest diagonal entry: the held displacement is about `1e-9` of the others, and the
/// outputs move by as little (measured against elimination in the tests).
const PENALTY: f64 = 1e9;

fn holds(m: &Mesh, setup: &Setup) -> Result<Holds, FeError> {
    let d = &setup.domain;
    let clamp = face_nodes(m, d, "clamp_bottom");
    let mut fixed = vec![false; 2 * m.nodes.len()];
    for &n in &clamp {
        fixed[2 * n] = true;
        fixed[2 * n + 1] = true;
    }
    let cut = face_nodes(m, d, SYMMETRY);
    Ok(Holds {
        pattern: Pattern::new(m, &fixed)?,
        cut_x: cut.iter().map(|&n| 2 * n).collect(),
        cut_y: cut.iter().map(|&n| 2 * n + 1).collect(),
        input_x: face_nodes(m, d, "input_right")
            .iter()
            .map(|&n| 2 * n)
            .collect(),
    })
}

/// One level's values (in the order of [`OUTPUTS`]; the modal ones NaN without a density),
/// with the locations of the stresses and the actuation fields.
struct LevelResult {
    values: [f64; 9],
    peak_at: [f64; 2],
    section_at: String,
    section_point: [f64; 2],
    displacement: Vec<f64>,
    von_mises: Vec<f64>,
}

fn column(x: &faer::Mat<f64>, j: usize) -> Vec<f64> {
    (0..x.nrows()).map(|i| x[(i, j)]).collect()
}

fn solve_level(
    m: &Mesh,
    setup: &Setup,
    holds: &Holds,
    mass: Option<&faer::sparse::SparseColMat<usize, f64>>,
    idealization: Idealization,
    force: f64,
) -> Result<LevelResult, FeError> {
    let d = &setup.domain;
    let (w, mat) = (setup.width, &setup.material);
    let input = face_edges(m, d, "input_right")?;
    let output = face_edges(m, d, "output_top")?;
    face_edges(m, d, "clamp_bottom")?;
    let p = &holds.pattern;
    let in_hinge = |e: usize| {
        let c = super::element::point(&m.element_nodes(e), [1.0 / 3.0; 3]);
        d.hinges.iter().any(|h| {
            let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
            let u = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
            let (dx, dy) = (c[0] - h.start[0], c[1] - h.start[1]);
            let along = dx * u[0] + dy * u[1];
            let across = (-dx * u[1] + dy * u[0]).abs();
            (0.0..=len).contains(&along) && across <= 0.5 * h.thickness
        })
    };
    let k0 = if setup.body_stiffening == 1.0 {
        p.stiffness(m, mat, w, idealization)?
    } else {
        let f = setup.body_stiffening;
        p.stiffness_scaled(m, mat, w, idealization, &[], &|e| {
            if in_hinge(e) {
                1.0
            } else {
                f
            }
        })?
    };
    let penalty = PENALTY * p.largest_diagonal(&k0);
    let held =
        |dofs: &[usize]| -> Vec<(usize, f64)> { dofs.iter().map(|&d| (d, penalty)).collect() };
    let factor = p.factor(&p.with_diagonal(&k0, &held(&holds.cut_x)))?;
    let n = p.dofs.count();
    // the test force on the input face, and half the test force on the half output face
    let loads = [
        loads::uniform_force(m, &input, w, [force, 0.0]),
        loads::uniform_force(m, &output, w, [0.0, 0.5 * force]),
    ];
    let mut rhs = faer::Mat::<f64>::zeros(n, 2);
    for (j, f) in loads.iter().enumerate() {
        for (dof, &v) in f.iter().enumerate() {
            if let Some(i) = p.dofs.free(dof) {
                rhs[(i, j)] += v;
            }
        }
    }
    factor.solve(&mut rhs);
    let zero = vec![0.0; 2 * m.nodes.len()];
    let u_in = p.dofs.expand(&column(&rhs, 0), &zero);
    let u_out = p.dofs.expand(&column(&rhs, 1), &zero);
    let x_in = 2.0 * loads::mean_displacement(m, &input, &u_in)[0];
    let y_out = -loads::mean_displacement(m, &output, &u_in)[1];
    let k_in = force / x_in;
    let k_out = force / loads::mean_displacement(m, &output, &u_out)[1];

    // the actuation: the largest input force, the stresses it gives
    let a = &setup.actuation;
    let actuation_force = a.nominal_stroke * k_in + a.preload;
    let scale = actuation_force / force;
    let u_act: Vec<f64> = u_in.iter().map(|v| v * scale).collect();
    let dm = mat.d_matrix(idealization);
    let nodal = nodal_stresses(m, &dm, &u_act);
    let von_mises: Vec<f64> = nodal
        .iter()
        .map(|s| mat.von_mises(*s, idealization))
        .collect();
    let (peak, peak_node) = peak_von_mises(&nodal, mat, idealization);
    let locator = Locator::new(m);
    let mut best = (f64::NEG_INFINITY, String::new(), [0.0; 2]);
    // the root sections' resultants from two inner sections, at a quarter and three
    // quarters of the thin section: along a strip free of loads the axial force is constant
    // and the moment linear (statics, exactly), so they give the roots' resultants without
    // integrating across a root, where a sharp corner's stress is singular
    for h in &d.hinges {
        let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
        let axis = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
        let at = |f: f64| {
            [
                h.start[0] + f * len * axis[0],
                h.start[1] + f * len * axis[1],
            ]
        };
        let cut = |f: f64| {
            section(m, &locator, &dm, &u_act, at(f), axis, h.thickness)
                .ok_or_else(|| FeError::Solve(format!("a section of {} leaves the mesh", h.name)))
        };
        let (a, b) = (cut(0.25)?, cut(0.75)?);
        let axial = 0.5 * (a.axial + b.axial);
        let t = h.thickness;
        for (end, moment, centre) in [
            ("start", 1.5 * a.moment - 0.5 * b.moment, h.start),
            ("end", 1.5 * b.moment - 0.5 * a.moment, h.end),
        ] {
            let stress = axial.abs() / t + 6.0 * moment.abs() / (t * t);
            if stress > best.0 {
                best = (
                    stress,
                    format!("{}, {end} of its thin section", h.name),
                    centre,
                );
            }
        }
    }

    // the modes: the symmetric family with the actuator holding the input face (springs of
    // its stiffness, each face node its share of 2 k_a as the other face is the mirror, or
    // held in x for an actuator much stiffer than the part); the antisymmetric family with
    // the cut held in y; each started from a static deflection close to its lowest mode
    let mut f_output = f64::NAN;
    let mut f_first = f64::NAN;
    if let Some(mass) = mass {
        let actuator: Vec<(usize, f64)> = match a.stiffness {
            None => held(&holds.input_x),
            Some(ka) => loads::uniform_force(m, &input, w, [1.0, 0.0])
                .iter()
                .enumerate()
                .filter(|(_, &v)| v != 0.0)
                .map(|(dof, &v)| (dof, 2.0 * ka * v))
                .collect(),
        };
        let lowest = |springs: Vec<(usize, f64)>, load: &[f64]| -> Result<f64, FeError> {
            let factor = p.factor(&p.with_diagonal(&k0, &springs))?;
            let mut r = faer::Mat::<f64>::zeros(n, 1);
            for (dof, &v) in load.iter().enumerate() {
                if let Some(i) = p.dofs.free(dof) {
                    r[(i, 0)] = v;
                }
            }
            factor.solve(&mut r);
            let modes = modal::lowest_modes(&factor, mass, 1, 1e-6, Some(column(&r, 0)))?;
            Ok(modes[0].frequency)
        };
        let symmetric = [held(&holds.cut_x), actuator].concat();
        f_output = lowest(symmetric, &loads[1])?;
        let sideways = loads::uniform_force(m, &output, w, [force, 0.0]);
        f_first = f_output.min(lowest(held(&holds.cut_y), &sideways)?);
    }
    let amplification = y_out / x_in;
    Ok(LevelResult {
        values: [
            x_in,
            y_out,
            amplification,
            k_in,
            k_out,
            best.0,
            peak,
            f_output,
            f_first,
        ],
        peak_at: m.nodes[peak_node],
        section_at: best.1,
        section_point: best.2,
        displacement: u_act,
        von_mises,
    })
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
    let modal = material.density > 0.0;
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

/// The whole part's mesh at one level of a verification, with its faces and the two static
/// load cases on it: the model the CalculiX decks describe.
pub struct FullModel {
    pub mesh: Mesh,
    pub domain: Domain,
    /// The nodes of each named face.
    pub sets: Vec<(String, Vec<usize>)>,
    pub clamp: Vec<usize>,
    pub cases: Vec<super::calculix::LoadCase>,
    /// The edges of the input faces (left, right) and of the output face.
    pub input: [Vec<[usize; 3]>; 2],
    pub output: Vec<[usize; 3]>,
}

impl Verification {
    /// The whole part's model at `level`: the half mesh mirrored, the test force on each
    /// input face (pushing them apart), then on the output face (pulling it outward).
    pub fn full_model(&self, level: usize) -> Result<FullModel, FeError> {
        let domain = Domain::of_part(&self.part);
        let tol = 1e-9 * domain.size();
        let mesh = self.meshes[level].mirrored_about_y(tol);
        let edges = |name: &str| face_edges(&mesh, &domain, name);
        let (left, right, output) = (
            edges("input_left")?,
            edges("input_right")?,
            edges("output_top")?,
        );
        let w = self.width;
        let f = self.test_force;
        let area = |e: &[[usize; 3]]| loads::length(&mesh, e) * w;
        let mut inputs = loads::uniform_force(&mesh, &left, w, [-f, 0.0]);
        for (a, b) in inputs
            .iter_mut()
            .zip(loads::uniform_force(&mesh, &right, w, [f, 0.0]))
        {
            *a += b;
        }
        let cases = vec![
            super::calculix::LoadCase {
                name: format!("{f} N on each input face, pushing them apart"),
                forces: inputs,
                tractions: vec![
                    (left.clone(), [-f / area(&left), 0.0]),
                    (right.clone(), [f / area(&right), 0.0]),
                ],
            },
            super::calculix::LoadCase {
                name: format!("{f} N on the output face, the input faces free"),
                forces: loads::uniform_force(&mesh, &output, w, [0.0, f]),
                tractions: vec![(output.clone(), [0.0, f / area(&output)])],
            },
        ];
        let sets = ["input_left", "input_right", "output_top", "clamp_bottom"]
            .iter()
            .map(|&name| (name.to_string(), face_nodes(&mesh, &domain, name)))
            .collect();
        Ok(FullModel {
            clamp: face_nodes(&mesh, &domain, "clamp_bottom"),
            mesh,
            domain,
            sets,
            cases,
            input: [left, right],
            output,
        })
    }
}

impl FullModel {
    /// The CalculiX deck of this model.
    pub fn deck(
        &self,
        title: &str,
        material: &Elastic,
        width: f64,
        thickness_scale: f64,
    ) -> super::calculix::Deck<'_> {
        super::calculix::Deck {
            title: title.to_string(),
            mesh: &self.mesh,
            material: *material,
            width,
            sets: self.sets.clone(),
            clamp: self.clamp.clone(),
            cases: self.cases.clone(),
            thickness_scale,
        }
    }

    /// The displacements (full vectors) of the two load cases, by flexopt's own solve of
    /// this whole mesh, the clamping face held.
    pub fn solve(
        &self,
        material: &Elastic,
        width: f64,
        idealization: Idealization,
    ) -> Result<Vec<Vec<f64>>, FeError> {
        let mut fixed = vec![false; 2 * self.mesh.nodes.len()];
        for &n in &self.clamp {
            fixed[2 * n] = true;
            fixed[2 * n + 1] = true;
        }
        let zero = vec![0.0; fixed.len()];
        let loads: Vec<Vec<f64>> = self.cases.iter().map(|c| c.forces.clone()).collect();
        super::solve_static(
            &self.mesh,
            material,
            width,
            idealization,
            &fixed,
            &zero,
            &loads,
        )
    }

    /// `x_in`, `y_out` (input case) and the output face's displacement (output case) of
    /// the displacement fields of the two cases (full vectors).
    pub fn face_outputs(&self, u_input: &[f64], u_output: &[f64]) -> [f64; 3] {
        let left = loads::mean_displacement(&self.mesh, &self.input[0], u_input);
        let right = loads::mean_displacement(&self.mesh, &self.input[1], u_input);
        [
            right[0] - left[0],
            -loads::mean_displacement(&self.mesh, &self.output, u_input)[1],
            loads::mean_displacement(&self.mesh, &self.output, u_output)[1],
        ]
    }
}

/// Verifies the part of `model` at the design `x` (SI): the model's part and material.
pub fn verify_design(
    model: &dyn crate::model::Model,
    x: &[f64],
    settings: &VerifySettings,
) -> Result<Verification, FeError> {
    let spec = match model.part(x) {
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
