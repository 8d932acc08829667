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
use std::borrow::Cow;
use std::cell::RefCell;
use std::convert::Infallible;

use super::description::{Axis, Description, HingeDescription, Keyed, Point};
use super::modes::{described_piece, DirectedMass, Inertia, ModeError};
use super::on_axis::flexure_on_mirror_axis;
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

/// The described part at one design (m), for its pictures ([`super::depiction`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Picture {
    /// Each body's points: its outline, or its link's two ends.
    pub bodies: Vec<Vec<[f64; 2]>>,
    /// Each flexure's start, end and least thickness: the hinges, then the beams.
    pub flexures: Vec<([f64; 2], [f64; 2], f64)>,
}

/// What an output is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Quantity {
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
    Measure(usize),
    /// The natural frequency of mode `i` (from 0).
    Frequency(usize),
}

/// What an evaluation's wanted outputs need ([`NetworkModel::needs`]).
#[derive(Debug, Clone, Copy, Default)]
struct Needs {
    /// How many natural frequencies, where any.
    modes: Option<usize>,
    /// The described points, for the spans or the masses.
    extent: bool,
    /// The input's load case.
    input: bool,
    /// The first output's load case.
    output: bool,
    /// The input's compliance condensed out of the output's (its case then read at the
    /// input too).
    condenses: bool,
    /// The hinges' end stresses.
    stresses: bool,
}

impl Needs {
    /// What output `q` needs, on an actuator of stiffness `actuator` where given.
    fn of(q: Quantity, actuator: Option<f64>) -> Self {
        use Quantity::*;
        Needs {
            modes: match q {
                Frequency(i) => Some(i + 1),
                _ => None,
            },
            extent: matches!(q, SpanX | SpanY),
            input: !matches!(q, SpanX | SpanY | Measure(_) | StrokeIn)
                || (q == StrokeIn && actuator.is_some()),
            output: matches!(q, KOut | KOutActuated | KOutBlocked | BlockedForce),
            condenses: matches!(q, KOutActuated | KOutBlocked | BlockedForce),
            stresses: matches!(q, StressMax | Stress(_) | StressEnd(..)),
        }
    }

    /// What both need.
    fn or(self, o: Self) -> Self {
        Needs {
            modes: self.modes.max(o.modes),
            extent: self.extent | o.extent,
            input: self.input | o.input,
            output: self.output | o.output,
            condenses: self.condenses | o.condenses,
            stresses: self.stresses | o.stresses,
        }
    }
}

/// How many natural frequencies the model names (`f1`, `f2`, ...).
const FREQUENCIES: usize = 3;

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
}

/// The linear network at one design (see [`NetworkModel::linear_at`]).
pub(super) struct LinearAt {
    pub network: Network<f64>,
    pub ports: Vec<Load<f64>>,
    pub dims: Vec<Vec<f64>>,
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

thread_local! {
    /// The thread's spare [`Work`]s, one per scalar type it evaluated with, each with its
    /// type's id: compared here, where asking each box for its type was a virtual call.
    static SPARE: RefCell<Vec<(TypeId, Box<dyn Any>)>> = const { RefCell::new(Vec::new()) };
}

/// The thread's spare [`Work`] for `D`, or a new one. Taken out rather than borrowed, so
/// that an evaluation inside another (none today) would only allocate its own.
fn take<D: 'static>() -> Box<Work<D>> {
    let id = TypeId::of::<Work<D>>();
    SPARE
        .with(|spare| {
            let mut spare = spare.borrow_mut();
            let i = spare.iter().position(|(t, _)| *t == id)?;
            spare.swap_remove(i).1.downcast().ok()
        })
        .unwrap_or_default()
}

/// `work` back among the thread's spares.
fn give<D: 'static>(work: Box<Work<D>>) {
    SPARE.with(|spare| spare.borrow_mut().push((TypeId::of::<Work<D>>(), work)));
}

impl NetworkModel {
    /// The description it was built from.
    /// The linear network at the design `x` (SI), its ports (input first, each a unit load
    /// along its direction), each flexure's dimensions (SI), and the ports' read factors and
    /// load shares: what the structure at stroke is built from ([`super::stroke`]).
    pub(super) fn linear_at(&self, x: &[f64]) -> Result<LinearAt, String> {
        let mut work = Work::<f64>::default();
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
        let mut outputs = Vec::new();
        let mut quantities = Vec::new();
        let d = &description;
        let mut add = |q: Quantity, name: String, dim: Dimension, what: String| {
            quantities.push(q);
            outputs.push(OutputInfo {
                name: Cow::Owned(name),
                dimension: dim,
                description: Cow::Owned(what),
                display: None,
                stand_in: None,
            });
        };
        let first = &d.outputs[0].name;
        add(
            Quantity::Amplification(0),
            "amplification".into(),
            Dimension::Ratio,
            format!("motion of output \"{first}\" over the input's (W_oi / W_ii)"),
        );
        for (o, p) in d.outputs.iter().enumerate().skip(1) {
            add(
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
            add(q, name.into(), dim, what);
        }
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
            add(
                Quantity::Stress(h),
                format!("stress_{name}"),
                Stress,
                format!("largest stress in {what} ({kind})"),
            );
        }
        for (h, (name, what)) in members.iter().enumerate() {
            for (to, end) in [(false, "from"), (true, "to")] {
                add(
                    Quantity::StressEnd(h, to),
                    format!("stress_{name}_{end}"),
                    Stress,
                    format!("stress in {what} at its end on its `{end}` body"),
                );
            }
        }
        for (h, (name, what)) in members.iter().enumerate() {
            add(
                Quantity::Rotation(h),
                format!("rotation_{name}"),
                Angle,
                format!("rotation of {what} (its `to` end against its `from` end) under the largest actuator force"),
            );
        }
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
            add(q, name, Length, what);
        }
        for (i, m) in d.measures.iter().enumerate() {
            if m.name != "span_x" && m.name != "span_y" {
                add(
                    Quantity::Measure(i),
                    m.name.clone(),
                    m.dimension,
                    format!("`{}`", m.value.expression.source()),
                );
            }
        }
        for i in 0..FREQUENCIES {
            add(
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
        let max_of = quantities
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
            .collect();
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
        }
    }

