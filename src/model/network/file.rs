//! The network's sections of a problem file (`model = "network"`): `[material]`,
//! `[network]` with its bodies, hinges, ports and measures, and `[actuator]`, read and
//! checked into a [`Description`] whose every coordinate and dimension is an
//! [`Expression`] parsed once against the model's parameters.
//!
//! The shape, and why (docs/guide/src/networks.md shows it whole):
//!
//! - `[network]`: `width` (out of plane), `unit` (the length unit of every expression,
//!   default `"mm"`; angles in radians, `deg` = pi/180), `parameters` (a list of `[name,
//!   dimension]` pairs, the dimension `"length"`, `"angle"` or `"ratio"`, in the order the
//!   model lists them: a list because a table's keys reach the reader sorted; each bound by
//!   a `[[variables]]` entry), `mirror` (the axes `"x"`, the line y = 0, and `"y"`,
//!   the line x = 0, about which the whole is symmetric; only one side is described).
//! - `[[network.bodies]]`: `name`, an optional `outline` (a polygon of expression pairs) or
//!   `link` (`from`, `to`, `width`), and `on_axis`: the mirror axes the body lies across.
//!   Declared, not detected: a body's place is an expression of the design, and whether a
//!   point lies on an axis cannot be told from a value that is zero at one design and not at
//!   the next. Such a body keeps its motion across the axis and its rotation at zero.
//! - `[[network.hinges]]`: `name`, `kind`, `from`, `to` (bodies; `"ground"` is the ground),
//!   `start` (a point), `angle` (its axis from `from` to `to`), and each of the kind's
//!   dimensions by the hinge library's stem (`l`, `t` of a strip; `r`, `t` of a circular
//!   notch; as `flexopt hinge` names its flags).
//! - `[network.input]` and `[[network.outputs]]`: `body`, `at`, `direction` (a vector,
//!   normalised), and `across` (a mirror axis): the port acts between its point and its
//!   mirror image about that axis, an actuator pushing the two apart or an output read as
//!   the change of their distance. A port on a body across an axis shares its load with
//!   the body's mirror half: the described part carries half of it per such axis. An
//!   output may carry a `payload` (a mass, e.g. `"20 g"`), for the natural frequencies.
//! - `[[network.measures]]`: named expressions reported as outputs (`name`, `dimension`,
//!   `value`); one named `span_x` or `span_y` replaces the described part's extent (a
//!   signed span, as the bridge's).
//! - `[[network.supports]]`: `body`, `at`, `direction`, `hold_rotation`: a guide or a
//!   roller ([`super::supports`]).
//! - `[actuator]`: `nominal_stroke`, `preload`, optional `stiffness` and `mass`, the bridge's section
//!   (its `length` and `height`, the stack's size, are for the part, still to come).
//!
//! - `[[network.beams]]`: `name`, `from`, `to` (bodies or `"ground"`), `start` and `end`
//!   (points) and `thickness` (in plane): a uniform straight beam clamped into both bodies
//!   at its ends, the plate's `width` out of plane. Unlike a hinge it is placed by its two
//!   ends, not by a start, an angle and a length: a frame member between two bodies is
//!   drawn from point to point, and its length and direction follow.

use super::checks::{self, Two};
use super::description::{
    Axis, BeamDescription, BodyDescription, Description, HingeDescription, Keyed,
    MeasureDescription, Point, PortDescription, DEG, GROUND,
};
pub use super::raw::{schema, SECTIONS};
use super::raw::{RawNetwork, RawNetworkPort};
use super::supports;
use crate::model::expression::Expression;
use crate::model::hinge::HingeKind;
use crate::model::{Dimension, ParameterInfo};
use crate::vocab::error::Segment;
use crate::vocab::reader::{k, quoted, Res};
use crate::vocab::sections::Sections;
use crate::vocab::units::{self, Unit};

