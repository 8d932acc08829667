//! The quarter model of paper 004 (Sec. 2, Appendix A): the compliance coefficients
//! `a11 .. a22` of Eq. 8 and the hinge loads of Eq. 3-6, for hinges of any kind.
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
//! Eq. 1 and Eq. 3-7, against the paper's own Tables 2 and 3 (see `tests/models/paper004_tables.rs`),
//! and against the independent matrix formulation of [`crate::model::reference::bridge_matrix`], which
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

use super::geometry::{Geometry, Trig};
use crate::model::hinge::{Compliance, HingeLoads};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

/// The quarter bridge with its hinge compliances and the shared sub-expressions of
/// The compliances of hinges b and d of `g`, in a material `modulus` times as stiff as
/// `material` where given.
pub(crate) fn hinge_compliances<D: Scalar>(
    g: &Geometry<D>,
    width: f64,
    material: &Material,
    modulus: Option<D>,
) -> (Compliance<D>, Compliance<D>) {
    let (b, d) = (
        g.b.compliance(width, material),
        g.d.compliance(width, material),
    );
    match modulus {
        Some(m) => (b.with_modulus(m), d.with_modulus(m)),
        None => (b, d),
    }
}

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
    pub fn new(g: &Geometry<D>, width: f64, material: &Material) -> Self {
        Self::with_trig(g, &g.trig(), width, material, None)
    }

    /// The quarter of `g`, its material's moduli `modulus` times the nominal ones where
    /// given ([`Compliance::with_modulus`]).
    pub(crate) fn with_trig(
        g: &Geometry<D>,
        trig: &Trig<D>,
        width: f64,
        material: &Material,
        modulus: Option<D>,
    ) -> Self {
        let (b, d) = hinge_compliances(g, width, material, modulus);
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
        Self::from_parts(b, d, l3, &Trig::new(delta2, delta3, delta4))
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
            // (c33b >> c33d) its two parts cancel to eight digits (tests/models/model_stability.rs)
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
    #[inline]
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
