//! Dynamics of the general bridge of paper 004 along its output direction: an equivalent
//! mass by Lagrange's equation, as paper 001 (Sec. 2.2) does for its bridge, joined to the
//! stiffness of the general quarter model.
//!
//! # Mounting and coordinate
//!
//! The bridge stands on one output face (bolted to the base) and drives a payload with the
//! other, the actuator sitting between the two input links: the usual piezo stage. The
//! generalized coordinate is the face-to-face displacement `q` (paper 001's `q = 2 dy`).
//!
//! # Stiffness
//!
//! A force `F` on the moving face loads each quarter with `FY = F/2` and moves the face by
//! two quarters' `Yout`, so the face-to-face stiffness is the quarter's `FY / Yout`. The
//! actuator of stiffness `k_pzt` holds the input links: each quarter feels
//! `FX = k_pzt Xin`. Eliminating `Xin` from Eq. 8 of paper 004 gives
//!
//! ```text
//! 1 / K_e = -a22 - a21^2 k_pzt / (1 + a11 k_pzt)
//! ```
//!
//! which is Eq. 11's `k_out = -1/a22` for a free input (`k_pzt = 0`) and
//! `1/(-a22 - a21^2/a11)` for a rigid actuator (no stiffness given, as Eq. 13 assumes).
//! Here the compliances are recomputed from a serial chain (hinge b, rigid link c, hinge d,
//! plane statics only), because the mass needs the motion of nodes 3 and 4 as well; the
//! tests check the chain against the closed-form `a11`, `a21`, `a22`.
//!
//! # Mass
//!
//! Rayleigh's method with the static deflection shape, as paper 001's Lagrange model does
//! with its kinematic relations (its Eq. 3-7): every body's velocity is taken from the
//! quasi-static motion of the nodes per unit `q`. A rigid slender link moving with end
//! velocities `v1`, `v2` has kinetic energy `m/6 (v1^2 + v1.v2 + v2^2)` exactly; the middle
//! link adds `m h^2/12 omega^2` for its in-plane thickness `h`; the hinges are given the same
//! linear velocity field (exact at their ends, an approximation inside; they are light).
//! The input and output links translate as wholes; the payload moves with `q`.
//!
//! In the frame of the bridge's centre the deflection is symmetric, and the bottom face is
//! brought to rest by adding the translation `Yout` of the whole bridge; the symmetric
//! motion carries no momentum along `y`, so the two energies add:
//!
//! ```text
//! T = 1/2 (mu_sym + M_all) Yout'^2 + 1/2 m_payload q'^2,    q = 2 Yout
//! M_e = (mu_sym + M_all) / 4 + m_payload
//! ```
//!
//! with `mu_sym` the symmetric motion's mass per unit `Yout'^2` (four quarters, two input
//! links, two output links) and `M_all` the bridge's whole mass. Then
//! `f_n = sqrt(K_e / M_e) / (2 pi)` (paper 001, Eq. 12) and, for a damping ratio `zeta`
//! (`C = 2 zeta sqrt(M_e K_e)`, Eq. 11), the settling time into a +-2 % band is
//! `ts = tau(zeta) / omega_n`, where `tau(zeta)` is the settling time of the unit-frequency
//! oscillator, from its exact solution ([`crate::dynamics::exact_settling_time`]; the tests
//! check it against the Runge-Kutta response). The scaling is exact for a linear
//! oscillator, and keeps `ts` a smooth function of the design.

use serde::Serialize;

use super::geometry::{Geometry, Trig};
use crate::dynamics::{exact_settling_time, Oscillator};
use crate::model::hinge::Compliance;
use crate::model::scalar::Scalar;

/// Masses, damping and mounting of a bridge for its dynamic outputs (SI units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DynamicsSettings {
    /// Mass carried by the moving output face (kg).
    pub payload_mass: f64,
    /// Mass of each of the two input links (kg).
    pub input_link_mass: f64,
    /// Mass of each of the two output links (kg).
    pub output_link_mass: f64,
    /// In-plane thickness of the four middle links c (m); their mass is
    /// `density * l3 * thickness * width`.
    pub link_thickness: f64,
    /// Damping ratio zeta of the output mode.
    pub damping_ratio: f64,
    /// The stack's own mass (kg; `[actuator] mass`, 0 where not given), a rod between the
    /// input links ([`DynamicsSettings::with_stack_mass`]).
    pub stack_mass: f64,
    /// `omega_n * ts` of an oscillator with this damping ratio.
    settling_scale: f64,
}

