//! The hinge kinds: closed forms against the numerical integration of their profiles,
//! their limits, the bridge's exact gradients with notch hinges, a mixed bridge against the
//! independent linear system, the problem file's per-hinge kinds and checks, the part's
//! notches measured on its outline, `flexopt hinge`, and the README's accuracy table.

use crate::common;

use std::path::Path;

use common::{flexopt, flexopt_ok, rng, DEG, MM};
use flexopt::model::bridge::{Bridge, BridgeSettings, QuarterBridge};
use flexopt::model::build_part;
use flexopt::model::hinge::{Compliance, HingeKind};
use flexopt::model::material::Material;
use flexopt::model::reference::bridge_matrix;
use flexopt::model::Model;
use flexopt::problem::Problem;
use rand::Rng;

const WIDTH: f64 = 10e-3;

fn worst(a: &Compliance<f64>, b: &Compliance<f64>) -> f64 {
    [
        (a.c11, b.c11),
        (a.c22, b.c22),
        (a.c23, b.c23),
        (a.c33, b.c33),
    ]
    .iter()
    .map(|(x, y)| ((x - y) / y).abs())
    .fold(0.0, f64::max)
}

/// Each kind's dimensions over the accuracy table's grid and beyond it.
fn grid() -> Vec<(HingeKind, Vec<f64>)> {
    let mut g = Vec::new();
    for tr in [0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 20.0] {
        g.push((HingeKind::Circular, vec![1.0 * MM, tr * MM]));
    }
    for ba in [0.1, 0.25, 0.5, 1.0, 2.0, 4.0] {
        for tb in [0.05, 0.2, 1.0, 10.0] {
            let b = 2.0 * ba * MM;
            g.push((HingeKind::Elliptical, vec![2.0 * MM, b, tb * b]));
        }
    }
    for rl in [0.01, 0.025, 0.05, 0.1, 0.25, 0.4, 0.5] {
        for tl in [0.02, 0.1, 0.3] {
            g.push((
                HingeKind::CornerFilleted,
                vec![4.0 * MM, tl * 4.0 * MM, rl * 4.0 * MM],
            ));
        }
    }
    g
}

#[test]
fn the_closed_forms_are_the_exact_integrals_of_their_profiles() {
    // Castigliano's integrals over the profile, in closed form and by adaptive quadrature:
    // the same beam model, so they agree to rounding (the closed forms claim to be exact)
    let m = Material::al7075_t6();
    for (kind, dims) in grid() {
        let c = kind.compliance(&dims, WIDTH, &m);
        let n = kind.compliance_numerical(&dims, WIDTH, &m);
        assert!(
            worst(&c, &n) < 1e-11,
            "{kind:?} {dims:?}: {c:?} against {n:?}"
        );
    }
}

#[test]
fn the_notches_reduce_to_the_strip_and_to_each_other() {
    let m = Material::al7075_t6();
    let strip = |l: f64, t: f64| HingeKind::Strip.compliance(&[l, t], WIDTH, &m);
    // an elliptical notch flattening (b -> 0) is a strip of its length 2a
    for b in [1e-4, 1e-6] {
        let (a, t) = (2.0 * MM, 0.4 * MM);
        let e = HingeKind::Elliptical.compliance(&[a, b * t, t], WIDTH, &m);
        assert!(worst(&e, &strip(2.0 * a, t)) < 10.0 * b, "b = {b} t: {e:?}");
    }
    // a corner-filleted leaf's fillets vanishing (r -> 0): a strip of its length
    for r in [1e-4, 1e-6] {
        let (l, t) = (4.0 * MM, 0.4 * MM);
        let c = HingeKind::CornerFilleted.compliance(&[l, t, r * t], WIDTH, &m);
        assert!(worst(&c, &strip(l, t)) < 10.0 * r, "r = {r} t: {c:?}");
    }
    // an elliptical notch with a = b is the circular one; fillets meeting in the middle
    // (2 r = l) too
    for (r, t) in [(1.0 * MM, 0.1 * MM), (0.5 * MM, 0.8 * MM)] {
        let c = HingeKind::Circular.compliance(&[r, t], WIDTH, &m);
        let e = HingeKind::Elliptical.compliance(&[r, r, t], WIDTH, &m);
        let f = HingeKind::CornerFilleted.compliance(&[2.0 * r, t, r], WIDTH, &m);
        assert!(
            worst(&c, &e) < 1e-13 && worst(&c, &f) < 1e-12,
            "{c:?} {e:?} {f:?}"
        );
    }
    // and the circular notch's rotational compliance tends to Paros and Weisbord's
    // simplified 9 pi sqrt(r) / (2 E w t^(5/2)) as t / r -> 0
    let (r, t) = (1.0 * MM, 1e-4 * MM);
    let c = HingeKind::Circular.compliance(&[r, t], WIDTH, &m);
    let pw = 9.0 * std::f64::consts::PI * r.sqrt() / (2.0 * m.youngs_modulus * WIDTH * t.powf(2.5));
    assert!(((pw - c.c33) / c.c33).abs() < 1e-3, "{pw} {}", c.c33);
}

