//! Issue 50, a network's description (cases 9 to 13 and 16): sizes checked for sign where
//! they are read, a gradient that is not finite named, names the model's outputs or the
//! expressions keep refused, points of exactly two coordinates, and each fault of the
//! description named by its key with what to do.

use std::path::{Path, PathBuf};

use flexopt::problem::Problem;

use crate::common::flexopt;

const LEVER: &str = "problems/lever_network.toml";
const GUIDE: &str = "problems/guide_network.toml";
const LINK: &str = "link = { from = [\"0\", \"0\"], to = [\"arm + 2\", \"0\"], width = \"8\" }";

/// `file` with each `[from, to]` made in order (each `from` must occur).
pub(crate) fn edited(file: &str, edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(file).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "fixture text {from:?} not in {file}");
        text = text.replacen(from, to, 1);
    }
    text
}

/// The edited file refused: its key is `key` (named in the message, with the file), and
/// the message holds each of `words`.
pub(crate) fn refused(file: &str, edits: &[(&str, &str)], key: &str, words: &[&str]) {
    let Err(e) = Problem::parse(Path::new("net.toml"), &edited(file, edits)) else {
        panic!("{edits:?} must be refused");
    };
    let shown = e.to_string();
    assert_eq!(e.key, key, "{shown}");
    assert!(shown.starts_with("net.toml"), "{shown}");
    assert!(shown.contains(&format!("`{key}`")), "{shown}");
    for w in words {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
}

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flexopt-net50-{}-{name}", std::process::id()))
}

