//! The bridge part's size rules as functions of the design ([`crate::model::part_rules`]):
//! the checks [`super::spec`] makes before any solid is built (`size_problems` and the
//! actuator's pocket), each a margin in metres, `>= 0` where the part meets it.
//!
//! In the part's frame (`super`'s module comment), with `h_b = max(link_thickness / 2,
//! t_b / 2 + r_b)` the half width of hinge b's faces (`t_b` its root thickness, `r_b` its
//! fillet) and `h_d` likewise:
//!
//! - each wall (`link_thickness`, `input_block_width`, `output_block_height`) at least as
//!   thick as each hinge's least thickness: one rule per wall and hinge, so that no rule
//!   holds a maximum;
//! - the input block holds the faces of its upper and lower hinges b: its half height less
//!   `h_b (1 + cos delta2)` (the lower end of the upper face above the actuator's axis);
//! - the output block holds the faces of hinges d: `output_block_height - 2 h_d cos delta4`;
//! - the slot between the output block's sides, which continue the faces of the left and
//!   right hinges d, at least `min_slot` at the block's bottom, `output_block_width - 2 h_d
//!   sin delta4`, and at its top, that plus `2 output_block_height tan delta4`;
//! - the actuator's pocket between the input blocks at least `[actuator] length` long:
//!   `output_block_width + 2 span_x + 2 r_d cos delta4 + 2 r_b cos delta2 - 2 h_b sin
//!   delta2`, where a length is given.
//!
//! `h_b` and `h_d` are the rules' only kinks: where a hinge with its fillets grows as wide
//! as the link, its faces stop following the link and follow the hinge.

use super::{clearances, PartSettings};
use crate::model::bridge::{Geometry, Layout};
use crate::model::hinge::HingeKind;
use crate::model::part_rules::{PartRule, Witness};
use crate::model::scalar::{max, Scalar};

/// The most rules a bridge part has.
pub const MAX_RULES: usize = SIZES + 1 + clearances::MAX_RULES;

/// How many size rules there are.
const SIZES: usize = 10;

/// Every rule but the pocket's, in the order of [`margins`].
const SIZE_RULES: [PartRule; SIZES] = [
    rule(
        "link_thickness_b",
        "part.link_thickness at least hinge b's least thickness",
    ),
    rule(
        "link_thickness_d",
        "part.link_thickness at least hinge d's least thickness",
    ),
    rule(
        "input_block_width_b",
        "part.input_block_width at least hinge b's least thickness",
    ),
    rule(
        "input_block_width_d",
        "part.input_block_width at least hinge d's least thickness",
    ),
    rule(
        "output_block_height_b",
        "part.output_block_height at least hinge b's least thickness",
    ),
    rule(
        "output_block_height_d",
        "part.output_block_height at least hinge d's least thickness",
    ),
    rule(
        "input_block_faces",
        "the input block holds the faces of its upper and lower hinges b",
    ),
    rule(
        "output_block_faces",
        "the output block holds the faces of hinges d",
    ),
    rule(
        "output_slot_bottom",
        "the slot between the output block's sides at least part.min_slot, at the block's bottom",
    ),
    rule(
        "output_slot_top",
        "the slot between the output block's sides at least part.min_slot, at the block's top",
    ),
];

const POCKET: PartRule = rule(
    "actuator_pocket",
    "the pocket between the input blocks at least [actuator] length long",
);

const fn rule(name: &'static str, description: &'static str) -> PartRule {
    PartRule {
        name: std::borrow::Cow::Borrowed(name),
        description: std::borrow::Cow::Borrowed(description),
    }
}

/// The rules of a bridge part with `settings`: the size rules, the pocket's where the
/// actuator's length is given, then the clearances ([`clearances`]).
pub fn rules(settings: &PartSettings) -> Vec<PartRule> {
    let mut rules = SIZE_RULES.to_vec();
    if settings.actuator_length.is_some() {
        rules.push(POCKET);
    }
    rules.extend(clearances::rules(settings));
    rules
}

/// The fillet at a hinge's roots: a strip's; a notch meets its bodies smoothly.
pub fn fillet(s: &PartSettings, kind: HingeKind) -> f64 {
    if kind.has_sharp_roots() {
        s.fillet_radius
    } else {
        0.0
    }
}

