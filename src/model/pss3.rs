//! The 3-PSS flexible parallel micro-manipulator of paper 000 (Ren, Cao, Micromachines 2021,
//! 12, 678), Sec. 3-4: a platform translating in x, y, z on three limbs 120 deg apart, each
//! limb a slider on a vertical rail and two parallel rods with a flexure spherical hinge at
//! each end.
//!
//! # Kinematics (Eq. 2-6)
//!
//! With `Er = ra - rp`, the rod of limb i runs from the slider's hinge `B_i` to the platform's
//! `P_i`, and its length is fixed:
//!
//! ```text
//! Eq. 3   (x - Er c_i)^2 + (y - Er s_i)^2 + (z + h - b_i)^2 = l^2,   h = sqrt(l^2 - Er^2)
//! Eq. 6   b_i' = J_i . P',   J_i = ((x - Er c_i), (y - Er s_i), (z + h - b_i)) / (z + h - b_i)
//! ```
//!
//! with `c_i = cos phi_i`, `s_i = sin phi_i`, `phi_i = 0, 120, 240 deg`. At rest,
//! `J_i = (-Er c_i / h, -Er s_i / h, 1)`: the signs the extraction lost follow from Eq. 3, and
//! the "approximate" Jacobian the paper prints is exact at the rest pose. The rod's tip
//! moves relative to its foot by `dr_i = (dx, dy, dz - J_i . dP)`, normal to the rod.
//!
//! # Hinge deformation (Eq. 7-13)
//!
//! The frame B_i2 has z2 along the rod at rest; the printed Eq. 8 with its signs rebuilt is
//! `Rz(phi_i) Ry(theta_l)`, giving `x2 = (cos theta_l c_i, cos theta_l s_i, sin theta_l)` (for
//! `Er > 0` the rod leans inwards: `z2 = (-sin theta_l c_i, -sin theta_l s_i, cos theta_l)`) and
//! `y2 = (-s_i, c_i, 0)`. Eq. 10 with small angles, `[[1, 0, beta], [0, 1, -alpha],
//! [-beta, alpha, 1]]`, carries the rod's tip `(0, 0, l)` to `l (beta, -alpha, 1)`, so Eq. 11 =
//! Eq. 12 gives `beta_i = x2 . dr_i / l` and `alpha_i = -y2 . dr_i / l`: the rows of `J_psi,i`
//! ([`Pss3::hinge_jacobians`]); the third angle (torsion) is blocked (Sec. 3).
//!
//! # Dynamics (Eq. 14-26)
//!
//! ```text
//! M = (mp + 3 mc) E + (mb + mc) J^T J
//! K = (4 kbm / l^2) sum_i A_i^T A_i + (mb + mc) g sum_i Hess(b_i),   A_i = d(dr_i)/dP
//! Hess(b_i) = E_h / h + w_i w_i^T / h^3,   w_i = (Er c_i, Er s_i, 0),  E_h = diag(1, 1, 0)
//! det(K - w^2 M) = 0
//! ```
//!
//! Rebuilt from the paper's own statements:
//! - Each rod's mass `mc` is split between its ends (Sec. 4): six half-rods ride on the
//!   platform, two on each slider. The kinetic energy `Tc` and `M` of Eq. 18 and 24 print
//!   `mc` on the platform where the gravity term `Vc` of Eq. 19 has `3 mc`; the split gives
//!   `3 mc`, which is used.
//! - Four hinges per limb, each bending as the rod turns (Eq. 20), give `4 kbm |dr_i|^2 / l^2`.
//! - Gravity (Eq. 15, 17, 19): the platform and the rods' upper halves rise with `z` only, a
//!   linear potential; the sliders and the rods' lower halves ride on `b_i(P)`, whose
//!   curvature gives a stiffness. Its exact Hessian is the expression above; the paper's
//!   `3 (mb + mc) g / h E_h` is its first part (the `w_i w_i^T` term, a factor
//!   `1 + Er^2/(2 h^2)` on the trace, is what the paper's constant-Jacobian approximation drops).
//!   It is 0.1 % of `K` at the paper's sizes.
//!
//! For three limbs 120 deg apart `M` and `K` are diagonal (`sum c_i = sum s_i = sum c_i s_i = 0`),
//! so the frequencies are the three diagonal ratios: `f_z = 0` (a rigid motion: the sliders
//! follow the platform, no hinge bends) and
//!
//! ```text
//! f_x = f_y = sqrt([12 kbm (1 + t^2/2) / l^2 + 3 (mb + mc) g (1 + t^2/2) / h]
//!                  / [mp + 3 mc + 3/2 (mb + mc) t^2]) / (2 pi),        t = tan theta_l = Er / h
//! ```
//!
//! The tests build the full matrices, check them diagonal, and solve the generalized
//! eigenproblem independently. Units: the paper gives `kbm = 5.18 N/m`; a hinge's bending
//! stiffness is a moment per angle, and 5.18 N m/rad is the reading that reproduces its
//! frequencies (tests/models/pss3.rs).

