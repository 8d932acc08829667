//! The six-node triangle's mesher, triangle-specific as every mesher is: the first mesh from
//! a constrained Delaunay triangulation of the outline with Ruppert refinement (the `spade`
//! crate), each next one by splitting every triangle into four, so that a sequence of
//! meshes refines uniformly (element size halved) for the error estimate's extrapolation.
//!
//! Element sizes follow a size function: the outline is split into segments of the local
//! size, and the refinement (minimum angle 25 degrees, largest area that of the coarsest
//! element) grades the interior from them.

use std::collections::{HashMap, HashSet};

use spade::handles::{FixedFaceHandle, InnerTag};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};

use super::{BoundaryEdge, Mesh, Mesher};
use crate::fe::element::{Element, Tri6};
use crate::fe::geometry::{Domain, Edge};
use crate::fe::FeError;

impl Mesher for Tri6 {
    fn first_mesh(
        domain: &Domain,
        size: &dyn Fn([f64; 2]) -> f64,
        max_size: f64,
        max_nodes: usize,
    ) -> Result<Mesh<Tri6>, FeError> {
        first_mesh(domain, size, max_size, max_nodes)
    }

    fn refine(mesh: &Mesh<Tri6>, domain: &Domain) -> Mesh<Tri6> {
        refine(mesh, domain)
    }
}

/// The grid the outline's points are put on for the triangulation to decide on: 2^-40 m
/// (about 0.9 pm, a million times finer than a wire-EDM cut holds). A Delaunay triangulation
/// decides between cocircular points, which a symmetric outline has in numbers, by the last
/// bits of their coordinates, and the refinement carries each decision on: without the grid
/// an outline moved by a few units in the last place (a change of units does that) meshed
/// into another number of triangles. On the grid, a power of two, the same integers give the
/// same points exactly. The mesh's nodes keep the outline's exact points: the grid decides
/// the triangles, not where the part is (a small hinge's faces are found within 1e-9 of its
/// size, finer than the grid).
const GRID: f64 = 1.0 / (1u64 << 40) as f64;

fn on_grid(p: [f64; 2]) -> [f64; 2] {
    p.map(|v| (v / GRID).round() * GRID)
}

/// The least whole number of pieces for `x`, a count whole in exact arithmetic often enough
/// (a 90-degree arc in 15-degree pieces, a side in pieces of a size it is a multiple of) to
/// be read as whole within a billionth: a few units in the last place must not add a point.
fn ceil_loose(x: f64) -> usize {
    (x * (1.0 - 1e-9)).ceil() as usize
}

/// The outline split into segments no longer than `size` where they lie, and arcs into
/// pieces of at most 15 degrees: each loop's points in order.
fn boundary_points(domain: &Domain, size: &dyn Fn([f64; 2]) -> f64) -> Vec<Vec<([f64; 2], usize)>> {
    let max_turn = 15f64.to_radians();
    let mut flat = 0;
    domain
        .loops
        .iter()
        .map(|l| {
            let mut points = Vec::new();
            for e in l {
                // the number of segments: the integral of 1/h along the edge, by 64 samples
                const SAMPLES: usize = 64;
                let len = e.length();
                let turn = match *e {
                    Edge::Arc { sweep, .. } => sweep.abs(),
                    Edge::Line { .. } => 0.0,
                };
                let density: Vec<f64> = (0..=SAMPLES)
                    .map(|k| {
                        let h = size(e.at(k as f64 / SAMPLES as f64));
                        len / h
                    })
                    .collect();
                let mut cumulative = vec![0.0; SAMPLES + 1];
                for k in 1..=SAMPLES {
                    cumulative[k] =
                        cumulative[k - 1] + 0.5 * (density[k - 1] + density[k]) / SAMPLES as f64;
                }
                let total = cumulative[SAMPLES];
                let n = ceil_loose(total).max(ceil_loose(turn / max_turn)).max(1);
                points.push((e.at(0.0), flat));
                for s in 1..n {
                    // the fraction of the edge where the integral reaches s/n of its total
                    let target = total * s as f64 / n as f64;
                    let k = cumulative
                        .partition_point(|&c| c < target)
                        .clamp(1, SAMPLES);
                    let (c0, c1) = (cumulative[k - 1], cumulative[k]);
                    let frac = if c1 > c0 {
                        (target - c0) / (c1 - c0)
                    } else {
                        0.0
                    };
                    let f = ((k - 1) as f64 + frac) / SAMPLES as f64;
                    // with the integral flat (uniform size), fractions are exactly s/n
                    let f = if total > 0.0 { f } else { s as f64 / n as f64 };
                    points.push((e.at(f), flat));
                }
                flat += 1;
            }
            points
        })
        .collect()
}

