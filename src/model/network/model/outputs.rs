//! The outputs a network's description names, each with its quantity, and what each needs
//! evaluated: apart from the evaluation so that the list reads as the file's reader sees
//! it, port by port, flexure by flexure, then the sizes and the modes.

use std::borrow::Cow;

use super::super::description::Description;
use crate::model::{Dimension, OutputInfo};

/// What an output is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Quantity {
    /// Output port `o`'s motion over the input's.
    Amplification(usize),
    KIn,
    KOut,
    KOutActuated,
    KOutBlocked,
    BlockedForce,
    StrokeIn,
    StrokeOut,
    StressMax,
    /// Flexure `h`'s largest stress: the hinges', then the beams'.
    Stress(usize),
    /// Flexure `h`'s stress at its end on `from` (false) or on `to` (true).
    StressEnd(usize, bool),
    Rotation(usize),
    SpanX,
    SpanY,
    /// The part's outline's width along x and height along y ([`Drawing::footprint`]).
    PartWidth,
    PartHeight,
    Measure(usize),
    /// The natural frequency of mode `i` (from 0).
    Frequency(usize),
    /// An output at the working stroke, with large deflection (`[analysis] deflection =
    /// "large"`).
    AtStroke(AtStroke),
    /// The critical load factor of the working stroke (`nl_critical`), with large
    /// deflection.
    Critical,
}

impl Quantity {
    /// Whether it is an output of the large-deflection solve.
    pub(super) fn at_stroke(self) -> bool {
        matches!(self, Quantity::AtStroke(_) | Quantity::Critical)
    }
}

/// How the outputs at the working stroke are solved: the beam elements a flexure and the
/// load steps from the unloaded part to the full stroke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LargeSettings {
    pub elements: usize,
    pub steps: usize,
    /// The critical load factor is looked for up to this multiple of the working stroke
    /// (above 1).
    pub critical_up_to: f64,
}

/// What an output at the working stroke is ([`crate::model::large::report::StrokePoint`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum AtStroke {
    StrokeIn,
    StrokeOut,
    Amplification,
    AmplificationTangent,
    KIn,
    KOut,
    StressMax,
    /// Flexure `h`'s largest stress: the hinges', then the beams'.
    Stress(usize),
    /// Output port `o`'s motion across its direction.
    Across(usize),
    /// Output port `o`'s body's rotation.
    Turn(usize),
    /// The natural frequency of mode `i` (from 0) about the equilibrium.
    Frequency(usize),
}

/// What an evaluation's wanted outputs need ([`NetworkModel::needs`]).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Needs {
    /// How many natural frequencies, where any.
    pub(super) modes: Option<usize>,
    /// The described points, for the spans or the masses.
    pub(super) extent: bool,
    /// The part's outline, for its width and height.
    pub(super) footprint: bool,
    /// The input's load case.
    pub(super) input: bool,
    /// The first output's load case.
    pub(super) output: bool,
    /// The input's compliance condensed out of the output's (its case then read at the
    /// input too).
    pub(super) condenses: bool,
    /// The hinges' end stresses.
    pub(super) stresses: bool,
    /// The solve at the working stroke.
    pub(super) stroke: bool,
    /// How many natural frequencies about the equilibrium at the working stroke, where any.
    pub(super) stroke_modes: Option<usize>,
    /// The critical load factor's search.
    pub(super) critical: bool,
}