/// The settling band of paper 001 (Sec. 4.2): +-2 %.
pub const SETTLING_BAND: f64 = 0.02;

impl DynamicsSettings {
    pub fn new(
        payload_mass: f64,
        input_link_mass: f64,
        output_link_mass: f64,
        link_thickness: f64,
        damping_ratio: f64,
    ) -> Self {
        DynamicsSettings {
            payload_mass,
            input_link_mass,
            output_link_mass,
            link_thickness,
            damping_ratio,
            stack_mass: 0.0,
            settling_scale: settling_scale(damping_ratio),
        }
    }

    /// With the stack's own mass `m`: a uniform rod whose ends move with the input links.
    /// In the symmetric motion its ends move apart by `+-Xin` and its middle stays, so it
    /// adds `m/3 Xin^2` to `mu_sym` (twice its kinetic energy per unit `Yout'^2`); it
    /// translates with the whole bridge, adding `m` to `M_all`
    /// ([`crate::part::stack_mass_share`]: `m/6` on each input face along the stack).
    pub fn with_stack_mass(self, m: f64) -> Self {
        DynamicsSettings {
            stack_mass: m,
            ..self
        }
    }

    /// `omega_n * ts`: the settling time of the oscillator of unit natural frequency.
    pub fn settling_scale(&self) -> f64 {
        self.settling_scale
    }
}

/// The settling time into [`SETTLING_BAND`] of the oscillator of unit angular frequency
/// and damping ratio `zeta`.
pub fn settling_scale(zeta: f64) -> f64 {
    let unit = Oscillator::from_frequency(0.5 / std::f64::consts::PI, zeta);
    exact_settling_time(&unit, SETTLING_BAND)
}

/// The deflection of one quarter per unit output displacement `Yout`, in the quarter's
/// frame (origin at node 2 of the undeformed quarter), and the stiffness it comes from.
#[derive(Debug, Clone, Copy)]
pub struct QuarterMode<D> {
    /// Displacements of nodes 2, 3, 4 and 5 (node 2 moves along `x` only, node 5 along `y`
    /// only, by 1).
    pub nodes: [[D; 2]; 4],
    /// Rotation of the middle link c.
    pub rotation: D,
    /// Face-to-face stiffness `K_e` (N/m).
    pub stiffness: D,
    /// The chain's compliance at node 5 relative to node 2, global axes, `[[xx, xy], [yx, yy]]`.
    pub compliance: [[D; 2]; 2],
}

/// One quarter's chain under a force `f` at node 5, with the moment there that keeps the
/// output link from turning: the displacements of nodes 3, 4, 5 relative to node 2, and the
/// rotation of link c.
fn chain<D: Scalar>(
    r: &[[D; 2]; 4],
    t: &Trig<D>,
    b: &Compliance<D>,
    d: &Compliance<D>,
    f: [D; 2],
) -> ([[D; 2]; 3], D) {
    let ([s2, _, s4], [c2, _, c4]) = (t.s, t.c);
    let diff = |p: [D; 2], q: [D; 2]| [p[0] - q[0], p[1] - q[1]];
    let (d53, d43, d54) = (diff(r[3], r[1]), diff(r[2], r[1]), diff(r[3], r[2]));
    // hinge-local axial and transverse components
    let (nb, vb) = (f[0] * c2 + f[1] * s2, f[1] * c2 - f[0] * s2);
    let (nd, vd) = (f[0] * c4 + f[1] * s4, f[1] * c4 - f[0] * s4);
    let lever = d53[0] * f[1] - d53[1] * f[0];
    // zero rotation at node 5: c23b Vb + c33b (m5 + lever) + c23d Vd + c33d m5 = 0
    let m5 = -(b.c23 * vb + b.c33 * lever + d.c23 * vd) / (b.c33 + d.c33);
    let m3 = m5 + lever;
    let theta = b.c23 * vb + b.c33 * m3;
    let rotate = |ux: D, uy: D, s: D, c: D| [ux * c - uy * s, ux * s + uy * c];
    let u3 = rotate(b.c11 * nb, b.c22 * vb + b.c23 * m3, s2, c2);
    let u4 = [u3[0] - theta * d43[1], u3[1] + theta * d43[0]];
    let ud = rotate(d.c11 * nd, d.c22 * vd + d.c23 * m5, s4, c4);
    let u5 = [
        u4[0] - theta * d54[1] + ud[0],
        u4[1] + theta * d54[0] + ud[1],
    ];
    ([u3, u4, u5], theta)
}

