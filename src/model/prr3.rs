//! The 3-PRR compliant parallel mechanism of paper 002 (Jia, Tian, Zhang, "Dynamics analysis
//! of 3-PRR compliant parallel mechanism", Trans. CSAM 2010), Sec. 3: a pseudo-rigid-body
//! Lagrange model of a platform on three prismatic-revolute-revolute limbs 120 deg apart.
//!
//! # Geometry
//!
//! Base joints `A_i = ra (cos a_i, sin a_i)`, platform joints `C_i = p + R(gamma) c_i` with
//! `c_i = rb (cos b_i, sin b_i)`, passive links `B_i C_i` of length `l` at angle `theta_i`,
//! and the sliders `A_i B_i` of length `q_i` along `e_i`, with `a_i = a_1 + 2(i-1) pi/3`,
//! likewise `b_i` and `theta_i^0`. The loop of limb i reads
//!
//! ```text
//! p + R(gamma) c_i = A_i + q_i e_i + l w_i,      w_i = (cos theta_i, sin theta_i)
//! ```
//!
//! The paper names `e_i` but not its direction. Its numbers fix it: with `theta_1^0 = pi`,
//! `b_1 = -pi/6`, `a_1 = -pi/12`, `rb = 30 mm`, `l = 20 mm`, the node `B_1 = C_1 - l w_1` lies at
//! (45.98, -15.00) mm and `A_1 = ra (cos a_1, sin a_1)` at (55.99, -15.00) mm: `ra = 57.96 mm` was
//! chosen so that `A_1 B_1` is horizontal. Each slider therefore moves along its passive link's
//! rest direction, `e_i = w_i^0`, pushing the link lengthwise (as the parallel leaf springs
//! at the drive of its Fig. 1 suggest), not radially.
//!
//! # Dynamics (Eq. 10-12)
//!
//! With the platform pose `s = (x, y, gamma)` as coordinates, `q' = J s'` and
//! `theta' = J_theta s'` at the rest configuration:
//!
//! ```text
//! M = diag(mp, mp, Ip) + mg J^T J + Ig J_theta^T J_theta,    Ip = mp rb^2 / 4,  Ig = mg l^2 / 3
//! K = k J_theta^T J_theta + k1 J^T J + k Jc^T Jc,            Jc = J_theta + N2
//! det(K - w^2 M) = 0
//! ```
//!
//! where `N2` has ones in its third column: the hinge at `C_i` turns by `dtheta_i + dgamma` in
//! the paper's sign convention, which is kept (with `dtheta_i - dgamma` the third frequency
//! would be 1672 Hz, far from the paper's FEA). From the loop:
//! `J_i = (w_i, (R' c_i) . w_i) / (e_i . w_i)` and
//! `J_theta,i = ((w_i^perp, (R' c_i) . w_i^perp) - J_i (e_i . w_i^perp)) / l`.
//!
//! # Against the paper (tests/models/prr3.rs)
//!
//! At the example of Sec. 2 and 4.3 this model gives 1106.87, 1106.87 and 1440.17 Hz. The
//! paper's FEA (Fig. 6) gives 1106.4, 1106.7 and 1446.3 Hz: 0.04, 0.02 and 0.4 % away. The
//! paper's own model values, 1201.6, 1201.7 and 1520.6 Hz, are 7.9 and 5.3 % higher and are
//! not reproduced: no reading of the printed model with the printed numbers gives them (a
//! disc's `mp rb^2 / 2`, a link inertia about its centre, the link inertia left out, either
//! hinge term left out were tried, and none does).

use nalgebra::{Matrix3, Vector3};

use super::entry::ModelEntry;
use super::scalar::Scalar;
use super::{
    check_parameters, model_from_all_outputs, AllOutputs, Dimension, Drawing, ModeShape,
    OutputInfo, ParameterInfo,
};

