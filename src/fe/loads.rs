//! Loads on the outline and averages over it: consistent nodal forces of a traction along
//! quadratic edges, and the mean displacement of a face.

use super::mesh::Mesh;

/// Gauss-Legendre, three points on [0, 1]: exact for a quadratic edge's straight length
/// times a quartic.
const EDGE_GAUSS: [(f64, f64); 3] = [
    (0.112_701_665_379_258_3, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

/// The quadratic edge's shape functions at `s` in [0, 1] (nodes: start, middle, end) and
/// their derivatives.
fn edge_shape(s: f64) -> ([f64; 3], [f64; 3]) {
    (
        [
            (1.0 - s) * (1.0 - 2.0 * s),
            4.0 * s * (1.0 - s),
            s * (2.0 * s - 1.0),
        ],
        [4.0 * s - 3.0, 4.0 - 8.0 * s, 4.0 * s - 1.0],
    )
}

/// Integrates `f(point, shape values, ds)` over the edges (each `[start, middle, end]`).
fn over_edges(
    mesh: &Mesh,
    edges: &[[usize; 3]],
    mut f: impl FnMut([f64; 2], [f64; 3], f64, [usize; 3]),
) {
    for e in edges {
        let x = e.map(|n| mesh.nodes[n]);
        for (s, w) in EDGE_GAUSS {
            let (n, dn) = edge_shape(s);
            let mut p = [0.0; 2];
            let mut t = [0.0; 2];
            for k in 0..3 {
                p[0] += n[k] * x[k][0];
                p[1] += n[k] * x[k][1];
                t[0] += dn[k] * x[k][0];
                t[1] += dn[k] * x[k][1];
            }
            f(p, n, w * t[0].hypot(t[1]), *e);
        }
    }
}

/// The nodal forces (full vector, two a node) of the traction `traction(point)` (Pa) over
/// `edges`, on a plate `width` wide.
pub fn traction_forces(
    mesh: &Mesh,
    edges: &[[usize; 3]],
    width: f64,
    traction: impl Fn([f64; 2]) -> [f64; 2],
) -> Vec<f64> {
    let mut f = vec![0.0; 2 * mesh.nodes.len()];
    over_edges(mesh, edges, |p, n, ds, e| {
        let t = traction(p);
        for k in 0..3 {
            f[2 * e[k]] += n[k] * t[0] * ds * width;
            f[2 * e[k] + 1] += n[k] * t[1] * ds * width;
        }
    });
    f
}

/// The length of `edges`.
pub fn length(mesh: &Mesh, edges: &[[usize; 3]]) -> f64 {
    let mut l = 0.0;
    over_edges(mesh, edges, |_, _, ds, _| l += ds);
    l
}

/// A force `total` (N) spread evenly over `edges`.
pub fn uniform_force(mesh: &Mesh, edges: &[[usize; 3]], width: f64, total: [f64; 2]) -> Vec<f64> {
    let area = length(mesh, edges) * width;
    traction_forces(mesh, edges, width, |_| [total[0] / area, total[1] / area])
}

/// The mean displacement over `edges` of the displacement field `u` (full vector).
pub fn mean_displacement(mesh: &Mesh, edges: &[[usize; 3]], u: &[f64]) -> [f64; 2] {
    let (mut s, mut l) = ([0.0; 2], 0.0);
    over_edges(mesh, edges, |_, n, ds, e| {
        for k in 0..3 {
            s[0] += n[k] * u[2 * e[k]] * ds;
            s[1] += n[k] * u[2 * e[k] + 1] * ds;
        }
        l += ds;
    });
    [s[0] / l, s[1] / l]
}
