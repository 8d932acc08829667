//! The general compliant bridge amplifier (paper 004: Wei et al., Micromachines 2017, 8, 238).
//!
//! # The quarter model
//!
//! By symmetry a quarter of the bridge is analysed: input link `a`, hinge `b` (node 2 to
//! node 3, length `l2`, angle `delta2`, thickness `t2`), rigid middle link `c` (node 3 to
//! node 4, `l3`, `delta3`), hinge `d` (node 4 to node 5, `l4`, `delta4`, `t4`) and output link
//! `e`. The frame has its origin at node 2, `x` pointing from the input link towards the
//! centre of the bridge and `y` along the output direction; angles are positive
//! anticlockwise from `x`. The input link only translates along `x`, the output link only
//! along `y`, and neither rotates.
//!
//! # Rebuilt equations
//!
//! The text of the paper lost its minus signs and fraction bars; the `+` signs survived.
//! Every equation below was rebuilt by putting a minus wherever two terms stand side by
//! side without an operator, and was then checked three ways: by re-deriving it from
//! Eq. 1 and Eq. 3-7, against the paper's own Tables 2 and 3 (see `tests/paper004.rs`),
//! and against the independent matrix formulation of [`super::bridge_matrix`], which
//! shares no formula with this file.
//!
//! Loads in the hinges (FX along the input, FY on the output link):
//!
//! ```text
//! Eq. 3  F3x = FX cos d2 + FY sin d2        F3y = FX sin d2 - FY cos d2
//! Eq. 4  F4x = FX cos d4 + FY sin d4        F4y = FX sin d4 - FY cos d4
//! Eq. 5  c32b F3y + c33b M3 = c32d F4y + c33d M4      (equal slopes at nodes 3 and 4)
//!        FX l3 sin d3 = M3 + M4 + FY l3 cos d3          (moments on the middle link)
//! Eq. 6  M3 = (FX Pb_s - FY Pb_c) / S                  M4 = (FX Pd_s - FY Pd_c) / S
//! ```
//!
//! with `S = c33b + c33d` and, writing `s_i = sin d_i`, `c_i = cos d_i`,
//!
//! ```text
//! Pb_s = c32d s4 - c32b s2 + c33d l3 s3      Pb_c = c32d c4 - c32b c2 + c33d l3 c3
//! Pd_s = c32b s2 - c32d s4 + c33b l3 s3      Pd_c = c32b c2 - c32d c4 + c33b l3 c3
//! C_s  = c32b c33d s2 + c32d c33b s4 + c33b c33d l3 s3
//! C_c  = c32b c33d c2 + c32d c33b c4 + c33b c33d l3 c3
//! ```
//!
//! Displacements (Eq. 7) `Xin = x3 c2 + y3 s2 + x4 c4 + y4 s4 + theta l3 s3` and
//! `Yout = y3 c2 - x3 s2 + y4 c4 - x4 s4 + theta l3 c3` give Eq. 8, `Xin = a11 FX + a12 FY`,
//! `Yout = a21 FX + a22 FY`, with the Appendix A coefficients
//!
//! ```text
//! a11 =  s2 (c22b s2 + c23b Pb_s/S) + s4 (c22d s4 + c23d Pd_s/S) + c11b c2^2 + c11d c4^2 + l3 s3 C_s/S
//! a21 =  c2 (c22b s2 + c23b Pb_s/S) + c4 (c22d s4 + c23d Pd_s/S) - c11b c2 s2 - c11d c4 s4 + l3 c3 C_s/S
//! a12 =  c11b c2 s2 + c11d c4 s4 - s2 (c22b c2 + c23b Pb_c/S) - s4 (c22d c4 + c23d Pd_c/S) - l3 s3 C_c/S
//! a22 = -c11b s2^2 - c11d s4^2 - c2 (c22b c2 + c23b Pb_c/S) - c4 (c22d c4 + c23d Pd_c/S) - l3 c3 C_c/S
//! ```
//!
//! Two misprints of the published appendix are corrected here:
//! - its `a21` ends in `l3 sin d3 C_s/S`; Eq. 7 (arc motion `theta l3 cos d3` in `Yout`) and
//!   the numerator of Eq. 9 both give `l3 cos d3`, and only `cos` reproduces Table 3's
//!   `da = 12.86`;
//! - its `a12` has `c22b sin d2` and `c22d sin d4` inside the brackets; the derivation
//!   (`F3y = -FY cos d2` when `FX = 0`) gives `cos`, and only `cos` makes `a12 = -a21`.
//!
//! Signs: `a11 > 0`, `a22 < 0` and `a12 = -a21` (Maxwell-Betti). `FY` is counted positive
//! in the sense that opposes a positive `Yout`, so the output stiffness is
//! `k_out = -1/a22 > 0` (Eq. 11 reported as a positive number).
//!
//! # Whole bridge and quarter
//!
//! Each input link is held by two quarters, so an actuator force `F` puts `F/2` on each
//! quarter while the actuator's elongation is twice a quarter's `Xin`. The actuator
//! therefore sees `k_in = 1/a11` exactly (Eq. 10), and `a11`, `a21` are at once the quarter
//! compliances and the face-to-face compliances of the whole bridge. The stresses
//! (Eq. 12-17) follow from the quarter loads under `FX = F_X,max / 2`: with the whole
//! actuator force on one quarter the optimum of Table 1 would reach 297 MPa, against the
//! paper's 148 MPa.