/// Parameters of the 3-PRR mechanism, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prr3<D> {
    /// Base radius ra (m).
    pub base_radius: D,
    /// Platform radius rb (m).
    pub platform_radius: D,
    /// Passive link length l (m).
    pub link_length: D,
    /// Position angle a_1 of A_1 on the base (rad).
    pub alpha1: D,
    /// Position angle b_1 of C_1 on the platform (rad).
    pub beta1: D,
    /// Rest angle theta_1^0 of link 1 (rad).
    pub theta1: D,
    /// Platform mass mp (kg).
    pub platform_mass: D,
    /// Passive link mass mg (kg).
    pub link_mass: D,
    /// Rotational stiffness k of each flexure hinge (N m/rad).
    pub hinge_stiffness: D,
    /// Stiffness k1 of each drive (N/m).
    pub drive_stiffness: D,
}

impl Prr3<f64> {
    /// The example of paper 002, Sec. 2 and 4.3.
    pub fn paper002() -> Self {
        use std::f64::consts::PI;
        Prr3 {
            base_radius: 57.96e-3,
            platform_radius: 30e-3,
            link_length: 20e-3,
            alpha1: -PI / 12.0,
            beta1: -PI / 6.0,
            theta1: PI,
            platform_mass: 0.060,
            link_mass: 0.004,
            hinge_stiffness: 34.53,
            drive_stiffness: 2.02e6,
        }
    }
}

/// The Jacobians `J` (sliders) and `J_theta` (link angles) at the rest configuration, rows
/// per limb, columns (x, y, gamma).
pub fn jacobians<D: Scalar>(p: &Prr3<D>) -> ([[D; 3]; 3], [[D; 3]; 3]) {
    let zero = D::from(0.0);
    let mut j = [[zero; 3]; 3];
    let mut jt = [[zero; 3]; 3];
    for i in 0..3 {
        let turn = 2.0 * std::f64::consts::PI / 3.0 * i as f64;
        let (st, ct) = (p.theta1 + turn).sin_cos();
        let (sb, cb) = (p.beta1 + turn).sin_cos();
        let (cx, cy) = (p.platform_radius * cb, p.platform_radius * sb);
        // R'(0) c = (-c_y, c_x); the slider moves along the rest direction of its link, so
        // e . w = 1 and e . w_perp = 0 at rest
        let rc_w = -cy * ct + cx * st;
        let rc_wp = cy * st + cx * ct;
        j[i] = [ct, st, rc_w];
        jt[i] = [
            -st / p.link_length,
            ct / p.link_length,
            rc_wp / p.link_length,
        ];
    }
    (j, jt)
}

/// The mass and stiffness matrices of Eq. 11.
pub fn mass_and_stiffness<D: Scalar>(p: &Prr3<D>) -> ([[D; 3]; 3], [[D; 3]; 3]) {
    let (j, jt) = jacobians(p);
    let zero = D::from(0.0);
    let (ip, ig) = p.inertias();
    let mut m = [[zero; 3]; 3];
    let mut k = [[zero; 3]; 3];
    m[0][0] = p.platform_mass;
    m[1][1] = p.platform_mass;
    m[2][2] = ip;
    for r in 0..3 {
        for c in 0..3 {
            let mut jj = zero;
            let mut tt = zero;
            let mut cc = zero;
            for i in 0..3 {
                jj = jj + j[i][r] * j[i][c];
                tt = tt + jt[i][r] * jt[i][c];
                // Jc = J_theta + N2: ones in the gamma column
                let jc = |col: usize| {
                    if col == 2 {
                        jt[i][col] + 1.0
                    } else {
                        jt[i][col]
                    }
                };
                cc = cc + jc(r) * jc(c);
            }
            m[r][c] = m[r][c] + p.link_mass * jj + ig * tt;
            k[r][c] = k[r][c] + p.hinge_stiffness * (tt + cc) + p.drive_stiffness * jj;
        }
    }
    (m, k)
}

