//! The network's [`Model`]: a [`Description`] evaluated at a design into the structure of
//! [`super::structure`], solved for the load cases the wanted outputs need, its outputs
//! named by port and hinge.
//!
//! The ports' quantities are the whole mechanism's, from the described part's compliance
//! `C_ij` (motion at port `i` under a unit load at port `j`): `W_ij = p_i C_ij f_j`, with
//! `p_i = 2` for a port across a mirror axis (it reads the change of distance between its
//! point and its mirror image) and `f_j = 1/2` per mirror axis port `j`'s body lies across
//! (the described part carries that share of its load). For a quarter bridge both factors
//! meet and `W = C`, which is paper 004's Eq. 8-11 (the quarter's `a11 = X / F` with the
//! stroke `X` and the actuator's force `F`).
//!
//! The stresses and rotations are under the actuator's largest force, `F = X_tr k_in +
//! F_preload` (paper 004, Eq. 12 and 14 at the true stroke `X_tr` of Eq. 13, which is the
//! paper's `X_nl` for a rigid actuator), as the bridge's: each hinge's end loads
//! ([`Network::flexure_loads`]) into the hinge library's peak stresses with the notch's
//! concentration. The actuator's true stroke is Eq. 13; the blocked force is the free
//! output stroke times the output stiffness with the actuator in place (Thevenin's
//! equivalent of the linear mechanism: Lobontiu, "Compliant Mechanisms", CRC 2002, Sec. 4.4).

use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::convert::Infallible;
use std::sync::Arc;

use super::description::{Axis, Description, HingeDescription, Keyed, Point};
use super::modes::{described_piece, DirectedMass, Inertia, ModeError};
use super::on_axis::flexure_on_mirror_axis;
use super::part::Drawing;
use super::structure::{beam_compliance, end_of};
use super::structure::{
    Body, Case, Displacements, Dof, Flexure, Guide, Load, Network, NetworkError, SolveBuffers,
    Spring,
};
use crate::model::actuator::Actuator;
use crate::model::expression::Tape;
use crate::model::fit::FitLimit;
use crate::model::hinge::{Compliance, HingeKind, HingeLoads, MAX_HINGE_DIMENSIONS};
use crate::model::material::Material;
use crate::model::scalar::{max, with_count, Jet, Scalar};
use crate::model::{unseed, Dimension, Model, OutputInfo, ParameterInfo};

pub(crate) mod at_stroke;
mod evaluate;
mod mirror;
mod natural;
mod outputs;
mod placing;
pub(crate) mod stroke;
mod stroke_modes;

use mirror::{expressions, Role};
use natural::axis_holds;
pub(super) use natural::Family;
use outputs::{AtStroke, Named, Needs, Quantity};
pub use outputs::{LargeSettings, CRITICAL_UP_TO};
use placing::{constant_direction, link_band, outline_crossing};

/// The described part at one design (m), for its pictures ([`super::depiction`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Picture {
    /// Each body's points: its outline, or its link's two ends.
    pub bodies: Vec<Vec<[f64; 2]>>,
    /// Each flexure's start, end and least thickness: the hinges, then the beams.
    pub flexures: Vec<([f64; 2], [f64; 2], f64)>,
}