use super::entry::ModelEntry;
use super::scalar::Scalar;
use super::{
    check_parameters, model_from_all_outputs, AllOutputs, Dimension, Drawing, ModeShape,
    OutputInfo, ParameterInfo,
};

/// Standard gravity (m/s^2).
pub const GRAVITY: f64 = 9.80665;

/// Parameters of the 3-PSS micro-manipulator, SI units, in the order of [`PARAMETERS`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pss3<D> {
    /// Radius ra of the static platform (the sliders' circle) (m).
    pub base_radius: D,
    /// Radius rp of the mobile platform (m).
    pub platform_radius: D,
    /// Rod length l (m).
    pub rod_length: D,
    /// Bending stiffness kbm of one flexure spherical hinge (N m/rad).
    pub hinge_stiffness: D,
    /// Mass mp of the mobile platform (kg).
    pub platform_mass: D,
    /// Mass mb of one slider (kg).
    pub slider_mass: D,
    /// Mass mc of one rod (kg).
    pub rod_mass: D,
}

/// The design parameters, in model order.
pub static PARAMETERS: [ParameterInfo; 7] = [
    ParameterInfo::new(
        "ra",
        Dimension::Length,
        "radius of the static platform, the sliders' circle",
    ),
    ParameterInfo::new("rp", Dimension::Length, "radius of the mobile platform"),
    ParameterInfo::new("l", Dimension::Length, "length of the link rods"),
    ParameterInfo::new(
        "kbm",
        Dimension::RotationalStiffness,
        "bending stiffness of one flexure spherical hinge",
    ),
    ParameterInfo::new("mp", Dimension::Mass, "mass of the mobile platform"),
    ParameterInfo::new("mb", Dimension::Mass, "mass of one slider"),
    ParameterInfo::new("mc", Dimension::Mass, "mass of one link rod"),
];

/// The outputs, in model order.
pub static OUTPUTS: [OutputInfo; 8] = [
    OutputInfo::new(
        "f1",
        Dimension::Frequency,
        "first natural frequency (the z mode, 0 Hz)",
    ),
    OutputInfo::new("f2", Dimension::Frequency, "second natural frequency (x)"),
    OutputInfo::new("f3", Dimension::Frequency, "third natural frequency (y)"),
    OutputInfo::new(
        "f_x",
        Dimension::Frequency,
        "natural frequency of the x translation",
    ),
    OutputInfo::new(
        "f_y",
        Dimension::Frequency,
        "natural frequency of the y translation",
    ),
    OutputInfo::new(
        "f_z",
        Dimension::Frequency,
        "natural frequency of the z translation (0: a rigid motion)",
    ),
    OutputInfo::new(
        "theta_l",
        Dimension::Angle,
        "angle of the rods to the z axis, asin(|Er| / l)",
    ),
    OutputInfo::new(
        "height",
        Dimension::Length,
        "height h of the mobile platform over the sliders, sqrt(l^2 - Er^2)",
    ),
];

impl<D: Scalar> Pss3<D> {
    pub fn from_slice(x: &[D]) -> Self {
        Pss3 {
            base_radius: x[0],
            platform_radius: x[1],
            rod_length: x[2],
            hinge_stiffness: x[3],
            platform_mass: x[4],
            slider_mass: x[5],
            rod_mass: x[6],
        }
    }

