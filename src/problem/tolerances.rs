//! The `[tolerances]` section: how far a made part strays from its design, input by input
//! (each design variable, free or fixed, and the material's Young's modulus), for the
//! tolerance analysis (`flexopt tolerance`) and the robust study (`[search] robust`).
//!
//! ```toml
//! [tolerances]
//! t2 = { plus_minus = 0.005 }                            # in the variable's unit (mm)
//! l2 = { sigma = 0.004, distribution = "uniform" }
//! youngs_modulus = { plus_minus = 0.03 }                 # a fraction of E
//! l3 = { plus_minus = 0.01, coverage = "2 sigma" }       # the band as the drawing states it
//! coverage = 3                                           # the section's, for every band
//! yield_of = ["k_in", "k_out"]                           # the constraints the yield counts
//! ```
//!
//! `plus_minus` is the band a process holds: `coverage` standard deviations of a normal
//! distribution (three, a capability index of 1, unless the tolerance or the section says
//! otherwise), the half width of a uniform one. A mechanism with a part gets the defaults of
//! its process, wire EDM ([`DEFAULTS`]), for every input the file leaves out. `yield_of`
//! names the constraints a made part must meet to count in the yield (every one by default).

use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use super::reader::{k, quoted, Reader, Res};
use super::{Constraint, Segment, Variable};
use crate::model::{Dimension, Mechanism};
use crate::vocab::values::{Choices, Number};

/// The key of the material's Young's modulus (with the shear modulus, at a fixed Poisson's
/// ratio): its tolerance is a fraction of `E`.
pub const YOUNGS_MODULUS: &str = "youngs_modulus";

/// The section's key of the coverage its bands are stated at.
pub const COVERAGE: &str = "coverage";
/// The section's key of the constraints the yield counts.
pub const YIELD_OF: &str = "yield_of";

/// A band's coverage as written: a number of standard deviations, or text such as
/// `"2 sigma"`.
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum RawCoverage {
    #[schemars(extend("exclusiveMinimum" = 0))]
    Sigmas(Number),
    #[schemars(extend("pattern" = COVERAGE_PATTERN))]
    Text(String),
}

/// The text a coverage may take: a positive number and `sigma` or `σ`.
pub const COVERAGE_PATTERN: &str = r"^\s*[0-9]*\.?[0-9]+\s*(sigma|σ)\s*$";

/// One entry of the section: a tolerance (a table), the section's coverage (a number or a
/// text) or the yield's constraints (a list); the key says which it must be. Read by its
/// shape, so that an error inside a tolerance keeps its key path.
#[derive(Debug)]
pub enum RawEntry {
    Tolerance(RawTolerance),
    Coverage(RawCoverage),
    Names(Vec<String>),
}

impl<'de> Deserialize<'de> for RawEntry {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
        struct Entry;
        impl<'de> serde::de::Visitor<'de> for Entry {
            type Value = RawEntry;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table such as { plus_minus = 0.005 }, a coverage or a list of names")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, m: A) -> Result<RawEntry, A::Error> {
                RawTolerance::deserialize(MapAccessDeserializer::new(m)).map(RawEntry::Tolerance)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, s: A) -> Result<RawEntry, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(s)).map(RawEntry::Names)
            }
            fn visit_i64<E>(self, v: i64) -> Result<RawEntry, E> {
                Ok(RawEntry::Coverage(RawCoverage::Sigmas(Number::Int(v))))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<RawEntry, E> {
                let v = i64::try_from(v).map_err(E::custom)?;
                self.visit_i64(v)
            }
            fn visit_f64<E>(self, v: f64) -> Result<RawEntry, E> {
                Ok(RawEntry::Coverage(RawCoverage::Sigmas(Number::Float(v))))
            }
            fn visit_str<E>(self, v: &str) -> Result<RawEntry, E> {
                Ok(RawEntry::Coverage(RawCoverage::Text(v.to_string())))
            }
        }
        d.deserialize_any(Entry)
    }
}

