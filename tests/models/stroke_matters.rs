//! When large deflection matters (issue 48): each shipped network at its optimum
//! (`results/<name>/optimum.json`) solved at its working stroke with the default
//! [`StrokeOptions`] (the actuator at its full free stroke and preload, 8 elements a flexure
//! and 16 for the check, 10 steps), against the linear solution of the same load. The
//! figures are the guide's table ("When large deflection matters", `networks.md`).

use std::path::Path;

use flexopt::model::large::report::StrokeOptions;
use flexopt::problem::Problem;

/// A shipped network and its figures at stroke, measured: the nonlinear output over the
/// linear minus one, in %, of `stroke_out`, the amplification, `k_in`, `k_out` (tangent),
/// `stress_max`, and the first output's motion across its direction (`None` where the
/// figure has no meaning: the guide's output is the stage's lateral motion, zero in the
/// linear model, and a port with no motion across); and the parameter that is the links'
/// inclination to the stack's axis, where the amplification comes from a small angle.
struct Measured {
    name: &'static str,
    inclination: Option<&'static str>,
    errors: [Option<f64>; 6],
}

const MEASURED: [Measured; 6] = [
    Measured {
        name: "bridge_lever_network",
        inclination: Some("delta"),
        errors: [
            Some(-0.4846),
            Some(-0.1673),
            Some(1.0667),
            Some(0.0808),
            Some(-0.3319),
            Some(1.0941),
        ],
    },
    Measured {
        name: "guide_network",
        inclination: None,
        errors: [None, None, Some(0.2994), Some(-50.2229), Some(0.1599), None],
    },
    Measured {
        name: "lever_network",
        inclination: None,
        errors: [
            Some(0.0730),
            Some(0.0842),
            Some(0.6034),
            Some(0.2629),
            Some(0.0838),
            Some(1.0359),
        ],
    },
    Measured {
        name: "rhombus_network",
        inclination: Some("delta"),
        errors: [
            Some(1.0000),
            Some(1.0000),
            Some(50.1613),
            Some(22.0025),
            Some(39.0263),
            None,
        ],
    },
    Measured {
        name: "scott_russell_network",
        inclination: Some("theta"),
        errors: [
            Some(2.6659),
            Some(0.4272),
            Some(-21.0395),
            Some(-11.1351),
            Some(0.5283),
            Some(-1.2690),
        ],
    },
    Measured {
        name: "wei2017_network",
        inclination: Some("delta3"),
        errors: [
            Some(5.5766),
            Some(5.5766),
            Some(56.1241),
            Some(18.2642),
            Some(9.8063),
            None,
        ],
    },
];

const FIGURES: [&str; 6] = [
    "stroke_out",
    "amplification",
    "k_in",
    "k_out",
    "stress_max",
    "across",
];

fn design(p: &Problem, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(format!("results/{name}/optimum.json")).unwrap();
    let optimum: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut x = vec![f64::NAN; p.mechanism.physics.parameters().len()];
    for v in &p.variables {
        x[v.parameter] = optimum["design_si"][v.name.as_str()].as_f64().unwrap();
    }
    assert!(
        x.iter().all(|v| v.is_finite()),
        "{name}: a parameter not a variable"
    );
    x
}

fn pct(a: f64, b: f64) -> f64 {
    100.0 * (a / b - 1.0)
}

fn largest(v: impl Iterator<Item = f64>) -> f64 {
    v.map(f64::abs).fold(0.0, f64::max)
}

