//! The network part's manufacturability rules as functions of the design
//! ([`crate::model::part_rules`]): the checks its solids get once placed
//! ([`crate::part::checks::before_union`]) and the spec's size refusals, each a margin in
//! metres, `>= 0` where the part meets it.
//!
//! The solids are rebuilt over [`Scalar`] from the description's expressions as
//! [`super::spec`] places them, in its order: each image of each hinge's and beam's solid and
//! pads, then each image of the bodies' pieces. A rule concerns two *groups*: a flexure's
//! image (its thin section's solid), or a body's image with every solid it owns (its drawn
//! pieces and the pads of its hinges and beams; the ground is one body). For two groups:
//!
//! - a flexure and a body it joins: the body kept behind the flexure's faces, out of its
//!   keep-out band shortened at the end the body meets (the check's `keep_out`);
//! - two groups not joined: their solids at least `part.min_slot` apart, and each out of the
//!   other's keep-out band where it is a flexure. One rule, not three: where they face each
//!   other along a hinge the band's margin and the slot's are the same number, and two rows
//!   with one value and gradient would leave the study's subproblems degenerate.
//!
//! A rule reads the least of its terms' margins over the pairs of pieces, the clearance of
//! two convex pieces by [`crate::model::clearance`]: searched for on `f64`, the winning
//! pair's feature (and, against a band, the end the body meets) then evaluated over dual
//! numbers. A piece drawn as a hull (a body of pads, a body across an axis with its image)
//! is given by all its points, every segment between two of them a side: the clearance of
//! their hull without building it. Mirror images: a pair and its image about an axis have
//! the same margin, so one rule stands for every image of a pair (the bridge's way).
//!
//! The size rules first ([`PartMaker::first_rules`](crate::model::PartMaker::first_rules)):
//! each beam's length and thickness, which the spec refuses at zero. The port faces' own
//! refusals (a port off its body or on a hinge's root) are not rules: they are not
//! functions of the design that change sign where the spec refuses, but searches along a
//! line; the spec still refuses such a part after the study.

use super::super::description::{Axis, Description, Keyed};
use super::images::Image;
use super::plane::{add, convex_piece_indices, scale};
use super::settings::PartSettings;
use super::values::Values;
use crate::model::clearance::{clearance, clearance_below, Feature, Pt, Solid};
use crate::model::expression::Tape;
use crate::model::hinge::{HingeKind, MAX_HINGE_DIMENSIONS};
use crate::model::part_rules::{PartRule, Witness};
use crate::model::scalar::{max, min, with_count, Jet, Scalar};
use crate::model::Dimension;

/// The margin (m) a clearance rule reads when every pair is farther than this beyond it:
/// the search looks only at the pieces whose bounding boxes come within it.
pub use crate::model::part_rules::CAP;

/// How far the keep-out bands stop short of the faces at the hinge's ends (m), as the
/// part's check has them ([`crate::part::checks::keep_out`]).
const FACE_INSET: f64 = 1e-9;

/// What a rule names: a flexure's image (the index among the hinges, then the beams) or a
/// body's image (its slot, 0 the ground, and the image it is, the ground's the identity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Group {
    Flexure(usize, Image),
    Body(usize, Image),
}

/// The rules of a network's part that do not depend on the design: the groups, the pairs
/// the rules look at (one of each set of mirror images) and their names.
#[derive(Debug, Clone)]
pub struct Layout {
    groups: Vec<Group>,
    /// Each rule after the size rules: its two groups.
    rows: Vec<(usize, usize)>,
    rules: Vec<PartRule>,
    /// How many size rules come first: two per beam.
    first: usize,
    /// The axes each body (by slot) lies across.
    own: Vec<Vec<Axis>>,
    /// Each flexure's bodies by slot.
    ends: Vec<(usize, usize)>,
    /// The expressions the solids are placed by, compiled together as the model's are: a
    /// tree walk per expression was a third of a study's time with the rules.
    tape: Tape,
    /// The sides of a piece of `n` corners, by `n`: each corner to the next around it
    /// (`rings`), or every segment between two of them (`pairs`, for a hull), worked out
    /// once rather than at each evaluation.
    rings: Vec<Vec<(usize, usize)>>,
    pairs: Vec<Vec<(usize, usize)>>,
    /// The described part's images, and each body's own (by slot): the bodies across an
    /// axis are drawn with their images.
    images: Vec<Image>,
    selves: Vec<Vec<Image>>,
    /// The most corners the bodies as drawn have together, and the whole part's solids.
    drawn_corners: usize,
    corners: usize,
}

