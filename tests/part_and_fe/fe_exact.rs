//! The finite elements against exact solutions: the patch test, Timoshenko's cantilever
//! under an end load and an end moment, Kirsch's plate with a hole, a cantilever's first
//! natural frequency.

use flexopt::fe::assembly::Pattern;
use flexopt::fe::geometry::{Domain, Edge};
use flexopt::fe::mesh::{mesh, Mesh};
use flexopt::fe::{loads, modal, solve_static, stress, Elastic, Idealization};

const STEEL: Elastic = Elastic {
    youngs_modulus: 200e9,
    poisson_ratio: 0.3,
    density: 7800.0,
};

/// Fixed degrees of freedom and their values from `field` at the nodes `nodes`.
fn prescribe(
    m: &Mesh,
    nodes: &[usize],
    field: impl Fn([f64; 2]) -> [f64; 2],
) -> (Vec<bool>, Vec<f64>) {
    let mut fixed = vec![false; 2 * m.nodes.len()];
    let mut value = vec![0.0; 2 * m.nodes.len()];
    for &n in nodes {
        let u = field(m.nodes[n]);
        for k in 0..2 {
            fixed[2 * n + k] = true;
            value[2 * n + k] = u[k];
        }
    }
    (fixed, value)
}

fn boundary_nodes(m: &Mesh) -> Vec<usize> {
    let mut b: Vec<usize> = m.boundary.iter().flat_map(|e| e.nodes).collect();
    b.sort_unstable();
    b.dedup();
    b
}

/// A square with a circular hole: the outer loop counterclockwise, the hole clockwise.
fn plate_with_hole(half: f64, radius: f64) -> Domain {
    let c = [[-half, -half], [half, -half], [half, half], [-half, half]];
    Domain {
        loops: vec![
            (0..4)
                .map(|i| Edge::Line {
                    a: c[i],
                    b: c[(i + 1) % 4],
                })
                .collect(),
            vec![Edge::Arc {
                centre: [0.0, 0.0],
                radius,
                start: 0.0,
                sweep: -std::f64::consts::TAU,
            }],
        ],
        faces: Vec::new(),
        hinges: Vec::new(),
    }
}

#[test]
fn the_patch_test_reproduces_a_linear_field_to_rounding_on_curved_and_graded_meshes() {
    let field = |p: [f64; 2]| {
        [
            1e-4 + 2e-3 * p[0] - 1e-3 * p[1],
            -2e-4 + 0.5e-3 * p[0] + 3e-3 * p[1],
        ]
    };
    let domain = plate_with_hole(0.02, 0.006);
    // graded: small near the hole, large at the edges
    let size = |p: [f64; 2]| 0.001 + 0.2 * (p[0].hypot(p[1]) - 0.006).max(0.0);
    for m in [
        mesh(&domain, &size, 0.004).unwrap(),
        mesh(&domain, &size, 0.004).unwrap().refined(&domain),
    ] {
        for idealization in Idealization::BOTH {
            let (fixed, value) = prescribe(&m, &boundary_nodes(&m), field);
            let u = solve_static(
                &m,
                &STEEL,
                0.01,
                idealization,
                &fixed,
                &value,
                &[vec![0.0; 2 * m.nodes.len()]],
            )
            .unwrap()
            .remove(0);
            let mut worst: f64 = 0.0;
            for (n, p) in m.nodes.iter().enumerate() {
                let want = field(*p);
                worst = worst
                    .max((u[2 * n] - want[0]).abs())
                    .max((u[2 * n + 1] - want[1]).abs());
            }
            // the displacements are of order 1e-4 m: 1e-12 relative
            assert!(
                worst < 1e-16,
                "{idealization:?}: worst nodal error {worst:e} m"
            );
            // and the stress is the constant D epsilon everywhere
            let d = STEEL.d_matrix(idealization);
            let eps = [2e-3, 3e-3, -1e-3 + 0.5e-3];
            let want: Vec<f64> = (0..3)
                .map(|r| (0..3).map(|c| d[r][c] * eps[c]).sum())
                .collect();
            for s in stress::nodal_stresses(&m, &d, &u) {
                for c in 0..3 {
                    assert!(
                        (s[c] - want[c]).abs() < 1e-12 * 1e9,
                        "{s:?} against {want:?}"
                    );
                }
            }
        }
    }
}

/// Timoshenko and Goodier, "Theory of Elasticity", 3rd ed., 1970, Art. 21: the cantilever
/// of depth `D` (y from -D/2 to D/2), held at x = 0 and loaded at x = L by a parabolic shear
/// of resultant `P` per unit width, in plane stress (the form of Augarde and Deeks, Finite
/// Elem. Anal. Des. 44, 2008, Eq. 1-2).
fn end_load_field(p: f64, l: f64, depth: f64, e: f64, nu: f64) -> impl Fn([f64; 2]) -> [f64; 2] {
    let i = depth.powi(3) / 12.0;
    move |x: [f64; 2]| {
        let (x, y) = (x[0], x[1]);
        [
            p * y / (6.0 * e * i)
                * ((6.0 * l - 3.0 * x) * x + (2.0 + nu) * (y * y - depth * depth / 4.0)),
            -p / (6.0 * e * i)
                * (3.0 * nu * y * y * (l - x)
                    + (4.0 + 5.0 * nu) * depth * depth * x / 4.0
                    + (3.0 * l - x) * x * x),
        ]
    }
}

