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

// Issue 50: the reader on random TOML structure, and the expression language on random
// expressions, deep and long, alone and inside a network's file.

/// Keys of every section, so that random tables reach past the first unknown key.
const KEYS: &[&str] = &[
    "name",
    "model",
    "material",
    "network",
    "bodies",
    "hinges",
    "beams",
    "outline",
    "link",
    "from",
    "to",
    "width",
    "unit",
    "parameters",
    "input",
    "outputs",
    "measures",
    "value",
    "dimension",
    "start",
    "angle",
    "l",
    "t",
    "r",
    "variables",
    "lower",
    "upper",
    "objective",
    "maximize",
    "minimize",
    "constraints",
    "output",
    "search",
    "starts",
    "robust",
    "yield",
    "tolerances",
    "sigma",
    "plus_minus",
    "part",
    "actuator",
    "preset",
    "stiffness",
    "mirror",
];

/// A random TOML value: scalars from [`TOKENS`]'s kinds, arrays and tables of them, nested.
fn toml_value() -> impl Strategy<Value = toml::Value> {
    let leaf = prop_oneof![
        any::<i64>().prop_map(toml::Value::Integer),
        any::<f64>().prop_map(toml::Value::Float),
        any::<bool>().prop_map(toml::Value::Boolean),
        "[-0-9a-z_ .*/()\"]{0,16}".prop_map(toml::Value::String),
        proptest::sample::select(TOKENS).prop_map(|t| toml::Value::String(t.to_string())),
    ];
    leaf.prop_recursive(6, 64, 8, |inner| {
        prop_oneof![
            proptest::collection::vec(inner.clone(), 0..6).prop_map(toml::Value::Array),
            proptest::collection::vec((proptest::sample::select(KEYS), inner), 0..6).prop_map(
                |pairs| {
                    let table = pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
                    toml::Value::Table(table)
                }
            ),
        ]
    })
}

/// An expression of the lever's parameters `arm` and `t` (and `deg`, `pi`), as text: the language's every
/// operator and function, random spacing, and nonsense now and then.
fn expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        proptest::sample::select(
            &["arm", "t", "deg", "pi", "0", "1", "2.5", ".5", "1e-3", "1e308", "0.0"][..]
        )
        .prop_map(String::from),
        "[-+*/^(), a-z0-9.]{0,6}",
    ];
    leaf.prop_recursive(8, 128, 3, |inner| {
        let f = proptest::sample::select(
            &[
                "sin", "cos", "tan", "asin", "acos", "atan", "sqrt", "abs", "-", "",
            ][..],
        );
        let g = proptest::sample::select(&["atan2", "hypot", "min", "max", "pow"][..]);
        let op = proptest::sample::select(&["+", "-", "*", "/", "^"][..]);
        prop_oneof![
            (inner.clone(), op, inner.clone()).prop_map(|(a, o, b)| format!("{a} {o} {b}")),
            (f, inner.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            (g, inner.clone(), inner).prop_map(|(g, a, b)| format!("{g}({a}, {b})")),
        ]
    })
}

/// An expression nested deep (parentheses, signs, calls) or long (sums, products, powers),
/// to the sizes the parser takes on a test's thread (2 MiB of stack) today: 5,000 nested
/// parentheses there, and 20,000 in `flexopt eval`, abort by stack overflow (issue 50, case
/// 5, whose parser without recursion on the input's depth lifts these bounds to the 1 MiB a
/// file may have).
fn deep_or_long() -> impl Strategy<Value = String> {
    prop_oneof![
        (1usize..2000).prop_map(|d| format!("{}arm{}", "(".repeat(d), ")".repeat(d))),
        (1usize..2000).prop_map(|d| format!("{}arm", "-".repeat(d))),
        (1usize..500).prop_map(|d| format!("{}arm{}", "sqrt(abs(".repeat(d), "))".repeat(d))),
        (1usize..5000).prop_map(|n| vec!["arm"; n].join(" + ")),
        (1usize..2000).prop_map(|n| vec!["t"; n].join("*")),
        (1usize..500).prop_map(|n| format!("arm{}", "^1".repeat(n))),
    ]
}

/// `text` parsed and evaluated with values and with derivatives: a value, or an error that
/// says where; never a panic, and never a value that is not finite.
fn check_expression(text: &str) {
    use flexopt::model::expression::Expression;
    use flexopt::model::scalar::Jet;
    let Ok(e) = Expression::parse(text, &["arm", "t", "deg"]) else {
        return;
    };
    if let Ok(v) = e.eval::<f64>(&[2e-3, 0.5, 0.0174]) {
        assert!(v.is_finite(), "{text}: {v}");
    }
    let x = [
        Jet::<2>::variable(2e-3, 0),
        Jet::variable(0.5, 1),
        Jet::from(0.0174),
    ];
    if let Ok(v) = e.eval(&x) {
        assert!(v.re.is_finite(), "{text}: {v:?}");
    }
}

/// The lever network with `value` as a measure's expression, which [`check`] reads and
/// evaluates at the middle of the bounds.
fn in_network(value: &str) -> String {
    let base = include_str!("../../problems/lever_network.toml");
    let measure = format!(
        "[[network.measures]]\nname = \"m\"\ndimension = \"length\"\nvalue = \"{value}\"\n\n[network.input]"
    );
    base.replacen("[network.input]", &measure, 1)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 10_000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(50),
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_toml_structure(root in proptest::collection::vec((proptest::sample::select(KEYS), toml_value()), 0..8)) {
        let table: toml::Table = root.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
        if let Ok(text) = toml::to_string(&table) {
            check(&text);
        }
    }

    #[test]
    fn random_sections_in_a_network_file(section in proptest::sample::select(&["network", "actuator", "material", "part", "search", "tolerances"][..]), value in toml_value()) {
        // a shipped network file with one section replaced by a random value
        let mut table: toml::Table = toml::from_str(include_str!("../../problems/lever_network.toml")).unwrap();
        table.insert(section.to_string(), value);
        if let Ok(text) = toml::to_string(&table) {
            check(&text);
        }
    }

    #[test]
    fn random_expressions(text in expression()) {
        check_expression(&text);
        check(&in_network(&text));
    }

    #[test]
    fn deep_and_long_expressions(text in deep_or_long()) {
        check_expression(&text);
        check(&in_network(&text));
    }
}

/// The fuzz's expressions reach the model: a measure of them is read and evaluated.
#[test]
fn an_expression_in_the_network_file_is_read_and_evaluated() {
    let text = in_network(&vec!["arm"; 1000].join(" + "));
    let p = Problem::parse(Path::new("fuzz.toml"), &text).unwrap();
    let m = p.model().output_index("m").unwrap();
    let mid: Vec<f64> = p
        .variables
        .iter()
        .map(|v| 0.5 * (v.lower + v.upper))
        .collect();
    let report = DesignReport::new(&p, &mid);
    let arm = mid[p.variables.iter().position(|v| v.name == "arm").unwrap()];
    let value = report.outputs[p.model().outputs()[m].name.as_ref()].unwrap();
    assert!((value / (1000.0 * arm) - 1.0).abs() < 1e-12, "{value}");
}