    /// The value of every expression of the description at the design `x` (SI), by slot;
    /// `None` where one has none.
    fn expression_values(&self, x: &[f64]) -> Option<Vec<f64>> {
        let mut work = Work::default();
        let Work {
            values, registers, ..
        } = &mut work;
        let unit = self.description.unit;
        values.extend(x.iter().zip(&self.description.parameters).map(|(&v, p)| {
            if p.dimension == Dimension::Length {
                v * unit.recip()
            } else {
                v
            }
        }));
        values.push(std::f64::consts::PI / 180.0);
        self.tape.run(values, registers).then(|| {
            (0..self.roles.len())
                .map(|slot| registers[self.tape.output(slot)])
                .collect()
        })
    }

    /// The network and its ports at the design `x` (SI, every parameter) into
    /// `work.evaluated`: the expressions from the tape, or where it fails, from their trees,
    /// which say which one and why.
    fn at<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        extent: bool,
        work: &mut Work<D>,
    ) -> Result<(), String> {
        let d = &self.description;
        let unit = d.unit;
        let Work {
            values,
            registers,
            placed,
            evaluated,
            ..
        } = work;
        // the parameters in the expressions' units, then `deg`, written into the tape's
        // registers
        let tape = if extent { &self.tape } else { &self.statics };
        let inputs = tape.inputs_mut(registers);
        let (deg, named) = inputs.split_last_mut().expect("`deg` is a name");
        for ((slot, &v), p) in named.iter_mut().zip(x).zip(&d.parameters) {
            *slot = if p.dimension == Dimension::Length {
                v * unit.recip()
            } else {
                v
            };
        }
        *deg = D::from(std::f64::consts::PI / 180.0);
        if tape.run_in(registers) {
            let registers = &*registers;
            let axes = &self.axes[usize::from(!extent)];
            self.build(
                modulus,
                extent,
                |e: &Keyed| Ok::<_, Infallible>(registers[tape.output(e.slot)]),
                |h| axes[h].map(|(sin, cos)| [registers[cos], registers[sin]]),
                evaluated,
                placed,
            )
        } else {
            // the trees read the names' values, which the tape has kept
            values.clear();
            values.extend_from_slice(&registers[..tape.inputs()]);
            let values = &*values;
            self.build(
                modulus,
                extent,
                |e: &Keyed| {
                    e.expression
                        .eval(values)
                        .map_err(|err| format!("{} = \"{}\": {err}", e.key, e.expression.source()))
                },
                |_| None,
                evaluated,
                placed,
            )
        }
    }

    /// [`NetworkModel::at`] with each expression's value from `eval`, into `out`'s buffers;
    /// the described points for the extent only if `extent`. The tape's `eval` cannot fail
    /// (`E` is [`Infallible`]): its values then pass through no `Result`, whose moves of
    /// `[Jet<8>; 2]` were a copy each.
    fn build<D: Scalar, E: Message>(
        &self,
        modulus: Option<D>,
        extent: bool,
        eval: impl Fn(&Keyed) -> Result<D, E>,
        axis: impl Fn(usize) -> Option<[D; 2]>,
        out: &mut Evaluated<D>,
        placed: &mut Vec<bool>,
    ) -> Result<(), String> {
        let d = &self.description;
        let unit = d.unit;
        let raw = &eval;
        let eval = |e: &Keyed| raw(e).map_err(Message::message);
        let length = |e: &Keyed| raw(e).map(|v| v * unit);
        let point = |p: &Point| -> Result<[D; 2], E> { Ok([length(&p[0])?, length(&p[1])?]) };
        // written in place: a point returned was a `memcpy` of two `Jet<8>`s
        let point_into = |p: &Point, out: &mut [D; 2]| -> Result<(), String> {
            out[0] = length(&p[0]).map_err(Message::message)?;
            out[1] = length(&p[1]).map_err(Message::message)?;
            Ok(())
        };
        let Evaluated {
            network,
            ports,
            points,
            offsets,
            link_widths,
            dims,
            measures,
        } = out;
        points.clear();
        offsets.clear();
        link_widths.clear();
        placed.clear();
        placed.resize(d.bodies.len(), false);
        let references = &mut network.references;
        if references.len() != d.bodies.len() {
            references.clear();
            references.resize(d.bodies.len(), [D::from(0.0); 2]);
        }
        for (b, body) in d.bodies.iter().enumerate() {
            // read by the statics too: a design that leaves a link no width has no value
            let width = body
                .link_width
                .as_ref()
                .map(|w| length(w).map_err(Message::message))
                .transpose()?;
            if let (Some(w), Some(keyed)) = (width, &body.link_width) {
                if w.re() <= 0.0 || w.re().is_nan() {
                    return Err(not_positive(&body.name, &keyed.key, "width", w.re()));
                }
            }
            if extent {
                offsets.push(points.len());
                link_widths.push(width);
            }
            // the statics read a body's first point alone, its reference
            if let Some(p) = body.points.first() {
                point_into(p, &mut references[b])?;
                placed[b] = true;
                if extent {
                    points.push(references[b]);
                    for p in &body.points[1..] {
                        points.push(point(p).map_err(Message::message)?);
                    }
                }
            }
        }
        if extent {
            offsets.push(points.len());
        }
        if extent {
            for p in &d.ground {
                points.push(point(p).map_err(Message::message)?);
            }
        }
        // each flexure written into its slot (a `Flexure` of `Jet<8>`s is 648 bytes, which
        // built and then pushed was copied twice)
        let count = d.hinges.len() + d.beams.len();
        if network.flexures.len() != count {
            network.flexures.clear();
            network.flexures.resize(count, idle_flexure());
        }
        dims.resize_with(count, Vec::new);
        for (i, ((h, dd), f)) in d
            .hinges
            .iter()
            .zip(dims.iter_mut())
            .zip(&mut network.flexures)
            .enumerate()
        {
            dd.clear();
            for (e, info) in h.dimensions.iter().zip(h.kind.dimensions()) {
                dd.push(if info.dimension == Dimension::Length {
                    length(e).map_err(Message::message)?
                } else {
                    eval(e)?
                });
            }
            if let Some(why) = domain_error(h, dd) {
                return Err(format!("hinge \"{}\": {why}", h.name));
            }
            f.from = h.from.map_or(Body::Ground, Body::Rigid);
            f.to = h.to.map_or(Body::Ground, Body::Rigid);
            point_into(&h.start, &mut f.start)?;
            f.axis = match axis(i) {
                Some(axis) => axis,
                None => {
                    let (s, c) = eval(&h.angle)?.sin_cos();
                    [c, s]
                }
            };
            f.length = h.kind.length(dd);
            if f.length.re() <= 0.0 || f.length.re().is_nan() {
                return Err(not_positive(&h.name, &h.key, "length", f.length.re()));
            }
            f.end = end_of(&f.start, &f.axis, f.length);
            hinge_compliance(h.kind, dd, d.width, &self.material, &mut f.compliance);
            join(
                f,
                modulus,
                references,
                placed,
                extent.then_some(&mut *points),
            );
        }
        let beams = d.beams.iter().zip(dims[d.hinges.len()..].iter_mut());
        for ((b, dd), f) in beams.zip(&mut network.flexures[d.hinges.len()..]) {
            let start = point(&b.start).map_err(Message::message)?;
            let end = point(&b.end).map_err(Message::message)?;
            let thickness = length(&b.thickness).map_err(Message::message)?;
            let (dx, dy) = (end[0] - start[0], end[1] - start[1]);
            let l = (dx * dx + dy * dy).sqrt();
            if l.re() == 0.0 {
                return Err(format!(
                    "beam \"{}\" ({}): its start and end are the same point",
                    b.name, b.key
                ));
            }
            if thickness.re() <= 0.0 || !thickness.re().is_finite() {
                return Err(format!(
                    "beam \"{}\" ({}.thickness): the thickness {} m is not positive",
                    b.name,
                    b.key,
                    thickness.re()
                ));
            }
            dd.clear();
            dd.push(l);
            dd.push(thickness);
            *f = Flexure::new(
                b.from.map_or(Body::Ground, Body::Rigid),
                b.to.map_or(Body::Ground, Body::Rigid),
                start,
                [dx / l, dy / l],
                l,
                beam_compliance(l, thickness, d.width, &self.material),
            );
            join(
                f,
                modulus,
                references,
                placed,
                extent.then_some(&mut *points),
            );
        }
        network.held.clear();
        network.held.extend_from_slice(&self.held);
        network.springs.clear();
        network.guides.clear();
        for g in &d.supports {
            let [dx, dy] = point(&g.direction).map_err(Message::message)?;
            let norm = (dx * dx + dy * dy).sqrt();
            if norm.re() == 0.0 || !norm.re().is_finite() {
                return Err(format!(
                    "support ({}.direction): its direction is zero",
                    g.key
                ));
            }
            network.guides.push(Guide {
                body: g.body,
                point: point(&g.at).map_err(Message::message)?,
                direction: [dx / norm, dy / norm],
            });
        }
        assert!(
            placed.iter().all(|&p| p),
            "every body has a hinge or a beam, whose end is a point of it"
        );
        // written in place, as the flexures
        if ports.len() != self.directions.len() {
            let zero = D::from(0.0);
            ports.clear();
            ports.resize(
                self.directions.len(),
                Load {
                    body: 0,
                    point: [zero; 2],
                    force: [zero; 2],
                    moment: zero,
                },
            );
        }
        let described = std::iter::once(&d.input).chain(&d.outputs);
        for ((p, known), port) in described.zip(&self.directions).zip(ports.iter_mut()) {
            port.force = match known {
                Some(unit) => unit.map(D::from),
                None => {
                    let [dx, dy] = point(&p.direction).map_err(Message::message)?;
                    let norm = (dx * dx + dy * dy).sqrt();
                    if norm.re() == 0.0 {
                        return Err(format!("port \"{}\": its direction is zero", p.name));
                    }
                    [dx / norm, dy / norm]
                }
            };
            port.body = p.body;
            point_into(&p.at, &mut port.point)?;
        }
        measures.clear();
        for m in &d.measures {
            let v = eval(&m.value)?;
            measures.push(if m.dimension == Dimension::Length {
                v * unit
            } else {
                v
            });
        }
        Ok(())
    }

    /// The wanted outputs at `x` into `out`, or why the design has none.
    pub fn evaluate_generic<D: Scalar + 'static>(
        &self,
        x: &[D],
        modulus: Option<D>,
        wanted: &[usize],
        out: &mut [D],
    ) -> Result<(), String> {
        let mut work = take::<D>();
        let result = self.evaluate_in(x, modulus, wanted, out, &mut work);
        give(work);
        result
    }

    /// [`NetworkModel::evaluate_generic`] in the buffers of `work`.
    fn evaluate_in<D: Scalar>(
        &self,
        x: &[D],
        modulus: Option<D>,
        wanted: &[usize],
        out: &mut [D],
        work: &mut Work<D>,
    ) -> Result<(), String> {
        let Needs {
            modes,
            extent,
            input: needs_input,
            output: needs_output,
            condenses,
            stresses: needs_stresses,
        } = self.needs(wanted);
        self.at(x, modulus, extent, work)?;
        let Work {
            evaluated: e,
            solve,
            stresses,
            ..
        } = work;
        let e = &*e;
        let free = |err| self.network_error(err);
        use Quantity::*;
        // read in place: a port copied out of the list, or into a load, was a `memcpy`
        let along = |u: &Displacements<D>, i: usize| {
            let p = &e.ports[i];
            u.along_ref(Body::Rigid(p.body), &p.point, &p.force)
        };
        // the load cases wanted, from one factorization: the input's, the first output's
        let (load_in, load_out) = (
            std::slice::from_ref(&e.ports[0]),
            std::slice::from_ref(&e.ports[1]),
        );
        // the output's case is read at the output alone, or at the input too where the
        // input's compliance is condensed out
        let port_bodies = [e.ports[1].body, e.ports[0].body];
        let read_out = &port_bodies[..if condenses { 2 } else { 1 }];
        let mut cases = [Case {
            loads: &[],
            read: None,
        }; 2];
        let mut count = 0;
        for (needed, loads, read) in [
            (needs_input, load_in, None),
            (needs_output, load_out, Some(read_out)),
        ] {
            if needed {
                cases[count] = Case { loads, read };
                count += 1;
            }
        }
        let solved = if count == 0 {
            None
        } else {
            Some(
                e.network
                    .solve_cases_in(&cases[..count], solve)
                    .map_err(free)?,
            )
        };
        let case = |c: usize| solved.as_ref().map(|s| s.case(c));
        let input: Option<Displacements<D>> = if needs_input { case(0) } else { None };
        let output: Option<Displacements<D>> = if needs_output { case(count - 1) } else { None };
        // W_ij = read_i C_ij share_j
        let w =
            |u: &Displacements<D>, i: usize, j: usize| along(u, i) * (self.read[i] * self.share[j]);
        let w_ii = input.as_ref().map(|u| w(u, 0, 0));
        let k_in = || w_ii.expect("listed").recip();
        let stroke_in = || match self.actuator.stiffness {
            None => D::from(self.actuator.nominal_stroke),
            Some(k_a) => {
                let ka = w_ii.expect("listed") * k_a;
                ka * self.actuator.nominal_stroke / (ka + 1.0)
            }
        };
        let amplification = |o: usize| {
            let u = input.as_ref().expect("listed");
            w(u, o + 1, 0) / w_ii.expect("listed")
        };
        // the first output's stiffnesses: the input free, on the actuator, held
        let condensed = |actuator: Option<f64>| {
            let (u_in, u_out) = (
                input.as_ref().expect("listed"),
                output.as_ref().expect("listed"),
            );
            let (c_oo, c_oi, c_io) = (w(u_out, 1, 1), w(u_in, 1, 0), w(u_out, 0, 1));
            let c_ii = w(u_in, 0, 0) + actuator.map_or(0.0, f64::recip);
            (c_oo - c_oi * c_io / c_ii).recip()
        };
        // the hinges' loads and stresses under the largest actuator force, found once: at
        // the true stroke (Eq. 13), which a stack of finite stiffness makes under the part
        let largest = w_ii.map(|w| w.recip() * stroke_in() + self.actuator.preload);
        // the described part's share of it, once for every flexure
        let shared = largest.map(|f| f * self.share[0]);
        let loads = |h: usize| {
            let u = input.as_ref().expect("listed");
            let l = e.network.flexure_loads(h, u);
            let f = shared.expect("listed");
            HingeLoads {
                axial: l.axial * f,
                shear: l.shear * f,
                moment: l.moment * f,
            }
        };
        let flexures = e.network.flexures.len();
        let ends = |h: usize| {
            // a beam's stresses are a strip's: the same beam, the same linear moment
            let kind = self
                .description
                .hinges
                .get(h)
                .map_or(HingeKind::Strip, |hinge| hinge.kind);
            // (loaded end, clamped end): the loads are at its end on `to`
            let (to, from) = kind.end_stresses(&e.dims[h], self.description.width, &loads(h));
            (from, to)
        };
        // each hinge's two end stresses once, however many outputs read them
        stresses.clear();
        if needs_stresses {
            stresses.extend((0..flexures).map(ends));
        }
        let stresses = &*stresses;
        // read in place: the pair copied out was two `Jet<8>`s for one
        let ends = |h: usize| &stresses[h];
        let extent = |i: usize| {
            let hi = e
                .points
                .iter()
                .skip(1)
                .fold(e.points[0][i], |m, p| max(m, p[i]));
            let lo = e
                .points
                .iter()
                .skip(1)
                .fold(-e.points[0][i], |m, p| max(m, -p[i]));
            hi + lo
        };
        let frequencies = match modes {
            Some(count) => self.frequencies(e, count)?,
            None => Vec::new(),
        };
        for (&k, slot) in wanted.iter().zip(out.iter_mut()) {
            *slot = match self.quantities[k] {
                Amplification(o) => amplification(o),
                KIn => k_in(),
                KOut => w(output.as_ref().expect("listed"), 1, 1).recip(),
                KOutActuated => condensed(self.actuator.stiffness),
                KOutBlocked => condensed(None),
                StrokeIn => stroke_in(),
                StrokeOut => amplification(0) * stroke_in(),
                BlockedForce => amplification(0) * stroke_in() * condensed(self.actuator.stiffness),
                StressMax => (0..flexures)
                    .map(|h| {
                        let (a, b) = *ends(h);
                        max(a, b)
                    })
                    .reduce(max)
                    .unwrap_or(D::from(0.0)),
                Stress(h) => {
                    let (a, b) = *ends(h);
                    max(a, b)
                }
                StressEnd(h, to) => {
                    let (a, b) = ends(h);
                    if to {
                        *b
                    } else {
                        *a
                    }
                }
                Rotation(h) => {
                    let u = input.as_ref().expect("listed");
                    let f = &e.network.flexures[h];
                    let turn = u.at(f.to, f.end)[2] - u.at(f.from, f.start)[2];
                    turn * shared.expect("listed")
                }
                SpanX => extent(0),
                SpanY => extent(1),
                Measure(m) => e.measures[m],
                Frequency(i) => frequencies[i],
            };
            if !slot.re().is_finite() {
                return Err(format!(
                    "output \"{}\" is not finite at this design",
                    self.outputs[k].name
                ));
            }
        }
        Ok(())
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

    /// What the `wanted` outputs need.
    fn needs(&self, wanted: &[usize]) -> Needs {
        let mut n = wanted
            .iter()
            .fold(Needs::default(), |n, &w| n.or(self.needs[w]));
        n.extent |= n.modes.is_some();
        n
    }

    /// How many modes [`Self::frequencies`] finds: the degrees of freedom of the described
    /// part in each family of modes ([`families`]), or of the whole about the axis its
    /// mounting stands across.
    fn mode_dofs(&self) -> usize {
        let d = &self.description;
        let mounting = self.mounting();
        let line = mounting.map(|(_, line)| line);
        let mount = mounting.map(|(port, _)| {
            if port == 0 {
                d.input.body
            } else {
                d.outputs[0].body
            }
        });
        let mut dofs = 0;
        for anti in families(&self.family_axes()) {
            let held = axis_holds(d, line, &anti);
            dofs += 3 * d.bodies.len() - held.len();
            if let (Some(line), Some(mount)) = (line, mount) {
                for (b, body) in d.bodies.iter().enumerate() {
                    if b != mount && !body.on_axis.contains(&line) {
                        dofs += 3 - held.iter().filter(|h| h.0 == b).count();
                    }
                }
            }
        }
        dofs
    }

    /// The mirror axes the modes are symmetric or antisymmetric about: every one, but that
    /// the part stands across ([`Self::mounting`]), about which it is unfolded whole.
    fn family_axes(&self) -> Vec<Axis> {
        let line = self.mounting().map(|(_, line)| line);
        let d = &self.description;
        d.mirror
            .iter()
            .copied()
            .filter(|&a| Some(a) != line)
            .collect()
    }

    /// Whether a hinge or a beam joins the ground.
    fn grounded(&self) -> bool {
        let d = &self.description;
        d.hinges.iter().any(|h| h.from.is_none() || h.to.is_none())
            || d.beams.iter().any(|b| b.from.is_none() || b.to.is_none())
    }

    /// The port whose image across its axis holds a part with mirror axes and no ground:
    /// the first output's, else the input's, as the part's check clamps it. `None` where
    /// the ground holds the part, or there are no mirror axes.
    fn mounting(&self) -> Option<(usize, Axis)> {
        let d = &self.description;
        if d.mirror.is_empty() || self.grounded() {
            return None;
        }
        d.outputs[0]
            .across
            .map(|a| (1, a))
            .or(d.input.across.map(|a| (0, a)))
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

    /// The `count` lowest natural frequencies of the network `e` (Hz): each body a plate of
    /// the material's density and the part's width cut to its outline or its link, the
    /// first output's payload at its point, the actuator a spring to the ground at the
    /// input along its direction (the stack's far end on the base), the flexures massless
    /// ([`super::modes`]). [`Model::unavailable`] has checked that every body has a shape
    /// and that the part has a mounting.
    ///
    /// With mirror axes the described part carries its share of each body across an axis
    /// ([`described_piece`]), and the modes are found family by family ([`families`]): those
    /// symmetric about every axis, then those antisymmetric about one or both, each family
    /// its own holds on the bodies across the axes ([`axis_holds`]); the lowest `count` of
    /// all are the whole part's. The stack, between the input's face and its image across
    /// `network.input.across`, is not stretched in a mode antisymmetric about that axis (the
    /// two faces move alike), and is left out of those families. A grounded part's payload
    /// rides on each image of the first output's face. A part without ground stands on the
    /// image of a port across an axis ([`Self::mounting`]), which breaks the symmetry about
    /// that axis: the described part is joined to its image across it, that port's image the
    /// ground ([`Network::unfolded`]), the payload on the port's face alone, and the
    /// families are those about the other axis.
    fn frequencies<D: Scalar>(&self, e: &Evaluated<D>, count: usize) -> Result<Vec<D>, String> {
        let d = &self.description;
        let (density, width) = (self.material.density, d.width);
        let mounting = self.mounting();
        let mut inertia: Vec<Inertia<D>> = d
            .bodies
            .iter()
            .enumerate()
            .map(|(b, body)| {
                let points = &e.points[e.offsets[b]..e.offsets[b + 1]];
                let axes: Vec<bool> = body.on_axis.iter().map(|a| *a == Axis::X).collect();
                match e.link_widths[b] {
                    Some(t) if axes.is_empty() => {
                        Inertia::link(points[0], points[1], t, density, width)
                    }
                    Some(t) => {
                        let band = link_band(points[0], points[1], t);
                        Inertia::polygon(&described_piece(&band, &axes), density, width)
                    }
                    None if points.len() >= 3 => {
                        Inertia::polygon(&described_piece(points, &axes), density, width)
                    }
                    None => Inertia {
                        mass: D::from(0.0),
                        centroid: e.network.references[b],
                        moment: D::from(0.0),
                    },
                }
            })
            .collect();
        // each beam's mass lumped at its ends, half to each body (the consistent mass of a
        // frame element would couple the bodies; the lumped one keeps them apart, and is
        // close while a beam weighs little against the bodies it joins)
        let flexures = e.network.flexures[d.hinges.len()..].iter();
        for ((b, f), dims) in d.beams.iter().zip(flexures).zip(&e.dims[d.hinges.len()..]) {
            let half = dims[0] * dims[1] * (0.5 * density * width);
            for (body, at) in [(b.from, f.start), (b.to, f.end)] {
                if let Some(body) = body {
                    inertia[body] = inertia[body].with_point_mass(half, at);
                }
            }
        }
        let stack = self.actuator.stiffness.map(|k| {
            let port = &e.ports[0];
            Spring {
                body: port.body,
                point: port.point,
                direction: port.force,
                stiffness: D::from(k * self.read[0] * self.share[0]),
            }
        });
        let line = mounting.map(|(_, line)| line);
        let mut found: Vec<D> = Vec::new();
        // a body across an axis is held at its point on the axis: in a mode antisymmetric
        // about it, it turns about that point, and a hold of its motion along the axis at a
        // reference off it would turn it about the reference instead (in a symmetric mode it
        // neither turns nor moves across, and the reference does not matter)
        let mut on_axes = e.network.clone();
        for (b, body) in d.bodies.iter().enumerate() {
            for a in &body.on_axis {
                match a {
                    Axis::X => on_axes.references[b][1] = D::from(0.0),
                    Axis::Y => on_axes.references[b][0] = D::from(0.0),
                }
            }
        }
        for anti in families(&self.family_axes()) {
            let mut network = on_axes.clone();
            let held = axis_holds(d, line, &anti);
            let stretched = !d.input.across.is_some_and(|a| anti.contains(&a));
            network.springs.extend(stack.filter(|_| stretched));
            let mut directed = self.stack_masses(e, stretched);
            let mut inertia = inertia.clone();
            let mut payload_share = self.share[1];
            let mut images = Vec::new();
            if let Some((port, line)) = mounting {
                let flip_y = line == Axis::X;
                let across: Vec<bool> =
                    d.bodies.iter().map(|b| b.on_axis.contains(&line)).collect();
                let (whole, image) = network.unfolded(flip_y, &across, &held, e.ports[port].body);
                for (b, im) in image.iter().enumerate() {
                    match *im {
                        Body::Rigid(i) if i == b => inertia[b] = inertia[b].doubled(flip_y),
                        Body::Rigid(_) => inertia.push(inertia[b].reflected(flip_y)),
                        Body::Ground => {}
                    }
                }
                if across[d.outputs[0].body] {
                    payload_share *= 2.0;
                }
                directed = DirectedMass::unfolded(&directed, &image, flip_y);
                network = whole;
                images = image;
            } else {
                network.held = held;
            }
            let (body, at) = (e.ports[1].body, e.ports[1].point);
            inertia[body] = inertia[body].with_point_mass(d.outputs[0].payload * payload_share, at);
            let family = || {
                if anti.is_empty() {
                    String::new()
                } else {
                    let names: Vec<&str> = anti.iter().map(|a| a.name()).collect();
                    format!(
                        " in the modes antisymmetric about the {} axis",
                        names.join(" and ")
                    )
                }
            };
            let modes =
                network
                    .modes_with(&inertia, &directed, count)
                    .map_err(|err| match err {
                        ModeError::Network(err) => {
                            format!("{}{}", self.network_error(err), family())
                        }
                        ModeError::Massless { body } => {
                            // an image is named by the body it images
                            let b = (0..d.bodies.len())
                                .find(|&b| body == b || images.get(b) == Some(&Body::Rigid(body)))
                                .unwrap_or(0);
                            format!(
                                "body \"{}\" ({}) has no mass where it can move{}",
                                d.bodies[b].name,
                                d.bodies[b].key,
                                family()
                            )
                        }
                    })?;
            found.extend(modes.into_iter().map(|m| m.frequency));
        }
        if found.len() < count {
            return Err(format!(
                "the network has {} modes; f{count} asks for more",
                found.len()
            ));
        }
        // by value, the families' order breaking ties, so that the same design gives the
        // same order
        found.sort_by(|a, b| a.re().total_cmp(&b.re()));
        found.truncate(count);
        Ok(found)
    }

    /// The stack's own mass (`[actuator] mass`) on the input port, the described part's
    /// share of it, in the family of modes where the stack is `stretched` or not
    /// ([`DirectedMass::stack`]).
    fn stack_masses<D: Scalar>(&self, e: &Evaluated<D>, stretched: bool) -> Vec<DirectedMass<D>> {
        let Some(mass) = self.actuator.mass.filter(|&m| m > 0.0) else {
            return Vec::new();
        };
        let port = &e.ports[0];
        let mirrored = self.read[0] > 1.0;
        DirectedMass::stack(
            mass * self.share[0],
            (mirrored, stretched),
            port.body,
            port.point,
            port.force,
        )
        .to_vec()
    }

    fn gradients<const N: usize>(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let seeded: [Jet<N>; N] = std::array::from_fn(|i| Jet::variable(x[i], i));
        let mut work = take::<Jet<N>>();
        // the outputs' buffer is the thread's too: allocated for each evaluation, it cost
        // about as much as the seeding and the unseeding together
        let mut y = std::mem::take(&mut work.outputs);
        // zeroed only when the count changes: the evaluation writes every slot it returns
        if y.len() != wanted.len() {
            y.clear();
            y.resize(wanted.len(), Jet::from(0.0));
        }
        if self
            .evaluate_in(&seeded, None, wanted, &mut y, &mut work)
            .is_ok()
        {
            unseed(&y, out, jacobian);
        } else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
        }
        work.outputs = y;
        give(work);
    }
}

