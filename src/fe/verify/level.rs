//! One mesh of a verification: its conditions, its solves, its outputs.

use crate::fe::assembly::Pattern;
use crate::fe::element::{Elastic, Idealization};
use crate::fe::geometry::Domain;
use crate::fe::mesh::{EdgeNodes, Mesh};
use crate::fe::stress::{nodal_stresses, peak_von_mises, section, Locator};
use crate::fe::{loads, modal, FeError};
use crate::part::analysis::{ActuationCase, Analysis, Quantity};
use crate::part::half::SYMMETRY;
use crate::part::{stack_mass_share, Actuation};

use super::statement::{
    case_forces, measure, output_values, static_value, Edges, HalfSpring, Stated,
};

/// What the part gives the analysis.
#[derive(Debug, Clone)]
pub(super) struct Setup {
    pub(super) domain: Domain,
    pub(super) material: Elastic,
    pub(super) width: f64,
    pub(super) actuation: Actuation,
    pub(super) body_stiffening: f64,
    /// The part's statement, for its outputs and its actuation case.
    pub(super) analysis: Analysis,
    pub(super) actuation_case: ActuationCase,
    /// The statement on the half.
    pub(super) stated: Stated,
}

/// The element size at `p`: `t / n` on and around each hinge's thin section, growing by 0.3
/// of the distance from it, never above a tenth of the part (returned beside it: the coarsest
/// size, which the first mesh is never above).
pub fn size_function(domain: &Domain, per_thickness: f64) -> (impl Fn([f64; 2]) -> f64, f64) {
    let hinges: Vec<(crate::fe::geometry::Edge, f64)> = domain
        .hinges
        .iter()
        .map(|h| {
            (
                crate::fe::geometry::Edge::Line {
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
pub(super) fn face_nodes(m: &Mesh, domain: &Domain, name: &str) -> Vec<usize> {
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

pub(super) fn face_edges(m: &Mesh, domain: &Domain, name: &str) -> Result<Vec<EdgeNodes>, FeError> {
    let tol = 1e-9 * domain.size();
    let edges: Vec<EdgeNodes> = domain
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

/// A mesh's one pattern: the clamped faces fixed, every other condition held by springs on
/// the diagonal (stiff ones, [`PENALTY`] times the stiffest diagonal entry, for conditions
/// that are exact), so that one ordering and one symbolic factorization serve the static
/// cases and both families of modes.
pub(super) struct Holds {
    pub(super) pattern: Pattern,
    /// The degrees of freedom of the cut, in x and in y, and of the actuator's face along
    /// its axis (held when the actuator is much stiffer than the part).
    pub(super) cut_x: Vec<usize>,
    pub(super) cut_y: Vec<usize>,
    pub(super) actuator: Vec<usize>,
}

/// The stiffness of a spring that stands for a fixed degree of freedom, relative to the
/// stiffest diagonal entry: the held displacement is about `1e-9` of the others, and the
/// outputs move by as little (measured against elimination in the tests).
const PENALTY: f64 = 1e9;

pub(super) fn holds(m: &Mesh, setup: &Setup) -> Result<Holds, FeError> {
    let d = &setup.domain;
    let mut clamp: Vec<usize> = setup
        .stated
        .clamped
        .iter()
        .flat_map(|name| face_nodes(m, d, name))
        .collect();
    clamp.sort_unstable();
    clamp.dedup();
    let mut fixed = vec![false; 2 * m.nodes.len()];
    for &n in &clamp {
        fixed[2 * n] = true;
        fixed[2 * n + 1] = true;
    }
    let cut = face_nodes(m, d, SYMMETRY);
    // an actuator along x holds the x degrees of freedom, one along y the y ones
    let actuator = setup.stated.spring.as_ref().map_or(Vec::new(), |s| {
        let along = usize::from(s.direction[1].abs() > s.direction[0].abs());
        face_nodes(m, d, &s.face)
            .iter()
            .map(|&n| 2 * n + along)
            .collect()
    });
    Ok(Holds {
        pattern: Pattern::new(m, &fixed)?,
        cut_x: cut.iter().map(|&n| 2 * n).collect(),
        cut_y: cut.iter().map(|&n| 2 * n + 1).collect(),
        actuator,
    })
}

/// One level's values (in the order of the analysis's outputs; the modal ones NaN without
/// a density), with the locations of the stresses and the actuation fields.
pub(super) struct LevelResult {
    pub(super) values: Vec<f64>,
    pub(super) peak_at: [f64; 2],
    /// The node of the peak stress.
    pub(super) peak_node: usize,
    pub(super) section_at: String,
    pub(super) section_point: [f64; 2],
    pub(super) displacement: Vec<f64>,
    pub(super) von_mises: Vec<f64>,
}

/// Masses spread over a face as a uniform load spreads a force (kg per degree of freedom):
/// each node its share of `mass[0]` along x and of `mass[1]` along y.
pub(super) fn face_masses(
    m: &Mesh,
    face: &[EdgeNodes],
    width: f64,
    mass: [f64; 2],
) -> Vec<(usize, f64)> {
    loads::uniform_force(m, face, width, mass)
        .into_iter()
        .enumerate()
        .filter(|&(_, v)| v != 0.0)
        .collect()
}

/// The stack's mass `mass` on its face in one family of modes (`stretched` where the stack
/// stretches: every mode of a stack on the ground, the symmetric ones of a stack between a
/// face and its mirror image): the share along the stack's axis on the degree of freedom
/// along it and the share across it on the other ([`stack_mass_share`]; exact for a stack
/// along x or y, as the actuator's springs are).
fn stack_masses(
    m: &Mesh,
    face: &[EdgeNodes],
    width: f64,
    spring: &HalfSpring,
    mass: f64,
    stretched: bool,
) -> Vec<(usize, f64)> {
    let (along, across) = stack_mass_share(mass, spring.factor > 1.0, stretched);
    let [nx, ny] = spring.direction;
    let length = nx.hypot(ny);
    let (cx, cy) = ((nx / length).powi(2), (ny / length).powi(2));
    face_masses(
        m,
        face,
        width,
        [along * cx + across * cy, along * cy + across * cx],
    )
}

fn column(x: &faer::Mat<f64>, j: usize) -> Vec<f64> {
    (0..x.nrows()).map(|i| x[(i, j)]).collect()
}

pub(super) fn solve_level(
    m: &Mesh,
    setup: &Setup,
    holds: &Holds,
    mass: Option<&faer::sparse::SparseColMat<usize, f64>>,
    idealization: Idealization,
    force: f64,
) -> Result<LevelResult, FeError> {
    let d = &setup.domain;
    let (w, mat) = (setup.width, &setup.material);
    let stated = &setup.stated;
    let edges = Edges::of(m, d, &stated.faces())?;
    let p = &holds.pattern;
    let in_hinge = |e: usize| {
        let c = m.centre(e);
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
    // the cases' loads on the half (a face across the axis carries half of its load)
    let loads: Vec<Vec<f64>> = stated
        .cases
        .iter()
        .map(|c| case_forces(m, &edges, w, c))
        .collect();
    let mut rhs = faer::Mat::<f64>::zeros(n, loads.len());
    for (j, f) in loads.iter().enumerate() {
        for (dof, &v) in f.iter().enumerate() {
            if let Some(i) = p.dofs.free(dof) {
                rhs[(i, j)] += v;
            }
        }
    }
    factor.solve(&mut rhs);
    let zero = vec![0.0; 2 * m.nodes.len()];
    let fields: Vec<Vec<f64>> = (0..loads.len())
        .map(|j| p.dofs.expand(&column(&rhs, j), &zero))
        .collect();
    let measured: Vec<f64> = stated
        .measures
        .iter()
        .map(|(case, terms)| measure(m, &edges, terms, &fields[*case]))
        .collect();
    let quantity = |k: usize| setup.analysis.outputs[k].quantity;

    // the actuation: the largest input force, the stresses it gives
    let a = &setup.actuation;
    let act = &setup.actuation_case;
    let stiffness =
        static_value(quantity(act.stiffness.0), &measured, force, a).unwrap_or(f64::NAN);
    let actuation_force = a.largest_force(stiffness);
    let scale = actuation_force / force;
    let u_act: Vec<f64> = fields[act.case].iter().map(|v| v * scale).collect();
    let dm = mat.d_matrix(idealization);
    let nodal = nodal_stresses(m, &dm, &u_act);
    let von_mises: Vec<f64> = nodal
        .iter()
        .map(|s| mat.von_mises(*s, idealization))
        .collect();
    let (peak, peak_node) = peak_von_mises(&nodal, mat, idealization);
    let locator = Locator::new(m);
    let mut best = (f64::NEG_INFINITY, String::new(), [0.0; 2]);
    // the hinges' resultants across two inner sections, at a quarter and three quarters of
    // their length: along a hinge free of loads the axial force is constant and the moment
    // linear (statics, exactly), so they give the resultants everywhere along it without
    // integrating across a root, where a sharp corner's stress is singular; the beam
    // stress `|N| / t + 6 |M| / t^2` is then taken where it is largest along the hinge's
    // own thickness, as the closed forms take it
    for h in &d.hinges {
        let len = h.length();
        let axis = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
        let at = |f: f64| {
            [
                h.start[0] + f * len * axis[0],
                h.start[1] + f * len * axis[1],
            ]
        };
        let cut = |f: f64| {
            section(
                m,
                &locator,
                &dm,
                &u_act,
                at(f),
                axis,
                h.thickness_at(f * len),
            )
            .ok_or_else(|| FeError::Solve(format!("a section of {} leaves the mesh", h.name)))
        };
        let (a, b) = (cut(0.25)?, cut(0.75)?);
        let axial = 0.5 * (a.axial + b.axial);
        const STATIONS: usize = 256;
        for k in 0..=STATIONS {
            let f = k as f64 / STATIONS as f64;
            let moment = a.moment + (f - 0.25) / 0.5 * (b.moment - a.moment);
            let t = h.thickness_at(f * len);
            let stress = axial.abs() / t + 6.0 * moment.abs() / (t * t);
            if stress > best.0 {
                let place = match k {
                    0 => "at its start".to_string(),
                    STATIONS => "at its end".to_string(),
                    _ => format!("{:.0} % along it", 100.0 * f),
                };
                best = (stress, format!("{}, {place}", h.name), at(f));
            }
        }
    }

    // the modes: the symmetric family with the actuator holding its face (springs of its
    // stiffness, each face node its share of 2 k_a as the other face is the mirror, or
    // held along its axis for an actuator much stiffer than the part); the antisymmetric
    // family with the cut held in y; each started from a static deflection close to its
    // lowest mode
    let mut f_output = f64::NAN;
    let mut f_first = f64::NAN;
    if let (Some(mass), Some(modal)) = (mass, &setup.analysis.modal) {
        let actuator: Vec<(usize, f64)> = match (&stated.spring, a.stiffness) {
            (None, _) => Vec::new(),
            (Some(_), None) => held(&holds.actuator),
            (Some(s), Some(ka)) => loads::uniform_force(m, edges.get(&s.face), w, s.direction)
                .iter()
                .enumerate()
                .filter(|(_, &v)| v != 0.0)
                // each node's share of the spring along the direction: `share n n^T`,
                // whose diagonal `share n_i^2` is `v n_i` (positive whichever way it acts)
                .map(|(dof, &v)| (dof, s.factor * ka * v * s.direction[dof % 2]))
                .collect(),
        };
        // the stack's mass on its face, its share by the family ([`stack_mass_share`])
        let mass_of = |stretched: bool| match &stated.spring {
            Some(s) if a.stack_mass > 0.0 => std::borrow::Cow::Owned(p.with_diagonal(
                mass,
                &stack_masses(m, edges.get(&s.face), w, s, a.stack_mass, stretched),
            )),
            _ => std::borrow::Cow::Borrowed(mass),
        };
        let lowest = |springs: Vec<(usize, f64)>,
                      load: &[f64],
                      mass: &faer::sparse::SparseColMat<usize, f64>|
         -> Result<f64, FeError> {
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
        f_output = lowest(symmetric, &loads[modal.start], &mass_of(true))?;
        let payload = stated.payload.as_ref().map_or(&modal.payload, |p| &p.0);
        let sideways = loads::uniform_force(m, edges.get(payload), w, [force, 0.0]);
        // a part solved whole has one family, found above
        f_first = if holds.cut_y.is_empty() {
            f_output
        } else {
            f_output.min(lowest(held(&holds.cut_y), &sideways, &mass_of(false))?)
        };
    }
    let values = output_values(&setup.analysis, &measured, force, a, |q| match q {
        Quantity::SectionStress => best.0,
        Quantity::PeakStress => peak,
        Quantity::SymmetricFrequency => f_output,
        _ => f_first,
    });
    Ok(LevelResult {
        values,
        peak_at: m.nodes[peak_node],
        peak_node,
        section_at: best.1,
        section_point: best.2,
        displacement: u_act,
        von_mises,
    })
}
