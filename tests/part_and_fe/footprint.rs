//! The part's footprint as outputs (issue 51): `part_width` and `part_height` equal the
//! bounding box of the outline the part is built with, `pocket_length` is the actuator
//! pocket's rule plus the stack's length, and their gradients equal central differences.

use crate::common;

use common::{random_design, rng, table1_bounds, wei2017_settings, MM};
use flexopt::model::bridge::part::PartSettings;
use flexopt::model::bridge::Bridge;
use flexopt::model::{build_part, Model, PartMaker};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

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
            let (mut up, mut down) = (x, x);
            up[p] += h;
            down[p] -= h;
            let (mut ou, mut od) = ([0.0; 3], [0.0; 3]);
            Model::evaluate(&model, &up, &wanted, &mut ou);
            Model::evaluate(&model, &down, &wanted, &mut od);
            for i in 0..3 {
                // a maximum over vertices: where the farthest vertex changes within the step
                // the one-sided differences disagree and there is no derivative
                let (forward, backward) = ((ou[i] - out[i]) / h, (out[i] - od[i]) / h);
                let exact = jac[i * n + p];
                if (forward - backward).abs() > 1e-4 * exact.abs() + 1e-7 {
                    kinks += 1;
                    continue;
                }
                let fd = (ou[i] - od[i]) / (2.0 * h);
                assert!(
                    (fd - exact).abs() <= 1e-6 * exact.abs() + 1e-9,
                    "output {i}: d/dx{p} exact {exact}, differences {fd}"
                );
                compared += 1;
            }
        }
    }
    assert!(
        compared > 4000 && kinks * 50 < compared,
        "{compared} compared, {kinks} at kinks"
    );
}