/// `f` joined to the network, its compliance at the evaluation's modulus where one is given:
/// its ends the reference points of the bodies that have none yet, and among the described
/// `points` when they are kept.
fn join<D: Scalar>(
    f: &mut Flexure<D>,
    modulus: Option<D>,
    references: &mut [[D; 2]],
    placed: &mut [bool],
    points: Option<&mut Vec<[D; 2]>>,
) {
    if let Some(m) = modulus {
        f.compliance = f.compliance.with_modulus(m);
    }
    for (body, p) in [(f.from, &f.start), (f.to, &f.end)] {
        if let Body::Rigid(b) = body {
            if !placed[b] {
                references[b] = *p;
                placed[b] = true;
            }
        }
    }
    if let Some(points) = points {
        points.push(f.start);
        points.push(f.end);
    }
}

/// Hinge `kind`'s compliance at `dims` (SI) into `out`: where the scalar is a number of first
/// derivatives alone and the kind has its partial derivatives in closed form, its tangent
/// is their chain rule, a few products a coefficient where the formula's every operation
/// over the number was one; elsewhere the kind's formula over the scalar. The values are
/// the formula's, bit for bit, either way.
#[inline(always)]
fn hinge_compliance<D: Scalar>(
    kind: HingeKind,
    dims: &[D],
    width: f64,
    material: &Material,
    out: &mut Compliance<D>,
) {
    if D::FROM_PARTIALS && dims.len() <= MAX_HINGE_DIMENSIONS {
        let mut plain = [0.0; MAX_HINGE_DIMENSIONS];
        for (p, v) in plain.iter_mut().zip(dims) {
            *p = v.re();
        }
        if let Some((c, by)) = kind.compliance_partials(&plain[..dims.len()], width, material) {
            let n = dims.len();
            let chain = |re: f64, pick: fn(&Compliance<f64>) -> f64| {
                let partials: [f64; MAX_HINGE_DIMENSIONS] = std::array::from_fn(|k| pick(&by[k]));
                D::from_partials(re, dims, &partials[..n])
            };
            out.c11 = chain(c.c11, |c| c.c11);
            out.c22 = chain(c.c22, |c| c.c22);
            out.c23 = chain(c.c23, |c| c.c23);
            out.c33 = chain(c.c33, |c| c.c33);
            return;
        }
    }
    *out = kind.compliance(dims, width, material);
}