use serde::Serialize;

use super::bridge_dynamics::{self, DynamicsSettings, QuarterMode};
use super::hinge::{Compliance, HingeKind, HingeLoads};
use super::material::Material;
use super::scalar::{max, Jet, Scalar};
use super::{Dimension, OutputInfo, ParameterInfo};

/// The design parameters of the general bridge, in model order.
pub const PARAMETERS: [ParameterInfo; 8] = [
    ParameterInfo::new("l2", Dimension::Length, "length of hinge b"),
    ParameterInfo::new("delta2", Dimension::Angle, "angle of hinge b"),
    ParameterInfo::new("t2", Dimension::Length, "thickness of hinge b"),
    ParameterInfo::new("l3", Dimension::Length, "length of the middle link c"),
    ParameterInfo::new("delta3", Dimension::Angle, "angle of the middle link c"),
    ParameterInfo::new("l4", Dimension::Length, "length of hinge d"),
    ParameterInfo::new("delta4", Dimension::Angle, "angle of hinge d"),
    ParameterInfo::new("t4", Dimension::Length, "thickness of hinge d"),
];

/// The outputs of the general bridge model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BridgeOutput {
    Amplification,
    KIn,
    KOut,
    StressMax,
    StressB,
    StressD,
    ForceInMax,
    SpanX,
    SpanY,
    StrokeIn,
    StrokeOut,
    A11,
    A12,
    A21,
    A22,
    StressNode2,
    StressNode3,
    StressNode4,
    StressNode5,
    KOutActuated,
    EquivalentMass,
    NaturalFrequency,
    SettlingTime,
}

impl BridgeOutput {
    /// Every output, in the order of [`OUTPUTS`].
    pub const ALL: [BridgeOutput; 23] = [
        BridgeOutput::Amplification,
        BridgeOutput::KIn,
        BridgeOutput::KOut,
        BridgeOutput::StressMax,
        BridgeOutput::StressB,
        BridgeOutput::StressD,
        BridgeOutput::ForceInMax,
        BridgeOutput::SpanX,
        BridgeOutput::SpanY,
        BridgeOutput::StrokeIn,
        BridgeOutput::StrokeOut,
        BridgeOutput::A11,
        BridgeOutput::A12,
        BridgeOutput::A21,
        BridgeOutput::A22,
        BridgeOutput::StressNode2,
        BridgeOutput::StressNode3,
        BridgeOutput::StressNode4,
        BridgeOutput::StressNode5,
        BridgeOutput::KOutActuated,
        BridgeOutput::EquivalentMass,
        BridgeOutput::NaturalFrequency,
        BridgeOutput::SettlingTime,
    ];

    /// Whether the output needs the masses and damping of [`BridgeSettings::dynamics`].
    pub fn needs_dynamics(self) -> bool {
        matches!(
            self,
            BridgeOutput::EquivalentMass
                | BridgeOutput::NaturalFrequency
                | BridgeOutput::SettlingTime
        )
    }
}

