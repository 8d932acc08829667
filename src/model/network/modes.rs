//! The natural modes of a flexure network: its bodies' masses and inertias against the
//! stiffness of [`super::structure`], the flexures massless (their mass is a few per cent
//! of the links' in a piezo stage, and the bodies carry it where the description puts it).
//!
//! `K phi = w^2 M phi` over the degrees of freedom not held, solved on the values by a
//! Cholesky factor of `M` and a symmetric eigensolver (nalgebra). The derivatives come from
//! the Rayleigh quotient `w^2 = phi^T K phi / phi^T M phi` evaluated in the scalar type at
//! the eigenvector found: the quotient is stationary at an eigenvector, so its first
//! derivative is exact for a simple eigenvalue without the eigenvector's (Fox and Kapoor,
//! "Rates of change of eigenvalues and eigenvectors", AIAA J. 6 (1968) 2426-2429, Eq. 9).
//! Its second derivatives would need the eigenvector's, which it does not carry: a robust
//! study on a frequency must not read them from here.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

pub use super::inertia::{described_piece, DirectedMass, Inertia};
use super::structure::{Body, Dof, Flexure, Network, NetworkError, Spring};
use crate::model::scalar::Scalar;

/// One mode: its frequency (Hz) and its shape, each body's `(u, v, theta)` at its
/// reference point (held ones zero), scaled to unit modal mass.
#[derive(Debug, Clone)]
pub struct Mode<D> {
    pub frequency: D,
    pub shape: Vec<[f64; 3]>,
}

/// What keeps the modes from being found, beside the network's own errors.
#[derive(Debug, Clone, PartialEq)]
pub enum ModeError {
    Network(NetworkError),
    /// Body `body` has no mass (or no inertia) where it can move.
    Massless {
        body: usize,
    },
}

impl std::fmt::Display for ModeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ModeError::Network(e) => e.fmt(f),
            ModeError::Massless { body } => write!(
                f,
                "body {body} has no mass or no inertia where it can move: give it an outline \
                 or a mass"
            ),
        }
    }
}

impl<D: Scalar> Network<D> {
    /// The mass matrix of the bodies' degrees of freedom at their reference points,
    /// row-major `3n x 3n`: each body's mass and inertia carried from its centroid by the
    /// rigid transfer.
    pub fn mass_matrix(&self, inertia: &[Inertia<D>]) -> Vec<D> {
        self.mass_matrix_with(inertia, &[])
    }

    /// The same with `directed` masses: each adds `m g g^T` to its body's block, `g` the
    /// velocity of its point along its direction per unit `(u, v, theta)` of the body,
    /// `[n_x, n_y, n_y r_x - n_x r_y]` for the point `r` from the reference.
    pub fn mass_matrix_with(&self, inertia: &[Inertia<D>], directed: &[DirectedMass<D>]) -> Vec<D> {
        let n = 3 * self.references.len();
        let mut m = vec![D::from(0.0); n * n];
        for d in directed {
            let r = [
                d.point[0] - self.references[d.body][0],
                d.point[1] - self.references[d.body][1],
            ];
            let [nx, ny] = d.direction;
            let g = [nx, ny, ny * r[0] - nx * r[1]];
            let o = 3 * d.body;
            for p in 0..3 {
                for q in 0..3 {
                    m[(o + p) * n + o + q] = m[(o + p) * n + o + q] + g[p] * g[q] * d.mass;
                }
            }
        }
        for (b, body) in inertia.iter().enumerate() {
            let r = [
                body.centroid[0] - self.references[b][0],
                body.centroid[1] - self.references[b][1],
            ];
            let o = 3 * b;
            let mass = body.mass;
            let entries = [
                (0, 0, mass),
                (1, 1, mass),
                (0, 2, -(mass * r[1])),
                (1, 2, mass * r[0]),
                (2, 2, body.moment + mass * (r[0] * r[0] + r[1] * r[1])),
            ];
            for (p, q, v) in entries {
                m[(o + p) * n + o + q] = m[(o + p) * n + o + q] + v;
                if p != q {
                    m[(o + q) * n + o + p] = m[(o + q) * n + o + p] + v;
                }
            }
        }
        m
    }