impl Group {
    /// The group this one is under the image `s`.
    fn under(self, s: Image, own: &[Vec<Axis>]) -> Group {
        match self {
            Group::Flexure(c, t) => Group::Flexure(c, s.then(t)),
            Group::Body(0, t) => Group::Body(0, t),
            Group::Body(b, t) => Group::Body(b, s.then(t).of_body(&own[b])),
        }
    }
}

/// The body key of slot `b` in the image `t`: its own image where it lies across an axis.
fn key(own: &[Vec<Axis>], b: usize, t: Image) -> Group {
    if b == 0 {
        Group::Body(0, Image::IDENTITY)
    } else {
        Group::Body(b, t.of_body(&own[b]))
    }
}

/// Every expression the solids are placed by, in the order [`Layout::shapes`] reads them.
fn placing(d: &mut Description) -> Vec<&mut Keyed> {
    let mut all: Vec<&mut Keyed> = Vec::new();
    for h in &mut d.hinges {
        all.extend(h.dimensions.iter_mut());
        all.push(&mut h.angle);
        all.extend(h.start.iter_mut());
    }
    for b in &mut d.beams {
        all.extend(b.start.iter_mut().chain(b.end.iter_mut()));
        all.push(&mut b.thickness);
    }
    all.extend(d.ground.iter_mut().flatten());
    for b in &mut d.bodies {
        all.extend(b.points.iter_mut().flatten());
        all.extend(b.link_width.iter_mut());
    }
    all
}

/// The most corners each body's pieces can have together (by slot, the ground first): its
/// outline, its link's band or the hull of its pads (six corners each), with its images
/// where it lies across an axis.
fn body_corners(d: &Description, ends: &[(usize, usize)]) -> Vec<usize> {
    let bodies = d.bodies.iter().enumerate().map(|(b, body)| {
        let own = match (&body.link_width, body.points.len()) {
            (Some(_), 2) => 4,
            (_, 0) => {
                6 * ends
                    .iter()
                    .filter(|&&(f, t)| f == b + 1 || t == b + 1)
                    .count()
            }
            // an outline's pieces: itself, or at most n - 2 triangles
            (_, n) => n.max(3 * n.saturating_sub(2)),
        };
        own << body.on_axis.len()
    });
    let ground = d.ground.len().max(3 * d.ground.len().saturating_sub(2));
    std::iter::once(ground).chain(bodies).collect()
}

impl Layout {
    /// The layout of the description's part; the expressions it reads are given their
    /// slots in the layout's own tape (the part's copy of the description).
    pub fn new(d: &mut Description) -> Layout {
        let tape = {
            let names = d.parameters.len() + 1;
            let mut all = placing(d);
            for (slot, e) in all.iter_mut().enumerate() {
                e.slot = slot;
            }
            Tape::compile(all.iter().map(|e| &e.expression), names)
        };
        let d = &*d;
        let slot = |b: Option<usize>| b.map_or(0, |b| b + 1);
        let own: Vec<Vec<Axis>> = std::iter::once(Vec::new())
            .chain(d.bodies.iter().map(|b| b.on_axis.clone()))
            .collect();
        let ends: Vec<(usize, usize)> = d
            .hinges
            .iter()
            .map(|h| (slot(h.from), slot(h.to)))
            .chain(d.beams.iter().map(|b| (slot(b.from), slot(b.to))))
            .collect();
        let images = Image::all(&d.mirror);
        let mut groups = Vec::new();
        for &t in &images {
            groups.extend((0..ends.len()).map(|c| Group::Flexure(c, t)));
        }
        let grounded = d.ground.len() >= 3 || ends.iter().any(|&(a, b)| a == 0 || b == 0);
        if grounded {
            groups.push(Group::Body(0, Image::IDENTITY));
        }
        for b in 1..own.len() {
            for &t in &images {
                let k = key(&own, b, t);
                if !groups.contains(&k) {
                    groups.push(k);
                }
            }
        }
        let index = |g: Group| groups.iter().position(|&h| h == g);
        let mut rows = Vec::new();
        for i in 0..groups.len() {
            for j in i + 1..groups.len() {
                // the first of the pair's images stands for them all
                let first = images
                    .iter()
                    .filter_map(|&s| {
                        let a = index(groups[i].under(s, &own))?;
                        let b = index(groups[j].under(s, &own))?;
                        Some((a.min(b), a.max(b)))
                    })
                    .min();
                let body_pair =
                    matches!((groups[i], groups[j]), (Group::Body(..), Group::Body(..)));
                // a body's images are one solid where it lies across the axis; two images of
                // one body are apart by what the description draws
                if first == Some((i, j)) || (body_pair && first.is_none()) {
                    rows.push((i, j));
                }
            }
        }
        let bodies = body_corners(d, &ends);
        let most = bodies.iter().copied().chain([6]).max().unwrap_or(6);
        let drawn_corners: usize = bodies.iter().sum::<usize>() * 2;
        let selves = own.iter().map(|axes| Image::all(axes)).collect();
        let corners = images.len() * (16 * ends.len() + drawn_corners);
        let mut layout = Layout {
            groups,
            rows,
            rules: Vec::new(),
            first: 2 * d.beams.len(),
            own,
            ends,
            tape,
            rings: (0..=most).map(around).collect(),
            pairs: (0..=most).map(all_pairs).collect(),
            selves,
            corners,
            drawn_corners,
            images,
        };
        layout.rules = layout.names(d);
        layout
    }

