//! The outline of a part: the Boolean union of its solids, exact coordinates, fillets.
//!
//! The union is georust `geo`'s `unary_union` (the `i_overlay` engine). That engine works
//! on an integer grid (about 1e-8 of the part's size), so every vertex it returns is moved
//! back onto the exact vertex of a solid it stands for, or onto the exact crossing of the
//! two solid edges it lies on: the outline keeps the design's dimensions to rounding error,
//! which the tests measure (hinge thickness and length to 1e-9 mm).
//!
//! Units: the outline is in metres, as the solids. Only the union is fed millimetres
//! ([`polygon_mm`]), as it always was: its integer grid is the one step here whose result
//! depends on the scale, and kept at the scale it has been tested at it cannot change which
//! pieces join. Its vertices never reach the outline: each, brought back to metres, only
//! picks the exact point (in metres) of the solids it stands for.
//!
//! Fillets: a hinge's solid runs `r` beyond each end of its thin section, to the faces of
//! the rigid bodies, so each of its four roots is a right-angled inner corner `r` from the
//! end of the thin section. The corner is replaced by a quarter circle of radius `r`, tangent
//! to the hinge's edge exactly where the thin section ends and to the face `r` out from the
//! hinge's edge. The thin section keeps the model's length `l`; the fillets add material
//! only beyond it, where the model has rigid links.
//!
//! Loops carry arcs as DXF does: each vertex has a `bulge`, the tangent of a quarter of the
//! arc's signed angle to the next vertex (0 for a straight edge).

use geo::{Coord, LineString, Polygon};
use serde::Serialize;

use super::roots::{add_fillets, add_profile};
use super::{PartSpec, MM};

/// A vertex of a loop (m) and the bulge of the edge to the next one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Vertex {
    pub x: f64,
    pub y: f64,
    pub bulge: f64,
}

/// A closed loop of the outline.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Loop {
    /// The outer boundary (counterclockwise), or an inner one (clockwise): a pocket.
    pub outer: bool,
    pub vertices: Vec<Vertex>,
}

/// Vertices closer than this (m, 1e-5 mm) are one; the union's grid is far finer than
/// this, the design's features far coarser.
const SNAP: f64 = 1e-8;

impl Loop {
    /// The signed area (m^2): the polygon's by the shoelace formula, plus each arc's
    /// circular segment.
    pub fn signed_area(&self) -> f64 {
        let n = self.vertices.len();
        (0..n)
            .map(|i| {
                let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
                let mut s = 0.5 * (a.x * b.y - b.x * a.y);
                if a.bulge != 0.0 {
                    // segment of an arc with included angle theta = 4 atan(bulge)
                    let theta = 4.0 * a.bulge.atan();
                    let chord = (b.x - a.x).hypot(b.y - a.y);
                    let radius = chord / (2.0 * (theta / 2.0).sin().abs());
                    s += 0.5 * radius * radius * (theta - theta.sin());
                }
                s
            })
            .sum()
    }

    /// The points of the loop with each arc split into `per_arc` chords, in the loop's
    /// unit.
    pub fn points(&self, per_arc: usize) -> Vec<[f64; 2]> {
        let n = self.vertices.len();
        let mut out = Vec::new();
        for i in 0..n {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            out.push([a.x, a.y]);
            if let Some(arc) = Arc::from_bulge(a, b) {
                for k in 1..per_arc {
                    out.push(arc.at(k as f64 / per_arc as f64));
                }
            }
        }
        out
    }

    /// `[x_min, y_min, x_max, y_max]`, arcs included (their extreme points where an arc
    /// crosses an axis direction).
    pub fn bounding_box(&self) -> [f64; 4] {
        let n = self.vertices.len();
        let mut bb = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut add = |p: [f64; 2]| {
            bb = [
                bb[0].min(p[0]),
                bb[1].min(p[1]),
                bb[2].max(p[0]),
                bb[3].max(p[1]),
            ];
        };
        for i in 0..n {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            add([a.x, a.y]);
            if let Some(arc) = Arc::from_bulge(a, b) {
                for p in arc.extremes() {
                    add(p);
                }
            }
        }
        bb
    }
}

/// An arc from a bulge: centre, radius, start angle and signed sweep.
#[derive(Debug, Clone, Copy)]
pub struct Arc {
    pub centre: [f64; 2],
    pub radius: f64,
    pub start: f64,
    pub sweep: f64,
}