/// A flexure of zeros, for a slot that each evaluation overwrites.
fn idle_flexure<D: Scalar>() -> Flexure<D> {
    let zero = D::from(0.0);
    Flexure {
        from: Body::Ground,
        to: Body::Ground,
        start: [zero; 2],
        axis: [zero; 2],
        length: zero,
        end: [zero; 2],
        compliance: Compliance {
            c11: zero,
            c22: zero,
            c23: zero,
            c33: zero,
        },
    }
}

/// The unit direction `(dx, dy)` (m) where a scalar's normalization, by a reciprocal or by
/// a division, gives the same numbers (both give them for an axis): `None` where they
/// differ or the direction is zero, and the scalars normalize it at each evaluation.
fn constant_direction(dx: f64, dy: f64) -> Option<[f64; 2]> {
    let norm = (dx * dx + dy * dy).sqrt();
    if norm == 0.0 || !norm.is_finite() {
        return None;
    }
    let inv = 1.0 / norm;
    let (by_reciprocal, by_division) = ([dx * inv, dy * inv], [dx / norm, dy / norm]);
    (by_reciprocal == by_division).then_some(by_division)
}

/// The message of an expression's failure: the trees' own, or none from the tape.
trait Message {
    fn message(self) -> String;
}

impl Message for String {
    fn message(self) -> String {
        self
    }
}

