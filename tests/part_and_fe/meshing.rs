//! The mesher's answer depends on the outline, not on its last bits: an outline moved by a
//! few units in the last place (what a change of units or an equivalent formula does to it)
//! meshes into the same triangles, so that the finite-element values move by as little as
//! the outline did.

use crate::common;

use flexopt::fe::geometry::{Domain, Edge};
use flexopt::fe::mesh::mesh;
use flexopt::fe::verify::size_function;
use flexopt::model::Mechanism;
use flexopt::part::Part;

/// `v` moved by `k` units in its last place (k in -4..=4, from a hash of the place); zero
/// stays zero, as it does through a change of units.
fn nudge(v: f64, seed: &mut u64) -> f64 {
    if v == 0.0 {
        return v;
    }
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let k = ((*seed >> 33) % 9) as i64 - 4;
    let mut w = v;
    for _ in 0..k.unsigned_abs() {
        w = if k > 0 { w.next_up() } else { w.next_down() };
    }
    w
}

/// `domain` with its points, radii and angles mapped.
fn mapped(
    domain: &Domain,
    mut point: impl FnMut([f64; 2]) -> [f64; 2],
    mut length: impl FnMut(f64) -> f64,
    mut angle: impl FnMut(f64) -> f64,
) -> Domain {
    let mut d = domain.clone();
    for e in d.loops.iter_mut().flatten() {
        *e = match *e {
            Edge::Line { a, b } => Edge::Line {
                a: point(a),
                b: point(b),
            },
            Edge::Arc {
                centre,
                radius,
                start,
                sweep,
            } => Edge::Arc {
                centre: point(centre),
                radius: length(radius),
                start: angle(start),
                sweep: angle(sweep),
            },
        };
    }
    d
}

fn nudged(domain: &Domain, seed: u64) -> Domain {
    let s = std::cell::Cell::new(seed);
    let one = |v: f64| {
        let mut seed = s.get();
        let w = nudge(v, &mut seed);
        s.set(seed);
        w
    };
    mapped(domain, |q| [one(q[0]), one(q[1])], one, one)
}

/// The region of the right half of paper 004's printed design, as the check meshes it.
fn printed_half() -> Domain {
    let mechanism = Mechanism::complete(flexopt::model::bridge::Bridge::new(
        common::wei2017_settings(),
    ));
    let spec = mechanism
        .part_spec(&common::table1_optimum())
        .unwrap()
        .unwrap();
    Domain::of_part(&Part::build(&spec.right_half().unwrap()).unwrap())
}

#[test]
fn an_outline_nudged_in_its_last_bits_meshes_into_the_same_triangles() {
    let domain = printed_half();
    // the check's own sizes: four elements through each hinge's thickness, growing away
    let (size, coarse) = size_function(&domain, 4.0);
    let reference = mesh(&domain, &size, coarse).unwrap();
    let scale = domain.size();
    for seed in 1..=6u64 {
        let other = nudged(&domain, seed);
        let (size, coarse) = size_function(&other, 4.0);
        let m = mesh(&other, &size, coarse).unwrap();
        assert_eq!(
            (m.elements.len(), m.nodes.len()),
            (reference.elements.len(), reference.nodes.len()),
            "seed {seed}: another mesh"
        );
        assert_eq!(m.elements, reference.elements, "seed {seed}");
        let moved = m
            .nodes
            .iter()
            .zip(&reference.nodes)
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max);
        assert!(
            moved < 1e-12 * scale,
            "seed {seed}: a node moved {moved:e} m"
        );
    }
}

/// The grid decides the triangles, not where the part is: every corner of the outline is a
/// node of the mesh to the last bit, at any scale (a 0.2 mm hinge's faces are found within
/// 2e-13 m, finer than the grid; before the nodes kept the exact points, its FE lost its
/// clamped corners and gave zero stress).
#[test]
fn the_outlines_corners_are_nodes_exactly_at_any_scale() {
    let domain = printed_half();
    for scale in [1.0, 1e-2, 1e-4] {
        let d = mapped(&domain, |p| p.map(|v| v * scale), |r| r * scale, |a| a);
        let size = d.size();
        let m = mesh(&d, &|_| 0.05 * size, 0.05 * size).unwrap();
        let nodes: std::collections::HashSet<[u64; 2]> =
            m.nodes.iter().map(|p| p.map(f64::to_bits)).collect();
        for e in d.loops.iter().flatten() {
            let corner = e.at(0.0);
            assert!(
                nodes.contains(&corner.map(f64::to_bits)),
                "scale {scale}: corner {corner:?} is not a node"
            );
        }
    }
}