/// Names, dimensions and meanings of the outputs, indexed like [`BridgeOutput::ALL`].
pub const OUTPUTS: [OutputInfo; 23] = [
    OutputInfo::new("amplification", Dimension::Ratio, "displacement amplification da = a21/a11 (Eq. 9)"),
    OutputInfo::new("k_in", Dimension::Stiffness, "input stiffness 1/a11 (Eq. 10)"),
    OutputInfo::new("k_out", Dimension::Stiffness, "output stiffness -1/a22 (Eq. 11)"),
    OutputInfo::new("stress_max", Dimension::Stress, "largest stress in the hinges under the nominal stroke and preload (Eq. 12-17)"),
    OutputInfo::new("stress_b", Dimension::Stress, "largest stress in hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_d", Dimension::Stress, "largest stress in hinge d (Eq. 17)"),
    OutputInfo::new("force_in_max", Dimension::Force, "largest actuator force: nominal stroke times k_in plus preload (Eq. 12, 14)"),
    OutputInfo::new("span_x", Dimension::Length, "extent of the quarter along x: l2 cos d2 + l3 cos d3 + l4 cos d4 (Sec. 3)"),
    OutputInfo::new("span_y", Dimension::Length, "extent of the quarter along y: l2 sin d2 + l3 sin d3 + l4 sin d4 (Sec. 3)"),
    OutputInfo::new("stroke_in", Dimension::Length, "true actuator stroke under the bridge's load (Eq. 13)"),
    OutputInfo::new("stroke_out", Dimension::Length, "change of the distance between the output faces for the true stroke: amplification x stroke_in"),
    OutputInfo::new("a11", Dimension::Compliance, "input compliance (Eq. 8, Appendix A)"),
    OutputInfo::new("a12", Dimension::Compliance, "input displacement per output force (Eq. 8, Appendix A)"),
    OutputInfo::new("a21", Dimension::Compliance, "output displacement per input force (Eq. 8, Appendix A)"),
    OutputInfo::new("a22", Dimension::Compliance, "output compliance, negative by the paper's sign convention (Eq. 8, Appendix A)"),
    OutputInfo::new("stress_node2", Dimension::Stress, "largest stress at node 2, the input-link end of hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_node3", Dimension::Stress, "largest stress at node 3, the middle-link end of hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_node4", Dimension::Stress, "largest stress at node 4, the middle-link end of hinge d (Eq. 17)"),
    OutputInfo::new("stress_node5", Dimension::Stress, "largest stress at node 5, the output-link end of hinge d (Eq. 17)"),
    OutputInfo::new("k_out_actuated", Dimension::Stiffness, "face-to-face output stiffness with the actuator holding the input links (k_out for a free input; see bridge_dynamics)"),
    OutputInfo::new("equivalent_mass", Dimension::Mass, "mass on the moving output face equivalent to the moving bridge and payload (Lagrange/Rayleigh, paper 001 Sec. 2.2)"),
    OutputInfo::new("natural_frequency", Dimension::Frequency, "natural frequency along the output, sqrt(k_out_actuated / equivalent_mass) / 2 pi (paper 001 Eq. 12)"),
    OutputInfo::new("settling_time", Dimension::Time, "settling time into +-2 % after a step, for the damping ratio of [dynamics] (paper 001 Sec. 4.2)"),
];

/// The piezo actuator that drives the bridge (paper 004, Eq. 12-14).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Actuator {
    /// Nominal stroke X_PZT^nl (m).
    pub nominal_stroke: f64,
    /// Preload F_preload (N).
    pub preload: f64,
    /// Stiffness k_pzt (N/m); `None` for an actuator much stiffer than the bridge.
    pub stiffness: Option<f64>,
}

/// Everything about a bridge that is not a design parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BridgeSettings {
    pub hinge: HingeKind,
    /// Width w of the mechanism (m).
    pub width: f64,
    pub material: Material,
    pub actuator: Actuator,
    /// Masses and damping for the dynamic outputs; `None` when the problem gives none.
    pub dynamics: Option<DynamicsSettings>,
}

/// A bridge design: the eight configuration parameters, SI units (m, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry<D> {
    pub l2: D,
    pub delta2: D,
    pub t2: D,
    pub l3: D,
    pub delta3: D,
    pub l4: D,
    pub delta4: D,
    pub t4: D,
}

impl Geometry<f64> {
    /// Why this design lies outside the model's domain, if it does: every value finite,
    /// lengths not negative, thicknesses positive, at least one hinge (`l2 + l4 > 0`, else
    /// `c33b + c33d = 0` and nothing bends), angles strictly between -90 and 90 deg.
    pub fn domain_error(&self) -> Option<String> {
        let all = [
            self.l2,
            self.delta2,
            self.t2,
            self.l3,
            self.delta3,
            self.l4,
            self.delta4,
            self.t4,
        ];
        if let Some((i, v)) = all.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Some(format!("{} = {v} is not finite", PARAMETERS[i].name));
        }
        for (name, l) in [("l2", self.l2), ("l3", self.l3), ("l4", self.l4)] {
            if l < 0.0 {
                return Some(format!("{name} = {l} m is negative"));
            }
        }
        for (name, t) in [("t2", self.t2), ("t4", self.t4)] {
            if t <= 0.0 {
                return Some(format!("{name} = {t} m is not positive"));
            }
        }
        if self.l2 + self.l4 == 0.0 {
            return Some("l2 = l4 = 0: a bridge without hinges does not deform".into());
        }
        let right = std::f64::consts::FRAC_PI_2;
        for (name, a) in [
            ("delta2", self.delta2),
            ("delta3", self.delta3),
            ("delta4", self.delta4),
        ] {
            if a.abs() >= right {
                return Some(format!(
                    "{name} = {} deg is not strictly between -90 and 90 deg",
                    a.to_degrees()
                ));
            }
        }
        None
    }
}

