//! A 2D mesh of six-node triangles extruded through the half-width of the plate into
//! fifteen-node wedges ([`super::wedge`]): the layers graded towards the free face, the
//! mid-width plane (`z = 0`) a plane of symmetry.

use crate::fe::element::Element;
use crate::fe::element::Tri6;
use crate::fe::mesh::{EdgeNodes, Mesh};

use super::wedge::{self, NODES};

/// The layers through the half-width `[0, w / 2]`: `z = (w / 2) phi(s)` at `s = k / n`,
/// where `phi(s) = 1 - (e^(beta (1 - s)) - 1) / (e^beta - 1)` puts thin layers at the free
/// face `s = 1` and thick ones at mid-width; the last layer is `e^beta` times thinner than
/// the first, nearly. Doubling `n` halves every layer in `s`, so that a sequence of layer
/// counts is a uniform refinement of one graded mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layers {
    pub count: usize,
    pub half_width: f64,
    pub beta: f64,
}

impl Layers {
    /// `count` layers over the half of `width`, graded so that the outer layers are about as
    /// thick as the thinnest hinge `thinnest` is at `count = 4` (uniform where the half-width
    /// is no thicker than that hinge).
    pub fn graded(count: usize, width: f64, thinnest: f64) -> Self {
        let half_width = 0.5 * width;
        Layers {
            count,
            half_width,
            beta: (half_width / thinnest).max(1.0).ln(),
        }
    }

    /// The z of plane `p` of the `2 n + 1` planes (the even ones bound the layers, the odd
    /// ones halve them).
    pub fn z(&self, plane: usize) -> f64 {
        let s = plane as f64 / (2 * self.count) as f64;
        if self.beta < 1e-12 {
            return self.half_width * s;
        }
        let phi = |s: f64| 1.0 - ((self.beta * (1.0 - s)).exp() - 1.0) / (self.beta.exp() - 1.0);
        if plane % 2 == 1 {
            // the middle of its layer, so that the wedges are straight through the width
            return 0.5 * (self.z(plane - 1) + self.z(plane + 1));
        }
        self.half_width * phi(s)
    }

    pub fn planes(&self) -> usize {
        2 * self.count + 1
    }
}

/// The extruded mesh.
#[derive(Debug, Clone)]
pub struct Extruded<'a> {
    pub flat: &'a Mesh<Tri6>,
    pub layers: Layers,
    /// The node id of `(plane, 2D node)`, `usize::MAX` where there is none (a midside node
    /// of the triangle on a middle plane).
    index: Vec<usize>,
    pub nodes: Vec<[f64; 3]>,
    pub elements: Vec<[usize; NODES]>,
}

/// A face of the extruded mesh on the outline: a boundary edge of the 2D mesh through one
/// layer, as the wedge it bounds and the triangle's side it stands on.
#[derive(Debug, Clone, Copy)]
pub struct SideFace {
    pub element: usize,
    pub side: (usize, usize),
}

/// Which of `flat`'s nodes are corners of its triangles: the nodes that stand on the middle
/// plane of a layer too (the midside nodes stand on its faces only).
pub fn corners(flat: &Mesh<Tri6>) -> Vec<bool> {
    let mut corner = vec![false; flat.nodes.len()];
    for el in &flat.elements {
        for &c in &el[..3] {
            corner[c] = true;
        }
    }
    corner
}

impl<'a> Extruded<'a> {
    pub fn new(flat: &'a Mesh<Tri6>, layers: Layers) -> Self {
        let n2 = flat.nodes.len();
        let planes = layers.planes();
        let corner = corners(flat);
        let mut index = vec![usize::MAX; planes * n2];
        let mut nodes = Vec::new();
        // plane by plane, so that the numbering follows the 2D one on each
        for plane in 0..planes {
            let z = layers.z(plane);
            for (i, p) in flat.nodes.iter().enumerate() {
                if plane % 2 == 0 || corner[i] {
                    index[plane * n2 + i] = nodes.len();
                    nodes.push([p[0], p[1], z]);
                }
            }
        }
        let mut elements = Vec::with_capacity(layers.count * flat.elements.len());
        for layer in 0..layers.count {
            for el in &flat.elements {
                elements.push(std::array::from_fn(|k| {
                    let (plane, node) = Tri6::EXTRUSION[k];
                    index[(2 * layer + plane) * n2 + el[node]]
                }));
            }
        }
        Extruded {
            flat,
            layers,
            index,
            nodes,
            elements,
        }
    }

    /// The node at `(plane, 2D node)`, if there is one.
    pub fn node(&self, plane: usize, node: usize) -> Option<usize> {
        let id = self.index[plane * self.flat.nodes.len() + node];
        (id != usize::MAX).then_some(id)
    }

    /// Every node standing on one of the 2D nodes `flat` (through the whole half-width).
    pub fn through(&self, flat: &[usize]) -> Vec<usize> {
        (0..self.layers.planes())
            .flat_map(|plane| flat.iter().filter_map(move |&n| self.node(plane, n)))
            .collect()
    }

    /// The coordinates of element `e`'s nodes.
    pub fn element_nodes(&self, e: usize) -> [[f64; 3]; NODES] {
        self.elements[e].map(|n| self.nodes[n])
    }

    /// The faces standing on the 2D boundary edges `edges`, through every layer.
    pub fn side_faces(&self, edges: &[EdgeNodes]) -> Vec<SideFace> {
        // each 2D boundary edge's triangle and side
        let mut sides = std::collections::HashMap::new();
        for (e, el) in self.flat.elements.iter().enumerate() {
            for &(i, j) in Tri6::SIDES {
                let (a, b) = (el[i], el[j]);
                sides.insert((a.min(b), a.max(b)), (e, (i, j)));
            }
        }
        let count = self.flat.elements.len();
        let mut faces = Vec::new();
        for edge in edges {
            let (a, b) = (edge[0], edge[Tri6::EDGE_NODES - 1]);
            if let Some(&(e, side)) = sides.get(&(a.min(b), a.max(b))) {
                for layer in 0..self.layers.count {
                    faces.push(SideFace {
                        element: layer * count + e,
                        side,
                    });
                }
            }
        }
        faces
    }

    /// Integrates `f(shape values, dA, element)` over `faces` (3 x 3 Gauss points a face:
    /// exact for the area of a quadratic edge's straight face and the mean of a quadratic
    /// field on it).
    pub fn over_faces(
        &self,
        faces: &[SideFace],
        mut f: impl FnMut(&[f64; NODES], f64, &[usize; NODES]),
    ) {
        let g = (0.6f64).sqrt();
        let along = crate::fe::element::QUADRATIC_EDGE_GAUSS;
        let through = [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)];
        for face in faces {
            let x = self.element_nodes(face.element);
            let el = &self.elements[face.element];
            for &(s, ws) in &along {
                for &(z, wz) in &through {
                    let r = wedge::on_side(face.side, s, z);
                    let n = wedge::shape(r);
                    let (ts, tz) = wedge::side_tangents(&x, face.side, s, z);
                    let cross = [
                        ts[1] * tz[2] - ts[2] * tz[1],
                        ts[2] * tz[0] - ts[0] * tz[2],
                        ts[0] * tz[1] - ts[1] * tz[0],
                    ];
                    let da =
                        (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
                    f(&n, ws * wz * da, el);
                }
            }
        }
    }
}
