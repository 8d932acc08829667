//! The bridge part's clearance rules ([`crate::model::part_rules`]): the checks a part's
//! solids get once placed ([`crate::part::checks`]: keep-out bands beside the hinges,
//! slots between solids not joined, the actuator's room) and the middle link's width
//! ([`crate::part::widths`]), each the least of [`crate::model::clearance`]'s clearances
//! over the pairs of solids it concerns, as functions of the design.
//!
//! The solids are placed as [`super::spec`] places them, over [`Scalar`]: the blocks, and
//! each quarter's hinges b and d and middle link c, mirrored into the four quarters. Every
//! one is convex but the input blocks, each cut into three convex pieces at the heights of
//! the pushed face's ends (above it, beside it, below it). The part is symmetric about both
//! axes, so each rule looks at one pair of every set of mirror images.
//!
//! - `clear/A/B`, two solids not joined: the least of their distance less `part.min_slot`
//!   and of each one's clearance from the other's keep-out band, where the other is a hinge
//!   (its root half thickness plus the narrowest slot or the fillet, whichever is wider, to
//!   each side).
//! - `behind_face/A/B`, a hinge and a body it joins: the body meets the band at one end,
//!   through its face; against it the band is shortened by its half width at that end, so
//!   that a body may fold back only as far as its own corner beside its face.
//! - `actuator/A`: the actuator's body, where its length and height are given, clear of a
//!   solid but the faces it pushes (whose room is the pocket's rule).
//! - `link_width`: the middle link's width, a disc as wide as the thickest hinge it carries
//!   travelling inside it from hinge to hinge (the disc the width check rolls through every
//!   body).
//!
//! A clearance more than [`CAP`] beyond its rule is not worked out: the rule reads
//! [`CAP`] there, continuously, as no pair is nearer than that, and the study's search
//! looks only at the pieces whose bounding circles and boxes come within it.

use std::cell::RefCell;
use std::sync::OnceLock;

use super::pieces::*;
use super::{rules::fillet, PartSettings, P};
use crate::model::bridge::{Geometry, Layout};
use crate::model::clearance::{clearance_below, reach, Feature, Reach, Solid, ANY_ORDER, IN_ORDER};
use crate::model::hinge::{HingeKind, MAX_HINGE_DIMENSIONS};
use crate::model::part_rules::{PartRule, Witness};
use crate::model::scalar::{max, min, Scalar};

/// The margin (m) a clearance rule reads when every pair is farther than this beyond it.
pub use crate::model::part_rules::CAP;

pub use super::pieces::FACE_INSET;

/// A pair of shapes a rule keeps apart, and by how much: the narrowest slot, or only not
/// to overlap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Term {
    a: usize,
    b: usize,
    slot: bool,
}

/// One rule: the solids it concerns (`a` the actuator for its rules) and its terms, the
/// least of whose margins it reads. Two solids not joined are kept a slot apart and out of
/// each other's keep-out bands by one rule, not three: where they face each other along a
/// hinge, the band's margin and the slot's are the same number, and two rules with the same
/// value and gradient would leave the study's subproblems degenerate.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    a: usize,
    b: usize,
    terms: Vec<Term>,
}

/// The solids' names in rules: short, and as the part's messages call them.
const SHORT: [&str; SOLIDS] = [
    "input_left",
    "input_right",
    "output_upper",
    "output_lower",
    "b_ul",
    "c_ul",
    "d_ul",
    "b_ur",
    "c_ur",
    "d_ur",
    "b_ll",
    "c_ll",
    "d_ll",
    "b_lr",
    "c_lr",
    "d_lr",
];

fn long(k: usize) -> String {
    const BLOCKS: [&str; 4] = [
        "the left input block",
        "the right input block",
        "the upper output block",
        "the lower output block",
    ];
    const QUARTERS: [&str; 4] = ["upper left", "upper right", "lower left", "lower right"];
    const PARTS: [&str; 3] = ["hinge b", "the middle link c", "hinge d"];
    if k == INPUT_UPPER {
        BLOCKS[0].to_string()
    } else if k < 4 {
        BLOCKS[k].to_string()
    } else {
        format!("{} ({})", PARTS[(k - 4) % 3], QUARTERS[(k - 4) / 3])
    }
}

/// The mirror image that takes the quarter of solid `h` (a hinge or link) to the upper
/// left one, applied to solid `k`.
fn from_quarter_of(h: usize, k: usize) -> usize {
    match (h - 4) / 3 {
        0 => k,
        1 => mirrored(k, true),
        2 => mirrored(k, false),
        _ => mirrored(mirrored(k, true), false),
    }
}

