//! The region a finite-element model meshes: a part's outline as lines and arcs, its named
//! faces and its hinges, in metres as the part itself (only its files are in millimetres).

use crate::part::outline::Arc as BulgeArc;
use crate::part::Part;

/// One edge of an outline loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Edge {
    Line {
        a: [f64; 2],
        b: [f64; 2],
    },
    /// An arc from `start` sweeping `sweep` (radians, counterclockwise positive) around
    /// `centre`.
    Arc {
        centre: [f64; 2],
        radius: f64,
        start: f64,
        sweep: f64,
    },
}

impl Edge {
    /// The point a fraction `f` along the edge.
    pub fn at(&self, f: f64) -> [f64; 2] {
        match *self {
            Edge::Line { a, b } => [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])],
            Edge::Arc {
                centre,
                radius,
                start,
                sweep,
            } => {
                let phi = start + f * sweep;
                [
                    centre[0] + radius * phi.cos(),
                    centre[1] + radius * phi.sin(),
                ]
            }
        }
    }

    pub fn length(&self) -> f64 {
        match *self {
            Edge::Line { a, b } => (b[0] - a[0]).hypot(b[1] - a[1]),
            Edge::Arc { radius, sweep, .. } => radius * sweep.abs(),
        }
    }

    /// The distance from `p` to the edge, and the point of the edge nearest to it.
    pub fn nearest(&self, p: [f64; 2]) -> (f64, [f64; 2]) {
        let q = match *self {
            Edge::Line { a, b } => {
                let d = [b[0] - a[0], b[1] - a[1]];
                let len2 = d[0] * d[0] + d[1] * d[1];
                let t = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0);
                [a[0] + t * d[0], a[1] + t * d[1]]
            }
            Edge::Arc { centre, radius, .. } => {
                let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
                let r = dx.hypot(dy);
                let on = if r > 0.0 {
                    [centre[0] + radius * dx / r, centre[1] + radius * dy / r]
                } else {
                    self.at(0.0)
                };
                // the nearest point of the circle, if it lies on the arc; else an end
                let within = self.contains_angle(dy.atan2(dx));
                if within {
                    on
                } else {
                    let (a, b) = (self.at(0.0), self.at(1.0));
                    let da = (a[0] - p[0]).hypot(a[1] - p[1]);
                    let db = (b[0] - p[0]).hypot(b[1] - p[1]);
                    if da <= db {
                        a
                    } else {
                        b
                    }
                }
            }
        };
        ((q[0] - p[0]).hypot(q[1] - p[1]), q)
    }

    /// Whether the direction `phi` from the centre lies within the arc's sweep.
    fn contains_angle(&self, phi: f64) -> bool {
        let Edge::Arc { start, sweep, .. } = *self else {
            return false;
        };
        let tau = std::f64::consts::TAU;
        let rel = if sweep >= 0.0 {
            (phi - start).rem_euclid(tau)
        } else {
            (start - phi).rem_euclid(tau)
        };
        rel <= sweep.abs() + 1e-12
    }

    /// `p` moved onto the edge: onto the circle for an arc (the point on an arc's chord that
    /// stands for a point of the arc), unchanged for a line.
    pub fn project(&self, p: [f64; 2]) -> [f64; 2] {
        match *self {
            Edge::Line { .. } => p,
            Edge::Arc { centre, radius, .. } => {
                let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
                let r = dx.hypot(dy);
                [centre[0] + radius * dx / r, centre[1] + radius * dy / r]
            }
        }
    }
}

/// A named straight face of the region (a load case's surface).
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    pub name: String,
    pub a: [f64; 2],
    pub b: [f64; 2],
}

impl Face {
    /// Whether `p` lies on the face, within `tol` (m).
    pub fn contains(&self, p: [f64; 2], tol: f64) -> bool {
        Edge::Line {
            a: self.a,
            b: self.b,
        }
        .nearest(p)
        .0 <= tol
    }

    pub fn length(&self) -> f64 {
        (self.b[0] - self.a[0]).hypot(self.b[1] - self.a[1])
    }
}

/// A hinge's thin section: centre line, thickness (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Hinge {
    pub name: String,
    pub start: [f64; 2],
    pub end: [f64; 2],
    /// The least thickness.
    pub thickness: f64,
    /// The outline above the centre line in the hinge's frame, `(x, y, bulge)` (m), from
    /// its start to its end.
    pub profile: Vec<[f64; 3]>,
}

