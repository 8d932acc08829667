//! Clearances between convex solids as functions of the design, for a part's rules
//! ([`super::part_rules`]) that keep solids apart.
//!
//! A solid is a convex polygon given by its corners (in any order: only their convex hull
//! counts), each corner a function of the design over [`Scalar`]. The clearance of two
//! solids is their distance when they are apart and minus the depth of their overlap when
//! they overlap (the least shift along an axis that parts them): continuous, zero exactly
//! where they touch, so that its sign is the test "do they overlap" and `clearance - slot`
//! the test "are they at least `slot` apart".
//!
//! - Apart: the distance of two convex polygons is that of a corner of one to an edge of the
//!   other (Ericson, Real-Time Collision Detection, Morgan Kaufmann 2005, Sec. 5.1.2 and
//!   9.1). Every segment between two corners is taken for an edge: a segment inside a hull
//!   is never nearer than its boundary, so the least over all of them is the hulls'
//!   distance, and no hull need be built.
//! - Overlapping: the separating-axis test (Gottschalk, Lin and Manocha, SIGGRAPH 1996;
//!   Ericson Sec. 4.4.1) along the normals of the same segments, which include the hulls'
//!   edges: the largest gap of the projections, negative, is the overlap's depth.
//!
//! The value is piecewise smooth: which corner and edge (or axis) gives it is chosen on the
//! real parts ([`Feature`]), and only that piece is evaluated over the dual numbers, so
//! that the gradient is exact on each piece and the search's cost is that of `f64`
//! arithmetic. Its kinks lie where the nearest pair of features changes, as the distance
//! itself has them.

use super::scalar::Scalar;

mod reach;
pub use reach::{reach, Reach};

/// A point of the plane.
pub type Pt<D> = [D; 2];

/// What gives a clearance: the corner `p` of one solid (`a` when `from_a`) and the segment
/// `(i, j)` of the other's corners, or, for an overlap, the axis normal to the segment
/// `(i, j)` of one solid and the two corners whose projections on it bound the gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feature {
    /// Distance from a corner to a segment, `clamp` telling where the foot lies: 0 or 1 at
    /// an end, `None` between them.
    CornerSegment {
        from_a: bool,
        p: usize,
        i: usize,
        j: usize,
        clamp: Option<usize>,
    },
    /// Gap along the normal of segment `(i, j)` of `a` (when `on_a`) or `b`: `lo` the
    /// corner of the solid ahead (the least projection), `hi` the corner of the solid
    /// behind (the largest), `a_behind` whether that solid is `a`.
    Axis {
        on_a: bool,
        i: usize,
        j: usize,
        a_behind: bool,
        lo: usize,
        hi: usize,
    },
}

fn sub<D: Scalar>(a: Pt<D>, b: Pt<D>) -> Pt<D> {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot<D: Scalar>(a: Pt<D>, b: Pt<D>) -> D {
    a[0] * b[0] + a[1] * b[1]
}

fn cross<D: Scalar>(a: Pt<D>, b: Pt<D>) -> D {
    a[0] * b[1] - a[1] * b[0]
}

fn norm<D: Scalar>(a: Pt<D>) -> D {
    dot(a, a).sqrt()
}

/// The real parts of `points`.
pub fn real<D: Scalar>(points: &[Pt<D>]) -> Vec<Pt<f64>> {
    points.iter().map(|p| [p[0].re(), p[1].re()]).collect()
}

/// The sides of a solid whose corners go once around it in order: each corner to the next.
pub const IN_ORDER: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];

/// Every segment between two of four corners in any order: their hull's sides among them.
pub const ANY_ORDER: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// A solid: its corners and the segments between them that include its hull's sides
/// ([`IN_ORDER`] for corners in order around a convex polygon, [`ANY_ORDER`] otherwise).
#[derive(Clone, Copy)]
pub struct Solid<'a> {
    pub corners: &'a [Pt<f64>],
    pub sides: &'a [(usize, usize)],
}

/// The clearance of the solids `a` and `b` and the feature that gives it.
pub fn clearance(a: Solid, b: Solid) -> (f64, Feature) {
    clearance_below(a, b, f64::INFINITY).expect("any clearance is below infinity")
}

/// As [`clearance`], where it is below `bound`: none where the gap along an axis already
/// shows it is not (the gap is a lower bound of the distance), at a fraction of the cost.
pub fn clearance_below(a: Solid, b: Solid, bound: f64) -> Option<(f64, Feature)> {
    match (quadrilateral(a), quadrilateral(b)) {
        (Some((a, true)), Some((b, true))) => quadrilaterals::<true, true>(a, b, bound),
        (Some((a, true)), Some((b, false))) => quadrilaterals::<true, false>(a, b, bound),
        (Some((a, false)), Some((b, true))) => quadrilaterals::<false, true>(a, b, bound),
        (Some((a, false)), Some((b, false))) => quadrilaterals::<false, false>(a, b, bound),
        _ => below(a, b, bound),
    }
}