    /// The described part joined to its image in the line `y = 0` (`flip_y`) or `x = 0`: the
    /// whole part about that line, standing on the image of body `mount`, which is the
    /// ground. The bodies `across` the line are their own images, whose holds become
    /// `held` (the holds of the other mirror axis, which every body and its image keep);
    /// every other body gets an image, every flexure and spring its image between the
    /// bodies' images (a spring on a body across the line its own, at twice the stiffness;
    /// on the mount, none). A flexure's image has the same compliance: the reflection
    /// flips its frame's lateral axis and its rotation together, which leaves `c23`.
    /// Returns the network and each body's image.
    pub fn unfolded(
        &self,
        flip_y: bool,
        across: &[bool],
        held: &[(usize, Dof)],
        mount: usize,
    ) -> (Network<D>, Vec<Body>) {
        let reflect = |p: [D; 2]| if flip_y { [p[0], -p[1]] } else { [-p[0], p[1]] };
        let mut references = self.references.clone();
        let image: Vec<Body> = (0..self.references.len())
            .map(|b| {
                if across[b] {
                    Body::Rigid(b)
                } else if b == mount {
                    Body::Ground
                } else {
                    references.push(reflect(self.references[b]));
                    Body::Rigid(references.len() - 1)
                }
            })
            .collect();
        let map = |body: Body| match body {
            Body::Ground => Body::Ground,
            Body::Rigid(b) => image[b],
        };
        let mut flexures = self.flexures.clone();
        flexures.extend(self.flexures.iter().map(|f| Flexure {
            from: map(f.from),
            to: map(f.to),
            start: reflect(f.start),
            axis: reflect(f.axis),
            end: reflect(f.end),
            ..*f
        }));
        let mut springs = Vec::new();
        for s in &self.springs {
            match image[s.body] {
                Body::Rigid(b) if b == s.body => springs.push(Spring {
                    stiffness: s.stiffness * 2.0,
                    ..*s
                }),
                Body::Rigid(b) => {
                    springs.push(*s);
                    springs.push(Spring {
                        body: b,
                        point: reflect(s.point),
                        direction: reflect(s.direction),
                        stiffness: s.stiffness,
                    });
                }
                Body::Ground => springs.push(*s),
            }
        }
        let mut all_held = held.to_vec();
        for &(b, dof) in held {
            if let Body::Rigid(i) = image[b] {
                if i != b {
                    all_held.push((i, dof));
                }
            }
        }
        all_held.sort_by_key(|&(b, dof)| (b, dof as usize));
        let network = Network {
            references,
            flexures,
            springs,
            held: all_held,
            guides: Vec::new(),
        };
        (network, image)
    }

    /// The `count` lowest modes (fewer where the network has fewer degrees of freedom).
    pub fn modes(&self, inertia: &[Inertia<D>], count: usize) -> Result<Vec<Mode<D>>, ModeError> {
        self.modes_with(inertia, &[], count)
    }

    /// The same with `directed` masses besides the bodies' ([`Self::mass_matrix_with`]).
    pub fn modes_with(
        &self,
        inertia: &[Inertia<D>],
        directed: &[DirectedMass<D>],
        count: usize,
    ) -> Result<Vec<Mode<D>>, ModeError> {
        let n = 3 * self.references.len();
        let k = self.stiffness().map_err(ModeError::Network)?;
        let m = self.mass_matrix_with(inertia, directed);
        // the degrees of freedom not held
        let free: Vec<usize> = (0..n)
            .filter(|&j| !self.held.iter().any(|&(b, d)| 3 * b + d as usize == j))
            .collect();
        let nf = free.len();
        let pick = |a: &[D]| DMatrix::from_fn(nf, nf, |i, j| a[free[i] * n + free[j]].re());
        // a free motion is the structure's error, named as a solve would name it
        self.solve(&[]).map_err(ModeError::Network)?;
        let pairs = eigenpairs(&pick(&k), &pick(&m))
            .map_err(|j| ModeError::Massless { body: free[j] / 3 })?;
        let mut modes = Vec::new();
        for (_, phi) in pairs.into_iter().take(count) {
            let mut full = vec![0.0; n];
            for (p, &j) in free.iter().enumerate() {
                full[j] = phi[p];
            }
            let omega2 = rayleigh(&k, &m, &full);
            modes.push(Mode {
                frequency: omega2.sqrt() / (2.0 * std::f64::consts::PI),
                shape: full.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
            });
        }
        Ok(modes)
    }
}

