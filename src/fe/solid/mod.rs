//! The part in 3D: its 2D mesh extruded through the half-width into fifteen-node wedges
//! ([`extruded`], [`wedge`]), the mid-width plane held in z (the part and its loads are
//! symmetric about it), solved by the same sparse Cholesky as the 2D meshes
//! ([`crate::fe::assembly::Pattern`], three degrees of freedom a node).
//!
//! Neither 2D idealization is the part: plane stress holds for a plate thin against its
//! hinges, plane strain for one wide against them, and a 10 mm plate over 0.4 mm hinges is
//! neither. The 3D solve is the part itself, up to its discretization.

pub mod extruded;
pub mod wedge;

pub use extruded::{Extruded, Layers, SideFace};

use super::assembly::{adjacency_of, Pattern};
use super::element::Elastic;
use super::FeError;
use wedge::{DOFS, NODES};

/// The degrees of freedom held: every one of the nodes standing on the 2D nodes `clamped`,
/// x on those standing on `held_x` (a plane of symmetry at x = 0), z on the mid-width plane.
pub fn fixed(ext: &Extruded, clamped: &[usize], held_x: &[usize]) -> Vec<bool> {
    let mut fixed = vec![false; 3 * ext.nodes.len()];
    for n in ext.through(clamped) {
        fixed[3 * n..3 * n + 3].fill(true);
    }
    for n in ext.through(held_x) {
        fixed[3 * n] = true;
    }
    for node in 0..ext.flat.nodes.len() {
        if let Some(n) = ext.node(0, node) {
            fixed[3 * n + 2] = true;
        }
    }
    fixed
}

/// The displacements (full vectors, three a node) of `ext` under each of `loads` (full force
/// vectors), the degrees of freedom `fixed` held at zero; and the free degrees of freedom.
pub fn solve(
    ext: &Extruded,
    material: &Elastic,
    fixed: &[bool],
    loads: &[Vec<f64>],
) -> Result<(Vec<Vec<f64>>, usize), FeError> {
    let adj = adjacency_of(ext.nodes.len(), ext.elements.iter().map(|e| e.as_slice()));
    let pattern = Pattern::of_graph(&adj, 3, fixed)?;
    let lame = wedge::lame(material.youngs_modulus, material.poisson_ratio);
    let mut values = vec![0.0; pattern.entries()];
    // element matrices in parallel a block at a time, added in element order (the sum is
    // the same whatever the thread count)
    const BLOCK: usize = 512;
    for start in (0..ext.elements.len()).step_by(BLOCK) {
        use rayon::prelude::*;
        let end = (start + BLOCK).min(ext.elements.len());
        let matrices: Vec<Result<Box<[[f64; DOFS]; DOFS]>, FeError>> = (start..end)
            .into_par_iter()
            .map(|e| {
                wedge::stiffness(&ext.element_nodes(e), lame).ok_or_else(|| {
                    let p = ext.nodes[ext.elements[e][0]];
                    FeError::Mesh(format!(
                        "wedge {e} near ({:.4}, {:.4}, {:.4}) mm is inverted",
                        p[0] * 1e3,
                        p[1] * 1e3,
                        p[2] * 1e3
                    ))
                })
            })
            .collect();
        for (e, k) in (start..end).zip(matrices) {
            let k = k?;
            let dofs: [usize; DOFS] = std::array::from_fn(|d| 3 * ext.elements[e][d / 3] + d % 3);
            pattern.scatter(&mut values, &dofs, |a, b| k[a][b])?;
        }
    }
    let factor = pattern.factor(&pattern.matrix(values))?;
    let n = pattern.dofs.count();
    let mut rhs = faer::Mat::<f64>::zeros(n, loads.len());
    for (j, f) in loads.iter().enumerate() {
        for (dof, &v) in f.iter().enumerate() {
            if let Some(i) = pattern.dofs.free(dof) {
                rhs[(i, j)] += v;
            }
        }
    }
    factor.solve(&mut rhs);
    let zero = vec![0.0; 3 * ext.nodes.len()];
    let fields = (0..loads.len())
        .map(|j| {
            let x: Vec<f64> = (0..n).map(|i| rhs[(i, j)]).collect();
            pattern.dofs.expand(&x, &zero)
        })
        .collect();
    Ok((fields, n))
}

/// The nodal forces (full vector) of a uniform traction `traction` (Pa) over `faces`.
pub fn traction_forces(ext: &Extruded, faces: &[SideFace], traction: [f64; 3]) -> Vec<f64> {
    let mut f = vec![0.0; 3 * ext.nodes.len()];
    ext.over_faces(faces, |n, da, el| {
        for k in 0..NODES {
            for c in 0..3 {
                f[3 * el[k] + c] += n[k] * traction[c] * da;
            }
        }
    });
    f
}

/// The area of `faces`.
pub fn area(ext: &Extruded, faces: &[SideFace]) -> f64 {
    let mut a = 0.0;
    ext.over_faces(faces, |_, da, _| a += da);
    a
}

/// The mean displacement over `faces` of the field `u` (full vector, three a node).
pub fn mean_displacement(ext: &Extruded, faces: &[SideFace], u: &[f64]) -> [f64; 3] {
    let (mut s, mut a) = ([0.0; 3], 0.0);
    ext.over_faces(faces, |n, da, el| {
        for k in 0..NODES {
            for c in 0..3 {
                s[c] += n[k] * u[3 * el[k] + c] * da;
            }
        }
        a += da;
    });
    s.map(|v| v / a)
}

/// The von Mises stress at each node under the field `u`, the elements' nodal stresses
/// averaged over the elements that share the node.
pub fn nodal_von_mises(ext: &Extruded, material: &Elastic, u: &[f64]) -> Vec<f64> {
    let lame = wedge::lame(material.youngs_modulus, material.poisson_ratio);
    let refs = wedge::node_coordinates();
    let mut sum = vec![[0.0; 6]; ext.nodes.len()];
    let mut count = vec![0u32; ext.nodes.len()];
    for (e, el) in ext.elements.iter().enumerate() {
        let x = ext.element_nodes(e);
        let ue: [f64; DOFS] = std::array::from_fn(|d| u[3 * el[d / 3] + d % 3]);
        for (k, &r) in refs.iter().enumerate() {
            let s = wedge::stress(&x, lame, &ue, r);
            for c in 0..6 {
                sum[el[k]][c] += s[c];
            }
            count[el[k]] += 1;
        }
    }
    sum.iter()
        .zip(&count)
        .map(|(s, &c)| wedge::von_mises(s.map(|v| v / f64::from(c.max(1)))))
        .collect()
}
