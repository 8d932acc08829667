//! The least width of the part's bodies (links, blocks), measured on the finished outline.
//!
//! A body is what is left of the outline once every hinge's own zone is taken out: its thin
//! section, its fillets and the root band between its faces (`fillet` beyond each end of
//! the thin section, `root / 2 + fillet` to each side of its centre line). Hinges are thin
//! on purpose and are not judged here. Each body is judged by the rule of the `[part]`
//! sizes that a wall must not be thinner than the hinges it carries (it would bend more
//! than they do): a disc as wide as the thickest hinge the body carries must travel inside
//! the body between the roots of all its hinges (meeting, at each, the round of the root's
//! width about the middle of the hinge's end) and to each named face on it. That is, the
//! body eroded by half that width keeps one piece that reaches all of them. Measured on the
//! outline, whatever made the body thin: a link swung across its hinges to a sliver, a
//! hinge's root in a sharp corner of its body, a block cut away.
//!
//! A body that fails is measured: the widest disc that still makes the journey (bisection
//! on the erosion) is its least width, and the place is where the body, eroded a little
//! more, parts.

use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{
    Area, BooleanOps, Buffer, Centroid, Coord, Distance, Euclidean, Line, MultiPolygon, Point,
    Polygon,
};

use super::outline::{polygon_mm, Loop};
use super::{HingeSite, PartSpec, MM};

/// Chords per arc when the outline is handed to `geo` (a fillet of 0.2 mm is then off by
/// less than 0.1 um).
const PER_ARC: usize = 32;

/// A body passes when a disc this much (relative) narrower than its rule makes the
/// journey: the rule itself is met exactly by a body as wide as its hinges.
const SLACK: f64 = 1e-4;

/// The relative precision of a measured width.
const PRECISION: f64 = 1e-5;

/// How far (mm) each hinge's zone reaches past the faces into the bodies, so that no
/// sliver of the root band is left on a body.
const MARGIN: f64 = 1e-5;

/// The round joins of an erosion: steps of this angle (rad).
const JOIN: f64 = 0.05;

/// A distance for a message: mm, four decimals.
fn short_mm(v: f64) -> String {
    format!("{v:.4} mm")
}

/// The zone of `h` (metres, counterclockwise): its thin section, its fillets and the root
/// band between its faces, `margin` (m) past them.
fn zone(h: &HingeSite, margin: f64) -> Vec<[f64; 2]> {
    let len = (h.end[0] - h.start[0]).hypot(h.end[1] - h.start[1]);
    let u = [(h.end[0] - h.start[0]) / len, (h.end[1] - h.start[1]) / len];
    let n = [-u[1], u[0]];
    let w = 0.5 * h.root + h.fillet + margin;
    let (a, b) = (-h.fillet - margin, len + h.fillet + margin);
    let at = |s: f64, t: f64| {
        [
            h.start[0] + s * u[0] + t * n[0],
            h.start[1] + s * u[1] + t * n[1],
        ]
    };
    vec![at(a, -w), at(b, -w), at(b, w), at(a, w)]
}

/// The outline as one `geo` polygon in mm, arcs in chords.
fn outline_mm(loops: &[Loop]) -> Polygon<f64> {
    let ring = |l: &Loop| {
        let points: Vec<[f64; 2]> = l.points(PER_ARC);
        polygon_mm(&points).exterior().clone()
    };
    Polygon::new(ring(&loops[0]), loops[1..].iter().map(ring).collect())
}

fn line_mm(a: [f64; 2], b: [f64; 2]) -> Line<f64> {
    Line::new(
        Coord {
            x: a[0] * MM,
            y: a[1] * MM,
        },
        Coord {
            x: b[0] * MM,
            y: b[1] * MM,
        },
    )
}

/// What a body must reach: a hinge's end (with the hinge's least thickness) or a named
/// face.
#[derive(Clone, Copy)]
struct End {
    line: Line<f64>,
    hinge: Option<f64>,
}

/// What is left of `body` when every point within `r` (mm) of its boundary is taken away:
/// the centres of the discs of radius `r` inside it.
fn erode(body: &Polygon<f64>, r: f64) -> MultiPolygon<f64> {
    let style = BufferStyle::new(-r).line_join(LineJoin::Round(JOIN));
    body.buffer_with_style(style)
}