impl Hinge {
    /// The hinge's thickness at the distance `x` (m) from its start: twice the height of
    /// its outline there.
    pub fn thickness_at(&self, x: f64) -> f64 {
        let p = &self.profile;
        for k in 0..p.len().saturating_sub(1) {
            let (a, b) = (p[k], p[k + 1]);
            if x < a[0] - 1e-15 || x > b[0] + 1e-15 {
                continue;
            }
            let va = crate::part::Vertex {
                x: a[0],
                y: a[1],
                bulge: a[2],
            };
            let vb = crate::part::Vertex {
                x: b[0],
                y: b[1],
                bulge: 0.0,
            };
            return 2.0
                * match BulgeArc::from_bulge(va, vb) {
                    None => {
                        let f = if b[0] > a[0] {
                            (x - a[0]) / (b[0] - a[0])
                        } else {
                            0.0
                        };
                        a[1] + f * (b[1] - a[1])
                    }
                    Some(arc) => {
                        // the arc's point above x: the root of the circle on the arc's side
                        let dx = (x - arc.centre[0]).clamp(-arc.radius, arc.radius);
                        let dy = (arc.radius * arc.radius - dx * dx).sqrt();
                        let mid = arc.at(0.5);
                        if mid[1] < arc.centre[1] {
                            arc.centre[1] - dy
                        } else {
                            arc.centre[1] + dy
                        }
                    }
                };
        }
        self.thickness
    }

    /// The hinge's length along its centre line.
    pub fn length(&self) -> f64 {
        (self.end[0] - self.start[0]).hypot(self.end[1] - self.start[1])
    }
}

/// The straight edge from `a` to `b`, split where a face ends inside it (within 1e-12 m of
/// the edge): a face that covers part of an edge then begins and ends at nodes of every
/// mesh, and its edges are exactly those of the mesh between them.
fn split_at_faces(a: [f64; 2], b: [f64; 2], faces: &[crate::part::Face]) -> Vec<Edge> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = d[0].hypot(d[1]);
    let mut cuts: Vec<f64> = faces
        .iter()
        .flat_map(|f| [f.a, f.b])
        .filter_map(|p| {
            let along = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len;
            let off = ((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]).abs() / len;
            (off <= 1e-12 && along > 1e-12 && along < len - 1e-12).then_some(along / len)
        })
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let at = |t: f64| [a[0] + t * d[0], a[1] + t * d[1]];
    let mut points = vec![a];
    points.extend(cuts.iter().map(|&t| at(t)));
    points.push(b);
    points
        .windows(2)
        .map(|w| Edge::Line { a: w[0], b: w[1] })
        .collect()
}

/// The region to mesh, in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Domain {
    /// The loops of the outline, the outer one first.
    pub loops: Vec<Vec<Edge>>,
    pub faces: Vec<Face>,
    pub hinges: Vec<Hinge>,
}

impl Domain {
    /// The region of a part.
    pub fn of_part(part: &Part) -> Self {
        let loops = part
            .loops
            .iter()
            .map(|l| {
                let n = l.vertices.len();
                (0..n)
                    .map(|i| {
                        let (a, b) = (l.vertices[i], l.vertices[(i + 1) % n]);
                        match BulgeArc::from_bulge(a, b) {
                            Some(arc) => vec![Edge::Arc {
                                centre: arc.centre,
                                radius: arc.radius,
                                start: arc.start,
                                sweep: arc.sweep,
                            }],
                            None => split_at_faces([a.x, a.y], [b.x, b.y], &part.faces),
                        }
                    })
                    .flat_map(|edges| edges.into_iter())
                    .collect()
            })
            .collect();
        Domain {
            loops,
            faces: part
                .faces
                .iter()
                .map(|f| Face {
                    name: f.name.clone(),
                    a: f.a,
                    b: f.b,
                })
                .collect(),
            hinges: part
                .hinges
                .iter()
                .map(|h| Hinge {
                    name: h.name.clone(),
                    start: h.start,
                    end: h.end,
                    thickness: h.thickness,
                    profile: h.profile.clone(),
                })
                .collect(),
        }
    }

    /// A rectangle `[x0, x1] x [y0, y1]` with no faces, for tests and checks.
    pub fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        let c = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
        Domain {
            loops: vec![(0..4)
                .map(|i| Edge::Line {
                    a: c[i],
                    b: c[(i + 1) % 4],
                })
                .collect()],
            faces: Vec::new(),
            hinges: Vec::new(),
        }
    }

    /// The face called `name`.
    pub fn face(&self, name: &str) -> Option<&Face> {
        self.faces.iter().find(|f| f.name == name)
    }

    /// The edge of the outline nearest to `p`, with its distance.
    pub fn nearest_edge(&self, p: [f64; 2]) -> (f64, Edge) {
        self.loops
            .iter()
            .flatten()
            .map(|e| (e.nearest(p).0, *e))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .expect("a domain has edges")
    }

    /// The size of the region: the longer side of its bounding box (m).
    /// The least thickness of its thinnest hinge (m; infinite without hinges).
    pub fn thinnest_hinge(&self) -> f64 {
        self.hinges
            .iter()
            .map(|h| h.thickness)
            .fold(f64::INFINITY, f64::min)
    }

    pub fn size(&self) -> f64 {
        let mut bb = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for e in self.loops.iter().flatten() {
            for k in 0..=8 {
                let p = e.at(k as f64 / 8.0);
                bb = [
                    bb[0].min(p[0]),
                    bb[1].min(p[1]),
                    bb[2].max(p[0]),
                    bb[3].max(p[1]),
                ];
            }
        }
        (bb[2] - bb[0]).max(bb[3] - bb[1])
    }
}
