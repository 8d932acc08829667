//! Validation of a problem file's common part: the name, the design variables, the
//! objective and constraints bound to the model's outputs, the search and the zones. The
//! model's own sections are read by the model ([`crate::model::registry`]).

use std::ops::Deref;

use super::reader::{k, quoted, Reader, Res};
use super::schema::{self, Number, RawProblem, MAX_ITERATIONS, STARTS, THREADS, TOLERANCE};
use super::sections::Sections;
use super::strength;
use super::units::{self, short, Unit};
use super::{
    Constraint, Objective, Problem, Sampling, SearchSettings, Segment, Sense, Solver, Variable,
    ZoneSettings, SAMPLINGS, SOLVERS,
};
use crate::model::registry::{self, ModelEntry};
use crate::model::{Dimension, Model};

/// Whether a variable of `dimension` must be positive: a length, a mass, a stiffness.
pub(crate) fn positive_only(dimension: Dimension) -> bool {
    matches!(
        dimension,
        Dimension::Length | Dimension::Mass | Dimension::Stiffness | Dimension::RotationalStiffness
    )
}

/// The number of limits of the constraints the yield counts: a range counts twice.
fn limits(constraints: &[Constraint]) -> usize {
    constraints
        .iter()
        .filter(|c| c.in_yield)
        .map(|c| usize::from(c.lower.is_some()) + usize::from(c.upper.is_some()))
        .sum()
}

/// Whether `name` (trimmed) may name a problem and its results folder: letters, digits,
/// `-`, `_` and `.`, not starting with `.` (no `.`, `..` or hidden folder); the schema's
/// [`NAME_PATTERN`] says the same.
pub(crate) fn name_ok(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
        && !name.starts_with('.')
}

/// [`name_ok`] as a pattern, white space around allowed as the reader trims it.
pub(crate) const NAME_PATTERN: &str = r"^\s*[A-Za-z0-9_-][A-Za-z0-9_.-]*\s*$";

pub(crate) struct Validator<'a, 'b> {
    pub reader: Reader<'a, 'b>,
    pub text: &'b str,
    pub models: &'a [ModelEntry],
}

impl<'a, 'b> Deref for Validator<'a, 'b> {
    type Target = Reader<'a, 'b>;

    fn deref(&self) -> &Self::Target {
        &self.reader
    }
}