/// Each rule's margin (m) at the design `g`, in the order of [`rules`]: the first
/// `out.len()` of them (all, or the [`first_rules`]).
pub fn margins(s: &PartSettings, layout: &Layout, g: &Geometry<f64>, out: &mut [f64]) {
    size_margins(s, layout, g, out);
    let first = first_rules(s);
    if out.len() > first {
        clearances::margins(s, layout, g, &mut out[first..]);
    }
}

/// [`margins`] at the design `real` into `values`, and over `D` at `g`, the same design
/// over dual numbers, into `out`: the clearances' nearest pairs are searched for once, on
/// the real design, and only their features evaluated over `D`.
pub fn margins_seeded<D: Scalar>(
    s: &PartSettings,
    layout: &Layout,
    real: &Geometry<f64>,
    g: &Geometry<D>,
    values: &mut [f64],
    out: &mut [D],
) {
    size_margins(s, layout, real, values);
    size_margins(s, layout, g, out);
    let first = first_rules(s);
    if out.len() > first {
        let selection = clearances::Selection::find(s, layout, real, &mut values[first..]);
        selection.margins(s, layout, g, &mut out[first..]);
    }
}

/// Where each rule is measured at the design `g`, in the order of [`rules`] (`out` one per
/// rule): the clearances' ([`clearances::Selection::witnesses`]); none for the size rules
/// and the pocket's, which are sums of the settings and the hinges' sizes, measured
/// nowhere on the drawing as one length.
pub fn witnesses(
    s: &PartSettings,
    layout: &Layout,
    g: &Geometry<f64>,
    out: &mut [Option<Witness>],
) {
    out.fill(None);
    let first = first_rules(s);
    if out.len() > first {
        let mut values = vec![0.0; out.len() - first];
        let selection = clearances::Selection::find(s, layout, g, &mut values);
        selection.witnesses(s, layout, g, &mut out[first..]);
    }
}

/// The size rules' margins and the pocket's, the first `out.len()` of them (at most
/// [`first_rules`]).
fn size_margins<D: Scalar>(s: &PartSettings, layout: &Layout, g: &Geometry<D>, out: &mut [D]) {
    let t = g.trig();
    let (s2, c2, s4, c4) = (t.s[0], t.c[0], t.s[2], t.c[2]);
    let (rb, rd) = (fillet(s, layout.hinge_b), fillet(s, layout.hinge_d));
    let least_b = layout.hinge_b.least_thickness(g.b.dims());
    let least_d = layout.hinge_d.least_thickness(g.d.dims());
    let half_face = |kind: HingeKind, dims: &[D], r: f64| {
        max(
            D::from(0.5 * s.link_thickness),
            kind.root_thickness(dims) * 0.5 + r,
        )
    };
    let hb = half_face(layout.hinge_b, g.b.dims(), rb);
    let hd = half_face(layout.hinge_d, g.d.dims(), rd);
    let wall = |v: f64, least: D| D::from(v) - least;
    let slot_bottom = D::from(s.output_block_width - s.min_slot) - hd * s4 * 2.0;
    let pocket = s.actuator_length.map_or(D::from(0.0), |length| {
        g.span_x_with(&t) * 2.0
            + (s.output_block_width - length)
            + c4 * (2.0 * rd)
            + c2 * (2.0 * rb)
            - hb * s2 * 2.0
    });
    let all = [
        wall(s.link_thickness, least_b),
        wall(s.link_thickness, least_d),
        wall(s.input_block_width, least_b),
        wall(s.input_block_width, least_d),
        wall(s.output_block_height, least_b),
        wall(s.output_block_height, least_d),
        D::from(0.5 * s.input_block_height) - hb * (c2 + 1.0),
        D::from(s.output_block_height) - hd * c4 * 2.0,
        slot_bottom,
        slot_bottom + s4 / c4 * (2.0 * s.output_block_height),
        pocket,
    ];
    // the pocket's rule after the size rules, where there is one
    let n = out.len().min(first_rules(s));
    out[..n].copy_from_slice(&all[..n]);
}

/// How many rules come before the clearances: the size rules and the pocket's. The study
/// keeps to them from every start, and to the clearances once a start has ended
/// ([`crate::model::PartMaker::first_rules`]): from random starts, where solids overlap,
/// the clearances' kinks and their subproblems' inconsistent linearizations cost wei2017's
/// study 20 times the time and 40 of its 300 starts.
pub fn first_rules(s: &PartSettings) -> usize {
    SIZES + usize::from(s.actuator_length.is_some())
}