impl<const N: usize> Geometry<Jet<N>> {
    /// The design `x` (order of [`PARAMETERS`]), each parameter an independent variable of
    /// the gradient.
    pub fn seeded(x: &[f64]) -> Self {
        let v = |i: usize| Jet::variable(x[i], i);
        Geometry {
            l2: v(0),
            delta2: v(1),
            t2: v(2),
            l3: v(3),
            delta3: v(4),
            l4: v(5),
            delta4: v(6),
            t4: v(7),
        }
    }
}

impl<D: Scalar> Geometry<D> {
    /// From the parameters in the order of [`PARAMETERS`].
    pub fn from_array(x: [D; 8]) -> Self {
        let [l2, delta2, t2, l3, delta3, l4, delta4, t4] = x;
        Geometry {
            l2,
            delta2,
            t2,
            l3,
            delta3,
            l4,
            delta4,
            t4,
        }
    }

    /// Sines and cosines of the three angles.
    #[inline]
    pub fn trig(&self) -> Trig<D> {
        let (s2, c2) = self.delta2.sin_cos();
        let (s3, c3) = self.delta3.sin_cos();
        let (s4, c4) = self.delta4.sin_cos();
        Trig {
            s: [s2, s3, s4],
            c: [c2, c3, c4],
        }
    }

    /// Extent of the quarter along `x` (Sec. 3 contour limits).
    pub fn span_x(&self) -> D {
        self.span_x_with(&self.trig())
    }

    /// Extent of the quarter along `y` (Sec. 3 contour limits).
    pub fn span_y(&self) -> D {
        self.span_y_with(&self.trig())
    }

    fn span_x_with(&self, t: &Trig<D>) -> D {
        self.l2 * t.c[0] + self.l3 * t.c[1] + self.l4 * t.c[2]
    }

    fn span_y_with(&self, t: &Trig<D>) -> D {
        self.l2 * t.s[0] + self.l3 * t.s[1] + self.l4 * t.s[2]
    }

    /// Node coordinates 2..=5 of the quarter (m), origin at node 2.
    pub fn nodes(&self) -> [[D; 2]; 4] {
        self.nodes_with(&self.trig())
    }

    /// [`Geometry::nodes`] from the angles' sines and cosines.
    pub fn nodes_with(&self, t: &Trig<D>) -> [[D; 2]; 4] {
        let zero = D::from(0.0);
        let mut p = [[zero, zero]; 4];
        for (i, l) in [self.l2, self.l3, self.l4].into_iter().enumerate() {
            p[i + 1] = [p[i][0] + l * t.c[i], p[i][1] + l * t.s[i]];
        }
        p
    }
}

/// `sin` and `cos` of `delta2`, `delta3`, `delta4`.
#[derive(Debug, Clone, Copy)]
pub struct Trig<D> {
    pub s: [D; 3],
    pub c: [D; 3],
}

/// The quarter bridge with its hinge compliances and the shared sub-expressions of
/// Eq. 6-9 worked out once.
#[derive(Debug, Clone, Copy)]
pub struct QuarterBridge<D> {
    pub b: Compliance<D>,
    pub d: Compliance<D>,
    l3: D,
    s: [D; 3],
    c: [D; 3],
    /// `1 / (c33b + c33d)`
    inv_sum33: D,
    pb: [D; 2],
    pd: [D; 2],
    cc: [D; 2],
}

impl<D: Scalar> QuarterBridge<D> {
    pub fn new(g: &Geometry<D>, hinge: HingeKind, width: f64, material: &Material) -> Self {
        Self::with_trig(g, &g.trig(), hinge, width, material)
    }

    fn with_trig(
        g: &Geometry<D>,
        trig: &Trig<D>,
        hinge: HingeKind,
        width: f64,
        material: &Material,
    ) -> Self {
        let b = hinge.compliance(g.l2, g.t2, width, material);
        let d = hinge.compliance(g.l4, g.t4, width, material);
        Self::from_parts(b, d, g.l3, trig)
    }