/// The rules in their order: one for each set of mirror images of pairs of solids that
/// are joined or that come near, then the actuator's where it has a body
/// (`with_actuator`).
fn rows(with_actuator: bool) -> &'static [Row] {
    static ALL: OnceLock<Vec<Row>> = OnceLock::new();
    let all = ALL.get_or_init(|| {
        let mut all = Vec::new();
        for &(i, j) in pair_orbits() {
            let mut terms = Vec::new();
            if !joined(i, j) {
                terms.push(Term {
                    a: i,
                    b: j,
                    slot: true,
                });
            }
            // the keep-out band of each hinge of the pair, seen from the upper left quarter
            for (h, k) in [(i, j), (j, i)] {
                if h < 4 || (h - 4) % 3 == 1 {
                    continue;
                }
                // the bodies joined at a hinge's start (the input block for b, the link for
                // d) and at its end (the link for b, the output block for d)
                let band = match (from_quarter_of(h, h), from_quarter_of(h, k)) {
                    (4, 0) => BAND_B_START,
                    (4, 5) => BAND_B_END,
                    (4, _) => BAND_B,
                    (_, 5) => BAND_D_START,
                    (_, 2) => BAND_D_END,
                    _ => BAND_D,
                };
                terms.push(Term {
                    a: band,
                    b: from_quarter_of(h, k),
                    slot: false,
                });
            }
            if !terms.is_empty() {
                all.push(Row { a: i, b: j, terms });
            }
        }
        all.extend(ACTUATOR_PAIRS.iter().map(|&(a, b)| Row {
            a,
            b,
            terms: vec![Term { a, b, slot: false }],
        }));
        all
    });
    if with_actuator {
        all
    } else {
        &all[..all.len() - ACTUATOR_PAIRS.len()]
    }
}

/// Whether a part with `s` has the actuator's rules: its length and height given.
fn with_actuator(s: &PartSettings) -> bool {
    s.actuator_length.is_some() && s.actuator_height.is_some()
}

/// The clearance rules of a part with `s`, in the order of [`margins`]: a rule for each
/// of [`rows`], then the link's width.
pub fn rules(s: &PartSettings) -> Vec<PartRule> {
    let mut out: Vec<PartRule> = rows(with_actuator(s))
        .iter()
        .map(|r| {
            let (name, description) = if r.a == ACTUATOR {
                (
                    format!("actuator/{}", short(r.b)),
                    format!("the actuator clear of {}", long(r.b)),
                )
            } else if joined(r.a, r.b) {
                (
                    format!("behind_face/{}/{}", SHORT[r.a], SHORT[r.b]),
                    format!(
                        "{} and {} kept to their sides of the face that joins them",
                        long(r.a),
                        long(r.b)
                    ),
                )
            } else {
                (
                    format!("clear/{}/{}", SHORT[r.a], SHORT[r.b]),
                    format!(
                        "{} and {} at least part.min_slot apart, and clear of each other's \
                         hinges by part.min_slot or the fillet",
                        long(r.a),
                        long(r.b)
                    ),
                )
            };
            PartRule {
                name: name.into(),
                description: description.into(),
            }
        })
        .collect();
    out.push(PartRule {
        name: "link_width".into(),
        description: "the middle link as wide as the thickest hinge it carries".into(),
    });
    out
}

fn short(k: usize) -> &'static str {
    if k == INPUT_UPPER {
        "input_left"
    } else {
        SHORT[k]
    }
}

/// The most rules [`rules`] gives: at most 40 sets of mirror images of the 120 pairs of
/// solids, the actuator's 5 and the link's width.
pub const MAX_RULES: usize = 40 + ACTUATOR_PAIRS.len() + 1;

/// How many rules [`rules`] gives.
pub fn count(s: &PartSettings) -> usize {
    rows(with_actuator(s)).len() + 1
}

/// The piece of the middle link of the upper left quarter: its corners, two on each face,
/// are not in order around it where the link folds.
const LINK: usize = 9;

/// What gives a clearance rule's margin at a design: the pieces and the feature of the
/// nearest pair, with the slot it asks; `None` where every pair is farther than [`CAP`]
/// beyond the rule.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Nearest {
    pa: usize,
    pb: usize,
    feature: Feature,
    need: f64,
}

