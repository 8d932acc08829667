//! The bridge-type amplifier of paper 001 (Lin, Zheng, Jiang, Sec. 2.2): stiffnesses,
//! amplification ratio, equivalent mass and stiffness by Lagrange's equation, damping and
//! natural frequency.
//!
//! Each quarter is a flexure hinge (length `l`, thickness `t`), a connecting beam (length
//! `L`, height `H`) and a second hinge; `theta` is the angle of the hinges, `d` the width of
//! the mechanism. The text lost fraction bars and some signs and symbols; every equation is
//! rebuilt below by dimensions and limits.
//!
//! ```text
//! Eq. 4   k1 = E d t / l            ktheta1 = E d t^3 / (12 l)        (hinge)
//! Eq. 9   k2 = E d H / L            ktheta2 = E d H^3 / (12 L)        (beam)
//! Eq. 8   m = 3 (L+l)^2 cos^2 th - 6 (L+l) L cos th + 4 L^2
//!         n = 3 (L+l)^2 cos^2 th - 6 (L+l) l cos th + 4 l^2
//! Eq. 6   A = tan th [k1 k2 (2 m kth2 + n kth1) - 12 kth1 kth2 (2 k2 + k1)]
//!             / [12 kth1 kth2 (2 k2 + k1) + k1 k2 tan^2 th (2 m kth2 + n kth1)]
//! Eq. 7   c = sin th cos th (m / (6 kth1) + n / (12 kth2) - 2 / k1 - 1 / k2)
//! Eq. 11  Me = m1 / (2 A^2) + m2 (L^2 + H^2) / (12 (L+l)^2) + m3
//!         Ke = 2 kth1 kth2 / ((L+l)^2 (kth1 + kth2))
//!         C  = 2 xi sqrt(Me Ke),   Q = F / (2 A)
//! Eq. 12  fn = sqrt(Ke / Me) / (2 pi)
//! ```
//!
//! How each was rebuilt:
//! - Eq. 6 reads as one fraction whose two bracketed terms are the numerator and the
//!   denominator. Dividing both by `12 k1 k2 kth1 kth2` gives
//!   `A = sin cos (S_b - S_a) / (S_a cos^2 + S_b sin^2)` with the bending compliance
//!   `S_b = m/(6 kth1) + n/(12 kth2)` and the axial one `S_a = 2/k1 + 1/k2`: as the
//!   hinges and beams become axially rigid (`S_a / S_b -> 0`), `A -> cot th`, the ideal
//!   lever. The minus sign in the numerator is printed, and it makes `A` vanish at
//!   `th = 0`, as a bridge's amplification does.
//! - Eq. 7's last term is printed `sin cos / ktheta2`, which is not a compliance (1/(N m)
//!   beside m/N). With `1/k2` it is, and `c` is then exactly Eq. 6's numerator over
//!   `12 k1 k2 kth1 kth2` times `cos^2`, the structure Eq. 6 and 7 share in the source.
//! - Eq. 11's `Ke` is printed `2 (L+l)^2 Kth1 Kth2 / (Kth1 + Kth1)`, a rotational stiffness
//!   times a squared length (N m^3). A translational stiffness needs `(L+l)^2` in the
//!   denominator, and `Kth1 + Kth1` is read as `kth1 + kth2`: the hinge and the beam bending
//!   in series, over the lever `L + l`.
//!
//! Findings (kept, not adjusted): the printed `Me` and `Ke` are not what Lagrange's equation
//! gives from the paper's own energies (Eq. 2-3) with its kinematics as printed (Eq. 5,
//! `dalpha = q / (4 (L+l))`). The beams' rotational term of Eq. 2 gives
//! `J / (4 (L+l)^2) = m2 (L^2 + H^2) / (48 (L+l)^2)` for `J = m2 (L^2 + H^2) / 12`, and the
//! hinges' bending term of Eq. 3 gives `ktheta1 / (2 (L+l)^2)`: the printed `Me` has four
//! times the first, and the printed `Ke` with a rigid beam (`ktheta2 -> inf`) is four times
//! the second. Both are what `dalpha = q / (2 (L+l))` gives, so the paper computed with twice
//! Eq. 5's hinge rotation. The printed `Ke` also leaves out Eq. 3's axial term. flexopt
//! implements the printed forms; [`BridgeLagrange::energy_mass`] and
//! [`BridgeLagrange::energy_stiffness`] are the forms of Eq. 2-3 with Eq. 5 as printed. Paper
//! 001's `fn = 266.95 Hz` (FEA 259.28 Hz) cannot be checked with either: the masses `m1`,
//! `m2`, `m3`, the beam height `H` and the angle `theta` are not in its text.

use crate::model::scalar::Scalar;

/// A bridge-type amplifier as paper 001 describes it (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BridgeLagrange<D> {
    /// Hinge length l (m).
    pub hinge_length: D,
    /// Hinge thickness t (m).
    pub hinge_thickness: D,
    /// Connecting beam length L (m).
    pub beam_length: D,
    /// Connecting beam height H (m).
    pub beam_height: D,
    /// Hinge angle theta (rad).
    pub angle: D,
    /// Width d of the mechanism (m).
    pub width: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Mass of each of the two side (input) beams m1 (kg).
    pub side_mass: f64,
    /// Mass m2 of the connecting beams, as Eq. 11 uses it (kg).
    pub beam_mass: f64,
    /// Mass m3 of the output beam and the fixed beam (kg).
    pub output_mass: f64,
}