fn net(rest: &[Segment]) -> Vec<Segment> {
    let mut p = vec![k("network")];
    p.extend_from_slice(rest);
    p
}

fn at(table: &str, i: usize) -> [Segment; 2] {
    [k(table), Segment::Index(i)]
}

/// The key path as a problem file's reader writes it.
fn written(path: &[Segment]) -> String {
    crate::vocab::error::format_path(path)
}

pub(super) fn describe(s: &Sections, n: &RawNetwork) -> Res<Description> {
    let width = s.measured(&net(&[k("width")]), &n.width)?;
    let unit_name = n.unit.as_deref().unwrap_or("mm");
    let unit = Unit::parse(unit_name, Dimension::Length)
        .map_err(|e| s.err(&net(&[k("unit")]), e))?
        .to_si(1.0);
    // the parameters, each with its dimension; their count bounded, as a design's
    // gradients are dual numbers of a derivative per parameter, compiled for each count
    let most = crate::model::MAX_PARAMETERS;
    if n.parameters.len() > most {
        let what = format!(
            "{} parameters; a network has at most {most}",
            n.parameters.len()
        );
        return Err(s.err(&net(&[k("parameters")]), what));
    }
    let mut parameters = Vec::new();
    for (i, Two([name, dim])) in n.parameters.iter().enumerate() {
        let path = net(&[k("parameters"), Segment::Index(i)]);
        if parameters
            .iter()
            .any(|p: &ParameterInfo| p.name == name.as_str())
        {
            return Err(s.err(&path, format!("parameter \"{name}\" is given twice")));
        }
        let dimension = [Dimension::Length, Dimension::Angle, Dimension::Ratio]
            .into_iter()
            .find(|&d| units::dimension_word(d) == dim || (d == Dimension::Ratio && dim == "ratio"))
            .ok_or_else(|| {
                s.err(
                    &path,
                    format!("unknown dimension \"{dim}\"; expected one of \"length\", \"angle\", \"ratio\""),
                )
            })?;
        if let Some(why) = checks::parameter_name_error(name) {
            let mut key = path.clone();
            key.push(Segment::Index(0));
            return Err(s.err(&key, why));
        }
        parameters.push(ParameterInfo {
            name: name.clone().into(),
            dimension,
            description: format!("parameter {name} of the network").into(),
        });
    }
    let mut names: Vec<&str> = parameters.iter().map(|p| p.name.as_ref()).collect();
    names.push(DEG);
    let parse = |path: Vec<Segment>, text: &str| -> Res<Keyed> {
        let key = written(&path);
        Expression::parse(text, &names)
            .map(|expression| Keyed {
                key,
                expression,
                slot: usize::MAX,
            })
            .map_err(|e| s.err(&path, format!("in \"{text}\" {e}")))
    };
    let point = |path: Vec<Segment>, p: &Two| -> Res<Point> {
        let one = |i: usize| {
            let mut q = path.clone();
            q.push(Segment::Index(i));
            parse(q, &p.0[i])
        };
        Ok([one(0)?, one(1)?])
    };
    let axis = |path: Vec<Segment>, name: &str| -> Res<Axis> {
        match name {
            "x" => Ok(Axis::X),
            "y" => Ok(Axis::Y),
            _ => Err(s.err(
                &path,
                format!("unknown axis \"{name}\"; expected \"x\" (the line y = 0) or \"y\" (the line x = 0)"),
            )),
        }
    };
    let mut mirror = Vec::new();
    for (i, m) in n.mirror.iter().flatten().enumerate() {
        let a = axis(net(&[k("mirror"), Segment::Index(i)]), m)?;
        if mirror.contains(&a) {
            return Err(s.err(&net(&[k("mirror")]), format!("axis \"{m}\" is given twice")));
        }
        mirror.push(a);
    }
    // the bodies
    let mut bodies: Vec<BodyDescription> = Vec::new();
    let mut ground = Vec::new();
    let mut grounds = 0;
    for (i, b) in n.bodies.iter().enumerate() {
        let path = net(&at("bodies", i));
        let sub = |key: &str| {
            let mut p = path.clone();
            p.push(k(key));
            p
        };
        grounds += usize::from(b.name == GROUND);
        if bodies.iter().any(|o| o.name == b.name) || grounds > 1 && b.name == GROUND {
            return Err(s.err(&sub("name"), format!("body \"{}\" is named twice", b.name)));
        }
        let mut points = Vec::new();
        let mut link_width = None;
        match (&b.outline, &b.link) {
            (Some(_), Some(_)) => {
                return Err(s.err(&sub("link"), "give an outline or a link, not both"))
            }
            (Some(outline), None) => {
                if outline.len() < 3 {
                    return Err(s.err(
                        &sub("outline"),
                        format!(
                            "an outline is a polygon of at least three points, not {}: add its \
                             other corners, or give the body a `link`",
                            outline.len()
                        ),
                    ));
                }
                for (j, p) in outline.iter().enumerate() {
                    let mut q = sub("outline");
                    q.push(Segment::Index(j));
                    points.push(point(q, p)?);
                }
            }
            (None, Some(link)) => {
                let mut q = sub("link");
                q.push(k("from"));
                points.push(point(q.clone(), &link.from)?);
                q.pop();
                q.push(k("to"));
                points.push(point(q.clone(), &link.to)?);
                q.pop();
                q.push(k("width"));
                let width = parse(q.clone(), &link.width)?;
                if let Some(why) = checks::constant_size_error(&width, "the link's width") {
                    return Err(s.err(&q, why));
                }
                link_width = Some(width);
            }
            (None, None) => {}
        }
        if b.name == GROUND {
            if b.on_axis.is_some() {
                return Err(s.err(
                    &sub("on_axis"),
                    "the ground does not move: it needs no axis",
                ));
            }
            ground = points;
            continue;
        }
        let mut on_axis = Vec::new();
        for (j, name) in b.on_axis.iter().flatten().enumerate() {
            let mut q = sub("on_axis");
            q.push(Segment::Index(j));
            let a = axis(q.clone(), name)?;
            if !mirror.contains(&a) {
                return Err(s.err(
                    &q,
                    format!("axis \"{name}\" is no mirror axis of the network: add it to `network.mirror`"),
                ));
            }
            on_axis.push(a);
        }
        bodies.push(BodyDescription {
            name: b.name.clone(),
            key: written(&path),
            points,
            link_width,
            on_axis,
        });
    }
    let body_names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let find_body = |path: &[Segment], name: &str| -> Res<Option<usize>> {
        if name == GROUND {
            return Ok(None);
        }
        if body_names.is_empty() {
            return Err(s.err(
                path,
                format!(
                    "unknown body \"{name}\": the network has no body but \"{GROUND}\"; \
                     describe it under [[network.bodies]]"
                ),
            ));
        }
        body_names
            .iter()
            .position(|&b| b == name)
            .map(Some)
            .ok_or_else(|| {
                s.err(
                    path,
                    format!(
                        "unknown body \"{name}\"; expected \"{GROUND}\" or one of {}",
                        quoted(&body_names)
                    ),
                )
            })
    };
    // the hinges
    let mut hinges: Vec<HingeDescription> = Vec::new();
    for (i, h) in n.hinges.iter().enumerate() {
        let path = net(&at("hinges", i));
        let sub = |key: &str| {
            let mut p = path.clone();
            p.push(k(key));
            p
        };
        if hinges.iter().any(|o| o.name == h.name) {
            return Err(s.err(&sub("name"), format!("hinge \"{}\" is named twice", h.name)));
        }
        let kind = HingeKind::from_name(&h.kind).ok_or_else(|| {
            s.err(
                &sub("kind"),
                format!(
                    "unknown hinge kind \"{}\"; expected one of {}",
                    h.kind,
                    quoted(HingeKind::NAMES)
                ),
            )
        })?;
        let from = find_body(&sub("from"), &h.from)?;
        let to = find_body(&sub("to"), &h.to)?;
        if from == to {
            return Err(s.err(
                &sub("to"),
                format!(
                    "hinge \"{}\" joins \"{}\" to itself: a hinge joins two bodies",
                    h.name, h.to
                ),
            ));
        }
        let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
        if let Some(unknown) = h
            .dimensions
            .keys()
            .find(|key| !stems.contains(&key.as_str()))
        {
            return Err(s.err(
                &sub(unknown),
                format!(
                    "unknown key \"{unknown}\" of a {} hinge; expected name, kind, from, to, start, angle and its dimensions {}",
                    kind.name(),
                    quoted(&stems)
                ),
            ));
        }
        let mut dimensions = Vec::new();
        let mut parameter_of = Vec::new();
        for stem in &stems {
            let Some(text) = h.dimensions.get(*stem) else {
                return Err(s.err(
                    &sub(stem),
                    format!(
                        "missing: a {} hinge needs its dimensions {}",
                        kind.name(),
                        quoted(&stems)
                    ),
                ));
            };
            let e = parse(sub(stem), text)?;
            let info = kind.dimensions().iter().find(|d| d.stem == *stem);
            if info.is_some_and(|d| d.dimension == Dimension::Length) {
                if let Some(why) = checks::constant_size_error(&e, &format!("the hinge's `{stem}`"))
                {
                    return Err(s.err(&sub(stem), why));
                }
            }
            parameter_of.push(
                names[..names.len() - 1]
                    .iter()
                    .position(|&p| p == text.trim()),
            );
            dimensions.push(e);
        }
        hinges.push(HingeDescription {
            name: h.name.clone(),
            key: written(&path),
            kind,
            from,
            to,
            start: point(sub("start"), &h.start)?,
            angle: parse(sub("angle"), &h.angle)?,
            dimensions,
            parameter_of,
        });
    }
    // the beams
    let mut beams: Vec<BeamDescription> = Vec::new();
    for (i, r) in n.beams.iter().enumerate() {
        let path = net(&at("beams", i));
        let sub = |key: &str| {
            let mut p = path.clone();
            p.push(k(key));
            p
        };
        // a beam's outputs are named as a hinge's: one name among both
        if beams.iter().any(|o| o.name == r.name) || hinges.iter().any(|o| o.name == r.name) {
            return Err(s.err(
                &sub("name"),
                format!(
                    "\"{}\" names another beam or hinge: their outputs share the names",
                    r.name
                ),
            ));
        }
        let from = find_body(&sub("from"), &r.from)?;
        let to = find_body(&sub("to"), &r.to)?;
        if from == to {
            return Err(s.err(
                &sub("to"),
                format!(
                    "beam \"{}\" joins \"{}\" to itself: a beam joins two bodies",
                    r.name, r.to
                ),
            ));
        }
        let thickness = parse(sub("thickness"), &r.thickness)?;
        if let Some(why) = checks::constant_size_error(&thickness, "the beam's thickness") {
            return Err(s.err(&sub("thickness"), why));
        }
        beams.push(BeamDescription {
            name: r.name.clone(),
            key: written(&path),
            from,
            to,
            start: point(sub("start"), &r.start)?,
            end: point(sub("end"), &r.end)?,
            thickness,
        });
    }
    // every body is joined to something
    for (b, body) in bodies.iter().enumerate() {
        if !hinges.iter().any(|h| h.from == Some(b) || h.to == Some(b))
            && !beams.iter().any(|h| h.from == Some(b) || h.to == Some(b))
        {
            let i = n
                .bodies
                .iter()
                .position(|r| r.name == body.name)
                .unwrap_or(0);
            return Err(s.err(
                &net(&[k("bodies"), Segment::Index(i), k("name")]),
                format!(
                    "body \"{}\" is joined to nothing: no hinge or beam has it as `from` or `to`",
                    body.name
                ),
            ));
        }
    }
    // the ports
    let port = |path: Vec<Segment>, p: &RawNetworkPort, name: String| -> Res<PortDescription> {
        let sub = |key: &str| {
            let mut q = path.clone();
            q.push(k(key));
            q
        };
        let body = find_body(&sub("body"), &p.body)?.ok_or_else(|| {
            s.err(
                &sub("body"),
                "a port on the ground neither moves nor takes a load: put it on a body",
            )
        })?;
        let across = p
            .across
            .as_deref()
            .map(|a| axis(sub("across"), a))
            .transpose()?;
        if let Some(a) = across {
            if !mirror.contains(&a) {
                return Err(s.err(
                    &sub("across"),
                    "no mirror axis of the network: add it to `network.mirror`",
                ));
            }
        }
        let payload = p
            .payload
            .as_ref()
            .map(|m| s.measured(&sub("payload"), m))
            .transpose()?
            .unwrap_or(0.0);
        Ok(PortDescription {
            name,
            body,
            at: point(sub("at"), &p.at)?,
            direction: point(sub("direction"), &p.direction)?,
            across,
            payload,
        })
    };
    if n.input.name.is_some() {
        return Err(s.err(&net(&[k("input"), k("name")]), "the input takes no name"));
    }
    if n.input.payload.is_some() {
        return Err(s.err(
            &net(&[k("input"), k("payload")]),
            "the input carries the actuator, not a payload: give the payload to an output",
        ));
    }
    let input = port(net(&[k("input")]), &n.input, "input".into())?;
    if n.outputs.is_empty() {
        return Err(s.err(&net(&[k("outputs")]), "give at least one output port"));
    }
    let mut outputs: Vec<PortDescription> = Vec::new();
    for (i, p) in n.outputs.iter().enumerate() {
        let path = net(&at("outputs", i));
        let mut q = path.clone();
        q.push(k("name"));
        let name = p
            .name
            .clone()
            .ok_or_else(|| s.err(&q, "missing: each output port has a name"))?;
        if outputs.iter().any(|o| o.name == name) {
            return Err(s.err(&q, format!("output \"{name}\" is named twice")));
        }
        if i > 0 && p.payload.is_some() {
            let mut q = path.clone();
            q.push(k("payload"));
            return Err(s.err(
                &q,
                "only the first output carries a payload (the part's check loads one face with \
                 it): move it there, or add its mass to the body's outline",
            ));
        }
        outputs.push(port(path, p, name)?);
    }
    let mut measures: Vec<MeasureDescription> = Vec::new();
    for (i, m) in n.measures.iter().enumerate() {
        let path = net(&at("measures", i));
        let sub = |key: &str| {
            let mut q = path.clone();
            q.push(k(key));
            q
        };
        let dimension = [Dimension::Length, Dimension::Angle, Dimension::Ratio]
            .into_iter()
            .find(|&d| units::dimension_word(d) == m.dimension || (d == Dimension::Ratio && m.dimension == "ratio"))
            .ok_or_else(|| {
                s.err(
                    &sub("dimension"),
                    format!("unknown dimension \"{}\"; expected one of \"length\", \"angle\", \"ratio\"", m.dimension),
                )
            })?;
        if measures.iter().any(|o| o.name == m.name) {
            return Err(s.err(
                &sub("name"),
                format!("measure \"{}\" is named twice", m.name),
            ));
        }
        measures.push(MeasureDescription {
            name: m.name.clone(),
            dimension,
            value: parse(sub("value"), &m.value)?,
        });
    }
    let supports = supports::read(s, &n.supports, find_body, point)?;
    Ok(Description {
        parameters,
        unit,
        width,
        mirror,
        bodies,
        ground,
        hinges,
        beams,
        input,
        outputs,
        measures,
        supports,
    })
}
