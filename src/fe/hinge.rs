//! One hinge on its own by finite elements, as the literature's checks of notch hinges
//! model it: the hinge between two square blocks of its root thickness (a notch is cut into
//! a bar, whose edges its arcs meet smoothly), the blocks a thousand times stiffer, the
//! first clamped on its far face, the second loaded on its far face by a pure moment, a
//! transverse force (the parabolic shear of a beam) and an axial force. The loaded face's
//! mean deflection and rotation, carried back across the rigid block to the hinge's end,
//! give the four compliances of paper 004's Eq. 1, each estimated on three uniformly
//! refined meshes: the check the accuracy table holds the closed forms against. The
//! stress concentration comes from the moment again with the blocks as elastic as the
//! hinge, as the links of a part are.

use serde::Serialize;

use super::assembly::Pattern;
use super::geometry::{Domain, Edge};
use super::mesh::{mesh, Mesh};
use super::richardson::{estimate, Estimate};
use super::stress::nodal_stresses;
use super::{loads, Elastic, FeError, Idealization};
use crate::model::hinge::{Compliance, HingeKind};
use crate::part::outline::Arc as BulgeArc;
use crate::part::Vertex;

/// The FE compliances of one hinge, each with its error estimate.
#[derive(Debug, Clone, Serialize)]
pub struct HingeFe {
    pub c11: Estimate,
    pub c22: Estimate,
    pub c23: Estimate,
    /// The slope per transverse force: `c23` again by reciprocity (a check of the FE).
    pub c32: Estimate,
    pub c33: Estimate,
    /// Under the pure moment: the largest von Mises stress over the beam stress at the
    /// thinnest section, `6 M / (w t^2)`: the notch's stress concentration.
    pub concentration: Estimate,
    /// The slope per moment with the blocks as elastic as the hinge: the hinge and one root
    /// thickness of the bar it is cut in on each side. Against `c33` it tells how much of
    /// the rotation happens beside the hinge, where a mechanism's rigid links take none.
    pub c33_elastic_blocks: Estimate,
    /// Elements of each mesh.
    pub elements: Vec<usize>,
    /// Each coefficient's (c11, c22, c23, c32, c33) relative change over the last
    /// refinement: the error to quote where the extrapolation does not apply.
    pub last_change: [f64; 5],
}

impl HingeFe {
    /// The larger of each coefficient's estimated error (or last change, where the
    /// extrapolation does not apply).
    pub fn error(&self) -> f64 {
        [&self.c11, &self.c22, &self.c23, &self.c32, &self.c33]
            .iter()
            .zip(self.last_change)
            .map(|(e, change)| e.relative_error.unwrap_or(change))
            .fold(0.0, f64::max)
    }
}

impl HingeFe {
    /// The finest values as a [`Compliance`].
    pub fn compliance(&self) -> Compliance<f64> {
        Compliance {
            c11: self.c11.value,
            c22: self.c22.value,
            c23: self.c23.value,
            c33: self.c33.value,
        }
    }
}