    /// A quarter from given hinge compliances, whatever the hinge kind.
    pub fn from_compliances(
        b: Compliance<D>,
        d: Compliance<D>,
        delta2: D,
        l3: D,
        delta3: D,
        delta4: D,
    ) -> Self {
        let zero = D::from(0.0);
        let g = Geometry::from_array([zero, delta2, zero, l3, delta3, zero, delta4, zero]);
        Self::from_parts(b, d, l3, &g.trig())
    }

    fn from_parts(b: Compliance<D>, d: Compliance<D>, l3: D, trig: &Trig<D>) -> Self {
        let Trig { s, c } = *trig;
        // index 0: the sine projections (load FX), index 1: the cosine ones (load FY)
        let (l3_b, l3_d, c23d_c33b) = (b.c33 * l3, d.c33 * l3, d.c23 * b.c33);
        let proj = |t: &[D; 3]| {
            let pb = d.c23 * t[2] - b.c23 * t[0] + l3_d * t[1];
            let pd = b.c23 * t[0] - d.c23 * t[2] + l3_b * t[1];
            // C = c32b c33d t2 + c32d c33b t4 + c33b c33d l3 t3, as the paper writes it
            // (factored over c33d, which adds no cancellation): the shorter
            // c33b Pb + c32b t2 S is the same number, but when hinge b dominates
            // (c33b >> c33d) its two parts cancel to eight digits (tests/model_stability.rs)
            let cc = d.c33 * (b.c23 * t[0] + l3_b * t[1]) + c23d_c33b * t[2];
            (pb, pd, cc)
        };
        let (pb_s, pd_s, cc_s) = proj(&s);
        let (pb_c, pd_c, cc_c) = proj(&c);
        QuarterBridge {
            b,
            d,
            l3,
            s,
            c,
            inv_sum33: (b.c33 + d.c33).recip(),
            pb: [pb_s, pb_c],
            pd: [pd_s, pd_c],
            cc: [cc_s, cc_c],
        }
    }

    /// The bracketed hinge terms of Appendix A for load `k` (0: FX, 1: FY), hinge b and d:
    /// `c22 t + c23 P/S`, with `t = s` for FX and `c` for FY.
    fn bending(&self, k: usize) -> (D, D) {
        let t = if k == 0 { &self.s } else { &self.c };
        (
            self.b.c22 * t[0] + self.b.c23 * self.pb[k] * self.inv_sum33,
            self.d.c22 * t[2] + self.d.c23 * self.pd[k] * self.inv_sum33,
        )
    }

    /// `(a11, a21)`, sharing their hinge terms.
    pub fn input_coefficients(&self) -> (D, D) {
        let (hb, hd) = self.bending(0);
        let [s2, s3, s4] = self.s;
        let [c2, c3, c4] = self.c;
        let arc = self.l3 * self.cc[0] * self.inv_sum33;
        let (axb, axd) = (self.b.c11 * c2, self.d.c11 * c4);
        let a11 = s2 * hb + s4 * hd + axb * c2 + axd * c4 + arc * s3;
        let a21 = c2 * hb + c4 * hd - axb * s2 - axd * s4 + arc * c3;
        (a11, a21)
    }

    /// Appendix A, `a11` (rebuilt, see the module docs).
    pub fn a11(&self) -> D {
        let (hb, hd) = self.bending(0);
        let [s2, s3, s4] = self.s;
        let [c2, _, c4] = self.c;
        s2 * hb
            + s4 * hd
            + self.b.c11 * c2 * c2
            + self.d.c11 * c4 * c4
            + self.l3 * s3 * self.cc[0] * self.inv_sum33
    }

    /// Appendix A, `a21` with the `l3 cos d3` of Eq. 9 (see the module docs).
    pub fn a21(&self) -> D {
        let (hb, hd) = self.bending(0);
        let [s2, _, s4] = self.s;
        let [c2, c3, c4] = self.c;
        c2 * hb + c4 * hd - self.b.c11 * c2 * s2 - self.d.c11 * c4 * s4
            + self.l3 * c3 * self.cc[0] * self.inv_sum33
    }

    /// Appendix A, `a12` with `c22 cos d` in the brackets (see the module docs).
    pub fn a12(&self) -> D {
        let (hb, hd) = self.bending(1);
        let [s2, s3, s4] = self.s;
        let [c2, _, c4] = self.c;
        self.b.c11 * c2 * s2 + self.d.c11 * c4 * s4
            - s2 * hb
            - s4 * hd
            - self.l3 * s3 * self.cc[1] * self.inv_sum33
    }

