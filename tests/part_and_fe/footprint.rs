//! The part's footprint as outputs (issue 51): `part_width` and `part_height` equal the
//! bounding box of the outline the part is built with, `pocket_length` is the actuator
//! pocket's rule plus the stack's length, and their gradients equal central differences;
//! the same for every shipped network with a part.

use crate::common;

use common::{random_design, rng, table1_bounds, wei2017_settings, MM};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::{build_part, Model, PartMaker};
use flexopt::part::Part;
use flexopt::problem::Problem;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// Part sizes drawn wide enough that many random designs make a part.
fn settings(r: &mut ChaCha8Rng) -> PartSettings {
    PartSettings {
        link_thickness: r.random_range(0.5..4.0) * MM,
        fillet_radius: r.random_range(0.0..0.4) * MM,
        input_block_width: r.random_range(2.0..8.0) * MM,
        input_block_height: r.random_range(6.0..16.0) * MM,
        output_block_width: r.random_range(2.0..12.0) * MM,
        output_block_height: r.random_range(2.0..8.0) * MM,
        min_slot: r.random_range(0.0..0.5) * MM,
        actuator_length: Some(r.random_range(5.0..30.0) * MM),
        actuator_height: None,
        enforce: true,
    }
}

fn bridge(part: PartSettings) -> Bridge {
    let mut s = wei2017_settings();
    s.part = part;
    Bridge::new(s)
}

fn outputs(model: &Bridge) -> [usize; 3] {
    ["part_width", "part_height", "pocket_length"].map(|n| model.output_index(n).unwrap())
}

#[test]
fn the_footprint_is_the_outlines_bounding_box_to_1e_9_mm() {
    let mut r = rng(5151);
    let mut made = 0;
    for _ in 0..300 {
        let model = bridge(settings(&mut r));
        let x = random_design(&mut r);
        let Ok(part) = build_part(&model, &x) else {
            continue;
        };
        made += 1;
        let wanted = outputs(&model);
        let mut out = [0.0; 3];
        Model::evaluate(&model, &x, &wanted, &mut out);
        let [x0, y0, x1, y1] = part.bounding_box;
        for (what, model_value, part_value) in
            [("width", out[0], x1 - x0), ("height", out[1], y1 - y0)]
        {
            assert!(
                (model_value - part_value).abs() < 1e-9 * MM,
                "{what}: output {model_value} m, outline {part_value} m at {x:?}"
            );
        }
        // the pocket's rule is the room less the stack's length
        let rules = model.rules();
        let mut m = vec![0.0; rules.len()];
        model.rule_margins(&x, &mut m);
        let pocket = m[rules
            .iter()
            .position(|r| r.name == "actuator_pocket")
            .unwrap()];
        let length = model.settings.part.actuator_length.unwrap();
        assert!(
            (out[2] - length - pocket).abs() < 1e-12,
            "pocket_length {} m, rule {pocket} m + stack {length} m",
            out[2]
        );
    }
    assert!(made >= 30, "only {made} of 300 designs made a part");
}

#[test]
fn the_footprints_gradients_equal_central_differences() {
    let mut r = rng(5152);
    let (mut compared, mut kinks) = (0, 0);
    for _ in 0..200 {
        let model = bridge(settings(&mut r));
        let x = random_design(&mut r);
        let wanted = outputs(&model);
        let n = x.len();
        let (mut out, mut jac) = ([0.0; 3], vec![0.0; 3 * n]);
        model.evaluate_with_gradient(&x, &wanted, &mut out, &mut jac);
        for p in 0..n {
            let (lo, hi) = table1_bounds()[p];
            let h = 1e-6 * (hi - lo);
            let (c, k) = differences(&model, &x, p, h, &wanted, (&out, &jac), "");
            compared += c;
            kinks += k;
        }
    }
    assert!(
        compared > 4000 && kinks * 50 < compared,
        "{compared} compared, {kinks} at kinks"
    );
}

