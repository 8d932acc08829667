//! The half of a part that is symmetric about the y axis: the solids at `x >= 0`, those
//! that straddle the axis cut there, and the cut named as the symmetry face. A finite-element
//! model of the half with the symmetry held on the cut gives the whole part's symmetric
//! response (and, with the other condition, its antisymmetric modes) at half the cost.

use super::{Face, PartSpec, Solid};

/// The name of the faces on the cut.
pub const SYMMETRY: &str = "symmetry";

/// A convex polygon (counterclockwise) clipped to `x >= 0` (Sutherland-Hodgman, one plane).
fn clip(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let n = points.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        if a[0] >= 0.0 {
            out.push(a);
        }
        if (a[0] < 0.0) != (b[0] < 0.0) {
            let t = a[0] / (a[0] - b[0]);
            out.push([0.0, a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

fn mirrored(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    points.iter().rev().map(|p| [-p[0], p[1]]).collect()
}

fn same(a: &[[f64; 2]], b: &[[f64; 2]], tol: f64) -> bool {
    a.len() == b.len()
        && (0..b.len()).any(|s| {
            a.iter().enumerate().all(|(i, p)| {
                let q = b[(i + s) % b.len()];
                (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol
            })
        })
}

impl PartSpec {
    /// The half at `x >= 0`, if the part is symmetric about the y axis (every solid's
    /// mirror image is a solid, to `1e-12` m); `None` otherwise.
    pub fn right_half(&self) -> Option<PartSpec> {
        let tol = 1e-12;
        // each solid's mirror image among the solids
        let image: Vec<usize> = self
            .solids
            .iter()
            .map(|s| {
                let m = mirrored(&s.points);
                self.solids.iter().position(|t| same(&m, &t.points, tol))
            })
            .collect::<Option<_>>()?;
        let mut index = vec![None; self.solids.len()];
        let mut solids = Vec::new();
        let mut faces = Vec::new();
        for (k, s) in self.solids.iter().enumerate() {
            if s.points.iter().all(|p| p[0] <= 0.0) {
                continue;
            }
            let straddles = s.points.iter().any(|p| p[0] < 0.0);
            let points = if straddles {
                clip(&s.points)
            } else {
                s.points.clone()
            };
            if straddles {
                // the cut: the clipped polygon's edge on the axis, bottom to top
                let on: Vec<[f64; 2]> = points.iter().copied().filter(|p| p[0] == 0.0).collect();
                if let (Some(lo), Some(hi)) = (
                    on.iter().copied().min_by(|a, b| a[1].total_cmp(&b[1])),
                    on.iter().copied().max_by(|a, b| a[1].total_cmp(&b[1])),
                ) {
                    faces.push(Face {
                        name: SYMMETRY.into(),
                        a: lo,
                        b: hi,
                    });
                }
            }
            if !straddles {
                // an edge on the axis where the solid's mirror image is joined to it (a
                // frame drawn to the axis from both sides) is a cut as well: left free, the
                // half would have a slit where the whole part is one piece
                let j = image[k];
                let joined = self
                    .joints
                    .iter()
                    .any(|&(a, b)| (a, b) == (k, j) || (a, b) == (j, k));
                if joined {
                    for (i, &p) in points.iter().enumerate() {
                        let q = points[(i + 1) % points.len()];
                        if p[0].abs() <= tol && q[0].abs() <= tol && p[1] != q[1] {
                            let (lo, hi) = if p[1] < q[1] { (p, q) } else { (q, p) };
                            faces.push(Face {
                                name: SYMMETRY.into(),
                                a: [0.0, lo[1]],
                                b: [0.0, hi[1]],
                            });
                        }
                    }
                }
            }
            index[k] = Some(solids.len());
            solids.push(Solid {
                name: s.name.clone(),
                points,
            });
        }
        let hinges = self
            .hinges
            .iter()
            .filter_map(|h| {
                let solid = index[h.solid]?;
                Some(super::HingeSite { solid, ..h.clone() })
            })
            .collect();
        let joints = self
            .joints
            .iter()
            .filter_map(|&(a, b)| Some((index[a]?, index[b]?)))
            .collect();
        // the faces on the right, those across the axis cut at it
        for f in &self.faces {
            let (a, b) = (f.a, f.b);
            if a[0] <= 0.0 && b[0] <= 0.0 {
                continue;
            }
            let cut = |p: [f64; 2], q: [f64; 2]| {
                if p[0] >= 0.0 {
                    p
                } else {
                    let t = p[0] / (p[0] - q[0]);
                    [0.0, p[1] + t * (q[1] - p[1])]
                }
            };
            faces.push(Face {
                name: f.name.clone(),
                a: cut(a, b),
                b: cut(b, a),
            });
        }
        Some(PartSpec {
            width: self.width,
            actuation: self.actuation,
            analysis: self.analysis.clone(),
            solids,
            joints,
            hinges,
            faces,
            annotations: Vec::new(),
            caption: self.caption.clone(),
            min_slot: self.min_slot,
            actuator: None,
            warnings: Vec::new(),
        })
    }
}
