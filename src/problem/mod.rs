//! Problem files: the TOML schema, its validation, units, and the binding of a model's
//! named outputs to an objective and constraints.
//!
//! The format is documented in the README ("Problem files"); `problems/wei2017.toml` is
//! a complete example.

pub mod bind;
pub mod design;
pub mod error;
pub mod nlp;
pub mod schema;
pub mod units;

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::model::bridge::{Actuator, Bridge, BridgeSettings};
use crate::model::bridge_dynamics::DynamicsSettings;
use crate::model::hinge::HingeKind;
use crate::model::material::Material;
use crate::model::prr3::Prr3Model;
use crate::model::pss3::Pss3Model;
use crate::model::{Dimension, Model};
pub use error::ProblemError;
use error::{Locator, Segment};
use schema::{Number, Quantity, RawProblem};
use units::{parse_quantity, Unit};

/// The mechanism models a problem can name.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ModelSpec {
    Bridge(Bridge),
    Prr3(Prr3Model),
    Pss3(Pss3Model),
}

impl ModelSpec {
    pub const NAMES: &'static [&'static str] = &["bridge", "prr3", "pss3"];

    pub fn as_model(&self) -> &dyn Model {
        match self {
            ModelSpec::Bridge(b) => b,
            ModelSpec::Prr3(p) => p,
            ModelSpec::Pss3(p) => p,
        }
    }

    /// The name a problem file gives the model.
    pub fn name(&self) -> &'static str {
        match self {
            ModelSpec::Bridge(_) => "bridge",
            ModelSpec::Prr3(_) => "prr3",
            ModelSpec::Pss3(_) => "pss3",
        }
    }
}

/// A design variable: one model parameter, free within bounds or fixed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Variable {
    pub name: String,
    /// Index among the model's parameters.
    pub parameter: usize,
    /// The unit the file uses for this variable.
    #[serde(skip)]
    pub unit: Unit,
    /// SI bounds, or the SI value twice for a fixed variable.
    pub lower: f64,
    pub upper: f64,
    pub fixed: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    Maximize,
    Minimize,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Objective {
    pub output: String,
    /// Index among the model's outputs.
    #[serde(skip)]
    pub index: usize,
    pub sense: Sense,
    /// Optimize the absolute value of the output.
    pub absolute: bool,
}

/// `lower <= output <= upper`, SI; at least one limit is present.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Constraint {
    pub output: String,
    #[serde(skip)]
    pub index: usize,
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    /// The unit the file uses, for reports.
    #[serde(skip)]
    pub unit: Unit,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Solver {
    Sqp,
    NelderMead,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sampling {
    Uniform,
    LatinHypercube,
}

/// How the multistart search runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SearchSettings {
    pub starts: usize,
    pub seed: u64,
    pub solver: Solver,
    pub sampling: Sampling,
    /// Stopping tolerance of the local solver (KKT residual, scaled).
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
}

/// How optima are merged and sorted into zones.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZoneSettings {
    /// Objective thresholds between zones, descending; empty: zones from gaps.
    pub thresholds: Vec<f64>,
    /// Optima closer than this in design space scaled to the bounds are one optimum.
    pub x_tolerance: f64,
    /// ... and whose objectives differ by less than this, relative.
    pub objective_tolerance: f64,
    /// Count a design and its mirror image (all angles negated) as one geometry.
    pub merge_mirror_images: bool,
}

/// A validated problem, SI units inside.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Problem {
    #[serde(skip)]
    pub file: PathBuf,
    pub name: String,
    pub description: String,
    pub model: ModelSpec,
    /// The bridge's material; models without one have `None`.
    pub material: Option<Material>,
    /// One per model parameter, in model order.
    pub variables: Vec<Variable>,
    pub objective: Objective,
    pub constraints: Vec<Constraint>,
    pub search: SearchSettings,
    pub zones: ZoneSettings,
}