/// A planar flexure network described in a problem file.
#[derive(Debug, Clone)]
pub struct NetworkModel {
    description: Description,
    material: Material,
    actuator: Actuator,
    outputs: Vec<OutputInfo>,
    quantities: Vec<Quantity>,
    /// What each output needs ([`NetworkModel::needs`]): found once, a pass over the wanted
    /// outputs' quantities at each evaluation cost about 300 instructions.
    needs: Vec<Needs>,
    /// For each output, the outputs it is the maximum of.
    max_of: Vec<Option<Vec<usize>>>,
    fit: Vec<FitLimit>,
    /// Every expression of the description, compiled together (each [`Keyed::slot`]).
    tape: Tape,
    /// The same without what only the extent and the masses read (each body's outline past
    /// its first point, the links' widths, the ground's points) and the ports' constant
    /// directions: the statics' evaluations run this one.
    statics: Tape,
    /// Each hinge's registers of the sine and the cosine of its angle in `tape` and in
    /// `statics`, where the tape computes them for another expression (wei2017's
    /// `l2*cos(delta2)`): read there, not computed again for the hinge's axis.
    axes: [Vec<Option<(usize, usize)>>; 2],
    /// Each port's unit direction (input first) where its expressions are constants: the
    /// same numbers the scalars' normalization gives, found once.
    directions: Vec<Option<[f64; 2]>>,
    /// The degrees of freedom the mirror axes hold, sorted, the same at every design.
    held: Vec<(usize, Dof)>,
    /// Each port's read factor and load share (input first), the same at every design.
    read: Vec<f64>,
    share: Vec<f64>,
    /// Each expression's [`Role`], by its slot.
    roles: Vec<Role>,
    /// The part as its `[part]` section draws it, for the footprint outputs; `None` without
    /// one, and then they are unavailable.
    drawing: Option<Arc<Drawing>>,
    /// How the outputs at the working stroke are solved, where the file asks for them
    /// (`[analysis] deflection = "large"`).
    large: Option<LargeSettings>,
}

/// The linear network at one design (see [`NetworkModel::linear_at`]).
pub(super) struct LinearAt<D> {
    pub network: Network<D>,
    pub ports: Vec<Load<D>>,
    pub dims: Vec<Vec<D>>,
    pub read: Vec<f64>,
    pub share: Vec<f64>,
}

/// The network at one design, with its ports.
#[derive(Debug)]
struct Evaluated<D> {
    network: Network<D>,
    /// Input first, then the outputs: each a unit load at the port's point along its unit
    /// direction (`force`), which the load cases take as they are, without a copy.
    ports: Vec<Load<D>>,
    /// Every described point (m), for the extent and the masses: each body's first, from
    /// `offsets[b]`, then the ground's, the hinges' ends and the beams'.
    points: Vec<[D; 2]>,
    offsets: Vec<usize>,
    /// Each body's link width (m), where it is a link; kept with `points`.
    link_widths: Vec<Option<D>>,
    /// Each hinge's dimensions (SI), then each beam's length and thickness (a strip's).
    dims: Vec<Vec<D>>,
    measures: Vec<D>,
}

impl<D> Default for Evaluated<D> {
    fn default() -> Self {
        Evaluated {
            network: Network {
                references: Vec::new(),
                flexures: Vec::new(),
                springs: Vec::new(),
                held: Vec::new(),
                guides: Vec::new(),
            },
            ports: Vec::new(),
            points: Vec::new(),
            offsets: Vec::new(),
            link_widths: Vec::new(),
            dims: Vec::new(),
            measures: Vec::new(),
        }
    }
}

/// Everything one evaluation builds, its buffers kept from one design to the next on the
/// thread that evaluates ([`take`], [`give`]): a network of a few bodies costs otherwise
/// about as much in allocations as in arithmetic. The study shares the model across its
/// threads, so the buffers are the thread's, not the model's.
#[derive(Debug)]
struct Work<D> {
    values: Vec<D>,
    registers: Vec<D>,
    /// Whether each body's reference point (the first of its points met) is written yet:
    /// the points are written into the network's references in place, where a list of
    /// `Option`s of them was copied into it.
    placed: Vec<bool>,
    evaluated: Evaluated<D>,
    solve: SolveBuffers<D>,
    stresses: Vec<(D, D)>,
    /// The wanted outputs over `D`, for an evaluation with gradients.
    outputs: Vec<D>,
}

impl<D> Default for Work<D> {
    fn default() -> Self {
        Work {
            values: Vec::new(),
            registers: Vec::new(),
            placed: Vec::new(),
            evaluated: Evaluated::default(),
            solve: SolveBuffers::default(),
            stresses: Vec::new(),
            outputs: Vec::new(),
        }
    }
}

