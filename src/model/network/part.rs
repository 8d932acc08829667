//! The part of a flexure network, drawn from the same description as its model, and the
//! finite-element check it states through the ports (issue 25).
//!
//! What is cut (metres, the description's points evaluated at the design):
//!
//! - each body as the file draws it: its outline (split into triangles where it is not
//!   convex, as the part's solids are convex), or its link, a band of its width around the
//!   segment; a body drawn by neither is the convex hull of its hinges' pads;
//! - each hinge's thin section from `start` along `angle` for the kind's length, the model's
//!   hinge, with the true profile of its kind ([`crate::model::hinge::HingeKind::outline`]);
//!   its solid runs the fillet radius beyond both ends (a strip's; a notch meets its bodies
//!   smoothly and has none) to a face across it, and behind each face a pad `pad` deep and
//!   `root/2 + fillet + pad_margin` to each side: the pad is joined to the hinge and to the
//!   body, so that a body drawn up to the hinge's end meets it through a face the fillets
//!   land on;
//! - the ground is its hinges' pads, each held on its far side (the faces `clamp`).
//!
//! A port's face lies where the line through the port along its direction leaves the body
//! on the side the port's force comes from (the actuator's side): every point of that line
//! moves alike along the direction under a rigid motion of the body, so the face's mean
//! displacement along it reads the port's. The face is `face` long, shorter where the edge
//! it lies on is.
//!
//! The check ([`crate::part::analysis`]): the clamped faces held; the test force on the input
//! face along the input's direction (the actuation case), the input's and the first output's
//! motions read under it; then on the first output's face, the input free. So `fe_k_in`,
//! `fe_amplification`, `fe_k_out` and the hinges' beam and peak stresses under the
//! actuation, each beside the model's output of the same meaning.
//!
//! Mirror axes: the whole part is the described one and its images about each axis (and
//! both). A body across an axis is drawn with its image about it as one solid (the convex
//! hull of the two), so its halves join; each port's face has its images, which share the
//! port's force where they lie on the port's own body (as the model's described half of such
//! a body carries its share). A port across an axis reads its face and its image's face
//! across it: the change of their distance. A part with no ground is held on the first
//! output's image across its axis, as the bridge's lower output block is. The part is
//! symmetric about the y axis where the description is, so the check solves its right half.
//!
//! Not yet: the natural modes.

use serde::Deserialize;

use super::file::{Axis, Description, Keyed, Point};
use crate::model::{Dimension, PartMaker};
use crate::part::analysis::{
    ActuationCase, Analysis, FeCounterpart, FeOutput, FeOutputId, Load, LoadCase, Measure,
    Quantity, Term,
};
use crate::part::{convex_hull, Actuation, Face, HingeSite, PartSpec, Solid};
use crate::vocab::reader::{k, Res};
use crate::vocab::schema::{Measured, NonNegativeLength, PositiveLength};
use crate::vocab::sections::Sections;

type P = [f64; 2];

/// `[part]` of a network: a file with this section has a part.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawNetworkPart {
    /// The radius of the fillets at a strip's roots (default 0.2 mm).
    fillet_radius: Option<Measured<NonNegativeLength>>,
    /// The narrowest slot the wire cuts (default 0.4 mm).
    min_slot: Option<Measured<NonNegativeLength>>,
    /// How deep each hinge's pad reaches into its body (default 2 mm).
    pad: Option<Measured<PositiveLength>>,
    /// How far a pad reaches beside the hinge's root and fillet (default 1 mm).
    pad_margin: Option<Measured<PositiveLength>>,
    /// The length of a port's face (default 2 mm).
    face: Option<Measured<PositiveLength>>,
}

/// `[part]` of a network (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartSettings {
    pub fillet_radius: f64,
    pub min_slot: f64,
    pub pad: f64,
    pub pad_margin: f64,
    pub face: f64,
}

impl Default for PartSettings {
    /// As the bridge's part: wire EDM with a 0.25 mm wire cuts inner corners of about 0.17
    /// mm radius and slots of about 0.33 mm.
    fn default() -> Self {
        PartSettings {
            fillet_radius: 0.2e-3,
            min_slot: 0.4e-3,
            pad: 2e-3,
            pad_margin: 1e-3,
            face: 2e-3,
        }
    }
}

