//! One 3D solve of a verification: the half part's 2D mesh extruded through the half-width
//! ([`crate::fe::solid`]), the statement's loads as uniform tractions on the faces through
//! the width, its measures as the faces' mean displacements.

use crate::fe::mesh::Mesh;
use crate::fe::solid::{self, Extruded, Layers};
use crate::fe::FeError;
use crate::part::analysis::Quantity;
use crate::part::half::SYMMETRY;

use serde::Serialize;

use super::level::{face_nodes, Setup};
use super::statement::{measure_solid, output_values, static_value, Edges};
use super::Output;
use crate::fe::richardson::{estimate, Estimate};

/// One 3D solve's values (in the order of the analysis's outputs; NaN for those it does
/// not give: the modes and the section stress).
pub(super) struct SolidResult {
    pub(super) values: Vec<f64>,
    pub(super) peak_at: [f64; 3],
    pub(super) dofs: usize,
}

/// The 3D solve of `m` in `layers`; its peak stress the largest von Mises stress through
/// the width over the 2D node `peak_node` (where the plane-strain peak is on this mesh).
pub(super) fn solve_solid(
    m: &Mesh,
    setup: &Setup,
    layers: Layers,
    force: f64,
    peak_node: usize,
) -> Result<SolidResult, FeError> {
    let d = &setup.domain;
    let stated = &setup.stated;
    let ext = Extruded::new(m, layers);
    let mut clamped: Vec<usize> = stated
        .clamped
        .iter()
        .flat_map(|name| face_nodes(m, d, name))
        .collect();
    clamped.sort_unstable();
    clamped.dedup();
    let fixed = solid::fixed(&ext, &clamped, &face_nodes(m, d, SYMMETRY));
    let edges = Edges::of(m, d, &stated.faces())?;
    // a load's total on the whole width: on the half-width, half of it, as a traction
    // over the face's whole area (twice the half's)
    let loads: Vec<Vec<f64>> = stated
        .cases
        .iter()
        .map(|case| {
            let mut f = vec![0.0; 3 * ext.nodes.len()];
            for a in case {
                let on = ext.side_faces(edges.get(&a.face));
                let whole = 2.0 * solid::area(&ext, &on);
                let t = [a.total[0] / whole, a.total[1] / whole, 0.0];
                for (s, v) in f.iter_mut().zip(solid::traction_forces(&ext, &on, t)) {
                    *s += v;
                }
            }
            f
        })
        .collect();
    let (fields, dofs) = solid::solve(&ext, &setup.material, &fixed, &loads)?;
    let measured: Vec<f64> = stated
        .measures
        .iter()
        .map(|(case, terms)| measure_solid(&ext, &edges, terms, &fields[*case]))
        .collect();
    let quantity = |k: usize| setup.analysis.outputs[k].quantity;
    let act = &setup.actuation_case;
    let a = &setup.actuation;
    let stiffness =
        static_value(quantity(act.stiffness.0), &measured, force, a).unwrap_or(f64::NAN);
    let scale = a.largest_force(stiffness) / force;
    let u_act: Vec<f64> = fields[act.case].iter().map(|v| v * scale).collect();
    let von_mises = solid::nodal_von_mises(&ext, &setup.material, &u_act);
    // through the width at the 2D peak: the same place on every solve, so that the ratio
    // to plane strain follows the design smoothly (the largest over the whole mesh jumps
    // between nodes of the coarse mesh as the design moves: measured, by 0.5 % for a step
    // of 3e-3 of the bounds)
    let (peak, node) = (0..layers.planes())
        .filter_map(|plane| ext.node(plane, peak_node))
        .map(|n| (von_mises[n], n))
        .fold(
            (f64::NEG_INFINITY, 0),
            |best, v| if v.0 > best.0 { v } else { best },
        );
    let values = output_values(&setup.analysis, &measured, force, a, |q| match q {
        Quantity::PeakStress => peak,
        _ => f64::NAN,
    });
    Ok(SolidResult {
        values,
        peak_at: ext.nodes[node],
        dofs,
    })
}

/// One 3D solve of the check, as `verify.json` lists it.
#[derive(Debug, Clone, Serialize)]
pub struct SolidSolve {
    /// The level of the in-plane mesh.
    pub level: usize,
    pub layers: usize,
    pub dofs: usize,
    pub seconds: f64,
}

/// The 3D check: each static output (and the peak stress) of the part in 3D.
///
/// A multi-fidelity estimate: the finest plane-strain value times the ratio 3D / plane
/// strain on the first in-plane mesh with [`SOLID_LAYERS`] layers, so that the in-plane
/// discretization is the fine 2D mesh's and the 3D solves stay small. Measured on wei2017's
/// optimum, the ratio changes by 1e-5 from the first in-plane mesh to the second (at one
/// layer and at four), while the 3D values themselves change by 1e-3: the ratio converges
/// much faster in the plane than the values do. Its error, stated, is the sum of three:
/// the plane-strain value's own estimate, the ratio's through the width (Richardson over
/// 1, 2 and 4 layers, [`estimate`], where the three converge; else, as a peak stress's
/// sequence turns, the spread of 2 and 4 layers), and the ratio's change from the first in-plane mesh to
/// the second at one layer (no extrapolation: the change itself).
#[derive(Debug, Clone)]
pub struct Solid3d {
    /// The finest grading through the half-width.
    pub layers: Layers,
    pub solves: Vec<SolidSolve>,
    /// The outputs the 3D check gives, their `values` the estimate at 1, 2, 4 layers.
    pub outputs: Vec<Output>,
    /// The actuation force on each loaded face of the actuation case, from the 3D stiffness
    /// (N).
    pub actuation_force: f64,
}

