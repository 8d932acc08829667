//! What a wire-EDM shop cannot make, found before the part is exported.
//!
//! - Beside every hinge's thin section, a keep-out band as wide as the fillet or the
//!   narrowest slot the wire cuts (whichever is wider): any other solid reaching into it
//!   cuts into the hinge or leaves a slot too narrow to cut. This holds for the bodies the
//!   hinge joins too, which must stay behind their faces.
//! - Every two solids that are not joined keep at least the narrowest slot apart: closer,
//!   they touch once cut (or overlap already: an arm through another, a block through a
//!   link).
//! - The actuator's rectangle, where the model gives it, stays clear of every solid but the
//!   two it pushes.
//!
//! Each problem names both parties and the distance found.

use geo::{Distance, Euclidean, Intersects, Polygon};

use super::outline::polygon_mm as polygon;

use super::{HingeSite, PartSpec, MM};

/// Which end of a hinge a body joined to it meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Joint {
    Start,
    End,
}

/// The band beside `h` (metres, counterclockwise): its root half thickness and `slot` to
/// each side of its centre line, kept `1e-9` m short of the faces at both ends, where the
/// bodies begin. Against a body the hinge joins, which meets it at one end through its
/// face, the band is `shortened` at that end by its half width: a body may fold back beside
/// its own face as far as its corner, no farther.
pub fn keep_out(h: &HingeSite, slot: f64, shortened: Option<Joint>) -> Vec<[f64; 2]> {
    let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
    let u = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
    let n = [-u[1], u[0]];
    let w = 0.5 * h.root + slot;
    let inset = 1e-9;
    let (mut a, mut b) = (-h.fillet + inset, len + (h.fillet - inset));
    match shortened {
        Some(Joint::Start) => a = (a + w).min(b),
        Some(Joint::End) => b = (b - w).max(a),
        None => {}
    }
    let at = |s: f64, t: f64| {
        [
            h.start[0] + s * u[0] + t * n[0],
            h.start[1] + s * u[1] + t * n[1],
        ]
    };
    vec![at(a, -w), at(b, -w), at(b, w), at(a, w)]
}

/// Whether `solid` (mm) reaches into the band with `corners` (m, counterclockwise) by more
/// than [`TOLERANCE`]: a band shortened to nothing is the segment across its end.
fn reaches_into(corners: &[[f64; 2]], solid: &Polygon<f64>) -> bool {
    let [a, b, d] = [corners[0], corners[1], corners[3]];
    if (b[0] - a[0]).hypot(b[1] - a[1]) > 0.0 {
        return polygon(&inset(corners, TOLERANCE)).intersects(solid);
    }
    // the segment from a to d, its ends moved in by the tolerance
    let len = (d[0] - a[0]).hypot(d[1] - a[1]);
    let t = TOLERANCE / len;
    let at = |s: f64| geo::Coord {
        x: (a[0] + s * (d[0] - a[0])) * MM,
        y: (a[1] + s * (d[1] - a[1])) * MM,
    };
    geo::Line::new(at(t), at(1.0 - t)).intersects(solid)
}

/// The end of `h` at which `body` (mm) meets it: the one whose face is nearer.
fn joint(h: &HingeSite, body: &Polygon<f64>) -> Joint {
    let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
    let u = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
    let face =
        |p: [f64; 2], s: f64| geo::Point::new((p[0] + s * u[0]) * MM, (p[1] + s * u[1]) * MM);
    let to = |p| Euclidean.distance(body, &p);
    if to(face(h.start, -h.fillet)) <= to(face(h.end, h.fillet)) {
        Joint::Start
    } else {
        Joint::End
    }
}

/// How far (m) a solid may reach into a band or the actuator, or a slot fall short, before
/// a check reports it: the study's feasibility tolerance for the part's rules
/// ([`crate::model::part_rules::TOLERANCE`], 1e-9 mm), so that a design the study ends on,
/// on a rule's limit, passes the check of the same thing.
pub const TOLERANCE: f64 = 1e-12;

/// `points` (a counterclockwise convex polygon, m) moved in by `d` along each side's normal.
fn inset(points: &[[f64; 2]], d: f64) -> Vec<[f64; 2]> {
    let n = points.len();
    // each side's line moved in, then the corners where consecutive lines meet
    let line = |i: usize| {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        let normal = [-dy / len, dx / len];
        let c = normal[0] * a[0] + normal[1] * a[1] + d;
        (normal, c)
    };
    (0..n)
        .map(|i| {
            let ((n1, c1), (n2, c2)) = (line((i + n - 1) % n), line(i));
            let det = n1[0] * n2[1] - n1[1] * n2[0];
            [
                (c1 * n2[1] - c2 * n1[1]) / det,
                (n1[0] * c2 - n2[0] * c1) / det,
            ]
        })
        .collect()
}

