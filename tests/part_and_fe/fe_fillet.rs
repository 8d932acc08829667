//! The peak stress at a filleted hinge root converges: the first mesh is graded at the
//! fillets that carry the peak (`r / PER_RADIUS` on the arc), and the sequence followed where
//! the finest mesh has its peak. A sharp root's peak still grows without bound
//! (`fe_verify.rs`).

use flexopt::fe::geometry::{Domain, Edge};
use flexopt::fe::verify::{verify_design, VerifySettings, PER_RADIUS};
use std::path::Path;

/// The fillet radius of wei2017's part (PartSettings' default).
const FILLET: f64 = 0.2e-3;

#[test]
fn a_filleted_roots_peak_stress_converges_on_meshes_graded_at_its_fillet() {
    let problem = flexopt::problem::Problem::load(Path::new("problems/wei2017.toml")).unwrap();
    let x = flexopt::problem::design::design_from_optimum(
        &problem,
        Path::new("results/wei2017/optimum.json"),
    )
    .unwrap()
    .x;
    let settings = VerifySettings::default();
    let v = verify_design(problem.mechanism(), &x, &settings).unwrap();
    let domain = Domain::of_part(&v.half);
    let edges: Vec<Edge> = domain.loops.iter().flatten().copied().collect();
    for r in &v.results {
        let peak = r
            .outputs
            .iter()
            .find(|o| o.name == "fe_stress_max")
            .unwrap();
        let e = &peak.estimate;
        let at = format!("{:?}: {e:?} {:?}", r.idealization, peak.values);
        // extrapolated at an order the six-node triangle's stresses show (h^2 in theory;
        // below 1 or far above 2 the sequence is not in its asymptotic range), to within the
        // default tolerance
        assert!(e.converging && !e.oscillating, "{at}");
        let order = e.order.unwrap();
        assert!((1.0..=4.0).contains(&order), "{at}: order {order}");
        assert!(e.within(settings.tolerance), "{at}");
        // the extrapolation stays within its own error of the finest value
        let extrapolated = e.extrapolated.unwrap();
        assert!(
            (extrapolated - e.value).abs() <= e.relative_error.unwrap() * e.value * (1.0 + 1e-12),
            "{at}"
        );

        // the peak lies on a fillet's arc, not at a corner
        let [px, py] = peak.location_mm.unwrap();
        let p = [px.abs() * 1e-3, py * 1e-3];
        let (distance, edge) = domain.nearest_edge(p);
        let Edge::Arc { radius, .. } = edge else {
            panic!("{at}: the peak at {p:?} is not on an arc");
        };
        assert!(
            (radius - FILLET).abs() < 1e-9 * FILLET,
            "{at}: radius {radius}"
        );
        assert!(distance < 1e-6 * FILLET, "{at}: {distance} m off the arc");

        // the first mesh puts at least PER_RADIUS elements a radius along that arc; the
        // fillets far from the peak keep the hinges' sizes (arcs in 15-degree pieces)
        let k = edges.iter().position(|e| *e == edge).unwrap();
        let longest = |k: usize| {
            v.meshes[0]
                .boundary
                .iter()
                .filter(|b| b.edge == k)
                .map(|b| {
                    let (a, c) = (v.meshes[0].nodes[b.nodes[0]], v.meshes[0].nodes[b.nodes[2]]);
                    (c[0] - a[0]).hypot(c[1] - a[1])
                })
                .fold(0.0, f64::max)
        };
        assert!(
            longest(k) <= FILLET / PER_RADIUS * (1.0 + 1e-9),
            "{at}: {} m along the arc",
            longest(k)
        );
        let coarse = edges
            .iter()
            .enumerate()
            .filter(|(_, e)| matches!(e, Edge::Arc { .. }))
            .filter(|&(i, _)| longest(i) > 2.0 * FILLET / PER_RADIUS)
            .count();
        assert!(coarse > 0, "{at}: every arc graded");
    }
}