/// The eigenpairs of `K phi = w^2 M phi` (`K` symmetric, `M` symmetric positive definite),
/// by `w^2` from the lowest, each `phi` of unit modal mass: `M = L L^T` (Cholesky), the
/// symmetric `L^-1 K L^-T` solved (nalgebra's symmetric eigensolver), `phi = L^-T y`. Where
/// `M` is not positive definite, the first degree of freedom with no mass (else 0).
pub(super) fn eigenpairs(
    k: &DMatrix<f64>,
    m: &DMatrix<f64>,
) -> Result<Vec<(f64, DVector<f64>)>, usize> {
    let massless = || (0..m.nrows()).find(|&i| m[(i, i)] <= 0.0).unwrap_or(0);
    let m = (m + m.transpose()) * 0.5;
    let l = m.cholesky().ok_or_else(massless)?.l();
    let y = l.solve_lower_triangular(k).ok_or_else(massless)?;
    let a = l
        .solve_lower_triangular(&y.transpose())
        .ok_or_else(massless)?;
    let eigen = SymmetricEigen::new((&a + a.transpose()) * 0.5);
    let lt = l.transpose();
    let mut pairs: Vec<(f64, DVector<f64>)> = (0..a.nrows())
        .map(|i| {
            let y = eigen.eigenvectors.column(i).into_owned();
            let phi = lt.solve_upper_triangular(&y).unwrap_or(y);
            (eigen.eigenvalues[i], phi)
        })
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(pairs)
}