/// A distance for a message: mm, four decimals.
fn short_mm(v: f64) -> String {
    format!("{v:.4} mm")
}

/// A polygon's bounding box, `[min x, min y, max x, max y]`; an empty one's spans nothing.
fn bounds(p: &Polygon<f64>) -> [f64; 4] {
    p.exterior().coords().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |[x0, y0, x1, y1], c| [x0.min(c.x), y0.min(c.y), x1.max(c.x), y1.max(c.y)],
    )
}

/// Whether the boxes `a` and `b` lie more than `gap` apart along an axis: then so do the
/// polygons within them.
fn apart(a: [f64; 4], b: [f64; 4], gap: f64) -> bool {
    a[0] > b[2] + gap || b[0] > a[2] + gap || a[1] > b[3] + gap || b[1] > a[3] + gap
}

/// The problems found on the solids themselves, before their union.
pub fn before_union(spec: &PartSpec) -> Vec<String> {
    let mut problems = Vec::new();
    let solids: Vec<Polygon<f64>> = spec.solids.iter().map(|s| polygon(&s.points)).collect();
    let name = |k: usize| spec.solids[k].name.as_str();
    // pairs already named, so that one collision gives one message
    let mut named = std::collections::BTreeSet::new();
    // a set, and the solids' boxes: a pair's look-up through the joints' list, and a
    // polygon distance for every pair however far apart, made a chain of n bodies' check
    // grow as n^3 (80 s at 200 bodies)
    let joints: std::collections::HashSet<(usize, usize)> = spec
        .joints
        .iter()
        .map(|&(a, b)| (a.min(b), a.max(b)))
        .collect();
    let joined = |i: usize, j: usize| joints.contains(&(i.min(j), i.max(j)));
    let boxes: Vec<_> = solids.iter().map(bounds).collect();
    for h in &spec.hinges {
        let slot = h.fillet.max(spec.min_slot);
        // the band before a joint shortens it, which holds every band of the hinge (mm)
        let band = bounds(&polygon(&keep_out(h, slot, None)));
        for (k, s) in solids.iter().enumerate() {
            if k == h.solid || apart(band, boxes[k], 0.0) {
                continue;
            }
            let joint = joined(k, h.solid).then(|| joint(h, s));
            if reaches_into(&keep_out(h, slot, joint), s) {
                named.insert((k.min(h.solid), k.max(h.solid)));
                let gap = Euclidean.distance(&solids[h.solid], s);
                problems.push(format!(
                    "{} reaches within {} of {} (its thin section needs {} free on each \
                     side: the fillet or the narrowest slot)",
                    name(k),
                    short_mm(gap),
                    h.name,
                    short_mm(slot * MM)
                ));
            }
        }
    }
    let slot = spec.min_slot * MM;
    for i in 0..solids.len() {
        for j in i + 1..solids.len() {
            if joined(i, j) || named.contains(&(i, j)) || apart(boxes[i], boxes[j], slot) {
                continue;
            }
            let gap = Euclidean.distance(&solids[i], &solids[j]);
            if gap < slot - TOLERANCE * MM {
                problems.push(if gap == 0.0 {
                    format!("{} and {} overlap", name(i), name(j))
                } else {
                    format!(
                        "{} and {} are {} apart, less than the narrowest slot the wire cuts \
                         ({})",
                        name(i),
                        name(j),
                        short_mm(gap),
                        short_mm(slot)
                    )
                });
            }
        }
    }
    if let Some((a, height)) = spec.actuator.as_ref().and_then(|a| Some((a, a.height?))) {
        // the actuator's body, a hair inside its length so that it only touches the faces
        // it pushes
        let (hl, hh) = (0.5 * a.length - 1e-9 - TOLERANCE, 0.5 * height - TOLERANCE);
        let body = polygon(&[[-hl, -hh], [hl, -hh], [hl, hh], [-hl, hh]]);
        for (k, s) in solids.iter().enumerate() {
            if body.intersects(s) {
                problems.push(format!(
                    "the actuator ({} long, {} high) overlaps {}",
                    short_mm(a.length * MM),
                    short_mm(height * MM),
                    name(k)
                ));
            }
        }
    }
    problems
}
