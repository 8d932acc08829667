//! The shipped flexure networks (problems/*_network.toml, issue 25) against exact answers:
//! the rhombus against paper 004's rhombic closed form (Eq. 25), the folded double
//! parallelogram guide and a single parallelogram against beam theory's guided leaves, the
//! lever against its statics by hand; each with values and gradients taken on a second path
//! (the closed forms over dual numbers), and every output's gradient against central
//! differences.

use std::path::Path;

use rand::Rng;

use crate::common::{rel, rng};
use flexopt::model::hinge::{Compliance, Hinge, HingeKind};
use flexopt::model::material::Material;
use flexopt::model::reference::closed_forms::{rhombic, rhombic_general};
use flexopt::model::scalar::{Jet, Scalar};
use flexopt::model::Model;
use flexopt::problem::Problem;

const WIDTH: f64 = 0.01;

fn load(file: &str) -> Problem {
    Problem::load(Path::new(file)).unwrap()
}

fn al7075() -> Material {
    Material::al7075_t6()
}

/// The named outputs' values and gradients (row by row) at `x`.
fn outputs(m: &dyn Model, x: &[f64], names: &[&str]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let wanted: Vec<usize> = names.iter().map(|n| m.output_index(n).unwrap()).collect();
    let n = x.len();
    let (mut v, mut jac) = (vec![0.0; names.len()], vec![0.0; names.len() * n]);
    m.evaluate_with_gradient(x, &wanted, &mut v, &mut jac);
    (v, jac.chunks(n).map(|r| r.to_vec()).collect())
}

/// A design drawn uniformly within `bounds` (SI).
fn draw(r: &mut impl Rng, bounds: &[(f64, f64)]) -> Vec<f64> {
    bounds
        .iter()
        .map(|&(lo, hi)| if hi > lo { r.random_range(lo..hi) } else { lo })
        .collect()
}

/// The worst relative difference of a value and of a gradient (against the gradient's
/// largest entry) between the network's output and a closed form's dual number.
fn compare<const N: usize>(worst: &mut [f64; 2], value: f64, gradient: &[f64], exact: Jet<N>) {
    worst[0] = worst[0].max(rel(value, exact.re, 1e-300));
    let scale = exact.grad.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    for (g, e) in gradient.iter().zip(exact.grad) {
        worst[1] = worst[1].max((g - e).abs() / scale.max(1e-300));
    }
}

fn jets<const N: usize>(x: &[f64]) -> [Jet<N>; N] {
    std::array::from_fn(|i| Jet::variable(x[i], i))
}

/// The rhombus (one leaf from the input block to the output block, mirrored about both
/// axes) amplifies as paper 004's rhombic limit of Eq. 9 for the library's strip, value and
/// gradient, and as Eq. 25 as printed within the strip's shear share: Eq. 25 uses
/// `c33 = 3 c22 / L^2` and `c23 = 6 c22 / (4 L)`, which hold for the bending part of c22
/// only, and the library's strip (paper 004 Eq. 2) adds `L / (G w t)`.
#[test]
fn the_rhombus_amplifies_as_paper_004s_rhombic_closed_form() {
    let p = load("problems/rhombus_network.toml");
    let m = p.model();
    let mut r = rng(250);
    let (mut worst, mut worst_printed) = ([0.0f64; 2], 0.0f64);
    // the file fixes t at 0.4 mm; the model takes any
    let bounds = [
        (5e-3, 20e-3),
        (0.5f64.to_radians(), 45f64.to_radians()),
        (0.4e-3, 2e-3),
    ];
    for _ in 0..25 {
        let x = draw(&mut r, &bounds);
        let (v, g) = outputs(m, &x, &["amplification"]);
        let [l, delta, t] = jets::<3>(&x);
        let c: Compliance<Jet<3>> = Hinge::strip(l, t).compliance(WIDTH, &al7075());
        compare(&mut worst, v[0], &g[0], rhombic_general(&c, delta));
        let printed = rhombic(&c, delta).re;
        let shear_share = (1.0 + al7075().poisson_ratio) * (x[2] / x[0]).powi(2) / 2.0;
        worst_printed = worst_printed.max(rel(v[0], printed, 1e-300) / shear_share);
    }
    eprintln!(
        "rhombus: Eq. 9's rhombic limit {worst:?}; Eq. 25 within {worst_printed:.3} shear shares"
    );
    assert!(worst[0] < 1e-12 && worst[1] < 1e-10, "{worst:?}");
    assert!(worst_printed < 2.0, "{worst_printed}");
}