    pub fn rules(&self) -> &[PartRule] {
        &self.rules
    }

    pub fn first_rules(&self) -> usize {
        self.first
    }

    fn name(&self, d: &Description, g: Group) -> String {
        match g {
            Group::Flexure(c, t) if c < d.hinges.len() => {
                format!("hinge {}{}", d.hinges[c].name, t.suffix())
            }
            Group::Flexure(c, t) => {
                format!("beam {}{}", d.beams[c - d.hinges.len()].name, t.suffix())
            }
            Group::Body(0, _) => "the ground".to_string(),
            Group::Body(b, t) => format!("body {}{}", d.bodies[b - 1].name, t.suffix()),
        }
    }

    /// Whether the flexure group `f` joins the body group `b`.
    fn joins(&self, f: Group, b: Group) -> bool {
        let Group::Flexure(c, t) = f else {
            return false;
        };
        let (from, to) = self.ends[c];
        key(&self.own, from, t) == b || key(&self.own, to, t) == b
    }

    fn names(&self, d: &Description) -> Vec<PartRule> {
        let mut out = Vec::new();
        for b in &d.beams {
            out.push(PartRule {
                name: format!("beam {}'s length", b.name).into(),
                description: format!("beam {}'s length ({}) positive", b.name, b.key).into(),
            });
            out.push(PartRule {
                name: format!("beam {}'s thickness", b.name).into(),
                description: format!("beam {}'s thickness ({}.thickness) positive", b.name, b.key)
                    .into(),
            });
        }
        for &(i, j) in &self.rows {
            let (a, b) = (self.groups[i], self.groups[j]);
            let (na, nb) = (self.name(d, a), self.name(d, b));
            let (name, description) = if self.joins(a, b) || self.joins(b, a) {
                let (f, body) = if self.joins(a, b) { (na, nb) } else { (nb, na) };
                (
                    format!("{f}'s band, {body}"),
                    format!(
                        "{body} behind the faces of {f}, out of its keep-out band (part.min_slot \
                         or the fillet beside its thin section)"
                    ),
                )
            } else if matches!(a, Group::Flexure(..)) || matches!(b, Group::Flexure(..)) {
                (
                    format!("slot, {na}, {nb}"),
                    format!(
                        "{na} and {nb} at least part.min_slot apart, and out of each other's \
                         keep-out bands (part.min_slot or the fillet beside a thin section)"
                    ),
                )
            } else {
                (
                    format!("slot, {na}, {nb}"),
                    format!("{na} and {nb} at least part.min_slot apart"),
                )
            };
            out.push(PartRule {
                name: name.into(),
                description: description.into(),
            });
        }
        out
    }
}

/// One solid of the part: where its corners lie among the shapes' corners, whether they go
/// around it in order (else only their hull counts), and its group.
#[derive(Debug, Clone, Copy)]
struct Piece {
    start: usize,
    end: usize,
    ordered: bool,
    group: usize,
}

/// A flexure's image as the check sees it: its centre line, root thickness and fillet, the
/// keep-out band's half width less the root's.
#[derive(Clone, Copy)]
struct Site<D> {
    start: Pt<D>,
    end: Pt<D>,
    root: D,
    fillet: f64,
}

/// The part's solids at a design over `D`, their corners in one vector, with the flexures'
/// sites (by flexure group) and the size rules' margins.
struct Shapes<D> {
    corners: Vec<Pt<D>>,
    pieces: Vec<Piece>,
    sites: Vec<Option<Site<D>>>,
    sizes: Vec<D>,
}

impl<D> Shapes<D> {
    fn corners(&self, k: usize) -> &[Pt<D>] {
        let p = self.pieces[k];
        &self.corners[p.start..p.end]
    }
}

/// The band of half width `half` around the segment `a`-`b`, counterclockwise.
fn band<D: Scalar>(a: Pt<D>, b: Pt<D>, half: D) -> [Pt<D>; 4] {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let n = [-d[1] / len * half, d[0] / len * half];
    [
        [a[0] - n[0], a[1] - n[1]],
        [b[0] - n[0], b[1] - n[1]],
        [b[0] + n[0], b[1] + n[1]],
        [a[0] + n[0], a[1] + n[1]],
    ]
}