fn settings(b: HingeKind, d: HingeKind) -> BridgeSettings {
    let mut s = common::wei2017_settings();
    s.hinge_b = b;
    s.hinge_d = d;
    s
}

/// A random design of the bridge with hinge kinds `b` and `d`: lengths and thicknesses of
/// Table 1's sizes, notches from shallow to deep.
fn random(model: &Bridge, r: &mut impl Rng) -> Vec<f64> {
    let params = model.parameters();
    params
        .iter()
        .map(|p| match (p.dimension, p.name.as_ref()) {
            (flexopt::model::Dimension::Angle, _) => r.random_range(-30.0..30.0) * DEG,
            (_, n) if n.starts_with('t') => r.random_range(0.3..1.5) * MM,
            (_, n) if n.starts_with('r') || n.starts_with('b') => r.random_range(0.3..2.0) * MM,
            _ => r.random_range(4.0..12.0) * MM,
        })
        .collect()
}

#[test]
fn every_bridge_output_has_exact_gradients_with_notch_hinges() {
    let kinds = [
        HingeKind::Circular,
        HingeKind::Elliptical,
        HingeKind::CornerFilleted,
    ];
    let mut r = rng(13);
    let mut checked = 0;
    for k in 0..1000 {
        let (b, d) = (kinds[k % 3], kinds[(k / 3) % 3]);
        let model = Bridge::new(settings(b, d));
        let x = random(&model, &mut r);
        if model.domain_error(&x).is_some() {
            continue;
        }
        checked += 1;
        let wanted = model.available_outputs();
        let n = x.len();
        let mut out = vec![0.0; wanted.len()];
        let mut jac = vec![0.0; wanted.len() * n];
        model.evaluate_with_gradient(&x, &wanted, &mut out, &mut jac);
        for j in 0..n {
            // five-point differences, the step a millionth of the parameter
            let h = 1e-6 * x[j].abs();
            let at = |s: f64| {
                let mut y = x.clone();
                y[j] += s * h;
                let mut o = vec![0.0; wanted.len()];
                Model::evaluate(&model, &y, &wanted, &mut o);
                o
            };
            let (m2, m1, p1, p2) = (at(-2.0), at(-1.0), at(1.0), at(2.0));
            for (i, &w) in wanted.iter().enumerate() {
                let fd = (m2[i] - 8.0 * m1[i] + 8.0 * p1[i] - p2[i]) / (12.0 * h);
                let g = jac[i * n + j];
                // against the output's own size over the parameter's: a derivative near zero
                // is measured absolutely there
                let scale = g.abs().max(out[i].abs() / x[j].abs());
                assert!(
                    (fd - g).abs() <= 1e-6 * scale,
                    "{:?}/{:?} {} at {x:?}: d/d{} exact {g:e}, differences {fd:e}",
                    b,
                    d,
                    model.outputs()[w].name,
                    model.parameters()[j].name
                );
            }
        }
    }
    assert!(checked > 900, "{checked} designs checked");
}

