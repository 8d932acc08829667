//! Every rejection rule of the problem-file format: the message names the file, the key
//! path and the bad value; the CLI exits with code 2.

use crate::common;

use std::path::Path;

use common::flexopt;
use flexopt::problem::design::parse_design;
use flexopt::problem::{Problem, ProblemError};

const FILE: &str = "problems/wei2017.toml";

fn original() -> String {
    std::fs::read_to_string(FILE).unwrap()
}

/// Parses the problem file with `from` replaced by `to` (which must occur).
fn mutated(from: &str, to: &str) -> Result<Problem, ProblemError> {
    let text = original();
    assert!(text.contains(from), "fixture text {from:?} not in {FILE}");
    Problem::parse(Path::new("mutated.toml"), &text.replacen(from, to, 1))
}

/// Asserts the error's key, and that its message contains each of `words`.
fn rejects(result: Result<Problem, ProblemError>, key: &str, words: &[&str]) -> ProblemError {
    let e = result.expect_err("the file must be rejected");
    assert_eq!(e.key, key, "{e}");
    let shown = e.to_string();
    assert!(
        shown.starts_with("mutated.toml:"),
        "the file is named: {shown}"
    );
    assert!(
        shown.contains(&format!("`{key}`")),
        "the key is named: {shown}"
    );
    for w in words {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
    e
}

#[test]
fn the_shipped_problem_is_accepted() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    assert_eq!(p.variables.len(), 8);
    assert_eq!(p.constraints.len(), 5);
    assert_eq!(p.free_variables().count(), 8);
}

#[test]
fn unknown_key() {
    let e = rejects(
        mutated("absolute = true", "absolute = true\nweight = 2"),
        "objective.weight",
        &["unknown field"],
    );
    assert!(e.position.is_some(), "TOML gives a line: {e}");
}

#[test]
fn unknown_key_in_an_array_of_tables() {
    rejects(
        mutated("lower = 0.4\nupper = 2", "lower = 0.4\nuper = 2"),
        "variables[2].uper",
        &["unknown field"],
    );
}

#[test]
fn missing_key() {
    rejects(
        mutated("model = \"bridge\"", ""),
        "model",
        &["missing field"],
    );
    rejects(
        mutated("unit = \"N/m\"\nupper = 7e6", "upper = 7e6"),
        "constraints[3].unit",
        &["missing field"],
    );
}

#[test]
fn missing_design_variable() {
    let text = original();
    let start = text.find("[[variables]]\nname = \"t4\"").unwrap();
    let end = start + text[start..].find("\n\n").unwrap();
    let cut = format!("{}{}", &text[..start], &text[end..]);
    let e = Problem::parse(Path::new("mutated.toml"), &cut).unwrap_err();
    assert_eq!(e.key, "variables");
    assert!(e.message.contains("\"t4\""), "{e}");
}

#[test]
fn lower_bound_above_upper_bound() {
    let e = rejects(
        mutated(
            "name = \"l3\"\nunit = \"mm\"\nlower = 0.5",
            "name = \"l3\"\nunit = \"mm\"\nlower = 25",
        ),
        "variables[3].lower",
        &["25", "20"],
    );
    assert!(e.position.is_some(), "{e}");
    rejects(
        mutated("lower = 7.5\nupper = 12", "lower = 13\nupper = 12"),
        "constraints[0].lower",
        &["13", "12"],
    );
}

#[test]
fn non_positive_length_and_thickness() {
    rejects(
        mutated(
            "name = \"l2\"\nunit = \"mm\"\nlower = 0.5",
            "name = \"l2\"\nunit = \"mm\"\nlower = 0",
        ),
        "variables[0].lower",
        &["positive", "0"],
    );
    rejects(
        mutated(
            "name = \"t2\"\nunit = \"mm\"\nlower = 0.4",
            "name = \"t2\"\nunit = \"mm\"\nlower = -0.4",
        ),
        "variables[2].lower",
        &["positive", "-0.4"],
    );
}

#[test]
fn non_positive_width() {
    rejects(
        mutated("width = \"10 mm\"", "width = \"0 mm\""),
        "hinge.width",
        &["positive", "\"0 mm\""],
    );
}

#[test]
fn non_positive_modulus() {
    rejects(
        mutated(
            "preset = \"al7075-t6\"",
            "preset = \"al7075-t6\"\nyoungs_modulus = \"-72 GPa\"",
        ),
        "material.youngs_modulus",
        &["positive", "\"-72 GPa\""],
    );
}

