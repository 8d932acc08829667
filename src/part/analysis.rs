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
    /// The force of the actuation case (`nominal_stroke * k + preload` on each loaded
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
/// `nominal_stroke * stiffness + preload` ([`super::Actuation`]), the largest force the
/// actuator exerts on the part.
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