/// Each shipped network's errors at its stroke, within 1 % of each effect (0.01 percentage
/// point at least) of the measured table; no critical point up to 4 x the stroke; 8 and 16
/// elements a flexure within 0.005 %. And the guide's rule: where the links turn by at most
/// 1 % of their inclination to the stack's axis (the bridge-lever, 0.86 %) or the mechanism
/// has none (the lever, the guide), `stroke_out`, the amplification and `stress_max` are
/// within 1 % of the linear model's; where they turn by 5 % of it or more (the
/// Scott-Russell, the rhombus, wei2017) one of them is 1 % off or more. A link's rotation
/// is the linear model's largest `rotation_*` output at the solve's linear stroke, the
/// rhombus's arm (a strip from block to block, whose ends do not turn) its chord's,
/// `(d_out cos delta + d_in sin delta) / L` from the half strokes.
#[test]
fn the_linear_models_error_at_each_shipped_networks_stroke() {
    for m in &MEASURED {
        let p = Problem::load(Path::new(&format!("problems/{}.toml", m.name))).unwrap();
        let x = design(&p, m.name);
        let model = &p.mechanism.physics;
        let all: Vec<usize> = (0..model.outputs().len()).collect();
        let mut out = vec![0.0; all.len()];
        model.evaluate(&x, &all, &mut out);
        let output = |name: &str| out[model.output_index(name).unwrap()];
        let param = |name: &str| {
            x[model
                .parameters()
                .iter()
                .position(|q| q.name == name)
                .unwrap()]
        };
        let r = p
            .mechanism
            .large
            .as_ref()
            .expect("a network solves at stroke")
            .at_stroke(&x, &StrokeOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", m.name));
        let (end, lin) = (r.at_stroke(), &r.linear);
        let finer = r.finer.as_ref().unwrap();
        let across = |q: &flexopt::model::large::report::StrokePoint| q.parasitic[0].across;
        let errors = [
            pct(end.stroke_out, lin.stroke_out),
            pct(end.amplification, lin.amplification),
            pct(end.k_in, lin.k_in),
            pct(end.k_out, lin.k_out),
            pct(end.stress_max, lin.stress_max),
            pct(across(end), across(lin)),
        ];
        // the link's rotation at the stroke, as the linear model states it
        let scale = lin.stroke_in / output("stroke_in");
        let rotation = if m.name == "rhombus_network" {
            let delta = param("delta");
            (0.5 * lin.stroke_out.abs() * delta.cos() + 0.5 * lin.stroke_in.abs() * delta.sin())
                / param("L")
        } else {
            scale
                * largest(
                    model
                        .outputs()
                        .iter()
                        .zip(&out)
                        .filter(|(o, _)| o.name.starts_with("rotation_"))
                        .map(|(_, &v)| v),
                )
        };
        let ratio = m.inclination.map(|a| rotation / param(a));
        let convergence = largest(
            [
                pct(end.stroke_out, finer.stroke_out),
                pct(end.amplification, finer.amplification),
                pct(end.k_in, finer.k_in),
                pct(end.k_out, finer.k_out),
                pct(end.stress_max, finer.stress_max),
            ]
            .into_iter(),
        );
        println!(
            "| {} | {} | {} | {:.2} | {} | {:.3} / {:.3} | {:?} | {convergence:.1e} |",
            m.name,
            errors
                .iter()
                .zip(&m.errors)
                .map(|(e, m)| m.map_or("-".to_string(), |_| format!("{e:+.6}")))
                .collect::<Vec<_>>()
                .join(" | "),
            format_args!("{:.3e} / {:.3e}", end.stroke_out, lin.stroke_out),
            1e3 * rotation,
            ratio.map_or("-".to_string(), |q| format!("{:.2} %", 100.0 * q)),
            1e3 * largest(end.parasitic.iter().map(|q| q.rotation)),
            1e3 * largest(lin.parasitic.iter().map(|q| q.rotation)),
            r.critical_load_factor,
        );
        for ((e, measured), figure) in errors.iter().zip(&m.errors).zip(FIGURES) {
            if let Some(measured) = measured {
                assert!(
                    (e - measured).abs() <= (0.01 * measured.abs()).max(0.01),
                    "{} {figure}: {e:+.4} %, measured {measured:+.4} %",
                    m.name
                );
            }
        }
        assert_eq!(r.critical_load_factor, None, "{}", m.name);
        assert!(convergence < 5e-3, "{}: n / 2n {convergence:e} %", m.name);
        let worst = largest(
            [0, 1, 4]
                .into_iter()
                .filter(|&i| m.errors[i].is_some())
                .map(|i| errors[i]),
        );
        match ratio {
            Some(q) if q > 0.05 => assert!(worst >= 0.999, "{}: {worst} % at {q}", m.name),
            Some(q) if q > 0.01 => panic!("{}: {q} between the rule's bounds", m.name),
            _ => assert!(worst < 1.0, "{}: {worst} %", m.name),
        }
    }
}