#[test]
fn nan_and_infinite_numbers() {
    rejects(
        mutated("upper = 45", "upper = nan"),
        "variables[1].upper",
        &["NaN", "finite"],
    );
    rejects(
        mutated("upper = 7e6", "upper = inf"),
        "constraints[3].upper",
        &["inf", "finite"],
    );
    rejects(
        mutated("thresholds = [12.7", "thresholds = [-inf"),
        "zones.thresholds[0]",
        &["finite"],
    );
}

#[test]
fn unknown_output() {
    rejects(
        mutated(
            "maximize = \"amplification\"",
            "maximize = \"amplificaton\"",
        ),
        "objective.maximize",
        &["\"amplificaton\"", "amplification"],
    );
    rejects(
        mutated("output = \"k_out\"", "output = \"k_output\""),
        "constraints[4].output",
        &["\"k_output\""],
    );
}

#[test]
fn unknown_unit() {
    rejects(
        mutated(
            "name = \"delta2\"\nunit = \"deg\"",
            "name = \"delta2\"\nunit = \"degrees\"",
        ),
        "variables[1].unit",
        &["\"degrees\"", "\"deg\""],
    );
    // a unit of the wrong dimension
    rejects(
        mutated("unit = \"N/m\"\nupper = 7e6", "unit = \"MPa\"\nupper = 7e6"),
        "constraints[3].unit",
        &["\"MPa\"", "\"N/m\""],
    );
    rejects(
        mutated(
            "nominal_stroke = \"17.4 um\"",
            "nominal_stroke = \"17.4 uN\"",
        ),
        "actuator.nominal_stroke",
        &["\"uN\""],
    );
}

#[test]
fn quantity_without_unit() {
    rejects(
        mutated("width = \"10 mm\"", "width = 10"),
        "hinge.width",
        &["no unit"],
    );
}

#[test]
fn unknown_material() {
    rejects(
        mutated("preset = \"al7075-t6\"", "preset = \"al6061\""),
        "material.preset",
        &["\"al6061\"", "al7075-t6"],
    );
}

#[test]
fn unknown_model_and_hinge_kind() {
    rejects(
        mutated("model = \"bridge\"", "model = \"lever\""),
        "model",
        &["\"lever\""],
    );
    rejects(
        mutated("kind = \"strip\"", "kind = \"notch\""),
        "hinge.kind",
        &["\"notch\""],
    );
}

#[test]
fn ultimate_fraction_needs_a_strength() {
    rejects(
        mutated(
            "preset = \"al7075-t6\"",
            "youngs_modulus = \"72 GPa\"\npoisson_ratio = 0.33\ndensity = \"2810 kg/m3\"",
        ),
        "constraints[2].unit",
        &["ultimate strength"],
    );
    // and a fraction of the yield strength, one
    let text = original()
        .replacen(
            "preset = \"al7075-t6\"",
            "youngs_modulus = \"72 GPa\"\npoisson_ratio = 0.33\nultimate_strength = \"505 MPa\"",
            1,
        )
        .replace("unit = \"ultimate\"", "unit = \"yield\"");
    let e = Problem::parse(Path::new("mutated.toml"), &text).unwrap_err();
    assert_eq!(e.key, "constraints[2].unit");
    assert!(e.to_string().contains("no yield strength"), "{e}");
    // with one, a yield fraction is a stress limit: 1/3 of 503 MPa for the preset
    let text = original().replace("unit = \"ultimate\"", "unit = \"yield\"");
    let p = Problem::parse(Path::new("yield.toml"), &text).unwrap();
    let c = p
        .constraints
        .iter()
        .find(|c| c.output == "stress_max")
        .unwrap();
    assert!((c.upper.unwrap() - 503e6 / 3.0).abs() < 1e-3);
}

#[test]
fn wrong_type() {
    rejects(
        mutated("starts = 300", "starts = \"many\""),
        "search.starts",
        &["invalid type"],
    );
}

#[test]
fn design_missing_a_variable_is_an_error() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    let e = parse_design(
        &p,
        "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07",
    )
    .unwrap_err();
    assert!(e.to_string().contains("problems/wei2017.toml"), "{e}");
    assert_eq!(e.key, "--design t4");
    let e = parse_design(&p, "l2=1.96,delta2=x").unwrap_err();
    assert_eq!(e.key, "--design delta2");
    assert!(e.message.contains("\"x\""));
    let e = parse_design(&p, "l9=1").unwrap_err();
    assert_eq!(e.key, "--design l9");
}