/// The Rayleigh quotient `phi^T K phi / phi^T M phi` of the row-major `K` and `M` (in the
/// scalar type) at the real `phi`. At an eigenvector of a simple eigenvalue it is `w^2`,
/// and, being stationary there, its first derivative is the eigenvalue's, `phi^T (dK - w^2
/// dM) phi / phi^T M phi`, without the eigenvector's (Fox and Kapoor, "Rates of change of
/// eigenvalues and eigenvectors", AIAA J. 6 (1968) 2426-2429, Eq. 9).
pub(super) fn rayleigh<D: Scalar>(k: &[D], m: &[D], phi: &[f64]) -> D {
    let n = phi.len();
    let quadratic = |a: &[D]| {
        let mut s = D::from(0.0);
        for (p, &fp) in phi.iter().enumerate() {
            if fp == 0.0 {
                continue;
            }
            for (q, &fq) in phi.iter().enumerate() {
                if fq != 0.0 {
                    s = s + a[p * n + q] * (fp * fq);
                }
            }
        }
        s
    };
    quadratic(k) / quadratic(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::hinge::HingeKind;
    use crate::model::material::Material;
    use crate::model::scalar::Jet;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs())
    }

    /// A body on three springs: one along x at its centroid, two along y at `+-a`. Its
    /// modes are `k_x / m`, `2 k_y / m` and `2 k_y a^2 / J`, whatever the reference point.
    #[test]
    fn a_body_on_springs_has_its_three_exact_modes() {
        let (m, j, a, kx, ky) = (0.05, 2e-5, 0.01, 3e5, 1e5);
        let spring = |point: [f64; 2], direction: [f64; 2], stiffness| Spring {
            body: 0,
            point,
            direction,
            stiffness,
        };
        let net = Network {
            references: vec![[0.004, -0.003]],
            flexures: vec![],
            springs: vec![
                spring([0.0, 0.0], [1.0, 0.0], kx),
                spring([a, 0.0], [0.0, 1.0], ky),
                spring([-a, 0.0], [0.0, 1.0], ky),
            ],
            held: vec![],
            guides: Vec::new(),
        };
        let inertia = [Inertia {
            mass: m,
            centroid: [0.0, 0.0],
            moment: j,
        }];
        let modes = net.modes(&inertia, 3).unwrap();
        let mut expected = [kx / m, 2.0 * ky / m, 2.0 * ky * a * a / j]
            .map(|w2: f64| w2.sqrt() / (2.0 * std::f64::consts::PI));
        expected.sort_by(f64::total_cmp);
        for (mode, f) in modes.iter().zip(expected) {
            assert!(
                close(mode.frequency, f, 1e-10),
                "{} against {f}",
                mode.frequency
            );
        }
    }

    /// A point mass is the same mass moving along any two perpendicular directions: the
    /// directed pair equals `Inertia::with_point_mass` entry by entry, wherever the point
    /// and the reference, whichever the direction.
    #[test]
    fn two_perpendicular_directed_masses_are_a_point_mass() {
        let net = Network::<f64> {
            references: vec![[0.0, 0.0], [0.004, -0.003]],
            flexures: vec![],
            springs: vec![],
            held: vec![],
            guides: Vec::new(),
        };
        let body = Inertia {
            mass: 0.05,
            centroid: [0.002, 0.001],
            moment: 2e-5,
        };
        let (m, at) = (0.012, [-0.007, 0.009]);
        let point = net.mass_matrix(&[body, body.with_point_mass(m, at)]);
        for angle in [0.0, 0.3, 1.0, 2.5] {
            let n = [f64::cos(angle), f64::sin(angle)];
            let pair = [(n, m), ([-n[1], n[0]], m)].map(|(direction, mass)| DirectedMass {
                body: 1,
                point: at,
                direction,
                mass,
            });
            let directed = net.mass_matrix_with(&[body, body], &pair);
            for (a, b) in point.iter().zip(&directed) {
                assert!((a - b).abs() < 1e-15, "{a} against {b} at angle {angle}");
            }
        }
    }

    /// A body on a spring along x, the stack's mass on it: along the stack it moves with
    /// the stack's share `m/3` (a stack on the ground), `sqrt(k / (M + m/3))`; a mirrored
    /// stack in its stretched family adds `m/6` along it. Across, it adds the other share.
    #[test]
    fn a_stacks_mass_lowers_the_mode_along_it_by_its_share() {
        let (mass, k, stack) = (0.05, 3e5, 0.015);
        let net = Network {
            references: vec![[0.0, 0.0]],
            flexures: vec![],
            springs: vec![Spring {
                body: 0,
                point: [0.0, 0.0],
                direction: [1.0, 0.0],
                stiffness: k,
            }],
            held: vec![(0, Dof::Y), (0, Dof::Rotation)],
            guides: Vec::new(),
        };
        let inertia = [Inertia {
            mass,
            centroid: [0.0, 0.0],
            moment: 1e-5,
        }];
        let f = |m: f64| (k / m).sqrt() / (2.0 * std::f64::consts::PI);
        for ((mirrored, stretched), share) in [
            ((false, true), stack / 3.0),
            ((true, true), stack / 6.0),
            ((true, false), stack / 2.0),
        ] {
            let directed =
                DirectedMass::stack(stack, (mirrored, stretched), 0, [0.0, 0.0], [2.0, 0.0]);
            let got = net.modes_with(&inertia, &directed, 1).unwrap()[0].frequency;
            assert!(
                close(got, f(mass + share), 1e-12),
                "{got} against {}",
                f(mass + share)
            );
        }
    }

    /// A stage on a parallelogram guide: its sideways mode is the guide's stiffness over
    /// the stage's mass (the stage held from turning), and the frequency's derivative by
    /// the strips' thickness, through the Rayleigh quotient, matches central differences.
    #[test]
    fn a_guided_stage_moves_at_its_guide_frequency_with_exact_derivatives() {
        let guide = |t: Jet<1>| {
            let c =
                HingeKind::Strip.compliance(&[Jet::from(0.01), t], 0.01, &Material::al7075_t6());
            let leaf = |y: f64| {
                Flexure::new(
                    Body::Ground,
                    Body::Rigid(0),
                    [Jet::from(0.0), Jet::from(y)],
                    [Jet::from(1.0), Jet::from(0.0)],
                    Jet::from(0.01),
                    c,
                )
            };
            Network {
                references: vec![[Jet::from(0.01), Jet::from(0.0)]],
                flexures: vec![leaf(-0.01), leaf(0.01)],
                springs: vec![],
                held: vec![(0, Dof::Rotation)],
                guides: Vec::new(),
            }
        };
        let inertia = [Inertia {
            mass: Jet::from(0.02),
            centroid: [Jet::from(0.01), Jet::from(0.0)],
            moment: Jet::from(1e-6),
        }];
        let t = 0.0003;
        let net = guide(Jet::variable(t, 0));
        let first = &net.modes(&inertia, 1).unwrap()[0];
        // the guide's sideways stiffness, by a static solve of the same network
        let u = net
            .solve(&[super::super::structure::Load {
                body: 0,
                point: net.references[0],
                force: [Jet::from(0.0), Jet::from(1.0)],
                moment: Jet::from(0.0),
            }])
            .unwrap();
        let k = 1.0 / u.bodies[0][1].re;
        let f = (k / 0.02).sqrt() / (2.0 * std::f64::consts::PI);
        assert!(
            close(first.frequency.re, f, 1e-10),
            "{} against {f}",
            first.frequency.re
        );
        assert!(
            first.shape[0][0].abs() < 1e-9 * first.shape[0][1].abs(),
            "sideways"
        );
        let at = |t: f64| {
            guide(Jet::from(t)).modes(&inertia, 1).unwrap()[0]
                .frequency
                .re
        };
        let h = 1e-9;
        let fd = (at(t + h) - at(t - h)) / (2.0 * h);
        assert!(
            close(first.frequency.grad[0], fd, 1e-6),
            "{} against {fd}",
            first.frequency.grad[0]
        );
    }

    /// A rectangle's mass, centroid and moment, `m (a^2 + b^2) / 12`, whichever its winding,
    /// far from the origin; an L of two rectangles by Steiner's rule; a link as its
    /// rectangle; a point mass added by the parallel-axis rule.
    #[test]
    fn plates_have_their_handbook_inertias() {
        let (rho, w) = (2810.0, 0.01);
        let (a, b, cx, cy) = (0.03, 0.012, 0.25, -0.4);
        let corners = [
            [cx - a / 2.0, cy - b / 2.0],
            [cx + a / 2.0, cy - b / 2.0],
            [cx + a / 2.0, cy + b / 2.0],
            [cx - a / 2.0, cy + b / 2.0],
        ];
        let m = rho * w * a * b;
        let j = m * (a * a + b * b) / 12.0;
        let mut clockwise = corners;
        clockwise.reverse();
        for pts in [corners, clockwise] {
            let r = Inertia::polygon(&pts, rho, w);
            assert!(close(r.mass, m, 1e-12), "{} against {m}", r.mass);
            assert!(close(r.moment, j, 1e-9), "{} against {j}", r.moment);
            assert!((r.centroid[0] - cx).abs() < 1e-14 && (r.centroid[1] - cy).abs() < 1e-14);
        }
        let link = Inertia::link([cx - a / 2.0, cy], [cx + a / 2.0, cy], b, rho, w);
        assert!(close(link.mass, m, 1e-12) && close(link.moment, j, 1e-12));
        // an L: a 0.02 x 0.004 foot and a 0.004 x 0.016 leg on its left end
        let l_shape = [
            [0.0, 0.0],
            [0.02, 0.0],
            [0.02, 0.004],
            [0.004, 0.004],
            [0.004, 0.02],
            [0.0, 0.02],
        ];
        let parts = [(0.02, 0.004, 0.01, 0.002), (0.004, 0.016, 0.002, 0.012)];
        let mass: f64 = parts.iter().map(|p| rho * w * p.0 * p.1).sum();
        let c = [
            parts.iter().map(|p| rho * w * p.0 * p.1 * p.2).sum::<f64>() / mass,
            parts.iter().map(|p| rho * w * p.0 * p.1 * p.3).sum::<f64>() / mass,
        ];
        let moment: f64 = parts
            .iter()
            .map(|p| {
                let mi = rho * w * p.0 * p.1;
                mi * (p.0 * p.0 + p.1 * p.1) / 12.0
                    + mi * ((p.2 - c[0]).powi(2) + (p.3 - c[1]).powi(2))
            })
            .sum();
        let r = Inertia::polygon(&l_shape, rho, w);
        assert!(close(r.mass, mass, 1e-12) && close(r.moment, moment, 1e-12));
        assert!(close(r.centroid[0], c[0], 1e-12) && close(r.centroid[1], c[1], 1e-12));
        // a point mass at a corner
        let p = 0.005;
        let loaded = Inertia::polygon(&corners, rho, w).with_point_mass(p, corners[2]);
        let shift = [a / 2.0 * p / (m + p), b / 2.0 * p / (m + p)];
        let d_body = shift[0].powi(2) + shift[1].powi(2);
        let d_point = (a / 2.0 - shift[0]).powi(2) + (b / 2.0 - shift[1]).powi(2);
        assert!(close(loaded.mass, m + p, 1e-14));
        assert!(close(loaded.moment, j + m * d_body + p * d_point, 1e-12));
        assert!(close(loaded.centroid[0], cx + shift[0], 1e-12));
    }

    #[test]
    fn a_massless_body_is_named() {
        let net: Network<f64> = Network {
            references: vec![[0.0, 0.0]],
            flexures: vec![],
            springs: vec![
                Spring {
                    body: 0,
                    point: [0.0, 0.0],
                    direction: [1.0, 0.0],
                    stiffness: 1e5,
                },
                Spring {
                    body: 0,
                    point: [0.01, 0.0],
                    direction: [0.0, 1.0],
                    stiffness: 1e5,
                },
                Spring {
                    body: 0,
                    point: [-0.01, 0.0],
                    direction: [0.0, 1.0],
                    stiffness: 1e5,
                },
            ],
            held: vec![],
            guides: Vec::new(),
        };
        let none = [Inertia {
            mass: 0.0,
            centroid: [0.0, 0.0],
            moment: 0.0,
        }];
        let err = net.modes(&none, 1).unwrap_err();
        assert_eq!(err, ModeError::Massless { body: 0 });
        assert!(err.to_string().contains("body 0 has no mass"));
    }
}