/// A leaf guided at its tip (no turn there) is a Timoshenko beam's guided cantilever:
/// compliance `L^3 / (E w t^3) + L / (G w t)` (Timoshenko and Gere, "Mechanics of
/// Materials", 1972, Sec. 9.10 for the shear part, with paper 004 Eq. 2's shear coefficient
/// 1). Two leaves side by side halve it; the folded guide's two parallelograms in series
/// double it again. Loaded on the line through the leaves' mid-lengths no leaf's end turns,
/// whatever the leaves' axial stiffness, so the guide's stiffness is exactly that; each leaf's
/// end moment is half its shear times L, so its stress `3 F L / (2 w t^2)` with `F = k X`.
/// Along the leaves (the first output) the four leaves stretch, two in parallel twice in
/// series: `E w t / L`, and the stage moves not at all across them.
#[test]
fn the_folded_guide_is_beam_theorys_guided_leaves() {
    let p = load("problems/guide_network.toml");
    let m = p.model();
    let mat = al7075();
    let (e, g) = (mat.youngs_modulus, mat.shear_modulus());
    let stroke = 0.5e-3;
    let names = [
        "k_in",
        "k_out",
        "stress_max",
        "amplification",
        "amplification_stage",
        "rotation_inner_top",
    ];
    let mut r = rng(251);
    let bounds = [(4e-3, 40e-3), (0.3e-3, 1.5e-3), (10e-3, 30e-3)];
    let (mut worst, mut worst_plain) = ([0.0f64; 2], 0.0f64);
    for _ in 0..25 {
        let x = draw(&mut r, &bounds);
        let (v, grad) = outputs(m, &x, &names);
        let [l, t, _] = jets::<3>(&x);
        let guided = l * l * l / (t * t * t * (e * WIDTH)) + l / (t * (g * WIDTH));
        let k = guided.recip();
        compare(&mut worst, v[0], &grad[0], k);
        compare(&mut worst, v[1], &grad[1], t * (e * WIDTH) / l);
        compare(
            &mut worst,
            v[2],
            &grad[2],
            k * stroke * l * 1.5 / (t * t * WIDTH),
        );
        worst_plain = worst_plain.max(v[3].abs()).max((v[4] - 1.0).abs());
        worst_plain = worst_plain.max(v[5].abs());
    }
    eprintln!("guide: beam theory {worst:?}; no parasitic motion or turn to {worst_plain:e}");
    assert!(worst[0] < 1e-12 && worst[1] < 1e-10, "{worst:?}");
    assert!(worst_plain < 1e-12, "{worst_plain:e}");
}