/// What gives each clearance rule's margin at a design, found on the real parts once: the
/// nearest pair of each rule of [`rows`], and the link width's two [`Reach`]es. The margins'
/// values and, over dual numbers, their gradients follow from it ([`Selection::margins`]).
#[derive(Clone, Copy)]
pub struct Selection {
    nearest: [Option<Nearest>; MAX_RULES],
    link: [Reach; 2],
}

/// Everything a search's outcome depends on, to the bit: the part's settings, the hinge
/// kinds, and the design's hinges, lengths and angles.
#[derive(Clone, Copy, PartialEq)]
struct SearchKey {
    kinds: [HingeKind; 4],
    bits: [u64; KEY_BITS],
    actuator: [bool; 2],
    enforce: bool,
}

/// The settings' seven lengths and the actuator's two, each hinge's dimensions, and the
/// link's length and three angles.
const KEY_BITS: usize = 9 + 2 * MAX_HINGE_DIMENSIONS + 4;

impl SearchKey {
    fn new(s: &PartSettings, layout: &Layout, g: &Geometry<f64>) -> Self {
        // every setting named, so that a setting added to the part is added here too
        let PartSettings {
            link_thickness,
            fillet_radius,
            input_block_width,
            input_block_height,
            output_block_width,
            output_block_height,
            min_slot,
            actuator_length,
            actuator_height,
            enforce,
        } = *s;
        let mut bits = [0; KEY_BITS];
        let values = [
            link_thickness,
            fillet_radius,
            input_block_width,
            input_block_height,
            output_block_width,
            output_block_height,
            min_slot,
            actuator_length.unwrap_or(0.0),
            actuator_height.unwrap_or(0.0),
        ]
        .into_iter()
        .chain(g.b.dims)
        .chain(g.d.dims)
        .chain([g.delta2, g.l3, g.delta3, g.delta4]);
        for (b, v) in bits.iter_mut().zip(values) {
            *b = v.to_bits();
        }
        SearchKey {
            kinds: [layout.hinge_b, layout.hinge_d, g.b.kind, g.d.kind],
            bits,
            actuator: [actuator_length.is_some(), actuator_height.is_some()],
            enforce,
        }
    }
}

/// The last search on this thread: its key, its selection and its margins.
type LastSearch = (SearchKey, Selection, [f64; MAX_RULES]);

thread_local! {
    static LAST_SEARCH: RefCell<Option<LastSearch>> = const { RefCell::new(None) };
}

/// A piece's bounding box: its least and largest `x`, then `y`.
type Bounds = [f64; 4];

fn bounds(p: &Piece<f64>) -> Bounds {
    let fold = |k: usize, f: fn(f64, f64) -> f64, from: f64| p.iter().map(|q| q[k]).fold(from, f);
    [
        fold(0, f64::min, f64::INFINITY),
        fold(0, f64::max, f64::NEG_INFINITY),
        fold(1, f64::min, f64::INFINITY),
        fold(1, f64::max, f64::NEG_INFINITY),
    ]
}

/// How far beyond a search's bound a bounding box's gap must be for its pair to be left
/// out (m): far above the rounding of the pieces' millimetres (1e-19 m), so that a pair
/// the boxes leave out is one whose clearance would not have been below the bound either,
/// and the search finds what it found without them, to the bit.
const BOX_MARGIN: f64 = 1e-12;

/// Whether the bounding boxes `a` and `b` show that their pieces' clearance is not below
/// `bound`. The gaps along `x` and `y` are gaps along axes, which the clearance is never
/// below (apart, the distance is at least either; overlapping, the least shift that parts
/// the pieces is along a side's normal and no longer than the shift along any other axis,
/// Ericson, Real-Time Collision Detection, 2005, Sec. 4.2 and 5.2.1), and where the boxes
/// are apart along both, so is the distance their hypotenuse. The blocks' pieces and the
/// actuator are rectangles along the axes, whose bounding circles are far looser: measured
/// on the studies of wei2017 and wei2017_min_stress, the circles leave out 88 and 86 % of
/// the pairs, the boxes 5.5 and 4.4 % more: 46 and 32 % of the pairs that went on to the
/// separating axes before.
fn boxes_apart(a: &Bounds, b: &Bounds, bound: f64) -> bool {
    let gx = (b[0] - a[1]).max(a[0] - b[1]);
    let gy = (b[2] - a[3]).max(a[2] - b[3]);
    let bound = bound + BOX_MARGIN;
    gx >= bound
        || gy >= bound
        || (bound > 0.0 && gx > 0.0 && gy > 0.0 && gx * gx + gy * gy >= bound * bound)
}