/// A solid's four corners and whether its sides are [`IN_ORDER`] (else [`ANY_ORDER`]), where
/// it is a quadrilateral with one of those.
fn quadrilateral<'a>(s: Solid<'a>) -> Option<(&'a [Pt<f64>; 4], bool)> {
    let corners = s.corners.try_into().ok()?;
    if s.sides == IN_ORDER {
        Some((corners, true))
    } else if s.sides == ANY_ORDER {
        Some((corners, false))
    } else {
        None
    }
}

/// [`clearance_below`] of two quadrilaterals, their sides [`IN_ORDER`] where `A` (`B`), else
/// [`ANY_ORDER`]: the same arithmetic in the same order, with every loop's length and every
/// corner's index known to the compiler. The parts' pieces are all quadrilaterals, and the
/// loops over slices cost more than their arithmetic: bounds checks, and loop counters on
/// the stack beside the products (wei2017's study: about 3,300 instructions a call).
#[inline(never)]
fn quadrilaterals<const A: bool, const B: bool>(
    a: &[Pt<f64>; 4],
    b: &[Pt<f64>; 4],
    bound: f64,
) -> Option<(f64, Feature)> {
    let sides = |in_order: bool| -> &'static [(usize, usize)] {
        if in_order {
            &IN_ORDER
        } else {
            &ANY_ORDER
        }
    };
    below(
        Solid {
            corners: a,
            sides: sides(A),
        },
        Solid {
            corners: b,
            sides: sides(B),
        },
        bound,
    )
}

/// [`clearance_below`] for any solids; inlined where their shapes are known.
#[inline(always)]
fn below(a: Solid, b: Solid, bound: f64) -> Option<(f64, Feature)> {
    let (gap, axis) = separation(a, b, bound)?;
    if gap <= 0.0 {
        return Some((gap, axis));
    }
    let mut best = (f64::INFINITY, axis);
    for (from_a, own, other) in [(true, a, b), (false, b, a)] {
        for (p, &q) in own.corners.iter().enumerate() {
            for &(i, j) in other.sides {
                let (d2, clamp) = to_segment(q, other.corners[i], other.corners[j]);
                if d2 < best.0 {
                    let f = Feature::CornerSegment {
                        from_a,
                        p,
                        i,
                        j,
                        clamp,
                    };
                    best = (d2, f);
                }
            }
        }
    }
    Some((best.0.sqrt(), best.1))
}

/// The squared distance from `p` to the segment `(a, b)`, and which end the foot is
/// clamped to.
#[inline(always)]
fn to_segment(p: Pt<f64>, a: Pt<f64>, b: Pt<f64>) -> (f64, Option<usize>) {
    let d = sub(b, a);
    let len2 = dot(d, d);
    let ap = sub(p, a);
    let t = if len2 > 0.0 { dot(ap, d) / len2 } else { 0.0 };
    if t <= 0.0 {
        (dot(ap, ap), Some(0))
    } else if t >= 1.0 {
        let bp = sub(p, b);
        (dot(bp, bp), Some(1))
    } else {
        let c = cross(d, ap);
        (c * c / len2, None)
    }
}

/// The largest gap between the projections of `a` and `b` on the normal of any side of
/// either, and its axis; `None` as soon as an axis shows a gap of `bound` or more.
#[inline(always)]
fn separation(a: Solid, b: Solid, bound: f64) -> Option<(f64, Feature)> {
    let mut best = (f64::NEG_INFINITY, None);
    for (on_a, own) in [(true, a), (false, b)] {
        for &(i, j) in own.sides {
            let d = sub(own.corners[j], own.corners[i]);
            let len = norm(d);
            if len == 0.0 {
                continue;
            }
            let n = [-d[1] / len, d[0] / len];
            let span = |pts: &[Pt<f64>]| {
                let mut lo = (f64::INFINITY, 0);
                let mut hi = (f64::NEG_INFINITY, 0);
                for (k, &p) in pts.iter().enumerate() {
                    let s = dot(n, p);
                    if s < lo.0 {
                        lo = (s, k);
                    }
                    if s > hi.0 {
                        hi = (s, k);
                    }
                }
                (lo, hi)
            };
            let ((a_lo, a_lo_k), (a_hi, a_hi_k)) = span(a.corners);
            let ((b_lo, b_lo_k), (b_hi, b_hi_k)) = span(b.corners);
            for (gap, a_behind, lo, hi) in [
                (b_lo - a_hi, true, b_lo_k, a_hi_k),
                (a_lo - b_hi, false, a_lo_k, b_hi_k),
            ] {
                if gap >= bound {
                    return None;
                }
                if gap > best.0 {
                    let f = Feature::Axis {
                        on_a,
                        i,
                        j,
                        a_behind,
                        lo,
                        hi,
                    };
                    best = (gap, Some(f));
                }
            }
        }
    }
    let (gap, f) = best;
    Some((gap, f.expect("a solid has at least two distinct corners")))
}