impl Message for Infallible {
    fn message(self) -> String {
        match self {}
    }
}

/// The degrees of freedom the mirror axes hold (all but `except`), sorted, in the modes
/// symmetric about every axis but those `antisymmetric`. A body across an axis keeps, in
/// a motion symmetric about it, its motion across the axis and its rotation at zero; in one
/// antisymmetric about it, its motion along the axis (the field at a point's image is
/// minus the point's reflected, which on the axis leaves the motion across it and the
/// turn free). The statics' loads are symmetric: `antisymmetric` empty.
fn axis_holds(d: &Description, except: Option<Axis>, antisymmetric: &[Axis]) -> Vec<(usize, Dof)> {
    let mut held = Vec::new();
    for (b, body) in d.bodies.iter().enumerate() {
        for a in body.on_axis.iter().filter(|&&a| Some(a) != except) {
            let (across, along) = match a {
                Axis::X => (Dof::Y, Dof::X),
                Axis::Y => (Dof::X, Dof::Y),
            };
            if antisymmetric.contains(a) {
                held.push((b, along));
            } else {
                held.push((b, across));
                held.push((b, Dof::Rotation));
            }
        }
    }
    held.sort_by_key(|&(b, dof)| (b, dof as usize));
    held.dedup();
    held
}

/// The families of modes of a part mirrored about `axes`: each set of the axes its modes
/// are antisymmetric about (the empty set first, the modes symmetric about every axis).
/// The whole part's modes are the union of the families' (a mode of a symmetric structure
/// is symmetric or antisymmetric about each of its mirror axes, and the two kinds do not
/// couple: Kangwai, Guest and Pellegrino, "An introduction to the analysis of symmetric
/// structures", Computers & Structures 71 (1999) 671-688; Bartilson, Jang and Smyth,
/// Mech. Syst. Signal Process. 143 (2020) 106797, Sec. 2).
fn families(axes: &[Axis]) -> Vec<Vec<Axis>> {
    (0..1usize << axes.len())
        .map(|mask| {
            axes.iter()
                .enumerate()
                .filter(|(i, _)| mask >> i & 1 == 1)
                .map(|(_, a)| *a)
                .collect()
        })
        .collect()
}

