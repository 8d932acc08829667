//! A model added from outside the library, the way a new model is added inside it: one
//! type implementing `Model` (the physics; a toy without pictures or a part has no other
//! capability) and one `ModelEntry`. Problem files, the study, its files, the
//! sweep and the error messages all work with it and nothing else is touched, which is what
//! the layout promises (docs/architecture.md, "What an extension touches").
//!
//! The toy is a mass on a spring under a preload: parameters `k` (N/m) and `m` (kg), outputs
//! `frequency = sqrt(k/m) / 2 pi` and `deflection = preload / k`, the preload from its own
//! `[spring]` section.

use std::path::Path;
use std::sync::Arc;

use flexopt::model::material::Material;
use flexopt::model::registry::{ModelEntry, MODELS};
use flexopt::model::{Dimension, Mechanism, Model, OutputInfo, ParameterInfo};
use flexopt::problem::reader::k;
use flexopt::problem::schema::Quantity;
use flexopt::problem::sections::Sections;
use flexopt::problem::{Problem, ProblemError};
use flexopt::study::{self, StudyOptions};

#[derive(Debug)]
struct Spring {
    preload: f64,
}

static PARAMETERS: [ParameterInfo; 2] = [
    ParameterInfo::new("k", Dimension::Stiffness, "spring stiffness"),
    ParameterInfo::new("m", Dimension::Mass, "mass"),
];

static OUTPUTS: [OutputInfo; 2] = [
    OutputInfo::new("frequency", Dimension::Frequency, "sqrt(k/m) / 2 pi"),
    OutputInfo::new("deflection", Dimension::Length, "preload / k"),
];

impl Model for Spring {
    fn name(&self) -> &'static str {
        "toy"
    }

    fn parameters(&self) -> &[ParameterInfo] {
        &PARAMETERS
    }

    fn outputs(&self) -> &[OutputInfo] {
        &OUTPUTS
    }

    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        let mut jac = vec![0.0; 2 * wanted.len()];
        self.evaluate_with_gradient(x, wanted, out, &mut jac);
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let (k, m) = (x[0], x[1]);
        let two_pi = 2.0 * std::f64::consts::PI;
        for (i, &w) in wanted.iter().enumerate() {
            let (v, dk, dm) = if w == 0 {
                let f = (k / m).sqrt() / two_pi;
                (f, 0.5 * f / k, -0.5 * f / m)
            } else {
                (self.preload / k, -self.preload / (k * k), 0.0)
            };
            out[i] = v;
            jacobian[2 * i] = dk;
            jacobian[2 * i + 1] = dm;
        }
    }

    fn domain_error(&self, x: &[f64]) -> Option<String> {
        (x[0] <= 0.0 || x[1] <= 0.0).then(|| "k and m must be positive".to_string())
    }

    fn box_error(&self, _: &[f64], _: &[f64]) -> Option<(usize, String)> {
        None
    }

    fn max_of(&self, _: usize) -> Option<&[usize]> {
        None
    }

    fn unavailable(&self, _: usize) -> Option<String> {
        None
    }

    fn material(&self) -> Option<&Material> {
        None
    }

    fn angle_limit(&self) -> Option<f64> {
        None
    }

    fn mirror(&self, _: &mut [f64]) -> bool {
        false
    }

    fn fit_limits(&self) -> &[flexopt::model::fit::FitLimit] {
        &[]
    }
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpring {
    preload: Quantity,
}

fn build(s: &mut Sections) -> Result<Mechanism, ProblemError> {
    let raw: RawSpring = s.required("spring")?;
    let preload = s.positive(&[k("spring"), k("preload")], &raw.preload, Dimension::Force)?;
    Ok(Mechanism::physics_only(Arc::new(Spring { preload })))
}

const TOY: ModelEntry = ModelEntry {
    name: "toy",
    sections: &["spring"],
    build,
    schema: flexopt::model::entry::no_sections,
    template: "",
    hinge_layout: None,
    optional_outputs: None,
};

fn models() -> Vec<ModelEntry> {
    MODELS.iter().copied().chain([TOY]).collect()
}

/// Maximize the deflection under a 2 N preload with the frequency at least 50 Hz: the
/// softest spring the floor allows on the lightest mass, k = (2 pi 50)^2 m_min.
const FILE: &str = r#"
name = "toy_spring"
model = "toy"

[spring]
preload = "2 N"

[[variables]]
name = "k"
unit = "N/m"
lower = 50
upper = 1000

[[variables]]
name = "m"
unit = "g"
lower = 1
upper = 10

[objective]
maximize = "deflection"

[[constraints]]
output = "frequency"
unit = "Hz"
lower = 50

[search]
starts = 20
seed = 1
"#;

fn parse(text: &str) -> Result<Problem, ProblemError> {
    Problem::parse_with(&models(), Path::new("toy.toml"), text)
}

