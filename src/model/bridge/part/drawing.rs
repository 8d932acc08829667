//! The drawing of a bridge's part: the dimensions `part.png` shows, and the way lengths and
//! angles print in it and in the part's messages.

use super::{across, add, scale, Quarter, P};
use crate::model::bridge::geometry::{Geometry, Layout};
use crate::part::Annotation;

pub(super) use crate::part::mm::{angle as deg, length as mm};

/// The drawing's dimensions: overall size, pocket, the upper left quarter's hinges and link.
pub(super) fn annotations(
    g: &Geometry<f64>,
    q: &Quarter,
    layout: &Layout,
    [in_far, in_h, out_top, pocket]: [f64; 4],
) -> Vec<Annotation> {
    let mid = |p: P, q: P| scale(add(p, q), 0.5);
    let top = in_h.max(out_top);
    let [a, _] = across(q.f[0], q.nb, q.hb);
    vec![
        Annotation::Length {
            a: [in_far, -top],
            b: [-in_far, -top],
            offset: -3e-3,
            label: mm(-2.0 * in_far),
        },
        Annotation::Length {
            a: [-in_far, -top],
            b: [-in_far, top],
            offset: -3e-3,
            label: mm(2.0 * top),
        },
        Annotation::Length {
            a: [a[0], 0.0],
            b: [-a[0], 0.0],
            offset: 0.0,
            label: format!("pocket {}", mm(pocket)),
        },
        Annotation::Length {
            a: q.n[0],
            b: q.n[1],
            offset: 1.2e-3,
            label: format!("{} {}", length_name(layout, 0), mm(g.l2())),
        },
        Annotation::Length {
            a: q.n[2],
            b: q.n[3],
            offset: 1.2e-3,
            label: format!("{} {}", length_name(layout, 1), mm(g.l4())),
        },
        Annotation::Length {
            a: q.n[1],
            b: q.n[2],
            offset: -(q.hb.max(q.hd) + 1.5e-3),
            label: format!("l3 {}", mm(g.l3)),
        },
        Annotation::Note {
            at: mid(q.n[0], q.n[1]),
            label_at: [mid(q.n[0], q.n[1])[0], top + 2e-3],
            label: format!("{}δ2 {}", other_dims(layout, 0, g.b.dims()), deg(g.delta2)),
        },
        Annotation::Note {
            at: mid(q.n[1], q.n[2]),
            label_at: [mid(q.n[1], q.n[2])[0], top + 4e-3],
            label: format!("δ3 {}", deg(g.delta3)),
        },
        Annotation::Note {
            at: mid(q.n[2], q.n[3]),
            label_at: [mid(q.n[2], q.n[3])[0], top + 6e-3],
            label: format!("{}δ4 {}", other_dims(layout, 1, g.d.dims()), deg(g.delta4)),
        },
    ]
}

/// The names of hinge `k`'s (0: b, 1: d) dimensions in the layout, the first one first.
fn dim_names(layout: &Layout, k: usize) -> Vec<String> {
    let (kind, number) = if k == 0 {
        (layout.hinge_b, '2')
    } else {
        (layout.hinge_d, '4')
    };
    kind.dimensions()
        .iter()
        .map(|d| format!("{}{number}", d.stem))
        .collect()
}

/// How the length of hinge `k` is named: its first dimension, doubled for a notch.
fn length_name(layout: &Layout, k: usize) -> String {
    let kind = if k == 0 {
        layout.hinge_b
    } else {
        layout.hinge_d
    };
    kind.length_label(dim_names(layout, k).remove(0))
}

/// Hinge `k`'s dimensions but the first, each with its value, and a separator.
fn other_dims(layout: &Layout, k: usize, dims: &[f64]) -> String {
    dim_names(layout, k)
        .iter()
        .zip(dims)
        .skip(1)
        .map(|(n, v)| format!("{n} {}, ", mm(*v)))
        .collect()
}
