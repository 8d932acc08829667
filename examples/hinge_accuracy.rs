//! The accuracy table of the hinge kinds: over a grid of each kind's dimensionless ratios,
//! the closed forms against the numerical integration of the profile (the same beam model:
//! they must agree to rounding) and against the finite elements of the single hinge (the
//! 2D solid: where beam theory can be trusted), the notch's stress concentration by its
//! formula against the FE's, and for the circular notch the error of Paros and Weisbord's
//! simplified rotational compliance.
//!
//! `cargo run --release --example hinge_accuracy` writes `results/hinges/accuracy.json` and
//! `results/hinges/accuracy.md` (the table the README shows); `scripts/regenerate.sh` runs
//! it, and `scripts/check_results.sh` checks the committed files come out the same.

use std::path::Path;

use flexopt::fe::hinge::single_hinge;
use flexopt::fe::{Elastic, Idealization};
use flexopt::model::hinge::{Compliance, HingeKind};
use flexopt::model::material::Material;
use flexopt::report::{write_atomic, write_json};
use serde::Serialize;

const WIDTH: f64 = 10e-3;

#[derive(Serialize)]
struct Row {
    kind: HingeKind,
    ratio: String,
    dims_mm: Vec<f64>,
    closed: Compliance<f64>,
    numerical: Compliance<f64>,
    /// The largest relative difference of the four, closed form against numerical.
    closed_vs_numerical: f64,
    fe: Compliance<f64>,
    /// `(closed - FE) / FE`, per coefficient.
    deviation: Compliance<f64>,
    /// The FE's own estimated error (the largest of the coefficients'; the last
    /// refinement's change where the extrapolation does not apply).
    fe_error: f64,
    /// FE peak von Mises stress over the beam stress at the thinnest section, pure moment.
    concentration: f64,
    /// The same by the kind's formula ([`HingeKind::stress_concentration`]).
    concentration_formula: f64,
    /// Paros and Weisbord's simplified c33 against the exact integral (circular only).
    #[serde(skip_serializing_if = "Option::is_none")]
    paros_weisbord: Option<f64>,
    elements: Vec<usize>,
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b
}

fn main() {
    let m = Material::al7075_t6();
    let fe_material = Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
        density: m.density,
    };
    let mm = 1e-3;
    let mut grid: Vec<(HingeKind, String, Vec<f64>)> = Vec::new();
    for lt in [2.0, 5.0, 10.0, 20.0] {
        grid.push((
            HingeKind::Strip,
            format!("l/t = {lt}"),
            vec![lt * 0.4 * mm, 0.4 * mm],
        ));
    }
    for tr in [0.05, 0.1, 0.2, 0.5, 1.0] {
        grid.push((
            HingeKind::Circular,
            format!("t/r = {tr}"),
            vec![1.0 * mm, tr * mm],
        ));
    }
    for ba in [0.25, 0.5, 1.0, 2.0] {
        let (a, b) = (2.0 * mm, 2.0 * ba * mm);
        grid.push((
            HingeKind::Elliptical,
            format!("b/a = {ba}, t/b = 0.2"),
            vec![a, b, 0.2 * b],
        ));
    }
    for rl in [0.025, 0.05, 0.1, 0.25, 0.5] {
        grid.push((
            HingeKind::CornerFilleted,
            format!("r/l = {rl}, t/l = 0.1"),
            vec![4.0 * mm, 0.4 * mm, rl * 4.0 * mm],
        ));
    }
    let mut rows = Vec::new();
    for (kind, ratio, dims) in grid {
        let closed = kind.compliance(&dims, WIDTH, &m);
        let numerical = kind.compliance_numerical(&dims, WIDTH, &m);
        let fe = single_hinge(kind, &dims, WIDTH, &fe_material, Idealization::PlaneStress)
            .unwrap_or_else(|e| panic!("{kind:?} {ratio}: {e}"));
        let f = fe.compliance();
        let pairs = |a: &Compliance<f64>, b: &Compliance<f64>| {
            [
                (a.c11, b.c11),
                (a.c22, b.c22),
                (a.c23, b.c23),
                (a.c33, b.c33),
            ]
        };
        let closed_vs_numerical = pairs(&closed, &numerical)
            .iter()
            .map(|(a, b)| rel(*a, *b).abs())
            .fold(0.0, f64::max);
        let fe_error = fe.error();
        let paros_weisbord = (kind == HingeKind::Circular).then(|| {
            let (r, t) = (dims[0], dims[1]);
            let simplified = 9.0 * std::f64::consts::PI * r.sqrt()
                / (2.0 * m.youngs_modulus * WIDTH * t.powf(2.5));
            rel(simplified, closed.c33)
        });
        rows.push(Row {
            kind,
            ratio,
            dims_mm: dims.iter().map(|d| d / mm).collect(),
            deviation: Compliance {
                c11: rel(closed.c11, f.c11),
                c22: rel(closed.c22, f.c22),
                c23: rel(closed.c23, f.c23),
                c33: rel(closed.c33, f.c33),
            },
            closed,
            numerical,
            closed_vs_numerical,
            fe: f,
            fe_error,
            concentration: fe.concentration.value,
            concentration_formula: kind.stress_concentration(&dims),
            paros_weisbord,
            elements: fe.elements,
        });
    }
    let pct = |v: f64| format!("{:+.1} %", 100.0 * v);
    let mut md = String::from(
        "| kind | ratio | closed form vs numerical integration | c33: closed vs FE | c22: closed vs FE | \
         c11: closed vs FE | FE error | stress concentration: formula / FE | Paros-Weisbord simplified c33 |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in &rows {
        md += &format!(
            "| {} | {} | {:.0e} | {} | {} | {} | {:.0e} | {} | {} |\n",
            r.kind.name(),
            r.ratio,
            r.closed_vs_numerical.max(1e-16),
            pct(r.deviation.c33),
            pct(r.deviation.c22),
            pct(r.deviation.c11),
            r.fe_error.max(1e-16),
            if r.kind == HingeKind::Strip {
                "- (sharp clamp)".to_string()
            } else {
                format!("{:.2} / {:.2}", r.concentration_formula, r.concentration)
            },
            r.paros_weisbord.map_or("-".into(), pct),
        );
    }
    // scripts/check_results.sh regenerates into a folder of its own
    let results = std::env::var("RESULTS").unwrap_or_else(|_| "results".into());
    let dir = Path::new(&results).join("hinges");
    std::fs::create_dir_all(&dir).unwrap();
    write_json(&dir.join("accuracy.json"), &rows).unwrap();
    write_atomic(&dir.join("accuracy.md"), md.as_bytes()).unwrap();
    print!("{md}");
}
