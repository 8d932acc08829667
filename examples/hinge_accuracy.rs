//! The accuracy table of the hinge kinds: over a grid of each kind's dimensionless ratios,
//! the closed forms against the numerical integration of the profile (the same beam model:
//! they must agree to rounding) and against the finite elements of the single hinge (the
//! 2D solid: where beam theory can be trusted), the notch's stress concentration by its
//! formula against the FE's, and for the circular notch the error of Paros and Weisbord's
//! simplified rotational compliance.
//!
//! The same checks at the edge of each kind's ranges of fit ([`HingeKind::fit`]) and
//! outside them: what justifies each range.
//!
//! `cargo run --release --example hinge_accuracy` writes `results/hinges/accuracy.json` and
//! `results/hinges/accuracy.md` (the table the README shows), and `fit_ranges.json` and
//! `fit_ranges.md` (the table `docs/hinges.md` shows); `scripts/regenerate.sh` runs it, and
//! `scripts/check_results.sh` checks the committed files come out the same.

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
    let (edges, md) = fit_edges(&m, &fe_material);
    write_json(&dir.join("fit_ranges.json"), &edges).unwrap();
    write_atomic(&dir.join("fit_ranges.md"), md.as_bytes()).unwrap();
    print!("{md}");
}

/// One hinge at a value of one of its ranges' ratios.
#[derive(Serialize)]
struct Edge {
    kind: HingeKind,
    ratio: String,
    range: String,
    value: f64,
    inside: bool,
    dims_mm: Vec<f64>,
    /// `(closed - FE) / FE` of the compliance that differs most.
    worst_compliance: f64,
    concentration_formula: f64,
    concentration: f64,
    /// The share of the rotation under a moment that happens in one root thickness of bar
    /// on each side: `1 - c33 / c33` with elastic blocks (notches only: a strip's and a
    /// leaf's blocks are their own thickness, not a bar's).
    #[serde(skip_serializing_if = "Option::is_none")]
    beside: Option<f64>,
    fe_error: f64,
}

/// Each range's edge and two or three values beyond it, the other ratios of the kind at a
/// typical value (`w = 10 mm`, aluminium 7075-T6).
fn fit_edges(m: &Material, fe_material: &Elastic) -> (Vec<Edge>, String) {
    let mm = 1e-3;
    // (kind, which range, dimensions (mm) as a function of the ratio, its values)
    type Dims = fn(f64) -> Vec<f64>;
    let cases: [(HingeKind, usize, Dims, &[f64]); 6] = [
        (
            HingeKind::Strip,
            0,
            |v| vec![0.4 * v, 0.4],
            &[2.0, 1.0, 0.5],
        ),
        (HingeKind::Circular, 0, |v| vec![1.0, v], &[1.0, 2.0, 8.0]),
        (
            HingeKind::Elliptical,
            0,
            |v| vec![2.0, 2.0 * v, 0.4 * v],
            &[1.0, 2.0, 4.0],
        ),
        (
            HingeKind::Elliptical,
            1,
            |v| vec![2.0, 1.0, v],
            &[1.0, 2.0, 5.0],
        ),
        (
            HingeKind::CornerFilleted,
            0,
            |v| vec![4.0, 0.4, 0.4 * v],
            &[0.05, 0.02, 0.01, 0.0025],
        ),
        (
            HingeKind::CornerFilleted,
            1,
            |v| vec![4.0, 4.0 * v, v],
            &[0.5, 0.75, 1.0],
        ),
    ];
    let mut rows = Vec::new();
    for (kind, which, dims_of, values) in cases {
        let fit = kind.fit()[which];
        let stems: Vec<&str> = kind.dimensions().iter().map(|d| d.stem).collect();
        for &v in values {
            // six digits: the dimensions as written, not their products' rounding
            let round = |d: f64| format!("{d:.5e}").parse::<f64>().unwrap_or(d);
            let dims_mm: Vec<f64> = dims_of(v).into_iter().map(round).collect();
            let dims: Vec<f64> = dims_mm.iter().map(|d| d * mm).collect();
            let value = round(dims[fit.numerator] / dims[fit.denominator]);
            let closed = kind.compliance(&dims, WIDTH, m);
            let fe = single_hinge(kind, &dims, WIDTH, fe_material, Idealization::PlaneStress)
                .unwrap_or_else(|e| panic!("{kind:?} {dims:?}: {e}"));
            let f = fe.compliance();
            let worst_compliance = [
                (closed.c11, f.c11),
                (closed.c22, f.c22),
                (closed.c23, f.c23),
                (closed.c33, f.c33),
            ]
            .iter()
            .map(|(a, b)| rel(*a, *b))
            .fold(0.0, |w: f64, d| if d.abs() > w.abs() { d } else { w });
            let notch = matches!(kind, HingeKind::Circular | HingeKind::Elliptical);
            rows.push(Edge {
                kind,
                ratio: format!("{}/{}", stems[fit.numerator], stems[fit.denominator]),
                range: fit.range.text(),
                value,
                inside: fit.range.contains(value),
                dims_mm,
                worst_compliance,
                concentration_formula: kind.stress_concentration(&dims),
                concentration: fe.concentration.value,
                beside: notch.then(|| 1.0 - f.c33 / fe.c33_elastic_blocks.value),
                fe_error: fe.error(),
            });
        }
    }
    let pct = |v: f64| format!("{:+.1} %", 100.0 * v);
    let mut md = String::from(
        "| kind | ratio | range | value | dimensions (mm) | worst compliance: closed vs FE | \
         stress concentration: formula / FE | rotation beside a notch | FE error |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in &rows {
        let dims: Vec<String> = r.dims_mm.iter().map(|d| format!("{d}")).collect();
        md += &format!(
            "| {} | {} | {} | {}{} | {} | {} | {} | {} | {:.0e} |\n",
            r.kind.name(),
            r.ratio,
            r.range,
            r.value,
            if r.inside { "" } else { " (outside)" },
            dims.join(", "),
            pct(r.worst_compliance),
            if r.kind == HingeKind::Strip {
                "- (sharp clamp)".to_string()
            } else {
                format!("{:.2} / {:.2}", r.concentration_formula, r.concentration)
            },
            r.beside
                .map_or("-".into(), |b| format!("{:.0} %", 100.0 * b)),
            r.fe_error.max(1e-16),
        );
    }
    (rows, md)
}