impl Needs {
    /// What output `q` needs, on an actuator of stiffness `actuator` where given.
    pub(super) fn of(q: Quantity, actuator: Option<f64>) -> Self {
        use Quantity::*;
        Needs {
            modes: match q {
                Frequency(i) => Some(i + 1),
                _ => None,
            },
            extent: matches!(q, SpanX | SpanY),
            footprint: matches!(q, PartWidth | PartHeight),
            input: !matches!(
                q,
                SpanX
                    | SpanY
                    | PartWidth
                    | PartHeight
                    | Measure(_)
                    | StrokeIn
                    | AtStroke(_)
                    | Critical
            ) || (q == StrokeIn && actuator.is_some()),
            output: matches!(q, KOut | KOutActuated | KOutBlocked | BlockedForce),
            condenses: matches!(q, KOutActuated | KOutBlocked | BlockedForce),
            stresses: matches!(q, StressMax | Stress(_) | StressEnd(..)),
            stroke: matches!(q, AtStroke(_)),
            stroke_modes: match q {
                AtStroke(self::AtStroke::Frequency(i)) => Some(i + 1),
                _ => None,
            },
            critical: q == Critical,
        }
    }

    /// What both need.
    pub(super) fn or(self, o: Self) -> Self {
        Needs {
            modes: self.modes.max(o.modes),
            extent: self.extent | o.extent,
            footprint: self.footprint | o.footprint,
            input: self.input | o.input,
            output: self.output | o.output,
            condenses: self.condenses | o.condenses,
            stresses: self.stresses | o.stresses,
            stroke: self.stroke | o.stroke,
            stroke_modes: self.stroke_modes.max(o.stroke_modes),
            critical: self.critical | o.critical,
        }
    }
}

/// The multiple of the working stroke the critical load factor is looked for up to, where
/// `[analysis] critical_up_to` does not say.
pub const CRITICAL_UP_TO: f64 = 4.0;

/// How many natural frequencies the model names (`f1`, `f2`, ...).
pub(super) const FREQUENCIES: usize = 3;

/// The outputs a description names, in their order, each with its quantity.
pub(super) struct Named {
    pub(super) quantities: Vec<Quantity>,
    pub(super) outputs: Vec<OutputInfo>,
}

impl Named {
    pub(super) fn of(d: &Description) -> Named {
        let mut named = Named {
            quantities: Vec::new(),
            outputs: Vec::new(),
        };
        named.ports(d);
        named.flexures(d);
        named.sizes(d);
        named.frequencies(d);
        named
    }

    fn add(&mut self, q: Quantity, name: String, dim: Dimension, what: String) {
        self.quantities.push(q);
        self.outputs.push(OutputInfo {
            name: Cow::Owned(name),
            dimension: dim,
            description: Cow::Owned(what),
            display: None,
            stand_in: None,
        });
    }

    /// The ports' ratios, stiffnesses and strokes, and the largest stress.
    fn ports(&mut self, d: &Description) {
        let first = &d.outputs[0].name;
        self.add(
            Quantity::Amplification(0),
            "amplification".into(),
            Dimension::Ratio,
            format!("motion of output \"{first}\" over the input's (W_oi / W_ii)"),
        );
        for (o, p) in d.outputs.iter().enumerate().skip(1) {
            self.add(
                Quantity::Amplification(o),
                format!("amplification_{}", p.name),
                Dimension::Ratio,
                format!("motion of output \"{}\" over the input's", p.name),
            );
        }
        use Dimension::*;
        for (q, name, dim, what) in [
            (Quantity::KIn, "k_in", Stiffness, "input stiffness, the outputs free (1 / W_ii)".to_string()),
            (Quantity::KOut, "k_out", Stiffness, format!("stiffness at output \"{first}\", the input free (1 / W_oo)")),
            (Quantity::KOutActuated, "k_out_actuated", Stiffness, format!("stiffness at output \"{first}\", the input on the actuator's stiffness")),
            (Quantity::KOutBlocked, "k_out_blocked", Stiffness, format!("stiffness at output \"{first}\", the input held")),
            (Quantity::BlockedForce, "blocked_force", Force, format!("force at output \"{first}\" held, under the true stroke: stroke_out k_out_actuated")),
            (Quantity::StrokeIn, "stroke_in", Length, "true actuator stroke under the network's load (paper 004 Eq. 13)".to_string()),
            (Quantity::StrokeOut, "stroke_out", Length, format!("motion of output \"{first}\" under the true stroke")),
            (Quantity::StressMax, "stress_max", Stress, "largest stress in the hinges under the largest actuator force (paper 004 Eq. 12-17)".to_string()),
        ] {
            self.add(q, name.into(), dim, what);
        }
    }