    /// Appendix A, `a22` (negative, see the module docs).
    pub fn a22(&self) -> D {
        let (hb, hd) = self.bending(1);
        let [s2, _, s4] = self.s;
        let [c2, c3, c4] = self.c;
        -(self.b.c11 * s2 * s2
            + self.d.c11 * s4 * s4
            + c2 * hb
            + c4 * hd
            + self.l3 * c3 * self.cc[1] * self.inv_sum33)
    }

    /// End loads of hinges b and d under the input force `fx` alone (Eq. 3, 4, 6 with
    /// `FY = 0`), the load case of the stress analysis.
    pub fn hinge_loads_input(&self, fx: D) -> (HingeLoads<D>, HingeLoads<D>) {
        let [s2, _, s4] = self.s;
        let [c2, _, c4] = self.c;
        let m = fx * self.inv_sum33;
        let b = HingeLoads {
            axial: fx * c2,
            shear: fx * s2,
            moment: m * self.pb[0],
        };
        let d = HingeLoads {
            axial: fx * c4,
            shear: fx * s4,
            moment: m * self.pd[0],
        };
        (b, d)
    }

    /// End loads of hinges b (at node 3) and d (at node 4) under the quarter loads
    /// `fx`, `fy` (Eq. 3, 4 and 6).
    pub fn hinge_loads(&self, fx: D, fy: D) -> (HingeLoads<D>, HingeLoads<D>) {
        let [s2, _, s4] = self.s;
        let [c2, _, c4] = self.c;
        let b = HingeLoads {
            axial: fx * c2 + fy * s2,
            shear: fx * s2 - fy * c2,
            moment: (fx * self.pb[0] - fy * self.pb[1]) * self.inv_sum33,
        };
        let d = HingeLoads {
            axial: fx * c4 + fy * s4,
            shear: fx * s4 - fy * c4,
            moment: (fx * self.pd[0] - fy * self.pd[1]) * self.inv_sum33,
        };
        (b, d)
    }
}

/// The general bridge model: settings plus the evaluation of named outputs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bridge {
    pub settings: BridgeSettings,
}

impl Bridge {
    pub fn new(settings: BridgeSettings) -> Self {
        Bridge { settings }
    }

    /// Evaluates the outputs `wanted` (indices into [`BridgeOutput::ALL`]) of design `g`
    /// (SI) into `out`. Only what those outputs need is computed.
    pub fn evaluate<D: Scalar>(&self, g: &Geometry<D>, wanted: &[usize], out: &mut [D]) {
        use BridgeOutput::*;
        let s = &self.settings;
        let trig = g.trig();
        let needs_quarter = wanted.iter().any(|&k| match BridgeOutput::ALL[k] {
            SpanX | SpanY | KOutActuated | EquivalentMass | NaturalFrequency | SettlingTime => {
                false
            }
            StrokeIn => s.actuator.stiffness.is_some(),
            _ => true,
        });
        // a local initialised in place, not an Option built by a closure: the quarter of a
        // gradient evaluation is kilobytes, and moving it showed in the profile
        let storage;
        let quarter = if needs_quarter {
            storage = QuarterBridge::with_trig(g, &trig, s.hinge, s.width, &s.material);
            Some(&storage)
        } else {
            None
        };
        // nearly every output of the quarter needs a11 and a21: compute them up front
        let input = quarter.map(|q| {
            let (a11, a21) = q.input_coefficients();
            (a11, a21, a11.recip())
        });
        let mut e = Evaluation {
            g,
            s,
            trig: &trig,
            quarter,
            input,
            stresses: None,
            mode: None,
            mass: None,
        };
        for (&k, slot) in wanted.iter().zip(out.iter_mut()) {
            *slot = e.output(BridgeOutput::ALL[k]);
        }
    }
}

/// One evaluation: the shared parts, and the intermediate results computed on demand.
struct Evaluation<'a, D> {
    g: &'a Geometry<D>,
    s: &'a BridgeSettings,
    trig: &'a Trig<D>,
    /// Present whenever an output needs the compliances.
    quarter: Option<&'a QuarterBridge<D>>,
    /// `(a11, a21, k_in = 1/a11)`, present with the quarter.
    input: Option<(D, D, D)>,
    stresses: Option<[D; 4]>,
    /// The output mode and its equivalent mass, computed on demand.
    mode: Option<QuarterMode<D>>,
    mass: Option<D>,
}