impl PartSettings {
    /// `[part]`, each key with its default.
    pub fn read(s: &Sections, p: &RawNetworkPart) -> Res<Self> {
        let at = |key: &str| [k("part"), k(key)];
        let d = PartSettings::default();
        Ok(PartSettings {
            fillet_radius: s.measured_or(
                &at("fillet_radius"),
                &p.fillet_radius,
                d.fillet_radius,
            )?,
            min_slot: s.measured_or(&at("min_slot"), &p.min_slot, d.min_slot)?,
            pad: s.measured_or(&at("pad"), &p.pad, d.pad)?,
            pad_margin: s.measured_or(&at("pad_margin"), &p.pad_margin, d.pad_margin)?,
            face: s.measured_or(&at("face"), &p.face, d.face)?,
        })
    }
}

/// The model's outputs the check measures, by their indices among the model's outputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Counterparts {
    pub amplification: Option<usize>,
    pub k_in: Option<usize>,
    pub k_out: Option<usize>,
    pub stress_max: Option<usize>,
}

/// A network's part: the description, the settings, the actuator.
#[derive(Debug, Clone)]
pub struct NetworkPart {
    pub description: Description,
    pub settings: PartSettings,
    pub actuation: Actuation,
    pub counterparts: Counterparts,
}

const FE_K_IN: FeOutputId = FeOutputId(0);
const FE_AMPLIFICATION: FeOutputId = FeOutputId(1);
const FE_K_OUT: FeOutputId = FeOutputId(2);
const FE_STRESS_SECTION: FeOutputId = FeOutputId(3);

impl PartMaker for NetworkPart {
    fn part(&self, x: &[f64]) -> Result<PartSpec, Vec<String>> {
        spec(self, x)
    }

    fn fe_counterpart(&self, output: usize) -> Option<FeCounterpart> {
        let c = &self.counterparts;
        let is = |o: Option<usize>| o == Some(output);
        if is(c.k_in) {
            Some(FeCounterpart::Output(FE_K_IN))
        } else if is(c.amplification) {
            Some(FeCounterpart::Output(FE_AMPLIFICATION))
        } else if is(c.k_out) {
            Some(FeCounterpart::Output(FE_K_OUT))
        } else if is(c.stress_max) {
            // the hinges' beam stress with each notch's concentration: the section stress
            // is its FE counterpart for strips, whose concentration is 1
            Some(FeCounterpart::Output(FE_STRESS_SECTION))
        } else {
            None
        }
    }
}

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}

fn scale(a: P, k: f64) -> P {
    [a[0] * k, a[1] * k]
}

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn signed_area(points: &[P]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| cross(points[i], points[(i + 1) % n]))
        .sum::<f64>()
}

fn is_convex(points: &[P]) -> bool {
    let n = points.len();
    (0..n).all(|i| {
        let (a, b, c) = (points[i], points[(i + 1) % n], points[(i + 2) % n]);
        cross(sub(b, a), sub(c, b)) >= 0.0
    })
}

/// An outline as the part's solids: itself where it is convex, else its triangles.
fn convex_pieces(mut points: Vec<P>) -> Vec<Vec<P>> {
    if signed_area(&points) < 0.0 {
        points.reverse();
    }
    if is_convex(&points) {
        vec![points]
    } else {
        triangles(&points)
    }
}

/// A simple polygon (counterclockwise) cut into triangles by ear clipping (Meisters, "Polygons
/// have ears", Amer. Math. Monthly 82, 1975): convex pieces for the union. A body's outline
/// has a handful of corners; geo's `earcut` feature is left out of the build (issue 28,
/// docs/performance.md) and spade's triangulation would need its outside triangles removed.
fn triangles(points: &[P]) -> Vec<Vec<P>> {
    let mut left: Vec<P> = points.to_vec();
    let mut out = Vec::new();
    while left.len() > 3 {
        let n = left.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (left[(i + n - 1) % n], left[i], left[(i + 1) % n]);
            cross(sub(b, a), sub(c, b)) > 0.0
                && left.iter().all(|&p| {
                    p == a
                        || p == b
                        || p == c
                        || !(cross(sub(b, a), sub(p, a)) >= 0.0
                            && cross(sub(c, b), sub(p, b)) >= 0.0
                            && cross(sub(a, c), sub(p, c)) >= 0.0)
                })
        });
        let Some(i) = ear else {
            // a self-crossing outline has no ear: keep what is left whole, the checks say
            break;
        };
        let n = left.len();
        out.push(vec![left[(i + n - 1) % n], left[i], left[(i + 1) % n]]);
        left.remove(i);
    }
    out.push(left);
    out
}