#[test]
fn a_model_from_outside_runs_the_whole_way() {
    let problem = parse(FILE).unwrap();
    let options = StudyOptions::from_problem(&problem);
    let s = study::run(&problem, &options);
    assert!(s.any_feasible);
    let best = &s.runs[s.best];
    let k_exact = (2.0 * std::f64::consts::PI * 50.0).powi(2) * 1e-3;
    assert!(
        (best.x_end[0] - k_exact).abs() < 1e-8 * k_exact,
        "{:?}",
        best.x_end
    );
    assert!((best.x_end[1] - 1e-3).abs() < 1e-12, "{:?}", best.x_end);
    assert!((best.objective - 2.0 / k_exact).abs() < 1e-8 * best.objective);

    // the study's files: a model without a drawing of configurations writes five
    let dir = std::env::temp_dir().join(format!("flexopt-toy-{}", std::process::id()));
    let files = flexopt::report::study::write_all(&dir, &problem, &s, None).unwrap();
    assert_eq!(files.len(), 6, "five files and the manifest");
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(optimum["model"], "toy");
    assert_eq!(optimum["configuration"], "-");
    let zones: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("zones.json")).unwrap()).unwrap();
    assert!(zones.get("configuration_rule").is_none());
    std::fs::remove_dir_all(&dir).unwrap();

    // and a sweep of its outputs against k
    let spec = flexopt::sweep::SweepSpec {
        variable: "k".into(),
        from: 100.0,
        to: 200.0,
        steps: 3,
        outputs: vec![],
    };
    let sweep = flexopt::sweep::sweep(&problem, &spec, &best.x_end).unwrap();
    let deflection = &sweep.outputs["deflection"];
    assert!((deflection[2].unwrap() - 2.0 / 200.0).abs() < 1e-15);
}

#[test]
fn its_section_is_read_and_checked_by_the_model() {
    let e = parse(&FILE.replace("\"2 N\"", "\"-2 N\"")).unwrap_err();
    assert_eq!(e.key, "spring.preload", "{e}");
    assert!(e.to_string().contains("must be positive"), "{e}");
    let e = parse(&FILE.replace("preload = \"2 N\"", "preload = \"2 N\"\nstiff = 1")).unwrap_err();
    assert_eq!(e.key, "spring.stiff", "{e}");
    let e = parse(&FILE.replace("[spring]\npreload = \"2 N\"\n", "")).unwrap_err();
    assert_eq!(e.key, "spring", "{e}");
    assert!(e.to_string().contains("the toy model needs it"), "{e}");
    // another model's section, and a key no model reads
    let e = parse(&format!("{FILE}\n[material]\npreset = \"al7075-t6\"\n")).unwrap_err();
    assert_eq!(e.key, "material", "{e}");
    assert!(
        e.to_string()
            .contains("the toy model takes no `material` section"),
        "{e}"
    );
    let e = parse(&FILE.replace("model = \"toy\"", "model = \"toy\"\nweight = 2")).unwrap_err();
    assert_eq!(e.key, "weight", "{e}");
    assert!(e.to_string().contains("unknown field"), "{e}");
    // the registry without the toy does not know it
    let e = Problem::parse(Path::new("toy.toml"), FILE).unwrap_err();
    assert_eq!(e.key, "model", "{e}");
}

/// A frequency floor beyond reach (the stiffest spring on the lightest mass gives
/// sqrt(1000 / 0.001) / 2 pi = 159.15 Hz) next to a deflection floor that can be met alone:
/// the least violating design meets the deflection floor exactly (k = 2 N / 10 mm = 200 N/m),
/// takes the highest frequency left (m = 1 g) and names the frequency, where a minimax
/// compromise would break both.
#[test]
fn an_unreachable_floor_is_named_and_the_others_are_met() {
    let text = FILE.replace(
        "lower = 50\n\n[search]",
        "lower = 200\n\n[[constraints]]\noutput = \"deflection\"\nunit = \"mm\"\nlower = 10\n\n[search]",
    );
    let problem = parse(&text).unwrap();
    let s = study::run(&problem, &StudyOptions::from_problem(&problem));
    assert!(!s.any_feasible);
    let l = s.least_violating.as_ref().unwrap();
    assert_eq!(l.unmet, vec![0], "frequency, the first constraint");
    let (k, m) = (l.x[0], l.x[1]);
    assert!((k - 200.0).abs() < 1e-6, "k {k}");
    assert!((m - 1e-3).abs() < 1e-12, "m {m}");
    let f = (k / m).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((f - 71.176_254).abs() < 1e-5, "{f}");
    // the objective is the deflection: at its floor, 10 mm
    assert!((s.reported_objective() - 0.01).abs() < 1e-10);

    // with only the frequency floor, the design goes to the highest frequency there is
    let text = FILE.replace("lower = 50\n\n[search]", "lower = 200\n\n[search]");
    let problem = parse(&text).unwrap();
    let s = study::run(&problem, &StudyOptions::from_problem(&problem));
    let l = s.least_violating.as_ref().unwrap();
    assert_eq!(l.unmet, vec![0]);
    assert!(
        (l.x[0] - 1000.0).abs() < 1e-6 && (l.x[1] - 1e-3).abs() < 1e-12,
        "{:?}",
        l.x
    );
}
