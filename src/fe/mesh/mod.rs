//! Meshes of any [`Element`], and the sequence of them the error estimate extrapolates:
//! the first mesh and each uniform refinement of it (element size halved) come from the
//! element's [`Mesher`], since generating and splitting elements depends on their shape;
//! the six-node triangle's is in `triangles.rs`. What the mesh does once made (its
//! boundary edges on a segment, its mirror image) works for every element.
//!
//! Nodes on arcs are put on the arc, so the elements' edges there are curved
//! (isoparametric) and stay on the outline at every level.

use super::element::{Array, Element, PartElement};
use super::geometry::{Domain, Edge};
use super::FeError;

mod triangles;

/// A mesh, in metres. Without its element named, of the element the part's checks use,
/// [`PartElement`].
#[derive(Debug, Clone)]
pub struct Mesh<E: Element = PartElement> {
    pub nodes: Vec<[f64; 2]>,
    /// Each element's nodes, in the element's node order.
    pub elements: Vec<E::PerNode<usize>>,
    /// The edges on the outline (their nodes in order along them), with the index of the
    /// outline edge (in the order of [`Domain::loops`], flattened) they lie on.
    pub boundary: Vec<BoundaryEdge<E>>,
    /// How many times the first mesh was refined uniformly to give this one.
    pub level: usize,
}

/// The nodes of an edge of the outline, in order along it.
pub type EdgeNodes<E = PartElement> = <E as Element>::PerEdge<usize>;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryEdge<E: Element = PartElement> {
    pub nodes: EdgeNodes<E>,
    pub edge: usize,
}

/// An element's mesher: what makes the first mesh of an outline and refines it.
pub trait Mesher: Element {
    /// The first mesh of `domain`, elements sized by `size` (m, a function of the place),
    /// never larger than `max_size`, with at most `max_nodes` nodes ([`FeError::Budget`]
    /// when it would need more: the mesher stops before it holds much more than that).
    fn first_mesh(
        domain: &Domain,
        size: &dyn Fn([f64; 2]) -> f64,
        max_size: f64,
        max_nodes: usize,
    ) -> Result<Mesh<Self>, FeError>;

    /// `mesh` refined uniformly (element size halved); new nodes on the outline put on it
    /// exactly.
    fn refine(mesh: &Mesh<Self>, domain: &Domain) -> Mesh<Self>;
}

/// The first mesh of `domain` with the part's element ([`PartElement`]), elements
/// sized by `size` (m, a function of the place), never larger than `max_size`.
pub fn mesh(
    domain: &Domain,
    size: &dyn Fn([f64; 2]) -> f64,
    max_size: f64,
) -> Result<Mesh, FeError> {
    mesh_within(domain, size, max_size, MAX_NODES)
}

/// The most nodes a first mesh may have where no budget is given: 2 million (4 million
/// degrees of freedom, far above what a solve on a workstation holds; a bound, not a goal).
pub const MAX_NODES: usize = 2_000_000;

/// [`mesh`] with at most `max_nodes` nodes ([`FeError::Budget`] when it would need more).
pub fn mesh_within(
    domain: &Domain,
    size: &dyn Fn([f64; 2]) -> f64,
    max_size: f64,
    max_nodes: usize,
) -> Result<Mesh, FeError> {
    Mesher::first_mesh(domain, size, max_size, max_nodes)
}

impl<E: Mesher> Mesh<E> {
    /// The mesh refined uniformly (element size halved), by its element's mesher.
    pub fn refined(&self, domain: &Domain) -> Mesh<E> {
        E::refine(self, domain)
    }
}

impl<E: Element> Mesh<E> {
    /// The coordinates of element `e`'s nodes.
    pub fn element_nodes(&self, e: usize) -> E::PerNode<[f64; 2]> {
        let el = &self.elements[e];
        E::PerNode::from_fn(|k| self.nodes[el[k]])
    }

    /// The point at the centre of element `e`'s reference element.
    pub fn centre(&self, e: usize) -> [f64; 2] {
        E::point(&self.element_nodes(e), E::CENTRE)
    }

    /// The total area of the elements.
    pub fn area(&self) -> f64 {
        (0..self.elements.len())
            .map(|e| E::area(&self.element_nodes(e)))
            .sum()
    }

    /// The boundary edges whose nodes all lie on the segment `a`-`b` (within `tol`).
    pub fn edges_on(&self, a: [f64; 2], b: [f64; 2], tol: f64) -> Vec<EdgeNodes<E>> {
        let line = Edge::Line { a, b };
        self.boundary
            .iter()
            .filter(|e| {
                e.nodes
                    .as_ref()
                    .iter()
                    .all(|&n| line.nearest(self.nodes[n]).0 <= tol)
            })
            .map(|e| e.nodes)
            .collect()
    }

    /// The nodes on the segment `a`-`b` of the boundary, sorted, without repeats.
    pub fn nodes_on(&self, a: [f64; 2], b: [f64; 2], tol: f64) -> Vec<usize> {
        let mut n: Vec<usize> = self
            .edges_on(a, b, tol)
            .iter()
            .flat_map(|e| e.as_ref().iter().copied())
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// The whole of a mesh of the half `x >= 0` of a part symmetric about the y axis: the
    /// half and its mirror image, sharing the nodes on the axis (within `tol`).
    pub fn mirrored_about_y(&self, tol: f64) -> Mesh<E> {
        let n = self.nodes.len();
        let on_axis: Vec<bool> = self.nodes.iter().map(|p| p[0].abs() <= tol).collect();
        let mut nodes = self.nodes.clone();
        let mut image = vec![0usize; n];
        for (i, p) in self.nodes.iter().enumerate() {
            image[i] = if on_axis[i] {
                i
            } else {
                nodes.push([-p[0], p[1]]);
                nodes.len() - 1
            };
        }
        let mut elements = self.elements.clone();
        // mirrored, and reordered to stay counterclockwise
        let order = E::mirror_order();
        elements.extend(
            self.elements
                .iter()
                .map(|e| E::PerNode::from_fn(|k| image[e[order[k]]])),
        );
        let mut boundary: Vec<BoundaryEdge<E>> = self
            .boundary
            .iter()
            .filter(|b| !b.nodes.as_ref().iter().all(|&k| on_axis[k]))
            .copied()
            .collect();
        let last = E::EDGE_NODES - 1;
        let mirrored: Vec<BoundaryEdge<E>> = boundary
            .iter()
            .map(|b| BoundaryEdge {
                nodes: E::PerEdge::from_fn(|k| image[b.nodes[last - k]]),
                edge: b.edge,
            })
            .collect();
        boundary.extend(mirrored);
        Mesh {
            nodes,
            elements,
            boundary,
            level: self.level,
        }
    }
}