#[test]
fn a_bridge_with_two_kinds_passes_the_linear_system_check() {
    let mut r = rng(7);
    for (b, d) in [
        (HingeKind::Circular, HingeKind::Strip),
        (HingeKind::Strip, HingeKind::Elliptical),
        (HingeKind::CornerFilleted, HingeKind::Circular),
    ] {
        let model = Bridge::new(settings(b, d));
        for _ in 0..500 {
            let x = random(&model, &mut r);
            let g = model.geometry(&x);
            let s = &model.settings;
            let q = QuarterBridge::new(&g, s.width, &s.material);
            let a = [[q.a11(), q.a12()], [q.a21(), q.a22()]];
            let m = bridge_matrix::coefficients(&g, s.width, &s.material);
            let cross = (a[0][0] * a[1][1].abs()).sqrt();
            for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                let scale = if i == j { m[(i, j)].abs() } else { cross };
                assert!(
                    (a[i][j] - m[(i, j)]).abs() < 1e-10 * scale,
                    "{b:?}/{d:?} a{i}{j}"
                );
            }
        }
    }
}

fn problem(edit: impl Fn(String) -> String) -> Result<Problem, flexopt::problem::ProblemError> {
    let text = std::fs::read_to_string("problems/bridge_circular.toml").unwrap();
    Problem::parse(Path::new("notch.toml"), &edit(text))
}

#[test]
fn problem_files_name_each_hinges_kind_and_check_its_dimensions() {
    // a strip at d beside the circular notch at b: d's dimensions are a strip's
    let p = problem(|t| {
        (t + "\n[hinge.d]\nkind = \"strip\"\n").replace(
            "name = \"r4\"\nunit = \"mm\"\nlower = 0.25\nupper = 10",
            "name = \"l4\"\nunit = \"mm\"\nlower = 0.5\nupper = 20",
        )
    })
    .unwrap();
    let names: Vec<&str> = p
        .model()
        .parameters()
        .iter()
        .map(|q| q.name.as_ref())
        .collect();
    assert_eq!(
        names,
        ["r2", "delta2", "t2", "l3", "delta3", "l4", "delta4", "t4"]
    );
    // [hinges.d] says the same as [hinge.d]; both at once is an error naming the table
    let strip_d = |t: String| {
        t.replace(
            "name = \"r4\"\nunit = \"mm\"\nlower = 0.25\nupper = 10",
            "name = \"l4\"\nunit = \"mm\"\nlower = 0.5\nupper = 20",
        )
    };
    let q = problem(|t| strip_d(t + "\n[hinges.d]\nkind = \"strip\"\n")).unwrap();
    let names_q: Vec<&str> = q
        .model()
        .parameters()
        .iter()
        .map(|q| q.name.as_ref())
        .collect();
    assert_eq!(names_q, names);
    let e =
        problem(|t| strip_d(t + "\n[hinges.d]\nkind = \"strip\"\n\n[hinge.d]\nkind = \"strip\"\n"))
            .unwrap_err();
    assert_eq!(e.key, "hinges.d");
    assert!(e.to_string().contains("given twice"), "{e}");
    // an unknown kind, named with its key
    let e = problem(|t| t.replace("kind = \"circular\"", "kind = \"hexagonal\"")).unwrap_err();
    assert_eq!(e.key, "hinge.kind");
    assert!(e.to_string().contains("\"hexagonal\"") && e.to_string().contains("corner-filleted"));
    // a circular notch's dimensions are r and t: a strip's l is not one of them
    let e = problem(|t| t.replace("name = \"r2\"", "name = \"l2\"")).unwrap_err();
    assert!(e.to_string().contains("\"l2\" is not a parameter"), "{e}");
    // a corner-filleted leaf whose fillets may grow past half its length
    let filleted = |r_upper: &str| {
        problem(move |t| {
            t.replace("kind = \"circular\"", "kind = \"corner-filleted\"")
                .replace("name = \"r2\"\nunit = \"mm\"\nlower = 0.25\nupper = 10", "name = \"l2\"\nunit = \"mm\"\nlower = 2\nupper = 20")
                .replace("name = \"r4\"\nunit = \"mm\"\nlower = 0.25\nupper = 10", "name = \"l4\"\nunit = \"mm\"\nlower = 2\nupper = 20")
                + &format!(
                    "\n[[variables]]\nname = \"r2\"\nunit = \"mm\"\nlower = 0.1\nupper = {r_upper}\n\
                     \n[[variables]]\nname = \"r4\"\nunit = \"mm\"\nvalue = 0.5\n"
                )
        })
    };
    let e = filleted("1.5").unwrap_err();
    assert!(
        e.key.starts_with("variables[") && e.key.ends_with("].upper"),
        "{}",
        e.key
    );
    assert!(
        e.to_string().contains("a fillet longer than half the leaf"),
        "{e}"
    );
    assert!(filleted("1").is_ok());
}

