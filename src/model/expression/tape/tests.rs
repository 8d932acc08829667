//! The tape against the tree it compiles.

use super::super::tests::{NAMES, SMOOTH};
use super::*;
use crate::model::scalar::Jet;

/// The tape gives the tree's values and gradients bit for bit, shares what the
/// expressions share, and fails where the tree fails.
#[test]
fn the_tape_computes_what_the_tree_computes() {
    let texts: Vec<&str> = SMOOTH
        .iter()
        .copied()
        .chain([
            "l2*cos(delta2)",
            "l2*cos(delta2) + t*sin(delta2)",
            "2*3 - l2/3 + (1 - t) - 4/l2",
            "-(2 + 1)*l2^2 + 0",
        ])
        .collect();
    let parsed: Vec<Expression> = texts
        .iter()
        .map(|t| Expression::parse(t, &NAMES).unwrap())
        .collect();
    let tape = Tape::compile(&parsed, 3);
    let x = [1.7, 0.4, 0.55];
    let jets: Vec<Jet<3>> = (0..3).map(|i| Jet::variable(x[i], i)).collect();
    let (mut plain, mut dual) = (Vec::new(), Vec::new());
    assert!(tape.run(&x, &mut plain));
    assert!(tape.run(&jets, &mut dual));
    for (k, e) in parsed.iter().enumerate() {
        let r = tape.output(k);
        assert_eq!(
            plain[r].to_bits(),
            e.eval(&x).unwrap().to_bits(),
            "{}",
            texts[k]
        );
        let tree = e.eval(&jets).unwrap();
        assert_eq!(dual[r].re.to_bits(), tree.re.to_bits(), "{}", texts[k]);
        for i in 0..3 {
            // the same numbers, a zero's sign aside (a constant's zero derivative)
            assert!(dual[r].grad[i] == tree.grad[i], "{} d/d{i}", texts[k]);
        }
    }
    // `l2*cos(delta2)` once, with one sin_cos of delta2 for every expression
    let one = Tape::compile(&parsed[8..10], 3);
    assert_eq!(one.ops.len(), 4, "{:?}", one.ops);
    // the odd expressions alone: their values bit for bit, the others' operations gone
    let odd = tape.only(|k| k % 2 == 1);
    assert!(odd.ops.len() < tape.ops.len());
    let mut kept = Vec::new();
    assert!(odd.run(&jets, &mut kept));
    for k in (1..parsed.len()).step_by(2) {
        let (a, b) = (kept[odd.output(k)], dual[tape.output(k)]);
        assert_eq!(a.re.to_bits(), b.re.to_bits(), "{}", texts[k]);
        assert!(a.grad == b.grad, "{}", texts[k]);
    }
    assert_eq!(odd.outputs[0], DROPPED);
    assert_eq!(kept.len(), odd.registers());
    // the operations of one code run together: fewer changes of code than compiled
    fn changes<T: PartialEq>(codes: Vec<T>) -> usize {
        codes.windows(2).filter(|w| w[0] != w[1]).count()
    }
    let compiled = tape
        .ops
        .iter()
        .map(|op| op.code)
        .filter(|&c| c != Code::Const);
    let planned = tape.plan.steps.iter().map(|op| (op.run, op.f));
    assert!(changes(planned.collect()) < changes(compiled.collect()));
    assert_eq!(
        tape.plan.steps.len() + tape.plan.constants.len(),
        tape.ops.len()
    );
    // an angle's sine and cosine where another expression takes them, bit for bit
    let angle = Expression::parse("delta2", &NAMES).unwrap();
    let both = Tape::compile([&angle, &parsed[8]], 3);
    let (sin, cos) = both.sin_cos_of(0).expect("cos(delta2) is on the tape");
    assert!(both.run(&jets, &mut dual));
    let (s, c) = jets[1].sin_cos();
    assert!(dual[sin] == s && dual[cos] == c);
    assert_eq!(both.sin_cos_of(1), None);
    assert_eq!(Tape::compile([&angle], 3).sin_cos_of(0), None);
    // a constant less a register: the tree's zero, with its sign
    let e = Expression::parse("1 - l2", &NAMES).unwrap();
    let one = Tape::compile([&e], 3);
    assert!(one.run(&[1.0, 0.0, 0.0], &mut plain));
    let zero = plain[one.output(0)];
    assert_eq!(zero.to_bits(), e.eval(&[1.0, 0.0, 0.0]).unwrap().to_bits());
    assert_eq!(zero.to_bits(), 0.0f64.to_bits());
    // a constant is known as one
    let constants: Vec<Expression> = ["-1", "l2", "2*3", "l2 - 1"]
        .iter()
        .map(|t| Expression::parse(t, &NAMES).unwrap())
        .collect();
    let c = Tape::compile(&constants, 3);
    let known: Vec<Option<f64>> = (0..4).map(|k| c.constant(k)).collect();
    assert_eq!(known, [Some(-1.0), None, Some(6.0), None]);
    // a division by zero, a root of a negative number: refused, as the tree refuses
    for text in ["1 / (l2 - t)", "sqrt(delta2 - l2)", "hypot(l2 - t, 0)"] {
        let e = Expression::parse(text, &NAMES).unwrap();
        let tape = Tape::compile([&e], 3);
        let x = [2.0, 0.5, 2.0];
        assert!(e.eval(&x).is_err(), "{text}");
        assert!(!tape.run(&x, &mut plain), "{text}");
    }
}
