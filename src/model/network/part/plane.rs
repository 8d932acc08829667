//! Plane geometry of the network's part (metres): vectors, convex pieces, bands, where a
//! ray leaves a convex polygon, what a polygon covers of a line, and what of a side is the
//! part's outline.

use crate::model::scalar::Scalar;
use crate::part::Solid;

pub(super) type P = [f64; 2];

// `add` and `scale` over any scalar: the part's rules place the same points over dual
// numbers ([`super::rules`]), with the same operations
pub(super) fn add<D: Scalar>(a: [D; 2], b: [D; 2]) -> [D; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

pub(super) fn scale<D: Scalar>(a: [D; 2], k: D) -> [D; 2] {
    [a[0] * k, a[1] * k]
}

pub(super) fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

pub(super) fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

pub(super) fn signed_area(points: &[P]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| cross(points[i], points[(i + 1) % n]))
        .sum::<f64>()
}

pub(super) fn is_convex(points: &[P]) -> bool {
    let n = points.len();
    (0..n).all(|i| {
        let (a, b, c) = (points[i], points[(i + 1) % n], points[(i + 2) % n]);
        cross(sub(b, a), sub(c, b)) >= 0.0
    })
}

/// An outline as the part's solids: itself where it is convex, else its triangles.
pub(super) fn convex_pieces(points: Vec<P>) -> Vec<Vec<P>> {
    convex_piece_indices(&points)
        .into_iter()
        .map(|piece| piece.into_iter().map(|k| points[k]).collect())
        .collect()
}

/// [`convex_pieces`] as indices into `points`, so that the part's rules can take the same
/// pieces of the outline over dual numbers.
pub(super) fn convex_piece_indices(points: &[P]) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    if signed_area(points) < 0.0 {
        order.reverse();
    }
    let ordered: Vec<P> = order.iter().map(|&k| points[k]).collect();
    if is_convex(&ordered) {
        vec![order]
    } else {
        triangles(&ordered)
            .into_iter()
            .map(|piece| piece.into_iter().map(|k| order[k]).collect())
            .collect()
    }
}

/// A simple polygon (counterclockwise) cut into triangles by ear clipping (Meisters, "Polygons
/// have ears", Amer. Math. Monthly 82, 1975): convex pieces for the union, as indices into
/// `points`. A body's outline has a handful of corners; geo's `earcut` feature is left out
/// of the build (issue 28, docs/performance.md) and spade's triangulation would need its
/// outside triangles removed.
fn triangles(points: &[P]) -> Vec<Vec<usize>> {
    let mut left: Vec<usize> = (0..points.len()).collect();
    let mut out = Vec::new();
    while left.len() > 3 {
        let n = left.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (
                points[left[(i + n - 1) % n]],
                points[left[i]],
                points[left[(i + 1) % n]],
            );
            cross(sub(b, a), sub(c, b)) > 0.0
                && left.iter().all(|&k| {
                    let p = points[k];
                    p == a
                        || p == b
                        || p == c
                        || !(cross(sub(b, a), sub(p, a)) >= 0.0
                            && cross(sub(c, b), sub(p, b)) >= 0.0
                            && cross(sub(a, c), sub(p, c)) >= 0.0)
                })
        });
        let Some(i) = ear else {
            // a self-crossing outline has no ear: keep what is left whole, the checks say
            break;
        };
        let n = left.len();
        out.push(vec![left[(i + n - 1) % n], left[i], left[(i + 1) % n]]);
        left.remove(i);
    }
    out.push(left);
    out
}

pub(super) fn band(a: P, b: P, half: f64) -> Vec<P> {
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
    vec![
        add(a, scale(n, -half)),
        add(b, scale(n, -half)),
        add(b, scale(n, half)),
        add(a, scale(n, half)),
    ]
}