/// The first mesh of `domain`, elements sized by `size` (m, a function of the place), never
/// larger than `max_size`, with at most `max_nodes` nodes.
fn first_mesh(
    domain: &Domain,
    size: &dyn Fn([f64; 2]) -> f64,
    max_size: f64,
    max_nodes: usize,
) -> Result<Mesh<Tri6>, FeError> {
    let over = |nodes: usize| {
        FeError::Budget(format!(
            "the first mesh needs more than {nodes} nodes ({} degrees of freedom), more than the \
             {max_nodes} allowed",
            2 * nodes
        ))
    };
    let loops = boundary_points(domain, size);
    // a six-node mesh has about four nodes per corner (corners and midsides), so the corners
    // the refinement may add are bounded first, before spade holds them
    let max_corners = max_nodes / 4;
    let input: usize = loops.iter().map(Vec::len).sum();
    if input > max_corners {
        return Err(over(4 * input));
    }
    let mut vertices = Vec::new();
    let mut constraints = Vec::new();
    // each point on the grid, back to the exact point it came from
    let mut exact: HashMap<[u64; 2], [f64; 2]> = HashMap::new();
    for l in &loops {
        let first = vertices.len();
        for (i, (p, _)) in l.iter().enumerate() {
            let q = on_grid(*p);
            exact.insert(q.map(f64::to_bits), *p);
            vertices.push(Point2::new(q[0], q[1]));
            let next = if i + 1 == l.len() {
                first
            } else {
                first + i + 1
            };
            constraints.push([first + i, next]);
        }
    }
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::bulk_load_cdt(vertices, constraints)
            .map_err(|e| FeError::Mesh(format!("the outline cannot be triangulated: {e:?}")))?;
    if cdt.num_vertices() != input {
        return Err(FeError::Mesh(
            "the outline touches itself: two of its points coincide".into(),
        ));
    }
    let smallest = loops
        .iter()
        .flatten()
        .map(|(p, _)| size(*p))
        .fold(max_size, f64::min);
    let area = |h: f64| 0.25 * 3f64.sqrt() * h * h;
    let result = cdt.refine(
        RefinementParameters::new()
            .exclude_outer_faces(true)
            .with_angle_limit(AngleLimit::from_deg(25.0))
            .with_max_allowed_area(area(max_size))
            .with_min_required_area(0.05 * area(smallest))
            .with_max_additional_vertices(max_corners - input),
    );
    if !result.refinement_complete {
        return Err(over(4 * max_corners));
    }
    let excluded: HashSet<FixedFaceHandle<InnerTag>> = result.excluded_faces.into_iter().collect();

    // the inner triangles, their corners renumbered densely
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut corners: Vec<[usize; 3]> = Vec::new();
    for face in cdt.inner_faces() {
        if excluded.contains(&face.fix()) {
            continue;
        }
        let v = face.vertices();
        let mut tri = [0; 3];
        for (k, vh) in v.iter().enumerate() {
            let id = vh.fix().index();
            let n = *index.entry(id).or_insert_with(|| {
                let p = vh.position();
                let p = [p.x, p.y];
                nodes.push(exact.get(&p.map(f64::to_bits)).copied().unwrap_or(p));
                nodes.len() - 1
            });
            tri[k] = n;
        }
        corners.push(tri);
    }
    if corners.is_empty() {
        return Err(FeError::Mesh("the outline encloses no area".into()));
    }
    // edges with one triangle lie on the outline
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &corners {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    // the refinement splits arcs' chords: put their points back on the arcs
    let on_outline: HashSet<usize> = count
        .iter()
        .filter(|(_, &c)| c == 1)
        .flat_map(|(&(a, b), _)| [a, b])
        .collect();
    for &n in &on_outline {
        let (_, e) = domain.nearest_edge(nodes[n]);
        nodes[n] = e.project(nodes[n]);
    }
    let flat: Vec<Edge> = domain.loops.iter().flatten().copied().collect();
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    let mut boundary = Vec::new();
    let mut elements = Vec::with_capacity(corners.len());
    for t in &corners {
        let mut el = [t[0], t[1], t[2], 0, 0, 0];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let m = *mids.entry(key).or_insert_with(|| {
                let mut p = [
                    0.5 * (nodes[a][0] + nodes[b][0]),
                    0.5 * (nodes[a][1] + nodes[b][1]),
                ];
                if count[&key] == 1 {
                    let (edge, _) = nearest_flat(&flat, p);
                    p = flat[edge].project(p);
                    boundary.push(BoundaryEdge {
                        nodes: [a, nodes.len(), b],
                        edge,
                    });
                }
                nodes.push(p);
                nodes.len() - 1
            });
            el[3 + k] = m;
        }
        elements.push(el);
    }
    if nodes.len() > max_nodes {
        return Err(over(nodes.len()));
    }
    let mesh = Mesh {
        nodes,
        elements,
        boundary,
        level: 0,
    };
    check_elements(&mesh)?;
    Ok(mesh)
}