    /// Each flexure's stress, its end stresses and its rotation.
    fn flexures(&mut self, d: &Description) {
        use Dimension::*;
        // the flexures: the hinges, then the beams, each named and called as the file does
        let members: Vec<(&str, String)> = d
            .hinges
            .iter()
            .map(|h| (h.name.as_str(), format!("hinge \"{}\"", h.name)))
            .chain(
                d.beams
                    .iter()
                    .map(|b| (b.name.as_str(), format!("beam \"{}\"", b.name))),
            )
            .collect();
        for (h, (name, what)) in members.iter().enumerate() {
            let kind = match d.hinges.get(h) {
                Some(hinge) => hinge.kind.name(),
                None => "Timoshenko beam, no stress concentration",
            };
            self.add(
                Quantity::Stress(h),
                format!("stress_{name}"),
                Stress,
                format!("largest stress in {what} ({kind})"),
            );
        }
        for (h, (name, what)) in members.iter().enumerate() {
            for (to, end) in [(false, "from"), (true, "to")] {
                self.add(
                    Quantity::StressEnd(h, to),
                    format!("stress_{name}_{end}"),
                    Stress,
                    format!("stress in {what} at its end on its `{end}` body"),
                );
            }
        }
        for (h, (name, what)) in members.iter().enumerate() {
            self.add(
                Quantity::Rotation(h),
                format!("rotation_{name}"),
                Angle,
                format!("rotation of {what} (its `to` end against its `from` end) under the largest actuator force"),
            );
        }
    }

    /// The spans of the described part, the part's footprint and the described measures.
    fn sizes(&mut self, d: &Description) {
        use Dimension::*;
        for axis in ["x", "y"] {
            let name = format!("span_{axis}");
            let (q, what) = match d.measures.iter().position(|m| m.name == name) {
                Some(i) => (
                    Quantity::Measure(i),
                    format!("`{}`", d.measures[i].value.expression.source()),
                ),
                None => (
                    if axis == "x" {
                        Quantity::SpanX
                    } else {
                        Quantity::SpanY
                    },
                    format!("extent of the described part along {axis}"),
                ),
            };
            self.add(q, name, Length, what);
        }
        for (q, name, what) in [
            (Quantity::PartWidth, "part_width", "the part's overall width along x: the outline's bounding box, pads, blocks and mirror images included"),
            (Quantity::PartHeight, "part_height", "the part's overall height along y: the outline's bounding box, pads, blocks and mirror images included"),
        ] {
            self.add(q, name.into(), Length, what.into());
        }
        for (i, m) in d.measures.iter().enumerate() {
            if m.name != "span_x" && m.name != "span_y" {
                self.add(
                    Quantity::Measure(i),
                    m.name.clone(),
                    m.dimension,
                    format!("`{}`", m.value.expression.source()),
                );
            }
        }
    }

    /// The natural frequencies.
    fn frequencies(&mut self, d: &Description) {
        use Dimension::*;
        for i in 0..FREQUENCIES {
            self.add(
                Quantity::Frequency(i),
                format!("f{}", i + 1),
                Frequency,
                format!(
                    "natural frequency of mode {} (the bodies' masses from their outlines or links, \
                     the outputs' payloads; the flexures massless; the actuator a spring){}",
                    i + 1,
                    if d.mirror.is_empty() {
                        ""
                    } else {
                        "; of the modes symmetric about the mirror axes, or, on a part standing \
                         on an output's image, about the other axis"
                    }
                ),
            );
        }
    }

