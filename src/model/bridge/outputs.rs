//! The named outputs of the general bridge and one evaluation of those a problem asks for.

use super::dynamics::{self, QuarterMode};
use super::geometry::{Geometry, Layout, Trig};
use super::part::footprint;
use super::quarter::{hinge_compliances, QuarterBridge};
use super::{Bridge, BridgeSettings};
use crate::model::scalar::{max, Scalar};
use crate::model::{Dimension, OutputInfo};

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
    StressBeamMax,
    OutputFrequency,
    FirstFrequency,
    PartWidth,
    PartHeight,
    PocketLength,
}

impl BridgeOutput {
    /// Every output, in the order of [`OUTPUTS`].
    pub const ALL: [BridgeOutput; 29] = [
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
        BridgeOutput::StressBeamMax,
        BridgeOutput::OutputFrequency,
        BridgeOutput::FirstFrequency,
        BridgeOutput::PartWidth,
        BridgeOutput::PartHeight,
        BridgeOutput::PocketLength,
    ];

    /// Whether the output needs the masses and damping of [`BridgeSettings::dynamics`].
    pub fn needs_dynamics(self) -> bool {
        matches!(
            self,
            BridgeOutput::EquivalentMass
                | BridgeOutput::NaturalFrequency
                | BridgeOutput::SettlingTime
                | BridgeOutput::OutputFrequency
                | BridgeOutput::FirstFrequency
        )
    }
}

/// Names, dimensions and meanings of the outputs, indexed like [`BridgeOutput::ALL`].
pub static OUTPUTS: [OutputInfo; 29] = [
    OutputInfo::new("amplification", Dimension::Ratio, "displacement amplification da = a21/a11 (Eq. 9)"),
    OutputInfo::new("k_in", Dimension::Stiffness, "input stiffness 1/a11 (Eq. 10)"),
    OutputInfo::full("k_out", Dimension::Stiffness, "output stiffness -1/a22 (Eq. 11)", Some("N/mm"), None),
    OutputInfo::new("stress_max", Dimension::Stress, "largest stress in the hinges under the nominal stroke and preload (Eq. 12-17)"),
    OutputInfo::new("stress_b", Dimension::Stress, "largest stress in hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_d", Dimension::Stress, "largest stress in hinge d (Eq. 17)"),
    OutputInfo::new("force_in_max", Dimension::Force, "largest actuator force: nominal stroke times k_in plus preload (Eq. 12, 14)"),
    OutputInfo::new("span_x", Dimension::Length, "extent of the quarter along x: l2 cos d2 + l3 cos d3 + l4 cos d4 (Sec. 3)"),
    OutputInfo::new("span_y", Dimension::Length, "extent of the quarter along y: l2 sin d2 + l3 sin d3 + l4 sin d4 (Sec. 3)"),
    OutputInfo::full("stroke_in", Dimension::Length, "true actuator stroke under the bridge's load (Eq. 13)", Some("um"), None),
    OutputInfo::full("stroke_out", Dimension::Length, "change of the distance between the output faces for the true stroke: amplification x stroke_in", Some("um"), None),
    OutputInfo::new("a11", Dimension::Compliance, "input compliance (Eq. 8, Appendix A)"),
    OutputInfo::new("a12", Dimension::Compliance, "input displacement per output force (Eq. 8, Appendix A)"),
    OutputInfo::new("a21", Dimension::Compliance, "output displacement per input force (Eq. 8, Appendix A)"),
    OutputInfo::new("a22", Dimension::Compliance, "output compliance, negative by the paper's sign convention (Eq. 8, Appendix A)"),
    OutputInfo::new("stress_node2", Dimension::Stress, "largest stress at node 2, the input-link end of hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_node3", Dimension::Stress, "largest stress at node 3, the middle-link end of hinge b (Eq. 15-16)"),
    OutputInfo::new("stress_node4", Dimension::Stress, "largest stress at node 4, the middle-link end of hinge d (Eq. 17)"),
    OutputInfo::new("stress_node5", Dimension::Stress, "largest stress at node 5, the output-link end of hinge d (Eq. 17)"),
    OutputInfo::full("k_out_actuated", Dimension::Stiffness, "face-to-face output stiffness with the actuator holding the input links (k_out for a free input; see model::bridge::dynamics)", Some("N/mm"), None),
    OutputInfo::new("equivalent_mass", Dimension::Mass, "mass on the moving output face equivalent to the moving bridge and payload (Lagrange/Rayleigh, paper 001 Sec. 2.2)"),
    OutputInfo::new("natural_frequency", Dimension::Frequency, "the output mode's frequency, output_frequency (the name files used before it)"),
    OutputInfo::new("settling_time", Dimension::Time, "settling time into +-2 % after a step, for the damping ratio of [dynamics] (paper 001 Sec. 4.2)"),
    OutputInfo::new("stress_beam_max", Dimension::Stress, "largest beam stress |N|/(w t) + 6|M|/(w t^2) in the hinges, without a notch's stress concentration (stress_max for strips)"),
    OutputInfo::new("output_frequency", Dimension::Frequency, "natural frequency of the output mode (along the output), sqrt(k_out_actuated / equivalent_mass) / 2 pi (paper 001 Eq. 12); by FE the lowest symmetric mode"),
    // the sideways sway of the output block needs the bodies' rotational inertias, which
    // [dynamics] does not give, and the whole bridge's motion where the quarter model has
    // one quarter's: no closed form, so the model's value is the output mode's, which the
    // first mode does not exceed, and the refinement's correction carries the sideways mode
    OutputInfo::full("first_frequency", Dimension::Frequency, "lowest natural frequency of the part, of either symmetry (the output block's sideways sway, or the output mode), as the FE measures it", None, Some("output_frequency, the output mode's frequency, at or above the part's first mode")),
    OutputInfo::full("part_width", Dimension::Length, "the part's overall width along the actuator: the outline's bounding box in x, blocks included", Some("mm"), None),
    OutputInfo::full("part_height", Dimension::Length, "the part's overall height along the output: the outline's bounding box in y, blocks included", Some("mm"), None),
    OutputInfo::full("pocket_length", Dimension::Length, "the room between the faces the actuator pushes: the longest stack the part holds", Some("mm"), None),
];

