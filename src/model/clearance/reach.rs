//! How wide a convex solid is along a path: a disc of a given radius moved into the solid
//! towards a target, for the rule that a link is as wide as the hinges it carries
//! ([`reach`]).

use super::{cross, dot, norm, sub, Pt};
use crate::model::scalar::Scalar;

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