/// Each of the outputs `wanted` (valued `at.0`, gradients `at.1` row-major) against central
/// differences of step `h` along parameter `p` at `x`: how many compared, and how many skipped
/// at a kink. The footprint is a maximum over corners: where the farthest corner changes
/// within the step the one-sided differences disagree and there is no derivative.
fn differences(
    model: &dyn Model,
    x: &[f64],
    p: usize,
    h: f64,
    wanted: &[usize],
    at: (&[f64], &[f64]),
    what: &str,
) -> (usize, usize) {
    let (out, jac) = at;
    let n = x.len();
    let (mut up, mut down) = (x.to_vec(), x.to_vec());
    up[p] += h;
    down[p] -= h;
    let (mut ou, mut od) = (vec![0.0; wanted.len()], vec![0.0; wanted.len()]);
    model.evaluate(&up, wanted, &mut ou);
    model.evaluate(&down, wanted, &mut od);
    let (mut compared, mut kinks) = (0, 0);
    for i in 0..wanted.len() {
        let (forward, backward) = ((ou[i] - out[i]) / h, (out[i] - od[i]) / h);
        let exact = jac[i * n + p];
        if (forward - backward).abs() > 1e-4 * exact.abs() + 1e-7 {
            kinks += 1;
            continue;
        }
        let fd = (ou[i] - od[i]) / (2.0 * h);
        assert!(
            (fd - exact).abs() <= 1e-6 * exact.abs() + 1e-9,
            "{what} output {i}: d/dx{p} exact {exact}, differences {fd}"
        );
        compared += 1;
    }
    (compared, kinks)
}

/// The shipped networks with a part: a lever, a guide, a Scott-Russell mechanism, and three
/// described on a half or a quarter (the rhombus, wei2017's bridge, the two-stage
/// amplifier), whose outlines are the description's images about the mirror axes.
const NETWORKS: [&str; 6] = [
    "problems/lever_network.toml",
    "problems/guide_network.toml",
    "problems/scott_russell_network.toml",
    "problems/rhombus_network.toml",
    "problems/wei2017_network.toml",
    "problems/bridge_lever_network.toml",
];

fn network_outputs(p: &Problem) -> [usize; 2] {
    ["part_width", "part_height"].map(|n| p.model().output_index(n).unwrap())
}

#[test]
fn a_networks_footprint_is_its_outlines_bounding_box_to_1e_9_mm() {
    let mut r = rng(5153);
    for file in NETWORKS {
        let p = Problem::load(Path::new(file)).unwrap();
        let wanted = network_outputs(&p);
        let (mut made, mut tried) = (0, 0);
        // random designs of a tightly packed part (wei2017's) seldom make one
        while made < 20 && tried < 2000 {
            tried += 1;
            let x = common::design_within_bounds(&p, &mut r);
            let Some(Ok(spec)) = p.mechanism().part_spec(&x) else {
                continue;
            };
            let Ok(part) = Part::build(&spec) else {
                continue;
            };
            made += 1;
            let mut out = [0.0; 2];
            p.model().evaluate(&x, &wanted, &mut out);
            let [x0, y0, x1, y1] = part.bounding_box;
            for (what, model_value, part_value) in
                [("width", out[0], x1 - x0), ("height", out[1], y1 - y0)]
            {
                assert!(
                    (model_value - part_value).abs() < 1e-9 * MM,
                    "{file}: {what}: output {model_value} m, outline {part_value} m at {x:?}"
                );
            }
        }
        println!("{file}: {made} parts of {tried} designs");
        assert!(
            made >= 10,
            "{file}: only {made} of {tried} designs made a part"
        );
    }
}

#[test]
fn a_networks_footprint_gradients_equal_central_differences() {
    let mut r = rng(5154);
    for file in NETWORKS {
        let p = Problem::load(Path::new(file)).unwrap();
        let model = p.model();
        let wanted = network_outputs(&p);
        let (mut compared, mut kinks) = (0, 0);
        for _ in 0..40 {
            let x = common::design_within_bounds(&p, &mut r);
            let n = x.len();
            let (mut out, mut jac) = ([0.0; 2], vec![0.0; 2 * n]);
            model.evaluate_with_gradient(&x, &wanted, &mut out, &mut jac);
            if !out[0].is_finite() {
                continue;
            }
            for v in p.variables.iter().filter(|v| !v.fixed) {
                let q = v.parameter;
                let h = 1e-6 * (v.upper - v.lower);
                let (c, k) = differences(model, &x, q, h, &wanted, (&out, &jac), file);
                compared += c;
                kinks += k;
            }
        }
        println!("{file}: {compared} compared, {kinks} at kinks");
        assert!(
            compared >= 40 && kinks * 20 < compared,
            "{file}: {compared} compared, {kinks} at kinks"
        );
    }
}

#[test]
fn a_network_without_a_part_says_its_footprint_needs_one() {
    let text = std::fs::read_to_string("problems/lever_network.toml").unwrap();
    let start = text.find("[part]").unwrap();
    let end = text[start + 1..]
        .find("\n[")
        .map_or(text.len(), |e| start + 1 + e);
    let bare = format!("{}{}", &text[..start], &text[end..]);
    let p = Problem::parse(Path::new("lever_no_part.toml"), &bare).unwrap();
    let i = p.model().output_index("part_width").unwrap();
    let why = p.model().unavailable(i).unwrap();
    assert!(why.contains("[part]"), "{why}");
}