#[test]
fn the_parts_notches_are_true_arcs_of_the_designs_sizes() {
    let model = Bridge::new(settings(HingeKind::Circular, HingeKind::Elliptical));
    let mut r = rng(3);
    let mut built = 0;
    for _ in 0..400 {
        let x = random(&model, &mut r);
        let Ok(part) = build_part(&model, &x) else {
            continue;
        };
        // in mm, as the tolerances below
        let part = part.in_mm();
        built += 1;
        for h in &part.hinges {
            // the least distance between the outline's arcs across the hinge's middle: its
            // least thickness
            let (s, e) = (h.start, h.end);
            let c = [0.5 * (s[0] + e[0]), 0.5 * (s[1] + e[1])];
            let len = (e[0] - s[0]).hypot(e[1] - s[1]);
            let n = [-(e[1] - s[1]) / len, (e[0] - s[0]) / len];
            let mut sides = Vec::new();
            for l in &part.loops {
                let k = l.vertices.len();
                for i in 0..k {
                    if let Some(arc) = flexopt::part::outline::Arc::from_bulge(
                        l.vertices[i],
                        l.vertices[(i + 1) % k],
                    ) {
                        // the arc's point on the line through the middle across the hinge
                        let d = (c[0] - arc.centre[0]) * n[0] + (c[1] - arc.centre[1]) * n[1];
                        let along = (c[0] - arc.centre[0]) * n[1] - (c[1] - arc.centre[1]) * n[0];
                        if along.abs() < 1e-9 && (d.abs() - arc.radius).abs() < 1.5 * h.root {
                            sides.push(d - d.signum() * arc.radius);
                        }
                    }
                }
            }
            if h.kind == "circular" {
                assert_eq!(sides.len(), 2, "{}: {sides:?}", h.name);
                let t = (sides[0] - sides[1]).abs();
                assert!(
                    (t - h.thickness).abs() < 1e-9,
                    "{}: {t} against {}",
                    h.name,
                    h.thickness
                );
            }
        }
    }
    assert!(built > 100, "{built} parts");
    let _ = MM;
}

