//! The hinges' roots cut into the union's outline: a notch's arcs in place of the straight
//! sides its solid left, and the fillets in place of a strip's right-angled root corners
//! (the geometry of both in [`super::outline`]'s notes).

use super::outline::{segment_distance, Loop, Vertex};
use super::HingeSite;

/// Points closer than this (m, 1e-9 mm) are one: rounding error on the part's coordinates,
/// far below the union's snapping and the design's features.
pub(super) const CLOSE: f64 = 1e-12;

/// Cuts a notch hinge's outline into the straight sides its solid left: the kind's
/// profile above the centre line and its mirror image below, between the bodies' faces.
pub(super) fn add_profile(loops: &mut [Loop], hinge: &HingeSite, problems: &mut Vec<String>) {
    let (s, e) = (hinge.start, hinge.end);
    let len = (e[0] - s[0]).hypot(e[1] - s[1]);
    let u = [(e[0] - s[0]) / len, (e[1] - s[1]) / len];
    let n = [-u[1], u[0]];
    for side in [1.0, -1.0] {
        // the mirror image below the centre line turns each arc the other way
        let path: Vec<([f64; 2], f64)> = hinge
            .profile
            .iter()
            .map(|v| {
                let (x, y) = (v[0], side * v[1]);
                (
                    [s[0] + x * u[0] + y * n[0], s[1] + x * u[1] + y * n[1]],
                    side * v[2],
                )
            })
            .collect();
        if !replace_edge(loops, &path) {
            problems.push(format!(
                "the {} side of {} is not a free edge of the outline: something covers the \
                 hinge",
                if side > 0.0 { "upper" } else { "lower" },
                hinge.name
            ));
        }
    }
}

/// Replaces the part of a straight loop edge from `path`'s first point to its last by the
/// path (points with the bulges of the arcs to their successors); false if no straight
/// edge holds both ends.
fn replace_edge(loops: &mut [Loop], path: &[([f64; 2], f64)]) -> bool {
    let (p0, p1) = (path[0].0, path[path.len() - 1].0);
    let tol = CLOSE;
    for l in loops.iter_mut() {
        let n = l.vertices.len();
        for i in 0..n {
            let (a, b) = (l.vertices[i], l.vertices[(i + 1) % n]);
            if a.bulge != 0.0 {
                continue;
            }
            let on = |p: [f64; 2]| segment_distance(p, [a.x, a.y], [b.x, b.y]) < tol;
            if !(on(p0) && on(p1)) {
                continue;
            }
            // the edge's direction decides the order: along it, p0 first or p1 first
            let along = |p: [f64; 2]| (p[0] - a.x) * (b.x - a.x) + (p[1] - a.y) * (b.y - a.y);
            let forward = along(p0) < along(p1);
            let mut inserted: Vec<Vertex> = if forward {
                path.iter()
                    .map(|&(p, bulge)| Vertex {
                        x: p[0],
                        y: p[1],
                        bulge,
                    })
                    .collect()
            } else {
                // reversed: each arc from the next point back, turning the other way
                (0..path.len())
                    .rev()
                    .map(|k| Vertex {
                        x: path[k].0[0],
                        y: path[k].0[1],
                        bulge: if k > 0 { -path[k - 1].1 } else { 0.0 },
                    })
                    .collect()
            };
            // the path's last point continues along the edge, straight, to b
            if let Some(last) = inserted.last_mut() {
                last.bulge = 0.0;
            }
            let close = |v: Vertex, w: Vertex| (v.x - w.x).hypot(v.y - w.y) < tol;
            if close(inserted[0], a) {
                l.vertices[i].bulge = inserted[0].bulge;
                inserted.remove(0);
            }
            if inserted.last().is_some_and(|&v| close(v, b)) {
                inserted.pop();
            }
            let at = i + 1;
            l.vertices.splice(at..at, inserted);
            return true;
        }
    }
    false
}

/// Rounds the four roots of `hinge` in `loops`.
pub(super) fn add_fillets(loops: &mut [Loop], hinge: &HingeSite, problems: &mut Vec<String>) {
    let (s, e) = (hinge.start, hinge.end);
    let (r, half) = (hinge.fillet, 0.5 * hinge.thickness);
    let len = (e[0] - s[0]).hypot(e[1] - s[1]);
    let u = [(e[0] - s[0]) / len, (e[1] - s[1]) / len];
    let n = [-u[1], u[0]];
    let at = |p: [f64; 2], a: f64, b: f64| [p[0] + a * u[0] + b * n[0], p[1] + a * u[1] + b * n[1]];
    for (end, base, back) in [("start", s, -r), ("end", e, r)] {
        for side in [1.0, -1.0] {
            let corner = at(base, back, side * half);
            let on_hinge = at(base, 0.0, side * half);
            let on_face = at(base, back, side * (half + r));
            if !replace_corner(loops, corner, on_hinge, on_face) {
                problems.push(format!(
                    "the root of {} at its {end} is not a free corner of the outline: \
                     something covers it or its face is shorter than the fillet radius",
                    hinge.name
                ));
            }
        }
    }
}

/// Replaces the vertex at `corner` by a quarter circle tangent at `p` and `q`; false if
/// the corner is not there with room for the arc on both of its edges.
fn replace_corner(loops: &mut [Loop], corner: [f64; 2], p: [f64; 2], q: [f64; 2]) -> bool {
    let close = |v: Vertex, w: [f64; 2]| (v.x - w[0]).hypot(v.y - w[1]) < CLOSE;
    for l in loops.iter_mut() {
        let n = l.vertices.len();
        let Some(i) = (0..n).find(|&i| close(l.vertices[i], corner)) else {
            continue;
        };
        let (prev, next) = (l.vertices[(i + n - 1) % n], l.vertices[(i + 1) % n]);
        // the tangent points must lie on the corner's two edges
        let on = |a: Vertex, t: [f64; 2]| {
            segment_distance(t, [a.x, a.y], corner) < CLOSE
                && prev.bulge == 0.0
                && l.vertices[i].bulge == 0.0
        };
        let (first, second) = if on(prev, p) && on(next, q) {
            (p, q)
        } else if on(prev, q) && on(next, p) {
            (q, p)
        } else {
            return false;
        };
        // a quarter turn, its sense from the corner's
        let cross = (corner[0] - first[0]) * (second[1] - corner[1])
            - (corner[1] - first[1]) * (second[0] - corner[0]);
        let bulge = std::f64::consts::FRAC_PI_8.tan() * cross.signum();
        l.vertices[i] = Vertex {
            x: first[0],
            y: first[1],
            bulge,
        };
        l.vertices.insert(
            i + 1,
            Vertex {
                x: second[0],
                y: second[1],
                bulge: 0.0,
            },
        );
        return true;
    }
    false
}