/// The rectangle `thickness` wide around the segment `a b`, counterclockwise.
fn link_band<D: Scalar>(a: [D; 2], b: [D; 2], thickness: D) -> Vec<[D; 2]> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let scale = thickness * 0.5 / (dx * dx + dy * dy).sqrt();
    let (nx, ny) = (-dy * scale, dx * scale);
    vec![
        [a[0] - nx, a[1] - ny],
        [b[0] - nx, b[1] - ny],
        [b[0] + nx, b[1] + ny],
        [a[0] + nx, a[1] + ny],
    ]
}

/// What an expression of the description is, for [`NetworkModel::mirror`]: how its value
/// changes when the mechanism is reflected about the `x` axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    /// A point's `x`, kept; its `y` (the next expression), negated.
    PointX,
    PointY,
    /// A hinge's dimension, kept.
    Dimension,
    /// A hinge's angle, negated (its sine negated, its cosine kept).
    Angle,
    /// A port's direction `(x, y)`: reflected, or reflected and reversed (the port then
    /// reads its motion with the other sign, an output up to sign).
    DirectionX,
    DirectionY,
    /// A measure: kept or negated (an output up to sign).
    Measure,
}

/// Every expression [`NetworkModel::at`] evaluates, with its [`Role`].
fn expressions(d: &mut Description) -> Vec<(&mut Keyed, Role)> {
    let mut all = Vec::new();
    fn point<'a>(all: &mut Vec<(&'a mut Keyed, Role)>, p: &'a mut Point) {
        let [x, y] = p;
        all.push((x, Role::PointX));
        all.push((y, Role::PointY));
    }
    let mut widths = Vec::new();
    for b in &mut d.bodies {
        for p in &mut b.points {
            point(&mut all, p);
        }
        widths.extend(b.link_width.iter_mut());
    }
    for p in &mut d.ground {
        point(&mut all, p);
    }
    for h in &mut d.hinges {
        all.extend(h.dimensions.iter_mut().map(|e| (e, Role::Dimension)));
        point(&mut all, &mut h.start);
        all.push((&mut h.angle, Role::Angle));
    }
    for p in std::iter::once(&mut d.input).chain(&mut d.outputs) {
        point(&mut all, &mut p.at);
        let [x, y] = &mut p.direction;
        all.push((x, Role::DirectionX));
        all.push((y, Role::DirectionY));
    }
    for m in &mut d.measures {
        all.push((&mut m.value, Role::Measure));
    }
    // the links' widths, for the bodies' masses: last, so that the others keep their slots
    all.extend(widths.into_iter().map(|e| (e, Role::Dimension)));
    // the beams after them, for the same reason, and the supports after the beams
    for b in &mut d.beams {
        point(&mut all, &mut b.start);
        point(&mut all, &mut b.end);
        all.push((&mut b.thickness, Role::Dimension));
    }
    for g in &mut d.supports {
        point(&mut all, &mut g.at);
        let [x, y] = &mut g.direction;
        all.push((x, Role::DirectionX));
        all.push((y, Role::DirectionY));
    }
    all
}