impl<D: Scalar> Evaluation<'_, D> {
    fn quarter(&self) -> &QuarterBridge<D> {
        self.quarter
            .expect("the outputs that need the quarter model were listed")
    }

    /// `(a11, a21, k_in)`.
    #[inline]
    fn input(&self) -> (D, D, D) {
        self.input
            .expect("the outputs that need the quarter model were listed")
    }

    /// Eq. 13: `X_tr = X_nl k_pzt / (k_in + k_pzt)`; the nominal stroke for a rigid actuator.
    fn stroke_in(&mut self) -> D {
        let act = &self.s.actuator;
        match act.stiffness {
            None => D::from(act.nominal_stroke),
            Some(k_pzt) => {
                // k_pzt / (1/a11 + k_pzt) = k_pzt a11 / (1 + k_pzt a11)
                let ka = self.input().0 * k_pzt;
                ka * act.nominal_stroke / (ka + 1.0)
            }
        }
    }

    /// Eq. 12 and 14: `F_X,max = X_nl k_in + F_preload`.
    fn force_in_max(&mut self) -> D {
        let act = &self.s.actuator;
        let (stroke, preload) = (act.nominal_stroke, act.preload);
        self.input().2 * stroke + preload
    }

    /// Eq. 15-17 for hinges b and d, each quarter carrying half the actuator force.
    /// Eq. 15-17: the stresses at nodes 2, 3 (hinge b) and 4, 5 (hinge d), each quarter
    /// carrying half the actuator force.
    fn stresses(&mut self) -> [D; 4] {
        if let Some(v) = self.stresses {
            return v;
        }
        let fx = self.force_in_max() * 0.5;
        let (g, s) = (self.g, self.s);
        let (lb, ld) = self.quarter().hinge_loads_input(fx);
        // the loads act at nodes 3 and 4; nodes 2 and 5 are the far (clamped) ends
        let (n3, n2) = s.hinge.end_stresses(g.l2, g.t2, s.width, &lb);
        let (n4, n5) = s.hinge.end_stresses(g.l4, g.t4, s.width, &ld);
        *self.stresses.insert([n2, n3, n4, n5])
    }

    /// The quarter's deflection along the output, with the actuator in place.
    fn mode(&mut self) -> QuarterMode<D> {
        if let Some(m) = self.mode {
            return m;
        }
        let (g, s) = (self.g, self.s);
        // the closed form's hinge compliances when it was built, else the hinges afresh
        let (b, d) = match self.quarter {
            Some(q) => (q.b, q.d),
            None => (
                s.hinge.compliance(g.l2, g.t2, s.width, &s.material),
                s.hinge.compliance(g.l4, g.t4, s.width, &s.material),
            ),
        };
        *self
            .mode
            .insert(QuarterMode::new(g, self.trig, &b, &d, s.actuator.stiffness))
    }

    fn equivalent_mass(&mut self) -> D {
        if let Some(m) = self.mass {
            return m;
        }
        let mode = self.mode();
        let (g, s) = (self.g, self.s);
        // without masses there is no mass: NaN, which the problem layer never asks for
        // (Model::unavailable) and reports omit
        let Some(dynamics) = s.dynamics.as_ref() else {
            return D::from(f64::NAN);
        };
        let masses = bridge_dynamics::quarter_masses(
            g,
            s.width,
            s.material.density,
            dynamics.link_thickness,
        );
        *self
            .mass
            .insert(bridge_dynamics::equivalent_mass(&mode, &masses, dynamics))
    }

    fn natural_frequency(&mut self) -> D {
        let k = self.mode().stiffness;
        bridge_dynamics::natural_frequency(k, self.equivalent_mass())
    }

    fn output(&mut self, o: BridgeOutput) -> D {
        use BridgeOutput::*;
        match o {
            Amplification => {
                let (_, a21, k_in) = self.input();
                a21 * k_in
            }
            KIn => self.input().2,
            KOut => -self.quarter().a22().recip(),
            StressMax => {
                let [n2, n3, n4, n5] = self.stresses();
                max(max(n2, n3), max(n4, n5))
            }
            StressB => {
                let [n2, n3, _, _] = self.stresses();
                max(n2, n3)
            }
            StressD => {
                let [_, _, n4, n5] = self.stresses();
                max(n4, n5)
            }
            StressNode2 => self.stresses()[0],
            StressNode3 => self.stresses()[1],
            StressNode4 => self.stresses()[2],
            StressNode5 => self.stresses()[3],
            ForceInMax => self.force_in_max(),
            SpanX => self.g.span_x_with(self.trig),
            SpanY => self.g.span_y_with(self.trig),
            StrokeIn => self.stroke_in(),
            StrokeOut => {
                let (_, a21, k_in) = self.input();
                a21 * k_in * self.stroke_in()
            }
            A11 => self.input().0,
            A12 => self.quarter().a12(),
            A21 => self.input().1,
            A22 => self.quarter().a22(),
            KOutActuated => self.mode().stiffness,
            EquivalentMass => self.equivalent_mass(),
            NaturalFrequency => self.natural_frequency(),
            SettlingTime => {
                let scale = self
                    .s
                    .dynamics
                    .as_ref()
                    .map_or(f64::NAN, |d| d.settling_scale());
                let omega = self.natural_frequency() * (2.0 * std::f64::consts::PI);
                omega.recip() * scale
            }
        }
    }
}