/// The least over `term`'s pairs of pieces of their clearance less the slot it asks, where
/// that is below `least` (the rule's least margin so far, or [`CAP`]): the pair and its
/// feature, or `None`. Pairs are taken in their order and a later one only where strictly
/// nearer, so that a rule's nearest pair does not depend on the bound it was searched under.
fn nearest(
    real: &[Piece<f64>; PIECES],
    circles: &[(P, f64); PIECES],
    boxes: &[Bounds; PIECES],
    term: Term,
    slot: f64,
    mut least: f64,
) -> Option<(f64, Nearest)> {
    let need = if term.slot { slot } else { 0.0 };
    let solid = |k: usize| Solid {
        corners: &real[k],
        sides: if k == LINK { &ANY_ORDER } else { &IN_ORDER },
    };
    let mut best = None;
    let (ra, rb) = (RANGES[term.a], RANGES[term.b]);
    for pa in ra.0..ra.0 + ra.1 {
        for pb in rb.0..rb.0 + rb.1 {
            // the bounding circles' gap, a lower bound of the clearance
            let ((ca, sa), (cb, sb)) = (circles[pa], circles[pb]);
            let reach = least + need + sa + sb;
            if (ca[0] - cb[0]).powi(2) + (ca[1] - cb[1]).powi(2) >= reach * reach
                || boxes_apart(&boxes[pa], &boxes[pb], least + need)
            {
                continue;
            }
            if let Some((c, feature)) = clearance_below(solid(pa), solid(pb), least + need) {
                if c - need < least {
                    least = c - need;
                    best = Some(Nearest {
                        pa,
                        pb,
                        feature,
                        need,
                    });
                }
            }
        }
    }
    best.map(|b| (least, b))
}