/// The piece of `body` eroded by `r` (mm) that reaches every one of `ends`, if one does.
fn joined(body: &Polygon<f64>, r: f64, ends: &[End]) -> Option<Polygon<f64>> {
    if r <= 0.0 {
        return Some(body.clone());
    }
    let eroded = erode(body, r);
    // a disc of radius r touching an end has its centre r from it; the erosion's own
    // rounding is far below this tolerance
    let reach = r * (1.0 + 1e-3) + 1e-6;
    eroded.0.into_iter().find(|piece| {
        ends.iter().all(|e| match e.hinge {
            // the disc reaches the hinge's root: it meets the round of the root's width
            // about the middle of the hinge's end
            Some(_) => {
                Euclidean.distance(piece, &e.line.centroid())
                    <= reach + 0.5 * e.line.dx().hypot(e.line.dy())
            }
            None => Euclidean.distance(piece, &e.line) <= reach,
        })
    })
}

/// The bodies of the part thinner than the hinges they carry, each named with the width
/// found, the rule and the place (mm).
pub fn too_thin(spec: &PartSpec, loops: &[Loop]) -> Vec<String> {
    if spec.hinges.is_empty() || loops.is_empty() {
        return Vec::new();
    }
    let zones: Vec<Polygon<f64>> = spec
        .hinges
        .iter()
        .map(|h| polygon_mm(&zone(h, MARGIN / MM)))
        .collect();
    let zones = geo::unary_union(&zones);
    let bodies: MultiPolygon<f64> = outline_mm(loops).difference(&zones);
    // each hinge's two ends: the short sides of its zone, where it meets its bodies
    let mut ends: Vec<End> = Vec::new();
    for h in &spec.hinges {
        let z = zone(h, MARGIN / MM);
        for (a, b) in [(z[3], z[0]), (z[1], z[2])] {
            ends.push(End {
                line: line_mm(a, b),
                hinge: Some(h.thickness),
            });
        }
    }
    ends.extend(spec.faces.iter().map(|f| End {
        line: line_mm(f.a, f.b),
        hinge: None,
    }));
    let hinge_solids: Vec<usize> = spec.hinges.iter().map(|h| h.solid).collect();
    // each problem with the index of the body's first solid, to list them in the spec's order
    let mut problems: Vec<(usize, String)> = Vec::new();
    for body in &bodies.0 {
        let on = |e: &End| Euclidean.distance(body, &e.line.centroid()) < 1e-6;
        let mine: Vec<End> = ends.iter().copied().filter(on).collect();
        let rule = mine.iter().filter_map(|e| e.hinge).fold(0.0_f64, f64::max) * MM;
        if rule <= 0.0 {
            continue;
        }
        let r = 0.5 * rule * (1.0 - SLACK);
        if joined(body, r, &mine).is_some() {
            continue;
        }
        let (width, at) = least_width(body, r, &mine);
        let solids: Vec<usize> = (0..spec.solids.len())
            .filter(|k| {
                !hinge_solids.contains(k)
                    && polygon_mm(&spec.solids[*k].points)
                        .centroid()
                        .is_some_and(|c| Euclidean.distance(body, &c) < 1e-6)
            })
            .collect();
        let name = if solids.is_empty() {
            "a body of the part".to_string()
        } else {
            let names: Vec<&str> = solids
                .iter()
                .map(|&k| spec.solids[k].name.as_str())
                .collect();
            names.join(" and ")
        };
        let first = solids.first().copied().unwrap_or(usize::MAX);
        problems.push((
            first,
            format!(
                "{name} is {} across at ({:.3}, {:.3}) mm, thinner than the hinges it carries \
             ({}): a link or block must be at least as thick as its hinges, or it bends \
             more than they do",
                short_mm(width),
                at.x(),
                at.y(),
                short_mm(rule)
            ),
        ));
    }
    problems.sort_by_key(|(first, _)| *first);
    problems.into_iter().map(|(_, p)| p).collect()
}

/// The widest disc that travels through `body` between all of `ends` (its diameter, mm,
/// from below to `PRECISION`), a disc of radius `fails` being too wide, and where the body
/// parts: the point of the eroded body farthest from what a slightly wider disc still
/// reaches (the middle of the narrow place), or its centroid when nothing is left.
fn least_width(body: &Polygon<f64>, fails: f64, ends: &[End]) -> (f64, Point<f64>) {
    let (mut lo, mut hi) = (0.0, fails);
    let mut last = body.clone();
    while hi - lo > PRECISION * fails {
        let mid = 0.5 * (lo + hi);
        match joined(body, mid, ends) {
            Some(piece) => {
                lo = mid;
                last = piece;
            }
            None => hi = mid,
        }
    }
    let beyond = erode(body, hi);
    let farthest = (beyond.unsigned_area() > 0.0)
        .then(|| {
            last.exterior()
                .points()
                .map(|p| (Euclidean.distance(&beyond, &p), p))
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, p)| p)
        })
        .flatten();
    let at = farthest
        .or_else(|| last.centroid())
        .unwrap_or_else(|| Point::from(body.exterior().0[0]));
    (2.0 * lo, at)
}