/// One parallelogram (two leaves of length `L`, `d` apart) loaded across at the leaves'
/// tips rather than their mid-length: the stage turns, held back by the leaves' axial
/// stiffness. Its stiffness by the direct stiffness method on the two leaves, each a
/// cantilever of stiffness `C^-1` (`C` the strip's tip compliances), with the stage turning
/// about the tips' midpoint: `k = 2/c - (2 b)^2 / (2 a + d^2 / (2 c11))` where
/// `[[c22, c23], [c23, c33]]^-1 = [[1/c, b], [b, a]]`. At `d -> inf` it tends to the guided
/// `2 / (c22 - c23^2 / c33)`.
#[test]
fn a_parallelogram_loaded_at_its_tips_turns_as_the_direct_stiffness_method_says() {
    let text = std::fs::read_to_string("problems/guide_network.toml").unwrap();
    let start = text.find("[[network.bodies]]").unwrap();
    let end = text.find("[actuator]").unwrap();
    let single = format!(
        "{}{}{}",
        &text[..start],
        r#"
[[network.bodies]]
name = "stage"
link = { from = ["L", "-d/2"], to = ["L", "d/2"], width = "3" }

[[network.hinges]]
name = "top"
kind = "strip"
from = "ground"
to = "stage"
start = ["0", "d/2"]
angle = "0"
l = "L"
t = "t"

[[network.hinges]]
name = "bottom"
kind = "strip"
from = "ground"
to = "stage"
start = ["0", "-d/2"]
angle = "0"
l = "L"
t = "t"

[network.input]
body = "stage"
at = ["L", "0"]
direction = ["0", "1"]

[[network.outputs]]
name = "corner"
body = "stage"
at = ["L + d", "0"]
direction = ["0", "1"]

"#,
        &text[end..]
    );
    let p = Problem::parse(Path::new("parallelogram.toml"), &single).unwrap();
    let m = p.model();
    let mut r = rng(252);
    let bounds = [(4e-3, 40e-3), (0.3e-3, 1.5e-3), (2e-3, 30e-3)];
    let mut worst = [0.0f64; 2];
    let mut turned = 0.0f64;
    for _ in 0..25 {
        let x = draw(&mut r, &bounds);
        let (v, grad) = outputs(m, &x, &["k_in"]);
        let [l, t, d] = jets::<3>(&x);
        let c = Hinge::strip(l, t).compliance(WIDTH, &al7075());
        let det = c.c22 * c.c33 - c.c23 * c.c23;
        let (kv, kvm, km) = (c.c33 / det, -c.c23 / det, c.c22 / det);
        let k = kv * 2.0 - (kvm * 2.0).powi(2) / (km * 2.0 + d * d / (c.c11 * 2.0));
        compare(&mut worst, v[0], &grad[0], k);
        turned = turned.max(1.0 - v[0] / ((c.c22 - c.c23 * c.c23 / c.c33).recip() * 2.0).re);
    }
    eprintln!("parallelogram at its tips: {worst:?}; softer than guided by up to {turned:e}");
    assert!(worst[0] < 1e-12 && worst[1] < 1e-10, "{worst:?}");
    assert!(
        turned > 1e-6,
        "the tips' load should turn the stage: {turned:e}"
    );
}

/// The lever turns on one notch below its pivot end, pushed along the notch's axis at `a`
/// and read at `arm`: the notch's end moves `c11 F` along the axis and turns `c33 F a`, so a
/// point at `p` moves `(c11 + c33 a p) F`, with the library's circular-notch compliances.
/// The port compliances `C_pq = c11 + c33 p q` give the amplification `C_ta / C_aa`, `k_in =
/// 1 / C_aa`, `k_out = 1 / C_tt` with the stack free, `1 / (C_tt - C_ta^2 / C_aa)` with it
/// held and `1 / (C_tt - C_ta^2 / (C_aa + 1 / k_a))` on its own stiffness `k_a`.
#[test]
fn the_lever_amplifies_as_its_statics_by_hand() {
    let p = load("problems/lever_network.toml");
    let m = p.model();
    let names = [
        "amplification",
        "k_in",
        "k_out",
        "k_out_blocked",
        "k_out_actuated",
    ];
    let k_a = 60e6;
    let mut r = rng(253);
    let bounds = [
        (0.5e-3, 3e-3),
        (0.3e-3, 1.5e-3),
        (2e-3, 15e-3),
        (20e-3, 60e-3),
    ];
    let mut worst = [[0.0f64; 2]; 5];
    for _ in 0..25 {
        let x = draw(&mut r, &bounds);
        let (v, grad) = outputs(m, &x, &names);
        let [radius, t, a, arm] = jets::<4>(&x);
        let c = Hinge::new(HingeKind::Circular, &[radius, t]).compliance(WIDTH, &al7075());
        let port = |p: Jet<4>, q: Jet<4>| c.c11 + c.c33 * p * q;
        let (caa, cta, ctt) = (port(a, a), port(arm, a), port(arm, arm));
        let exact = [
            cta / caa,
            caa.recip(),
            ctt.recip(),
            (ctt - cta * cta / caa).recip(),
            (ctt - cta * cta / (caa + 1.0 / k_a)).recip(),
        ];
        for (i, e) in exact.into_iter().enumerate() {
            compare(&mut worst[i], v[i], &grad[i], e);
        }
    }
    eprintln!("lever: statics by hand {worst:?}");
    // with the stack held or on its stiffness the tip's compliance is a difference,
    // `C_tt - C_ta^2 / C_aa`, that cancels all but a few parts in 1e4 of `C_tt`
    for (i, (w, name)) in worst.iter().zip(names).enumerate() {
        let tolerance = if i < 3 { 1e-12 } else { 1e-10 };
        assert!(w[0] < tolerance && w[1] < 1e-10, "{name}: {w:?}");
    }
}