fn band(a: P, b: P, half: f64) -> Vec<P> {
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
    vec![
        add(a, scale(n, -half)),
        add(b, scale(n, -half)),
        add(b, scale(n, half)),
        add(a, scale(n, half)),
    ]
}

/// Where the ray from `p` along `dir` first leaves the convex polygon `poly`, if `p` lies in
/// it: the distance along the ray and the edge's index.
fn exit(poly: &[P], p: P, dir: P) -> Option<(f64, usize)> {
    let n = poly.len();
    let inside = (0..n).all(|i| cross(sub(poly[(i + 1) % n], poly[i]), sub(p, poly[i])) >= -1e-15);
    if !inside {
        return None;
    }
    (0..n)
        .filter_map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let e = sub(b, a);
            // only a side the ray leaves through (counterclockwise: its outward normal
            // along the ray), not one it enters by or lies on
            let denom = cross(dir, e);
            if denom < 1e-30 {
                return None;
            }
            let s = cross(sub(a, p), e) / denom;
            let t = cross(sub(a, p), dir) / denom;
            (s >= 0.0 && (-1e-12..=1.0 + 1e-12).contains(&t)).then_some((s, i))
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
}

/// The stretch `[c0, c1]` of the line `q + s e` (`s` in `[lo, hi]`) that the convex polygon
/// `poly` covers, its boundary included (to 1e-12 m), if any.
fn covered(poly: &[P], q: P, e: P, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (mut a, mut b) = (lo, hi);
    let n = poly.len();
    for i in 0..n {
        let (p0, p1) = (poly[i], poly[(i + 1) % n]);
        let edge = sub(p1, p0);
        let len = edge[0].hypot(edge[1]);
        // inside: cross(edge, point - p0) / len >= -tol, linear in s
        let at0 = cross(edge, sub(q, p0)) / len + 1e-12;
        let slope = cross(edge, e) / len;
        if slope.abs() < 1e-15 {
            if at0 < 0.0 {
                return None;
            }
            continue;
        }
        let root = -at0 / slope;
        if slope > 0.0 {
            a = a.max(root);
        } else {
            b = b.min(root);
        }
    }
    (a < b).then_some((a, b))
}

/// The description's expressions evaluated at `x` (SI) in f64.
struct Values<'a> {
    d: &'a Description,
    values: Vec<f64>,
}

impl<'a> Values<'a> {
    fn new(d: &'a Description, x: &[f64]) -> Self {
        let mut values: Vec<f64> = x
            .iter()
            .zip(&d.parameters)
            .map(|(&v, p)| {
                if p.dimension == Dimension::Length {
                    v / d.unit
                } else {
                    v
                }
            })
            .collect();
        values.push(std::f64::consts::PI / 180.0);
        Values { d, values }
    }

    fn eval(&self, e: &Keyed) -> Result<f64, String> {
        e.expression
            .eval(&self.values)
            .map_err(|err| format!("{} = \"{}\": {err}", e.key, e.expression.source()))
    }

    fn length(&self, e: &Keyed) -> Result<f64, String> {
        Ok(self.eval(e)? * self.d.unit)
    }

    fn point(&self, p: &Point) -> Result<P, String> {
        Ok([self.length(&p[0])?, self.length(&p[1])?])
    }
}

/// One of the images the mirror axes make of the described part: `flip_x` maps x to -x
/// (the axis `y`, the line x = 0), `flip_y` maps y to -y (the axis `x`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Image {
    flip_x: bool,
    flip_y: bool,
}

impl Image {
    const IDENTITY: Image = Image {
        flip_x: false,
        flip_y: false,
    };

    /// The identity first, then the image about each axis and about both.
    fn all(mirror: &[Axis]) -> Vec<Image> {
        let y = mirror.contains(&Axis::Y);
        let x = mirror.contains(&Axis::X);
        let mut out = vec![Image::IDENTITY];
        for (flip_x, flip_y) in [(false, true), (true, false), (true, true)] {
            if (!flip_x || y) && (!flip_y || x) {
                out.push(Image { flip_x, flip_y });
            }
        }
        out
    }

    fn across(axis: Axis) -> Image {
        Image {
            flip_x: axis == Axis::Y,
            flip_y: axis == Axis::X,
        }
    }

    fn point(self, p: P) -> P {
        [
            if self.flip_x { -p[0] } else { p[0] },
            if self.flip_y { -p[1] } else { p[1] },
        ]
    }

