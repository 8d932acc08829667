//! Loads on the outline and averages over it: consistent nodal forces of a traction along
//! the elements' edges (their shape functions and rule the element's), and the mean
//! displacement of a face.

use super::element::{Array, Element};
use super::mesh::{EdgeNodes, Mesh};

/// Integrates `f(point, shape values, ds)` over the edges (each its nodes in order).
fn over_edges<E: Element>(
    mesh: &Mesh<E>,
    edges: &[EdgeNodes<E>],
    mut f: impl FnMut([f64; 2], E::PerEdge<f64>, f64, EdgeNodes<E>),
) {
    for e in edges {
        let x = E::PerEdge::from_fn(|k| mesh.nodes[e[k]]);
        for &(s, w) in E::edge_quadrature() {
            let (n, dn) = E::edge_shape(s);
            let mut p = [0.0; 2];
            let mut t = [0.0; 2];
            for k in 0..E::EDGE_NODES {
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
pub fn traction_forces<E: Element>(
    mesh: &Mesh<E>,
    edges: &[EdgeNodes<E>],
    width: f64,
    traction: impl Fn([f64; 2]) -> [f64; 2],
) -> Vec<f64> {
    let mut f = vec![0.0; 2 * mesh.nodes.len()];
    over_edges(mesh, edges, |p, n, ds, e| {
        let t = traction(p);
        for k in 0..E::EDGE_NODES {
            f[2 * e[k]] += n[k] * t[0] * ds * width;
            f[2 * e[k] + 1] += n[k] * t[1] * ds * width;
        }
    });
    f
}

/// The length of `edges`.
pub fn length<E: Element>(mesh: &Mesh<E>, edges: &[EdgeNodes<E>]) -> f64 {
    let mut l = 0.0;
    over_edges(mesh, edges, |_, _, ds, _| l += ds);
    l
}

/// A force `total` (N) spread evenly over `edges`.
pub fn uniform_force<E: Element>(
    mesh: &Mesh<E>,
    edges: &[EdgeNodes<E>],
    width: f64,
    total: [f64; 2],
) -> Vec<f64> {
    let area = length(mesh, edges) * width;
    traction_forces(mesh, edges, width, |_| [total[0] / area, total[1] / area])
}

/// The mean displacement over `edges` of the displacement field `u` (full vector).
pub fn mean_displacement<E: Element>(
    mesh: &Mesh<E>,
    edges: &[EdgeNodes<E>],
    u: &[f64],
) -> [f64; 2] {
    let (mut s, mut l) = ([0.0; 2], 0.0);
    over_edges(mesh, edges, |_, n, ds, e| {
        for k in 0..E::EDGE_NODES {
            s[0] += n[k] * u[2 * e[k]] * ds;
            s[1] += n[k] * u[2 * e[k] + 1] * ds;
        }
        l += ds;
    });
    [s[0] / l, s[1] / l]
}