impl Arc {
    /// The arc from `a` to `b` with `a`'s bulge; `None` for a straight edge.
    pub fn from_bulge(a: Vertex, b: Vertex) -> Option<Arc> {
        if a.bulge == 0.0 {
            return None;
        }
        let sweep = 4.0 * a.bulge.atan();
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let chord = dx.hypot(dy);
        let radius = chord / (2.0 * (sweep / 2.0).sin().abs());
        // the centre lies on the chord's bisector, at distance d, to the left for a
        // counterclockwise (positive) sweep of less than a half turn
        let d = radius * (sweep / 2.0).cos().abs();
        let side = if sweep > 0.0 { 1.0 } else { -1.0 };
        let (mx, my) = (0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
        let centre = [mx - side * d * dy / chord, my + side * d * dx / chord];
        let start = (a.y - centre[1]).atan2(a.x - centre[0]);
        Some(Arc {
            centre,
            radius,
            start,
            sweep,
        })
    }

    /// The point a fraction `f` along the arc.
    pub fn at(&self, f: f64) -> [f64; 2] {
        let phi = self.start + f * self.sweep;
        [
            self.centre[0] + self.radius * phi.cos(),
            self.centre[1] + self.radius * phi.sin(),
        ]
    }

    /// The arc's points where its tangent is horizontal or vertical.
    fn extremes(&self) -> Vec<[f64; 2]> {
        let (lo, hi) = if self.sweep > 0.0 {
            (self.start, self.start + self.sweep)
        } else {
            (self.start + self.sweep, self.start)
        };
        let quarter = std::f64::consts::FRAC_PI_2;
        let mut k = (lo / quarter).ceil();
        let mut out = Vec::new();
        while k * quarter <= hi {
            let phi = k * quarter;
            out.push([
                self.centre[0] + self.radius * phi.cos(),
                self.centre[1] + self.radius * phi.sin(),
            ]);
            k += 1.0;
        }
        out
    }
}

/// A polygon of points in metres, in millimetres for `geo`: the union's grid and the
/// slot checks' distances work at the scale they were measured at (see the notes above).
pub(crate) fn polygon_mm(points: &[[f64; 2]]) -> Polygon<f64> {
    let ring: Vec<Coord<f64>> = points
        .iter()
        .map(|p| Coord {
            x: p[0] * MM,
            y: p[1] * MM,
        })
        .collect();
    Polygon::new(LineString::new(ring), vec![])
}

/// The solids' union as loops with fillets; the problems found otherwise.
pub fn outline(spec: &PartSpec) -> Result<Vec<Loop>, Vec<String>> {
    let polygons: Vec<Polygon<f64>> = spec.solids.iter().map(|s| polygon_mm(&s.points)).collect();
    let union = geo::unary_union(&polygons);
    if union.0.len() != 1 {
        return Err(vec![format!(
            "the solids do not join into one part but {} separate pieces",
            union.0.len()
        )]);
    }
    let exact = Exact::new(spec);
    let polygon = &union.0[0];
    let mut loops = Vec::new();
    for (k, ring) in std::iter::once(polygon.exterior())
        .chain(polygon.interiors())
        .enumerate()
    {
        let mut points: Vec<[f64; 2]> = ring
            .0
            .iter()
            .map(|c| exact.snap([c.x / MM, c.y / MM]))
            .collect();
        points.pop(); // closed ring: the first point again
        let points = simplify(points);
        let outer = k == 0;
        let area: f64 = shoelace(&points);
        let mut points = points;
        if (area > 0.0) != outer {
            points.reverse();
        }
        loops.push(Loop {
            outer,
            vertices: points
                .into_iter()
                .map(|p| Vertex {
                    x: p[0],
                    y: p[1],
                    bulge: 0.0,
                })
                .collect(),
        });
    }
    let mut problems = Vec::new();
    for hinge in &spec.hinges {
        if hinge.profile.len() > 2 || hinge.profile.iter().any(|v| v[2] != 0.0) {
            add_profile(&mut loops, hinge, &mut problems);
        }
        if hinge.fillet > 0.0 {
            add_fillets(&mut loops, hinge, &mut problems);
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    for l in &mut loops {
        drop_zero_edges(l);
        start_at_lowest(l);
    }
    // the pockets in a fixed order: by their first vertex
    loops[1..].sort_by(|a, b| {
        let (p, q) = (a.vertices[0], b.vertices[0]);
        p.y.total_cmp(&q.y).then(p.x.total_cmp(&q.x))
    });
    Ok(loops)
}

fn shoelace(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            0.5 * (a[0] * b[1] - b[0] * a[1])
        })
        .sum()
}

/// Drops repeated points and points on a straight line between their neighbours.
fn simplify(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    loop {
        let n = points.len();
        if n < 4 {
            return points;
        }
        let drop = (0..n).find(|&i| {
            let (p, a, q) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let (ux, uy) = (a[0] - p[0], a[1] - p[1]);
            let (vx, vy) = (q[0] - a[0], q[1] - a[1]);
            let (lu, lv) = (ux.hypot(uy), vx.hypot(vy));
            lu < SNAP || (ux * vy - uy * vx).abs() <= 1e-12 * lu * lv && ux * vx + uy * vy > 0.0
        });
        match drop {
            Some(i) => {
                points.remove(i);
            }
            None => return points,
        }
    }
}

/// Removes the straight edges of zero length a fillet leaves where its arc ends exactly at a
/// corner of the body (a face as wide as the fillet reaches).
fn drop_zero_edges(l: &mut Loop) {
    let mut i = 0;
    while i < l.vertices.len() && l.vertices.len() > 3 {
        let n = l.vertices.len();
        let (a, b) = (l.vertices[i], l.vertices[(i + 1) % n]);
        if a.bulge == 0.0 && (a.x - b.x).hypot(a.y - b.y) < super::roots::CLOSE {
            l.vertices.remove(i);
        } else {
            i += 1;
        }
    }
}

fn start_at_lowest(l: &mut Loop) {
    let first = (0..l.vertices.len())
        .min_by(|&i, &j| {
            let (p, q) = (l.vertices[i], l.vertices[j]);
            p.y.total_cmp(&q.y).then(p.x.total_cmp(&q.x))
        })
        .unwrap_or(0);
    l.vertices.rotate_left(first);
}

/// The solids' exact vertices and edges (m), to put the union's vertices back on.
struct Exact {
    vertices: Vec<[f64; 2]>,
    /// Each edge with the index of its solid.
    edges: Vec<([f64; 2], [f64; 2], usize)>,
}

impl Exact {
    fn new(spec: &PartSpec) -> Self {
        let mut vertices = Vec::new();
        let mut edges = Vec::new();
        for (k, s) in spec.solids.iter().enumerate() {
            let n = s.points.len();
            for i in 0..n {
                let (a, b) = (s.points[i], s.points[(i + 1) % n]);
                vertices.push(a);
                edges.push((a, b, k));
            }
        }
        Exact { vertices, edges }
    }