impl Problem {
    /// Reads and validates a problem file.
    pub fn load(path: &Path) -> Result<Problem, ProblemError> {
        let text = std::fs::read_to_string(path).map_err(|e| ProblemError {
            file: path.to_path_buf(),
            key: String::new(),
            position: None,
            message: format!("cannot read the file: {e}"),
        })?;
        Self::parse(path, &text)
    }

    /// Validates the text of a problem file; `path` names it in errors.
    pub fn parse(path: &Path, text: &str) -> Result<Problem, ProblemError> {
        let loc = Locator::new(path, text);
        let raw = deserialize(&loc, text)?;
        Validator { loc: &loc }.problem(raw)
    }

    pub fn model(&self) -> &dyn Model {
        self.model.as_model()
    }

    /// The free variables, in model order.
    pub fn free_variables(&self) -> impl Iterator<Item = &Variable> {
        self.variables.iter().filter(|v| !v.fixed)
    }

    /// The folder a run writes to by default: `results/<name>/`.
    pub fn default_output_dir(&self) -> PathBuf {
        Path::new("results").join(&self.name)
    }
}

fn deserialize(loc: &Locator, text: &str) -> Result<RawProblem, ProblemError> {
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let key = e.span().map(|s| key_at(text, s.start)).unwrap_or_default();
        loc.error_at(key, e.span(), e.message().trim().to_string())
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let mut key = e.path().to_string();
        if key == "." {
            key.clear();
        }
        let inner = e.into_inner();
        let message = inner.message().trim().to_string();
        // name the offending key itself, not only the table that holds it
        for prefix in ["unknown field `", "missing field `"] {
            if let Some(rest) = message.strip_prefix(prefix) {
                let field = rest
                    .split('`')
                    .next()
                    .filter(|f| !key.ends_with(&format!(".{f}")) && key != *f);
                if let Some(field) = field {
                    key = if key.is_empty() {
                        field.to_string()
                    } else {
                        format!("{key}.{field}")
                    };
                }
            }
        }
        let message = if message.contains("untagged enum Number") {
            "expected a number".to_string()
        } else if message.contains("untagged enum Quantity") {
            "expected a quantity with its unit, e.g. \"10 mm\"".to_string()
        } else {
            message
        };
        loc.error_at(key, inner.span(), message)
    })
}