/// One tolerance as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("oneOf" = [
    {"required": ["plus_minus"], "not": {"required": ["sigma"]}},
    {"required": ["sigma"], "not": {"required": ["plus_minus"]}},
]))]
pub struct RawTolerance {
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub plus_minus: Option<Number>,
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub sigma: Option<Number>,
    #[schemars(extend("enum" = DISTRIBUTIONS.names()))]
    pub distribution: Option<String>,
    pub coverage: Option<RawCoverage>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Distribution {
    Normal,
    Uniform,
}

/// `distribution`; the first is the default.
pub const DISTRIBUTIONS: Choices<Distribution> = Choices(&[
    ("normal", Distribution::Normal),
    ("uniform", Distribution::Uniform),
]);

impl Distribution {
    /// The band `plus_minus` stands for, in standard deviations, where the file states no
    /// coverage.
    pub fn band(self) -> f64 {
        match self {
            Distribution::Normal => 3.0,
            Distribution::Uniform => 3f64.sqrt(),
        }
    }
}

/// What a tolerance varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Input {
    /// A model parameter, by index.
    Parameter(usize),
    /// The material's moduli, as a factor on the nominal ones.
    Modulus,
}

/// Where a tolerance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Origin {
    File,
    /// The process's default ([`DEFAULTS`]).
    Default,
}

/// One validated tolerance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tolerance {
    pub name: String,
    pub input: Input,
    /// The standard deviation: SI for a parameter, a fraction for the modulus.
    pub sigma: f64,
    pub distribution: Distribution,
    /// The band's coverage: the standard deviations `plus_minus` stands for.
    pub coverage: f64,
    /// The band, `coverage` standard deviations, in `unit`.
    pub plus_minus: f64,
    /// The file's unit of the input (`"1"` for the modulus's fraction).
    pub unit: String,
    pub origin: Origin,
}

impl Tolerance {
    /// The band, SI (a fraction for the modulus).
    pub fn band(&self) -> f64 {
        self.sigma * self.coverage
    }
}

/// The defaults of wire EDM, the process the parts are cut by, as bands of a normal
/// distribution (three standard deviations), each with its source.
pub struct Defaults {
    /// A hinge's thickness (m): cut from both sides, the wire's wander and the spark gap's
    /// scatter both land on it.
    pub thickness: f64,
    /// Any other length (m).
    pub length: f64,
    /// Young's modulus, a fraction.
    pub youngs_modulus: f64,
}

/// Wire EDM holds +-0.005 mm on a fine finish (four to six passes) and +-0.01 mm on a
/// standard one (shops' published tables, e.g. mecvil.com's "Wire EDM: tolerances,
/// materials and industrial applications" and tongrencnc.com's on multi-pass cutting, which
/// gives +-0.003 to 0.005 mm after skim passes): the hinges take the fine finish, the other
/// lengths the standard one. Young's modulus comes without a tolerance in the handbooks; its
/// figures for one alloy differ by one to three per cent (7075-T6: 72 GPa in paper 004,
/// 71.7 GPa in MatWeb), so +-3 % covers a bar of unknown heat.
pub const DEFAULTS: Defaults = Defaults {
    thickness: 5e-6,
    length: 10e-6,
    youngs_modulus: 0.03,
};

/// Whether a parameter is a hinge's thickness: its description names one (every hinge kind
/// describes its thickness so, [`crate::model::hinge`]).
fn is_thickness(description: &str) -> bool {
    description.contains("thickness")
}