    /// The outputs at the working stroke: the ports', each flexure's stress, each output
    /// port's parasitic motion.
    pub(super) fn at_stroke(&mut self, d: &Description) {
        use Dimension::*;
        let first = &d.outputs[0].name;
        let at = "at the working stroke, with large deflection";
        for (q, name, dim, what) in [
            (
                AtStroke::StrokeIn,
                "nl_stroke_in",
                Length,
                format!("the input's motion {at} (the stack at its free stroke and preload)"),
            ),
            (
                AtStroke::StrokeOut,
                "nl_stroke_out",
                Length,
                format!("motion of output \"{first}\" {at}"),
            ),
            (
                AtStroke::Amplification,
                "nl_amplification",
                Ratio,
                format!("nl_stroke_out / nl_stroke_in: the secant amplification {at}"),
            ),
            (
                AtStroke::AmplificationTangent,
                "nl_amplification_tangent",
                Ratio,
                format!("the tangent amplification {at}"),
            ),
            (
                AtStroke::KIn,
                "nl_k_in",
                Stiffness,
                format!("tangent input stiffness {at}, the outputs free"),
            ),
            (
                AtStroke::KOut,
                "nl_k_out",
                Stiffness,
                format!("tangent stiffness at output \"{first}\" {at}, the input free"),
            ),
            (
                AtStroke::StressMax,
                "nl_stress_max",
                Stress,
                format!("largest stress in the flexures {at}"),
            ),
        ] {
            self.add(Quantity::AtStroke(q), name.into(), dim, what);
        }
        let members = d
            .hinges
            .iter()
            .map(|h| &h.name)
            .chain(d.beams.iter().map(|b| &b.name));
        for (h, name) in members.enumerate() {
            self.add(
                Quantity::AtStroke(AtStroke::Stress(h)),
                format!("nl_stress_{name}"),
                Stress,
                format!("largest stress in \"{name}\" {at}"),
            );
        }
        self.add(
            Quantity::Critical,
            "nl_critical".into(),
            Ratio,
            format!(
                "the critical load factor: the multiple of the working stroke (the stack's free \
                 stroke and preload times it) at which the tangent stiffness stops being positive \
                 definite (buckling, a limit point), looked for up to `[analysis] critical_up_to` \
                 (default {CRITICAL_UP_TO}); without one up to there it is `critical_up_to` itself \
                 with a zero gradient, so that a constraint `nl_critical >= m` with m below \
                 `critical_up_to` holds"
            ),
        );
        for (o, p) in d.outputs.iter().enumerate() {
            let name = &p.name;
            self.add(
                Quantity::AtStroke(AtStroke::Across(o)),
                format!("nl_across_{name}"),
                Length,
                format!("parasitic motion of output \"{name}\" across its direction {at}"),
            );
            self.add(
                Quantity::AtStroke(AtStroke::Turn(o)),
                format!("nl_turn_{name}"),
                Angle,
                format!("rotation of output \"{name}\"'s body {at}"),
            );
        }
        for i in 0..FREQUENCIES {
            self.add(
                Quantity::AtStroke(AtStroke::Frequency(i)),
                format!("nl_f{}", i + 1),
                Frequency,
                format!(
                    "natural frequency of mode {} about the equilibrium {at}: the tangent \
                     stiffness there, the masses of f{} where the bodies stand",
                    i + 1,
                    i + 1
                ),
            );
        }
    }

    /// For each output, the outputs it is the maximum of: the largest stresses' ends.
    pub(super) fn maxima(&self) -> Vec<Option<Vec<usize>>> {
        let quantities = &self.quantities;
        quantities
            .iter()
            .map(|q| {
                let ends = |pick: &dyn Fn(usize) -> bool| {
                    quantities
                        .iter()
                        .enumerate()
                        .filter(|(_, e)| matches!(e, Quantity::StressEnd(h, _) if pick(*h)))
                        .map(|(i, _)| i)
                        .collect::<Vec<_>>()
                };
                match *q {
                    Quantity::StressMax => Some(ends(&|_| true)),
                    Quantity::Stress(h) => Some(ends(&|g| g == h)),
                    _ => None,
                }
            })
            .collect()
    }
}
