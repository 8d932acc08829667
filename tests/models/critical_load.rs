//! The critical load factor as an output (`nl_critical`, `[analysis] critical_up_to`) with
//! its exact gradient ([`flexopt::model::large::critical::by_design`]): Euler's loads of a
//! strip network pushed along its strip, clamped-free and clamped-pinned (the far end
//! on a roller), and their gradients against central differences and the closed forms'
//! derivatives; a shallow two-bar truss's limit point and its gradient against central
//! differences; and the cap where there is no critical point.

use std::f64::consts::PI;
use std::path::Path;

use flexopt::model::large::critical::by_design::critical_by_design;
use flexopt::model::large::critical::critical_load_factor;
use flexopt::model::large::solve::Options;
use flexopt::model::large::{Dof, Section, StructureOf};
use flexopt::model::material::Material;
use flexopt::model::scalar::Scalar;
use flexopt::problem::Problem;
use num_dual::Dual64;

const WIDTH: f64 = 10e-3;

/// A strip of length `L` and thickness `t` (mm, the variables) from the ground at the
/// origin along x to a body at its end, where the stack pushes it back along the strip
/// (its free stroke `stroke_um`, no preload, 50 N/um); the body held across the
/// strip where `pinned` says so (a support at the input's point, a roller).
fn column_text(stroke_um: f64, pinned: bool, analysis: &str) -> String {
    let support = if pinned {
        "[[network.supports]]\nbody = \"tip\"\nat = [\"L\", \"0\"]\ndirection = [\"0\", \"1\"]\n"
    } else {
        ""
    };
    format!(
        r#"
name = "column"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
parameters = [["L", "length"], ["t", "length"]]

[[network.bodies]]
name = "tip"
link = {{ from = ["L", "-1"], to = ["L", "1"], width = "1" }}

[[network.hinges]]
name = "column"
kind = "strip"
from = "ground"
to = "tip"
start = ["0", "0"]
angle = "0"
l = "L"
t = "t"

{support}
[network.input]
body = "tip"
at = ["L", "0"]
direction = ["-1", "0"]

[[network.outputs]]
name = "tip"
body = "tip"
at = ["L", "1"]
direction = ["1", "0"]

[actuator]
nominal_stroke = "{stroke_um} um"
preload = "0 N"
stiffness = "50 N/um"

[[variables]]
name = "L"
unit = "mm"
lower = 20
upper = 60

[[variables]]
name = "t"
unit = "mm"
lower = 0.03
upper = 0.1

[objective]
maximize = "amplification"

[analysis]
deflection = "large"
{analysis}
"#
    )
}

fn column(stroke_um: f64, pinned: bool, analysis: &str) -> Problem {
    let text = column_text(stroke_um, pinned, analysis);
    Problem::parse(Path::new("column.toml"), &text).unwrap()
}

/// The stack's force on the straight strip per unit load factor: the stack (`k_a`, its
/// free stroke its extension per unit factor) in series with the strip's axial stiffness
/// `E w t / L`.
fn force_per_factor(stroke: f64, l: f64, t: f64) -> f64 {
    let k_a = 50e6;
    let k_axial = Material::al7075_t6().youngs_modulus * WIDTH * t / l;
    k_a * k_axial / (k_a + k_axial) * stroke
}

/// The distance of the stack's anchor behind the input port (m): the stack is a strut
/// from there, so its force on the strip's end is directed through that fixed point.
const ANCHOR: f64 = 1.0;