#[test]
fn design_outside_bounds_is_a_warning() {
    let p = Problem::load(Path::new(FILE)).unwrap();
    let d = parse_design(
        &p,
        "l2=25,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
    )
    .unwrap();
    assert_eq!(d.warnings.len(), 1);
    assert!(
        d.warnings[0].contains("l2 = 25 mm") && d.warnings[0].contains("[0.5, 20]"),
        "{:?}",
        d.warnings
    );
    assert!((d.x[0] - 0.025).abs() < 1e-15);
}

#[test]
fn the_command_line_exits_2_and_names_file_and_key() {
    let dir = std::env::temp_dir().join(format!("flexopt-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, original().replacen("upper = 45", "upper = -50", 1)).unwrap();
    let out = flexopt(&["eval", bad.to_str().unwrap(), "--design", "l2=1"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:") && err.contains("`variables[1].lower`"),
        "{err}"
    );
    assert!(
        out.stdout.is_empty(),
        "nothing on stdout for a rejected file"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn counts_out_of_range() {
    rejects(
        mutated("starts = 300", "starts = 9223372036854775807"),
        "search.starts",
        &["between"],
    );
    rejects(
        mutated("threads = 0", "threads = -1"),
        "search.threads",
        &["between", "-1"],
    );
}

#[test]
fn angle_bounds_at_or_beyond_a_right_angle() {
    rejects(
        mutated("upper = 45", "upper = 90"),
        "variables[1].upper",
        &["strictly between -90 and 90", "90"],
    );
}

#[test]
fn a_lone_table_bracket_names_a_key() {
    let e = Problem::parse(Path::new("mutated.toml"), "[").unwrap_err();
    assert!(!e.key.is_empty(), "{e}");
}

#[test]
fn sections_a_model_does_not_take_or_needs() {
    let prr3 = std::fs::read_to_string("problems/prr3_frequency.toml").unwrap();
    let with_hinge = prr3.replacen(
        "model = \"prr3\"",
        "model = \"prr3\"\n[hinge]\nkind = \"strip\"\nwidth = \"10 mm\"",
        1,
    );
    let e = Problem::parse(Path::new("mutated.toml"), &with_hinge).unwrap_err();
    assert_eq!(e.key, "hinge", "{e}");
    let e = mutated(
        "[hinge]\nkind = \"strip\"              # leaf hinges, compliances of Eq. 2\nwidth = \"10 mm\"             # Sec. 3: \"The width of the mechanism was fixed at w = 10 mm\"",
        "",
    )
    .unwrap_err();
    assert_eq!(e.key, "hinge", "{e}");
    assert!(e.message.contains("bridge"), "{e}");
}

#[test]
fn part_keys_are_checked_like_every_other() {
    let height = "height = \"5 mm\"";
    let with_part = |part: &str| mutated(height, &format!("{height}\n\n[part]\n{part}"));
    rejects(
        with_part("fillet_radius = \"-0.1 mm\""),
        "part.fillet_radius",
        &["-0.1 mm", "negative"],
    );
    rejects(
        with_part("link_thickness = \"0 mm\""),
        "part.link_thickness",
        &["positive"],
    );
    rejects(
        with_part("input_block_width = 6"),
        "part.input_block_width",
        &["no unit"],
    );
    rejects(
        with_part("output_block_height = \"6 N\""),
        "part.output_block_height",
        &["unit"],
    );
    rejects(
        with_part("wall = \"1 mm\""),
        "part.wall",
        &["unknown field"],
    );
    rejects(
        mutated(height, "height = \"-5 mm\""),
        "actuator.height",
        &["positive"],
    );
    rejects(
        mutated("length = \"20 mm\"", "length = \"20 kg\""),
        "actuator.length",
        &["unit"],
    );
    // a fillet of zero is allowed: the part says what it costs when it is drawn
    let p = with_part("fillet_radius = \"0 mm\"").unwrap();
    let x = parse_design(
        &p,
        "l2=1.96,delta2=4.07,t2=0.4,l3=8.1,delta3=4.01,l4=1.96,delta4=4.07,t4=0.4",
    )
    .unwrap()
    .x;
    let part = p.mechanism().part_or_error(&x).unwrap();
    assert!(part.warnings[0].contains("fillet_radius is 0"));
}
