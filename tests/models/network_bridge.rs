//! wei2017 written as a flexure network (problems/wei2017_network.toml, issue 25) against
//! the built-in bridge: the same outputs and gradients at random designs of Table 1, and
//! every output's gradient against central differences.

use std::path::Path;

use crate::common::{random_design, rel, rng, table1_bounds, wei2017};
use crate::network_shipped::worst_central_difference;
use flexopt::model::Model;
use flexopt::problem::Problem;

fn network() -> Problem {
    Problem::load(Path::new("problems/wei2017_network.toml")).unwrap()
}

/// The outputs both models have, by name.
const SHARED: [&str; 10] = [
    "amplification",
    "k_in",
    "k_out",
    "stress_max",
    "stress_b",
    "stress_d",
    "span_x",
    "span_y",
    "stroke_in",
    "stroke_out",
];

#[test]
fn the_network_gives_the_bridges_outputs_and_gradients() {
    let p = network();
    let net = p.model();
    let bridge = wei2017();
    let index = |m: &dyn Model| -> Vec<usize> {
        SHARED.iter().map(|n| m.output_index(n).unwrap()).collect()
    };
    let (wn, wb) = (index(net), index(&bridge));
    let n = 8;
    let mut r = rng(25);
    let (mut worst_value, mut worst_gradient) = ((0.0f64, ""), (0.0f64, ""));
    for _ in 0..25 {
        let x = random_design(&mut r);
        let (mut vn, mut jn) = (vec![0.0; SHARED.len()], vec![0.0; SHARED.len() * n]);
        let (mut vb, mut jb) = (vec![0.0; SHARED.len()], vec![0.0; SHARED.len() * n]);
        net.evaluate_with_gradient(&x, &wn, &mut vn, &mut jn);
        Model::evaluate_with_gradient(&bridge, &x, &wb, &mut vb, &mut jb);
        for (i, name) in SHARED.iter().enumerate() {
            let d = rel(vn[i], vb[i], 1e-300);
            if d > worst_value.0 {
                worst_value = (d, name);
            }
            let scale = (0..n).fold(0.0f64, |m, j| m.max(jb[i * n + j].abs()));
            for j in 0..n {
                let d = (jn[i * n + j] - jb[i * n + j]).abs() / scale.max(1e-300);
                if d > worst_gradient.0 {
                    worst_gradient = (d, name);
                }
            }
        }
    }
    eprintln!("network vs bridge: values {worst_value:?}, gradients {worst_gradient:?}");
    assert!(worst_value.0 < 1e-10, "{worst_value:?}");
    assert!(worst_gradient.0 < 1e-10, "{worst_gradient:?}");
}

/// Every output's exact gradient against central differences, scaled by the bounds, where
/// no kink of a max lies within the stencil (the one-sided slopes agree).
#[test]
fn every_network_output_has_its_central_difference_gradient() {
    let p = network();
    let mut r = rng(26);
    let designs: Vec<Vec<f64>> = (0..25).map(|_| random_design(&mut r).to_vec()).collect();
    let (worst, kinks, checks) =
        worst_central_difference(p.model(), &designs, &table1_bounds(), &[]);
    eprintln!(
        "network gradients vs central differences: worst {worst:?}, {kinks} kinks in {checks}"
    );
    assert!(kinks * 50 < checks, "{kinks} kinks in {checks} checks");
    assert!(worst.0 < 1e-6, "{worst:?}");
}