impl NetworkModel {
    /// The linear network at the design `x` (SI), its ports (input first, each a unit load
    /// along its direction), each flexure's dimensions (SI), and the ports' read factors and
    /// load shares: what the structure at stroke is built from ([`super::stroke`]).
    pub(super) fn linear_at<D: Scalar>(&self, x: &[D]) -> Result<LinearAt<D>, String> {
        let mut work = Work::<D>::default();
        self.at(x, None, false, &mut work)?;
        let e = work.evaluated;
        Ok(LinearAt {
            network: e.network,
            ports: e.ports,
            dims: e.dims,
            read: self.read.clone(),
            share: self.share.clone(),
        })
    }

    pub(super) fn material_and_actuator(&self) -> (&Material, &Actuator) {
        (&self.material, &self.actuator)
    }

    /// The description it was built from.
    pub(super) fn description(&self) -> &Description {
        &self.description
    }

    pub fn new(mut description: Description, material: Material, actuator: Actuator) -> Self {
        let mut roles = Vec::new();
        let tape = {
            let names = description.parameters.len() + 1;
            let mut all = expressions(&mut description);
            for (slot, (e, role)) in all.iter_mut().enumerate() {
                e.slot = slot;
                roles.push(*role);
            }
            Tape::compile(all.iter().map(|(e, _)| &e.expression), names)
        };
        let directions: Vec<Option<[f64; 2]>> = std::iter::once(&description.input)
            .chain(&description.outputs)
            .map(|p| {
                let [x, y] = &p.direction;
                let unit = description.unit;
                constant_direction(tape.constant(x.slot)? * unit, tape.constant(y.slot)? * unit)
            })
            .collect();
        let statics = {
            let d = &description;
            let mut unread = vec![false; roles.len()];
            let mut skip = |e: &Keyed| unread[e.slot] = true;
            for body in &d.bodies {
                body.points.iter().skip(1).flatten().for_each(&mut skip);
            }
            d.ground.iter().flatten().for_each(&mut skip);
            let ports = std::iter::once(&d.input).chain(&d.outputs);
            for (p, known) in ports.zip(&directions) {
                if known.is_some() {
                    p.direction.iter().for_each(&mut skip);
                }
            }
            tape.only(|slot| !unread[slot])
        };
        let named = Named::of(&description);
        let max_of = named.maxima();
        let Named {
            quantities,
            outputs,
        } = named;
        let d = &description;
        let mut held = axis_holds(d, None, &[]);
        held.extend(
            d.supports
                .iter()
                .filter(|g| g.hold_rotation)
                .map(|g| (g.body, Dof::Rotation)),
        );
        held.sort_by_key(|&(b, dof)| (b, dof as usize));
        held.dedup();
        let ports = || std::iter::once(&d.input).chain(&d.outputs);
        let read = ports()
            .map(|p| if p.across.is_some() { 2.0 } else { 1.0 })
            .collect();
        let share = ports()
            .map(|p| 0.5f64.powi(d.bodies[p.body].on_axis.len() as i32))
            .collect();
        let mut fit = Vec::new();
        for hinge in &d.hinges {
            // a range of fit binds a ratio of parameters: only where each dimension is one
            if let Some(index) = hinge
                .parameter_of
                .iter()
                .copied()
                .collect::<Option<Vec<_>>>()
            {
                let names: Vec<&str> = index
                    .iter()
                    .map(|&i| d.parameters[i].name.as_ref())
                    .collect();
                let owner = format!("hinge {} ({})", hinge.name, hinge.kind.name());
                fit.extend(hinge.kind.fit_limits(&owner, &index, &names));
            }
        }
        let needs = quantities
            .iter()
            .map(|&q| Needs::of(q, actuator.stiffness))
            .collect();
        let axes = [&tape, &statics].map(|t| {
            let hinges = description.hinges.iter();
            hinges.map(|h| t.sin_cos_of(h.angle.slot)).collect()
        });
        NetworkModel {
            description,
            material,
            actuator,
            outputs,
            needs,
            quantities,
            max_of,
            fit,
            axes,
            tape,
            statics,
            directions,
            held,
            read,
            share,
            roles,
            drawing: None,
            large: None,
        }
    }

