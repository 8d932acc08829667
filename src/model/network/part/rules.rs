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

use super::super::file::{Axis, Description};
use super::images::Image;
use super::plane::{add, convex_piece_indices, scale};
use super::{PartSettings, Values};
use crate::model::clearance::{clearance, clearance_below, Feature, Pt, Solid};
use crate::model::hinge::HingeKind;
use crate::model::part_rules::{PartRule, Witness};
use crate::model::scalar::{max, min, Jet, Scalar};
use crate::model::{Dimension, MAX_PARAMETERS};

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

impl Layout {
    pub fn new(d: &Description) -> Layout {
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
        let mut layout = Layout {
            groups,
            rows,
            rules: Vec::new(),
            first: 2 * d.beams.len(),
            own,
            ends,
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

/// One solid of the part over `D`: its corners, whether they go around it in order (else
/// only their hull counts), and its group.
struct Piece<D> {
    corners: Vec<Pt<D>>,
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

/// The part's solids at a design over `D`, with the flexures' sites (by flexure group) and
/// the size rules' margins.
struct Shapes<D> {
    pieces: Vec<Piece<D>>,
    sites: Vec<Option<Site<D>>>,
    sizes: Vec<D>,
}

/// The band of half width `half` around the segment `a`-`b`, counterclockwise.
fn band<D: Scalar>(a: Pt<D>, b: Pt<D>, half: D) -> Vec<Pt<D>> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let n = [-d[1] / len * half, d[0] / len * half];
    vec![
        [a[0] - n[0], a[1] - n[1]],
        [b[0] - n[0], b[1] - n[1]],
        [b[0] + n[0], b[1] + n[1]],
        [a[0] + n[0], a[1] + n[1]],
    ]
}

/// A flexure as [`super::flexures::cut`] cuts it: its solid, its pads, its site.
struct Cut<D> {
    solid: Vec<Pt<D>>,
    pads: [Vec<Pt<D>>; 2],
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
    let solid = vec![
        at(f0, 0.0, -r),
        at(f1, 0.0, -r),
        at(f1, 0.0, r),
        at(f0, 0.0, r),
    ];
    let pads = [
        vec![
            at(f0, -s.pad, -half),
            at(f0, 0.0, -half),
            solid[0],
            solid[3],
            at(f0, 0.0, half),
            at(f0, -s.pad, half),
        ],
        vec![
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
    /// where an expression has no value there (the model refuses such a design too).
    fn shapes<D: Scalar>(&self, d: &Description, s: &PartSettings, x: &[D]) -> Option<Shapes<D>> {
        let v = Values::new(d, x);
        let mut cuts = Vec::new();
        let mut sizes = Vec::new();
        for h in &d.hinges {
            let mut dims = Vec::with_capacity(h.dimensions.len());
            for (e, info) in h.dimensions.iter().zip(h.kind.dimensions()) {
                dims.push(if info.dimension == Dimension::Length {
                    v.length(e).ok()?
                } else {
                    v.eval(e).ok()?
                });
            }
            let (sin, cos) = v.eval(&h.angle).ok()?.sin_cos();
            cuts.push(cut(h.kind, &dims, v.point(&h.start).ok()?, [cos, sin], s));
        }
        for b in &d.beams {
            let (start, end) = (v.point(&b.start).ok()?, v.point(&b.end).ok()?);
            let thickness = v.length(&b.thickness).ok()?;
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
        // the bodies as drawn: each piece, and whether its corners go around it
        let mut drawn: Vec<(usize, Vec<Pt<D>>, bool)> = Vec::new();
        let outline = |b: usize, points: Vec<Pt<D>>, drawn: &mut Vec<(usize, Vec<Pt<D>>, bool)>| {
            let real: Vec<[f64; 2]> = points.iter().map(|p| [p[0].re(), p[1].re()]).collect();
            for piece in convex_piece_indices(&real) {
                drawn.push((b, piece.iter().map(|&k| points[k]).collect(), true));
            }
        };
        if d.ground.len() >= 3 {
            let points = v.points(&d.ground).ok()?;
            outline(0, points, &mut drawn);
        }
        for (b, body) in d.bodies.iter().enumerate() {
            let points = v.points(&body.points).ok()?;
            let first = drawn.len();
            match (&body.link_width, points.len()) {
                (Some(w), 2) => drawn.push((
                    b + 1,
                    band(points[0], points[1], v.length(w).ok()? * 0.5),
                    true,
                )),
                (_, 0) => {
                    let all: Vec<Pt<D>> = cuts
                        .iter()
                        .zip(&self.ends)
                        .flat_map(|(c, &(from, to))| {
                            [(from, &c.pads[0]), (to, &c.pads[1])]
                                .into_iter()
                                .filter(|(o, _)| *o == b + 1)
                                .flat_map(|(_, p)| p.iter().copied())
                        })
                        .collect();
                    drawn.push((b + 1, all, false));
                }
                _ => outline(b + 1, points, &mut drawn),
            }
            if !body.on_axis.is_empty() {
                let selves = Image::all(&body.on_axis);
                for piece in &mut drawn[first..] {
                    piece.1 = selves
                        .iter()
                        .flat_map(|&t| piece.1.iter().map(move |&p| t.point(p)))
                        .collect();
                    piece.2 = false;
                }
            }
        }
        let group = |g: Group| {
            self.groups
                .iter()
                .position(|&h| h == g)
                .expect("every solid's group is among the layout's")
        };
        let mut pieces = Vec::new();
        let mut sites = vec![None; self.groups.len()];
        for t in Image::all(&d.mirror) {
            for (c, cut) in cuts.iter().enumerate() {
                let f = group(Group::Flexure(c, t));
                let image = |points: &[Pt<D>]| points.iter().map(|&p| t.point(p)).collect();
                pieces.push(Piece {
                    corners: image(&cut.solid),
                    ordered: true,
                    group: f,
                });
                sites[f] = Some(Site {
                    start: t.point(cut.site.start),
                    end: t.point(cut.site.end),
                    ..cut.site
                });
                let (from, to) = self.ends[c];
                for (pad, body) in cut.pads.iter().zip([from, to]) {
                    pieces.push(Piece {
                        corners: image(pad),
                        ordered: true,
                        group: group(key(&self.own, body, t)),
                    });
                }
            }
            for (b, points, ordered) in &drawn {
                if t.of_body(&self.own[*b]) != t {
                    continue;
                }
                pieces.push(Piece {
                    corners: points.iter().map(|&p| t.point(p)).collect(),
                    ordered: *ordered,
                    group: group(key(&self.own, *b, t)),
                });
            }
        }
        Some(Shapes {
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
fn keep_out<D: Scalar>(site: &Site<D>, slot: f64, which: Band) -> Vec<Pt<D>> {
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
    vec![at(a, -w), at(b, -w), at(b, w), at(a, w)]
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

/// A piece's bounding box: least and largest `x`, then `y`.
fn bounds(corners: &[Pt<f64>]) -> [f64; 4] {
    corners.iter().fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].max(p[0]),
                b[2].min(p[1]),
                b[3].max(p[1]),
            ]
        },
    )
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

/// The f64 geometry of a design and the sides of each shape, for the search.
struct Search<'a> {
    shapes: &'a Shapes<f64>,
    slot: f64,
    sides: Vec<Vec<(usize, usize)>>,
    boxes: Vec<[f64; 4]>,
    /// Each flexure's three bands, by flexure group.
    bands: Vec<Option<[Vec<Pt<f64>>; 3]>>,
}

const BANDS: [Band; 3] = [Band::Whole, Band::Start, Band::End];

impl<'a> Search<'a> {
    fn new(shapes: &'a Shapes<f64>, s: &PartSettings) -> Self {
        let slot_of = |site: &Site<f64>| site.fillet.max(s.min_slot);
        Search {
            shapes,
            slot: s.min_slot,
            sides: shapes
                .pieces
                .iter()
                .map(|p| {
                    if p.ordered {
                        around(p.corners.len())
                    } else {
                        all_pairs(p.corners.len())
                    }
                })
                .collect(),
            boxes: shapes.pieces.iter().map(|p| bounds(&p.corners)).collect(),
            bands: shapes
                .sites
                .iter()
                .map(|site| site.map(|site| BANDS.map(|b| keep_out(&site, slot_of(&site), b))))
                .collect(),
        }
    }

    fn corners(&self, shape: Shape) -> &[Pt<f64>] {
        match shape {
            Shape::Solid(k) => &self.shapes.pieces[k].corners,
            Shape::Band(f, b) => &self.bands[f].as_ref().expect("a flexure's band")[b as usize],
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
        let piece = Solid {
            corners: &self.shapes.pieces[k].corners,
            sides: &self.sides[k],
        };
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

    /// The least margin below `least` of the pairs of `a` and `b`, each with the slot it
    /// asks, and what gives it.
    fn nearest(&self, pairs: &[(Shape, Shape, f64)], mut least: f64) -> Option<(f64, Nearest)> {
        let mut best = None;
        for &(a, b, need) in pairs {
            let solid = |shape: Shape| -> (Solid<'_>, [f64; 4]) {
                match shape {
                    Shape::Solid(k) => (
                        Solid {
                            corners: &self.shapes.pieces[k].corners,
                            sides: &self.sides[k],
                        },
                        self.boxes[k],
                    ),
                    Shape::Band(..) => {
                        const IN_ORDER: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (3, 0)];
                        let corners = self.corners(shape);
                        (
                            Solid {
                                corners,
                                sides: &IN_ORDER,
                            },
                            bounds(corners),
                        )
                    }
                }
            };
            let ((sa, ba), (sb, bb)) = (solid(a), solid(b));
            // the boxes' gap along an axis is a lower bound of the clearance
            let gap = (bb[0] - ba[1])
                .max(ba[0] - bb[1])
                .max((bb[2] - ba[3]).max(ba[2] - bb[3]));
            if gap >= least + need + 1e-12 {
                continue;
            }
            if let Some((c, feature)) = clearance_below(sa, sb, least + need) {
                if c - need < least {
                    least = c - need;
                    best = Some(Nearest {
                        a,
                        b,
                        feature,
                        need,
                    });
                }
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
    /// The terms of the rule `row`: each pair of shapes it compares, with the slot asked.
    fn terms(&self, search: &Search<'_>, (i, j): (usize, usize)) -> Vec<(Shape, Shape, f64)> {
        let pieces = &search.shapes.pieces;
        let of = |g: usize| {
            pieces
                .iter()
                .enumerate()
                .filter(move |(_, p)| p.group == g)
                .map(|(k, _)| k)
        };
        let (gi, gj) = (self.groups[i], self.groups[j]);
        let joined = self.joins(gi, gj) || self.joins(gj, gi);
        let mut terms = Vec::new();
        if !joined {
            for a in of(i) {
                for b in of(j) {
                    terms.push((Shape::Solid(a), Shape::Solid(b), search.slot));
                }
            }
        }
        for (f, other) in [(i, j), (j, i)] {
            if !matches!(self.groups[f], Group::Flexure(..)) {
                continue;
            }
            for k in of(other) {
                let band = if joined {
                    search.joint(f, k)
                } else {
                    Band::Whole
                };
                terms.push((Shape::Band(f, band), Shape::Solid(k), 0.0));
            }
        }
        terms
    }

    /// Each rule's margin (m) at the design whose real geometry is `shapes`, into `out`
    /// (the first `out.len()` rules), with what gives each clearance.
    fn find(&self, shapes: &Shapes<f64>, s: &PartSettings, out: &mut [f64]) -> Selection {
        let first = self.first.min(out.len());
        out[..first].copy_from_slice(&shapes.sizes[..first]);
        let search = Search::new(shapes, s);
        let mut nearest = Vec::new();
        for (o, &row) in out[first..].iter_mut().zip(&self.rows) {
            let chosen = search
                .nearest(&self.terms(&search, row), CAP)
                .map(|(_, n)| n);
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
        let corners = |shape: Shape| match shape {
            Shape::Solid(k) => shapes.pieces[k].corners.clone(),
            Shape::Band(f, b) => {
                let site = shapes.sites[f].expect("a flexure's site");
                keep_out(&site, site.fillet.max(s.min_slot), b)
            }
        };
        for (o, n) in out[first..].iter_mut().zip(&self.nearest) {
            *o = n.map_or(D::from(CAP), |n| {
                n.feature.value(&corners(n.a), &corners(n.b)) - n.need
            });
        }
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
        match self.layout.shapes(self.d, self.s, x) {
            Some(shapes) => {
                self.layout.find(&shapes, self.s, out);
            }
            None => out.fill(f64::NAN),
        }
    }

    /// As [`Rules::margins`], with their gradients over every parameter, row-major.
    pub fn margins_with_gradient(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        let n = x.len();
        assert!(
            n <= MAX_PARAMETERS,
            "a network has at most {MAX_PARAMETERS} parameters"
        );
        let Some(real) = self.layout.shapes(self.d, self.s, x) else {
            out.fill(f64::NAN);
            jacobian.fill(f64::NAN);
            return;
        };
        // the values as `margins` computes them, and the nearest pairs found once, on them
        let selection = self.layout.find(&real, self.s, out);
        let seeded: Vec<Jet<MAX_PARAMETERS>> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Jet::variable(v, i))
            .collect();
        let dual = self
            .layout
            .shapes(self.d, self.s, &seeded)
            .expect("the expressions have values where their real parts do");
        let mut y = vec![Jet::<MAX_PARAMETERS>::from(0.0); out.len()];
        selection.margins(self.layout, &dual, self.s, &mut y);
        for (i, yi) in y.iter().enumerate() {
            jacobian[i * n..(i + 1) * n].copy_from_slice(&yi.grad[..n]);
        }
    }

    /// Where each rule is measured at `x` (SI): the nearest pair's witness points, the slot
    /// asked the limit; none for the size rules and where no pair is near.
    pub fn witnesses(&self, x: &[f64], out: &mut [Option<Witness>]) {
        out.fill(None);
        let Some(shapes) = self.layout.shapes(self.d, self.s, x) else {
            return;
        };
        let mut values = vec![0.0; out.len()];
        let selection = self.layout.find(&shapes, self.s, &mut values);
        let search = Search::new(&shapes, self.s);
        let first = self.layout.first.min(out.len());
        for (o, n) in out[first..].iter_mut().zip(&selection.nearest) {
            *o = n.map(|n| Witness {
                points: n.feature.witness(search.corners(n.a), search.corners(n.b)),
                limit: n.need,
            });
        }
    }
}