/// The network's mirror image is the bridge's, every angle negated, and has the same
/// outputs up to sign (the file's quarter stands off the axes, for its part, so it is
/// a reflection as a mechanism, not expression by expression); a description that is not
/// symmetric about the `x` axis (hinge d started 0.1 mm off the link's end) has none.
#[test]
fn the_networks_mirror_image_is_the_bridges_with_the_same_outputs_up_to_sign() {
    let p = network();
    let net = p.model();
    let bridge = wei2017();
    // the mechanism's outputs: the part drawn from the quarter off the axes is another
    // part at the image (below)
    let all: Vec<usize> = net
        .available_outputs()
        .into_iter()
        .filter(|&k| !net.outputs()[k].name.starts_with("part_"))
        .collect();
    let mut r = rng(26);
    for _ in 0..25 {
        let x = random_design(&mut r);
        let (mut y, mut yb) = (x, x);
        assert!(net.mirror(&mut y), "{x:?}");
        assert!(Model::mirror(&bridge, &mut yb));
        assert_eq!(y, yb, "the bridge's mirror image");
        let (mut vx, mut vy) = (vec![0.0; all.len()], vec![0.0; all.len()]);
        net.evaluate(&x, &all, &mut vx);
        net.evaluate(&y, &all, &mut vy);
        for ((a, b), &k) in vx.iter().zip(&vy).zip(&all) {
            assert!(
                rel(a.abs(), b.abs(), 1e-300) < 1e-12 && a.is_finite(),
                "{}: {a} against {b}",
                net.outputs()[k].name
            );
        }
        let mut back = y;
        assert!(net.mirror(&mut back));
        assert_eq!(back, x, "the mirror image's mirror image");
    }
    let text = std::fs::read_to_string("problems/wei2017_network.toml").unwrap();
    let off = text.replacen(
        "start = [\"-5 - l4*cos(delta4)\", \"4.5 + l2*sin(delta2) + l3*sin(delta3)\"]",
        "start = [\"-5 - l4*cos(delta4)\", \"4.5 + l2*sin(delta2) + l3*sin(delta3) + 0.1\"]",
        1,
    );
    assert_ne!(off, text);
    let asymmetric = Problem::parse(Path::new("off.toml"), &off).unwrap();
    let x = random_design(&mut r);
    let mut y = x;
    assert!(!asymmetric.model().mirror(&mut y));
    assert_eq!(y, x, "left as it was");
}

/// The study's mirror image is the problem's: wei2017's network merges its images while the
/// problem bounds mechanical outputs only, and keeps them apart once it bounds the part's
/// height, which the quarter drawn off the axes makes another at the image.
#[test]
fn a_mirror_image_with_another_part_is_none_for_a_problem_bounding_the_part() {
    use flexopt::problem::nlp::DesignNlp;
    let text = std::fs::read_to_string("problems/wei2017_network.toml").unwrap();
    let bounded =
        format!("{text}\n[[constraints]]\noutput = \"part_height\"\nunit = \"mm\"\nupper = 60\n");
    let bounded = Problem::parse(Path::new("wei2017_network_height.toml"), &bounded).unwrap();
    let plain = network();
    let height = plain.model().output_index("part_height").unwrap();
    assert!(plain.variables.iter().all(|v| !v.fixed));
    let (nlp, nlp_bounded) = (DesignNlp::new(&plain), DesignNlp::new(&bounded));
    let mut r = rng(27);
    let (mut apart, mut tried) = (0, 0);
    for _ in 0..25 {
        let x = random_design(&mut r);
        let u = nlp.scale(&x);
        let Some(image) = nlp.mirror(&u) else {
            continue;
        };
        tried += 1;
        let y = nlp.full_design(&image);
        let (mut hx, mut hy) = ([0.0], [0.0]);
        plain.model().evaluate(&x, &[height], &mut hx);
        plain.model().evaluate(&y, &[height], &mut hy);
        let same_part = rel(hx[0], hy[0], 1e-300) <= 1e-10;
        assert_eq!(
            nlp_bounded.mirror(&u).is_some(),
            same_part,
            "part_height {} against {} mm",
            hx[0] * 1e3,
            hy[0] * 1e3
        );
        apart += usize::from(!same_part);
    }
    assert!(tried >= 10 && apart >= 5, "{apart} kept apart of {tried}");
}
