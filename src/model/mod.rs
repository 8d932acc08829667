//! The physics: closed-form mechanism models, pure functions of a design, SI units.
//!
//! Each model is written once, generic over [`scalar::Scalar`], and exposed through the
//! object-safe [`Model`] trait, which speaks `f64` at its boundary and uses dual numbers
//! inside for exact gradients. A model owns everything about itself: its problem-file
//! sections (read by its [`registry::ModelEntry`]), its parameters and outputs, and, as
//! capabilities beside its physics ([`mechanism`]), the names of its configurations, its
//! drawing data, its part and the finite-element check the part states. The rest of flexopt
//! reaches a model only through a [`Mechanism`] and the [`registry`].

pub mod bridge;
pub mod clearance;
pub mod entry;
pub mod expression;
pub mod fit;
pub mod hinge;
pub mod jet2;
pub mod material;
pub mod mechanism;
pub mod network;
pub mod part_rules;
pub mod prr3;
pub mod pss3;
pub mod reference;
pub mod registry;
pub mod scalar;

use std::borrow::Cow;

use serde::Serialize;

use material::Material;
pub use mechanism::{build_part, Depiction, Mechanism, PartMaker};

use scalar::Jet;

pub use crate::vocab::Dimension;

/// A design parameter of a model. Names are owned where a model builds them (the bridge
/// names its hinges' dimensions after the hinge).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterInfo {
    pub name: Cow<'static, str>,
    pub dimension: Dimension,
    pub description: Cow<'static, str>,
}

impl ParameterInfo {
    pub const fn new(name: &'static str, dimension: Dimension, description: &'static str) -> Self {
        ParameterInfo {
            name: Cow::Borrowed(name),
            dimension,
            description: Cow::Borrowed(description),
        }
    }
}

/// A named output of a model. Names are owned where a model builds them at run time (a
/// network names outputs after its ports and hinges).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputInfo {
    pub name: Cow<'static, str>,
    pub dimension: Dimension,
    pub description: Cow<'static, str>,
    /// The unit a designer reads it in, where the dimension's usual one does not suit it
    /// (a stroke of micrometres among spans of millimetres).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub display: Option<&'static str>,
    /// Set where only a higher fidelity gives the quantity (the part's first natural mode,
    /// which no closed form of the model reaches): what the model's value is instead, for
    /// the refinement to correct. Analytic reports leave such an output out and mark a
    /// limit on it; only a refined optimum meets it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stand_in: Option<&'static str>,
}

impl OutputInfo {
    pub const fn new(name: &'static str, dimension: Dimension, description: &'static str) -> Self {
        OutputInfo {
            name: Cow::Borrowed(name),
            dimension,
            description: Cow::Borrowed(description),
            display: None,
            stand_in: None,
        }
    }

    /// As [`OutputInfo::new`], read in `display` (one of the dimension's units) where the
    /// dimension's usual one does not suit it, and given only by a higher fidelity where
    /// `stand_in` says what the model's value is instead. One constructor rather than
    /// builder methods: a const fn may not take apart a value with owned parts.
    pub const fn full(
        name: &'static str,
        dimension: Dimension,
        description: &'static str,
        display: Option<&'static str>,
        stand_in: Option<&'static str>,
    ) -> Self {
        OutputInfo {
            name: Cow::Borrowed(name),
            dimension,
            description: Cow::Borrowed(description),
            display,
            stand_in,
        }
    }
}

/// A natural mode of a mechanism: its frequency (Hz) and its shape in the platform
/// coordinates, normalised so that `v^T M v = 1`: `(x, y, gamma)` (m, m, rad) for a planar
/// mechanism, `(x, y, z)` (m) for a spatial one.
#[derive(Debug, Clone, Serialize)]
pub struct ModeShape {
    pub frequency: f64,
    pub x: f64,
    pub y: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
}

/// What a design report shows of a design besides its outputs.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Drawing {
    /// The mechanism's nodes in mm (the bridge's quarter: nodes 2..5, origin at node 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nodes_mm: Option<Vec<[f64; 2]>>,
    /// The natural modes, mass-normalised (parallel mechanisms).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode_shapes: Option<Vec<ModeShape>>,
}

/// A design drawn as a chain of straight members, for the plot of every optimum's
/// configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Skeleton {
    /// The chain's nodes (mm); a node that is not a number breaks the chain (a network's
    /// pieces), and neither member beside it is drawn.
    pub nodes_mm: Vec<(f64, f64)>,
    /// Whether each member (between nodes `i` and `i + 1`) is rigid; flexible members are
    /// drawn in the zone's colour, rigid ones in grey.
    pub rigid: Vec<bool>,
    /// Each member's in-plane thickness (mm), drawn to scale; 0 draws its centre line.
    pub thickness_mm: Vec<f64>,
}