/// The tolerances of the `[tolerances]` section `raw`, with the defaults for the inputs it
/// leaves out where `mechanism` has a part.
pub(crate) fn tolerances(
    reader: &Reader,
    mechanism: &Mechanism,
    variables: &[Variable],
    raw: &IndexMap<String, RawEntry>,
) -> Res<Vec<Tolerance>> {
    let model = mechanism.physics.as_ref();
    let params = model.parameters();
    let has_modulus = mechanism.modulus.is_some() && model.material().is_some();
    let section_coverage = match raw.get(COVERAGE) {
        None => None,
        Some(RawEntry::Coverage(c)) => Some(coverage(reader, &[k("tolerances"), k(COVERAGE)], c)?),
        Some(_) => {
            return Err(reader.err(
                &[k("tolerances"), k(COVERAGE)],
                "the section's coverage is a number of standard deviations or a text such as \
                 \"2 sigma\"",
            ))
        }
    };
    let mut out = Vec::new();
    for (name, entry) in raw {
        if name == COVERAGE || name == YIELD_OF {
            continue;
        }
        let RawEntry::Tolerance(t) = entry else {
            return Err(reader.err(
                &[k("tolerances"), k(name)],
                format!(
                    "expected {}",
                    crate::vocab::reader::table_expected("RawTolerance")
                ),
            ));
        };
        let (input, unit) = if name == YOUNGS_MODULUS {
            if !has_modulus {
                return Err(reader.err(
                    &[k("tolerances"), k(name)],
                    format!(
                        "the {} model cannot vary its material's modulus: remove this \
                         tolerance",
                        model.name()
                    ),
                ));
            }
            (Input::Modulus, None)
        } else {
            let Some(v) = variables.iter().find(|v| &v.name == name) else {
                let mut names: Vec<&str> = variables.iter().map(|v| v.name.as_str()).collect();
                if has_modulus {
                    names.push(YOUNGS_MODULUS);
                }
                return Err(reader.err(
                    &[k("tolerances"), k(name)],
                    format!(
                        "\"{name}\" is no design variable or material property of this \
                         problem, nor `{COVERAGE}` or `{YIELD_OF}`; expected one of {}",
                        quoted(&names)
                    ),
                ));
            };
            (Input::Parameter(v.parameter), Some(&v.unit))
        };
        out.push(one(reader, name, t, input, unit, section_coverage)?);
    }
    if mechanism.part_maker.is_some() {
        for v in variables {
            let p = &params[v.parameter];
            let band = match p.dimension {
                Dimension::Length if is_thickness(&p.description) => DEFAULTS.thickness,
                Dimension::Length => DEFAULTS.length,
                _ => continue,
            };
            if !raw.contains_key(&v.name) {
                out.push(default(
                    v.name.clone(),
                    Input::Parameter(v.parameter),
                    band,
                    v.unit.from_si(band),
                    &v.unit.name,
                ));
            }
        }
        if has_modulus && !raw.contains_key(YOUNGS_MODULUS) {
            let band = DEFAULTS.youngs_modulus;
            out.push(default(
                YOUNGS_MODULUS.into(),
                Input::Modulus,
                band,
                band,
                "1",
            ));
        }
    }
    // in the model's order of inputs, the modulus last, whatever the file's order
    out.sort_by_key(|t| match t.input {
        Input::Parameter(i) => i,
        Input::Modulus => usize::MAX,
    });
    Ok(out)
}

/// The tolerance `name` as written, `t`, on `input` in `unit` (none: the modulus's
/// fraction), its band at its own coverage, else the section's, else the distribution's.
fn one(
    reader: &Reader,
    name: &str,
    t: &RawTolerance,
    input: Input,
    unit: Option<&crate::vocab::units::Unit>,
    section_coverage: Option<f64>,
) -> Res<Tolerance> {
    let path = |key: &str| [k("tolerances"), k(name), k(key)];
    let distribution = match &t.distribution {
        Some(d) => reader.choice(&path("distribution"), d, &DISTRIBUTIONS)?,
        None => Distribution::Normal,
    };
    let own = t
        .coverage
        .as_ref()
        .map(|c| coverage(reader, &path(COVERAGE), c))
        .transpose()?;
    if own.is_some() && (distribution == Distribution::Uniform || t.plus_minus.is_none()) {
        return Err(reader.err(
            &path(COVERAGE),
            "a coverage says how many standard deviations a normal `plus_minus` band stands \
             for: give it with `plus_minus` and a normal distribution (a uniform band is its \
             half width, a `sigma` the standard deviation itself)",
        ));
    }
    let band_sigmas = match distribution {
        Distribution::Normal => own.or(section_coverage).unwrap_or(distribution.band()),
        Distribution::Uniform => distribution.band(),
    };
    let (key, n, in_sigmas) = match (t.plus_minus, t.sigma) {
        (Some(n), None) => ("plus_minus", n, band_sigmas),
        (None, Some(n)) => ("sigma", n, 1.0),
        _ => {
            return Err(reader.err(
                &[k("tolerances"), k(name)],
                "give one of `plus_minus` (the band) and `sigma` (the standard deviation)",
            ))
        }
    };
    let value = reader.finite(&path(key), n)?;
    let unit_name = unit.map_or("1".to_string(), |u| u.name.clone());
    if value <= 0.0 {
        return Err(reader.err(
            &path(key),
            format!(
                "a tolerance must be positive, got {} {unit_name}",
                crate::vocab::units::short(value)
            ),
        ));
    }
    let si = unit.map_or(value, |u| u.to_si(value));
    let sigma = si / in_sigmas;
    Ok(Tolerance {
        name: name.to_string(),
        input,
        sigma,
        distribution,
        coverage: band_sigmas,
        plus_minus: unit.map_or(sigma, |u| u.from_si(sigma)) * band_sigmas,
        unit: unit_name,
        origin: Origin::File,
    })
}