impl<D: Scalar> QuarterMode<D> {
    /// The quarter's deflection with the actuator of stiffness `k_pzt` (N/m) between the
    /// input links, `None` for a rigid one.
    pub fn new(
        g: &Geometry<D>,
        t: &Trig<D>,
        b: &Compliance<D>,
        d: &Compliance<D>,
        k_pzt: Option<f64>,
    ) -> Self {
        let r = g.nodes_with(t);
        let (zero, one) = (D::from(0.0), D::from(1.0));
        let (ux, tx) = chain(&r, t, b, d, [one, zero]);
        let (uy, ty) = chain(&r, t, b, d, [zero, one]);
        let compliance = [[ux[2][0], uy[2][0]], [ux[2][1], uy[2][1]]];
        let [[cxx, cxy], [cyx, cyy]] = compliance;
        // FX = k_pzt Xin and Xin = -u5x: -Xin = cxx FX + cxy FY, per unit FY
        let fx = match k_pzt {
            Some(k) => -cxy * k / (cxx * k + 1.0),
            None => -cxy / cxx,
        };
        let yout = cyx * fx + cyy;
        let per_y = yout.recip();
        let input = -(cxx * fx + cxy) * per_y;
        let mut nodes = [[zero, zero]; 4];
        nodes[0] = [input, zero];
        for i in 0..3 {
            for j in 0..2 {
                nodes[i + 1][j] = nodes[0][j] + (ux[i][j] * fx + uy[i][j]) * per_y;
            }
        }
        QuarterMode {
            nodes,
            rotation: (tx * fx + ty) * per_y,
            stiffness: per_y,
            compliance,
        }
    }
}

/// Twice the kinetic energy per unit velocity squared of a slender rigid link of mass `m`
/// whose ends move with `v1` and `v2`: `m/3 (v1^2 + v1.v2 + v2^2)`.
fn link_mass<D: Scalar>(m: D, v1: [D; 2], v2: [D; 2]) -> D {
    let dot = |a: [D; 2], b: [D; 2]| a[0] * b[0] + a[1] * b[1];
    m * (dot(v1, v1) + dot(v1, v2) + dot(v2, v2)) / 3.0
}

/// The masses of one quarter's three bodies: hinge b, middle link c, hinge d (kg).
pub fn quarter_masses<D: Scalar>(
    g: &Geometry<D>,
    width: f64,
    density: f64,
    link_thickness: f64,
) -> [D; 3] {
    let rho_w = density * width;
    [
        g.b.area() * rho_w,
        g.l3 * (link_thickness * rho_w),
        g.d.area() * rho_w,
    ]
}

/// The equivalent mass `M_e` on the face-to-face coordinate (kg), see the module docs.
pub fn equivalent_mass<D: Scalar>(
    mode: &QuarterMode<D>,
    masses: &[D; 3],
    s: &DynamicsSettings,
) -> D {
    let n = &mode.nodes;
    let [mb, mc, md] = *masses;
    let quarter = link_mass(mb, n[0], n[1])
        + link_mass(mc, n[1], n[2])
        + mc * (s.link_thickness * s.link_thickness / 12.0) * mode.rotation * mode.rotation
        + link_mass(md, n[2], n[3]);
    let input = n[0][0];
    let symmetric = quarter * 4.0
        + input * input * (2.0 * s.input_link_mass + s.stack_mass / 3.0)
        + 2.0 * s.output_link_mass;
    let whole =
        (mb + mc + md) * 4.0 + 2.0 * (s.input_link_mass + s.output_link_mass) + s.stack_mass;
    (symmetric + whole) * 0.25 + s.payload_mass
}

/// Natural frequency `f_n = sqrt(K_e / M_e) / (2 pi)` (Hz).
pub fn natural_frequency<D: Scalar>(stiffness: D, mass: D) -> D {
    (stiffness / mass).sqrt() * (0.5 / std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settling_scale_lies_near_the_envelope_estimate() {
        // the +-2 % envelope exp(-zeta w t) / sqrt(1 - zeta^2) = 0.02 bounds the true
        // settling time from above; for light damping the response reaches the envelope
        // within half a period of it
        for zeta in [0.005, 0.02, 0.1] {
            let tau = settling_scale(zeta);
            let envelope = -(SETTLING_BAND * (1.0 - zeta * zeta).sqrt()).ln() / zeta;
            assert!(tau <= envelope + 1e-9, "zeta {zeta}: {tau} > {envelope}");
            assert!(
                tau >= envelope - std::f64::consts::PI,
                "zeta {zeta}: {tau} << {envelope}"
            );
        }
    }
}