impl Validator<'_, '_> {
    pub fn problem(&self, raw: RawProblem) -> Res<Problem> {
        let name = raw.name.trim().to_string();
        if !name_ok(&name) {
            return Err(self.err(
                &[k("name")],
                format!(
                    "\"{}\" cannot name a results folder: use letters, digits, '-', '_' and '.'",
                    raw.name
                ),
            ));
        }
        let Some(entry) = registry::find(self.models, &raw.model) else {
            let names: Vec<&str> = self.models.iter().map(|m| m.name).collect();
            return Err(self.err(
                &[k("model")],
                format!(
                    "unknown model \"{}\"; expected one of {}",
                    raw.model,
                    quoted(&names)
                ),
            ));
        };
        // a section the model does not read is refused before the model looks at the rest
        for key in raw.sections.keys() {
            if entry.sections.contains(&key.as_str()) {
                continue;
            }
            let message = if self
                .models
                .iter()
                .any(|m| m.sections.contains(&key.as_str()))
            {
                format!("the {} model takes no `{key}` section", entry.name)
            } else {
                let known: Vec<&str> = schema::COMMON_KEYS
                    .iter()
                    .chain(entry.sections)
                    .copied()
                    .collect();
                format!(
                    "unknown field `{key}`, expected one of {}",
                    known
                        .iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            };
            return Err(self.err(&[k(key)], message));
        }
        let mechanism = (entry.build)(&mut Sections::new(self.loc, self.text, entry.name))?;
        let model = mechanism.physics.as_ref();
        let variables = self.variables(model, &raw.variables)?;
        let objective = self.objective(model, &raw.objective)?;
        let constraints = raw
            .constraints
            .iter()
            .enumerate()
            .map(|(i, c)| self.constraint(model, i, c))
            .collect::<Res<Vec<_>>>()?;
        // two constraints on one output are one range said twice, or a contradiction
        for (j, c) in constraints.iter().enumerate() {
            if let Some(i) = constraints[..j].iter().position(|d| d.index == c.index) {
                return Err(self.err(
                    &[k("constraints"), Segment::Index(j), k("output")],
                    format!(
                        "\"{}\" is constrained already by constraints[{i}]: give one constraint \
                         per output, with `lower`, `upper` or both",
                        c.output
                    ),
                ));
            }
        }
        let mut constraints = constraints;
        super::tolerances::yield_of(self, &raw.tolerances, &mut constraints)?;
        let search = self.search(&raw.search, limits(&constraints))?;
        let tolerances =
            super::tolerances::tolerances(self, &mechanism, &variables, &raw.tolerances)?;
        let used = std::iter::once((vec![k("objective")], objective.index)).chain(
            (constraints.iter().enumerate()).map(|(j, c)| {
                (
                    vec![k("constraints"), Segment::Index(j), k("output")],
                    c.index,
                )
            }),
        );
        let robust = search.robust.is_some();
        super::tolerances::first_order_only(self, &mechanism, robust, used)?;
        if search.robust.is_some() {
            let path = [k("search"), k("robust")];
            if mechanism.modulus.is_none() {
                return Err(self.err(
                    &path,
                    format!(
                        "the {} model gives no second derivatives under tolerances: a robust \
                         study needs them",
                        entry.name
                    ),
                ));
            }
            if tolerances.is_empty() {
                return Err(self.err(&path, "a robust study needs a [tolerances] section"));
            }
        }
        Ok(Problem {
            file: self.loc.file().to_path_buf(),
            name,
            description: raw.description,
            mechanism,
            variables,
            objective,
            constraints,
            search,
            zones: self.zones(&raw.zones)?,
            refine: super::refine::settings(self, raw.refine.as_ref())?,
            tolerances,
            fingerprint: super::fingerprint(self.text),
        })
    }

    fn variables(&self, model: &dyn Model, raw: &[schema::RawVariable]) -> Res<Vec<Variable>> {
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
                        quoted(&params.iter().map(|p| p.name.as_ref()).collect::<Vec<_>>())
                    ),
                ));
            };
            if found[p].is_some() {
                return Err(self.err(
                    &path("name"),
                    format!("variable \"{}\" is defined twice", v.name),
                ));
            }
            let var = self.variable(model, i, v, p)?;
            found[p] = Some(var);
        }
        let vars: Vec<Variable> = found
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
            .collect::<Res<_>>()?;
        // designs the bounds allow that the model has no value for (a fillet longer than
        // half its leaf, say): refused here, not met by the optimizer
        let lower: Vec<f64> = vars.iter().map(|v| v.lower).collect();
        let upper: Vec<f64> = vars.iter().map(|v| v.upper).collect();
        if let Some((p, why)) = model.box_error(&lower, &upper) {
            let i = raw
                .iter()
                .position(|v| v.name == params[p].name)
                .unwrap_or(0);
            let key = if vars[p].fixed { "value" } else { "upper" };
            return Err(self.err(&[k("variables"), Segment::Index(i), k(key)], why));
        }
        Ok(vars)
    }

    /// The file's `i`-th variable `v`, the model's parameter `p`: its unit, and its value
    /// or bounds checked (positive, within an angle's limits, physical).
    fn variable(
        &self,
        model: &dyn Model,
        i: usize,
        v: &schema::RawVariable,
        p: usize,
    ) -> Res<Variable> {
        let params = model.parameters();
        let path = |key: &str| [k("variables"), Segment::Index(i), k(key)];
        let dim = params[p].dimension;
        let unit = Unit::parse(&v.unit, dim).map_err(|m| self.err(&path("unit"), m))?;
        let must_be_positive = positive_only(dim);
        let check = |key: &str, n: Number| -> Res<f64> {
            let x = self.finite(&path(key), n)?;
            let limit = model.angle_limit().filter(|_| dim == Dimension::Angle);
            if limit.is_some_and(|limit| unit.to_si(x).abs() >= limit) {
                return Err(self.err(
                    &path(key),
                    format!(
                        "{} is an angle: it must lie strictly between -90 and 90 deg, got {} {}",
                        v.name,
                        short(x),
                        unit.name
                    ),
                ));
            }
            if must_be_positive && x <= 0.0 {
                return Err(self.err(
                    &path(key),
                    format!(
                        "{} is a {}: it must be positive, got {} {}",
                        v.name,
                        params[p].description,
                        short(x),
                        unit.name
                    ),
                ));
            }
            let si = unit.to_si(x);
            units::physical(si, dim).map_err(|why| {
                self.err(
                    &path(key),
                    format!("{} = {} {} {why}", v.name, short(x), unit.name),
                )
            })?;
            Ok(si)
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
        Ok(var)
    }

    fn output(&self, model: &dyn Model, path: &[Segment], name: &str) -> Res<usize> {
        let index = model.output_index(name).ok_or_else(|| {
            self.err(
                path,
                format!(
                    "unknown output \"{name}\"; expected one of {}",
                    quoted(
                        &model
                            .outputs()
                            .iter()
                            .map(|o| o.name.as_ref())
                            .collect::<Vec<_>>()
                    )
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
        i: usize,
        c: &schema::RawConstraint,
    ) -> Res<Constraint> {
        let mat = model.material();
        let path = |key: &str| [k("constraints"), Segment::Index(i), k(key)];
        let index = self.output(model, &path("output"), &c.output)?;
        let dim = model.outputs()[index].dimension;
        let unit = match strength::strength_fraction(&c.unit, dim, mat, &c.output)
            .map_err(|m| self.err(&path("unit"), m))?
        {
            Some(u) => u,
            None => Unit::parse(&c.unit, dim).map_err(|m| self.err(&path("unit"), m))?,
        };
        let limit = |key: &str, n: Option<Number>| -> Res<Option<f64>> {
            n.map(|n| {
                let v = self.finite(&path(key), n)?;
                let si = unit.to_si(v);
                units::physical(si, dim).map_err(|why| {
                    self.err(&path(key), format!("{} {} {why}", short(v), unit.name))
                })?;
                Ok(si)
            })
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
                in_yield: true,
            }),
        }
    }

    fn search(&self, s: &schema::RawSearch, limits: usize) -> Res<SearchSettings> {
        let path = |key: &str| [k("search"), k(key)];
        let count =
            |key: &str, v: Option<i64>, default: usize, (min, max): (i64, i64)| -> Res<usize> {
                match v {
                    None => Ok(default),
                    Some(n) if (min..=max).contains(&n) => Ok(n as usize),
                    Some(n) => Err(self.err(
                        &path(key),
                        format!("must lie between {min} and {max}, got {n}"),
                    )),
                }
            };
        let solver = match &s.solver {
            Some(name) => self.choice(&path("solver"), name, &SOLVERS)?,
            None => Solver::Sqp,
        };
        let sampling = match &s.sampling {
            Some(name) => self.choice(&path("sampling"), name, &SAMPLINGS)?,
            None => Sampling::Uniform,
        };
        let tolerance = match s.tolerance {
            None => 1e-10,
            Some(n) => {
                let t = self.finite(&path("tolerance"), n)?;
                if !(TOLERANCE.0..=TOLERANCE.1).contains(&t) {
                    return Err(self.err(
                        &path("tolerance"),
                        format!(
                            "must lie between {:e} and {:e}, got {t:e}",
                            TOLERANCE.0, TOLERANCE.1
                        ),
                    ));
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
            starts: count("starts", s.starts, 300, STARTS)?,
            seed,
            solver,
            sampling,
            tolerance,
            max_iterations: count("max_iterations", s.max_iterations, 500, MAX_ITERATIONS)?,
            threads: count("threads", s.threads, 0, THREADS)?,
            fit_ranges: s.fit_ranges.unwrap_or_default(),
            robust: s
                .robust
                .as_ref()
                .map(|r| self.robust(r, limits))
                .transpose()?,
        })
    }

    /// `[search] robust`: a yield becomes a margin in standard deviations by Bonferroni's
    /// inequality over the problem's `limits` (each limit then fails at most
    /// `(1 - yield) / limits` of the parts, all together at most `1 - yield`).
    fn robust(&self, r: &schema::RawRobust, limits: usize) -> Res<super::Robust> {
        let path = |key: &str| [k("search"), k("robust"), k(key)];
        match (r.target_yield, r.k_sigma) {
            (Some(y), None) => {
                let y = self.finite(&path("yield"), y)?;
                let (lo, hi) = schema::ROBUST_YIELD;
                if !(y > lo && y < hi) {
                    return Err(self.err(
                        &path("yield"),
                        format!("must lie strictly between {lo} and {hi}, got {}", short(y)),
                    ));
                }
                if limits == 0 {
                    return Err(self.err(
                        &path("yield"),
                        "the problem has no constraint: a yield needs limits to meet",
                    ));
                }
                let per_limit = 1.0 - (1.0 - y) / limits as f64;
                Ok(super::Robust {
                    k_sigma: super::tolerances::normal_quantile(per_limit),
                    target_yield: Some(y),
                })
            }
            (None, Some(n)) => {
                let v = self.finite(&path("k_sigma"), n)?;
                if !(v > 0.0 && v <= schema::K_SIGMA_MAX) {
                    return Err(self.err(
                        &path("k_sigma"),
                        format!(
                            "must be positive and at most {}, got {}",
                            schema::K_SIGMA_MAX,
                            short(v)
                        ),
                    ));
                }
                Ok(super::Robust {
                    k_sigma: v,
                    target_yield: None,
                })
            }
            _ => Err(self.err(
                &[k("search"), k("robust")],
                "give one of `yield` (a fraction of parts, e.g. 0.99) and `k_sigma` (standard \
                 deviations of margin, e.g. 3)",
            )),
        }
    }

    fn zones(&self, z: &schema::RawZones) -> Res<ZoneSettings> {
        let path = |key: &str| [k("zones"), k(key)];
        let mut thresholds = Vec::new();
        for (i, n) in z.thresholds.iter().flatten().enumerate() {
            let path = [k("zones"), k("thresholds"), Segment::Index(i)];
            let t = self.finite(&path, *n)?;
            if let Some(j) = thresholds.iter().position(|&u| u == t) {
                return Err(self.err(
                    &path,
                    format!(
                        "{} repeats thresholds[{j}]: each zone boundary once",
                        short(t)
                    ),
                ));
            }
            thresholds.push(t);
        }
        thresholds.sort_by(|a, b| b.total_cmp(a));
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
