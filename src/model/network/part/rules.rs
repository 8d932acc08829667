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

mod build;
mod search;
pub use search::Rules;

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

/// A body's piece as drawn: the body (by slot), its corners' range among the drawn
/// corners, and whether they go around it.
type DrawnPiece = (usize, usize, usize, bool);

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

    /// The bounding box of the part's solids at the design `x` over `D` (m): the least x
    /// and y of a corner, then the largest; `None` where an expression has no value there.
    /// The outline is the union of the solids, whose fillets at the flexures' roots are
    /// concave and lie inside the pieces' hull: its box is the corners' box. Each side is a
    /// maximum over corners, continuous, with the gradient of the corner that attains it.
    pub fn extent<D: Scalar>(&self, d: &Description, s: &PartSettings, x: &[D]) -> Option<[D; 4]> {
        let shapes = self.shapes(d, s, x, |_| true)?;
        let first = *shapes.corners.first()?;
        let mut bb = [first[0], first[1], first[0], first[1]];
        for p in &shapes.corners[1..] {
            bb = [
                min(bb[0], p[0]),
                min(bb[1], p[1]),
                max(bb[2], p[0]),
                max(bb[3], p[1]),
            ];
        }
        Some(bb)
    }

    /// The bodies as drawn at a design, each body's points from `point` and its link's width
    /// from `length`, a body of pads from the flexures' `cuts`: the corners of every piece in
    /// one vector, and each piece's body (by slot), its corners' range among them, and
    /// whether they go around it (else only their hull counts: a body of pads, a body drawn
    /// with its images across an axis).
    fn drawn_bodies<D: Scalar>(
        &self,
        d: &Description,
        point: &impl Fn(&[Keyed; 2]) -> Option<Pt<D>>,
        length: &impl Fn(&Keyed) -> Option<D>,
        cuts: &[Cut<D>],
    ) -> Option<(Vec<Pt<D>>, Vec<DrawnPiece>)> {
        let mut at: Vec<Pt<D>> = Vec::with_capacity(self.drawn_corners);
        let mut drawn: Vec<DrawnPiece> = Vec::with_capacity(self.drawn_corners);
        let mut points: Vec<Pt<D>> = Vec::with_capacity(self.drawn_corners);
        let outline =
            |b: usize, points: &[Pt<D>], at: &mut Vec<Pt<D>>, drawn: &mut Vec<DrawnPiece>| {
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
        Some((at, drawn))
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
        let (at, drawn) = self.drawn_bodies(d, &point, &length, &cuts)?;
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
