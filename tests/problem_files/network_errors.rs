//! A flexure network's description refused (model = "network", issue 25): each fault named
//! with its key and what is wrong. Kept apart from `refused.toml`, whose cases the JSON
//! Schema must refuse too: none of these can be told by a schema (names of the file's own
//! bodies, relations between tables, values at a design).

use std::path::Path;

use flexopt::problem::Problem;

const FILE: &str = "problems/wei2017_network.toml";

/// The file with each `[from, to]` made in order (each `from` must occur), parsed: its
/// error's key and message.
fn refused(edits: &[(&str, &str)]) -> (String, String) {
    refused_in(FILE, edits)
}

fn says(edits: &[(&str, &str)], key: &str, words: &[&str]) {
    let (k, shown) = refused(edits);
    assert_eq!(k, key, "{shown}");
    assert!(
        shown.contains(&format!("`{key}`")),
        "the key is named: {shown}"
    );
    for w in words {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
}

#[test]
fn the_shipped_network_is_read() {
    assert!(Problem::load(Path::new(FILE)).is_ok());
}

#[test]
fn a_hinge_joining_a_body_to_itself_is_refused() {
    says(
        &[(
            "from = \"middle\"\nto = \"output\"",
            "from = \"middle\"\nto = \"middle\"",
        )],
        "network.hinges[1].to",
        &["joins \"middle\" to itself"],
    );
}

#[test]
fn a_body_joined_to_nothing_is_refused() {
    says(
        &[(
            "on_axis = [\"y\"]",
            "on_axis = [\"y\"]\n\n[[network.bodies]]\nname = \"spare\"",
        )],
        "network.bodies[3].name",
        &["\"spare\" is joined to nothing"],
    );
}

/// Without the output block's mirror axis nothing holds the quarter along x: the free body
/// and its direction are named, at the middle of the bounds.
#[test]
fn rigid_body_motion_left_names_the_free_body_and_its_direction() {
    let edits = [
        (
            "name = \"output\"              # the output block, cut by the other axis\non_axis = [\"y\"]",
            "name = \"output\"",
        ),
        ("across = \"x\"", ""),
    ];
    let (key, shown) = refused(&edits);
    assert_eq!(key, "variables[0].upper", "{shown}");
    for w in [
        "is free to move (",
        "network.bodies[",
        "middle of the bounds",
    ] {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
}

#[test]
fn an_unknown_name_in_an_expression_is_refused_with_its_position() {
    says(
        &[("angle = \"delta2\"", "angle = \"delta9\"")],
        "network.hinges[0].angle",
        &["delta9", "at character 1"],
    );
}

#[test]
fn a_division_by_zero_at_the_design_names_the_expression() {
    says(
        &[("angle = \"delta4\"", "angle = \"delta4/(l3 - l3)\"")],
        "variables[0].upper",
        &["network.hinges[1].angle", "`(l3 - l3)` is zero"],
    );
}

#[test]
fn a_port_on_the_ground_is_refused() {
    says(
        &[(
            "[network.input]\nbody = \"input\"",
            "[network.input]\nbody = \"ground\"",
        )],
        "network.input.body",
        &["on the ground"],
    );
}

#[test]
fn an_unknown_body_is_refused_with_the_known_ones() {
    says(
        &[("from = \"input\"", "from = \"inptu\"")],
        "network.hinges[0].from",
        &["unknown body \"inptu\"", "\"input\""],
    );
}

#[test]
fn a_dimension_the_hinges_kind_has_not_is_refused() {
    says(
        &[(
            "l = \"l2\"\nt = \"t2\"",
            "l = \"l2\"\nt = \"t2\"\nr = \"t2\"",
        )],
        "network.hinges[0].r",
        &["unknown key \"r\" of a strip hinge", "\"l\", \"t\""],
    );
}

/// `file` with each `[from, to]` made in order, parsed: its error's key and message.
fn refused_in(file: &str, edits: &[(&str, &str)]) -> (String, String) {
    let mut text = std::fs::read_to_string(file).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "fixture text {from:?} not in {file}");
        text = text.replacen(from, to, 1);
    }
    let Err(e) = Problem::parse(Path::new("net.toml"), &text) else {
        panic!("the description must be refused");
    };
    (e.key.clone(), e.to_string())
}

const LEVER: &str = "problems/lever_network.toml";
const F1_LIMIT: &str =
    "\n[[constraints]]\noutput = \"f1\"\nunit = \"Hz\"\nlower = 1000\n\n[part]\n";

/// The natural frequencies as a limit: refused, with the reason, where the network cannot
/// give them (issue 25).
#[test]
fn a_frequency_the_network_cannot_give_is_refused_with_why() {
    // a quarter standing on its output's image, its input across no axis: the stack has no
    // far end
    let (key, shown) = refused_in(
        FILE,
        &[
            ("\n[part]\n", F1_LIMIT),
            (
                "preload = \"40 N\"",
                "preload = \"40 N\"\nstiffness = \"20 N/um\"",
            ),
            ("across = \"y\"\n", ""),
        ],
    );
    assert!(key.starts_with("constraints["), "{key}: {shown}");
    assert!(
        shown.contains("the stack's far end has no place"),
        "{shown}"
    );
    // the input stands on the actuator in every mode
    let (key, shown) = refused_in(
        LEVER,
        &[("\n[part]\n", F1_LIMIT), ("stiffness = \"60 N/um\"", "")],
    );
    assert!(key.starts_with("constraints["), "{key}: {shown}");
    assert!(shown.contains("needs the actuator's stiffness"), "{shown}");
    // the bodies' masses need a density
    let (key, shown) = refused_in(
        LEVER,
        &[
            ("\n[part]\n", F1_LIMIT),
            (
                "preset = \"al7075-t6\"",
                "youngs_modulus = \"71.7 GPa\"\npoisson_ratio = 0.33\nyield_strength = \"503 MPa\"",
            ),
        ],
    );
    assert!(key.starts_with("constraints["), "{key}: {shown}");
    assert!(shown.contains("needs the material's density"), "{shown}");
}