/// A flexure as [`super::flexures::cut`] cuts it: its solid, its pads, its site.
struct Cut<D> {
    solid: [Pt<D>; 4],
    pads: [[Pt<D>; 6]; 2],
    site: Site<D>,
}

fn cut<D: Scalar>(kind: HingeKind, dims: &[D], start: Pt<D>, u: Pt<D>, s: &PartSettings) -> Cut<D> {
    let n = [-u[1], u[0]];
    let end = add(start, scale(u, kind.length(dims)));
    let root = kind.root_thickness(dims);
    let fillet = if kind.has_sharp_roots() {
        s.fillet_radius
    } else {
        0.0
    };
    let f0 = add(start, scale(u, D::from(-fillet)));
    let f1 = add(end, scale(u, D::from(fillet)));
    let half = root * 0.5 + (fillet + s.pad_margin);
    let r = root * 0.5;
    let at = |p: Pt<D>, along: f64, side: D| add(add(p, scale(u, D::from(along))), scale(n, side));
    let solid = [
        at(f0, 0.0, -r),
        at(f1, 0.0, -r),
        at(f1, 0.0, r),
        at(f0, 0.0, r),
    ];
    let pads = [
        [
            at(f0, -s.pad, -half),
            at(f0, 0.0, -half),
            solid[0],
            solid[3],
            at(f0, 0.0, half),
            at(f0, -s.pad, half),
        ],
        [
            at(f1, 0.0, -half),
            at(f1, s.pad, -half),
            at(f1, s.pad, half),
            at(f1, 0.0, half),
            solid[2],
            solid[1],
        ],
    ];
    Cut {
        solid,
        pads,
        site: Site {
            start,
            end,
            root,
            fillet,
        },
    }
}

impl Layout {
    /// The part's solids at the design `x` over `D`, in [`super::spec`]'s order; `None`
    /// where an expression has no value there (the model refuses such a design too). The
    /// expressions from the layout's tape, which computes what their trees do operation
    /// for operation; where it fails, from the trees, which say whether any has no value.
    /// Only the pieces `keep` tells have their corners (the others none, in their place).
    fn shapes<D: Scalar>(
        &self,
        d: &Description,
        s: &PartSettings,
        x: &[D],
        keep: impl Fn(usize) -> bool,
    ) -> Option<Shapes<D>> {
        let v = Values::new(d, x);
        let mut registers = Vec::with_capacity(self.tape.registers());
        if self.tape.run(&v.values, &mut registers) {
            let eval = |e: &Keyed| Some(registers[self.tape.output(e.slot)]);
            self.shapes_from(d, s, eval, keep)
        } else {
            self.shapes_from(d, s, |e: &Keyed| v.eval(e).ok(), keep)
        }
    }