/// Natural frequencies (Hz, ascending) and mode shapes (columns, M-normalised, in
/// (x, y, gamma)) of Eq. 12, from the symmetric generalized eigenproblem `K v = w^2 M v`
/// reduced by the Cholesky factor of `M`. `None` if `M` is not positive definite.
pub fn modes(m: &[[f64; 3]; 3], k: &[[f64; 3]; 3]) -> Option<([f64; 3], Matrix3<f64>)> {
    let m = Matrix3::from_fn(|r, c| m[r][c]);
    let k = Matrix3::from_fn(|r, c| k[r][c]);
    let l = m.cholesky()?.l();
    let li = l.try_inverse()?;
    let a = li * k * li.transpose();
    let a = (a + a.transpose()) * 0.5;
    let eig = a.symmetric_eigen();
    let mut order = [0usize, 1, 2];
    order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
    let mut freqs = [0.0; 3];
    let mut shapes = Matrix3::zeros();
    for (slot, &i) in order.iter().enumerate() {
        let w2 = eig.eigenvalues[i];
        if w2 < 0.0 {
            return None;
        }
        freqs[slot] = w2.sqrt() / (2.0 * std::f64::consts::PI);
        let v: Vector3<f64> = li.transpose() * eig.eigenvectors.column(i);
        shapes.set_column(slot, &v);
    }
    Some((freqs, shapes))
}

/// The natural frequencies (Hz) with their derivatives: for an eigenpair with `v^T M v = 1`,
/// `d(w^2) = v^T (dK - w^2 dM) v`, so that the gradient needs no more than the dual
/// matrices. Exact for simple eigenvalues; for the pair that the three-fold symmetry makes
/// equal it is the derivative along perturbations that keep the symmetry (every parameter
/// of [`Prr3`] does).
pub fn frequencies<D: Scalar>(p: &Prr3<D>) -> Option<[D; 3]> {
    let (m, k) = mass_and_stiffness(p);
    let re = |a: &[[D; 3]; 3]| a.map(|row| row.map(|v| v.re()));
    let (freqs, shapes) = modes(&re(&m), &re(&k))?;
    let mut out = [D::from(0.0); 3];
    for (slot, f) in freqs.iter().enumerate() {
        let w2 = (2.0 * std::f64::consts::PI * f).powi(2);
        let v = shapes.column(slot);
        // the real part of v^T (K - w2 M) v is 0; its dual part is d(w2)
        let mut dw2 = D::from(0.0);
        for r in 0..3 {
            for c in 0..3 {
                dw2 = dw2 + (k[r][c] - m[r][c] * w2) * (v[r] * v[c]);
            }
        }
        let w2 = dw2 + w2;
        out[slot] = w2.sqrt() * (1.0 / (2.0 * std::f64::consts::PI));
    }
    Some(out)
}

/// The design parameters of the 3-PRR model, in model order.
pub static PARAMETERS: [ParameterInfo; 10] = [
    ParameterInfo::new("ra", Dimension::Length, "base radius"),
    ParameterInfo::new("rb", Dimension::Length, "platform radius"),
    ParameterInfo::new("l", Dimension::Length, "passive link length"),
    ParameterInfo::new(
        "alpha1",
        Dimension::Angle,
        "position angle of A1 on the base",
    ),
    ParameterInfo::new(
        "beta1",
        Dimension::Angle,
        "position angle of C1 on the platform",
    ),
    ParameterInfo::new("theta1", Dimension::Angle, "rest angle of link 1"),
    ParameterInfo::new("mp", Dimension::Mass, "platform mass"),
    ParameterInfo::new("mg", Dimension::Mass, "passive link mass"),
    ParameterInfo::new(
        "k",
        Dimension::RotationalStiffness,
        "rotational stiffness of each flexure hinge",
    ),
    ParameterInfo::new("k1", Dimension::Stiffness, "stiffness of each drive"),
];

