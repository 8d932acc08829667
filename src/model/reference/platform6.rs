//! The 6-DOF compliant platform of paper 001 (Sec. 2.3): a bottom platform with two
//! bridges per horizontal axis guided by double four-bar mechanisms, four bridges lifting
//! the top platform, and two bridges turning it. Each axis is an uncoupled oscillator
//! (Eq. 30-32): diagonal mass, damping and stiffness built from the bridge's `Me` and `Ke`.
//!
//! ```text
//! Eq. 31  Mx = My = MM + MT + 4 MB + 8 m4 + 2 Me + 8 J4 / (2 l3 + L3)^2
//!         Mz = MT + 4 Me
//!         Jthx = Jthy = 3/2 L4^2 Me + JT
//!         Jthz = 2 R^2 Me + J5
//! Eq. 32  Kx = Ky = 2 Ke + k3 + 2 kg,   k3 = E d t1 / l3,   kg = 12 E I3 / (4 l3^3 + 6 L3 l3^2 + 3 l3 L3^2)
//!         Kz = 4 Ke
//!         Kthx = Kthy = 3/2 Ke L4^2
//!         Kthz = 2 Ke R^2 + 2 ktheta5,   ktheta5 = E d t^3 / (12 l5)
//! Eq. 33  C_i = 2 xi_i sqrt(M_i K_i)
//! ```
//!
//! Each line follows from the energies of Eq. 14-29 by Lagrange's equation; the tests redo
//! that. One difference from the print: Eq. 31 as extracted omits `8 m4` from `Mx`, which
//! the kinetic energy `Tx` (Eq. 14) contains; it is kept here, so `m4 = 0` gives the
//! printed line. The gravity term `MT g dz` of `Vz` shifts the equilibrium of `z` and not its
//! frequency. The paper gives neither the platform's masses and inertias nor `L4`, `t1`
//! and `I3` (its Table 2 lists L1, L2, L3, l3, l5, B and R), so its Table 3 frequencies
//! cannot be recomputed: they are inputs to this model, not outputs of it.

use serde::Serialize;

use crate::dynamics::{step_response, Oscillator, StepResponse};
use crate::model::scalar::Scalar;

/// The six axes of the platform, in the order of Eq. 30.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Axis {
    X,
    Y,
    Z,
    ThetaX,
    ThetaY,
    ThetaZ,
}

impl Axis {
    pub const ALL: [Axis; 6] = [
        Axis::X,
        Axis::Y,
        Axis::Z,
        Axis::ThetaX,
        Axis::ThetaY,
        Axis::ThetaZ,
    ];
}

/// The platform's parameters (SI): the bridge's equivalent mass and stiffness, the
/// platform's masses and inertias, and the guide and hinge dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Platform<D> {
    /// Equivalent mass `Me` and stiffness `Ke` of one bridge (kg, N/m).
    pub bridge_mass: D,
    pub bridge_stiffness: D,
    /// Masses of the middle platform `MM`, the top platform `MT`, a beam of the bottom
    /// platform `MB`, and a connecting beam of the guide `m4` (kg).
    pub middle_mass: f64,
    pub top_mass: f64,
    pub beam_mass: f64,
    pub guide_beam_mass: f64,
    /// Moment of inertia `J4` of a guide beam, `JT` of the top platform about x (and y), and
    /// `J5` of the turning part about z (kg m^2).
    pub guide_beam_inertia: f64,
    pub top_inertia: f64,
    pub turning_inertia: f64,
    /// Guide hinge length `l3`, guide beam length `L3`, top-platform lever `L4` and the
    /// radius `R` of the turning bridges (m).
    pub guide_hinge_length: f64,
    pub guide_beam_length: f64,
    pub lever: f64,
    pub radius: f64,
    /// Axial stiffness `k3` of a guide hinge, bending stiffness `kg` of a double four-bar
    /// guide (N/m) and bending stiffness `ktheta5` of a top-platform hinge (N m/rad).
    pub guide_hinge_stiffness: f64,
    pub guide_bending_stiffness: f64,
    pub top_hinge_stiffness: f64,
}

/// `kg = 12 E I3 / (4 l3^3 + 6 L3 l3^2 + 3 l3 L3^2)` (Eq. 19) of a double four-bar guide.
pub fn guide_bending_stiffness(youngs_modulus: f64, area_moment: f64, l3: f64, big_l3: f64) -> f64 {
    12.0 * youngs_modulus * area_moment
        / (4.0 * l3.powi(3) + 6.0 * big_l3 * l3 * l3 + 3.0 * l3 * big_l3 * big_l3)
}

impl<D: Scalar> Platform<D> {
    /// Eq. 31: the generalized mass (kg) or inertia (kg m^2) of an axis.
    pub fn mass(&self, axis: Axis) -> D {
        let me = self.bridge_mass;
        match axis {
            Axis::X | Axis::Y => {
                let guide = 2.0 * self.guide_hinge_length + self.guide_beam_length;
                me * 2.0
                    + (self.middle_mass
                        + self.top_mass
                        + 4.0 * self.beam_mass
                        + 8.0 * self.guide_beam_mass
                        + 8.0 * self.guide_beam_inertia / (guide * guide))
            }
            Axis::Z => me * 4.0 + self.top_mass,
            Axis::ThetaX | Axis::ThetaY => me * (1.5 * self.lever * self.lever) + self.top_inertia,
            Axis::ThetaZ => me * (2.0 * self.radius * self.radius) + self.turning_inertia,
        }
    }

    /// Eq. 32: the stiffness (N/m) or rotational stiffness (N m/rad) of an axis.
    pub fn stiffness(&self, axis: Axis) -> D {
        let ke = self.bridge_stiffness;
        match axis {
            Axis::X | Axis::Y => {
                ke * 2.0 + (self.guide_hinge_stiffness + 2.0 * self.guide_bending_stiffness)
            }
            Axis::Z => ke * 4.0,
            Axis::ThetaX | Axis::ThetaY => ke * (1.5 * self.lever * self.lever),
            Axis::ThetaZ => ke * (2.0 * self.radius * self.radius) + 2.0 * self.top_hinge_stiffness,
        }
    }

    /// The natural frequency of an axis (Hz).
    pub fn frequency(&self, axis: Axis) -> D {
        (self.stiffness(axis) / self.mass(axis)).sqrt() * (0.5 / std::f64::consts::PI)
    }

    /// Eq. 33: the damping coefficient of an axis for its modal damping ratio.
    pub fn damping(&self, axis: Axis, zeta: f64) -> D {
        (self.mass(axis) * self.stiffness(axis)).sqrt() * (2.0 * zeta)
    }
}

impl Platform<f64> {
    /// The axis as an oscillator with damping ratio `zeta`.
    pub fn oscillator(&self, axis: Axis, zeta: f64) -> Oscillator {
        Oscillator {
            mass: self.mass(axis),
            damping: self.damping(axis, zeta),
            stiffness: self.stiffness(axis),
        }
    }

    /// The response of an axis to a step load (N, or N m for a rotation) with damping
    /// ratio `zeta`, integrated with Runge-Kutta (Sec. 4.2): Sp, ts (+-2 %), Mp.
    pub fn step_response(&self, axis: Axis, zeta: f64, load: f64) -> StepResponse {
        step_response(&self.oscillator(axis, zeta), load, 0.02, 1e-6)
    }
}