/// The paper's closed forms for the special configurations (Sec. 5).
pub mod closed_forms {
    use super::*;

    /// Eq. 23, parallel bridge (`l2 = l4 = l`, `delta2 = delta4 = 0`):
    ///
    /// ```text
    /// da = sin d3 (c33 cos d3 l3^2 + 2 c23 l3) / (c33 l3^2 sin^2 d3 + 4 c11)
    /// ```
    ///
    /// The extracted text reads `cos^2 d3` in the denominator; the derivation from Eq. 9
    /// gives `sin^2 d3`, which is also the only form that tends to the ideal lever
    /// `cot d3` for rigid hinges and vanishes for `d3 = 0`.
    pub fn parallel<D: Scalar>(h: &Compliance<D>, l3: D, delta3: D) -> D {
        let (s, c) = delta3.sin_cos();
        s * (h.c33 * c * l3 * l3 + h.c23 * l3 * 2.0) / (h.c33 * l3 * l3 * s * s + h.c11 * 4.0)
    }

    /// Eq. 25, rhombic bridge (`l2 = l3 = delta2 = delta3 = 0`, `l4 = L`, `delta4 = delta`):
    ///
    /// ```text
    /// da = -sin(2 d) (2 c11 - c22/2) / (c22 + 4 c11 cos^2 d - c22 cos^2 d)
    /// ```
    ///
    /// The paper reaches it with the strip identities `c33 = 3 c22 / L^2` and
    /// `c23 = 6 c22 / (4 L)`, which hold for the bending part of `c22` only, so Eq. 25 is
    /// exact for a hinge without shear compliance. [`rhombic_general`] is the same limit
    /// for any hinge.
    pub fn rhombic<D: Scalar>(h: &Compliance<D>, delta: D) -> D {
        let c = delta.cos();
        -(delta * 2.0).sin() * (h.c11 * 2.0 - h.c22 * 0.5)
            / (h.c22 + h.c11 * 4.0 * c * c - h.c22 * c * c)
    }

    /// The rhombic limit of Eq. 9 before the strip identities are applied:
    /// `da = sin(2 d) (k - c11) / (2 (k sin^2 d + c11 cos^2 d))` with `k = c22 - c23^2/c33`.
    pub fn rhombic_general<D: Scalar>(h: &Compliance<D>, delta: D) -> D {
        let (s, c) = delta.sin_cos();
        let k = h.c22 - h.c23 * h.c23 / h.c33;
        (delta * 2.0).sin() * (k - h.c11) / ((k * s * s + h.c11 * c * c) * 2.0)
    }

    /// Eq. 27, aligned bridge (`delta2 = delta3 = delta4 = delta`, `l2 = l4 = l`):
    ///
    /// ```text
    /// da = sin d cos d (4 c22 - 4 c11 + 2 c23 l3 + 2 c32 l3 + c33 l3^2)
    ///      / (4 c22 sin^2 d + 4 c11 cos^2 d + 2 l3 c23 sin^2 d + 2 l3 c32 sin^2 d + l3^2 c33 sin^2 d)
    /// ```
    pub fn aligned<D: Scalar>(h: &Compliance<D>, l3: D, delta: D) -> D {
        let (s, c) = delta.sin_cos();
        let (s2, c2) = (s * s, c * c);
        s * c * (h.c22 * 4.0 - h.c11 * 4.0 + h.c23 * l3 * 4.0 + h.c33 * l3 * l3)
            / (h.c22 * 4.0 * s2 + h.c11 * 4.0 * c2 + l3 * h.c23 * 4.0 * s2 + l3 * l3 * h.c33 * s2)
    }
}