#[test]
fn a_payload_on_the_input_is_refused() {
    let (key, shown) = refused_in(
        LEVER,
        &[(
            "[network.input]\nbody = \"lever\"",
            "[network.input]\nbody = \"lever\"\npayload = \"10 g\"",
        )],
    );
    assert_eq!(key, "network.input.payload", "{shown}");
    assert!(shown.contains("give the payload to an output"), "{shown}");
}

/// A first output written as the input (a stage read where it is pushed) is read: its
/// stiffness with the input held is infinite, so `k_out_blocked` is left out and says why,
/// and with the actuator's spring `k_out_actuated` is `k_in + k_a` exactly.
#[test]
fn a_first_output_at_the_input_is_read_without_its_blocked_stiffness() {
    let text = std::fs::read_to_string(LEVER).unwrap().replacen(
        "at = [\"arm\", \"0\"]",
        "at = [\"a\", \"0\"]",
        1,
    );
    let p = Problem::parse(Path::new("net.toml"), &text).unwrap();
    let m = p.model();
    let blocked = m.output_index("k_out_blocked").unwrap();
    let why = m.unavailable(blocked).expect("left out");
    assert!(why.contains("the first output is the input"), "{why}");
    assert!(!m.available_outputs().contains(&blocked));
    let x = [1.174e-3, 1.174e-3, 6e-3, 40e-3];
    let names = ["k_in", "k_out", "k_out_actuated", "amplification"];
    let wanted: Vec<usize> = names.iter().map(|n| m.output_index(n).unwrap()).collect();
    let mut v = [0.0; 4];
    m.evaluate(&x, &wanted, &mut v);
    let k_a = 60e6;
    assert!(
        (v[1] / v[0] - 1.0).abs() < 1e-12,
        "k_out {} k_in {}",
        v[1],
        v[0]
    );
    assert!(
        (v[2] / (v[0] + k_a) - 1.0).abs() < 1e-12,
        "{} against {}",
        v[2],
        v[0] + k_a
    );
    assert!((v[3] - 1.0).abs() < 1e-12, "{}", v[3]);
}

/// A block held by one strip along the mirror axis `x`, pulled along it: the strip is its
/// own mirror image.
const ON_AXIS: &str = r#"
name = "plunger"
model = "network"

[material]
preset = "al7075-t6"

[network]
width = "10 mm"
unit = "mm"
parameters = [["l", "length"], ["t", "length"]]
mirror = ["x"]

[[network.bodies]]
name = "block"
on_axis = ["x"]
outline = [["l", "-5"], ["l + 10", "-5"], ["l + 10", "5"], ["l", "5"]]

[[network.bodies]]
name = "plate"
on_axis = ["x"]
outline = [["l + 15", "-5"], ["l + 25", "-5"], ["l + 25", "5"], ["l + 15", "5"]]

[[network.hinges]]
name = "leaf"
kind = "strip"
from = "ground"
to = "block"
start = ["0", "0"]
angle = "0"
l = "l"
t = "t"

[[network.hinges]]
name = "tie"
kind = "strip"
from = "block"
to = "plate"
start = ["l + 10", "3"]
angle = "0"
l = "5"
t = "t"

[network.input]
body = "block"
at = ["l + 5", "0"]
direction = ["1", "0"]

[[network.outputs]]
name = "tip"
body = "plate"
at = ["l + 25", "0"]
direction = ["1", "0"]

[actuator]
nominal_stroke = "15 um"
preload = "20 N"
stiffness = "60 N/um"

[[variables]]
name = "l"
unit = "mm"
value = 10

[[variables]]
name = "t"
unit = "mm"
lower = 0.5
upper = 1.5

[objective]
maximize = "k_in"
"#;

/// A flexure on a mirror axis would be counted twice by the half (its stiffness doubled);
/// it is refused with its key, while the same part without the mirror axis is read.
#[test]
fn a_flexure_lying_on_a_mirror_axis_is_refused() {
    let Err(e) = Problem::parse(Path::new("net.toml"), ON_AXIS) else {
        panic!("a flexure on the mirror axis must be refused");
    };
    let shown = e.to_string();
    for w in [
        "hinge \"leaf\" (network.hinges[0]) lies on the mirror axis \"x\"",
        "middle of the bounds",
        "move it off the axis",
    ] {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
    // the tie stands 3 mm off the axis: only the leaf is named
    assert!(!shown.contains("\"tie\""), "{shown}");
    let whole = ON_AXIS
        .replace("mirror = [\"x\"]\n", "")
        .replace("on_axis = [\"x\"]\n", "");
    assert!(Problem::parse(Path::new("net.toml"), &whole).is_ok());
}