/// A coverage as written at `path`, in standard deviations: positive and finite.
fn coverage(reader: &Reader, path: &[Segment], c: &RawCoverage) -> Res<f64> {
    let sigmas = match c {
        RawCoverage::Sigmas(n) => Some(n.get()),
        RawCoverage::Text(text) => {
            let t = text.trim();
            t.strip_suffix("sigma")
                .or_else(|| t.strip_suffix('σ'))
                .and_then(|n| n.trim().parse::<f64>().ok())
        }
    };
    match sigmas {
        Some(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(reader.err(
            path,
            format!(
                "a coverage is a positive number of standard deviations, such as 2, \
                 \"2 sigma\" or \"3σ\"; got {}",
                match c {
                    RawCoverage::Sigmas(n) => crate::vocab::units::short(n.get()),
                    RawCoverage::Text(t) => format!("\"{t}\""),
                }
            ),
        )),
    }
}

/// Marks the constraints `[tolerances] yield_of` names as the ones the yield counts (every
/// constraint where the key is absent); a name that is no constrained output is an error.
pub(crate) fn yield_of(
    reader: &Reader,
    raw: &IndexMap<String, RawEntry>,
    constraints: &mut [Constraint],
) -> Res<()> {
    let path = [k("tolerances"), k(YIELD_OF)];
    let names = match raw.get(YIELD_OF) {
        None => return Ok(()),
        Some(RawEntry::Names(names)) => names,
        Some(_) => {
            return Err(reader.err(
                &path,
                "a list of constrained outputs, such as [\"k_in\", \"k_out\"]",
            ))
        }
    };
    if names.is_empty() {
        return Err(reader.err(
            &path,
            "names no constraint: list the constrained outputs the yield counts, or leave the \
             key out to count every constraint",
        ));
    }
    for c in constraints.iter_mut() {
        c.in_yield = false;
    }
    for (i, name) in names.iter().enumerate() {
        let Some(c) = constraints.iter_mut().find(|c| &c.output == name) else {
            let outputs: Vec<&str> = constraints.iter().map(|c| c.output.as_str()).collect();
            return Err(reader.err(
                &[k("tolerances"), k(YIELD_OF), Segment::Index(i)],
                format!(
                    "\"{name}\" is no constrained output of this problem; expected one of {}",
                    quoted(&outputs)
                ),
            ));
        };
        c.in_yield = true;
    }
    Ok(())
}

fn default(name: String, input: Input, band: f64, shown: f64, unit: &str) -> Tolerance {
    Tolerance {
        name,
        input,
        sigma: band / Distribution::Normal.band(),
        distribution: Distribution::Normal,
        coverage: Distribution::Normal.band(),
        plus_minus: shown,
        unit: unit.to_string(),
        origin: Origin::Default,
    }
}

/// The standard normal distribution's cumulative probability at `x`.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The standard normal quantile of `p` (0 < p < 1): bisection of [`normal_cdf`], which
/// is monotone, down to adjacent floating-point numbers.
pub fn normal_quantile(p: f64) -> f64 {
    let (mut lo, mut hi) = (-40.0, 40.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if normal_cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Refuses, in a robust study, an output used by the objective or a constraint (`used`: its
/// key path and index) that cannot be differentiated twice
/// ([`crate::model::mechanism::ModulusScaling::first_order_only`]).
pub(crate) fn first_order_only(
    reader: &Reader,
    mechanism: &Mechanism,
    robust: bool,
    used: impl Iterator<Item = (Vec<Segment>, usize)>,
) -> Res<()> {
    let Some(scaling) = mechanism.modulus.as_ref().filter(|_| robust) else {
        return Ok(());
    };
    for (path, index) in used {
        if let Some(why) = scaling.first_order_only(index) {
            return Err(reader.err(&path, why));
        }
    }
    Ok(())
}
