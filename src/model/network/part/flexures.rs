//! The flexures of a network's part as cut: each hinge, and each flexible beam, its solid
//! and its two pads.
//!
//! A beam is cut as a strip hinge of its length and thickness is: a [`HingeSite`], so that
//! every check and the finite elements treat it as the flexure it is in the model. The
//! keep-out band beside a hinge's thin section holds beside a beam's too (a solid crossing
//! it, or closer than the narrowest slot, is named with it), the fillets round its four
//! roots, the mesh is graded to its thickness along its length, it keeps its own stiffness
//! where the bodies are stiffened, and its section stresses join the hinges' in
//! `fe_stress_section`, the counterpart of `stress_max`, which takes the beams' stresses
//! beside the hinges'. A beam drawn as a link would be none of these.

use super::plane::{add, band, scale, P};
use super::settings::PartSettings;
use crate::model::hinge::HingeKind;
use crate::part::{HingeSite, Solid};

/// A described hinge or beam as cut: its solid, its site and its two pads with their
/// bodies (by slot, 0 the ground).
pub(super) struct CutHinge {
    pub(super) solid: Solid,
    pub(super) site: HingeSite,
    pub(super) from: usize,
    pub(super) to: usize,
    /// Each pad and, for a pad on the ground, its clamped side.
    pub(super) pads: [(Solid, Option<(P, P)>); 2],
}

/// What a flexure is called on the drawing (`"hinge"`, `"beam"`) and by name.
pub(super) struct Named<'a> {
    pub(super) what: &'static str,
    pub(super) name: &'a str,
}

/// The flexure of `kind` and `dims` (SI) from `start` along the unit vector `u`, from body
/// slot `from` to `to`: its thin section, its solid the fillet radius beyond both ends (a
/// kind with sharp roots; a notch meets its bodies smoothly and has none) to a face across
/// it, and behind each face a pad `pad` deep and `root/2 + fillet + pad_margin` to each
/// side, holding the solid's corners on its face edge. A pad on the ground is held on its
/// far side.
pub(super) fn cut(
    named: Named<'_>,
    kind: HingeKind,
    dims: &[f64],
    start: P,
    u: P,
    (from, to): (usize, usize),
    s: &PartSettings,
) -> CutHinge {
    let n = [-u[1], u[0]];
    let length = kind.length(dims);
    let end = add(start, scale(u, length));
    let root = kind.root_thickness(dims);
    let fillet = if kind.has_sharp_roots() {
        s.fillet_radius
    } else {
        0.0
    };
    let (f0, f1) = (add(start, scale(u, -fillet)), add(end, scale(u, fillet)));
    let half = 0.5 * root + fillet + s.pad_margin;
    let body = band(f0, f1, 0.5 * root);
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
    let clamp_from = (from == 0).then(|| (pad_from[5], pad_from[0]));
    let clamp_to = (to == 0).then(|| (pad_to[1], pad_to[2]));
    let Named { what, name } = named;
    let pad = |side: &str, points| Solid {
        name: format!("the pad at {what} {name}'s {side}"),
        points,
    };
    CutHinge {
        solid: Solid {
            name: format!("{what} {name}"),
            points: body,
        },
        site: HingeSite {
            name: name.to_string(),
            start,
            end,
            thickness: kind.least_thickness(dims),
            root,
            fillet,
            kind: if what == "beam" { "beam" } else { kind.name() },
            profile: kind.outline(dims),
            solid: 0,
        },
        from,
        to,
        pads: [
            (pad("start", pad_from), clamp_from),
            (pad("end", pad_to), clamp_to),
        ],
    }
}