impl Feature {
    /// The clearance this feature gives for the solids with corners `a` and `b` (the same
    /// solids it was found on, now over dual numbers).
    pub fn value<D: Scalar>(&self, a: &[Pt<D>], b: &[Pt<D>]) -> D {
        match *self {
            Feature::CornerSegment {
                from_a,
                p,
                i,
                j,
                clamp,
            } => {
                let (own, other) = if from_a { (a, b) } else { (b, a) };
                let (q, s, e) = (own[p], other[i], other[j]);
                match clamp {
                    Some(0) => norm(sub(q, s)),
                    Some(_) => norm(sub(q, e)),
                    None => {
                        let d = sub(e, s);
                        let c = cross(d, sub(q, s));
                        // the corner's side of the segment, on the real part
                        let c = if c.re() < 0.0 { -c } else { c };
                        c / norm(d)
                    }
                }
            }
            Feature::Axis {
                on_a,
                i,
                j,
                a_behind,
                lo,
                hi,
            } => {
                let own = if on_a { a } else { b };
                let d = sub(own[j], own[i]);
                let n = [-d[1], d[0]];
                let (ahead, behind) = if a_behind { (b, a) } else { (a, b) };
                (dot(n, ahead[lo]) - dot(n, behind[hi])) / norm(d)
            }
        }
    }
}

impl Feature {
    /// Where this feature measures the clearance of the solids with corners `a` and `b`
    /// (real parts): `a`'s point, then `b`'s. Apart, a corner and its foot on the other's
    /// segment, as far apart as the clearance; overlapping, the corner ahead along the
    /// axis and its projection on the line across the axis through the corner behind, as
    /// far apart as the overlap is deep.
    pub fn witness(&self, a: &[Pt<f64>], b: &[Pt<f64>]) -> [Pt<f64>; 2] {
        match *self {
            Feature::CornerSegment {
                from_a,
                p,
                i,
                j,
                clamp,
            } => {
                let (own, other) = if from_a { (a, b) } else { (b, a) };
                let (q, s, e) = (own[p], other[i], other[j]);
                let foot = match clamp {
                    Some(0) => s,
                    Some(_) => e,
                    None => {
                        let d = sub(e, s);
                        let t = dot(sub(q, s), d) / dot(d, d);
                        [s[0] + t * d[0], s[1] + t * d[1]]
                    }
                };
                if from_a {
                    [q, foot]
                } else {
                    [foot, q]
                }
            }
            Feature::Axis {
                on_a,
                i,
                j,
                a_behind,
                lo,
                hi,
            } => {
                let own = if on_a { a } else { b };
                let d = sub(own[j], own[i]);
                let len = norm(d);
                let n = [-d[1] / len, d[0] / len];
                let (ahead, behind) = if a_behind { (b, a) } else { (a, b) };
                let p = ahead[lo];
                let gap = dot(n, p) - dot(n, behind[hi]);
                let q = [p[0] - n[0] * gap, p[1] - n[1] * gap];
                if a_behind {
                    [q, p]
                } else {
                    [p, q]
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, h: f64) -> Vec<Pt<f64>> {
        vec![
            [x - h, y - h],
            [x + h, y - h],
            [x + h, y + h],
            [x - h, y + h],
        ]
    }

    fn clear(a: &[Pt<f64>], b: &[Pt<f64>]) -> (f64, Feature) {
        let solid = |corners| Solid {
            corners,
            sides: &ANY_ORDER,
        };
        clearance(solid(a), solid(b))
    }

    #[test]
    fn apart_side_by_side_corner_to_corner_and_overlapping() {
        let a = square(0.0, 0.0, 1.0);
        // side by side: the gap between the faces
        let (c, f) = clear(&a, &square(3.5, 0.3, 1.0));
        assert!((c - 1.5).abs() < 1e-15, "{c}");
        assert!((f.value(&a, &square(3.5, 0.3, 1.0)) - c).abs() < 1e-15);
        // corner to corner: the diagonal, which no axis of the two squares gives
        let (c, _) = clear(&a, &square(3.0, 3.0, 1.0));
        assert!((c - 2f64.sqrt()).abs() < 1e-15, "{c}");
        // overlapping by 0.25 along x
        let (c, f) = clear(&a, &square(1.75, 0.1, 1.0));
        assert!((c + 0.25).abs() < 1e-15, "{c}");
        assert!(matches!(f, Feature::Axis { .. }));
        // the order of the corners does not matter
        let mut shuffled = square(3.0, 3.0, 1.0);
        shuffled.swap(0, 2);
        assert!((clear(&a, &shuffled).0 - 2f64.sqrt()).abs() < 1e-15);
    }
}