/// The hinge's outline (m): along its bottom, up its end face, back along its top, down its
/// start face.
fn outline(kind: HingeKind, dims: &[f64]) -> Vec<Edge> {
    let profile = kind.outline(dims);
    let arcs = |path: &[([f64; 2], f64)]| -> Vec<Edge> {
        path.windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let va = Vertex {
                    x: a.0[0],
                    y: a.0[1],
                    bulge: a.1,
                };
                let vb = Vertex {
                    x: b.0[0],
                    y: b.0[1],
                    bulge: 0.0,
                };
                match BulgeArc::from_bulge(va, vb) {
                    Some(arc) => Edge::Arc {
                        centre: arc.centre,
                        radius: arc.radius,
                        start: arc.start,
                        sweep: arc.sweep,
                    },
                    None => Edge::Line { a: a.0, b: b.0 },
                }
            })
            .collect()
    };
    // the bottom: the profile mirrored, left to right, its arcs turning the other way
    let bottom: Vec<([f64; 2], f64)> = profile.iter().map(|v| ([v[0], -v[1]], -v[2])).collect();
    // the top: right to left, each arc from the next point back
    let top: Vec<([f64; 2], f64)> = (0..profile.len())
        .rev()
        .map(|k| {
            let bulge = if k > 0 { -profile[k - 1][2] } else { 0.0 };
            ([profile[k][0], profile[k][1]], bulge)
        })
        .collect();
    let (l, h) = (kind.length(dims), profile[0][1]);
    let b = block(h);
    let mut edges = vec![Edge::Line {
        a: [-b, -h],
        b: [0.0, -h],
    }];
    edges.extend(arcs(&bottom));
    edges.push(Edge::Line {
        a: [l, -h],
        b: [l + b, -h],
    });
    edges.push(Edge::Line {
        a: [l + b, -h],
        b: [l + b, h],
    });
    edges.push(Edge::Line {
        a: [l + b, h],
        b: [l, h],
    });
    edges.extend(arcs(&top));
    edges.push(Edge::Line {
        a: [0.0, h],
        b: [-b, h],
    });
    edges.push(Edge::Line {
        a: [-b, h],
        b: [-b, -h],
    });
    edges
}

/// The blocks' length for a root half thickness `h`: the root thickness, so that the
/// clamp's and the load's local disturbances have faded where the hinge begins.
fn block(h: f64) -> f64 {
    2.0 * h
}

/// The blocks' stiffness against the hinge's.
const RIGID: f64 = 1e3;

/// The FE compliances of a hinge of `kind` and `dims` (SI), `width` wide, on three meshes
/// (four elements through the local thickness on the first, then halved twice).
pub fn single_hinge(
    kind: HingeKind,
    dims: &[f64],
    width: f64,
    material: &Elastic,
    idealization: Idealization,
) -> Result<HingeFe, FeError> {
    let domain = Domain {
        loops: vec![outline(kind, dims)],
        faces: Vec::new(),
        hinges: Vec::new(),
    };
    let l = kind.length(dims);
    let h = 0.5 * kind.root_thickness(dims);
    let t_min = kind.least_thickness(dims);
    let size = move |p: [f64; 2]| {
        let xi = (p[0] / l).clamp(0.0, 1.0);
        0.25 * kind.thickness_at(dims, xi)
    };
    let mut m = mesh(&domain, &size, 0.5 * h)?;
    let mut values: Vec<[f64; 7]> = Vec::new();
    let mut elements = Vec::new();
    for _ in 0..3 {
        values.push(one_mesh(&m, l, h, t_min, width, material, idealization)?);
        elements.push(m.elements.len());
        m = m.refined(&domain);
    }
    let series = |k: usize| estimate(&values.iter().map(|v| v[k]).collect::<Vec<_>>());
    let change = |k: usize| ((values[2][k] - values[1][k]) / values[2][k]).abs();
    Ok(HingeFe {
        last_change: [change(0), change(1), change(2), change(3), change(4)],
        c11: series(0),
        c22: series(1),
        c23: series(2),
        c32: series(3),
        c33: series(4),
        concentration: series(5),
        c33_elastic_blocks: series(6),
        elements,
    })
}

