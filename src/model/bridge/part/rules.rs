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
use crate::model::bridge::Trig;
use crate::model::bridge::{Geometry, Layout};
use crate::model::hinge::HingeKind;
use crate::model::hinge::MAX_HINGE_DIMENSIONS;
use crate::model::jet2::Jet2;
use crate::model::part_rules::{PartRule, Witness};
use crate::model::scalar::{max, Jet, Scalar};

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
        clearances::Selection::find_with(s, layout, real, &mut values[first..], |selection| {
            selection.margins(s, layout, g, &mut out[first..])
        });
    }
}

/// [`margins`] at the design `x` (the model's parameters, `N` of them) into `out`, the
/// same numbers to the bit, and their gradients into `jacobian` (row-major, `N` a row):
/// the size rules' and the pocket's alone written out ([`size_margins_with_gradient`]);
/// with the clearances, [`margins_seeded`] over `Jet<N>`. (The size rules written out
/// beside the clearances' `Jet<N>` moved the compiler's inlining of
/// [`clearances::Selection::margins`]: 2.7 times its instructions, callgrind, in
/// wei2017_min_stress's second stages.)
pub fn margins_with_gradient<const N: usize>(
    s: &PartSettings,
    layout: &Layout,
    x: &[f64],
    out: &mut [f64],
    jacobian: &mut [f64],
) {
    let real = layout.geometry(x);
    if out.len() <= first_rules(s) {
        size_margins_with_gradient(s, layout, &real, out, jacobian);
        return;
    }
    let mut y = [Jet::<N>::from(0.0); MAX_RULES];
    let y = &mut y[..out.len()];
    let mut values = [0.0; MAX_RULES];
    // the values as `margins` computes them, to the last digit (a dual number's quotient
    // rounds otherwise), and the clearances' nearest pairs found once, on them
    margins_seeded(
        s,
        layout,
        &real,
        &layout.seeded::<N>(x),
        &mut values[..out.len()],
        y,
    );
    for (row, yi) in jacobian.chunks_exact_mut(N).zip(y.iter()) {
        row.copy_from_slice(&yi.grad);
    }
    out.copy_from_slice(&values[..out.len()]);
}

/// [`margins`] at the design `x` (`N` parameters) into `out`, the same numbers to the bit,
/// their gradients into `jacobian` (`N` a row) and their Hessians into `hessian` (`N * N`
/// a rule, row-major): [`margins_seeded`] over [`Jet2<N>`], for the spreads of a robust
/// study's rules.
pub fn margins_with_hessian<const N: usize>(
    s: &PartSettings,
    layout: &Layout,
    x: &[f64],
    out: &mut [f64],
    jacobian: &mut [f64],
    hessian: &mut [f64],
) {
    let real = layout.geometry(x);
    let seeded: Vec<Jet2<N>> = x
        .iter()
        .enumerate()
        .map(|(i, &v)| Jet2::variable(v, i))
        .collect();
    let mut y = vec![Jet2::<N>::from(0.0); out.len()];
    let mut values = vec![0.0; out.len()];
    margins_seeded(
        s,
        layout,
        &real,
        &layout.geometry(&seeded),
        &mut values,
        &mut y,
    );
    for (k, yk) in y.iter().enumerate() {
        jacobian[k * N..(k + 1) * N].copy_from_slice(&yk.grad);
        yk.hessian(&mut hessian[k * N * N..(k + 1) * N * N]);
    }
    out.copy_from_slice(&values);
}

