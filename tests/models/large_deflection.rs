//! The geometrically nonlinear planar structure (`flexopt::model::large`, issue 48) against
//! exact answers: the Bisshopp-Drucker cantilever, Euler's loads from the critical load
//! factor, a fixed-guided leaf's shortening against the elastica shot in this file with its
//! own Runge-Kutta stepper, the linear answers at a vanishing load (rigid bodies and the
//! spring included), and an arc-length path through the limit point of a two-spring truss.

use std::f64::consts::PI;
use std::time::Instant;

use flexopt::model::large::critical::critical_load_factor;
use flexopt::model::large::solve::{arc_length, continuation, Options};
use flexopt::model::large::{Dof, LargeError, Section, Spring, Structure};

const L: f64 = 0.02;
/// A steel strip 10 mm wide and 0.1 mm thick: its `E I`; and an axial stiffness `E A` a
/// hundred times its own, so that the axial strain at the loads below is below 1e-7 (the
/// tabulated answers and Euler's loads are for an inextensible beam).
const EI: f64 = 200e9 * 0.01 * 1e-12 / 12.0;
const EA: f64 = 100.0 * 200e9 * 0.01 * 1e-4;

fn strip(_: f64) -> Section {
    Section { ea: EA, ei: EI }
}

/// A clamped strip along x from the origin in `n` elements; the structure and its tip.
fn clamped(n: usize) -> (Structure, usize) {
    let mut s = Structure::default();
    let root = s.node(0.0, 0.0);
    let tip = s.node(L, 0.0);
    s.flexure(root, tip, n, strip);
    s.fix(root);
    (s, tip)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// One classical Runge-Kutta step of `y' = f(y)` over `h`.
fn rk4<const N: usize>(y: [f64; N], h: f64, f: &impl Fn(&[f64; N]) -> [f64; N]) -> [f64; N] {
    let add = |a: [f64; N], b: [f64; N], s: f64| std::array::from_fn(|i| a[i] + s * b[i]);
    let k1 = f(&y);
    let k2 = f(&add(y, k1, h / 2.0));
    let k3 = f(&add(y, k2, h / 2.0));
    let k4 = f(&add(y, k3, h));
    std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// The inextensible elastica of unit length clamped at s = 0, a load `f = F L^2 / EI`
/// across its original axis at s = 1 and a moment making the end curvature `kappa0`
/// at the root: `theta'' = -f cos(theta)` (no axial force), integrated in 4000 steps;
/// `(theta, theta', x, y)` at s = 1.
fn elastica(kappa0: f64, f: f64) -> [f64; 4] {
    let rhs = |y: &[f64; 4]| [y[1], -f * y[0].cos(), y[0].cos(), y[0].sin()];
    let steps = 4000;
    let mut y = [0.0, kappa0, 0.0, 0.0];
    for _ in 0..steps {
        y = rk4(y, 1.0 / steps as f64, &rhs);
    }
    y
}

/// Bisshopp and Drucker's cantilever by shooting: the root curvature that leaves the free
/// end unbent (`theta'(1) = 0`) by the secant method; `(w / L, u / L)` at the tip.
fn bisshopp_drucker(alpha: f64) -> (f64, f64) {
    let (mut a, mut b) = (alpha, 0.9 * alpha);
    let (mut fa, mut fb) = (elastica(a, alpha)[1], elastica(b, alpha)[1]);
    for _ in 0..50 {
        if fb == 0.0 || (b - a).abs() < 1e-15 {
            break;
        }
        let c = b - fb * (b - a) / (fb - fa);
        (a, fa) = (b, fb);
        (b, fb) = (c, elastica(c, alpha)[1]);
    }
    let end = elastica(b, alpha);
    (end[3], end[2] - 1.0)
}

/// The clamped-guided leaf by shooting: the root curvature and end load that bring the end
/// to `theta(1) = 0` at `y(1) = delta`, by Newton's method with a difference Jacobian from
/// the linear leaf's `f = 12 delta`, `kappa0 = 6 delta`; the end's axial shortening `x(1) - 1`.
fn guided_shortening(delta: f64) -> f64 {
    let mut p = [6.0 * delta, 12.0 * delta];
    let miss = |p: [f64; 2]| {
        let e = elastica(p[0], p[1]);
        [e[0], e[3] - delta]
    };
    for _ in 0..30 {
        let m = miss(p);
        if m[0].abs().max(m[1].abs()) < 1e-14 {
            break;
        }
        let h = 1e-7;
        let d0 = miss([p[0] + h, p[1]]);
        let d1 = miss([p[0], p[1] + h]);
        let j = [
            [(d0[0] - m[0]) / h, (d1[0] - m[0]) / h],
            [(d0[1] - m[1]) / h, (d1[1] - m[1]) / h],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        p[0] -= (j[1][1] * m[0] - j[0][1] * m[1]) / det;
        p[1] -= (-j[1][0] * m[0] + j[0][0] * m[1]) / det;
    }
    elastica(p[0], p[1])[2] - 1.0
}

/// The tip's `(w / L, u / L)` of the cantilever under `P = alpha EI / L^2` across it.
fn cantilever(n: usize, alpha: f64) -> (f64, f64) {
    let (mut s, tip) = clamped(n);
    s.load(tip, [0.0, alpha * EI / (L * L), 0.0]);
    let opts = Options {
        steps: 8,
        ..Options::default()
    };
    let end = continuation(&s, 1.0, &opts).unwrap();
    let p = end.end();
    (p.at(tip, Dof::Y) / L, p.at(tip, Dof::X) / L)
}

#[test]
fn bisshopp_drucker_cantilever_to_1e_4_and_its_convergence() {
    for (alpha, w, u) in [(1.0, 0.30172, -0.05643), (2.0, 0.49346, -0.16064)] {
        // the shooting reproduces the table to its last digit
        let (ws, us) = bisshopp_drucker(alpha);
        assert!(
            (ws - w).abs() <= 5e-6 && (us - u).abs() <= 5e-6,
            "{ws} {us}"
        );
        let mut errors = Vec::new();
        for n in [4, 8, 16, 32] {
            let start = Instant::now();
            let (wn, un) = cantilever(n, alpha);
            let error = relative(wn, ws).max(relative(un, us));
            eprintln!(
                "alpha {alpha}, {n} elements: w/L {wn:.7}, u/L {un:.7}, error {error:.2e}, {:.1} ms",
                start.elapsed().as_secs_f64() * 1e3
            );
            errors.push(error);
        }
        // falling at least as the square of the element length to the strain's 1e-7
        for pair in errors.windows(2) {
            assert!(pair[1] < pair[0] / 3.0 || pair[1] < 1e-6, "{errors:?}");
        }
        let (wn, un) = cantilever(32, alpha);
        assert!(
            relative(wn, w) <= 1e-4 && relative(un, u) <= 1e-4,
            "{wn} {un}"
        );
    }
}

#[test]
fn arc_length_path_meets_the_load_controlled_cantilever() {
    let (mut s, tip) = clamped(16);
    s.load(tip, [0.0, 2.0 * EI / (L * L), 0.0]);
    let arc = arc_length(&s, 1.0, &Options::default()).unwrap();
    let newton = continuation(&s, 1.0, &Options::default()).unwrap();
    assert_eq!(arc.end().lambda, 1.0);
    assert!(arc.points.len() > 5);
    for dof in [Dof::X, Dof::Y, Dof::Rotation] {
        let (a, b) = (arc.end().at(tip, dof), newton.end().at(tip, dof));
        assert!(relative(a, b) < 1e-9, "{dof:?}: {a} {b}");
    }
    // the path rises monotonically here, every point in equilibrium at its own factor
    for pair in arc.points.windows(2) {
        assert!(pair[1].lambda > pair[0].lambda);
    }
}

/// The critical load factor of a strip of `n` elements under `EI / L^2` along it, its end
/// held in `held`.
fn euler(n: usize, held: &[Dof]) -> f64 {
    let (mut s, tip) = clamped(n);
    for &dof in held {
        s.hold(tip, dof);
    }
    s.load(tip, [-EI / (L * L), 0.0, 0.0]);
    let opts = Options {
        steps: 10,
        ..Options::default()
    };
    critical_load_factor(&s, 50.0, &opts).unwrap().lambda
}

#[test]
fn euler_loads_from_the_critical_load_factor() {
    // fixed-free: pi^2 EI / (4 L^2); fixed-guided (the end's rotation held, free to sway
    // and to slide): pi^2 EI / L^2; fixed-fixed (rotation and sway held, free to slide
    // along the axis): 4 pi^2 EI / L^2
    let cases: [(&[Dof], f64, usize); 3] = [
        (&[], PI * PI / 4.0, 48),
        (&[Dof::Rotation], PI * PI, 48),
        (&[Dof::Rotation, Dof::Y], 4.0 * PI * PI, 96),
    ];
    for (held, exact, n) in cases {
        let coarse = euler(n / 4, held);
        let start = Instant::now();
        let fine = euler(n, held);
        eprintln!(
            "held {held:?}: {} elements {coarse:.6}, {n} elements {fine:.8} against {exact:.8} ({:.2e}), {:.0} ms",
            n / 4,
            relative(fine, exact),
            start.elapsed().as_secs_f64() * 1e3
        );
        assert!(
            relative(fine, exact) <= 1e-4,
            "{held:?}: {fine} against {exact}"
        );
        assert!(
            relative(fine, exact) < relative(coarse, exact) / 8.0 || relative(fine, exact) < 1e-7
        );
    }
}

#[test]
fn no_critical_point_below_the_euler_load_is_an_error() {
    let (mut s, tip) = clamped(8);
    s.load(tip, [-EI / (L * L), 0.0, 0.0]);
    let got = critical_load_factor(&s, 2.0, &Options::default());
    assert_eq!(got, Err(LargeError::NoCriticalPoint { lambda_max: 2.0 }));
}

#[test]
fn fixed_guided_leaf_shortening_against_the_shot_elastica() {
    for delta in [0.1, 0.3] {
        let exact = guided_shortening(delta);
        // the leaf's parasitic shortening is about 0.6 delta^2 / L at small delta
        assert!(relative(exact, -0.6 * delta * delta) < 0.05, "{exact}");
        for n in [8, 16, 32] {
            let (mut s, tip) = clamped(n);
            s.hold(tip, Dof::Rotation);
            s.prescribe(tip, Dof::Y, delta * L);
            let opts = Options {
                steps: 6,
                ..Options::default()
            };
            let start = Instant::now();
            let path = continuation(&s, 1.0, &opts).unwrap();
            let got = path.end().at(tip, Dof::X) / L;
            eprintln!(
                "delta/L {delta}, {n} elements: u/L {got:.8} against {exact:.8} ({:.2e}), {:.1} ms",
                relative(got, exact),
                start.elapsed().as_secs_f64() * 1e3
            );
            assert_eq!(path.end().at(tip, Dof::Y), delta * L);
            if n == 32 {
                assert!(relative(got, exact) <= 1e-4, "{got} {exact}");
            }
        }
    }
}

#[test]
fn vanishing_load_gives_the_linear_answers() {
    let p = 1e-6 * EI / (L * L);
    let tip_of = |s: &Structure, node: usize, dof: Dof| {
        continuation(s, 1.0, &Options::default())
            .unwrap()
            .end()
            .at(node, dof)
    };
    // cantilever: P L^3 / 3 EI
    let (mut s, tip) = clamped(5);
    s.load(tip, [0.0, p, 0.0]);
    let w = tip_of(&s, tip, Dof::Y);
    assert!(relative(w, p * L.powi(3) / (3.0 * EI)) < 1e-9, "{w}");
    // guided: P L^3 / 12 EI
    s.hold(tip, Dof::Rotation);
    let w = tip_of(&s, tip, Dof::Y);
    assert!(relative(w, p * L.powi(3) / (12.0 * EI)) < 1e-9, "{w}");
    // a rigid arm of length a beyond the tip, loaded at its end
    let a = 0.3 * L;
    let (mut s, tip) = clamped(5);
    let arm = s.node(L + a, 0.0);
    s.attach(tip, arm);
    s.load(arm, [0.0, p, 0.0]);
    let (m, l2, l3) = (p * a, L * L, L.powi(3));
    let w_tip = p * l3 / (3.0 * EI) + m * l2 / (2.0 * EI);
    let turn = p * l2 / (2.0 * EI) + m * L / EI;
    assert!(relative(tip_of(&s, tip, Dof::Y), w_tip) < 1e-9);
    assert!(relative(tip_of(&s, arm, Dof::Y), w_tip + a * turn) < 1e-9);
    assert!(relative(tip_of(&s, arm, Dof::Rotation), turn) < 1e-9);
    // a stack under the tip, its free stroke and preload pushing the tip up against the
    // cantilever's 3 EI / L^3
    let (mut s, tip) = clamped(5);
    let base = s.node(L, -0.005);
    s.fix(base);
    let (k, stroke, preload) = (50.0, 1e-8, 2e-7);
    s.springs.push(Spring {
        a: base,
        b: tip,
        stiffness: k,
        free_stroke: stroke,
        preload,
    });
    let kb = 3.0 * EI / l3;
    let w = tip_of(&s, tip, Dof::Y);
    assert!(relative(w, (k * stroke + preload) / (k + kb)) < 1e-9, "{w}");
}

#[test]
fn arc_length_passes_the_limit_point_of_a_two_spring_truss() {
    // von Mises' truss: springs from (-a, 0) and (a, 0) to the apex at (0, h), the apex
    // pressed down by P and held against turning and sideways motion
    let (a, h, k, p) = (0.1, 0.02, 1e4, 10.0);
    let mut s = Structure::default();
    let left = s.node(-a, 0.0);
    let right = s.node(a, 0.0);
    let apex = s.node(0.0, h);
    s.fix(left);
    s.fix(right);
    s.hold(apex, Dof::X);
    s.hold(apex, Dof::Rotation);
    for end in [left, right] {
        s.springs.push(Spring {
            a: end,
            b: apex,
            stiffness: k,
            free_stroke: 0.0,
            preload: 0.0,
        });
    }
    s.load(apex, [0.0, -p, 0.0]);
    // the apex's resistance at a drop v: 2 k (l0 - l) y / l, y = h - v
    let l0 = a.hypot(h);
    let resist = |v: f64| {
        let y = h - v;
        let l = a.hypot(y);
        2.0 * k * (l0 - l) * y / l
    };
    // the limit: the largest resistance before the apex passes the supports' line
    let limit = (0..=100000)
        .map(|i| resist(h * i as f64 / 100000.0))
        .fold(0.0, f64::max)
        / p;
    let end = 1.2 * limit;
    let opts = Options {
        steps: 40,
        ..Options::default()
    };
    let path = arc_length(&s, end, &opts).unwrap();
    let mut highest: f64 = 0.0;
    let mut fell = false;
    for pair in path.points.windows(2) {
        let v = -pair[1].at(apex, Dof::Y);
        assert!((resist(v) - pair[1].lambda * p).abs() < 1e-8 * p, "{v}");
        fell |= pair[1].lambda < pair[0].lambda;
        // the highest load before the path first falls: the limit point
        if !fell {
            highest = highest.max(pair[1].lambda);
        }
    }
    assert!(fell, "the load factor never fell");
    assert!(
        highest <= limit * (1.0 + 1e-8),
        "{highest} above the limit {limit}"
    );
    assert!(
        highest > 0.95 * limit,
        "{highest} far below the limit {limit}"
    );
    assert!(path.points.iter().any(|q| q.lambda < 0.0));
    assert_eq!(path.end().lambda, end);
    assert!(-path.end().at(apex, Dof::Y) > 2.0 * h);
    // load control snaps: one step carries the apex more than h, to the same far branch
    let snap = continuation(&s, end, &opts).unwrap();
    let v = |q: &flexopt::model::large::PathPoint| -q.at(apex, Dof::Y);
    assert!(snap.points.windows(2).any(|w| v(&w[1]) - v(&w[0]) > h));
    assert!(relative(v(snap.end()), v(path.end())) < 1e-9);
}

#[test]
fn malformed_structures_are_named() {
    let (mut s, tip) = clamped(2);
    s.attach(tip, 0);
    s.hold(tip, Dof::X);
    let got = continuation(&s, 1.0, &Options::default()).unwrap_err();
    assert!(got.to_string().contains("is a slave"), "{got}");
    let (mut s, _) = clamped(2);
    s.beams[0].section.ei = -1.0;
    let got = continuation(&s, 1.0, &Options::default()).unwrap_err();
    assert!(got.to_string().contains("beam 0"), "{got}");
    let mut s = Structure::default();
    s.node(0.0, 0.0);
    let got = continuation(&s, 1.0, &Options::default()).unwrap_err();
    assert_eq!(got, LargeError::Singular { lambda: 0.0 });
}