/// `c11, c22, c23, c32, c33`, the concentration and `c33` with elastic blocks on one mesh.
fn one_mesh(
    m: &Mesh,
    l: f64,
    h: f64,
    t_min: f64,
    width: f64,
    material: &Elastic,
    idealization: Idealization,
) -> Result<[f64; 7], FeError> {
    let b = block(h);
    let tol = 1e-9 * l.max(h);
    let mut fixed = vec![false; 2 * m.nodes.len()];
    for n in m.nodes_on([-b, -h], [-b, h], tol) {
        fixed[2 * n] = true;
        fixed[2 * n + 1] = true;
    }
    let end = m.edges_on([l + b, -h], [l + b, h], tol);
    let i = width * (2.0 * h).powi(3) / 12.0;
    // unit loads on the loaded block's face: moment, transverse force, axial force
    let moment = loads::traction_forces(m, &end, width, |p| [-p[1] / i, 0.0]);
    let shear = loads::traction_forces(m, &end, width, |p| {
        [0.0, 1.5 / (2.0 * h * width) * (1.0 - (p[1] / h).powi(2))]
    });
    let axial = loads::uniform_force(m, &end, width, [1.0, 0.0]);
    let pattern = Pattern::new(m, &fixed)?;
    let inside = |e: usize| {
        let c = m.centre(e);
        (0.0..=l).contains(&c[0])
    };
    let k = pattern.stiffness_scaled(m, material, width, idealization, &[], &|e| {
        if inside(e) {
            1.0
        } else {
            RIGID
        }
    })?;
    let factor = pattern.factor(&k)?;
    let n = pattern.dofs.count();
    let cases = [moment, shear, axial];
    let mut rhs = faer::Mat::<f64>::zeros(n, cases.len());
    for (j, f) in cases.iter().enumerate() {
        for (d, &v) in f.iter().enumerate() {
            if let Some(r) = pattern.dofs.free(d) {
                rhs[(r, j)] = v;
            }
        }
    }
    factor.solve(&mut rhs);
    let zero = vec![0.0; fixed.len()];
    let u: Vec<Vec<f64>> = (0..cases.len())
        .map(|j| {
            pattern
                .dofs
                .expand(&(0..n).map(|r| rhs[(r, j)]).collect::<Vec<_>>(), &zero)
        })
        .collect();
    // the loaded face's mean displacements and its rotation (least squares: u_x = -theta y)
    let face = |u: &[f64]| -> [f64; 3] {
        let mean = loads::mean_displacement(m, &end, u);
        let y = loads::traction_forces(m, &end, 1.0, |p| [p[1], 0.0]);
        let y2 = loads::traction_forces(m, &end, 1.0, |p| [p[1] * p[1], 0.0]);
        let uy: f64 = y.iter().zip(u).step_by(2).map(|(w, ux)| w * ux).sum();
        let second: f64 = y2.iter().step_by(2).sum();
        [mean[0], mean[1], -uy / second]
    };
    let (fm, fv, fa) = (face(&u[0]), face(&u[1]), face(&u[2]));
    // back across the rigid block to the hinge's end: the moment there is M + V b, the
    // deflection there the face's less the rotation times b
    let c33 = fm[2];
    let c23 = fm[1] - fm[2] * b;
    let c32 = fv[2] - c33 * b;
    let c22 = fv[1] - fv[2] * b - c23 * b;
    // the peak von Mises stress in the hinge under the moment against the beam stress at
    // its thinnest section, 6 M / (w t^2), with the blocks of the hinge's own material: a
    // notch's concentration depends on its shoulders' stiffness (a rigid shoulder lowers a
    // corner fillet's by a tenth), and in a part the hinge meets elastic links
    let elastic = pattern.stiffness_scaled(m, material, width, idealization, &[], &|_| 1.0)?;
    let mut bending = faer::Mat::<f64>::zeros(n, 1);
    for (dof, &v) in cases[0].iter().enumerate() {
        if let Some(r) = pattern.dofs.free(dof) {
            bending[(r, 0)] = v;
        }
    }
    pattern.factor(&elastic)?.solve(&mut bending);
    let u_bending = pattern
        .dofs
        .expand(&(0..n).map(|r| bending[(r, 0)]).collect::<Vec<_>>(), &zero);
    let d = material.d_matrix(idealization);
    let stresses = nodal_stresses(m, &d, &u_bending);
    let peak = m
        .nodes
        .iter()
        .zip(&stresses)
        .filter(|(p, _)| p[0] > 0.0 && p[0] < l)
        .map(|(_, s)| material.von_mises(*s, idealization))
        .fold(0.0, f64::max);
    let beam = 6.0 / (width * t_min * t_min);
    Ok([fa[0], c22, c23, c32, c33, peak / beam, face(&u_bending)[2]])
}