    fn shapes_from<D: Scalar>(
        &self,
        d: &Description,
        s: &PartSettings,
        eval: impl Fn(&Keyed) -> Option<D>,
        keep: impl Fn(usize) -> bool,
    ) -> Option<Shapes<D>> {
        let length = |e: &Keyed| Some(eval(e)? * d.unit);
        let point = |p: &[Keyed; 2]| Some([length(&p[0])?, length(&p[1])?]);
        let mut cuts = Vec::with_capacity(d.hinges.len() + d.beams.len());
        let mut sizes = Vec::with_capacity(2 * d.beams.len());
        for h in &d.hinges {
            let mut dims = [D::from(0.0); MAX_HINGE_DIMENSIONS];
            for ((e, info), dim) in h.dimensions.iter().zip(h.kind.dimensions()).zip(&mut dims) {
                *dim = if info.dimension == Dimension::Length {
                    length(e)?
                } else {
                    eval(e)?
                };
            }
            let (sin, cos) = eval(&h.angle)?.sin_cos();
            let dims = &dims[..h.dimensions.len()];
            cuts.push(cut(h.kind, dims, point(&h.start)?, [cos, sin], s));
        }
        for b in &d.beams {
            let (start, end) = (point(&b.start)?, point(&b.end)?);
            let thickness = length(&b.thickness)?;
            let along = [end[0] - start[0], end[1] - start[1]];
            let length = (along[0] * along[0] + along[1] * along[1]).sqrt();
            sizes.extend([length, thickness]);
            let u = if length.re() > 0.0 {
                scale(along, length.recip())
            } else {
                [D::from(1.0), D::from(0.0)]
            };
            cuts.push(cut(HingeKind::Strip, &[length, thickness], start, u, s));
        }
        // the bodies as drawn: each piece's body, its corners among `at`, and whether they
        // go around it
        let mut at: Vec<Pt<D>> = Vec::with_capacity(self.drawn_corners);
        let mut drawn: Vec<(usize, usize, usize, bool)> = Vec::with_capacity(self.drawn_corners);
        let mut points: Vec<Pt<D>> = Vec::with_capacity(self.drawn_corners);
        let outline = |b: usize,
                       points: &[Pt<D>],
                       at: &mut Vec<Pt<D>>,
                       drawn: &mut Vec<(usize, usize, usize, bool)>| {
            let real: Vec<[f64; 2]> = points.iter().map(|p| [p[0].re(), p[1].re()]).collect();
            for piece in convex_piece_indices(&real) {
                let first = at.len();
                at.extend(piece.iter().map(|&k| points[k]));
                drawn.push((b, first, at.len(), true));
            }
        };
        if d.ground.len() >= 3 {
            points.clear();
            for p in &d.ground {
                points.push(point(p)?);
            }
            outline(0, &points, &mut at, &mut drawn);
        }
        for (b, body) in d.bodies.iter().enumerate() {
            points.clear();
            for p in &body.points {
                points.push(point(p)?);
            }
            let first = drawn.len();
            match (&body.link_width, points.len()) {
                (Some(w), 2) => {
                    let start = at.len();
                    at.extend(band(points[0], points[1], length(w)? * 0.5));
                    drawn.push((b + 1, start, at.len(), true));
                }
                (_, 0) => {
                    let start = at.len();
                    for (c, &(from, to)) in cuts.iter().zip(&self.ends) {
                        for (o, pad) in [(from, &c.pads[0]), (to, &c.pads[1])] {
                            if o == b + 1 {
                                at.extend_from_slice(pad);
                            }
                        }
                    }
                    drawn.push((b + 1, start, at.len(), false));
                }
                _ => outline(b + 1, &points, &mut at, &mut drawn),
            }
            if !body.on_axis.is_empty() {
                for piece in &mut drawn[first..] {
                    let (_, from, to, _) = *piece;
                    let start = at.len();
                    for &t in &self.selves[b + 1] {
                        for k in from..to {
                            at.push(t.point(at[k]));
                        }
                    }
                    *piece = (b + 1, start, at.len(), false);
                }
            }
        }
        let group = |g: Group| {
            self.groups
                .iter()
                .position(|&h| h == g)
                .expect("every solid's group is among the layout's")
        };
        let mut corners = Vec::with_capacity(self.corners);
        let mut pieces = Vec::with_capacity(self.corners / 3);
        let mut sites = vec![None; self.groups.len()];
        let mut push = |points: &mut dyn Iterator<Item = Pt<D>>, ordered: bool, group: usize| {
            let start = corners.len();
            if keep(pieces.len()) {
                corners.extend(points);
            }
            pieces.push(Piece {
                start,
                end: corners.len(),
                ordered,
                group,
            });
        };
        for &t in &self.images {
            for (c, cut) in cuts.iter().enumerate() {
                let f = group(Group::Flexure(c, t));
                push(&mut cut.solid.iter().map(|&p| t.point(p)), true, f);
                sites[f] = Some(Site {
                    start: t.point(cut.site.start),
                    end: t.point(cut.site.end),
                    ..cut.site
                });
                let (from, to) = self.ends[c];
                for (pad, body) in cut.pads.iter().zip([from, to]) {
                    let g = group(key(&self.own, body, t));
                    push(&mut pad.iter().map(|&p| t.point(p)), true, g);
                }
            }
            for &(b, from, to, ordered) in &drawn {
                if t.of_body(&self.own[b]) != t {
                    continue;
                }
                let g = group(key(&self.own, b, t));
                push(&mut at[from..to].iter().map(|&p| t.point(p)), ordered, g);
            }
        }
        Some(Shapes {
            corners,
            pieces,
            sites,
            sizes,
        })
    }
}

/// Which of a flexure's keep-out bands a term compares: the whole, or shortened at the end
/// the body it joins meets ([`crate::part::checks::keep_out`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Band {
    Whole,
    Start,
    End,
}

/// The keep-out band of `site`, `slot` beyond its root's half thickness to each side.
fn keep_out<D: Scalar>(site: &Site<D>, slot: f64, which: Band) -> [Pt<D>; 4] {
    let d = [site.end[0] - site.start[0], site.end[1] - site.start[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let u = [d[0] / len, d[1] / len];
    let n = [-u[1], u[0]];
    let w = site.root * 0.5 + slot;
    let whole = [
        D::from(-site.fillet + FACE_INSET),
        len + (site.fillet - FACE_INSET),
    ];
    let [a, b] = match which {
        Band::Whole => whole,
        Band::Start => [min(whole[0] + w, whole[1]), whole[1]],
        Band::End => [whole[0], max(whole[1] - w, whole[0])],
    };
    let at = |along: D, side: D| add(add(site.start, scale(u, along)), scale(n, side));
    [at(a, -w), at(b, -w), at(b, w), at(a, w)]
}

/// A shape a term compares: a solid (by its index among the pieces) or a flexure's band.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Solid(usize),
    Band(usize, Band),
}

/// What gives a clearance rule's margin at a design: the pair of shapes, the feature of
/// their clearance and the slot asked.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Nearest {
    a: Shape,
    b: Shape,
    feature: Feature,
    need: f64,
}