    /// A counterclockwise polygon's image, counterclockwise.
    fn polygon(self, points: &[P]) -> Vec<P> {
        let mut out: Vec<P> = points.iter().map(|&p| self.point(p)).collect();
        if self.flip_x != self.flip_y {
            out.reverse();
        }
        out
    }

    /// The same image of a body that lies across `own`: the flips about those axes map the
    /// body onto itself.
    fn of_body(self, own: &[Axis]) -> Image {
        Image {
            flip_x: self.flip_x && !own.contains(&Axis::Y),
            flip_y: self.flip_y && !own.contains(&Axis::X),
        }
    }

    fn suffix(self) -> &'static str {
        match (self.flip_x, self.flip_y) {
            (false, false) => "",
            (false, true) => " (mirror x)",
            (true, false) => " (mirror y)",
            (true, true) => " (mirror x, y)",
        }
    }
}

/// A physical body of the whole part: its slot (0 the ground) and which of its images.
type BodyKey = (usize, Image);

/// A described hinge as cut: its solid, its site and its two pads with their bodies.
struct CutHinge {
    solid: Solid,
    site: HingeSite,
    from: usize,
    to: usize,
    /// Each pad and, for a pad on the ground, its clamped side.
    pads: [(Solid, Option<(P, P)>); 2],
}

fn same_face(a: (P, P), b: (P, P)) -> bool {
    let tol = 1e-12;
    let near = |p: P, q: P| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol;
    (near(a.0, b.0) && near(a.1, b.1)) || (near(a.0, b.1) && near(a.1, b.0))
}