/// The index of the outline edge nearest to `p`, and its distance.
fn nearest_flat(flat: &[Edge], p: [f64; 2]) -> (usize, f64) {
    flat.iter()
        .enumerate()
        .map(|(i, e)| (i, e.nearest(p).0))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, f64::INFINITY))
}

/// Every element's map must be one to one at its integration points.
fn check_elements(mesh: &Mesh<Tri6>) -> Result<(), FeError> {
    for e in 0..mesh.elements.len() {
        let x = mesh.element_nodes(e);
        for l in Tri6::node_coordinates() {
            if Tri6::gradients(&x, l).is_none() {
                return Err(FeError::Mesh(format!(
                    "element {e} near ({:.4}, {:.4}) mm is inverted",
                    x[0][0] * 1e3,
                    x[0][1] * 1e3
                )));
            }
        }
    }
    Ok(())
}

/// The area coordinates, in the parent, of the nodes of its four children: the parent's
/// corners and midsides, then the midpoints of the children's edges.
const CHILD_POINTS: [[f64; 3]; 9] = [
    // on the parent's edges: halves of 0-1, 1-2, 2-0
    [0.75, 0.25, 0.0],
    [0.25, 0.75, 0.0],
    [0.0, 0.75, 0.25],
    [0.0, 0.25, 0.75],
    [0.25, 0.0, 0.75],
    [0.75, 0.0, 0.25],
    // inside: the midsides of the inner child
    [0.25, 0.5, 0.25],
    [0.25, 0.25, 0.5],
    [0.5, 0.25, 0.25],
];

/// The mesh with every triangle split into four (element size halved); new nodes on the
/// outline put on it exactly.
fn refine(mesh: &Mesh<Tri6>, domain: &Domain) -> Mesh<Tri6> {
    let flat: Vec<Edge> = domain.loops.iter().flatten().copied().collect();
    let mut nodes = mesh.nodes.clone();
    // the boundary edge (corner, corner) -> its outline edge
    let outline: HashMap<(usize, usize), usize> = mesh
        .boundary
        .iter()
        .flat_map(|b| {
            let [a, m, c] = b.nodes;
            [
                ((a.min(m), a.max(m)), b.edge),
                ((m.min(c), m.max(c)), b.edge),
            ]
        })
        .collect();
    let mut shared: HashMap<(usize, usize), usize> = HashMap::new();
    let mut elements = Vec::with_capacity(4 * mesh.elements.len());
    for (e, el) in mesh.elements.iter().enumerate() {
        let x = mesh.element_nodes(e);
        let [c0, c1, c2, m01, m12, m20] = *el;
        // the parent's half edges, each with its new midpoint
        let halves = [
            (c0, m01),
            (m01, c1),
            (c1, m12),
            (m12, c2),
            (c2, m20),
            (m20, c0),
        ];
        let mut q = [0usize; 9];
        for (k, &(a, b)) in halves.iter().enumerate() {
            let key = (a.min(b), a.max(b));
            q[k] = *shared.entry(key).or_insert_with(|| {
                let mut p = Tri6::point(&x, CHILD_POINTS[k]);
                if let Some(&edge) = outline.get(&key) {
                    p = flat[edge].project(p);
                }
                nodes.push(p);
                nodes.len() - 1
            });
        }
        for k in 6..9 {
            nodes.push(Tri6::point(&x, CHILD_POINTS[k]));
            q[k] = nodes.len() - 1;
        }
        // children: (corner, corner, corner, mid 01, mid 12, mid 20)
        elements.push([c0, m01, m20, q[0], q[8], q[5]]);
        elements.push([m01, c1, m12, q[1], q[2], q[6]]);
        elements.push([m20, m12, c2, q[7], q[3], q[4]]);
        elements.push([m01, m12, m20, q[6], q[7], q[8]]);
    }
    let boundary = mesh
        .boundary
        .iter()
        .flat_map(|b| {
            let [a, m, c] = b.nodes;
            [
                BoundaryEdge {
                    nodes: [a, shared[&(a.min(m), a.max(m))], m],
                    edge: b.edge,
                },
                BoundaryEdge {
                    nodes: [m, shared[&(m.min(c), m.max(c))], c],
                    edge: b.edge,
                },
            ]
        })
        .collect();
    Mesh {
        nodes,
        elements,
        boundary,
        level: mesh.level + 1,
    }
}