const EMPTY: [f64; 4] = [
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
];

/// A piece's bounding box: least and largest `x`, then `y`. By comparisons, which pass over
/// a NaN as `f64::min` does, without its handling of one at every corner.
fn bounds(corners: &[Pt<f64>]) -> [f64; 4] {
    let mut b = EMPTY;
    for p in corners {
        if p[0] < b[0] {
            b[0] = p[0];
        }
        if p[0] > b[1] {
            b[1] = p[0];
        }
        if p[1] < b[2] {
            b[2] = p[1];
        }
        if p[1] > b[3] {
            b[3] = p[1];
        }
    }
    b
}

/// The box holding both boxes.
fn union(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}

/// The boxes' gap along an axis: a lower bound of the clearance of what they hold.
fn gap(a: [f64; 4], b: [f64; 4]) -> f64 {
    (b[0] - a[1])
        .max(a[0] - b[1])
        .max((b[2] - a[3]).max(a[2] - b[3]))
}

/// Every segment between two of `n` corners: a hull's sides among them.
fn all_pairs(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// Each corner to the next, around.
fn around(n: usize) -> Vec<(usize, usize)> {
    (0..n).map(|i| (i, (i + 1) % n)).collect()
}

/// The f64 geometry of a design for the search: the shapes, each flexure's three bands (by
/// flexure group) and the boxes of the pieces, the bands and the groups, the pieces by
/// group.
struct Search<'a> {
    layout: &'a Layout,
    shapes: &'a Shapes<f64>,
    slot: f64,
    boxes: Vec<[f64; 4]>,
    bands: Vec<Option<[[Pt<f64>; 4]; 3]>>,
    band_boxes: Vec<[[f64; 4]; 3]>,
    /// Each group's box: its pieces' and, for a flexure, its whole band's.
    group_boxes: Vec<[f64; 4]>,
    /// The pieces in order of their group, and where each group's begin.
    by_group: Vec<usize>,
    group_start: Vec<usize>,
}

const BANDS: [Band; 3] = [Band::Whole, Band::Start, Band::End];
const IN_ORDER: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];

impl<'a> Search<'a> {
    fn new(layout: &'a Layout, shapes: &'a Shapes<f64>, s: &PartSettings) -> Self {
        let slot_of = |site: &Site<f64>| site.fillet.max(s.min_slot);
        let boxes: Vec<[f64; 4]> = (0..shapes.pieces.len())
            .map(|k| bounds(shapes.corners(k)))
            .collect();
        let bands: Vec<Option<[[Pt<f64>; 4]; 3]>> = shapes
            .sites
            .iter()
            .map(|site| site.map(|site| BANDS.map(|b| keep_out(&site, slot_of(&site), b))))
            .collect();
        let band_boxes: Vec<[[f64; 4]; 3]> = bands
            .iter()
            .map(|b| {
                b.as_ref()
                    .map_or([EMPTY; 3], |b| b.each_ref().map(|c| bounds(c)))
            })
            .collect();
        let groups = layout.groups.len();
        let mut group_boxes: Vec<[f64; 4]> = band_boxes.iter().map(|b| b[0]).collect();
        group_boxes.resize(groups, EMPTY);
        let mut count = vec![0; groups + 1];
        for (p, &b) in shapes.pieces.iter().zip(&boxes) {
            group_boxes[p.group] = union(group_boxes[p.group], b);
            count[p.group + 1] += 1;
        }
        for g in 0..groups {
            count[g + 1] += count[g];
        }
        let group_start = count.clone();
        let mut by_group = vec![0; shapes.pieces.len()];
        for (k, p) in shapes.pieces.iter().enumerate() {
            by_group[count[p.group]] = k;
            count[p.group] += 1;
        }
        Search {
            layout,
            shapes,
            slot: s.min_slot,
            boxes,
            bands,
            band_boxes,
            group_boxes,
            by_group,
            group_start,
        }
    }

    /// The pieces of group `g`, in their order among the pieces.
    fn of(&self, g: usize) -> &[usize] {
        &self.by_group[self.group_start[g]..self.group_start[g + 1]]
    }

    fn corners(&self, shape: Shape) -> &[Pt<f64>] {
        match shape {
            Shape::Solid(k) => self.shapes.corners(k),
            Shape::Band(f, b) => &self.bands[f].as_ref().expect("a flexure's band")[b as usize],
        }
    }