    /// `Er = ra - rp` (m).
    pub fn radius_difference(&self) -> D {
        self.base_radius - self.platform_radius
    }

    /// `h = sqrt(l^2 - Er^2)` (m).
    pub fn height(&self) -> D {
        let er = self.radius_difference();
        (self.rod_length * self.rod_length - er * er).sqrt()
    }

    /// The rest Jacobians `J_i` of Eq. 6, rows `i = 1, 2, 3`.
    pub fn jacobian(&self) -> [[D; 3]; 3] {
        let (er, h) = (self.radius_difference(), self.height());
        let one = D::from(1.0);
        LIMB_ANGLES.map(|(s, c)| [-(er * c) / h, -(er * s) / h, one])
    }

    /// The mass matrix `M` (kg).
    pub fn mass_matrix(&self) -> [[D; 3]; 3] {
        let j = self.jacobian();
        let lumped = self.platform_mass + self.rod_mass * 3.0;
        let riding = self.slider_mass + self.rod_mass;
        let mut m = [[D::from(0.0); 3]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                let jtj = j[0][r] * j[0][c] + j[1][r] * j[1][c] + j[2][r] * j[2][c];
                *v = riding * jtj + if r == c { lumped } else { D::from(0.0) };
            }
        }
        m
    }

    /// The hinge angular-deformation Jacobians of Eq. 13, `psi_i = J_psi,i P` with
    /// `psi_i = (alpha_i, beta_i, 0)`: the two small turns of the equivalent spherical hinge
    /// about the axes x2, y2 of its frame B_i2 (Eq. 8: z2 along the rod at rest, x2 in the
    /// plane of the rod and the z axis, y2 = (-sin phi_i, cos phi_i, 0)). The rod's tip moves
    /// by `dr_i = (dx, dy, dz - J_i . dP)`; Eq. 9-12 read `dr_i = l (beta_i x2 - alpha_i y2)`.
    pub fn hinge_jacobians(&self) -> [[[D; 3]; 3]; 3] {
        let (er, h, l) = (self.radius_difference(), self.height(), self.rod_length);
        let (ts, tc) = (er / l, h / l);
        let j = self.jacobian();
        let zero = D::from(0.0);
        std::array::from_fn(|i| {
            let (s, c) = LIMB_ANGLES[i];
            let x2 = [tc * c, tc * s, ts];
            let y2 = [D::from(-s), D::from(c), zero];
            // d(dr_i)/dP, column by column
            let dr = |col: usize| {
                let mut v = [zero; 3];
                if col < 2 {
                    v[col] = D::from(1.0);
                }
                v[2] = v[2] + if col == 2 { D::from(1.0) } else { zero } - j[i][col];
                v
            };
            let dot = |a: &[D; 3], b: [D; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let inv_l = l.recip();
            [
                std::array::from_fn(|col| -dot(&y2, dr(col)) * inv_l),
                std::array::from_fn(|col| dot(&x2, dr(col)) * inv_l),
                [zero; 3],
            ]
        })
    }

    /// The stiffness matrix `K` (N/m) of Eq. 24: the four hinges of each limb,
    /// `4 sum J_psi^T K_b J_psi` with `K_b = diag(kbm, kbm, 0)`, and the gravity on the sliders.
    pub fn stiffness_matrix(&self) -> [[D; 3]; 3] {
        let (er, h) = (self.radius_difference(), self.height());
        let weight = (self.slider_mass + self.rod_mass) * GRAVITY;
        let bending = self.hinge_stiffness * 4.0;
        let zero = D::from(0.0);
        let mut k = [[zero; 3]; 3];
        for (jp, (s, c)) in self.hinge_jacobians().iter().zip(LIMB_ANGLES) {
            let w = [er * c, er * s, zero];
            for r in 0..3 {
                for col in 0..3 {
                    // K_b has no torsion: only the rows alpha and beta count
                    let hinge = jp[0][r] * jp[0][col] + jp[1][r] * jp[1][col];
                    let flat = if r == col && r < 2 { h.recip() } else { zero };
                    let hess = flat + w[r] * w[col] / (h * h * h);
                    k[r][col] = k[r][col] + bending * hinge + weight * hess;
                }
            }
        }
        k
    }

    /// `(f_x, f_y, f_z)` (Hz): the diagonal ratios of `K` and `M`, see the module docs.
    pub fn axis_frequencies(&self) -> [D; 3] {
        let (m, k) = (self.mass_matrix(), self.stiffness_matrix());
        std::array::from_fn(|a| {
            if k[a][a].re() == 0.0 {
                // the rigid z motion: exactly zero, with a zero gradient
                D::from(0.0)
            } else {
                (k[a][a] / m[a][a]).sqrt() * (0.5 / std::f64::consts::PI)
            }
        })
    }

    /// Every output, in the order of [`OUTPUTS`].
    pub fn outputs(&self) -> [D; 8] {
        let [fx, fy, fz] = self.axis_frequencies();
        let mut sorted = [fx, fy, fz];
        sorted.sort_by(|a, b| a.re().total_cmp(&b.re()));
        let (er, l) = (self.radius_difference(), self.rod_length);
        let theta = (er.abs() / l).arcsin();
        [
            sorted[0],
            sorted[1],
            sorted[2],
            fx,
            fy,
            fz,
            theta,
            self.height(),
        ]
    }
}