/// The strip's critical load, `z^2 E I / L^2`: clamped-pinned (its far end held across,
/// free to turn and to slide along) the least positive root of `tan z = z`, 4.4934;
/// clamped-free under a force
/// directed through the stack's anchor at the distance `c` behind its end, the least root of
/// `tan z = z (1 + c / L)` (from `E I w'' = P (delta - w) + (P delta / c) (L - x)`, `w(0) =
/// w'(0) = 0`, `w(L) = delta`: Timoshenko and Gere, *Theory of Elastic Stability*, 2nd ed.,
/// 1961, sec. 2.2's clamped-free bar with the lateral force of a load through a fixed
/// point), which tends to Euler's `pi / 2` as `c` grows (3.1 % below it at `c / L = 25`).
fn euler(pinned: bool, l: f64, t: f64) -> f64 {
    let ei = Material::al7075_t6().youngs_modulus * WIDTH * t.powi(3) / 12.0;
    // the least root of `tan z = m z` on (1, pi / 2) or (pi, 3 pi / 2), by bisection
    let root = |m: f64, lo: f64, hi: f64| {
        let f = |z: f64| z.tan() - m * z;
        let (mut lo, mut hi) = (lo, hi);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let z = if pinned {
        root(1.0, PI + 1e-9, 1.5 * PI - 1e-12)
    } else {
        root(1.0 + ANCHOR / l, 1.0, PI / 2.0 - 1e-12)
    };
    z * z * ei / (l * l)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// `nl_critical` and its gradient at `x`.
fn critical_with_gradient(p: &Problem, x: &[f64]) -> (f64, Vec<f64>) {
    let m = &p.mechanism.physics;
    let i = m.output_index("nl_critical").unwrap();
    let (mut out, mut jac) = ([0.0], vec![0.0; x.len()]);
    m.evaluate_with_gradient(x, &[i], &mut out, &mut jac);
    (out[0], jac)
}

fn critical(p: &Problem, x: &[f64]) -> f64 {
    let m = &p.mechanism.physics;
    let mut out = [0.0];
    m.evaluate(x, &[m.output_index("nl_critical").unwrap()], &mut out);
    out[0]
}

/// Richardson's extrapolation of central differences of `f` along `j` at `x` (steps `h`
/// and `h / 2`: `(4 D(h/2) - D(h)) / 3`, its error of order `h^4`).
fn richardson(f: &impl Fn(&[f64]) -> f64, x: &[f64], j: usize, h: f64) -> f64 {
    let central = |h: f64| {
        let (mut up, mut down) = (x.to_vec(), x.to_vec());
        up[j] += h;
        down[j] -= h;
        (f(&up) - f(&down)) / (2.0 * h)
    };
    (4.0 * central(h / 2.0) - central(h)) / 3.0
}

/// Euler's loads from `nl_critical` times the stack's force per unit factor: the strip
/// clamped-free under the stack's force through its anchor ([`euler`], 3.1 % below `pi^2 E
/// I / (4 L^2)`), and clamped-pinned (its far end on a roller across it), `20.19 E I / L^2`. The strip is slender (`L / t
/// = 800`), so that its shear (`P / (G A)`, below 2e-5) and its axial strain (below 1e-5)
/// leave Euler's loads of the inextensible Euler-Bernoulli strip within 1e-4. A network
/// holds a body's rotation only with its sway, and a strip held so at the input would hold
/// the whole body (an output on it infinitely stiff): the clamped-guided strip is not among
/// the cases.
#[test]
fn euler_loads_from_nl_critical() {
    let (l, t) = (40e-3, 0.05e-3);
    let x = [l, t];
    for (pinned, stroke) in [(false, 0.0065e-6), (true, 0.05e-6)] {
        let exact = euler(pinned, l, t);
        let mut errors = Vec::new();
        for elements in [16, 64] {
            let p = column(stroke * 1e6, pinned, &format!("elements = {elements}"));
            let lambda = critical(&p, &x);
            assert!(lambda > 1.0 && lambda < 4.0, "{lambda}");
            let load = lambda * force_per_factor(stroke, l, t);
            errors.push(relative(load, exact));
            eprintln!(
                "pinned {pinned}: {elements} elements, lambda_c {lambda:.10}, load {load:.8e} \
                 against {exact:.8e} ({:.2e})",
                relative(load, exact)
            );
        }
        // past 16 elements both at the floor of the strip's shear and axial strain (P / (G A)
        // 7e-6 clamped-pinned), which Euler's loads leave out
        assert!(errors[1] <= 1e-4, "{pinned}: {errors:?}");
        assert!(
            errors[1] < errors[0] || errors[1] < 1e-5,
            "{pinned}: {errors:?}"
        );
    }
}

/// The gradient of `nl_critical` at Euler's bifurcation against Richardson's central
/// differences (steps 1e-2 of the parameter: the root carries the round-off of the lowest
/// eigenvalue over its rate along the path), and against the closed form's derivatives:
/// `lambda_c f = P_cr`, so `d(lambda_c f) = dP_cr` (to the closed form's own error, 1e-4).
#[test]
fn the_gradient_of_nl_critical_at_a_bifurcation() {
    let (l, t) = (40e-3, 0.05e-3);
    let x = [l, t];
    for (pinned, stroke) in [(false, 0.0065e-6), (true, 0.05e-6)] {
        let p = column(stroke * 1e6, pinned, "elements = 32");
        let (lambda, gradient) = critical_with_gradient(&p, &x);
        let f = |x: &[f64]| critical(&p, x);
        let mut worst = 0.0f64;
        for j in 0..2 {
            let fds = [2e-3, 1e-2].map(|h| richardson(&f, &x, j, h * x[j]));
            let fd = fds[1];
            let error = relative(gradient[j], fd);
            worst = worst.max(error);
            eprintln!(
                "pinned {pinned}: d lambda_c / d x{j} exact {:.12e} differences {:.12e} and {:.12e} ({error:.1e}, at 2e-3 {:.1e})",
                gradient[j],
                fds[0],
                fds[1],
                relative(gradient[j], fds[0])
            );
            assert!(error <= 3e-6, "{pinned} x{j}: {} against {fd}", gradient[j]);
        }
        // the closed form's derivatives: d(lambda f)/dx = f dlambda/dx + lambda df/dx
        let force = |x: &[f64]| force_per_factor(stroke, x[0], x[1]);
        let closed = |x: &[f64]| euler(pinned, x[0], x[1]);
        for j in 0..2 {
            let expected = richardson(&closed, &x, j, 1e-3 * x[j]);
            let df = richardson(&force, &x, j, 1e-4 * x[j]);
            let got = force(&x) * gradient[j] + lambda * df;
            assert!(
                relative(got, expected) <= 1e-3,
                "{pinned} x{j}: {got} against {expected}"
            );
        }
        eprintln!("pinned {pinned}: worst {worst:.1e}");
    }
}

/// A shallow two-bar truss (von Mises's): two bars of `E A`, `E I` pinned at `(-a, 0)` and
/// `(a, 0)`, joined rigidly at the apex `(0, h)` where a dead load pulls down, over a
/// design `p = (h, E A)` carried by `D`.
fn truss<D: Scalar>(h: D, ea: D) -> StructureOf<D> {
    let (a, ei) = (10e-3, 0.06);
    let mut s = StructureOf::<D>::default();
    let left = s.node(D::from(-a), D::from(0.0));
    let right = s.node(D::from(a), D::from(0.0));
    let apex = s.node(D::from(0.0), h);
    let section = Section { ea: ea.re(), ei };
    for end in [left, right] {
        let chain = s.flexure(end, apex, 4, |_| section);
        debug_assert_eq!(chain.len(), 5);
        s.hold(end, Dof::X);
        s.hold(end, Dof::Y);
    }
    // the design's E A carried by the local stiffnesses, which the dual scalar sees
    let l0 = |s: &StructureOf<D>, b: usize| {
        let (p, q) = (s.nodes[s.beams[b].a], s.nodes[s.beams[b].b]);
        ((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1])).sqrt()
    };
    for b in 0..s.beams.len() {
        let mut local = section.local(l0(&s, b));
        local.axial = ea / l0(&s, b);
        s.beams[b].local = Some(local);
    }
    s.load(apex, [D::from(0.0), D::from(-50.0), D::from(0.0)]);
    s
}

/// The truss's limit point: found (the tangent singular with the load doing work on its
/// null vector), and its gradient by the rise and the axial stiffness against Richardson's
/// central differences.
#[test]
fn a_limit_point_and_its_gradient() {
    // Newton held to 4 iterations a step: with more, a step past the limit can converge on
    // the snapped-through branch, stable again, and the search would pass the limit by
    let opts = Options {
        steps: 80,
        iterations: 4,
        ..Options::default()
    };
    let design = [0.4e-3, 5e6];
    let lambda_of = |x: &[f64]| {
        critical_load_factor(&truss(x[0], x[1]), 8.0, &opts)
            .unwrap()
            .lambda
    };
    let real = truss(design[0], design[1]);
    let critical = critical_load_factor(&real, 8.0, &opts).unwrap();
    assert!(
        critical.lambda > 0.5 && critical.lambda < 8.0,
        "{}",
        critical.lambda
    );
    for j in 0..2 {
        let seeded: Vec<Dual64> = (0..2)
            .map(|i| Dual64::new(design[i], f64::from(u8::from(i == j))))
            .collect();
        let dual = truss(seeded[0], seeded[1]);
        let exact = critical_by_design(&real, &dual, &critical).unwrap();
        assert_eq!(exact.re, critical.lambda);
        let fd = richardson(&lambda_of, &design, j, 1e-3 * design[j]);
        eprintln!(
            "limit point {:.12}: d/dp{j} exact {:.12e} differences {fd:.12e} ({:.1e})",
            critical.lambda,
            exact.eps,
            relative(exact.eps, fd)
        );
        assert!(
            relative(exact.eps, fd) <= 1e-6,
            "{} against {fd}",
            exact.eps
        );
    }
}

/// Without a critical point up to `critical_up_to`, `nl_critical` is `critical_up_to`
/// itself with a zero gradient.
#[test]
fn without_a_critical_point_nl_critical_is_its_cap() {
    let x = [40e-3, 0.05e-3];
    let p = column(0.002, false, "elements = 8\ncritical_up_to = 1.5");
    let (value, gradient) = critical_with_gradient(&p, &x);
    assert_eq!(value, 1.5);
    assert_eq!(gradient, vec![0.0, 0.0]);
}

/// The key refused out of its range, and without large deflection, with the key named.
#[test]
fn critical_up_to_is_refused_out_of_range() {
    for (analysis, key) in [
        ("critical_up_to = 1.0", "critical_up_to"),
        ("critical_up_to = 1000", "critical_up_to"),
    ] {
        let text = column_text(0.02, false, analysis);
        let err = Problem::parse(Path::new("column.toml"), &text)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains(&format!("analysis.{key}")) && err.contains("above 1"),
            "{analysis}: {err}"
        );
    }
    let text = column_text(0.02, false, "critical_up_to = 2")
        .replace("deflection = \"large\"", "deflection = \"small\"");
    let err = Problem::parse(Path::new("column.toml"), &text)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("critical_up_to"), "{err}");
}