    /// The exact point the union's vertex `p` (converted to metres) stands for: a solid's vertex, else the crossing
    /// of two solids' edges through it; `p` itself if neither is near.
    fn snap(&self, p: [f64; 2]) -> [f64; 2] {
        let d = |a: [f64; 2]| (a[0] - p[0]).hypot(a[1] - p[1]);
        if let Some(v) = self
            .vertices
            .iter()
            .copied()
            .filter(|&v| d(v) < SNAP)
            .min_by(|a, b| d(*a).total_cmp(&d(*b)))
        {
            return v;
        }
        let near: Vec<_> = self
            .edges
            .iter()
            .filter(|(a, b, _)| segment_distance(p, *a, *b) < SNAP)
            .collect();
        let mut best: Option<[f64; 2]> = None;
        for (i, e) in near.iter().enumerate() {
            for f in &near[i + 1..] {
                if e.2 == f.2 {
                    continue;
                }
                if let Some(x) = crossing(e.0, e.1, f.0, f.1) {
                    if d(x) < SNAP && best.is_none_or(|b| d(x) < d(b)) {
                        best = Some(x);
                    }
                }
            }
        }
        best.unwrap_or(p)
    }
}

pub(super) fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (vx, vy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = vx * vx + vy * vy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * vx + (p[1] - a[1]) * vy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a[0] + t * vx - p[0]).hypot(a[1] + t * vy - p[1])
}

/// The crossing of the lines through `a`-`b` and `c`-`d`; `None` if they are parallel.
fn crossing(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Option<[f64; 2]> {
    let (rx, ry) = (b[0] - a[0], b[1] - a[1]);
    let (sx, sy) = (d[0] - c[0], d[1] - c[1]);
    let den = rx * sy - ry * sx;
    if den.abs() <= 1e-14 * (rx.hypot(ry) * sx.hypot(sy)) {
        return None;
    }
    let t = ((c[0] - a[0]) * sy - (c[1] - a[1]) * sx) / den;
    Some([a[0] + t * rx, a[1] + t * ry])
}