    fn solid(&self, shape: Shape) -> (Solid<'_>, [f64; 4]) {
        match shape {
            Shape::Solid(k) => {
                let p = self.shapes.pieces[k];
                let n = p.end - p.start;
                let sides = if p.ordered {
                    &self.layout.rings[n]
                } else {
                    &self.layout.pairs[n]
                };
                (
                    Solid {
                        corners: self.shapes.corners(k),
                        sides,
                    },
                    self.boxes[k],
                )
            }
            Shape::Band(f, b) => (
                Solid {
                    corners: self.corners(shape),
                    sides: &IN_ORDER,
                },
                self.band_boxes[f][b as usize],
            ),
        }
    }

    /// The end of the flexure `f` at which the piece `k` meets it: the one whose face is
    /// nearer, as the check's `joint` has it.
    fn joint(&self, f: usize, k: usize) -> Band {
        let site = self.shapes.sites[f].expect("a flexure's site");
        let d = [site.end[0] - site.start[0], site.end[1] - site.start[1]];
        let len = d[0].hypot(d[1]);
        let u = [d[0] / len, d[1] / len];
        let face = |p: Pt<f64>, along: f64| [p[0] + along * u[0], p[1] + along * u[1]];
        let (piece, _) = self.solid(Shape::Solid(k));
        let to = |p: Pt<f64>| {
            let point = Solid {
                corners: &[p],
                sides: &[],
            };
            clearance(point, piece).0.max(0.0)
        };
        if to(face(site.start, -site.fillet)) <= to(face(site.end, site.fillet)) {
            Band::Start
        } else {
            Band::End
        }
    }

    /// The least margin below `least` of the rule `(i, j)`'s terms (each pair of shapes it
    /// compares, with the slot asked), and what gives it. A term whose boxes are at least
    /// `least` beyond its slot apart cannot give it and is passed over (its group's pair
    /// first): its value would be the same.
    fn nearest(&self, (i, j): (usize, usize), mut least: f64) -> Option<(f64, Nearest)> {
        if gap(self.group_boxes[i], self.group_boxes[j]) >= least + 1e-12 {
            return None;
        }
        let mut best = None;
        let mut term = |a: Shape, b: Shape, need: f64, least: &mut f64| {
            let ((sa, ba), (sb, bb)) = (self.solid(a), self.solid(b));
            if gap(ba, bb) >= *least + need + 1e-12 {
                return;
            }
            if let Some((c, feature)) = clearance_below(sa, sb, *least + need) {
                if c - need < *least {
                    *least = c - need;
                    best = Some(Nearest {
                        a,
                        b,
                        feature,
                        need,
                    });
                }
            }
        };
        let layout = self.layout;
        let (gi, gj) = (layout.groups[i], layout.groups[j]);
        let joined = layout.joins(gi, gj) || layout.joins(gj, gi);
        if !joined {
            for &a in self.of(i) {
                for &b in self.of(j) {
                    term(Shape::Solid(a), Shape::Solid(b), self.slot, &mut least);
                }
            }
        }
        for (f, other) in [(i, j), (j, i)] {
            if !matches!(layout.groups[f], Group::Flexure(..)) {
                continue;
            }
            for &k in self.of(other) {
                let band = if joined {
                    // the shortened band lies within the whole one's box
                    if gap(self.band_boxes[f][0], self.boxes[k]) >= least + 1e-12 {
                        continue;
                    }
                    self.joint(f, k)
                } else {
                    Band::Whole
                };
                term(Shape::Band(f, band), Shape::Solid(k), 0.0, &mut least);
            }
        }
        best.map(|b| (least, b))
    }
}

/// What gives each clearance rule's margin at a design, found on the real parts.
struct Selection {
    nearest: Vec<Option<Nearest>>,
}

impl Layout {
    /// Each rule's margin (m) at the design whose real geometry is `shapes`, into `out`
    /// (the first `out.len()` rules), with what gives each clearance.
    fn find(&self, shapes: &Shapes<f64>, s: &PartSettings, out: &mut [f64]) -> Selection {
        let first = self.first.min(out.len());
        out[..first].copy_from_slice(&shapes.sizes[..first]);
        if out.len() == first {
            return Selection {
                nearest: Vec::new(),
            };
        }
        let search = Search::new(self, shapes, s);
        let mut nearest = Vec::new();
        for (o, &row) in out[first..].iter_mut().zip(&self.rows) {
            let chosen = search.nearest(row, CAP).map(|(_, n)| n);
            *o = chosen.map_or(CAP, |n| {
                n.feature.value(search.corners(n.a), search.corners(n.b)) - n.need
            });
            nearest.push(chosen);
        }
        Selection { nearest }
    }
}