/// The size rules' margins and the pocket's at `g`, the first `out.len()` of them, as
/// [`size_margins`] gives them, and their gradients over the model's parameters into
/// `jacobian` (row-major, `jacobian.len() / out.len()` a row).
///
/// The rules are sums and products of the settings, each hinge's length, least and root
/// thickness, `l3` and the angles' sines and cosines, with `max` in the faces' half widths:
/// each partial is written out here as [`Jet`]'s operations form it, term for term in the
/// same order with the terms that are zero left out, so that the gradients are the bits
/// the generic code over `Jet<N>` gives ([`margins_seeded`]; a test compares them). Only
/// a hinge's three quantities, of a kind's own formulas, are worked over dual numbers, of
/// its own dimensions alone, and spread to the parameters by their slots: the local
/// preaccumulation of Griewank and Walther, "Evaluating Derivatives", 2nd ed., SIAM 2008,
/// Sec. 10.2. Over `Jet<N>` the rules and their sines and cosines carried `N` derivatives
/// through every operation, most of them zero, and the values' sines and cosines were
/// worked out again: about 2,100 instructions an evaluation in wei2017's first stages,
/// 1,200 written out (callgrind).
pub fn size_margins_with_gradient(
    s: &PartSettings,
    layout: &Layout,
    g: &Geometry<f64>,
    out: &mut [f64],
    jacobian: &mut [f64],
) {
    if out.is_empty() {
        return;
    }
    let t = g.trig();
    size_margins_with(s, layout, g, &t, out);
    let n = jacobian.len() / out.len();
    jacobian.fill(0.0);
    let (b_slots, d_slots, [i2, i3l, i3, i4]) = layout.slots();
    let (s2, c2, s3, c3, s4, c4) = (t.s[0], t.c[0], t.s[1], t.c[1], t.s[2], t.c[2]);
    let (rb, rd) = (fillet(s, layout.hinge_b), fillet(s, layout.hinge_d));
    let b = HingeParts::new(layout.hinge_b, g.b.dims(), rb, s.link_thickness);
    let d = HingeParts::new(layout.hinge_d, g.d.dims(), rd, s.link_thickness);
    let (hb, hd) = (b.half_face.re, d.half_face.re);
    let obh = s.output_block_height;
    // the slot's top: (s4 / c4)' = (c4 - (-s4) (s4 / c4)) / c4 (`Jet`'s quotient rule)
    let inv = 1.0 / c4;
    let tan_grad = (c4 - (-s4) * (s4 * inv)) * inv;
    let mut rows = jacobian.chunks_exact_mut(n);
    // the walls: a constant less a least thickness
    for (slots, least) in [(b_slots, &b.least), (d_slots, &d.least)]
        .iter()
        .cycle()
        .take(6)
    {
        let Some(r) = rows.next() else { return };
        for (&p, g) in slots.iter().zip(least.grad) {
            r[p] = 0.0 - g;
        }
    }
    // input_block_faces: 0.5 H - hb (c2 + 1)
    let Some(r) = rows.next() else { return };
    for (&p, g) in b_slots.iter().zip(b.half_face.grad) {
        r[p] = 0.0 - g * (c2 + 1.0);
    }
    r[i2] = 0.0 - (-s2) * hb;
    // output_block_faces: OBH - hd c4 2
    let Some(r) = rows.next() else { return };
    for (&p, g) in d_slots.iter().zip(d.half_face.grad) {
        r[p] = 0.0 - (g * c4) * 2.0;
    }
    r[i4] = 0.0 - ((-s4) * hd) * 2.0;
    // output_slot_bottom and _top: W - min_slot - hd s4 2, the top plus s4 / c4 (2 OBH)
    for top in [false, true] {
        let Some(r) = rows.next() else { return };
        for (&p, g) in d_slots.iter().zip(d.half_face.grad) {
            r[p] = 0.0 - (g * s4) * 2.0;
        }
        let bottom = 0.0 - (c4 * hd) * 2.0;
        r[i4] = if top {
            bottom + tan_grad * (2.0 * obh)
        } else {
            bottom
        };
    }
    // actuator_pocket: (l2 c2 + l3 c3 + l4 c4) 2 + (W - L) + c4 (2 rd) + c2 (2 rb) - hb s2 2
    let Some(r) = rows.next() else { return };
    let (lb, ld) = (b.length.re, d.length.re);
    for ((&p, gl), gh) in b_slots.iter().zip(b.length.grad).zip(b.half_face.grad) {
        r[p] = (gl * c2) * 2.0 - (gh * s2) * 2.0;
    }
    for (&p, gl) in d_slots.iter().zip(d.length.grad) {
        r[p] = (gl * c4) * 2.0;
    }
    r[i2] = ((-s2) * lb) * 2.0 + (-s2) * (2.0 * rb) - (c2 * hb) * 2.0;
    r[i3l] = c3 * 2.0;
    r[i3] = ((-s3) * g.l3) * 2.0;
    r[i4] = ((-s4) * ld) * 2.0 + (-s4) * (2.0 * rd);
}

