//! The drawing of a bridge's part: the dimensions `part.png` shows, and the way lengths and
//! angles print in it and in the part's messages.

use super::{across, add, scale, Quarter, P};
use crate::model::bridge::geometry::Geometry;
use crate::part::Annotation;

/// A length for a drawing or message: mm, at most three decimals.
pub(super) fn mm(v: f64) -> String {
    format!("{} mm", trimmed(v * 1e3, 3))
}

pub(super) fn deg(v: f64) -> String {
    format!("{}°", trimmed(v.to_degrees(), 2))
}

/// `v` with at most `decimals` decimals, no trailing zeros, and no sign on a zero.
fn trimmed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// The drawing's dimensions: overall size, pocket, the upper left quarter's hinges and link.
pub(super) fn annotations(
    g: &Geometry<f64>,
    q: &Quarter,
    tb: f64,
    td: f64,
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
            label: format!("l2 {}", mm(g.l2())),
        },
        Annotation::Length {
            a: q.n[2],
            b: q.n[3],
            offset: 1.2e-3,
            label: format!("l4 {}", mm(g.l4())),
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
            label: format!("t2 {}, δ2 {}", mm(tb), deg(g.delta2)),
        },
        Annotation::Note {
            at: mid(q.n[1], q.n[2]),
            label_at: [mid(q.n[1], q.n[2])[0], top + 4e-3],
            label: format!("δ3 {}", deg(g.delta3)),
        },
        Annotation::Note {
            at: mid(q.n[2], q.n[3]),
            label_at: [mid(q.n[2], q.n[3])[0], top + 6e-3],
            label: format!("t4 {}, δ4 {}", mm(td), deg(g.delta4)),
        },
    ]
}
