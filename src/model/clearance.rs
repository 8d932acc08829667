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

/// A side of a convex solid: its corners `(i, j)` and whether the solid lies to its left.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Side {
    i: usize,
    j: usize,
    left: bool,
}

/// The most corners a solid of [`reach`] has (the part's pieces are quadrilaterals), and
/// so the most segments between them: the sides and lines live in arrays of this size, as
/// a width is worked out at every evaluation of the study's rules.
const MAX_CORNERS: usize = 4;
const MAX_SIDES: usize = MAX_CORNERS * (MAX_CORNERS - 1) / 2;

/// The sides of the convex hull of `corners`: the segments with every other corner on one
/// side of them, the first `count` of the array.
fn sides(corners: &[Pt<f64>]) -> ([Side; MAX_SIDES], usize) {
    assert!(
        corners.len() <= MAX_CORNERS,
        "a solid of at most {MAX_CORNERS} corners"
    );
    let mut out = [Side::default(); MAX_SIDES];
    let mut count = 0;
    for i in 0..corners.len() {
        for j in i + 1..corners.len() {
            let d = sub(corners[j], corners[i]);
            let (mut left, mut right) = (false, false);
            for (k, &c) in corners.iter().enumerate() {
                if k != i && k != j {
                    let side = cross(d, sub(c, corners[i]));
                    left |= side > 0.0;
                    right |= side < 0.0;
                }
            }
            if left != right {
                out[count] = Side { i, j, left };
                count += 1;
            }
        }
    }
    (out, count)
}

impl Side {
    /// The outward unit normal `n` and the line's offset `n . corner` less `inset`: the
    /// solid eroded by `inset` is where `n . p <= offset` for every side.
    fn line<D: Scalar>(&self, corners: &[Pt<D>], inset: D) -> (Pt<D>, D) {
        let d = sub(corners[self.j], corners[self.i]);
        let len = norm(d);
        let n = if self.left {
            [d[1] / len, -d[0] / len]
        } else {
            [-d[1] / len, d[0] / len]
        };
        (n, dot(n, corners[self.i]) - inset)
    }
}

/// The constraints that hold with equality at a [`reach`]'s optimum, the sides by their
/// place in a list of lines.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Active {
    /// The point at the target itself, deep inside.
    AtTarget,
    /// The target's disc and one side.
    OneSide(usize),
    /// The target's disc and two sides; `root` of the quadratic (`-1` or `1`).
    TwoSides(usize, usize, f64),
    /// Three sides: the centre of the largest disc inside (the disc of the target slack).
    ThreeSides(usize, usize, usize),
}

/// What gives a [`reach`]: the constraints that hold with equality at its optimum, with the
/// sides among them (the first of `sides`, as many as `active` names, in its order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    active: Active,
    sides: [Side; 3],
}

/// How far a disc of radius `radius` that travels inside the convex solid with `corners`
/// comes to reach within `allowance` of `target`, as a margin: the largest `s` for which a
/// disc of radius `radius + s` inside the solid has its centre within `allowance - s` of
/// `target`. Non-negative exactly where the solid eroded by `radius` is not empty and comes
/// within `allowance` of the target: the test of a body's width between its ends
/// ([`crate::part::widths`]). The maximization is a convex program in the centre and `s`; its
/// optimum is one of the points where the disc's constraint and up to two sides hold with
/// equality, or three sides do, and the feasible one with the largest `s` is it.
pub fn reach(corners: &[Pt<f64>], radius: f64, target: Pt<f64>, allowance: f64) -> (f64, Reach) {
    let (sides, count) = sides(corners);
    let mut lines = [([0.0; 2], 0.0); MAX_SIDES];
    for (l, s) in lines.iter_mut().zip(&sides[..count]) {
        *l = s.line(corners, radius);
    }
    let lines = &lines[..count];
    let scale = allowance.abs().max(radius).max(1e-300);
    let feasible = |(p, s): (Pt<f64>, f64)| {
        let slack = 1e-9 * scale;
        norm(sub(p, target)) <= allowance - s + slack
            && lines.iter().all(|&(n, c)| dot(n, p) + s <= c + slack)
    };
    let mut best = (f64::NEG_INFINITY, Active::AtTarget);
    let mut consider = |r: Active| {
        if let Some((p, s)) = solve(r, lines, target, allowance) {
            if s > best.0 && feasible((p, s)) {
                best = (s, r);
            }
        }
    };
    consider(Active::AtTarget);
    let k = lines.len();
    for a in 0..k {
        consider(Active::OneSide(a));
        for b in a + 1..k {
            consider(Active::TwoSides(a, b, -1.0));
            consider(Active::TwoSides(a, b, 1.0));
            for c in b + 1..k {
                consider(Active::ThreeSides(a, b, c));
            }
        }
    }
    // the sides the optimum stands on, renumbered to their place among them
    let (active, named, count) = match best.1 {
        Active::AtTarget => (Active::AtTarget, [0; 3], 0),
        Active::OneSide(a) => (Active::OneSide(0), [a, 0, 0], 1),
        Active::TwoSides(a, b, r) => (Active::TwoSides(0, 1, r), [a, b, 0], 2),
        Active::ThreeSides(a, b, c) => (Active::ThreeSides(0, 1, 2), [a, b, c], 3),
    };
    let mut chosen = [Side::default(); 3];
    for (slot, &k) in chosen.iter_mut().zip(&named[..count]) {
        *slot = sides[k];
    }
    let at = Reach {
        active,
        sides: chosen,
    };
    (best.0, at)
}