/// Layers through the half-width of the finest 3D solve (the sequence: 1, 2, 4).
pub const SOLID_LAYERS: usize = 4;

/// The free degrees of freedom of `m` extruded in `layers` layers, about (every node's
/// three).
fn solid_dofs(m: &Mesh, layers: usize) -> usize {
    let corners = crate::fe::solid::extruded::corners(m)
        .iter()
        .filter(|&&c| c)
        .count();
    3 * ((layers + 1) * m.nodes.len() + layers * corners)
}

/// The 3D check of a verification whose meshes are `meshes` and whose plane-strain results
/// are `strain` (values per level, and the outputs' estimates); `None` with the reason
/// where the budget does not allow it.
pub(super) fn check(
    meshes: &[Mesh],
    setup: &Setup,
    strain_levels: &[(Vec<f64>, usize)],
    strain: &[Output],
    force: f64,
    max_dofs: usize,
) -> Result<Result<Solid3d, String>, FeError> {
    let need = solid_dofs(&meshes[0], SOLID_LAYERS);
    if need > max_dofs {
        return Ok(Err(format!(
            "the 3D check would need about {need} degrees of freedom, more than the budget of \
             {max_dofs} (--max-dofs)"
        )));
    }
    let thinnest = setup.domain.thinnest_hinge();
    let layers = |n: usize| Layers::graded(n, setup.width, thinnest);
    let timed = |level: usize, n: usize| -> Result<(SolidResult, SolidSolve), FeError> {
        let start = std::time::Instant::now();
        let r = solve_solid(
            &meshes[level],
            setup,
            layers(n),
            force,
            strain_levels[level].1,
        )?;
        let solve = SolidSolve {
            level,
            layers: n,
            dofs: r.dofs,
            seconds: start.elapsed().as_secs_f64(),
        };
        Ok((r, solve))
    };
    // the largest solve beside the others (two cores: about the same time each way)
    let in_plane = meshes.len() >= 2 && solid_dofs(&meshes[1], 1) <= max_dofs;
    let (finest, rest) = rayon::join(
        || timed(0, SOLID_LAYERS),
        || -> Result<Vec<(SolidResult, SolidSolve)>, FeError> {
            let mut rest = vec![timed(0, 1)?, timed(0, 2)?];
            if in_plane {
                rest.push(timed(1, 1)?);
            }
            Ok(rest)
        },
    );
    let mut rest = rest?;
    let finest = finest?;
    let second = if in_plane { rest.pop() } else { None };
    let through = [&rest[0].0, &rest[1].0, &finest.0];
    let mut outputs = Vec::new();
    for o in strain {
        let k = o.id.0;
        let ratio = |r: &SolidResult, level: usize| r.values[k] / strain_levels[level].0[k];
        let ratios: Vec<f64> = through.iter().map(|r| ratio(r, 0)).collect();
        if !ratios.iter().all(|r| r.is_finite()) {
            continue;
        }
        let mut layered = estimate(&ratios);
        if !layered.converging {
            // one layer has no zone at the free face, where a stress peaks: for a peak it
            // lies outside the asymptotic range, and the spread of the last two (2 and 4
            // layers) is the error quoted, never an extrapolation
            layered.relative_error = Some((ratios[2] - ratios[1]).abs() / ratios[2].abs());
            layered.oscillating = true;
        }
        let moved = second.as_ref().map(|(r, _)| {
            let (a, b) = (ratio(&rest[0].0, 0), ratio(r, 1));
            (b - a).abs() / b.abs()
        });
        let value = o.estimate.value * ratios[2];
        let e = o.estimate;
        let accepted = |e: &Estimate| e.converging || e.oscillating;
        // converging where both parts extrapolate; within its spread where either turns
        let known = accepted(&e) && accepted(&layered) && moved.is_some();
        let converging = known && e.converging && layered.converging;
        let relative_error = match (e.relative_error, layered.relative_error, moved) {
            (Some(a), Some(b), Some(c)) => Some(a + b + c),
            _ => None,
        };
        outputs.push(Output {
            id: o.id,
            name: o.name,
            unit: o.unit,
            values: ratios.iter().map(|r| o.estimate.value * r).collect(),
            estimate: Estimate {
                value,
                extrapolated: e.extrapolated.zip(layered.extrapolated).map(|(v, r)| v * r),
                relative_error,
                order: layered.order,
                converging,
                oscillating: known && !converging,
            },
            location_mm: (setup.analysis.outputs[k].quantity == Quantity::PeakStress)
                .then(|| [finest.0.peak_at[0] * 1e3, finest.0.peak_at[1] * 1e3]),
            at: None,
        });
    }
    let stiffness = outputs
        .iter()
        .find(|o| o.id == setup.actuation_case.stiffness)
        .map_or(f64::NAN, |o| o.estimate.value);
    let a = &setup.actuation;
    let mut solves: Vec<SolidSolve> = rest.iter().map(|(_, s)| s.clone()).collect();
    solves.push(finest.1);
    if let Some((_, s)) = second {
        solves.push(s);
    }
    Ok(Ok(Solid3d {
        layers: layers(SOLID_LAYERS),
        solves,
        outputs,
        actuation_force: a.largest_force(stiffness),
    }))
}