/// The part of design `x`: the described part, then its images about the mirror axes.
fn spec(part: &NetworkPart, x: &[f64]) -> Result<PartSpec, Vec<String>> {
    let d = &part.description;
    let s = &part.settings;
    let v = Values::new(d, x);
    let one = |r: Result<P, String>| r.map_err(|e| vec![e]);
    let slot = |b: Option<usize>| b.map_or(0, |b| b + 1);
    // the axes each body (by slot) lies across: a body's images about them are itself
    let own: Vec<&[Axis]> = std::iter::once(&[][..])
        .chain(d.bodies.iter().map(|b| b.on_axis.as_slice()))
        .collect();

    // each hinge: its solid and its two pads
    let mut cut: Vec<CutHinge> = Vec::new();
    for h in &d.hinges {
        let mut dims = Vec::with_capacity(h.dimensions.len());
        for (e, info) in h.dimensions.iter().zip(h.kind.dimensions()) {
            let value = if info.dimension == Dimension::Length {
                v.length(e)
            } else {
                v.eval(e)
            };
            dims.push(value.map_err(|e| vec![e])?);
        }
        let start = one(v.point(&h.start))?;
        let angle = v.eval(&h.angle).map_err(|e| vec![e])?;
        let u = [angle.cos(), angle.sin()];
        let n = [-u[1], u[0]];
        let length = h.kind.length(&dims);
        let end = add(start, scale(u, length));
        let root = h.kind.root_thickness(&dims);
        let fillet = if h.kind.has_sharp_roots() {
            s.fillet_radius
        } else {
            0.0
        };
        let (f0, f1) = (add(start, scale(u, -fillet)), add(end, scale(u, fillet)));
        let half = 0.5 * root + fillet + s.pad_margin;
        let body = band(f0, f1, 0.5 * root);
        // the pads: behind each face, their face edge holding the hinge's corners
        let pad_from = vec![
            add(add(f0, scale(u, -s.pad)), scale(n, -half)),
            add(f0, scale(n, -half)),
            body[0],
            body[3],
            add(f0, scale(n, half)),
            add(add(f0, scale(u, -s.pad)), scale(n, half)),
        ];
        let pad_to = vec![
            add(f1, scale(n, -half)),
            add(add(f1, scale(u, s.pad)), scale(n, -half)),
            add(add(f1, scale(u, s.pad)), scale(n, half)),
            add(f1, scale(n, half)),
            body[2],
            body[1],
        ];
        // the ground is held on a pad's far side, along the pad's outline
        let clamp_from = h.from.is_none().then(|| (pad_from[5], pad_from[0]));
        let clamp_to = h.to.is_none().then(|| (pad_to[1], pad_to[2]));
        let pad = |side: &str, points| Solid {
            name: format!("the pad at hinge {}'s {side}", h.name),
            points,
        };
        cut.push(CutHinge {
            solid: Solid {
                name: format!("hinge {}", h.name),
                points: body,
            },
            site: HingeSite {
                name: h.name.clone(),
                start,
                end,
                thickness: h.kind.least_thickness(&dims),
                root,
                fillet,
                kind: h.kind.name(),
                profile: h.kind.outline(&dims),
                solid: 0,
            },
            from: slot(h.from),
            to: slot(h.to),
            pads: [
                (pad("start", pad_from), clamp_from),
                (pad("end", pad_to), clamp_to),
            ],
        });
    }

    // the bodies as drawn, or the hull of their pads; a body across an axis with its image
    // about it, so that its two halves are one solid
    let mut shapes: Vec<(usize, Solid)> = Vec::new();
    if d.ground.len() >= 3 {
        let mut points = Vec::with_capacity(d.ground.len());
        for p in &d.ground {
            points.push(one(v.point(p))?);
        }
        for (i, points) in convex_pieces(points).into_iter().enumerate() {
            let name = if i == 0 {
                "the ground".to_string()
            } else {
                format!("the ground ({})", i + 1)
            };
            shapes.push((0, Solid { name, points }));
        }
    }
    for (b, body) in d.bodies.iter().enumerate() {
        let mut points = Vec::with_capacity(body.points.len());
        for p in &body.points {
            points.push(one(v.point(p))?);
        }
        let mut drawn: Vec<Vec<P>> = match (&body.link_width, points.len()) {
            (Some(w), 2) => {
                let width = v.length(w).map_err(|e| vec![e])?;
                vec![band(points[0], points[1], 0.5 * width)]
            }
            (_, 0) => {
                let all: Vec<P> = cut
                    .iter()
                    .flat_map(|c| {
                        [(c.from, &c.pads[0].0), (c.to, &c.pads[1].0)]
                            .into_iter()
                            .filter(|(o, _)| *o == b + 1)
                            .flat_map(|(_, p)| p.points.iter().copied())
                    })
                    .collect();
                vec![convex_hull(&all)]
            }
            _ => convex_pieces(points),
        };
        if !body.on_axis.is_empty() {
            let selves: Vec<Image> = Image::all(&body.on_axis);
            for shape in &mut drawn {
                let all: Vec<P> = selves
                    .iter()
                    .flat_map(|t| shape.iter().map(|&p| t.point(p)))
                    .collect();
                *shape = convex_hull(&all);
            }
        }
        for (i, points) in drawn.into_iter().enumerate() {
            let name = if i == 0 {
                format!("body {}", body.name)
            } else {
                format!("body {} ({})", body.name, i + 1)
            };
            shapes.push((b + 1, Solid { name, points }));
        }
    }

    // the whole: each image of the described part
    let images = Image::all(&d.mirror);
    let mut solids: Vec<Solid> = Vec::new();
    let mut hinges: Vec<HingeSite> = Vec::new();
    let mut joints: Vec<(usize, usize)> = Vec::new();
    let mut faces: Vec<Face> = Vec::new();
    let mut owners: Vec<(BodyKey, usize)> = Vec::new();
    let key = |b: usize, t: Image| -> BodyKey {
        if b == 0 {
            (0, Image::IDENTITY)
        } else {
            (b, t.of_body(own[b]))
        }
    };
    // the sides the ground may be held on: (its solid, its ends)
    let mut held: Vec<(usize, P, P)> = Vec::new();
    // each hinge image's solid and the bodies it meets
    let mut meets: Vec<(usize, BodyKey, BodyKey)> = Vec::new();
    for &t in &images {
        for c in &cut {
            let k = solids.len();
            solids.push(Solid {
                name: format!("{}{}", c.solid.name, t.suffix()),
                points: t.polygon(&c.solid.points),
            });
            hinges.push(HingeSite {
                name: format!("{}{}", c.site.name, t.suffix()),
                start: t.point(c.site.start),
                end: t.point(c.site.end),
                solid: k,
                ..c.site.clone()
            });
            let (from, to) = (key(c.from, t), key(c.to, t));
            meets.push((k, from, to));
            for ((pad, clamp), body) in c.pads.iter().zip([from, to]) {
                let p = solids.len();
                solids.push(Solid {
                    name: format!("{}{}", pad.name, t.suffix()),
                    points: t.polygon(&pad.points),
                });
                joints.push((k, p));
                owners.push((body, p));
                if let Some((a, b)) = clamp {
                    held.push((p, t.point(*a), t.point(*b)));
                }
            }
        }
        for (b, shape) in &shapes {
            let body = key(*b, t);
            if t.of_body(own[*b]) != t {
                // the image of a body across an axis about that axis: the body itself
                continue;
            }
            let k = solids.len();
            let points = t.polygon(&shape.points);
            if *b == 0 {
                let n = points.len();
                held.extend((0..n).map(|i| (k, points[i], points[(i + 1) % n])));
            }
            solids.push(Solid {
                name: format!("{}{}", shape.name, t.suffix()),
                points,
            });
            owners.push((body, k));
        }
    }
    // the ground is held wherever its outline and its pads' far sides are the part's
    faces.extend(held.iter().flat_map(|&(k, a, b)| {
        exposed(&solids, k, a, b).into_iter().map(|(a, b)| Face {
            name: "clamp".into(),
            a,
            b,
        })
    }));
    let of = |body: BodyKey| -> Vec<usize> {
        owners
            .iter()
            .filter(|(o, _)| *o == body)
            .map(|&(_, k)| k)
            .collect()
    };
    // a hinge meets its two bodies through its faces, and every solid of a body is joined
    // to every other of it
    for &(own, from, to) in &meets {
        for k in of(from).into_iter().chain(of(to)) {
            if !joints.contains(&(own, k)) {
                joints.push((own, k));
            }
        }
    }
    let mut bodies: Vec<BodyKey> = owners.iter().map(|(o, _)| *o).collect();
    bodies.dedup();
    bodies.sort_by_key(|&(b, t)| (b, t.flip_x, t.flip_y));
    bodies.dedup();
    for &body in &bodies {
        let list = of(body);
        for (i, &a) in list.iter().enumerate() {
            for &c in &list[i + 1..] {
                joints.push((a, c));
            }
        }
    }

    // the ports' faces, on the side the force comes from, and their images
    let mut problems = Vec::new();
    let ports = std::iter::once(("input".to_string(), &d.input))
        .chain(d.outputs.iter().map(|o| (format!("output_{}", o.name), o)));
    let mut placed: Vec<PlacedPort> = Vec::new();
    for (name, port) in ports {
        let at = one(v.point(&port.at))?;
        let dir = one(v.point(&port.direction))?;
        let norm = dir[0].hypot(dir[1]);
        let dir = [dir[0] / norm, dir[1] / norm];
        let body = key(port.body + 1, Image::IDENTITY);
        let mine = of(body);
        let body_name = &d.bodies[port.body].name;
        match port_face(&solids, &mine, at, dir, s.face) {
            Err(FaceProblem::Outside) => problems.push(format!(
                "port {name} at ({:.3}, {:.3}) mm lies on no solid of body \"{body_name}\": put \
                 it on the body",
                at[0] * 1e3,
                at[1] * 1e3,
            )),
            Err(FaceProblem::Corner) => problems.push(format!(
                "port {name}: its face falls on a corner of body \"{body_name}\"; move the port \
                 along the body's edge"
            )),
            Err(FaceProblem::Covered(q, other)) => problems.push(format!(
                "port {name}: its face at ({:.3}, {:.3}) mm lies on {}; move the port clear of \
                 it",
                q[0] * 1e3,
                q[1] * 1e3,
                solids[other].name
            )),
            Ok(face) => placed.push(PlacedPort {
                name,
                face,
                direction: dir,
                across: port.across,
                own: &d.bodies[port.body].on_axis,
            }),
        }
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let grounded = faces.iter().any(|f| f.name == "clamp");
    let check = ports_check(&placed, &images, grounded, &mut faces).map_err(|e| vec![e])?;
    Ok(PartSpec {
        width: d.width,
        actuation: Some(part.actuation),
        analysis: Some(check),
        solids,
        joints,
        hinges,
        faces,
        annotations: Vec::new(),
        caption: format!(
            "flexure network: {} bodies, {} hinges{}",
            d.bodies.len(),
            d.hinges.len(),
            if images.len() > 1 {
                format!(", {} images of the described part", images.len())
            } else {
                String::new()
            }
        ),
        min_slot: s.min_slot,
        actuator: None,
        warnings: Vec::new(),
    })
}

/// The stretches of the side `a`-`b` of solid `own` that no other solid covers: the part's
/// outline there. The side itself where nothing covers it.
fn exposed(solids: &[Solid], own: usize, a: P, b: P) -> Vec<(P, P)> {
    // shorter stretches are left free: a sliver beside a pad is no place to hold a part
    const SHORTEST: f64 = 0.1e-3;
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let e = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    let mut cover: Vec<(f64, f64)> = solids
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != own)
        .filter_map(|(_, s)| covered(&s.points, a, e, 0.0, len))
        .filter(|&(c0, c1)| c1 - c0 > 1e-9)
        .collect();
    if cover.is_empty() {
        return vec![(a, b)];
    }
    cover.sort_by(|x, y| x.0.total_cmp(&y.0));
    cover.push((len, len));
    let at = |s: f64| {
        if s <= 1e-9 {
            a
        } else if s >= len - 1e-9 {
            b
        } else {
            add(a, scale(e, s))
        }
    };
    let mut out = Vec::new();
    let mut from = 0.0;
    for (c0, c1) in cover {
        if c0 - from >= SHORTEST {
            out.push((at(from), at(c0)));
        }
        from = f64::max(from, c1);
    }
    out
}