impl NetworkModel {
    /// Whether every output at `m` is the one at `x` up to sign (relative 1e-10): the test of
    /// a mirror image for a description that is no reflection of itself expression by
    /// expression but is one as a mechanism, such as a body across an axis drawn off it (its
    /// place along the axis changes nothing, as it neither turns nor moves across it).
    fn same_outputs(&self, x: &[f64], m: &[f64]) -> bool {
        let all = self.available_outputs();
        let (mut a, mut b) = (vec![0.0; all.len()], vec![0.0; all.len()]);
        self.evaluate(x, &all, &mut a);
        self.evaluate(m, &all, &mut b);
        a.iter().zip(&b).all(|(&a, &b)| {
            let (a, b) = (a.abs(), b.abs());
            a == b || (a - b).abs() <= 1e-10 * a.max(b)
        })
    }
}

/// Whether `mirrored`, the values of the description's expressions at the design with its
/// angles negated, are those of `values` reflected about the `x` axis, each by its role
/// (relative 1e-12; a point's coordinates against the largest of them).
fn reflects(roles: &[Role], values: &[f64], mirrored: &[f64]) -> bool {
    let size = roles
        .iter()
        .zip(values)
        .filter(|(r, _)| matches!(r, Role::PointX | Role::PointY))
        .fold(0.0f64, |m, (_, v)| m.max(v.abs()));
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
    let mut i = 0;
    while i < roles.len() {
        let (a, b) = (values[i], mirrored[i]);
        let fine = match roles[i] {
            Role::PointX => close(b, a, size),
            Role::PointY => close(b, -a, size),
            Role::Dimension => close(b, a, a.abs()),
            Role::Angle => {
                let ((s, c), (sm, cm)) = (a.sin_cos(), b.sin_cos());
                close(sm, -s, 1.0) && close(cm, c, 1.0)
            }
            Role::DirectionX => {
                let (ay, by) = (values[i + 1], mirrored[i + 1]);
                let norm = a.hypot(ay);
                i += 1;
                (close(b, a, norm) && close(by, -ay, norm))
                    || (close(b, -a, norm) && close(by, ay, norm))
            }
            Role::DirectionY => unreachable!("read with its DirectionX"),
            Role::Measure => close(b, a, a.abs()) || close(b, -a, a.abs()),
        };
        if !fine {
            return false;
        }
        i += 1;
    }
    true
}