/// The Scott-Russell mechanism in its guided form tends to its ideal pins' kinematics,
/// `cot(theta)` (the ends at `(2 l cos theta, 0)` and `(0, 2 l sin theta)`, the input pushed
/// towards the output's line; Howell, "Compliant Mechanisms", Wiley 2001, Sec. 5.3,
/// pseudo-rigid-body model), as its notches shrink about the joints (radius
/// `r`, web `r/2`) and its guides' leaves thin (their stretch against their bending): the
/// error falls at every step of both and ends below 1e-4. Without a crank the guides carry
/// the coupler's whole force, so the leaves' stretch leaves `(tg/g)^2`-small errors and the
/// leaves are thinned to 4 um, the notches to 1 um.
#[test]
fn the_scott_russell_mechanism_tends_to_its_pins_kinematics() {
    let p = load("problems/scott_russell_network.toml");
    let m = p.model();
    let mm = 1e-3;
    for (l, theta) in [
        (12.0 * mm, 10f64.to_radians()),
        (18.0 * mm, 4f64.to_radians()),
    ] {
        let ideal = 1.0 / theta.tan();
        let error = |r: f64, tg: f64| {
            let (v, _) = outputs(
                m,
                &[l, theta, r, r / 2.0, 15.0 * mm, tg],
                &["amplification"],
            );
            (v[0] / ideal - 1.0).abs()
        };
        let mut last = f64::INFINITY;
        for tg in [
            0.5, 0.25, 0.125, 0.0625, 0.03125, 0.015625, 0.0078125, 0.00390625,
        ]
        .map(|v| v * mm)
        {
            let mut along_r = f64::INFINITY;
            for r in [
                0.0625,
                0.03125,
                0.015625,
                0.0078125,
                0.00390625,
                0.001953125,
                0.0009765625,
            ]
            .map(|v| v * mm)
            {
                let e = error(r, tg);
                assert!(
                    e < along_r,
                    "l {l}, theta {theta}: {e} after {along_r} at r {r}"
                );
                along_r = e;
            }
            assert!(
                along_r < last,
                "l {l}, theta {theta}: {along_r} after {last} at tg {tg}"
            );
            last = along_r;
        }
        eprintln!("scott-russell at theta {theta}: {last:e} from cot(theta)");
        assert!(last < 1e-4, "{last}");
    }
}

/// The port compliances of a network are symmetric (Maxwell-Betti reciprocity: the input's
/// motion under a unit output load is the output's under a unit input load), so its
/// stiffnesses and amplification obey `1 / k_out_blocked = 1 / k_out - A^2 / k_in` and
/// `1 / k_out_actuated = 1 / k_out - A^2 k_a / (k_in (k_in + k_a))`, A the amplification,
/// for a network without mirror axes (whose ports' shares differ).
#[test]
fn the_shipped_networks_ports_are_reciprocal() {
    for (file, k_a) in [
        ("problems/lever_network.toml", 60e6),
        ("problems/scott_russell_network.toml", 60e6),
    ] {
        let p = load(file);
        let bounds: Vec<(f64, f64)> = p.variables.iter().map(|v| (v.lower, v.upper)).collect();
        let mut r = rng(270);
        let mut worst = 0.0f64;
        for _ in 0..25 {
            let x = draw(&mut r, &bounds);
            let names = [
                "amplification",
                "k_in",
                "k_out",
                "k_out_blocked",
                "k_out_actuated",
            ];
            let (v, _) = outputs(p.model(), &x, &names);
            let [a, k_in, k_out, blocked, actuated] = [v[0], v[1], v[2], v[3], v[4]];
            let held = 1.0 / k_out - a * a / k_in;
            let sprung = 1.0 / k_out - a * a * k_a / (k_in * (k_in + k_a));
            worst = worst.max(rel(1.0 / blocked, held, 1e-300));
            worst = worst.max(rel(1.0 / actuated, sprung, 1e-300));
        }
        eprintln!("{file}: reciprocity {worst:e}");
        assert!(worst < 1e-9, "{file}: {worst:e}");
    }
}

