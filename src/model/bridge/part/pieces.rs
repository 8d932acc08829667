//! The bridge part's solids over [`Scalar`] as the clearance rules and the footprint see
//! them: each a convex piece of four corners placed as [`super::spec`] places the solid
//! (the input blocks cut into three pieces at the heights of the pushed face's ends), the
//! keep-out bands beside the hinges, the actuator's body, and the part's symmetry about both
//! axes, by which one pair of every set of mirror images is looked at.

use std::sync::OnceLock;

use super::{across, band, rules::fillet, PartSettings, Quarter, P};
use crate::model::bridge::{Geometry, Layout};
use crate::model::scalar::{max, min, Scalar};

/// How far the keep-out bands stop short of the faces at the hinge's ends (m), as the
/// part's check has them ([`crate::part::checks::keep_out`]).
pub const FACE_INSET: f64 = 1e-9;

/// A convex piece of a solid: four corners.
pub(super) type Piece<D> = [P<D>; 4];

/// The solids in [`super::spec`]'s order: the left and right input blocks, the upper and
/// lower output blocks, then hinge b, link c and hinge d of the upper left, upper right,
/// lower left and lower right quarters.
pub(super) const SOLIDS: usize = 16;
/// The shapes the rules compare beyond the solids.
pub(super) const BAND_B: usize = 16;
pub(super) const BAND_B_START: usize = 17;
pub(super) const BAND_D: usize = 18;
pub(super) const BAND_D_START: usize = 19;
pub(super) const ACTUATOR: usize = 20;
pub(super) const INPUT_UPPER: usize = 21;
pub(super) const BAND_B_END: usize = 22;
pub(super) const BAND_D_END: usize = 23;

/// Each shape's pieces: `(first, count)` in [`pieces`]'s array.
pub(super) const RANGES: [(usize, usize); 24] = [
    (0, 3),
    (3, 3),
    (6, 1),
    (7, 1),
    (8, 1),
    (9, 1),
    (10, 1),
    (11, 1),
    (12, 1),
    (13, 1),
    (14, 1),
    (15, 1),
    (16, 1),
    (17, 1),
    (18, 1),
    (19, 1),
    (20, 1),
    (21, 1),
    (22, 1),
    (23, 1),
    (24, 1),
    // the left input block's piece above the pushed face
    (0, 1),
    (25, 1),
    (26, 1),
];
pub(super) const PIECES: usize = 27;
/// How many of [`pieces`], the first ones, are the part's solids.
pub(super) const SOLID_PIECES: usize = 20;

pub(super) fn mirror_x<D: Scalar>(p: P<D>) -> P<D> {
    [-p[0], p[1]]
}

pub(super) fn mirror_y<D: Scalar>(p: P<D>) -> P<D> {
    [p[0], -p[1]]
}