/// The message of a body's or a flexure's size `value` (m) that the design makes zero or
/// negative, naming its key.
fn not_positive(name: &str, key: &str, size: &str, value: f64) -> String {
    format!(
        "\"{name}\" ({key}): its {size} {} m is not positive at this design: a size is \
         positive; keep its expression above zero over the bounds",
        crate::vocab::units::short(value)
    )
}

/// The first outline, a body's or the ground's, that crosses itself at the evaluated
/// design: no solid has it.
fn outline_crossing(d: &Description, e: &Evaluated<f64>) -> Option<String> {
    let bodies = d.bodies.iter().enumerate().filter_map(|(b, body)| {
        let points = &e.points[e.offsets[b]..e.offsets[b + 1]];
        (body.link_width.is_none()).then(|| {
            let what = format!("body \"{}\" ({}.outline)", body.name, body.key);
            (what, points)
        })
    });
    let ground_at = e.offsets[d.bodies.len()];
    let ground = std::iter::once((
        "the ground's outline".to_string(),
        &e.points[ground_at..ground_at + d.ground.len()],
    ));
    bodies.chain(ground).find_map(|(what, points)| {
        let (i, j) = super::checks::crossing(points)?;
        Some(format!(
            "{what} crosses itself at this design (its edges from points {i} and {j}): list \
             its points in order around it"
        ))
    })
}

/// Why hinge `h`'s dimensions `dims` (SI) make no hinge of its kind, named by their keys;
/// the check on the values alone, without allocating, and the names only for a message.
fn domain_error<D: Scalar>(h: &HingeDescription, dims: &[D]) -> Option<String> {
    const MOST: usize = 8;
    if dims.len() <= MOST {
        let mut plain = [0.0; MOST];
        for (p, v) in plain.iter_mut().zip(dims) {
            *p = v.re();
        }
        // the names only make the message, which the second call below makes (a constant:
        // an array of them built at each call was 128 bytes written)
        const NONE: [&str; MOST] = [""; MOST];
        h.kind
            .domain_error(&plain[..dims.len()], &NONE[..dims.len()])?;
    }
    let names: Vec<&str> = h.dimensions.iter().map(|e| e.key.as_str()).collect();
    let plain: Vec<f64> = dims.iter().map(|v| v.re()).collect();
    h.kind.domain_error(&plain, &names)
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
        // that the statics do not check (every body's mass is checked once, by `unavailable`)
        let all: Vec<usize> = self
            .available_outputs()
            .into_iter()
            .filter(|&i| !matches!(self.quantities[i], Quantity::Frequency(_)))
            .collect();
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
        let Quantity::Frequency(i) = self.quantities[output] else {
            return None;
        };
        let name = &self.outputs[output].name;
        let d = &self.description;
        if let Some(g) = d.supports.first() {
            return Some(format!(
                "output \"{name}\": the natural frequencies of a network with supports \
                 ({}) are not modelled",
                g.key
            ));
        }
        if !self.material.density.is_finite() {
            return Some(format!(
                "output \"{name}\" needs the material's density: give `[material] density` \
                 (e.g. \"2810 kg/m3\") or a preset"
            ));
        }
        if !d.mirror.is_empty() && !self.grounded() {
            match self.mounting() {
                None => {
                    return Some(format!(
                        "output \"{name}\": the part has no ground, and neither its input nor \
                         its first output is across a mirror axis: nothing holds it"
                    ))
                }
                Some((1, _)) if d.input.across.is_none() => {
                    return Some(format!(
                        "output \"{name}\": the part stands on the first output's image, and \
                         the input is across no mirror axis, so the stack's far end has no \
                         place: give `network.input.across` or join a hinge to the ground"
                    ))
                }
                _ => {}
            }
        }
        if self.actuator.stiffness.is_none() {
            return Some(format!(
                "output \"{name}\" needs the actuator's stiffness (`[actuator] stiffness`): the \
                 input stands on it in every mode"
            ));
        }
        if let Some(body) = d
            .bodies
            .iter()
            .find(|body| body.link_width.is_none() && body.points.len() < 3)
        {
            return Some(format!(
                "output \"{name}\" needs every body's mass: body \"{}\" ({}) has no outline or \
                 link to give it",
                body.name, body.key
            ));
        }
        let dofs = self.mode_dofs();
        if i >= dofs {
            return Some(format!(
                "output \"{name}\": the network has {dofs} degrees of freedom, so {dofs} modes"
            ));
        }
        None
    }

    fn material(&self) -> Option<&Material> {
        Some(&self.material)
    }

    fn angle_limit(&self) -> Option<f64> {
        None
    }

    /// Every angle negated, as the bridge's, where that reflects the described mechanism
    /// about the `x` axis at this design: each point's `y` and each hinge's angle negated,
    /// the rest kept, each port's direction reflected (or reflected and reversed: the port
    /// reads its motion with the other sign) and each measure kept up to sign, so that the
    /// outputs are the same up to sign. A description written so (wei2017's, with
    /// `l2*sin(delta2)`) has its mirror image at every design; one that is not (a point at
    /// `l2*sin(delta2) + 1`) has none, and the study keeps its mirror images apart.
    fn mirror(&self, x: &mut [f64]) -> bool {
        let mut m = x.to_vec();
        if !crate::model::negate_angles(&self.description.parameters, &mut m) {
            return false;
        }
        let (Some(values), Some(mirrored)) =
            (self.expression_values(x), self.expression_values(&m))
        else {
            return false;
        };
        if !reflects(&self.roles, &values, &mirrored) && !self.same_outputs(x, &m) {
            return false;
        }
        x.copy_from_slice(&m);
        true
    }

    fn fit_limits(&self) -> &[FitLimit] {
        &self.fit
    }
}