/// The link width's inputs at a design: the radius of the disc, and at each of the link's
/// ends the face's centre it must reach within the allowance.
fn link_ends<D: Scalar>(
    s: &PartSettings,
    layout: &Layout,
    g: &Geometry<D>,
    link: &Piece<D>,
) -> (D, [(P<D>, D); 2]) {
    let thickest = max(
        layout.hinge_b.least_thickness(g.b.dims()),
        layout.hinge_d.least_thickness(g.d.dims()),
    );
    let radius = thickest * 0.5;
    // the faces' centres: the middles of the link's two ends
    let centre = |a: P<D>, b: P<D>| [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    let end = |target: P<D>, root: D, r: f64| (target, radius + root * 0.5 + r);
    (
        radius,
        [
            end(
                centre(link[0], link[1]),
                layout.hinge_b.root_thickness(g.b.dims()),
                fillet(s, layout.hinge_b),
            ),
            end(
                centre(link[2], link[3]),
                layout.hinge_d.root_thickness(g.d.dims()),
                fillet(s, layout.hinge_d),
            ),
        ],
    )
}

impl Selection {
    /// Each clearance rule's margin (m) at the design `g` into `out` ([`count`] of them), in
    /// the order of [`rules`], with what gives each. A rule's terms share the search's
    /// bound: a term's pairs are looked at only below the least margin of the terms before
    /// it, which leaves the least, and the first term that has it, as they were.
    ///
    /// The last search on the thread is kept with what it was found from, and a search at
    /// the same design with the same settings, to the bit, is answered by it: a search is
    /// a function of those alone. An SQP's line search evaluates the values at the point it
    /// accepts, and the solver then the values and gradients at the same point: in the
    /// second stages, every accepted step searched twice.
    pub fn find(s: &PartSettings, layout: &Layout, g: &Geometry<f64>, out: &mut [f64]) -> Self {
        Self::find_with(s, layout, g, out, |selection| *selection)
    }

    /// [`Selection::find`], the selection lent to `keep` (a selection is some kilobytes,
    /// and the values alone need none of it); `keep` must not search again.
    pub(super) fn find_with<R>(
        s: &PartSettings,
        layout: &Layout,
        g: &Geometry<f64>,
        out: &mut [f64],
        keep: impl FnOnce(&Selection) -> R,
    ) -> R {
        let key = SearchKey::new(s, layout, g);
        let n = count(s);
        LAST_SEARCH.with_borrow_mut(|last| match last {
            Some((k, selection, margins)) if *k == key => {
                out[..n].copy_from_slice(&margins[..n]);
                keep(selection)
            }
            _ => {
                let (_, selection, margins) =
                    last.insert((key, Self::search(s, layout, g, out), [0.0; MAX_RULES]));
                margins[..n].copy_from_slice(&out[..n]);
                keep(selection)
            }
        })
    }

    /// [`Selection::find`] without the last search.
    fn search(s: &PartSettings, layout: &Layout, g: &Geometry<f64>, out: &mut [f64]) -> Self {
        let real = pieces(s, layout, g);
        let circles = real.each_ref().map(circle);
        let boxes = real.each_ref().map(bounds);
        let rows = rows(with_actuator(s));
        let mut nearest = [None; MAX_RULES];
        for ((o, row), chosen) in out.iter_mut().zip(rows).zip(&mut nearest) {
            let mut least = CAP;
            for &t in &row.terms {
                if let Some((m, n)) = self::nearest(&real, &circles, &boxes, t, s.min_slot, least) {
                    least = m;
                    *chosen = Some(n);
                }
            }
            // the value as the feature gives it, the same arithmetic the gradient's
            *o = chosen.map_or(CAP, |n| n.feature.value(&real[n.pa], &real[n.pb]) - n.need);
        }
        let (radius, ends) = link_ends(s, layout, g, &real[LINK]);
        let link = ends.map(|(target, allowance)| reach(&real[LINK], radius, target, allowance).1);
        let selection = Selection { nearest, link };
        out[rows.len()] = selection.link_width(radius, ends, &real[LINK]);
        selection
    }

    /// The margins at the design `g` over `D` (dual numbers whose real parts are the design
    /// the selection was found at), each by what gives it there: [`CAP`] where no pair is
    /// near.
    pub fn margins<D: Scalar>(
        &self,
        s: &PartSettings,
        layout: &Layout,
        g: &Geometry<D>,
        out: &mut [D],
    ) {
        let exact = pieces(s, layout, g);
        let rules = rows(with_actuator(s)).len();
        for (o, n) in out[..rules].iter_mut().zip(&self.nearest) {
            *o = n.map_or(D::from(CAP), |n| {
                n.feature.value(&exact[n.pa], &exact[n.pb]) - n.need
            });
        }
        let (radius, ends) = link_ends(s, layout, g, &exact[LINK]);
        out[rules] = self.link_width(radius, ends, &exact[LINK]);
    }

    /// Where each rule's margin is measured at the design `g` (the real one the selection
    /// was found at), into `out` ([`count`] of them): the nearest pair's witness points,
    /// the slot asked the limit; none where no pair is near ([`CAP`]). The link's width
    /// at the end whose margin is the lesser: the disc's centre and the side it touches,
    /// the disc's radius the limit.
    pub fn witnesses(
        &self,
        s: &PartSettings,
        layout: &Layout,
        g: &Geometry<f64>,
        out: &mut [Option<Witness>],
    ) {
        let real = pieces(s, layout, g);
        let rules = rows(with_actuator(s)).len();
        for (o, n) in out[..rules].iter_mut().zip(&self.nearest) {
            *o = n.map(|n| Witness {
                points: n.feature.witness(&real[n.pa], &real[n.pb]),
                limit: n.need,
            });
        }
        let (radius, ends) = link_ends(s, layout, g, &real[LINK]);
        let link = &real[LINK];
        let value = |k: usize| self.link[k].value(link, radius, ends[k].0, ends[k].1);
        // the end link_width's value comes from: the first where the two tie, as `min`
        let k = if value(1) < value(0) { 1 } else { 0 };
        out[rules] = self.link[k]
            .witness(link, radius, ends[k].0, ends[k].1)
            .map(|points| Witness {
                points,
                limit: radius,
            });
    }

    /// The middle link's width rule: a disc as wide as the thickest hinge the link carries
    /// travels inside it from hinge to hinge, meeting, at each, the round of the hinge's
    /// root width and fillets about the middle of its end (the face's centre), as the width
    /// check has it; the lesser of the two ends' [`reach`] margins.
    fn link_width<D: Scalar>(&self, radius: D, ends: [(P<D>, D); 2], link: &Piece<D>) -> D {
        let [a, b] = [0, 1].map(|k| self.link[k].value(link, radius, ends[k].0, ends[k].1));
        min(a, b)
    }
}

/// Each clearance rule's margin (m) at the design `g`, in the order of [`rules`], into
/// `out` ([`count`] of them).
pub fn margins(s: &PartSettings, layout: &Layout, g: &Geometry<f64>, out: &mut [f64]) {
    Selection::find_with(s, layout, g, out, |_| ());
}

#[cfg(test)]
mod tests;