impl Reach {
    /// The margin this optimum gives for the solid with `corners` (the one it was found
    /// on, now over dual numbers).
    pub fn value<D: Scalar>(&self, corners: &[Pt<D>], radius: D, target: Pt<D>, allowance: D) -> D {
        let count = match self.active {
            Active::AtTarget => 0,
            Active::OneSide(_) => 1,
            Active::TwoSides(..) => 2,
            Active::ThreeSides(..) => 3,
        };
        let zero = D::from(0.0);
        let mut lines = [([zero; 2], zero); 3];
        for (l, s) in lines.iter_mut().zip(&self.sides[..count]) {
            *l = s.line(corners, radius);
        }
        solve(self.active, &lines[..count], target, allowance).map_or(D::from(f64::NAN), |(_, s)| s)
    }
}

impl Reach {
    /// Where this optimum measures the width (real parts): the centre of the widest disc
    /// and the point where it touches the first side it stands on, `radius` plus the margin
    /// apart; `None` where it stands on no side (the disc at the target, far inside).
    pub fn witness(
        &self,
        corners: &[Pt<f64>],
        radius: f64,
        target: Pt<f64>,
        allowance: f64,
    ) -> Option<[Pt<f64>; 2]> {
        if matches!(self.active, Active::AtTarget) {
            return None;
        }
        let lines = self.sides.map(|s| s.line(corners, radius));
        let (p, _) = solve(self.active, &lines, target, allowance)?;
        let (n, c) = self.sides[0].line(corners, 0.0);
        let gap = c - dot(n, p);
        Some([p, [p[0] + n[0] * gap, p[1] + n[1] * gap]])
    }
}

/// The centre and margin where the constraints of `r` hold with equality, if they meet.
fn solve<D: Scalar>(r: Active, lines: &[(Pt<D>, D)], f: Pt<D>, rho: D) -> Option<(Pt<D>, D)> {
    match r {
        Active::AtTarget => Some((f, rho)),
        Active::OneSide(a) => {
            // from the target straight towards the side: the disc's radius and the side's
            // slack meet halfway
            let (n, c) = lines[a];
            let gap = c - dot(n, f);
            let along = (rho - gap) * 0.5;
            if along.re() < 0.0 {
                return None;
            }
            Some((sub(f, [n[0] * along, n[1] * along]), (rho + gap) * 0.5))
        }
        Active::TwoSides(a, b, root) => {
            // the centre on both sides' lines, p(s) = p0 - s v, at distance rho - s from f
            let ((n1, c1), (n2, c2)) = (lines[a], lines[b]);
            let det = cross(n1, n2);
            if det.re().abs() < 1e-12 {
                return None;
            }
            let solve2 = |r1: D, r2: D| {
                [
                    (r1 * n2[1] - r2 * n1[1]) / det,
                    (n1[0] * r2 - n2[0] * r1) / det,
                ]
            };
            let p0 = solve2(c1, c2);
            let one = D::from(1.0);
            let v = solve2(one, one);
            let w = sub(p0, f);
            let qa = dot(v, v) - 1.0;
            let qb = (rho - dot(w, v)) * 2.0;
            let qc = dot(w, w) - rho * rho;
            let s = if qa.re().abs() < 1e-12 {
                if root > 0.0 {
                    return None;
                }
                -qc / qb
            } else {
                let disc = qb * qb - qa * qc * 4.0;
                if disc.re() < 0.0 {
                    return None;
                }
                (-qb + disc.sqrt() * root) / (qa * 2.0)
            };
            if (rho - s).re() < 0.0 {
                return None;
            }
            Some((sub(p0, [v[0] * s, v[1] * s]), s))
        }
        Active::ThreeSides(a, b, c) => {
            // n_k . p + s = c_k for three sides: Cramer's rule
            let rows = [lines[a], lines[b], lines[c]];
            let det3 = |m: [[D; 3]; 3]| {
                m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
            };
            let one = D::from(1.0);
            let m = rows.map(|(n, _)| [n[0], n[1], one]);
            let det = det3(m);
            if det.re().abs() < 1e-12 {
                return None;
            }
            let rhs = rows.map(|(_, c)| c);
            let with = |col: usize| {
                let mut m = m;
                for (row, r) in m.iter_mut().zip(rhs) {
                    row[col] = r;
                }
                det3(m) / det
            };
            Some(([with(0), with(1)], with(2)))
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
