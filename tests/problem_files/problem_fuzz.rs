//! The problem-file parser on random and mutated files: never a panic, and every rejection
//! names a key. Accepted files must also evaluate without a panic.

use std::path::Path;

use flexopt::problem::Problem;
use flexopt::report::DesignReport;
use proptest::prelude::*;

const BASE: &str = include_str!("../../problems/wei2017.toml");

/// Values a careless or hostile file might hold.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "1e-320",
    "\"\"",
    "\"10 mm\"",
    "\"10\"",
    "\"mm\"",
    "\"-5 deg\"",
    "\"nan mm\"",
    "\"1e999 GPa\"",
    "true",
    "[]",
    "[1, 2]",
    "{}",
    "\"bridge\"",
    "\"ultimate\"",
    "\"al7075-t6\"",
    "12.0",
    "\"amplification\"",
    "=",
    "[[",
    "]]",
    "\"unterminated",
    "9223372036854775807",
    "-9223372036854775808",
    "0x10",
    "1_000",
    "\"\\u0000\"",
    // quantities at the limits of f64, and units at every scale
    "\"1e300 GPa\"",
    "\"1e-300 GPa\"",
    "\"1e308 kN\"",
    "\"5e-324 mm\"",
    "\"1e-300 nm\"",
    "\"1e300 kg/m3\"",
    "\"1e-300 g/cm3\"",
    "\"1.7976931348623157e308 N/um\"",
    "\"2.2250738585072014e-308 mN\"",
    "1e300",
    "-1e300",
    "2.2250738585072014e-308",
];

#[derive(Debug, Clone)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    ReplaceValue(usize, usize),
    InsertLine(usize, usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::DeleteLine),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::ReplaceValue(a, b)),
        (any::<usize>(), any::<usize>(), any::<usize>())
            .prop_map(|(a, b, c)| Mutation::InsertLine(a, b, c)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let keys = [
        "name", "unit", "lower", "upper", "value", "output", "width", "kind", "preset", "weight",
        "starts", "seed", "x",
    ];
    for m in mutations {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match *m {
            Mutation::DeleteLine(i) => {
                lines.remove(i % n);
            }
            Mutation::DuplicateLine(i) => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Mutation::SwapLines(a, b) => lines.swap(a % n, b % n),
            Mutation::ReplaceValue(i, t) => {
                let l = &mut lines[i % n];
                if let Some(eq) = l.find('=') {
                    *l = format!("{}= {}", &l[..eq], TOKENS[t % TOKENS.len()]);
                }
            }
            Mutation::InsertLine(i, k, t) => {
                lines.insert(
                    i % n,
                    format!("{} = {}", keys[k % keys.len()], TOKENS[t % TOKENS.len()]),
                );
            }
            Mutation::Truncate(i) => lines.truncate(i % n),
        }
    }
    lines.join("\n")
}

fn check(text: &str) {
    match Problem::parse(Path::new("fuzz.toml"), text) {
        Ok(p) => {
            // an accepted problem evaluates at the middle of its bounds without a panic
            let mid: Vec<f64> = p
                .variables
                .iter()
                .map(|v| 0.5 * (v.lower + v.upper))
                .collect();
            let _ = DesignReport::new(&p, &mid);
            // every quantity past validation is a finite number of physical size
            for v in &p.variables {
                assert!(v.lower.is_finite() && v.upper.is_finite(), "{v:?}\n{text}");
            }
            for c in &p.constraints {
                for l in c.lower.iter().chain(&c.upper) {
                    assert!(l.is_finite(), "{c:?}\n{text}");
                }
            }
            if let Some(m) = p.model().material() {
                let all = [m.youngs_modulus, m.poisson_ratio, m.density];
                assert!(all.iter().all(|v| v.is_finite()), "{m:?}\n{text}");
                assert!(m.ultimate_strength.is_none_or(f64::is_finite), "{m:?}");
            }
        }
        Err(e) => {
            assert!(
                !e.key.is_empty(),
                "a rejection without a key: {e}\n--- file ---\n{text}"
            );
            assert!(e.to_string().starts_with("fuzz.toml"), "{e}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 3000,
        // a fixed seed: CI runs the same cases every time
        rng_seed: proptest::test_runner::RngSeed::Fixed(2017),
        // the saved failures beside this file (by default, proptest would look in
        // tests/proptest-regressions/, next to the folder of the nearest main.rs)
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_problem_files(mutations in proptest::collection::vec(mutation(), 1..5)) {
        check(&apply(BASE, &mutations));
    }

    #[test]
    fn random_text(text in "\\PC{0,200}") {
        check(&text);
    }

    #[test]
    fn random_key_value_lines(lines in proptest::collection::vec("[a-z_\\[\\]]{1,12} ?= ?[-0-9a-z\\.\"\\[\\] ]{0,12}", 0..12)) {
        check(&lines.join("\n"));
    }
}