/// The keep-out band beside the hinge from `start` to `end` with root thickness `root` and
/// fillet `r`: `slot` beyond its root half thickness to each side, from `from` to `to`
/// along it (m, from `start`).
pub(super) fn keep_out<D: Scalar>(
    start: P<D>,
    end: P<D>,
    root: D,
    slot: f64,
    [from, to]: [D; 2],
) -> Piece<D> {
    let d = [end[0] - start[0], end[1] - start[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let u = [d[0] / len, d[1] / len];
    let n = [-u[1], u[0]];
    let w = root * 0.5 + slot;
    let at = |s: D, t: D| {
        [
            start[0] + u[0] * s + n[0] * t,
            start[1] + u[1] * s + n[1] * t,
        ]
    };
    [at(from, -w), at(to, -w), at(to, w), at(from, w)]
}

/// The ends of a keep-out band along its hinge of length `len` with fillet `r`: the whole
/// band's, then, shortened by its half width `w` at its start and at its end, the ones the
/// body joined there is held to (a body may fold back beside its own face as far as its
/// corner), as the part's check has them ([`crate::part::checks::keep_out`]).
pub(super) fn band_ends<D: Scalar>(len: D, r: f64, w: D) -> [[D; 2]; 3] {
    let whole = [D::from(-r + FACE_INSET), len + (r - FACE_INSET)];
    let start = min(whole[0] + w, whole[1]);
    let end = max(whole[1] - w, whole[0]);
    [whole, [start, whole[1]], [whole[0], end]]
}

/// Every piece of the part's solids and of the shapes the rules compare them with, at the
/// design `g`, in [`RANGES`]' order.
pub(super) fn pieces<D: Scalar>(
    s: &PartSettings,
    layout: &Layout,
    g: &Geometry<D>,
) -> [Piece<D>; PIECES] {
    let tb = layout.hinge_b.root_thickness(g.b.dims());
    let td = layout.hinge_d.root_thickness(g.d.dims());
    let (rb, rd) = (fillet(s, layout.hinge_b), fillet(s, layout.hinge_d));
    let q = Quarter::new(g, s, [tb, td], [rb, rd]);
    let [f2, f3, f4, f5] = q.f;
    let hinge_b = band(f2, f3, q.nb, tb * 0.5);
    let hinge_d = band(f4, f5, q.nd, td * 0.5);
    let [l3a, l3b] = across(f3, q.nb, q.hb);
    let [l4a, l4b] = across(f4, q.nd, q.hd);
    let link = [l3a, l3b, l4a, l4b];
    let [a, b] = across(f2, q.nb, q.hb);
    let in_h = D::from(0.5 * s.input_block_height);
    let in_far = f2[0] - s.input_block_width;
    let upper = [[in_far, a[1]], a, b, [in_far, in_h]];
    let middle = [[in_far, -a[1]], [a[0], -a[1]], a, [in_far, a[1]]];
    let lower = upper.map(mirror_y);
    let out_bottom = f5[1] - q.hd * q.nd[1];
    let out_top = out_bottom + s.output_block_height;
    let side = |y: D| f5[0] + (y - f5[1]) / q.nd[1] * q.nd[0];
    let output = [
        [side(out_bottom), out_bottom],
        [-side(out_bottom), out_bottom],
        [-side(out_top), out_top],
        [side(out_top), out_top],
    ];
    let slot_b = rb.max(s.min_slot);
    let slot_d = rd.max(s.min_slot);
    let length = |p: P<D>, q: P<D>| {
        let d = [q[0] - p[0], q[1] - p[1]];
        (d[0] * d[0] + d[1] * d[1]).sqrt()
    };
    let [whole_b, start_b, end_b] = band_ends(length(q.n[0], q.n[1]), rb, tb * 0.5 + slot_b);
    let [whole_d, start_d, end_d] = band_ends(length(q.n[2], q.n[3]), rd, td * 0.5 + slot_d);
    let (hl, hh) = (
        0.5 * s.actuator_length.unwrap_or(0.0) - FACE_INSET,
        0.5 * s.actuator_height.unwrap_or(0.0),
    );
    let actuator = [[-hl, -hh], [hl, -hh], [hl, hh], [-hl, hh]].map(|p| p.map(D::from));
    let zero = [D::from(0.0); 2];
    let mut out = [[zero; 4]; PIECES];
    out[..3].copy_from_slice(&[upper, middle, lower]);
    for k in 0..3 {
        out[3 + k] = out[k].map(mirror_x);
    }
    out[6] = output;
    out[7] = output.map(mirror_y);
    let quarter = [hinge_b, link, hinge_d];
    for (k, m) in [(|p| p) as fn(P<D>) -> P<D>, mirror_x, mirror_y, |p| {
        mirror_x(mirror_y(p))
    }]
    .into_iter()
    .enumerate()
    {
        for (i, piece) in quarter.iter().enumerate() {
            out[8 + 3 * k + i] = piece.map(m);
        }
    }
    out[20] = keep_out(q.n[0], q.n[1], tb, slot_b, whole_b);
    out[21] = keep_out(q.n[0], q.n[1], tb, slot_b, start_b);
    out[22] = keep_out(q.n[2], q.n[3], td, slot_d, whole_d);
    out[23] = keep_out(q.n[2], q.n[3], td, slot_d, start_d);
    out[24] = actuator;
    out[25] = keep_out(q.n[0], q.n[1], tb, slot_b, end_b);
    out[26] = keep_out(q.n[2], q.n[3], td, slot_d, end_d);
    out
}

/// A solid's mirror image about the x axis (`mirror_x`: x negated) and the y axis.
pub(super) fn mirrored(i: usize, about_y_axis: bool) -> usize {
    if i < 4 {
        let swap = if about_y_axis {
            [1, 0, 2, 3]
        } else {
            [0, 1, 3, 2]
        };
        return swap[i];
    }
    let (k, m) = ((i - 4) / 3, (i - 4) % 3);
    let swap = if about_y_axis {
        [1, 0, 3, 2]
    } else {
        [2, 3, 0, 1]
    };
    4 + 3 * swap[k] + m
}

/// Whether two solids are joined (a hinge and the body it ends in), as the part joins them.
pub(super) fn joined(i: usize, j: usize) -> bool {
    (0..4).any(|k| {
        let first = 4 + 3 * k;
        let (input, output) = (k % 2, 2 + k / 2);
        [
            (first, input),
            (first, first + 1),
            (first + 1, first + 2),
            (first + 2, output),
        ]
        .iter()
        .any(|&(a, b)| (a, b) == (i, j) || (a, b) == (j, i))
    })
}

/// One pair of every set of mirror images of the pairs of solids.
pub(super) fn pair_orbits() -> &'static [(usize, usize)] {
    static PAIRS: OnceLock<Vec<(usize, usize)>> = OnceLock::new();
    PAIRS.get_or_init(|| {
        let mut pairs = Vec::new();
        for i in 0..SOLIDS {
            for j in i + 1..SOLIDS {
                let images = [
                    (i, j),
                    (mirrored(i, true), mirrored(j, true)),
                    (mirrored(i, false), mirrored(j, false)),
                    (
                        mirrored(mirrored(i, true), false),
                        mirrored(mirrored(j, true), false),
                    ),
                ];
                let first = images.iter().map(|&(a, b)| (a.min(b), a.max(b))).min();
                if first == Some((i, j)) {
                    pairs.push((i, j));
                }
            }
        }
        pairs
    })
}

/// The actuator against the upper left quarter's solids, the upper output block and the
/// left input block's piece above the face it pushes: by symmetry, every other.
pub(super) const ACTUATOR_PAIRS: [(usize, usize); 5] = [
    (ACTUATOR, INPUT_UPPER),
    (ACTUATOR, 2),
    (ACTUATOR, 4),
    (ACTUATOR, 5),
    (ACTUATOR, 6),
];

/// A piece's bounding circle: the mean of its corners and the farthest corner's distance.
pub(super) fn circle(p: &Piece<f64>) -> (P, f64) {
    let c = [
        0.25 * (p[0][0] + p[1][0] + p[2][0] + p[3][0]),
        0.25 * (p[0][1] + p[1][1] + p[2][1] + p[3][1]),
    ];
    let r2 = p
        .iter()
        .map(|q| (q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2))
        .fold(0.0, f64::max);
    (c, r2.sqrt())
}