/// A port's face on the described part: its name, ends, the port's direction and axis.
struct PlacedPort<'a> {
    name: String,
    face: (P, P),
    direction: P,
    across: Option<Axis>,
    /// The axes its body lies across.
    own: &'a [Axis],
}

enum FaceProblem {
    Outside,
    Corner,
    /// Where the face would be, and the solid it lies on.
    Covered(P, usize),
}

/// The face of the port at `at` along `dir` on the body whose solids are `mine`: where the
/// line leaves the body on the side the force comes from, `length` long or shorter where the
/// edge is, and off every other solid.
fn port_face(
    solids: &[Solid],
    mine: &[usize],
    at: P,
    dir: P,
    length: f64,
) -> Result<(P, P), FaceProblem> {
    let back = [-dir[0], -dir[1]];
    // through the body's convex pieces (its triangles, its pads) until the line leaves them
    // all: a piece's exit inside another piece goes on through that one
    let leave = |p: P| {
        mine.iter()
            .filter_map(|&k| exit(&solids[k].points, p, back).map(|(t, e)| (t, k, e)))
            .max_by(|x, y| x.0.total_cmp(&y.0))
    };
    let (t, mut k, mut e) = leave(at).ok_or(FaceProblem::Outside)?;
    let mut q = add(at, scale(back, t));
    let mut stepped = false;
    for _ in 0..mine.len() {
        match leave(q) {
            Some((t, k2, e2)) if t > 1e-12 => {
                (k, e, stepped) = (k2, e2, true);
                q = add(q, scale(back, t));
            }
            _ => break,
        }
    }
    let poly = &solids[k].points;
    let (a, b) = (poly[e], poly[(e + 1) % poly.len()]);
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let along = ((q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1])) / len;
    let half = (0.5 * length).min(along).min(len - along);
    if half < 1e-6 {
        return Err(FaceProblem::Corner);
    }
    let e_u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    // on the side itself, whatever the steps through the pieces rounded
    let q = if stepped {
        add(a, scale(e_u, along))
    } else {
        q
    };
    // the face keeps off every solid of another body or hinge, whose material stands on
    // that edge there and leaves it no outline
    let (mut lo, mut hi) = (-half, half);
    for (j, other) in solids.iter().enumerate() {
        if mine.contains(&j) {
            continue;
        }
        if let Some((c0, c1)) = covered(&other.points, q, e_u, -half, half) {
            if c0 <= 0.0 && c1 >= 0.0 {
                return Err(FaceProblem::Covered(q, j));
            } else if c1 < 0.0 {
                lo = lo.max(c1);
            } else {
                hi = hi.min(c0);
            }
        }
    }
    if hi <= lo {
        return Err(FaceProblem::Covered(q, k));
    }
    Ok((add(q, scale(e_u, lo)), add(q, scale(e_u, hi))))
}

