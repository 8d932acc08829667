//! Supports in one direction, `[[network.supports]]`: a guide or a roller holding a body's
//! point along a direction (`at`, `direction`), the motion across it and the body's rotation
//! free, or the rotation held too (`hold_rotation = true`). Read here apart from the rest of
//! the description ([`super::file`]), which hands over its parsing of points and bodies.
//!
//! The structure holds a support exactly, as a constraint on the bodies' motions
//! ([`Constraints`]): a stiff spring in its place would leave an error of the structure's
//! stiffness over the spring's, and the round-off of a matrix that stiff.

use serde::Deserialize;

use super::checks::Two;
use super::description::{Point, SupportDescription};
use crate::model::scalar::Scalar;
use crate::vocab::error::Segment;
use crate::vocab::reader::{k, Res};
use crate::vocab::sections::Sections;

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNetworkSupport {
    /// The body held (not the ground).
    body: String,
    /// The point held, on the body.
    #[schemars(with = "[String; 2]")]
    at: Two,
    /// The direction its motion is held in (a vector, normalised).
    #[schemars(with = "[String; 2]")]
    direction: Two,
    /// Whether the body's rotation is held too (default: free).
    hold_rotation: Option<bool>,
}

/// Each `network.supports[i]` into its description: `body` found by `find_body` (the ground
/// refused), `at` and `direction` parsed by `point`, a direction of constants that is zero
/// refused.
pub(super) fn read(
    s: &Sections,
    raw: &[RawNetworkSupport],
    find_body: impl Fn(&[Segment], &str) -> Res<Option<usize>>,
    point: impl Fn(Vec<Segment>, &Two) -> Res<Point>,
) -> Res<Vec<SupportDescription>> {
    let mut supports = Vec::with_capacity(raw.len());
    for (i, r) in raw.iter().enumerate() {
        let path = vec![k("network"), k("supports"), Segment::Index(i)];
        let sub = |key: &str| {
            let mut q = path.clone();
            q.push(k(key));
            q
        };
        let body = find_body(&sub("body"), &r.body)?.ok_or_else(|| {
            s.err(
                &sub("body"),
                "the ground does not move: a support holds a body, name one",
            )
        })?;
        let direction = point(sub("direction"), &r.direction)?;
        let constant = |e: &super::description::Keyed| {
            let e = &e.expression;
            e.names_used()
                .is_empty()
                .then(|| e.eval::<f64>(&[]).ok())
                .flatten()
        };
        if let (Some(0.0), Some(0.0)) = (constant(&direction[0]), constant(&direction[1])) {
            return Err(s.err(
                &sub("direction"),
                "the direction [0, 0] has zero length: give the direction the motion is held in, \
                 e.g. [\"1\", \"0\"]",
            ));
        }
        supports.push(SupportDescription {
            key: crate::vocab::error::format_path(&path),
            body,
            at: point(sub("at"), &r.at)?,
            direction,
            hold_rotation: r.hold_rotation.unwrap_or(false),
        });
    }
    Ok(supports)
}

/// The supports' constraints `a_i . u = 0` on the free degrees of freedom `u` of a
/// structure whose stiffness `K_s` is `K` plus a spring `s a_i a_i^T` in each support's
/// place: with `W = K_s^-1 A` (a solve per support) and `G = A^T W`, the constrained motion
/// under a load `f` is `u = u_s - W G^-1 A^T u_s`, `u_s = K_s^-1 f` (the multipliers'
/// elimination; the springs do no work where `A^T u = 0`, so any `s > 0` gives the same
/// `u`, exactly).
pub struct Constraints<D> {
    /// Each support's row, sparse: (free index, coefficient).
    rows: Vec<Vec<(usize, D)>>,
    /// `W` by columns, `m` entries each.
    w: Vec<D>,
    /// `G` factored in place, `L D L^T` (its pivots on the diagonal).
    g: Vec<D>,
}

impl<D: Scalar> Constraints<D> {
    /// From the rows, `m` free degrees of freedom and `solve`, which overwrites a load
    /// vector with `K_s^-1` times it; or the first support that holds a motion the others
    /// (or the structure's held degrees of freedom) hold already.
    pub fn new(
        rows: Vec<Vec<(usize, D)>>,
        m: usize,
        mut solve: impl FnMut(&mut [D]),
    ) -> Result<Self, usize> {
        let n = rows.len();
        let mut w = vec![D::from(0.0); n * m];
        for (row, column) in rows.iter().zip(w.chunks_exact_mut(m.max(1))) {
            for &(i, a) in row {
                column[i] = column[i] + a;
            }
            solve(column);
        }
        let dot = |row: &[(usize, D)], x: &[D]| {
            row.iter().fold(D::from(0.0), |acc, &(i, a)| acc + a * x[i])
        };
        let mut g: Vec<D> = (0..n * n)
            .map(|ij| dot(rows[ij / n].as_slice(), &w[(ij % n) * m..(ij % n + 1) * m]))
            .collect();
        let scale: Vec<f64> = (0..n).map(|i| g[i * n + i].re()).collect();
        for j in 0..n {
            for p in 0..j {
                g[j * n + j] = g[j * n + j] - g[j * n + p] * g[j * n + p] * g[p * n + p];
            }
            let pivot = g[j * n + j].re();
            if pivot.is_nan() || pivot <= 1e-10 * scale[j] {
                return Err(j);
            }
            for i in j + 1..n {
                let mut v = g[i * n + j];
                for p in 0..j {
                    v = v - g[i * n + p] * g[j * n + p] * g[p * n + p];
                }
                g[i * n + j] = v / g[j * n + j];
            }
        }
        Ok(Constraints { rows, w, g })
    }

    /// `u_s` into the constrained motion `u` in place.
    pub fn correct(&self, u: &mut [D]) {
        let n = self.rows.len();
        let m = u.len();
        let g = &self.g;
        let mut l: Vec<D> = self
            .rows
            .iter()
            .map(|row| row.iter().fold(D::from(0.0), |acc, &(i, a)| acc + a * u[i]))
            .collect();
        for i in 0..n {
            for p in 0..i {
                l[i] = l[i] - g[i * n + p] * l[p];
            }
        }
        for i in 0..n {
            l[i] = l[i] / g[i * n + i];
        }
        for i in (0..n).rev() {
            for p in i + 1..n {
                l[i] = l[i] - g[p * n + i] * l[p];
            }
        }
        for (lambda, column) in l.iter().zip(self.w.chunks_exact(m.max(1))) {
            for (x, wx) in u.iter_mut().zip(column) {
                *x = *x - *lambda * *wx;
            }
        }
    }
}