/// A mechanism's physics, as the problem layer and the optimizer see it: parameters in,
/// outputs out, and the few facts about its domain and symmetry that a study needs.
///
/// `x` holds every parameter of [`Model::parameters`] in SI units; `wanted` lists indices
/// into [`Model::outputs`]; only those outputs are computed. Every method but the two
/// derived ones must be written by each model: a wrapper (the refinement's corrected model)
/// cannot drop one of the inner model's answers by forgetting to forward it. What a model
/// can do beyond its physics (pictures, a part, finite-element load cases) are separate
/// capabilities, bundled with the physics in a [`Mechanism`].
pub trait Model: Send + Sync + std::fmt::Debug {
    /// The name a problem file's `model` key gives it.
    fn name(&self) -> &'static str;
    fn parameters(&self) -> &[ParameterInfo];
    fn outputs(&self) -> &[OutputInfo];
    /// Writes the wanted outputs into `out` (same length as `wanted`).
    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]);
    /// As [`Model::evaluate`], and the exact gradients into `jacobian`, row-major:
    /// `jacobian[i * n + j]` is d out_i / d x_j with `n = parameters().len()`.
    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    );

    /// Why the design `x` (SI) lies outside the model's domain, if it does; the model's
    /// outputs are finite everywhere else.
    fn domain_error(&self, x: &[f64]) -> Option<String>;

    /// Why some design between `lower` and `upper` (SI, every parameter) lies outside the
    /// model's domain although each bound is valid on its own (a corner-filleted hinge whose
    /// fillets may grow longer than half its leaf, say), with the parameter to blame.
    fn box_error(&self, lower: &[f64], upper: &[f64]) -> Option<(usize, String)>;

    /// The outputs whose maximum this output is, when it is defined so (a largest stress
    /// over several places, say). A max is not differentiable where its arguments cross, so
    /// an optimizer given `max <= limit` does better with `part <= limit` for every part.
    fn max_of(&self, output: usize) -> Option<&[usize]>;

    /// Why this output cannot be computed with the model's settings, if it cannot (a
    /// dynamic output of a bridge without masses, say).
    fn unavailable(&self, output: usize) -> Option<String>;

    /// The material, where the model has one: constraints may set a stress limit as a
    /// fraction of its strength.
    fn material(&self) -> Option<&Material>;

    /// The bound on every angle parameter's size, exclusive, where the model has one (the
    /// bridge's angles stay within a right angle); bounds in a problem file must respect it.
    fn angle_limit(&self) -> Option<f64>;

    /// The mirror image of the design `x` (SI, every parameter), written over it: a design
    /// that the model evaluates to the same outputs up to sign and draws as the same
    /// geometry the other way round. `false`, and `x` untouched, for a model without such a
    /// symmetry; a study merges a design with its mirror image only where this says so.
    fn mirror(&self, x: &mut [f64]) -> bool;

    /// The ranges of ratios of parameters within which the model's fitted formulas hold
    /// (each hinge's, say): `eval`, `run` and `hinge` warn of a design outside them, and a
    /// study keeps to them as constraints unless the problem file says otherwise. Empty for
    /// a model without fitted formulas.
    fn fit_limits(&self) -> &[fit::FitLimit];

    /// The outputs that can be computed with the model's settings.
    fn available_outputs(&self) -> Vec<usize> {
        (0..self.outputs().len())
            .filter(|&i| self.unavailable(i).is_none())
            .collect()
    }

    /// The available outputs the model itself gives: without those whose value only stands
    /// in for a higher fidelity's ([`OutputInfo::stand_in`]).
    fn analytic_outputs(&self) -> Vec<usize> {
        let infos = self.outputs();
        self.available_outputs()
            .into_iter()
            .filter(|&i| infos[i].stand_in.is_none())
            .collect()
    }

    /// Index of the output called `name`.
    fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs().iter().position(|o| o.name == name)
    }
}

/// Negates the angle parameters of `x` (the mirror image of a planar mechanism whose every
/// angle is measured from its symmetry axis); `false` where it has none.
pub(crate) fn negate_angles(parameters: &[ParameterInfo], x: &mut [f64]) -> bool {
    let mut any = false;
    for (xi, p) in x.iter_mut().zip(parameters) {
        if p.dimension == Dimension::Angle {
            *xi = -*xi;
            any = true;
        }
    }
    any
}