impl Bridge {
    /// Evaluates the outputs `wanted` (indices into [`BridgeOutput::ALL`]) of design `g`
    /// (SI) into `out`. Only what those outputs need is computed.
    pub fn evaluate<D: Scalar>(&self, g: &Geometry<D>, wanted: &[usize], out: &mut [D]) {
        self.evaluate_with_modulus(g, None, wanted, out);
    }

    /// As [`Bridge::evaluate`], the material's Young's and shear moduli `modulus` times the
    /// nominal ones where given (Poisson's ratio kept): a number carrying a derivative gives
    /// the outputs' sensitivity to the modulus, which the material's tolerance needs.
    pub fn evaluate_with_modulus<D: Scalar>(
        &self,
        g: &Geometry<D>,
        modulus: Option<D>,
        wanted: &[usize],
        out: &mut [D],
    ) {
        use BridgeOutput::*;
        let s = &self.settings;
        let trig = g.trig();
        let needs_quarter = wanted.iter().any(|&k| match BridgeOutput::ALL[k] {
            SpanX | SpanY | PartWidth | PartHeight | PocketLength | KOutActuated
            | EquivalentMass | NaturalFrequency | SettlingTime | OutputFrequency
            | FirstFrequency => false,
            StrokeIn => s.actuator.stiffness.is_some(),
            _ => true,
        });
        // a local initialised in place, not an Option built by a closure: the quarter of a
        // gradient evaluation is kilobytes, and moving it showed in the profile
        let storage;
        let quarter = if needs_quarter {
            storage = QuarterBridge::with_trig(g, &trig, s.width, &s.material, modulus);
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
            layout: &self.layout,
            trig: &trig,
            quarter,
            input,
            modulus,
            stresses: None,
            mode: None,
            mass: None,
            extent: None,
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
    layout: &'a Layout,
    trig: &'a Trig<D>,
    /// Present whenever an output needs the compliances.
    quarter: Option<&'a QuarterBridge<D>>,
    /// `(a11, a21, k_in = 1/a11)`, present with the quarter.
    input: Option<(D, D, D)>,
    /// The material's moduli over the nominal ones, where they differ.
    modulus: Option<D>,
    stresses: Option<[D; 4]>,
    /// The output mode and its equivalent mass, computed on demand.
    mode: Option<QuarterMode<D>>,
    mass: Option<D>,
    /// The part's width and height, computed on demand once for both.
    extent: Option<[D; 2]>,
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

    /// Eq. 12 and 14 at the stroke the actuator makes: `F_X,max = X_tr k_in + F_preload`,
    /// `X_tr` of Eq. 13. The paper writes `X_nl`, the same for its rigid actuator; a stack
    /// of finite stiffness extends the part by `X_tr` only, and the force on the part at full
    /// stroke is the part's own stiffness times that (plus the preload it carries anyway).
    fn force_in_max(&mut self) -> D {
        let preload = self.s.actuator.preload;
        self.input().2 * self.stroke_in() + preload
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
        let (n3, n2) = g.b.end_stresses(s.width, &lb);
        let (n4, n5) = g.d.end_stresses(s.width, &ld);
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
            None => hinge_compliances(g, s.width, &s.material, self.modulus),
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
        let masses =
            dynamics::quarter_masses(g, s.width, s.material.density, dynamics.link_thickness);
        *self
            .mass
            .insert(dynamics::equivalent_mass(&mode, &masses, dynamics))
    }

    fn extent(&mut self) -> [D; 2] {
        if let Some(e) = self.extent {
            return e;
        }
        *self
            .extent
            .insert(footprint::extent(&self.s.part, self.layout, self.g))
    }

    fn natural_frequency(&mut self) -> D {
        let k = self.mode().stiffness;
        dynamics::natural_frequency(k, self.equivalent_mass())
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
            StressBeamMax => {
                let [n2, n3, n4, n5] = self.stresses();
                let (b, d) = (&self.g.b, &self.g.d);
                let kt_b = b.kind.stress_concentration(b.dims());
                let kt_d = d.kind.stress_concentration(d.dims());
                max(max(n2, n3) / kt_b, max(n4, n5) / kt_d)
            }
            StressNode2 => self.stresses()[0],
            StressNode3 => self.stresses()[1],
            StressNode4 => self.stresses()[2],
            StressNode5 => self.stresses()[3],
            ForceInMax => self.force_in_max(),
            SpanX => self.g.span_x_with(self.trig),
            SpanY => self.g.span_y_with(self.trig),
            PartWidth => self.extent()[0],
            PartHeight => self.extent()[1],
            PocketLength => footprint::pocket_length(&self.s.part, self.layout, self.g),
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
            NaturalFrequency | OutputFrequency | FirstFrequency => self.natural_frequency(),
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
