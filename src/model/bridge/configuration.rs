//! The names of bridge configurations (paper 004, Fig. 2 and Sec. 5) and the drawing of a
//! design's quarter.

use super::geometry::Geometry;
use crate::model::Skeleton;

/// The rule of [`configuration`], for readers of the results.
pub const RULE: &str = "rhombic: middle link shorter than a quarter of l2 + l3 + l4; \
parallel: |delta2|, |delta4| <= 1 deg; aligned: delta2, delta3, delta4 within 1 deg of each other; general: otherwise (first match)";

/// The kind of a bridge configuration, by this rule (first match wins), with angle
/// tolerance 1 deg:
/// - `rhombic`: the rigid middle link shorter than a quarter of the chain `l2 + l3 + l4`,
///   so that the flexible hinges make most of the arm, as in the rhombic type of paper
///   004 (Fig. 2c, Eq. 24: one flexible beam from input to output);
/// - `parallel`: both hinges horizontal (`delta2 = delta4 = 0`, Eq. 22);
/// - `aligned`: hinges and middle link in one line (`delta2 = delta3 = delta4`, Eq. 26);
/// - `general`: anything else.
pub fn configuration(g: &Geometry<f64>) -> &'static str {
    let tol = 1f64.to_radians();
    let (l2, l4) = (g.l2(), g.l4());
    if g.l3 < 0.25 * (l2 + g.l3 + l4) {
        "rhombic"
    } else if g.delta2.abs() <= tol && g.delta4.abs() <= tol {
        "parallel"
    } else if (g.delta2 - g.delta3).abs() <= tol && (g.delta4 - g.delta3).abs() <= tol {
        "aligned"
    } else {
        "general"
    }
}

/// The quarter's centre line: hinge b, the rigid middle link, hinge d (mm, origin at node 2),
/// each hinge as thick as its thinnest section.
pub fn skeleton(g: &Geometry<f64>) -> Skeleton {
    let t = |h: &crate::model::hinge::Hinge<f64>| h.kind.least_thickness(h.dims()) * 1e3;
    Skeleton {
        nodes_mm: g.nodes().iter().map(|p| (p[0] * 1e3, p[1] * 1e3)).collect(),
        rigid: vec![false, true, false],
        thickness_mm: vec![t(&g.b), 0.0, t(&g.d)],
    }
}

/// What the colours of [`skeleton`]'s plot mean.
pub const SKELETON_LEGEND: &str =
    "to scale: hinges in colour at their least thickness, middle link's centre line grey, origin at node 2";
