//! The expressions' language: values, derivatives and messages against hand-worked cases.

use super::*;
use crate::model::scalar::Jet;
use num_dual::Dual2SVec64;

pub(super) const NAMES: [&str; 3] = ["l2", "delta2", "t"];

fn value(text: &str, x: [f64; 3]) -> f64 {
    Expression::parse(text, &NAMES)
        .unwrap_or_else(|e| panic!("{text}: {e}"))
        .eval(&x)
        .unwrap_or_else(|e| panic!("{text}: {e}"))
}

#[test]
fn values_follow_the_usual_precedence() {
    let x = [2.0, 0.3, 0.5];
    let (l, d, t) = (x[0], x[1], x[2]);
    for (text, expected) in [
        ("1 + 2*3", 7.0),
        ("(1 + 2)*3", 9.0),
        ("-2^2", -4.0),
        ("2^3^2", 512.0),
        ("2^-1", 0.5),
        ("10 - 4 - 3", 3.0),
        ("12 / 3 / 2", 2.0),
        ("- -3", 3.0),
        ("+3 * -2", -6.0),
        ("1e-3 + .5 + 2.5E+2", 250.501),
        ("pi", PI),
        ("l2*cos(delta2)", l * d.cos()),
        ("l2 * sin(delta2) - t/2", l * d.sin() - t / 2.0),
        ("sqrt(l2^2 + t^2)", (l * l + t * t).sqrt()),
        ("hypot(l2, t)", l.hypot(t)),
        ("l2^0.5", l.sqrt()),
        ("t^(1/3)", t.cbrt()),
        ("tan(delta2)", d.tan()),
        ("asin(t) + acos(t)", FRAC_PI_2),
        ("atan(l2)", l.atan()),
        ("abs(t - l2)", (t - l).abs()),
        ("min(l2, t) + 10*max(l2, t)", t + 10.0 * l),
    ] {
        let v = value(text, x);
        assert!(
            (v - expected).abs() <= 1e-14 * expected.abs().max(1.0),
            "{text}: {v} against {expected}"
        );
    }
}

#[test]
fn atan2_takes_each_quadrant() {
    for k in 0..72 {
        let angle = -PI + (k as f64 + 0.5) * PI / 36.0;
        for r in [1e-3, 1.0, 7.0] {
            let (y, x) = (r * angle.sin(), r * angle.cos());
            let v = value("atan2(l2, delta2)", [y, x, 0.0]);
            assert!((v - y.atan2(x)).abs() < 1e-14, "{angle}: {v}");
        }
    }
    // the axes
    for (y, x) in [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)] {
        assert_eq!(value("atan2(l2, delta2)", [y, x, 0.0]), f64::atan2(y, x));
    }
}

pub(super) const SMOOTH: [&str; 8] = [
    "l2*cos(delta2) - t/2",
    "sqrt(l2^2 + t^2) * sin(delta2)",
    "t^(1/3) / (l2 + 1)",
    "atan2(l2*sin(delta2), l2*cos(delta2) + t)",
    "hypot(l2 - t, 2*delta2) + tan(delta2)^2",
    "asin(t/l2) - acos(delta2)",
    "(l2 - t)^-2 * abs(delta2 - 1)",
    "max(l2, 3*t) * min(delta2, t)",
];