#[test]
fn the_hinge_calculator_prints_one_hinge_and_refuses_what_is_not_one() {
    let out = flexopt_ok(&[
        "hinge", "--kind", "circular", "--r", "1", "--t", "0.4", "--width", "10",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let m = Material::al7075_t6();
    let c = HingeKind::Circular.compliance(&[1.0 * MM, 0.4 * MM], WIDTH, &m);
    assert_eq!(json["compliance"]["c33"].as_f64().unwrap(), c.c33);
    assert!((json["stiffness"]["k33"].as_f64().unwrap() - 1.0 / c.c33).abs() < 1e-9 / c.c33);
    // the rotation at which the thinnest section reaches a third of 505 MPa, the notch's
    // concentration (1 + t / 2 r)^0.45 included
    let kt = (1.0f64 + 0.4 / 2.0).powf(0.45);
    assert!((json["stress_concentration"].as_f64().unwrap() - kt).abs() < 1e-12);
    let moment = 505e6 / 3.0 * WIDTH * (0.4 * MM).powi(2) / 6.0 / kt;
    assert!((json["max_rotation"].as_f64().unwrap() - c.c33 * moment).abs() < 1e-12);
    for (args, words) in [
        (
            vec!["--kind", "circular", "--r", "1", "--width", "10"],
            "--t",
        ),
        (
            vec![
                "--kind", "circular", "--r", "1", "--t", "0.4", "--l", "2", "--width", "10",
            ],
            "no such dimension",
        ),
        (
            vec!["--kind", "hexagonal", "--width", "10"],
            // the choices come from the hinge library's own list
            "[possible values: strip, circular, elliptical, corner-filleted]",
        ),
        (
            vec![
                "--kind",
                "corner-filleted",
                "--l",
                "2",
                "--t",
                "0.4",
                "--r",
                "1.5",
                "--width",
                "10",
            ],
            "half the leaf",
        ),
        (
            vec!["--kind", "strip", "--l", "2", "--t=-1", "--width", "10"],
            "positive",
        ),
    ] {
        let out = flexopt(&[&["hinge"][..], &args].concat());
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(words), "{words:?} not in {err}");
    }
}

#[test]
fn the_readme_states_the_regenerated_accuracy_table() {
    // results/hinges/accuracy.md is written by `cargo run --release --example
    // hinge_accuracy` (scripts/regenerate.sh, checked byte for byte in CI)
    let table = std::fs::read_to_string("results/hinges/accuracy.md").unwrap();
    let readme = std::fs::read_to_string("README.md").unwrap();
    assert!(
        readme.contains(table.trim()),
        "README.md does not show results/hinges/accuracy.md"
    );
}

#[test]
fn the_single_hinge_fe_agrees_with_beam_theory_where_it_holds_and_with_the_concentration_fits() {
    use flexopt::fe::hinge::single_hinge;
    use flexopt::fe::{Elastic, Idealization};
    let m = Material::al7075_t6();
    let e = Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
        density: m.density,
    };
    let cases: [(HingeKind, Vec<f64>); 4] = [
        (HingeKind::Strip, vec![8.0 * MM, 0.4 * MM]),
        (HingeKind::Circular, vec![1.0 * MM, 0.5 * MM]),
        (HingeKind::Elliptical, vec![2.0 * MM, 4.0 * MM, 0.8 * MM]),
        (
            HingeKind::CornerFilleted,
            vec![4.0 * MM, 0.4 * MM, 0.2 * MM],
        ),
    ];
    for (kind, dims) in cases {
        let fe = single_hinge(kind, &dims, WIDTH, &e, Idealization::PlaneStress).unwrap();
        // Maxwell-Betti: the slope per force is the deflection per moment
        let (c23, c32) = (fe.c23.value, fe.c32.value);
        assert!(
            ((c23 - c32) / c23).abs() < 2e-3,
            "{kind:?}: c23 {c23} c32 {c32}"
        );
        if kind == HingeKind::Strip {
            // a slender strip (l/t = 20) is a beam: Eq. 2 within half a per cent
            let c = kind.compliance(&dims, WIDTH, &m);
            assert!(
                worst(&c, &fe.compliance()) < 5e-3,
                "{:?} vs {:?}",
                c,
                fe.compliance()
            );
        } else {
            // each notch's fit within 4 % of the FE's peak stress
            let (formula, measured) = (kind.stress_concentration(&dims), fe.concentration.value);
            assert!(
                (formula / measured - 1.0).abs() < 0.04,
                "{kind:?}: K_t {formula} by its formula, {measured} by FE"
            );
            assert!(measured > 1.05, "{kind:?}: {measured}");
        }
    }
}
