//! The network's pictures ([`Depiction`]): the described part at a design, its bodies'
//! points and its flexures, for the design report (`nodes_mm`: every body's points, then
//! each flexure's two ends) and the configuration plot (each body's outline, or its link's
//! centre line, in grey; each flexure a band of its least thickness). A network is no chain:
//! its skeleton is broken between pieces by a node that is not a number, across which no
//! member is drawn ([`Skeleton`]).

use super::model::NetworkModel;
use crate::model::mechanism::Depiction;
use crate::model::{Drawing, Skeleton};

/// The described part at one design (m).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Picture {
    /// Each body's points: its outline, or its link's two ends.
    pub bodies: Vec<Vec<[f64; 2]>>,
    /// Each flexure's start, end and least thickness: the hinges, then the beams.
    pub flexures: Vec<([f64; 2], [f64; 2], f64)>,
}

/// What [`NetworkModel`]'s skeleton draws.
const LEGEND: &str = "to scale, the described part: hinges and beams in colour at their least \
                      thickness, bodies' outlines and links' centre lines grey";

fn mm(p: [f64; 2]) -> (f64, f64) {
    (p[0] * 1e3, p[1] * 1e3)
}

/// `picture` as pieces joined into one chain, a node of NaNs between two pieces.
fn skeleton(picture: &Picture) -> Skeleton {
    let mut s = Skeleton {
        nodes_mm: Vec::new(),
        rigid: Vec::new(),
        thickness_mm: Vec::new(),
    };
    let mut piece = |nodes: &[(f64, f64)], rigid: bool, thickness_mm: f64| {
        if !s.nodes_mm.is_empty() {
            s.nodes_mm.push((f64::NAN, f64::NAN));
            s.rigid.extend([true, true]);
            s.thickness_mm.extend([0.0, 0.0]);
        }
        s.nodes_mm.extend_from_slice(nodes);
        s.rigid.extend(std::iter::repeat_n(rigid, nodes.len() - 1));
        s.thickness_mm
            .extend(std::iter::repeat_n(thickness_mm, nodes.len() - 1));
    };
    for points in &picture.bodies {
        let mut outline: Vec<(f64, f64)> = points.iter().map(|&p| mm(p)).collect();
        if outline.len() >= 3 {
            outline.push(outline[0]);
        }
        if outline.len() >= 2 {
            piece(&outline, true, 0.0);
        }
    }
    for &(start, end, t) in &picture.flexures {
        piece(&[mm(start), mm(end)], false, t * 1e3);
    }
    s
}

impl Depiction for NetworkModel {
    fn drawing(&self, x: &[f64]) -> Drawing {
        let nodes_mm = self.picture(x).map(|p| {
            let bodies = p.bodies.iter().flatten().copied();
            let ends = p.flexures.iter().flat_map(|&(a, b, _)| [a, b]);
            bodies
                .chain(ends)
                .map(|q| [q[0] * 1e3, q[1] * 1e3])
                .collect()
        });
        Drawing {
            nodes_mm,
            mode_shapes: None,
        }
    }

    fn skeleton(&self, x: &[f64]) -> Option<Skeleton> {
        self.picture(x).as_ref().map(skeleton)
    }

    fn skeleton_legend(&self) -> &'static str {
        LEGEND
    }
}