/// Where the ray from `p` along `dir` first leaves the convex polygon `poly`, if `p` lies in
/// it: the distance along the ray and the edge's index.
pub(super) fn exit(poly: &[P], p: P, dir: P) -> Option<(f64, usize)> {
    let n = poly.len();
    let inside = (0..n).all(|i| cross(sub(poly[(i + 1) % n], poly[i]), sub(p, poly[i])) >= -1e-15);
    if !inside {
        return None;
    }
    (0..n)
        .filter_map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let e = sub(b, a);
            // only a side the ray leaves through (counterclockwise: its outward normal
            // along the ray), not one it enters by or lies on
            let denom = cross(dir, e);
            if denom < 1e-30 {
                return None;
            }
            let s = cross(sub(a, p), e) / denom;
            let t = cross(sub(a, p), dir) / denom;
            (s >= 0.0 && (-1e-12..=1.0 + 1e-12).contains(&t)).then_some((s, i))
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
}

/// The stretch `[c0, c1]` of the line `q + s e` (`s` in `[lo, hi]`) that the convex polygon
/// `poly` covers, its boundary included (to 1e-12 m), if any.
pub(super) fn covered(poly: &[P], q: P, e: P, lo: f64, hi: f64) -> Option<(f64, f64)> {
    covered_to(poly, q, e, lo, hi, 1e-12)
}

/// [`covered`] with the boundary's tolerance `tol` (m) where an edge crosses the line: at 0
/// the stretch ends where the edge crosses the line, as the union's vertex there does (a
/// line along an edge stays covered to 1e-12 m).
fn covered_to(poly: &[P], q: P, e: P, lo: f64, hi: f64, tol: f64) -> Option<(f64, f64)> {
    let (mut a, mut b) = (lo, hi);
    let n = poly.len();
    for i in 0..n {
        let (p0, p1) = (poly[i], poly[(i + 1) % n]);
        let edge = sub(p1, p0);
        let len = edge[0].hypot(edge[1]);
        // inside: cross(edge, point - p0) / len >= -tol, linear in s
        let at0 = cross(edge, sub(q, p0)) / len;
        let slope = cross(edge, e) / len;
        if slope.abs() < 1e-15 {
            if at0 + 1e-12 < 0.0 {
                return None;
            }
            continue;
        }
        let root = -(at0 + tol) / slope;
        if slope > 0.0 {
            a = a.max(root);
        } else {
            b = b.min(root);
        }
    }
    (a < b).then_some((a, b))
}

pub(super) fn same_face(a: (P, P), b: (P, P)) -> bool {
    let tol = 1e-12;
    let near = |p: P, q: P| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol;
    (near(a.0, b.0) && near(a.1, b.1)) || (near(a.0, b.1) && near(a.1, b.0))
}

/// The stretches of the side `a`-`b` of solid `own` that no other solid covers: the part's
/// outline there. The side itself where nothing covers it.
pub(super) fn exposed(solids: &[Solid], own: usize, a: P, b: P) -> Vec<(P, P)> {
    // shorter stretches are left free: a sliver beside a pad is no place to hold a part
    const SHORTEST: f64 = 0.1e-3;
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let e = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    let mut cover: Vec<(f64, f64)> = solids
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != own)
        // the stretches end where the union's outline turns, not 1e-12 m short of it: the
        // mesh splits the outline at a face's end, and a split that close is a sliver
        .filter_map(|(_, s)| covered_to(&s.points, a, e, 0.0, len, 0.0))
        .filter(|&(c0, c1)| c1 - c0 > 1e-9)
        .collect();
    if cover.is_empty() {
        return vec![(a, b)];
    }
    cover.sort_by(|x, y| x.0.total_cmp(&y.0));
    cover.push((len, len));
    let at = |s: f64| {
        if s <= 1e-9 {
            a
        } else if s >= len - 1e-9 {
            b
        } else {
            add(a, scale(e, s))
        }
    };
    let mut out = Vec::new();
    let mut from = 0.0;
    for (c0, c1) in cover {
        if c0 - from >= SHORTEST {
            out.push((at(from), at(c0)));
        }
        from = f64::max(from, c1);
    }
    out
}