    /// The model with its outputs at the working stroke too (`nl_...`), as `settings` says.
    pub fn with_large(self, settings: LargeSettings) -> Self {
        let mut named = Named {
            quantities: self.quantities,
            outputs: self.outputs,
        };
        named.at_stroke(&self.description);
        let needs = named
            .quantities
            .iter()
            .map(|&q| Needs::of(q, self.actuator.stiffness))
            .collect();
        NetworkModel {
            max_of: named.maxima(),
            needs,
            quantities: named.quantities,
            outputs: named.outputs,
            large: Some(settings),
            ..self
        }
    }

    /// Whether output `output` is one at the working stroke.
    pub(super) fn at_stroke_output(&self, output: usize) -> bool {
        self.quantities[output].at_stroke()
    }

    /// How the outputs at stroke are solved, where the model has them.
    pub(super) fn large_settings(&self) -> Option<LargeSettings> {
        self.large
    }

    /// The model with the part `drawing` draws, whose outline's box the footprint outputs
    /// read.
    pub fn with_drawing(self, drawing: Arc<Drawing>) -> Self {
        NetworkModel {
            drawing: Some(drawing),
            ..self
        }
    }

    /// The described part at the design `x` (SI) for its pictures; `None` where an
    /// expression fails there.
    pub(super) fn picture(&self, x: &[f64]) -> Option<Picture> {
        let mut work = Work::default();
        self.at(x, None, true, &mut work).ok()?;
        let e = &work.evaluated;
        let d = &self.description;
        let thickness = |h: usize| match d.hinges.get(h) {
            Some(hinge) => hinge.kind.least_thickness(&e.dims[h]),
            None => e.dims[h][1],
        };
        Some(Picture {
            bodies: e
                .offsets
                .windows(2)
                .map(|o| e.points[o[0]..o[1]].to_vec())
                .collect(),
            flexures: (e.network.flexures.iter().enumerate())
                .map(|(h, f)| (f.start, f.end, thickness(h)))
                .collect(),
        })
    }

    /// Whether the first output is written as the input: the same body and the same
    /// expressions for its point and direction (a guide's stage read where it is pushed).
    fn first_output_is_input(&self) -> bool {
        let (i, o) = (&self.description.input, &self.description.outputs[0]);
        let same = |a: &Point, b: &Point| {
            a.iter()
                .zip(b)
                .all(|(p, q)| p.expression.source() == q.expression.source())
        };
        i.body == o.body && same(&i.at, &o.at) && same(&i.direction, &o.direction)
    }

    /// What keeps the network from being solved, its body named as the file names it.
    fn network_error(&self, err: NetworkError) -> String {
        match err {
            NetworkError::Free { body, direction } => format!(
                "body \"{}\" ({}) is free to move ({direction}): nothing holds it against the \
                 ground",
                self.description.bodies[body].name, self.description.bodies[body].key
            ),
            NetworkError::Redundant { guide } => format!(
                "support {}: it holds a motion of body \"{}\" that is held already (by a \
                 support before it, or a mirror axis): remove it",
                self.description.supports[guide].key,
                self.description.bodies[self.description.supports[guide].body].name
            ),
            other => other.to_string(),
        }
    }
}