/// The outputs of the 3-PRR model.
pub static OUTPUTS: [OutputInfo; 5] = [
    OutputInfo::new(
        "f1",
        Dimension::Frequency,
        "first natural frequency (Eq. 12)",
    ),
    OutputInfo::new(
        "f2",
        Dimension::Frequency,
        "second natural frequency (Eq. 12)",
    ),
    OutputInfo::new(
        "f3",
        Dimension::Frequency,
        "third natural frequency (Eq. 12)",
    ),
    OutputInfo::new(
        "mass_ratio",
        Dimension::Ratio,
        "platform mass over link mass, mp / mg (the abscissa of Fig. 4a)",
    ),
    OutputInfo::new(
        "inertia_ratio",
        Dimension::Ratio,
        "platform inertia over link inertia, Ip / Ig = (mp rb^2 / 4) / (mg l^2 / 3) (Fig. 4b)",
    ),
];

/// Every output of the 3-PRR, in the order of [`OUTPUTS`]; `None` where the eigen-solve
/// fails (a mass matrix that is not positive definite).
fn all_outputs<D: Scalar>(p: &Prr3<D>) -> Option<[D; 5]> {
    let [f1, f2, f3] = frequencies(p)?;
    let (ip, ig) = p.inertias();
    Some([f1, f2, f3, p.platform_mass / p.link_mass, ip / ig])
}

impl<D: Scalar> Prr3<D> {
    /// The platform's inertia about its centre `Ip = mp rb^2 / 4` and a link's about its
    /// hinge `Ig = mg l^2 / 3` (kg m^2).
    pub fn inertias(&self) -> (D, D) {
        (
            self.platform_mass * self.platform_radius * self.platform_radius * 0.25,
            self.link_mass * self.link_length * self.link_length * (1.0 / 3.0),
        )
    }

    /// From the parameters in the order of [`PARAMETERS`].
    pub fn from_slice(x: &[D]) -> Self {
        Prr3 {
            base_radius: x[0],
            platform_radius: x[1],
            link_length: x[2],
            alpha1: x[3],
            beta1: x[4],
            theta1: x[5],
            platform_mass: x[6],
            link_mass: x[7],
            hinge_stiffness: x[8],
            drive_stiffness: x[9],
        }
    }
}

/// The 3-PRR model as problem files use it: every parameter is a design variable.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Prr3Model;

model_from_all_outputs!(
    Prr3Model,
    "prr3",
    PARAMETERS,
    OUTPUTS,
    domain_error,
    drawing
);

/// How a problem file selects the 3-PRR: it takes no section, every parameter is a variable.
pub const ENTRY: ModelEntry = ModelEntry {
    name: "prr3",
    sections: &[],
    schema: super::entry::no_sections,
    template: include_str!("templates/prr3.toml"),
    hinge_layout: None,
    optional_outputs: None,
    build: |_| Ok(super::Mechanism::depicted(Prr3Model)),
};

/// The three natural modes of the design `x` (SI), in the platform coordinates.
fn drawing(x: &[f64]) -> Drawing {
    let p = Prr3::from_slice(x);
    let (m, k) = mass_and_stiffness(&p);
    Drawing {
        nodes_mm: None,
        mode_shapes: modes(&m, &k).map(|(f, v)| {
            (0..3)
                .map(|i| ModeShape {
                    frequency: f[i],
                    x: v[(0, i)],
                    y: v[(1, i)],
                    z: None,
                    gamma: Some(v[(2, i)]),
                })
                .collect()
        }),
    }
}

/// Why `x` lies outside the model's domain, if it does.
fn domain_error(x: &[f64]) -> Option<String> {
    check_parameters("3-PRR", &PARAMETERS, x, &[0, 1, 2, 6, 7, 8, 9], &[])
}

impl AllOutputs<10, 5> for Prr3Model {
    fn all<D: Scalar>(&self, x: &[D]) -> Option<[D; 5]> {
        all_outputs(&Prr3::from_slice(x))
    }
}
