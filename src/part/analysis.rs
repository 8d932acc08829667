//! The finite-element check a model asks of its part, stated on the whole part in SI units:
//! which faces are held, which load cases the test force makes, which displacements are
//! measured and which outputs are reported from them. The part layer states it so that the
//! solver needs to know no model: any part whose faces are named can carry its own check,
//! and the solver derives from this statement whatever it solves (the half of a symmetric
//! part, or the whole one for CalculiX).
//!
//! Faces are named by [`super::Face::name`]; a name may cover several straight faces, a load
//! or a measure on it then spans them all.

use crate::vocab::Dimension;

/// An output of an [`Analysis`]: its index in [`Analysis::outputs`], so that a model can
/// point at what the check measures without a name to misspell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FeOutputId(pub usize);

/// What of the finite-element check measures a model's output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeCounterpart {
    /// One of the analysis's outputs.
    Output(FeOutputId),
    /// The force of the actuation case ([`super::Actuation::largest_force`] on each loaded
    /// face), which is no output of its own: it carries the error of its stiffness.
    ActuationForce,
}

/// A share of the test force on a face: `share * test force` along `direction` (a unit
/// vector), spread evenly over the face.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    pub face: String,
    pub direction: [f64; 2],
    pub share: f64,
}

/// Loads applied together. The solver writes the name after the force, as in
/// `"10 N on the output face"`, so it says where the test force goes.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCase {
    pub name: String,
    pub loads: Vec<Load>,
}

/// One term of a [`Measure`]: `weight * (mean displacement of the face . direction)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    pub weight: f64,
    pub face: String,
    pub direction: [f64; 2],
}

/// A displacement (m) measured under a load case: the sum of its terms, in their order.
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    /// The index of the load case among [`Analysis::cases`].
    pub case: usize,
    pub terms: Vec<Term>,
}

/// What an output is; measures are indices into [`Analysis::measures`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// The measure itself (m).
    Displacement(usize),
    /// `test force / measure` (N/m).
    Stiffness(usize),
    /// One measure over another.
    Ratio {
        numerator: usize,
        denominator: usize,
    },
    /// The largest beam stress `|N| / (w t) + 6 |M| / (w t^2)` over the hinges' root
    /// sections under the actuation (Pa): what a beam model of the hinges predicts.
    SectionStress,
    /// The largest nodal von Mises stress under the actuation (Pa): at a sharp root it grows
    /// without bound as the mesh is refined.
    PeakStress,
    /// The lowest mode symmetric about the y axis (Hz).
    SymmetricFrequency,
    /// The lowest mode of either symmetry (Hz).
    LowestFrequency,
    /// What the part does driven by its actuator, read through its two ports ([`Ports`]).
    Actuated { ports: Ports, what: Actuated },
}

impl Quantity {
    /// Needs the natural modes (and so a density and a [`Modal`] set-up).
    pub fn is_modal(self) -> bool {
        matches!(
            self,
            Quantity::SymmetricFrequency | Quantity::LowestFrequency
        )
    }

    /// A stress under the actuation, which scales with the actuation force.
    pub fn is_stress(self) -> bool {
        matches!(self, Quantity::SectionStress | Quantity::PeakStress)
    }
}

/// The part's two ports as its measures read them (indices into [`Analysis::measures`]), each
/// over the test force a compliance `C_ij`, the read of port `i` per force on port `j`: the
/// input is read as `k_in` reads it under the actuation case, the output as the stroke at the
/// output is read.
///
/// The actuator is a spring of its stiffness `k_a` on the input's read `g . u`, pushing as
/// the actuation case's loads `h` do, driven by its free stroke: `(K + k_a h g^T) u = k_a
/// stroke h`. The rank-one term is solved on the factorization already made (Sherman and
/// Morrison): every field of the part with the spring in place is a combination of the two
/// cases' fields, so every read of it is the same combination of the four reads. Nothing
/// more is solved, in 2D or in 3D; the stack's force being the actuation case's loads
/// scaled, the amplification under the stack is `fe_amplification` itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ports {
    /// The input under the actuation case: `C_ii`.
    pub input: usize,
    /// The output under the actuation case: `C_oi`.
    pub output: usize,
    /// The output under the output's case, read along its load: `C_oo`.
    pub output_loaded: usize,
    /// The input under the output's case per force along the direction [`Ports::output`]
    /// reads the output (its terms negated where the case loads the other way): `C_io`.
    pub input_by_output: usize,
}