impl Model for NetworkModel {
    fn name(&self) -> &'static str {
        "network"
    }

    fn parameters(&self) -> &[ParameterInfo] {
        &self.description.parameters
    }

    fn outputs(&self) -> &[OutputInfo] {
        &self.outputs
    }

    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        if self.evaluate_generic(x, None, wanted, out).is_err() {
            out.fill(f64::NAN);
        }
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        with_count!(x.len(), |N| self.gradients::<N>(x, wanted, out, jacobian))
    }

    fn domain_error(&self, x: &[f64]) -> Option<String> {
        if let Some(why) =
            crate::model::check_parameters("network", &self.description.parameters, x, &[], &[])
        {
            return Some(why);
        }
        // the statics' outputs: the modes add an eigensolve and no condition of the design
        // that the statics do not check (every body's mass is checked once, by `unavailable`);
        // the footprint is the part's, whose own checks say where it cannot be made
        let all = self.available_but(|q| {
            matches!(
                q,
                Quantity::Frequency(_) | Quantity::PartWidth | Quantity::PartHeight
            )
        });
        let mut out = vec![0.0; all.len()];
        self.evaluate_generic(x, None, &all, &mut out)
            .and_then(|()| {
                // every expression, the outline's too, which the statics do not read
                let mut work = Work::default();
                self.at(x, None, true, &mut work)?;
                flexure_on_mirror_axis(&self.description, &work.evaluated.network.flexures)
                    .or_else(|| outline_crossing(&self.description, &work.evaluated))
                    .map_or(Ok(()), Err)
            })
            .err()
    }

    /// The description checked at the middle of the bounds: a hinge joined so that a body
    /// stays free, or an expression that fails there, is a fault of the file, not of one
    /// design.
    fn box_error(&self, lower: &[f64], upper: &[f64]) -> Option<(usize, String)> {
        let middle: Vec<f64> = lower
            .iter()
            .zip(upper)
            .map(|(a, b)| 0.5 * (a + b))
            .collect();
        if let Some(why) = self.domain_error(&middle) {
            let why = format!("the network has no value at the middle of the bounds: {why}");
            return Some((0, why));
        }
        let mut d = self.description.clone();
        let all: Vec<&Keyed> = expressions(&mut d).into_iter().map(|(e, _)| &*e).collect();
        let (parameters, unit) = (&self.description.parameters, self.description.unit);
        super::checks::derivative_error(&all, parameters, unit, &middle).map(|why| {
            let why = format!("the network has no gradient at the middle of the bounds: {why}");
            (0, why)
        })
    }

    fn max_of(&self, output: usize) -> Option<&[usize]> {
        self.max_of[output].as_deref()
    }

    fn unavailable(&self, output: usize) -> Option<String> {
        let held_input = match self.quantities[output] {
            Quantity::KOutBlocked => true,
            Quantity::KOutActuated | Quantity::BlockedForce => self.actuator.stiffness.is_none(),
            _ => false,
        };
        if held_input && self.first_output_is_input() {
            return Some(format!(
                "output \"{}\": the first output is the input (the same body, point and \
                 direction), which holding the input holds: its stiffness there is infinite",
                self.outputs[output].name
            ));
        }
        if matches!(
            self.quantities[output],
            Quantity::PartWidth | Quantity::PartHeight
        ) && self.drawing.is_none()
        {
            return Some(format!(
                "output \"{}\" is a size of the part's outline, which a [part] section draws: \
                 add one (or bound the described part with a [[network.measures]] entry)",
                self.outputs[output].name
            ));
        }
        let (Quantity::Frequency(i) | Quantity::AtStroke(AtStroke::Frequency(i))) =
            self.quantities[output]
        else {
            return None;
        };
        self.frequency_unavailable(i, &self.outputs[output].name)
    }

    fn material(&self) -> Option<&Material> {
        Some(&self.material)
    }

    fn angle_limit(&self) -> Option<f64> {
        None
    }

    /// Every angle negated, where that reflects the mechanism ([`NetworkModel::reflect`]).
    fn mirror(&self, x: &mut [f64]) -> bool {
        self.reflect(x)
    }

    fn fit_limits(&self) -> &[FitLimit] {
        &self.fit
    }
}