/// Gradients by `Jet<3>` against central differences of the `f64` values, and
/// Hessians by num-dual's second-order numbers against central differences of the
/// gradients: one tree, every order.
#[test]
fn derivatives_of_every_order_agree_with_differences() {
    let x = [1.7, 0.4, 0.55];
    for text in SMOOTH {
        let e = Expression::parse(text, &NAMES).unwrap();
        let jet = |x: [f64; 3]| {
            let v: Vec<Jet<3>> = (0..3).map(|i| Jet::variable(x[i], i)).collect();
            e.eval(&v).unwrap()
        };
        let g = jet(x);
        assert_eq!(g.re, e.eval(&x).unwrap(), "{text}");
        let seeded: Vec<Dual2SVec64<3>> = (0..3)
            .map(|i| Dual2SVec64::from_re(x[i]).derivative(i))
            .collect();
        let second = e.eval(&seeded).unwrap();
        let first = second.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
        let hessian = second
            .v2
            .unwrap_generic(nalgebra::Const::<3>, nalgebra::Const::<3>);
        for i in 0..3 {
            let h = 1e-6 * x[i].abs().max(1.0);
            let (mut up, mut down) = (x, x);
            up[i] += h;
            down[i] -= h;
            let fd = (e.eval(&up).unwrap() - e.eval(&down).unwrap()) / (2.0 * h);
            let scale = g.grad[i].abs().max(1.0);
            assert!(
                (g.grad[i] - fd).abs() < 1e-7 * scale,
                "{text} d/d{i}: {} {fd}",
                g.grad[i]
            );
            assert!((first[i] - g.grad[i]).abs() < 1e-12 * scale, "{text}");
            let (gu, gd) = (jet(up), jet(down));
            for j in 0..3 {
                let fd2 = (gu.grad[j] - gd.grad[j]) / (2.0 * h);
                let s = hessian[(i, j)].abs().max(1.0);
                assert!(
                    (hessian[(i, j)] - fd2).abs() < 1e-6 * s,
                    "{text} d2/d{i}d{j}: {} {fd2}",
                    hessian[(i, j)]
                );
            }
        }
    }
}

#[test]
fn names_used_are_listed_once() {
    let e = Expression::parse("t*l2 + t^2 - pi", &NAMES).unwrap();
    assert_eq!(e.names_used(), [0, 2]);
    assert_eq!(e.source(), "t*l2 + t^2 - pi");
}

fn parse_error(text: &str) -> ParseError {
    Expression::parse(text, &NAMES).expect_err(text)
}

#[test]
fn bad_text_is_refused_where_it_goes_wrong() {
    for (text, position, words) in [
        ("", 0, "empty"),
        ("   ", 0, "empty"),
        (
            "l3 * 2",
            0,
            "unknown name `l3`: the names here are `l2`, `delta2`, `t`, `pi`",
        ),
        ("2 * cosh(t)", 4, "unknown function `cosh`"),
        ("2 * sqrt", 4, "`sqrt` is a function"),
        ("(l2 + t", 7, "expected `)`, found the end"),
        ("l2 + * t", 5, "expected a number, a name or `(`, found `*`"),
        ("l2 t", 3, "`t` follows a complete expression"),
        ("l2 +", 4, "found the end"),
        ("2^t", 2, "the exponent `t` depends on the design"),
        ("atan2(l2)", 0, "`atan2` takes 2 arguments, not 1"),
        ("sin(l2, t)", 0, "`sin` takes 1 argument, not 2"),
        ("1.2.3", 0, "`1.2.3` is not a number"),
        ("l2 # 2", 3, "`#` is not part of an expression"),
        ("l2 = 2", 3, "`=` is not part of an expression"),
    ] {
        let e = parse_error(text);
        assert_eq!(e.position, position, "{text}: {e}");
        assert!(e.message.contains(words), "{text}: {e}");
    }
}

#[test]
fn values_outside_a_functions_domain_name_the_sub_expression() {
    let at = |text: &str, x: [f64; 3]| -> String {
        Expression::parse(text, &NAMES)
            .unwrap()
            .eval(&x)
            .expect_err(text)
            .message
    };
    let x = [2.0, 0.5, 2.0];
    for (text, words) in [
        (
            "1 / (l2 - t)",
            "`(l2 - t)` is zero, a division by zero, at this design",
        ),
        ("(l2 - t)^-1", "`(l2 - t)` is zero under a negative power"),
        (
            "sqrt(delta2 - l2)",
            "`delta2 - l2` is -1.5, and a square root needs it at least 0",
        ),
        (
            "(delta2 - t)^0.5",
            "`(delta2 - t)` is -1.5 under the power 0.5",
        ),
        (
            "asin(l2)",
            "`l2` is 2, where asin needs it strictly between -1 and 1",
        ),
        (
            "atan2(l2 - t, 0)",
            "`atan2(l2 - t, 0)` has both arguments zero",
        ),
        ("10^400 * l2", "`10^400 * l2` is not a finite number"),
    ] {
        let m = at(text, x);
        assert!(m.contains(words), "{text}: {m}");
    }
    // the same through a dual number: the domain is the value's
    let e = Expression::parse("1 / (l2 - t)", &NAMES).unwrap();
    let v: Vec<Jet<3>> = (0..3).map(|i| Jet::variable(x[i], i)).collect();
    assert!(e.eval(&v).is_err());
}
