//! The `[tolerances]` section: how far a made part strays from its design, input by input
//! (each design variable, free or fixed, and the material's Young's modulus), for the
//! tolerance analysis (`flexopt tolerance`) and the robust study (`[search] robust`).
//!
//! ```toml
//! [tolerances]
//! t2 = { plus_minus = 0.005 }                            # in the variable's unit (mm)
//! l2 = { sigma = 0.004, distribution = "uniform" }
//! youngs_modulus = { plus_minus = 0.03 }                 # a fraction of E
//! ```
//!
//! `plus_minus` is the band a process holds: three standard deviations of a normal
//! distribution (a capability index of 1), the half width of a uniform one. A mechanism
//! with a part gets the defaults of its process, wire EDM ([`DEFAULTS`]), for every input
//! the file leaves out.

use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use super::reader::{k, quoted, Reader, Res};
use super::Variable;
use crate::model::{Dimension, Mechanism};
use crate::vocab::values::{Choices, Number};

/// The key of the material's Young's modulus (with the shear modulus, at a fixed Poisson's
/// ratio): its tolerance is a fraction of `E`.
pub const YOUNGS_MODULUS: &str = "youngs_modulus";

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
    /// The band `plus_minus` stands for, in standard deviations.
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
    /// The band, `distribution.band()` standard deviations, in `unit`.
    pub plus_minus: f64,
    /// The file's unit of the input (`"1"` for the modulus's fraction).
    pub unit: String,
    pub origin: Origin,
}

impl Tolerance {
    /// The band, SI (a fraction for the modulus).
    pub fn band(&self) -> f64 {
        self.sigma * self.distribution.band()
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
    raw: &IndexMap<String, RawTolerance>,
) -> Res<Vec<Tolerance>> {
    let model = mechanism.physics.as_ref();
    let params = model.parameters();
    let has_modulus = mechanism.modulus.is_some() && model.material().is_some();
    let mut out = Vec::new();
    for (name, t) in raw {
        let path = |key: &str| [k("tolerances"), k(name), k(key)];
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
                         problem; expected one of {}",
                        quoted(&names)
                    ),
                ));
            };
            (Input::Parameter(v.parameter), Some(&v.unit))
        };
        let distribution = match &t.distribution {
            Some(d) => reader.choice(&path("distribution"), d, &DISTRIBUTIONS)?,
            None => Distribution::Normal,
        };
        let (key, n, in_sigmas) = match (t.plus_minus, t.sigma) {
            (Some(n), None) => ("plus_minus", n, distribution.band()),
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
        out.push(Tolerance {
            name: name.clone(),
            input,
            sigma,
            distribution,
            plus_minus: unit.map_or(sigma, |u| u.from_si(sigma)) * distribution.band(),
            unit: unit_name,
            origin: Origin::File,
        });
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

fn default(name: String, input: Input, band: f64, shown: f64, unit: &str) -> Tolerance {
    Tolerance {
        name,
        input,
        sigma: band / Distribution::Normal.band(),
        distribution: Distribution::Normal,
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