/// Every output of each shipped network has its central-difference gradient, at random
/// designs within the file's bounds (fixed variables at their values).
#[test]
fn every_shipped_networks_outputs_have_their_central_difference_gradients() {
    for (i, file) in [
        "problems/rhombus_network.toml",
        "problems/guide_network.toml",
        "problems/lever_network.toml",
        "problems/scott_russell_network.toml",
        "problems/bridge_lever_network.toml",
    ]
    .into_iter()
    .enumerate()
    {
        let p = load(file);
        let bounds: Vec<(f64, f64)> = p.variables.iter().map(|v| (v.lower, v.upper)).collect();
        let mut r = rng(260 + i as u64);
        let designs: Vec<Vec<f64>> = (0..25).map(|_| draw(&mut r, &bounds)).collect();
        // the guide's parasitic motion and its leaves' turns are zero and its stage's motion
        // is the input's; the two-stage amplifier's bridge arms do not turn (their ends are
        // the held upper block, the ground and the input block between them, which the
        // symmetric pair keeps from turning) and its span along x is its ground frame's
        // fixed reach, from the axis to its post: their gradients are rounding
        let constant: &[&str] = match i {
            1 => &[
                "amplification",
                "amplification_stage",
                "stroke_out",
                "blocked_force",
                "rotation_",
            ],
            4 => &["rotation_upper_arm", "rotation_lower_arm", "span_x"],
            _ => &[],
        };
        let (worst, kinks, checks) =
            worst_central_difference(p.model(), &designs, &bounds, constant);
        eprintln!("{file}: worst {worst:?}, {kinks} kinks in {checks}");
        assert!(
            checks > 0 && kinks * 50 < checks,
            "{file}: {kinks} kinks in {checks} checks"
        );
        assert!(worst.0 < 1e-6, "{file}: {worst:?}");
    }
}

/// The worst difference between each output's exact gradient and its central difference
/// over `designs`, scaled by the bounds' ranges (a fixed variable is not varied), skipping
/// the stencils across which a max has a kink (the one-sided slopes differ); the real and
/// dual paths' values must agree to 1e-10 too. The outputs named in `constant` (or starting with
/// an entry that ends in `_`) are left out.
/// Returns the worst, the kinks and the checks.
pub fn worst_central_difference(
    m: &dyn Model,
    designs: &[Vec<f64>],
    bounds: &[(f64, f64)],
    constant: &[&str],
) -> ((f64, String), usize, usize) {
    let all: Vec<usize> = m
        .available_outputs()
        .into_iter()
        .filter(|&i| {
            let name = &m.outputs()[i].name;
            !constant
                .iter()
                .any(|z| name == z || (z.ends_with('_') && name.starts_with(z)))
        })
        .collect();
    let (mo, n) = (all.len(), bounds.len());
    let ranges: Vec<f64> = bounds.iter().map(|(lo, hi)| hi - lo).collect();
    let mut worst = (0.0f64, String::new());
    let (mut checks, mut kinks) = (0, 0);
    for x in designs {
        let (mut v, mut jac) = (vec![0.0; mo], vec![0.0; mo * n]);
        m.evaluate_with_gradient(x, &all, &mut v, &mut jac);
        let mut plain = vec![0.0; mo];
        m.evaluate(x, &all, &mut plain);
        for ((a, b), &i) in v.iter().zip(&plain).zip(&all) {
            let name = &m.outputs()[i].name;
            assert!(
                rel(*a, *b, 1e-300) < 1e-10,
                "{name}: dual {a:e} vs real {b:e}"
            );
        }
        for j in (0..n).filter(|&j| ranges[j] > 0.0) {
            let h = 1e-6 * ranges[j];
            let at = |k: f64| {
                let mut y = x.clone();
                y[j] += k * h;
                let mut f = vec![0.0; mo];
                m.evaluate(&y, &all, &mut f);
                f
            };
            let (f1, f0, fm1) = (at(1.0), at(0.0), at(-1.0));
            for i in 0..mo {
                let scale = (0..n).fold(0.0f64, |s, k| s.max((jac[i * n + k] * ranges[k]).abs()));
                if scale == 0.0 {
                    continue;
                }
                checks += 1;
                let (right, left) = ((f1[i] - f0[i]) / h, (f0[i] - fm1[i]) / h);
                if (right - left).abs() * ranges[j] > 1e-3 * scale {
                    kinks += 1;
                    continue;
                }
                let fd = (f1[i] - fm1[i]) / (2.0 * h);
                let err = (fd - jac[i * n + j]).abs() * ranges[j] / scale;
                if err > worst.0 {
                    worst = (err, format!("d {} / d x{j}", m.outputs()[all[i]].name));
                }
            }
        }
    }
    (worst, kinks, checks)
}