/// A hinge's length, least thickness and faces' half width (`max(link_thickness / 2, t_root
/// / 2 + r)`, the branch its value takes) over the hinge's own dimensions.
struct HingeParts {
    length: Jet<MAX_HINGE_DIMENSIONS>,
    least: Jet<MAX_HINGE_DIMENSIONS>,
    half_face: Jet<MAX_HINGE_DIMENSIONS>,
}

impl HingeParts {
    fn new(kind: HingeKind, dims: &[f64], fillet: f64, link_thickness: f64) -> Self {
        let mut seeded = [Jet::from(0.0); MAX_HINGE_DIMENSIONS];
        for (k, (j, &v)) in seeded.iter_mut().zip(dims).enumerate() {
            *j = Jet::variable(v, k);
        }
        let dims = &seeded[..dims.len()];
        HingeParts {
            length: kind.length(dims),
            least: kind.least_thickness(dims),
            half_face: max(
                Jet::from(0.5 * link_thickness),
                kind.root_thickness(dims) * 0.5 + fillet,
            ),
        }
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
    size_margins_with(s, layout, g, &g.trig(), out);
}

/// [`size_margins`] with the angles' sines and cosines `t`.
fn size_margins_with<D: Scalar>(
    s: &PartSettings,
    layout: &Layout,
    g: &Geometry<D>,
    t: &Trig<D>,
    out: &mut [D],
) {
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
        g.span_x_with(t) * 2.0 + (s.output_block_width - length) + c4 * (2.0 * rd) + c2 * (2.0 * rb)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::bridge::Layout;
    use crate::model::scalar::Jet;
    use rand::{Rng, SeedableRng};

    /// The written-out gradients against the generic code over `Jet<N>`, to the bit (a
    /// zero's sign aside), and the values against [`margins`], for every pair of hinge
    /// kinds, with and without the pocket, on both sides of the faces' kinks.
    fn agree<const N: usize>(layout: &Layout, r: &mut rand_chacha::ChaCha8Rng) {
        let mm = 1e-3;
        let mut s = PartSettings {
            actuator_length: r.random_bool(0.7).then(|| r.random_range(5.0..45.0) * mm),
            ..PartSettings::default()
        };
        // the default sizes scaled, each on its own, from a tenth to four times
        for v in [
            &mut s.link_thickness,
            &mut s.fillet_radius,
            &mut s.input_block_width,
            &mut s.input_block_height,
            &mut s.output_block_width,
            &mut s.output_block_height,
            &mut s.min_slot,
        ] {
            *v *= r.random_range(0.1..4.0);
        }
        let x: Vec<f64> = layout
            .parameters()
            .iter()
            .map(|p| match p.dimension {
                crate::model::Dimension::Angle => r.random_range(-0.6..0.6),
                _ => r.random_range(0.1..12.0) * mm,
            })
            .collect();
        assert_eq!(x.len(), N);
        let all = rules(&s).len();
        for count in [first_rules(&s), all] {
            let (mut out, mut jac) = (vec![0.0; count], vec![f64::NAN; count * N]);
            margins_with_gradient::<N>(&s, layout, &x, &mut out, &mut jac);
            let mut plain = vec![0.0; count];
            margins(&s, layout, &layout.geometry(&x), &mut plain);
            assert_eq!(out, plain);
            let (mut values, mut y) = (vec![0.0; count], vec![Jet::<N>::from(0.0); count]);
            let (real, seeded) = (layout.geometry(&x), layout.seeded::<N>(&x));
            margins_seeded(&s, layout, &real, &seeded, &mut values, &mut y);
            for (i, yi) in y.iter().enumerate() {
                assert_eq!(values[i], out[i]);
                assert_eq!(
                    &jac[i * N..(i + 1) * N],
                    &yi.grad,
                    "rule {i} at {x:?}, {s:?}"
                );
            }
        }
    }

    #[test]
    fn the_written_out_gradients_are_the_dual_numbers_bits() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        for &kb in HingeKind::ALL {
            for &kd in HingeKind::ALL {
                let layout = Layout::new(kb, kd);
                for _ in 0..200 {
                    match layout.parameters().len() {
                        8 => agree::<8>(&layout, &mut r),
                        9 => agree::<9>(&layout, &mut r),
                        10 => agree::<10>(&layout, &mut r),
                        n => panic!("{n} parameters"),
                    }
                }
            }
        }
    }
}