/// Solves the cantilever `l` by `depth` on uniform refinements of one mesh, with the exact
/// displacements held at x = 0 and the exact traction at x = l; returns the tip deflection
/// at y = 0 at each level.
fn cantilever(
    l: f64,
    depth: f64,
    levels: usize,
    exact: &dyn Fn([f64; 2]) -> [f64; 2],
    traction: &dyn Fn([f64; 2]) -> [f64; 2],
) -> Vec<f64> {
    let domain = Domain::rectangle(0.0, -depth / 2.0, l, depth / 2.0);
    let mut m = mesh(&domain, &|_| depth / 2.0, depth / 2.0).unwrap();
    let mut tips = Vec::new();
    for _ in 0..levels {
        let root = m.nodes_on([0.0, -depth / 2.0], [0.0, depth / 2.0], 1e-12);
        let (fixed, value) = prescribe(&m, &root, exact);
        let end = m.edges_on([l, -depth / 2.0], [l, depth / 2.0], 1e-12);
        let f = loads::traction_forces(&m, &end, 1.0, traction);
        let u = solve_static(
            &m,
            &STEEL,
            1.0,
            Idealization::PlaneStress,
            &fixed,
            &value,
            &[f],
        )
        .unwrap()
        .remove(0);
        let tip = m
            .nodes
            .iter()
            .position(|p| (p[0] - l).abs() < 1e-12 && p[1].abs() < 1e-12)
            .unwrap();
        tips.push(u[2 * tip + 1]);
        m = m.refined(&domain);
    }
    tips
}

#[test]
fn a_cantilever_under_an_end_load_converges_to_timoshenkos_solution_at_the_elements_order() {
    let (l, depth, p): (f64, f64, f64) = (0.05, 0.01, 1000.0);
    let (e, nu) = (STEEL.youngs_modulus, STEEL.poisson_ratio);
    let exact = end_load_field(p, l, depth, e, nu);
    let i = depth.powi(3) / 12.0;
    let traction = move |x: [f64; 2]| [0.0, -p / (2.0 * i) * (depth * depth / 4.0 - x[1] * x[1])];
    let want = exact([l, 0.0])[1];
    // beam theory: bending plus shear with Timoshenko's factor 2/3 for this loading
    let beam = -(p * l.powi(3) / (3.0 * e * i)
        + (4.0 + 5.0 * nu) * p * l * depth * depth / (24.0 * e * i));
    assert!((want - beam).abs() < 1e-12 * want.abs(), "{want} {beam}");
    let tips = cantilever(l, depth, 4, &exact, &traction);
    let errors: Vec<f64> = tips.iter().map(|t| ((t - want) / want).abs()).collect();
    for w in errors.windows(2) {
        // quadratic elements: displacement error O(h^3) or better
        let rate = (w[0] / w[1]).log2();
        assert!(rate > 2.5 || w[1] < 1e-9, "errors {errors:?}");
    }
    assert!(errors[3] < 1e-6, "{errors:?}");
}

#[test]
fn a_cantilever_under_an_end_moment_is_exact_pure_bending() {
    let (l, depth, moment): (f64, f64, f64) = (0.05, 0.01, 20.0);
    let (e, nu) = (STEEL.youngs_modulus, STEEL.poisson_ratio);
    let i = depth.powi(3) / 12.0;
    // sigma_xx = -M y / I; u = -M x y / (E I), v = M (x^2 + nu y^2) / (2 E I)
    let exact = move |p: [f64; 2]| {
        [
            -moment * p[0] * p[1] / (e * i),
            moment * (p[0] * p[0] + nu * p[1] * p[1]) / (2.0 * e * i),
        ]
    };
    let traction = move |p: [f64; 2]| [-moment * p[1] / i, 0.0];
    let tips = cantilever(l, depth, 2, &exact, &traction);
    let want = exact([l, 0.0])[1];
    for t in tips {
        // quadratic fields are in the elements' space: exact to rounding
        assert!(((t - want) / want).abs() < 1e-9, "{t} against {want}");
    }
}