/// A quantity of the part driven by its actuator ([`Ports`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Actuated {
    /// The stroke the stack makes against the part (m): paper 004's Eq. 13,
    /// `stroke C_ii / (C_ii + 1 / k_a)`, the free stroke for a rigid stack.
    StrokeIn,
    /// The output's motion under that stroke (m): `C_oi / C_ii` times it.
    StrokeOut,
    /// The output's stiffness with the stack in place (N/m): `1 / (C_oo - C_oi C_io / (C_ii
    /// + 1 / k_a))`.
    KOutActuated,
    /// The output's stiffness with the input held (N/m), as under a rigid stack.
    KOutBlocked,
    /// The force that holds the output still under the stroke (N): `stroke_out k_out_actuated`.
    BlockedForce,
}

impl Actuated {
    /// Every one, in the order [`actuated_outputs`] states them.
    pub const ALL: [Actuated; 5] = [
        Actuated::StrokeIn,
        Actuated::StrokeOut,
        Actuated::KOutActuated,
        Actuated::KOutBlocked,
        Actuated::BlockedForce,
    ];

    /// Its output's id where [`actuated_outputs`] start at `first`.
    pub fn id(self, first: usize) -> FeOutputId {
        FeOutputId(first + Actuated::ALL.iter().position(|&a| a == self).unwrap_or(0))
    }
}

impl Ports {
    /// Every measure it reads.
    pub fn measures(&self) -> [usize; 4] {
        [
            self.input,
            self.output,
            self.output_loaded,
            self.input_by_output,
        ]
    }

    /// `what` from the measures `m` at the test force `force`, the actuator's free stroke
    /// `stroke` (m) and stiffness `stiffness` (N/m; `None` for a rigid stack).
    pub fn value(
        &self,
        what: Actuated,
        m: &[f64],
        force: f64,
        stroke: f64,
        stiffness: Option<f64>,
    ) -> f64 {
        let c = |i: usize| m[i] / force;
        let (c_ii, c_oi) = (c(self.input), c(self.output));
        let (c_oo, c_io) = (c(self.output_loaded), c(self.input_by_output));
        // the stack's compliance, in series with the input's
        let c_a = stiffness.map_or(0.0, f64::recip);
        let stroke_in = stroke * c_ii / (c_ii + c_a);
        let held = |c_a: f64| (c_oo - c_oi * c_io / (c_ii + c_a)).recip();
        match what {
            Actuated::StrokeIn => stroke_in,
            Actuated::StrokeOut => stroke_in * c_oi / c_ii,
            Actuated::KOutActuated => held(c_a),
            Actuated::KOutBlocked => held(0.0),
            Actuated::BlockedForce => stroke_in * c_oi / c_ii * held(c_a),
        }
    }
}

/// The outputs of the part driven by its actuator, read through `ports`, in the order of
/// [`Actuated::ALL`]: strokes in micrometres, stiffnesses in `stiffness_display`.
pub fn actuated_outputs(ports: Ports, stiffness_display: Option<&'static str>) -> Vec<FeOutput> {
    let out = |name, dimension, meaning, what, display| FeOutput {
        name,
        dimension,
        meaning,
        quantity: Quantity::Actuated { ports, what },
        converges: true,
        display,
        analytic: None,
    };
    let um = Some("um");
    vec![
        out(
            "fe_stroke_in",
            Dimension::Length,
            "the stack's stroke against the part: a spring of its stiffness between the faces it pushes, driven by its free stroke",
            Actuated::StrokeIn,
            um,
        ),
        out(
            "fe_stroke_out",
            Dimension::Length,
            "the output's motion under the stack's stroke",
            Actuated::StrokeOut,
            um,
        ),
        out(
            "fe_k_out_actuated",
            Dimension::Stiffness,
            "the output's stiffness, the stack's spring between its faces",
            Actuated::KOutActuated,
            stiffness_display,
        ),
        out(
            "fe_k_out_blocked",
            Dimension::Stiffness,
            "the output's stiffness, the stack's faces held",
            Actuated::KOutBlocked,
            stiffness_display,
        ),
        out(
            "fe_blocked_force",
            Dimension::Force,
            "the force that holds the output still under the stack's stroke",
            Actuated::BlockedForce,
            None,
        ),
    ]
}