/// A model that computes all its outputs at once (a parallel mechanism's frequencies come
/// from one eigen-solve): `evaluate` and `evaluate_with_gradient` pick the wanted ones.
pub(crate) trait AllOutputs<const N: usize, const K: usize> {
    /// Every output at `x` (model order); `None` where the model has no value.
    fn all<D: scalar::Scalar>(&self, x: &[D]) -> Option<[D; K]>;

    fn pick_values(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        let all = self.all(x).unwrap_or([f64::NAN; K]);
        for (slot, &k) in out.iter_mut().zip(wanted) {
            *slot = all[k];
        }
    }

    fn pick_gradients(&self, x: &[f64], wanted: &[usize], out: &mut [f64], jacobian: &mut [f64]) {
        let seeded: [Jet<N>; N] = std::array::from_fn(|i| Jet::variable(x[i], i));
        let nan = Jet {
            re: f64::NAN,
            grad: [f64::NAN; N],
        };
        let all = self.all(&seeded).unwrap_or([nan; K]);
        let picked: Vec<Jet<N>> = wanted.iter().map(|&k| all[k]).collect();
        unseed(&picked, out, jacobian);
    }
}

/// Implements [`Model`] for a type with [`AllOutputs`] (its parameters and outputs tables,
/// its domain check, a function of the design, and evaluation by picking from all outputs),
/// and [`Depiction`] with its drawing (a function of the design): a parallel mechanism
/// without material, part, configurations or bounds between parameters.
macro_rules! model_from_all_outputs {
    ($model:ty, $name:expr, $parameters:expr, $outputs:expr, $domain_error:expr, $drawing:expr) => {
        impl $crate::model::Model for $model {
            fn name(&self) -> &'static str {
                $name
            }

            fn parameters(&self) -> &[$crate::model::ParameterInfo] {
                &$parameters
            }

            fn outputs(&self) -> &[$crate::model::OutputInfo] {
                &$outputs
            }

            fn domain_error(&self, x: &[f64]) -> Option<String> {
                $domain_error(x)
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

            fn material(&self) -> Option<&$crate::model::material::Material> {
                None
            }

            fn angle_limit(&self) -> Option<f64> {
                None
            }

            fn mirror(&self, x: &mut [f64]) -> bool {
                $crate::model::negate_angles(&$parameters, x)
            }

            fn fit_limits(&self) -> &[$crate::model::fit::FitLimit] {
                &[]
            }

            fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
                self.pick_values(x, wanted, out);
            }

            fn evaluate_with_gradient(
                &self,
                x: &[f64],
                wanted: &[usize],
                out: &mut [f64],
                jacobian: &mut [f64],
            ) {
                self.pick_gradients(x, wanted, out, jacobian);
            }
        }

        impl $crate::model::Depiction for $model {
            fn drawing(&self, x: &[f64]) -> $crate::model::Drawing {
                $drawing(x)
            }
        }
    };
}
pub(crate) use model_from_all_outputs;

/// The checks every parallel mechanism's `domain_error` starts with: the number of
/// parameters, finite values, positive lengths (`positive`) and non-negative ones
/// (`non_negative`, masses and stiffnesses, say).
pub(crate) fn check_parameters(
    model: &str,
    info: &[ParameterInfo],
    x: &[f64],
    positive: &[usize],
    non_negative: &[usize],
) -> Option<String> {
    if x.len() != info.len() {
        return Some(format!(
            "a {model} design has {} parameters, got {}",
            info.len(),
            x.len()
        ));
    }
    if let Some((i, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Some(format!("{} = {v} is not finite", info[i].name));
    }
    if let Some(&i) = positive.iter().find(|&&i| x[i] <= 0.0) {
        return Some(format!(
            "{} = {} must be positive",
            info[i].name,
            crate::vocab::units::short(x[i])
        ));
    }
    if let Some(&i) = non_negative.iter().find(|&&i| x[i] < 0.0) {
        return Some(format!(
            "{} = {} must not be negative",
            info[i].name,
            crate::vocab::units::short(x[i])
        ));
    }
    None
}

/// Splits gradient-carrying results into values and a row-major Jacobian.
pub(crate) fn unseed<const N: usize>(y: &[Jet<N>], out: &mut [f64], jacobian: &mut [f64]) {
    for (i, yi) in y.iter().enumerate() {
        out[i] = yi.re;
        jacobian[i * N..(i + 1) * N].copy_from_slice(&yi.grad);
    }
}

/// Largest number of outputs one evaluation may ask for.
pub const MAX_WANTED: usize = 128;

/// Largest number of parameters a model may have.
pub const MAX_PARAMETERS: usize = 16;