#[test]
fn kirschs_hole_concentrates_the_stress_three_times() {
    // a quarter of a square plate, 10 hole radii wide, the exact Kirsch tractions on its
    // outer edges, symmetry on the axes
    let (a, b, s): (f64, f64, f64) = (0.002, 0.02, 1e6);
    let domain = Domain {
        loops: vec![vec![
            Edge::Line {
                a: [a, 0.0],
                b: [b, 0.0],
            },
            Edge::Line {
                a: [b, 0.0],
                b: [b, b],
            },
            Edge::Line {
                a: [b, b],
                b: [0.0, b],
            },
            Edge::Line {
                a: [0.0, b],
                b: [0.0, a],
            },
            Edge::Arc {
                centre: [0.0, 0.0],
                radius: a,
                start: std::f64::consts::FRAC_PI_2,
                sweep: -std::f64::consts::FRAC_PI_2,
            },
        ]],
        faces: Vec::new(),
        hinges: Vec::new(),
    };
    let kirsch = move |p: [f64; 2]| {
        let (r, th) = (p[0].hypot(p[1]), p[1].atan2(p[0]));
        let (a2, a4) = (a * a / (r * r), a.powi(4) / r.powi(4));
        let srr = s / 2.0 * (1.0 - a2) + s / 2.0 * (1.0 - 4.0 * a2 + 3.0 * a4) * (2.0 * th).cos();
        let stt = s / 2.0 * (1.0 + a2) - s / 2.0 * (1.0 + 3.0 * a4) * (2.0 * th).cos();
        let srt = -s / 2.0 * (1.0 + 2.0 * a2 - 3.0 * a4) * (2.0 * th).sin();
        let (c, sn) = (th.cos(), th.sin());
        [
            srr * c * c + stt * sn * sn - 2.0 * srt * sn * c,
            srr * sn * sn + stt * c * c + 2.0 * srt * sn * c,
            (srr - stt) * sn * c + srt * (c * c - sn * sn),
        ]
    };
    let size = |p: [f64; 2]| (0.6 * a + 0.3 * (p[0].hypot(p[1]) - a)).min(0.3 * b);
    let mut m = mesh(&domain, &size, 0.3 * b).unwrap();
    let mut peaks = Vec::new();
    for _ in 0..3 {
        let mut fixed = vec![false; 2 * m.nodes.len()];
        for (n, p) in m.nodes.iter().enumerate() {
            if p[0].abs() < 1e-12 {
                fixed[2 * n] = true;
            }
            if p[1].abs() < 1e-12 {
                fixed[2 * n + 1] = true;
            }
        }
        let mut f = loads::traction_forces(&m, &m.edges_on([b, 0.0], [b, b], 1e-12), 1.0, |p| {
            let t = kirsch(p);
            [t[0], t[2]]
        });
        let g = loads::traction_forces(&m, &m.edges_on([b, b], [0.0, b], 1e-12), 1.0, |p| {
            let t = kirsch(p);
            [t[2], t[1]]
        });
        f.iter_mut().zip(&g).for_each(|(x, y)| *x += y);
        let zero = vec![0.0; f.len()];
        let u = solve_static(
            &m,
            &STEEL,
            1.0,
            Idealization::PlaneStress,
            &fixed,
            &zero,
            &[f],
        )
        .unwrap()
        .remove(0);
        let d = STEEL.d_matrix(Idealization::PlaneStress);
        let st = stress::nodal_stresses(&m, &d, &u);
        let top = m
            .nodes
            .iter()
            .position(|p| p[0].abs() < 1e-12 && (p[1] - a).abs() < 1e-12)
            .unwrap();
        peaks.push(st[top][0] / s);
        m = m.refined(&domain);
    }
    assert!((peaks[2] - 3.0).abs() < 0.02 * 3.0, "{peaks:?}");
    // and the error falls as the mesh is refined
    assert!((peaks[2] - 3.0).abs() < (peaks[0] - 3.0).abs(), "{peaks:?}");
}

#[test]
fn a_slender_cantilevers_first_frequency_is_euler_bernoullis() {
    let (l, depth, width): (f64, f64, f64) = (0.2, 0.005, 0.01);
    let domain = Domain::rectangle(0.0, -depth / 2.0, l, depth / 2.0);
    let m = mesh(&domain, &|_| depth / 2.0, depth / 2.0)
        .unwrap()
        .refined(&domain);
    let mut fixed = vec![false; 2 * m.nodes.len()];
    for n in m.nodes_on([0.0, -depth / 2.0], [0.0, depth / 2.0], 1e-12) {
        fixed[2 * n] = true;
        fixed[2 * n + 1] = true;
    }
    let pattern = Pattern::new(&m, &fixed).unwrap();
    let k = pattern
        .stiffness(&m, &STEEL, width, Idealization::PlaneStress)
        .unwrap();
    let mass = pattern.mass(&m, &STEEL, width).unwrap();
    let modes = modal::lowest_modes(&pattern.factor(&k).unwrap(), &mass, 3, 1e-10, None).unwrap();
    // (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4)); slender (L / D = 40): shear and rotary
    // inertia lower it by about (D / L)^2, 0.1 %
    let (i, a) = (width * depth.powi(3) / 12.0, width * depth);
    let beta = 1.875_104_068_711_961;
    let euler = beta * beta / std::f64::consts::TAU
        * (STEEL.youngs_modulus * i / (STEEL.density * a * l.powi(4))).sqrt();
    let f = modes[0].frequency;
    assert!(
        f < euler && (euler - f) / euler < 0.005,
        "{f} against {euler}"
    );
    // the second bending mode: 4.6941 / 1.8751 squared times the first
    let ratio = (4.694_091_132_974_175f64 / beta).powi(2);
    assert!(
        (modes[1].frequency / f - ratio).abs() / ratio < 0.01,
        "{:?}",
        modes.iter().map(|m| m.frequency).collect::<Vec<_>>()
    );
}