impl Selection {
    /// The margins over `D` at `shapes` (the design the selection was found at).
    fn margins<D: Scalar>(
        &self,
        layout: &Layout,
        shapes: &Shapes<D>,
        s: &PartSettings,
        out: &mut [D],
    ) {
        let first = layout.first.min(out.len());
        out[..first].copy_from_slice(&shapes.sizes[..first]);
        let band = |f: usize, b: Band| {
            let site = shapes.sites[f].expect("a flexure's site");
            keep_out(&site, site.fillet.max(s.min_slot), b)
        };
        for (o, n) in out[first..].iter_mut().zip(&self.nearest) {
            *o = n.map_or(D::from(CAP), |n| {
                let (band_a, band_b);
                let a = match n.a {
                    Shape::Solid(k) => shapes.corners(k),
                    Shape::Band(f, b) => {
                        band_a = band(f, b);
                        &band_a
                    }
                };
                let b = match n.b {
                    Shape::Solid(k) => shapes.corners(k),
                    Shape::Band(f, b) => {
                        band_b = band(f, b);
                        &band_b
                    }
                };
                n.feature.value(a, b) - n.need
            });
        }
    }

    /// Whether the piece `k` is among the shapes the margins read.
    fn reads(&self, k: usize) -> bool {
        self.nearest
            .iter()
            .flatten()
            .any(|n| n.a == Shape::Solid(k) || n.b == Shape::Solid(k))
    }
}

/// The network part's rules at a design: its layout, the description and the settings.
pub struct Rules<'a> {
    pub layout: &'a Layout,
    pub d: &'a Description,
    pub s: &'a PartSettings,
}

impl Rules<'_> {
    /// Each rule's margin (m) at the design `x` (SI), the first `out.len()` of them; NaN
    /// where an expression has no value at `x`.
    pub fn margins(&self, x: &[f64], out: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        match self
            .layout
            .shapes(self.d, self.s, x, |_| self.searched(out.len()))
        {
            Some(shapes) => {
                self.layout.find(&shapes, self.s, out);
            }
            None => out.fill(f64::NAN),
        }
    }

    /// As [`Rules::margins`], with their gradients over every parameter, row-major.
    pub fn margins_with_gradient(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        if out.is_empty() {
            return;
        }
        let searched = self.searched(out.len());
        let Some(real) = self.layout.shapes(self.d, self.s, x, |_| searched) else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
            return;
        };
        // the values as `margins` computes them, and the nearest pairs found once, on them
        let selection = self.layout.find(&real, self.s, out);
        let rows = out.len();
        with_count!(x.len(), |N| self
            .gradients::<N>(x, &selection, rows, jacobian));
    }

    /// Whether the first `rows` rules take clearances, not only the size rules: a study's
    /// first stage asks for the size rules alone (none for a network without beams), and
    /// the solids were built and searched at each of its evaluations for nothing.
    fn searched(&self, rows: usize) -> bool {
        rows > self.layout.first
    }

    /// The rows' gradients over `Jet<N>`, `N` the count of parameters.
    fn gradients<const N: usize>(
        &self,
        x: &[f64],
        selection: &Selection,
        rows: usize,
        jacobian: &mut [f64],
    ) {
        let seeded: Vec<Jet<N>> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Jet::variable(v, i))
            .collect();
        // only the pieces the winning pairs read: the others' corners over dual numbers were
        // most of an evaluation with gradients
        let dual = self
            .layout
            .shapes(self.d, self.s, &seeded, |k| selection.reads(k))
            .expect("the expressions have values where their real parts do");
        let mut y = vec![Jet::<N>::from(0.0); rows];
        selection.margins(self.layout, &dual, self.s, &mut y);
        for (row, yi) in jacobian.chunks_exact_mut(N).zip(&y) {
            row.copy_from_slice(&yi.grad);
        }
    }

    /// Where each rule is measured at `x` (SI): the nearest pair's witness points, the slot
    /// asked the limit; none for the size rules and where no pair is near.
    pub fn witnesses(&self, x: &[f64], out: &mut [Option<Witness>]) {
        out.fill(None);
        let Some(shapes) = self.layout.shapes(self.d, self.s, x, |_| true) else {
            return;
        };
        let mut values = vec![0.0; out.len()];
        let selection = self.layout.find(&shapes, self.s, &mut values);
        let search = Search::new(self.layout, &shapes, self.s);
        let first = self.layout.first.min(out.len());
        for (o, n) in out[first..].iter_mut().zip(&selection.nearest) {
            *o = n.map(|n| Witness {
                points: n.feature.witness(search.corners(n.a), search.corners(n.b)),
                limit: n.need,
            });
        }
    }
}
