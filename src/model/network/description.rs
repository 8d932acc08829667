//! The network as a problem file describes it: bodies, hinges, beams, ports and measures, each
//! coordinate and dimension an [`Expression`] of the parameters. The parser ([`super::file`])
//! makes it; the model ([`super::model`]) and the part ([`super::part`]) are built from it. It
//! imports nothing else of the network, so that each of those can import it without a circle.

use crate::model::expression::Expression;
use crate::model::hinge::HingeKind;
use crate::model::{Dimension, ParameterInfo};

/// The name of the ground among the bodies.
pub const GROUND: &str = "ground";

/// The constant `deg` beside the parameters: pi / 180.
pub const DEG: &str = "deg";

/// A mirror axis: `X` the line y = 0, `Y` the line x = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
}

impl Axis {
    /// As the file names it.
    pub fn name(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
        }
    }
}

/// An expression and the key it was read from (for errors at a design).
#[derive(Debug, Clone)]
pub struct Keyed {
    pub key: String,
    pub expression: Expression,
    /// Its place among the expressions compiled into one tape
    /// ([`crate::model::expression::Tape`]), set by whoever compiles it: the model in its
    /// description, the part's rules in their own copy of it.
    pub slot: usize,
}

pub type Point = [Keyed; 2];

/// A body: its name, its geometry's points (outline vertices, or a link's ends) and the
/// axes it lies across.
#[derive(Debug, Clone)]
pub struct BodyDescription {
    pub name: String,
    /// Its key in the file (`network.bodies[2]`).
    pub key: String,
    pub points: Vec<Point>,
    /// A link's width (its two points the segment's ends); `None` for an outline.
    pub link_width: Option<Keyed>,
    pub on_axis: Vec<Axis>,
}

/// A hinge: which bodies it joins (`None` the ground), where, and its dimensions in the
/// kind's order.
#[derive(Debug, Clone)]
pub struct HingeDescription {
    pub name: String,
    /// Its key in the file (`network.hinges[0]`).
    pub key: String,
    pub kind: HingeKind,
    pub from: Option<usize>,
    pub to: Option<usize>,
    pub start: Point,
    pub angle: Keyed,
    pub dimensions: Vec<Keyed>,
    /// The parameter each dimension is, where it is one alone (for the ranges of fit).
    pub parameter_of: Vec<Option<usize>>,
}

/// A flexible beam: which bodies it joins (`None` the ground), from its `start` on `from`
/// to its `end` on `to`, and its in-plane thickness.
#[derive(Debug, Clone)]
pub struct BeamDescription {
    pub name: String,
    /// Its key in the file (`network.beams[0]`).
    pub key: String,
    pub from: Option<usize>,
    pub to: Option<usize>,
    pub start: Point,
    pub end: Point,
    pub thickness: Keyed,
}

/// A port: a point of a body and a direction, maybe across a mirror axis.
#[derive(Debug, Clone)]
pub struct PortDescription {
    pub name: String,
    pub body: usize,
    pub at: Point,
    pub direction: Point,
    pub across: Option<Axis>,
    /// The mass it carries (kg), at its point: an output's payload (zero if none).
    pub payload: f64,
}

/// A support in one direction (a guide, a roller): the motion of a body's point along a
/// direction held at zero, the motion across it free, the body's rotation free or held.
#[derive(Debug, Clone)]
pub struct SupportDescription {
    /// Its key in the file (`network.supports[0]`).
    pub key: String,
    pub body: usize,
    pub at: Point,
    pub direction: Point,
    pub hold_rotation: bool,
}

/// A named expression reported as an output.
#[derive(Debug, Clone)]
pub struct MeasureDescription {
    pub name: String,
    pub dimension: Dimension,
    pub value: Keyed,
}

/// The whole description, its expressions parsed against the parameters and `deg`.
#[derive(Debug, Clone)]
pub struct Description {
    pub parameters: Vec<ParameterInfo>,
    /// Metres per unit of the expressions' lengths.
    pub unit: f64,
    pub width: f64,
    pub mirror: Vec<Axis>,
    /// The bodies other than the ground, in the file's order.
    pub bodies: Vec<BodyDescription>,
    /// The ground's outline points, for the extent.
    pub ground: Vec<Point>,
    pub hinges: Vec<HingeDescription>,
    pub beams: Vec<BeamDescription>,
    pub input: PortDescription,
    pub outputs: Vec<PortDescription>,
    pub measures: Vec<MeasureDescription>,
    pub supports: Vec<SupportDescription>,
}