/// A port's faces on the whole part: the described one and its distinct images, each with
/// its direction, and the share of the port's force each carries (the images on one body
/// share it, as the model's port on a body across an axis does).
struct PortFaces {
    faces: Vec<(String, P, Image)>,
    share: f64,
}

/// The check through the ports on the whole part, its faces added to `faces`. A part
/// without ground is held on the first output's image across its axis (the input's where the
/// output is across none), as the bridge's lower output block is.
fn ports_check(
    placed: &[PlacedPort<'_>],
    images: &[Image],
    grounded: bool,
    faces: &mut Vec<Face>,
) -> Result<Analysis, String> {
    let held = match (grounded, placed[1].across, placed[0].across) {
        (true, _, _) => None,
        (false, Some(_), _) => Some(1),
        (false, None, Some(_)) => Some(0),
        (false, None, None) => {
            return Err(
                "the network has no ground, and neither its input nor its first output \
                        is across a mirror axis: nothing holds its part for the check; join a \
                        hinge to the ground"
                    .into(),
            )
        }
    };
    let mut all = Vec::new();
    for (i, p) in placed.iter().take(2).enumerate() {
        let mut mine: Vec<(String, P, Image, (P, P))> = Vec::new();
        for &t in images {
            let f = (t.point(p.face.0), t.point(p.face.1));
            if mine.iter().any(|m| same_face(m.3, f)) {
                continue;
            }
            let d = t.point(p.direction);
            let name = format!("{}{}", p.name, t.suffix());
            mine.push((name, d, t, f));
        }
        // the images of the port on its own body (about the axes the body lies across)
        // share the port's force, as the model's described half of such a body carries its
        // share of it
        let on_body = mine
            .iter()
            .filter(|m| m.2.of_body(p.own) == Image::IDENTITY)
            .count();
        let held_image = held.filter(|&h| h == i).and(p.across).map(Image::across);
        let mut kept = Vec::new();
        for (name, d, t, f) in mine {
            if Some(t) == held_image {
                faces.push(Face {
                    name: "clamp".into(),
                    a: f.0,
                    b: f.1,
                });
                continue;
            }
            faces.push(Face {
                name: name.clone(),
                a: f.0,
                b: f.1,
            });
            kept.push((name, d, t));
        }
        all.push(PortFaces {
            faces: kept,
            share: 1.0 / on_body as f64,
        });
    }
    let (input, output) = (&all[0], &all[1]);
    let term = |face: &str, direction: P| Term {
        weight: 1.0,
        face: face.into(),
        direction,
    };
    let loads = |p: &PortFaces| -> Vec<Load> {
        p.faces
            .iter()
            .map(|(face, direction, _)| Load {
                face: face.clone(),
                direction: *direction,
                share: p.share,
            })
            .collect()
    };
    // what the model reads: the port's motion, or across an axis the change of its
    // distance from its image (the image's term where the image is not held)
    let reads = |p: &PortFaces, across: Option<Axis>| -> Vec<Term> {
        p.faces
            .iter()
            .filter(|(_, _, t)| {
                *t == Image::IDENTITY || across.is_some_and(|a| *t == Image::across(a))
            })
            .map(|(face, direction, _)| term(face, *direction))
            .collect()
    };
    Ok(analysis(
        loads(input),
        reads(input, placed[0].across),
        loads(output),
        reads(output, placed[1].across),
    ))
}

/// The check through the ports: the test force on the input's faces (the actuation case),
/// the input's and the first output's motions under it; then on the first output's faces,
/// the input free.
fn analysis(
    input_loads: Vec<Load>,
    input_reads: Vec<Term>,
    output_loads: Vec<Load>,
    output_reads: Vec<Term>,
) -> Analysis {
    let out = |name: &'static str, dimension, meaning: &'static str, quantity| FeOutput {
        name,
        dimension,
        meaning,
        quantity,
        converges: quantity != Quantity::PeakStress,
        display: None,
        analytic: None,
    };
    Analysis {
        clamped: vec!["clamp".into()],
        cases: vec![
            LoadCase {
                name: "on the input face".into(),
                loads: input_loads,
            },
            LoadCase {
                name: "on the first output's face".into(),
                loads: output_loads,
            },
        ],
        measures: vec![
            Measure {
                case: 0,
                terms: input_reads,
            },
            Measure {
                case: 0,
                terms: output_reads.clone(),
            },
            Measure {
                case: 1,
                terms: output_reads,
            },
        ],
        outputs: vec![
            out(
                "fe_k_in",
                Dimension::Stiffness,
                "the test force over the input face's motion along the input",
                Quantity::Stiffness(0),
            ),
            out(
                "fe_amplification",
                Dimension::Ratio,
                "the first output face's motion over the input face's, the force on the input",
                Quantity::Ratio {
                    numerator: 1,
                    denominator: 0,
                },
            ),
            out(
                "fe_k_out",
                Dimension::Stiffness,
                "the test force on the first output over its face's motion, the input free",
                Quantity::Stiffness(2),
            ),
            out(
                "fe_stress_section",
                Dimension::Stress,
                "the largest beam stress at the hinges' sections under the actuation",
                Quantity::SectionStress,
            ),
            out(
                "fe_stress_max",
                Dimension::Stress,
                "the largest von Mises stress under the actuation",
                Quantity::PeakStress,
            ),
        ],
        actuation: Some(ActuationCase {
            name: "actuation_force",
            case: 0,
            stiffness: FE_K_IN,
        }),
        modal: None,
    }
}