/// `(sin phi_i, cos phi_i)` for `phi_i = 0, 120, 240 deg`.
const LIMB_ANGLES: [(f64, f64); 3] = [
    (0.0, 1.0),
    (0.866_025_403_784_438_6, -0.5),
    (-0.866_025_403_784_438_6, -0.5),
];

/// `asin` for the scalar types, exact in value and first derivative (all a `Jet` carries):
/// the value from `f64::asin`, the derivative `1 / sqrt(1 - x^2)` applied to the perturbation.
trait Arcsin {
    fn arcsin(self) -> Self;
}

impl<D: Scalar> Arcsin for D {
    fn arcsin(self) -> Self {
        let x = self.re();
        (self - x) * (1.0 - x * x).sqrt().recip() + x.asin()
    }
}

/// The 3-PSS as a [`Model`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Pss3Model;

model_from_all_outputs!(
    Pss3Model,
    "pss3",
    PARAMETERS,
    OUTPUTS,
    domain_error,
    drawing
);

/// How a problem file selects the 3-PSS: it takes no section, every parameter is a variable.
pub const ENTRY: ModelEntry = ModelEntry {
    name: "pss3",
    sections: &[],
    schema: super::entry::no_sections,
    template: include_str!("templates/pss3.toml"),
    hinge_layout: None,
    optional_outputs: None,
    build: |_| Ok(super::Mechanism::depicted(Pss3Model)),
};

/// The natural modes of the design `x` (SI): M and K are diagonal, so each axis is a mode.
fn drawing(x: &[f64]) -> Drawing {
    let p = Pss3::from_slice(x);
    let (m, f) = (p.mass_matrix(), p.axis_frequencies());
    let mut modes: Vec<ModeShape> = (0..3)
        .map(|a| {
            let mut v = [0.0; 3];
            v[a] = m[a][a].sqrt().recip();
            ModeShape {
                frequency: f[a],
                x: v[0],
                y: v[1],
                z: Some(v[2]),
                gamma: None,
            }
        })
        .collect();
    modes.sort_by(|a, b| a.frequency.total_cmp(&b.frequency));
    Drawing {
        nodes_mm: None,
        mode_shapes: Some(modes),
    }
}

/// Why `x` lies outside the model's domain, if it does.
fn domain_error(x: &[f64]) -> Option<String> {
    if let Some(why) = check_parameters("3-PSS", &PARAMETERS, x, &[0, 1, 2], &[3, 4, 5, 6]) {
        return Some(why);
    }
    if x[4] + 3.0 * x[6] <= 0.0 {
        return Some("mp + 3 mc = 0: nothing moves with the platform".into());
    }
    let er = x[0] - x[1];
    if er.abs() >= x[2] {
        return Some(format!(
            "|ra - rp| = {} m is not shorter than the rods (l = {} m): the platform cannot stand",
            er.abs(),
            x[2]
        ));
    }
    None
}

impl AllOutputs<7, 8> for Pss3Model {
    fn all<D: Scalar>(&self, x: &[D]) -> Option<[D; 8]> {
        Some(Pss3::from_slice(x).outputs())
    }
}