/// The analytic value an output is compared with when no model output has it as its
/// [`FeCounterpart`]; indices are the model's outputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Comparison {
    /// The model's output itself.
    Output(usize),
    /// `times * test force / stiffness` (`times` 1 when `None`): a displacement the model
    /// states through a stiffness and, for a displacement elsewhere, a ratio.
    PerTestForce {
        stiffness: usize,
        times: Option<usize>,
    },
}

/// An output of the check.
#[derive(Debug, Clone, PartialEq)]
pub struct FeOutput {
    pub name: &'static str,
    /// What it measures; its SI unit is the one `verify.json` writes.
    pub dimension: Dimension,
    pub meaning: &'static str,
    pub quantity: Quantity,
    /// Whether the mesh sequence must converge on it: a peak stress at a sharp root never
    /// does, and is reported without holding the check back.
    pub converges: bool,
    /// The unit a designer reads it in where the dimension's usual one does not suit it (a
    /// stroke of micrometres beside parts of millimetres), as a model's output states it.
    pub display: Option<&'static str>,
    pub analytic: Option<Comparison>,
}

/// Which load case gives the stress fields: scaled so that a face of share 1 carries
/// [`super::Actuation::largest_force`] at the case's stiffness, the largest force the
/// actuator exerts on the part (at the stroke it makes against the part).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActuationCase {
    /// What the actuation force is reported as.
    pub name: &'static str,
    pub case: usize,
    /// An output whose quantity is a [`Quantity::Stiffness`].
    pub stiffness: FeOutputId,
}

/// The actuator as a spring between two faces along `direction` (its stiffness
/// [`super::Actuation::stiffness`]; the faces held along `direction` when it has none).
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    pub faces: [String; 2],
    pub direction: [f64; 2],
}

/// What the natural modes need besides the part.
#[derive(Debug, Clone, PartialEq)]
pub struct Modal {
    /// The face that carries the payload ([`super::Actuation::payload_mass`]).
    pub payload: String,
    pub actuator: Option<Spring>,
    /// The load case whose deflection starts the symmetric family's iteration: one close
    /// to its lowest mode converges in few steps.
    pub start: usize,
}

/// A part's finite-element check.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The faces held in both directions.
    pub clamped: Vec<String>,
    pub cases: Vec<LoadCase>,
    pub measures: Vec<Measure>,
    pub outputs: Vec<FeOutput>,
    pub actuation: Option<ActuationCase>,
    pub modal: Option<Modal>,
}

impl Analysis {
    /// The output called `name`.
    pub fn output(&self, name: &str) -> Option<FeOutputId> {
        self.outputs
            .iter()
            .position(|o| o.name == name)
            .map(FeOutputId)
    }

    /// The first output of the quantity `q`.
    pub fn find(&self, q: Quantity) -> Option<FeOutputId> {
        self.outputs
            .iter()
            .position(|o| o.quantity == q)
            .map(FeOutputId)
    }

    /// Every face name the statement uses, each once, in the order first met.
    pub fn faces(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        let all = self
            .clamped
            .iter()
            .chain(
                self.cases
                    .iter()
                    .flat_map(|c| c.loads.iter().map(|l| &l.face)),
            )
            .chain(
                self.measures
                    .iter()
                    .flat_map(|m| m.terms.iter().map(|t| &t.face)),
            )
            .chain(self.modal.iter().flat_map(|m| {
                std::iter::once(&m.payload).chain(m.actuator.iter().flat_map(|s| s.faces.iter()))
            }));
        for name in all {
            if !names.contains(&name.as_str()) {
                names.push(name);
            }
        }
        names
    }
}