/// The key a syntax error at `offset` belongs to, read from the text: the last table
/// header before it and the key of its line (or the header itself, or `(top level)`).
fn key_at(text: &str, offset: usize) -> String {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let line = text[line_start..line_end].trim();
    let strip = |l: &str| l.trim_matches(|c| c == '[' || c == ']').trim().to_string();
    if line.starts_with('[') {
        let header = strip(line);
        return if header.is_empty() {
            "(table header)".to_string()
        } else {
            header
        };
    }
    let header = before[..line_start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .map(strip)
        .filter(|h| !h.is_empty());
    let key = line
        .split('=')
        .next()
        .map(str::trim)
        .filter(|k| !k.is_empty() && !k.starts_with('#'));
    match (header, key) {
        (Some(h), Some(k)) => format!("{h}.{k}"),
        (None, Some(k)) => k.to_string(),
        (Some(h), None) => h,
        (None, None) => "(top level)".to_string(),
    }
}

/// Key paths are built from these.
fn k(key: &str) -> Segment {
    Segment::Key(key.to_string())
}

struct Validator<'a, 'b> {
    loc: &'a Locator<'b>,
}

type Res<T> = Result<T, ProblemError>;

impl Validator<'_, '_> {
    fn err(&self, path: &[Segment], message: impl Into<String>) -> ProblemError {
        self.loc.error(path, message)
    }

    fn finite(&self, path: &[Segment], n: Number) -> Res<f64> {
        let v = n.get();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(path, format!("{v} is not a finite number")))
        }
    }

    fn quantity(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        match q {
            Quantity::Text(t) => parse_quantity(t, dim).map_err(|m| self.err(path, m)),
            Quantity::Bare(n) => Err(self.err(
                path,
                format!(
                    "{} has no unit: write it as a string with its unit, one of {}",
                    n.get(),
                    units::accepted(dim)
                ),
            )),
        }
    }

    fn positive(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        let v = self.quantity(path, q, dim)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be positive, got {}", show(q))))
        }
    }

    fn non_negative(&self, path: &[Segment], q: &Quantity, dim: Dimension) -> Res<f64> {
        let v = self.quantity(path, q, dim)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must not be negative, got {}", show(q))))
        }
    }

    fn problem(&self, raw: RawProblem) -> Res<Problem> {
        let name = raw.name.trim().to_string();
        let name_ok = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
            && !name.starts_with('.');
        if !name_ok {
            return Err(self.err(
                &[k("name")],
                format!(
                    "\"{}\" cannot name a results folder: use letters, digits, '-', '_' and '.'",
                    raw.name
                ),
            ));
        }
        let missing = |key: &str| {
            self.err(
                &[k(key)],
                format!("missing field `{key}`: the {} model needs it", raw.model),
            )
        };
        let refused = |present: bool, key: &str| -> Res<()> {
            if present {
                Err(self.err(
                    &[k(key)],
                    format!("the {} model takes no `{key}` section", raw.model),
                ))
            } else {
                Ok(())
            }
        };
        let (material, model) = match raw.model.as_str() {
            "bridge" => {
                let m = raw.material.as_ref().ok_or_else(|| missing("material"))?;
                let h = raw.hinge.as_ref().ok_or_else(|| missing("hinge"))?;
                let a = raw.actuator.as_ref().ok_or_else(|| missing("actuator"))?;
                let material = self.material(m)?;
                let model = ModelSpec::Bridge(Bridge::new(BridgeSettings {
                    hinge: self.hinge_kind(&h.kind)?,
                    width: self.positive(&[k("hinge"), k("width")], &h.width, Dimension::Length)?,
                    material: material.clone(),
                    actuator: self.actuator(a)?,
                    dynamics: raw
                        .dynamics
                        .as_ref()
                        .map(|d| self.dynamics(d))
                        .transpose()?,
                }));
                (Some(material), model)
            }
            "prr3" | "pss3" => {
                refused(raw.material.is_some(), "material")?;
                refused(raw.hinge.is_some(), "hinge")?;
                refused(raw.actuator.is_some(), "actuator")?;
                refused(raw.dynamics.is_some(), "dynamics")?;
                let spec = if raw.model == "prr3" {
                    ModelSpec::Prr3(Prr3Model)
                } else {
                    ModelSpec::Pss3(Pss3Model)
                };
                (None, spec)
            }
            other => {
                return Err(self.err(
                    &[k("model")],
                    format!(
                        "unknown model \"{other}\"; expected one of {}",
                        quoted(ModelSpec::NAMES)
                    ),
                ))
            }
        };
        // the bridge's angles must stay within a right angle (Geometry::domain_error)
        let right_angle_limit = matches!(model, ModelSpec::Bridge(_));
        let variables = self.variables(model.as_model(), right_angle_limit, &raw.variables)?;
        let objective = self.objective(model.as_model(), &raw.objective)?;
        let constraints = raw
            .constraints
            .iter()
            .enumerate()
            .map(|(i, c)| self.constraint(model.as_model(), material.as_ref(), i, c))
            .collect::<Res<Vec<_>>>()?;
        Ok(Problem {
            file: self.loc.file().to_path_buf(),
            name,
            description: raw.description,
            model,
            material,
            variables,
            objective,
            constraints,
            search: self.search(&raw.search)?,
            zones: self.zones(&raw.zones)?,
        })
    }

    fn material(&self, m: &schema::RawMaterial) -> Res<Material> {
        let path = |key: &str| [k("material"), k(key)];
        let mut mat = match &m.preset {
            Some(p) => Material::preset(p).ok_or_else(|| {
                self.err(
                    &path("preset"),
                    format!(
                        "unknown material \"{p}\"; expected one of {}",
                        quoted(Material::PRESETS)
                    ),
                )
            })?,
            None => {
                if m.youngs_modulus.is_none() || m.poisson_ratio.is_none() {
                    let missing = if m.youngs_modulus.is_none() {
                        "youngs_modulus"
                    } else {
                        "poisson_ratio"
                    };
                    return Err(self.err(
                        &path(missing),
                        format!(
                            "missing: give a `preset` ({}) or the material's values",
                            quoted(Material::PRESETS)
                        ),
                    ));
                }
                Material {
                    name: "custom".into(),
                    youngs_modulus: f64::NAN,
                    poisson_ratio: f64::NAN,
                    ultimate_strength: None,
                    density: f64::NAN,
                }
            }
        };
        if let Some(n) = &m.name {
            mat.name = n.clone();
        }
        if let Some(q) = &m.youngs_modulus {
            mat.youngs_modulus = self.positive(&path("youngs_modulus"), q, Dimension::Stress)?;
        }
        if let Some(n) = m.poisson_ratio {
            let nu = self.finite(&path("poisson_ratio"), n)?;
            if !(nu > -1.0 && nu < 0.5) {
                return Err(self.err(
                    &path("poisson_ratio"),
                    format!("must lie in (-1, 0.5), got {nu}"),
                ));
            }
            mat.poisson_ratio = nu;
        }
        if let Some(q) = &m.ultimate_strength {
            mat.ultimate_strength =
                Some(self.positive(&path("ultimate_strength"), q, Dimension::Stress)?);
        }
        if let Some(q) = &m.density {
            mat.density = density(q).map_err(|msg| self.err(&path("density"), msg))?;
        }
        Ok(mat)
    }

    fn hinge_kind(&self, kind: &str) -> Res<HingeKind> {
        HingeKind::from_name(kind).ok_or_else(|| {
            self.err(
                &[k("hinge"), k("kind")],
                format!(
                    "unknown hinge kind \"{kind}\"; expected one of {}",
                    quoted(HingeKind::NAMES)
                ),
            )
        })
    }

    fn actuator(&self, a: &schema::RawActuator) -> Res<Actuator> {
        let path = |key: &str| [k("actuator"), k(key)];
        Ok(Actuator {
            nominal_stroke: self.positive(
                &path("nominal_stroke"),
                &a.nominal_stroke,
                Dimension::Length,
            )?,
            preload: self.non_negative(&path("preload"), &a.preload, Dimension::Force)?,
            stiffness: match &a.stiffness {
                Some(q) => Some(self.positive(&path("stiffness"), q, Dimension::Stiffness)?),
                None => None,
            },
        })
    }

    fn dynamics(&self, d: &schema::RawDynamics) -> Res<DynamicsSettings> {
        let path = |key: &str| [k("dynamics"), k(key)];
        let mass = |key: &str, q: &Quantity| self.non_negative(&path(key), q, Dimension::Mass);
        let zeta = self.finite(&path("damping_ratio"), d.damping_ratio)?;
        // the settling time is that of an oscillator: it needs some damping, and above
        // critical damping the +-2 % band is reached without oscillation, which is fine
        if !(zeta > 0.0 && zeta <= 10.0) {
            return Err(self.err(
                &path("damping_ratio"),
                format!("must lie in (0, 10], got {zeta}"),
            ));
        }
        Ok(DynamicsSettings::new(
            mass("payload_mass", &d.payload_mass)?,
            mass("input_link_mass", &d.input_link_mass)?,
            mass("output_link_mass", &d.output_link_mass)?,
            self.non_negative(
                &path("link_thickness"),
                &d.link_thickness,
                Dimension::Length,
            )?,
            zeta,
        ))
    }

    fn variables(
        &self,
        model: &dyn Model,
        right_angle_limit: bool,
        raw: &[schema::RawVariable],
    ) -> Res<Vec<Variable>> {
        let params = model.parameters();
        let mut found: Vec<Option<Variable>> = vec![None; params.len()];
        for (i, v) in raw.iter().enumerate() {
            let path = |key: &str| [k("variables"), Segment::Index(i), k(key)];
            let Some(p) = params.iter().position(|p| p.name == v.name) else {
                return Err(self.err(
                    &path("name"),
                    format!(
                        "\"{}\" is not a parameter of this model; expected one of {}",
                        v.name,
                        quoted(&params.iter().map(|p| p.name).collect::<Vec<_>>())
                    ),
                ));
            };
            if found[p].is_some() {
                return Err(self.err(
                    &path("name"),
                    format!("variable \"{}\" is defined twice", v.name),
                ));
            }
            let dim = params[p].dimension;
            let unit = Unit::parse(&v.unit, dim).map_err(|m| self.err(&path("unit"), m))?;
            let must_be_positive = matches!(
                dim,
                Dimension::Length
                    | Dimension::Mass
                    | Dimension::Stiffness
                    | Dimension::RotationalStiffness
            );
            let check = |key: &str, n: Number| -> Res<f64> {
                let x = self.finite(&path(key), n)?;
                if right_angle_limit
                    && dim == Dimension::Angle
                    && unit.to_si(x).abs() >= std::f64::consts::FRAC_PI_2
                {
                    return Err(self.err(
                        &path(key),
                        format!("{} is an angle: it must lie strictly between -90 and 90 deg, got {x} {}", v.name, unit.name),
                    ));
                }
                if must_be_positive && x <= 0.0 {
                    return Err(self.err(
                        &path(key),
                        format!(
                            "{} is a {}: it must be positive, got {x} {}",
                            v.name, params[p].description, unit.name
                        ),
                    ));
                }
                Ok(unit.to_si(x))
            };
            let var = match (v.value, v.lower, v.upper) {
                (Some(val), None, None) => {
                    let x = check("value", val)?;
                    Variable {
                        name: v.name.clone(),
                        parameter: p,
                        unit: unit.clone(),
                        lower: x,
                        upper: x,
                        fixed: true,
                    }
                }
                (None, Some(lo), Some(hi)) => {
                    let (lower, upper) = (check("lower", lo)?, check("upper", hi)?);
                    if lower >= upper {
                        return Err(self.err(
                            &path("lower"),
                            format!(
                                "lower bound {} is not below upper bound {} (for a fixed variable write `value`)",
                                lo.get(),
                                hi.get()
                            ),
                        ));
                    }
                    Variable {
                        name: v.name.clone(),
                        parameter: p,
                        unit: unit.clone(),
                        lower,
                        upper,
                        fixed: false,
                    }
                }
                (Some(_), _, _) => {
                    return Err(self.err(
                        &path("value"),
                        "a variable has either `value` (fixed) or `lower` and `upper`, not both",
                    ))
                }
                (None, None, _) => {
                    return Err(self.err(
                        &path("lower"),
                        "missing: a free variable needs `lower` and `upper`",
                    ))
                }
                (None, _, None) => {
                    return Err(self.err(
                        &path("upper"),
                        "missing: a free variable needs `lower` and `upper`",
                    ))
                }
            };
            found[p] = Some(var);
        }
        found
            .into_iter()
            .enumerate()
            .map(|(p, v)| {
                v.ok_or_else(|| {
                    self.err(
                        &[k("variables")],
                        format!(
                            "missing design variable \"{}\" ({}); every model parameter needs bounds or a fixed value",
                            params[p].name, params[p].description
                        ),
                    )
                })
            })
            .collect()
    }

    fn output(&self, model: &dyn Model, path: &[Segment], name: &str) -> Res<usize> {
        let index = model.output_index(name).ok_or_else(|| {
            self.err(
                path,
                format!(
                    "unknown output \"{name}\"; expected one of {}",
                    quoted(&model.outputs().iter().map(|o| o.name).collect::<Vec<_>>())
                ),
            )
        })?;
        match model.unavailable(index) {
            Some(why) => Err(self.err(path, why)),
            None => Ok(index),
        }
    }

    fn objective(&self, model: &dyn Model, o: &schema::RawObjective) -> Res<Objective> {
        let (sense, name, key) = match (&o.maximize, &o.minimize) {
            (Some(n), None) => (Sense::Maximize, n, "maximize"),
            (None, Some(n)) => (Sense::Minimize, n, "minimize"),
            (Some(_), Some(_)) => {
                return Err(self.err(
                    &[k("objective"), k("minimize")],
                    "give either `maximize` or `minimize`, not both",
                ))
            }
            (None, None) => {
                return Err(self.err(
                    &[k("objective"), k("maximize")],
                    "missing: give `maximize` or `minimize` and an output name",
                ))
            }
        };
        Ok(Objective {
            output: name.clone(),
            index: self.output(model, &[k("objective"), k(key)], name)?,
            sense,
            absolute: o.absolute,
        })
    }

    fn constraint(
        &self,
        model: &dyn Model,
        mat: Option<&Material>,
        i: usize,
        c: &schema::RawConstraint,
    ) -> Res<Constraint> {
        let path = |key: &str| [k("constraints"), Segment::Index(i), k(key)];
        let index = self.output(model, &path("output"), &c.output)?;
        let dim = model.outputs()[index].dimension;
        let unit = if c.unit == "ultimate" {
            if dim != Dimension::Stress {
                return Err(self.err(
                    &path("unit"),
                    format!("\"ultimate\" (a fraction of the ultimate strength) only fits stress outputs, not \"{}\"", c.output),
                ));
            }
            let su = mat.and_then(|m| m.ultimate_strength).ok_or_else(|| {
                self.err(
                    &path("unit"),
                    match mat {
                        Some(m) => format!(
                            "material \"{}\" has no ultimate strength: set material.ultimate_strength",
                            m.name
                        ),
                        None => "this model has no material, so no ultimate strength".to_string(),
                    },
                )
            })?;
            Unit {
                name: "ultimate".into(),
                dimension: dim,
                to_si: su,
            }
        } else {
            Unit::parse(&c.unit, dim).map_err(|m| self.err(&path("unit"), m))?
        };
        let limit = |key: &str, n: Option<Number>| -> Res<Option<f64>> {
            n.map(|n| self.finite(&path(key), n).map(|v| unit.to_si(v)))
                .transpose()
        };
        let (lower, upper) = (limit("lower", c.lower)?, limit("upper", c.upper)?);
        match (lower, upper) {
            (None, None) => Err(self.err(
                &path("upper"),
                "missing: a constraint needs `lower`, `upper` or both",
            )),
            (Some(lo), Some(hi)) if lo > hi => Err(self.err(
                &path("lower"),
                format!(
                    "lower limit {} is above upper limit {}",
                    c.lower.unwrap().get(),
                    c.upper.unwrap().get()
                ),
            )),
            _ => Ok(Constraint {
                output: c.output.clone(),
                index,
                lower,
                upper,
                unit,
            }),
        }
    }

    fn search(&self, s: &schema::RawSearch) -> Res<SearchSettings> {
        let path = |key: &str| [k("search"), k(key)];
        let count = |key: &str, v: Option<i64>, default: usize, min: i64, max: i64| -> Res<usize> {
            match v {
                None => Ok(default),
                Some(n) if (min..=max).contains(&n) => Ok(n as usize),
                Some(n) => Err(self.err(
                    &path(key),
                    format!("must lie between {min} and {max}, got {n}"),
                )),
            }
        };
        let solver = match s.solver.as_deref() {
            None | Some("sqp") => Solver::Sqp,
            Some("nelder-mead") => Solver::NelderMead,
            Some(o) => {
                return Err(self.err(
                    &path("solver"),
                    format!("unknown solver \"{o}\"; expected \"sqp\" or \"nelder-mead\""),
                ))
            }
        };
        let sampling = match s.sampling.as_deref() {
            None | Some("uniform") => Sampling::Uniform,
            Some("latin-hypercube") => Sampling::LatinHypercube,
            Some(o) => {
                return Err(self.err(
                    &path("sampling"),
                    format!(
                        "unknown sampling \"{o}\"; expected \"uniform\" or \"latin-hypercube\""
                    ),
                ))
            }
        };
        let tolerance = match s.tolerance {
            None => 1e-10,
            Some(n) => {
                let t = self.finite(&path("tolerance"), n)?;
                if t <= 0.0 {
                    return Err(self.err(&path("tolerance"), format!("must be positive, got {t}")));
                }
                t
            }
        };
        let seed = match s.seed {
            None => 0,
            Some(n) if n >= 0 => n as u64,
            Some(n) => {
                return Err(self.err(&path("seed"), format!("must not be negative, got {n}")))
            }
        };
        Ok(SearchSettings {
            starts: count("starts", s.starts, 300, 1, 1_000_000)?,
            seed,
            solver,
            sampling,
            tolerance,
            max_iterations: count("max_iterations", s.max_iterations, 500, 1, 1_000_000)?,
            threads: count("threads", s.threads, 0, 0, 1024)?,
        })
    }

    fn zones(&self, z: &schema::RawZones) -> Res<ZoneSettings> {
        let path = |key: &str| [k("zones"), k(key)];
        let mut thresholds = Vec::new();
        for (i, n) in z.thresholds.iter().flatten().enumerate() {
            thresholds.push(self.finite(&[k("zones"), k("thresholds"), Segment::Index(i)], *n)?);
        }
        thresholds.sort_by(|a, b| b.total_cmp(a));
        thresholds.dedup();
        let tol = |key: &str, n: Option<Number>, default: f64| -> Res<f64> {
            match n {
                None => Ok(default),
                Some(n) => {
                    let v = self.finite(&path(key), n)?;
                    if v > 0.0 {
                        Ok(v)
                    } else {
                        Err(self.err(&path(key), format!("must be positive, got {v}")))
                    }
                }
            }
        };
        Ok(ZoneSettings {
            thresholds,
            x_tolerance: tol("x_tolerance", z.x_tolerance, 1e-3)?,
            objective_tolerance: tol("objective_tolerance", z.objective_tolerance, 1e-6)?,
            merge_mirror_images: z.merge_mirror_images.unwrap_or(true),
        })
    }
}

/// Density has a unit of its own: `"2810 kg/m3"` or `"2.81 g/cm3"`.
fn density(q: &Quantity) -> Result<f64, String> {
    let Quantity::Text(t) = q else {
        return Err("expected a density with its unit, e.g. \"2810 kg/m3\"".into());
    };
    let t = t.trim();
    let (num, unit) = t.split_at(t.find(char::is_whitespace).unwrap_or(t.len()));
    let factor = match unit.trim() {
        "kg/m3" | "kg/m^3" => 1.0,
        "g/cm3" | "g/cm^3" => 1000.0,
        u => {
            return Err(format!(
                "unknown unit \"{u}\" for a density; expected \"kg/m3\" or \"g/cm3\""
            ))
        }
    };
    match num.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v * factor),
        _ => Err(format!(
            "\"{t}\" is not a positive density, e.g. \"2810 kg/m3\""
        )),
    }
}

fn show(q: &Quantity) -> String {
    match q {
        Quantity::Text(t) => format!("\"{t}\""),
        Quantity::Bare(n) => n.get().to_string(),
    }
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}