/// The hinge and beam stiffnesses `(k1, ktheta1, k2, ktheta2)` of Eq. 4 and 9.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stiffnesses<D> {
    pub k1: D,
    pub ktheta1: D,
    pub k2: D,
    pub ktheta2: D,
}

impl<D: Scalar> BridgeLagrange<D> {
    /// Eq. 4 and 9.
    pub fn stiffnesses(&self) -> Stiffnesses<D> {
        let ed = self.youngs_modulus * self.width;
        let (t, h) = (self.hinge_thickness, self.beam_height);
        Stiffnesses {
            k1: t / self.hinge_length * ed,
            ktheta1: t * t * t / self.hinge_length * (ed / 12.0),
            k2: h / self.beam_length * ed,
            ktheta2: h * h * h / self.beam_length * (ed / 12.0),
        }
    }

    /// Eq. 8: `(m, n)`.
    pub fn polynomials(&self) -> (D, D) {
        let (l, big_l) = (self.hinge_length, self.beam_length);
        let c = self.angle.cos();
        let sum = big_l + l;
        let common = sum * sum * c * c * 3.0;
        (
            common - sum * big_l * c * 6.0 + big_l * big_l * 4.0,
            common - sum * l * c * 6.0 + l * l * 4.0,
        )
    }

    /// `(S_b, S_a)`: the bending and axial compliance sums of Eq. 6-7 (see the module docs).
    fn compliance_sums(&self) -> (D, D) {
        let k = self.stiffnesses();
        let (m, n) = self.polynomials();
        (
            m / (k.ktheta1 * 6.0) + n / (k.ktheta2 * 12.0),
            k.k1.recip() * 2.0 + k.k2.recip(),
        )
    }

    /// Eq. 6, the amplification ratio `A`.
    pub fn amplification(&self) -> D {
        let (sb, sa) = self.compliance_sums();
        let (s, c) = self.angle.sin_cos();
        s * c * (sb - sa) / (sa * c * c + sb * s * s)
    }

    /// Eq. 6 as printed, term by term, for the tests' check of the rebuilt form.
    pub fn amplification_as_printed(&self) -> D {
        let k = self.stiffnesses();
        let (m, n) = self.polynomials();
        let tan = self.angle.sin() / self.angle.cos();
        let bending = m * k.ktheta2 * 2.0 + n * k.ktheta1;
        let axial = (k.k2 * 2.0 + k.k1) * k.ktheta1 * k.ktheta2 * 12.0;
        tan * (k.k1 * k.k2 * bending - axial) / (axial + k.k1 * k.k2 * tan * tan * bending)
    }

    /// Eq. 7, the compliance unit `c` (m/N).
    pub fn compliance(&self) -> D {
        let (sb, sa) = self.compliance_sums();
        let (s, c) = self.angle.sin_cos();
        s * c * (sb - sa)
    }

    /// Eq. 11, the equivalent mass `Me` (kg) as printed.
    pub fn equivalent_mass(&self) -> D {
        self.mass_with_beam_term(12.0)
    }

    /// `m1/(2A^2) + m2 (L^2+H^2)/(divisor (L+l)^2) + m3`: Eq. 11 has `divisor = 12`.
    fn mass_with_beam_term(&self, divisor: f64) -> D {
        let a = self.amplification();
        let (big_l, h) = (self.beam_length, self.beam_height);
        let lever = big_l + self.hinge_length;
        (a * a * 2.0).recip() * self.side_mass
            + (big_l * big_l + h * h) / (lever * lever * divisor) * self.beam_mass
            + D::from(self.output_mass)
    }

    /// Eq. 11, the equivalent stiffness `Ke` (N/m) as rebuilt.
    pub fn equivalent_stiffness(&self) -> D {
        let k = self.stiffnesses();
        let lever = self.beam_length + self.hinge_length;
        k.ktheta1 * k.ktheta2 * 2.0 / (lever * lever * (k.ktheta1 + k.ktheta2))
    }

    /// Eq. 12, the natural frequency (Hz).
    pub fn natural_frequency(&self) -> D {
        (self.equivalent_stiffness() / self.equivalent_mass()).sqrt() * (0.5 / std::f64::consts::PI)
    }

    /// Eq. 11, the damping coefficient `C = 2 xi sqrt(Me Ke)` (N s/m).
    pub fn damping(&self, xi: f64) -> D {
        (self.equivalent_mass() * self.equivalent_stiffness()).sqrt() * (2.0 * xi)
    }

    /// The generalized force of an actuator force `F`: `Q = F / (2 A)` (Eq. 10-11).
    pub fn generalized_force(&self, force: D) -> D {
        force / (self.amplification() * 2.0)
    }

    /// The mass Lagrange's equation gives from Eq. 2 and Eq. 5, with `m2` the mass of one
    /// connecting beam turning about its centre: `m1/(2A^2) + m2 (L^2+H^2)/(48 (L+l)^2) + m3`.
    pub fn energy_mass(&self) -> D {
        self.mass_with_beam_term(48.0)
    }

    /// The bending stiffness Lagrange's equation gives from Eq. 3 with Eq. 5's
    /// `dalpha = q / (4 (L+l))`: `ktheta1 / (2 (L+l)^2)` (the axial term left out, as the
    /// printed `Ke` leaves it).
    pub fn energy_stiffness(&self) -> D {
        let k = self.stiffnesses();
        let lever = self.beam_length + self.hinge_length;
        k.ktheta1 / (lever * lever * 2.0)
    }
}