/// Case 9: a literal width, thickness or hinge length of zero or less is refused at
/// reading with its key; one that the design makes non-positive is a domain error naming
/// the key, and the study keeps off it.
#[test]
fn sizes_are_checked_for_sign_where_they_are_read() {
    for width in ["0", "-1"] {
        let link = LINK.replace("width = \"8\"", &format!("width = \"{width}\""));
        refused(
            LEVER,
            &[(LINK, &link)],
            "network.bodies[0].link.width",
            &[&format!("\"{width}\""), "not positive"],
        );
    }
    refused(
        GUIDE,
        &[("l = \"L\"", "l = \"0\"")],
        "network.hinges[0].l",
        &["not positive"],
    );
    // a width that the design makes negative: named at that design, not a NaN
    let text = edited(LEVER, &[(LINK, &LINK.replace("\"8\"", "\"16*(r - 0.8)\""))]);
    let p = Problem::parse(Path::new("net.toml"), &text).unwrap();
    let why = p
        .model()
        .domain_error(&[0.7e-3, 1e-3, 6e-3, 40e-3])
        .expect("a negative width is outside the domain");
    assert!(why.contains("network.bodies[0].link.width"), "{why}");
    assert!(why.contains("-0.0016 m is not positive"), "{why}");
    // the study, its objective the first frequency, which reads the width, ends at a design
    // where every constraint has its value
    let file = temp("width.toml");
    let text = text.replacen("maximize = \"amplification\"", "maximize = \"f1\"", 1);
    std::fs::write(&file, text).unwrap();
    let out = temp("width-out");
    let run = flexopt(&[
        "run",
        file.to_str().unwrap(),
        "--starts",
        "20",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}");
    assert!(!stdout.contains("VIOLATED"), "{stdout}");
    let optimum = std::fs::read_to_string(out.join("optimum.json")).unwrap();
    assert!(optimum.contains("\"feasible\": true"), "{optimum}");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::remove_file(&file).unwrap();
}

/// Case 10: an expression whose value is finite and whose derivative is not is named, with
/// the variable, where every start failed without a word.
#[test]
fn a_gradient_that_is_not_finite_names_the_expression_and_the_variable() {
    refused(
        GUIDE,
        &[("value = \"L\"", "value = \"-L + 0*(sqrt(L-L))\"")],
        "variables[0].upper",
        &[
            "`-L + 0*(sqrt(L-L))` (network.measures[0].value)",
            "no finite derivative by L",
        ],
    );
}

/// Case 11: a measure, or a flexure, whose output's name the network gives already.
#[test]
fn a_name_clashing_with_an_output_is_refused() {
    for name in ["k_in", "stress_pivot", "f1"] {
        let measure = format!(
            "[[network.measures]]\nname = \"{name}\"\ndimension = \"length\"\nvalue = \"arm\"\n\n[network.input]"
        );
        refused(
            LEVER,
            &[("[network.input]", &measure)],
            "network.measures[0].name",
            &[&format!("measure \"{name}\""), "name it otherwise"],
        );
    }
    // a hinge "outer_top_to" beside a hinge "outer_top": stress_outer_top_to twice
    refused(
        GUIDE,
        &[("name = \"outer_bottom\"", "name = \"outer_top_to\"")],
        "network.hinges[1].name",
        &[
            "\"outer_top_to\" gives the output \"stress_outer_top_to\"",
            "rename one",
        ],
    );
}

/// Case 12: a parameter named as the expressions' constant or a function.
#[test]
fn names_the_expressions_reserve_are_refused() {
    for (name, why) in [
        ("pi", "the constant π"),
        ("sqrt", "a function"),
        ("deg", "pi / 180"),
    ] {
        refused(
            LEVER,
            &[("[\"r\", \"length\"]", &format!("[\"{name}\", \"length\"]"))],
            "network.parameters[0][0]",
            &[&format!("\"{name}\" cannot name a parameter"), why],
        );
    }
}

/// Case 13: a point, or a parameter's pair, of three values.
#[test]
fn points_have_exactly_two_coordinates() {
    refused(
        LEVER,
        &[(
            "start = [\"0\", \"-4 - 2*r\"]",
            "start = [\"0\", \"-4 - 2*r\", \"banana\"]",
        )],
        "network.hinges[0].start",
        &["invalid length 3", "exactly two"],
    );
    refused(
        LEVER,
        &[("[\"r\", \"length\"]", "[\"r\", \"length\", \"x\"]")],
        "network.parameters[0]",
        &["invalid length 3"],
    );
    refused(
        LEVER,
        &[(
            LINK,
            "link = { from = [\"0\"], to = [\"arm + 2\", \"0\"], width = \"8\" }",
        )],
        "network.bodies[0].link.from",
        &["invalid length 1"],
    );
}

/// Case 16: the network's faults that were told by another (a free body, a port on no
/// solid, a part in two pieces) or not told at all.
#[test]
fn each_fault_of_a_description_is_named_by_its_key() {
    // no body but the ground: no empty list of the known ones
    let no_body = format!("[[network.bodies]]\nname = \"lever\"\n{LINK}\n");
    refused(
        LEVER,
        &[(no_body.as_str(), "")],
        "network.hinges[0].to",
        &["no body but \"ground\"", "[[network.bodies]]"],
    );
    // two grounds, as two bodies of one name
    let twice = "[[network.bodies]]\nname = \"ground\"\noutline = [[\"-9\", \"-9\"], [\"-5\", \"-9\"], [\"-5\", \"-5\"]]\n\n";
    let both = format!("{twice}{twice}[[network.bodies]]\nname = \"lever\"");
    refused(
        LEVER,
        &[("[[network.bodies]]\nname = \"lever\"", &both)],
        "network.bodies[1].name",
        &["\"ground\" is named twice"],
    );
    // an outline of two points: no polygon (and not "no outline or link")
    refused(
        LEVER,
        &[(LINK, "outline = [[\"0\", \"-4\"], [\"arm\", \"-4\"]]")],
        "network.bodies[0].outline",
        &["at least three points, not 2"],
    );
    // an outline crossing itself (a bow tie), not "port ... lies on no solid"
    let bow =
        "outline = [[\"0\", \"-4\"], [\"arm + 2\", \"4\"], [\"arm + 2\", \"-4\"], [\"0\", \"4\"]]";
    refused(
        LEVER,
        &[(LINK, bow)],
        "variables[0].upper",
        &[
            "body \"lever\" (network.bodies[0].outline) crosses itself",
            "in order",
        ],
    );
    // a hinge of no length whose length the design makes zero, not "free to move"
    refused(
        GUIDE,
        &[("l = \"L\"", "l = \"L - 22\"")],
        "variables[0].upper",
        &["\"outer_top\" (network.hinges[0]): its length 0 m is not positive"],
    );
}
