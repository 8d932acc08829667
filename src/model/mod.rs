//! The physics: closed-form mechanism models, pure functions of a design, SI units.
//!
//! Each model is written once, generic over [`scalar::Scalar`], and exposed through the
//! object-safe [`Model`] trait, which speaks `f64` at its boundary and uses dual numbers
//! inside for exact gradients. A model owns everything about itself: its problem-file
//! sections (read by its [`registry::ModelEntry`]), its parameters and outputs, the names of
//! its configurations and its drawing data. The rest of flexopt reaches a model only
//! through [`Model`] and the [`registry`].

pub mod bridge;
pub mod hinge;
pub mod material;
pub mod prr3;
pub mod pss3;
pub mod reference;
pub mod registry;
pub mod scalar;

use std::borrow::Cow;

use serde::Serialize;

use material::Material;

use scalar::Jet;

/// The physical dimension of a parameter or output; the problem layer converts units
/// against it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Dimension {
    /// Dimensionless.
    Ratio,
    /// m
    Length,
    /// rad
    Angle,
    /// N
    Force,
    /// Pa
    Stress,
    /// N/m
    Stiffness,
    /// m/N
    Compliance,
    /// kg
    Mass,
    /// N m/rad
    RotationalStiffness,
    /// Hz
    Frequency,
    /// s
    Time,
}

impl Dimension {
    /// The SI unit, as printed in outputs.
    pub fn si_unit(self) -> &'static str {
        match self {
            Dimension::Ratio => "1",
            Dimension::Length => "m",
            Dimension::Angle => "rad",
            Dimension::Force => "N",
            Dimension::Stress => "Pa",
            Dimension::Stiffness => "N/m",
            Dimension::Compliance => "m/N",
            Dimension::Mass => "kg",
            Dimension::RotationalStiffness => "N m/rad",
            Dimension::Frequency => "Hz",
            Dimension::Time => "s",
        }
    }
}

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

/// A named output of a model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OutputInfo {
    pub name: &'static str,
    pub dimension: Dimension,
    pub description: &'static str,
    /// The unit a designer reads it in, where the dimension's usual one does not suit it
    /// (a stroke of micrometres among spans of millimetres).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub display: Option<&'static str>,
}

impl OutputInfo {
    pub const fn new(name: &'static str, dimension: Dimension, description: &'static str) -> Self {
        OutputInfo {
            name,
            dimension,
            description,
            display: None,
        }
    }

    /// The same, read in `unit` (one of the dimension's units).
    pub const fn shown_in(self, unit: &'static str) -> Self {
        OutputInfo {
            display: Some(unit),
            ..self
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
    /// The chain's nodes (mm).
    pub nodes_mm: Vec<(f64, f64)>,
    /// Whether each member (between nodes `i` and `i + 1`) is rigid; flexible members are
    /// drawn in the zone's colour, rigid ones in grey.
    pub rigid: Vec<bool>,
    /// Each member's in-plane thickness (mm), drawn to scale; 0 draws its centre line.
    pub thickness_mm: Vec<f64>,
}

/// A mechanism model as the problem layer and the optimizer see it.
///
/// `x` holds every parameter of [`Model::parameters`] in SI units; `wanted` lists indices
/// into [`Model::outputs`]; only those outputs are computed.
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
    fn domain_error(&self, _x: &[f64]) -> Option<String> {
        None
    }

    /// Why some design between `lower` and `upper` (SI, every parameter) lies outside the
    /// model's domain although each bound is valid on its own (a corner-filleted hinge whose
    /// fillets may grow longer than half its leaf, say), with the parameter to blame.
    fn box_error(&self, _lower: &[f64], _upper: &[f64]) -> Option<(usize, String)> {
        None
    }

    /// The outputs whose maximum this output is, when it is defined so (a largest stress
    /// over several places, say). A max is not differentiable where its arguments cross, so
    /// an optimizer given `max <= limit` does better with `part <= limit` for every part.
    fn max_of(&self, _output: usize) -> Option<&[usize]> {
        None
    }

    /// Why this output cannot be computed with the model's settings, if it cannot (a
    /// dynamic output of a bridge without masses, say).
    fn unavailable(&self, _output: usize) -> Option<String> {
        None
    }

    /// The outputs that can be computed with the model's settings.
    fn available_outputs(&self) -> Vec<usize> {
        (0..self.outputs().len())
            .filter(|&i| self.unavailable(i).is_none())
            .collect()
    }

    /// Index of the output called `name`.
    fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs().iter().position(|o| o.name == name)
    }

    /// The material, where the model has one: constraints may set a stress limit as a
    /// fraction of its strength.
    fn material(&self) -> Option<&Material> {
        None
    }

    /// The bound on every angle parameter's size, exclusive, where the model has one (the
    /// bridge's angles stay within a right angle); bounds in a problem file must respect it.
    fn angle_limit(&self) -> Option<f64> {
        None
    }

    /// The kind of configuration the design `x` (SI) is, by [`Model::configuration_rule`];
    /// `-` for a model whose topology does not change.
    fn configuration(&self, _x: &[f64]) -> &'static str {
        "-"
    }

    /// The rule by which [`Model::configuration`] names designs, for readers of the results.
    fn configuration_rule(&self) -> Option<&'static str> {
        None
    }

    /// Nodes and mode shapes of the design `x` (SI) for its report.
    fn drawing(&self, _x: &[f64]) -> Drawing {
        Drawing::default()
    }

    /// The design `x` (SI) as a chain of members, for the configuration plot; `None` where
    /// the model has no such picture, and then no plot is drawn.
    fn skeleton(&self, _x: &[f64]) -> Option<Skeleton> {
        None
    }

    /// The legend of the configuration plot: what the colours and the origin mean.
    fn skeleton_legend(&self) -> &'static str {
        ""
    }

    /// Whether the mirror image of `x` (every angle negated), which the model evaluates to
    /// the same outputs up to sign, is the orientation to report: a study that merges mirror
    /// images reports its optimum in the orientation a designer draws (the bridge: output
    /// blocks outward, as paper 004's Fig. 1 and 3 draw them).
    fn prefers_mirror(&self, _x: &[f64]) -> bool {
        false
    }

    /// The solids of the design `x` (SI) as a part ([`crate::part`]), or what makes the
    /// part impossible; `None` for a model without a part.
    fn part(&self, _x: &[f64]) -> Option<Result<crate::part::PartSpec, Vec<String>>> {
        None
    }

    /// What of the finite-element check its part states ([`crate::part::analysis`])
    /// measures what the model's output `output` computes, if anything does: what `flexopt
    /// verify` compares it with and `run --refine fe` corrects it by.
    fn fe_counterpart(&self, _output: usize) -> Option<crate::part::analysis::FeCounterpart> {
        None
    }
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

/// Implements [`Model`] for a type with [`AllOutputs`]: its parameters and outputs tables, its
/// domain check (a function of the design), and evaluation by picking from all outputs.
macro_rules! model_from_all_outputs {
    ($model:ty, $name:expr, $parameters:expr, $outputs:expr, $domain_error:expr, $drawing:expr) => {
        impl $crate::model::Model for $model {
            fn name(&self) -> &'static str {
                $name
            }

            fn drawing(&self, x: &[f64]) -> $crate::model::Drawing {
                $drawing(x)
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
        return Some(format!("{} = {} must be positive", info[i].name, x[i]));
    }
    if let Some(&i) = non_negative.iter().find(|&&i| x[i] < 0.0) {
        return Some(format!("{} = {} must not be negative", info[i].name, x[i]));
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
pub const MAX_WANTED: usize = 32;

/// Largest number of parameters a model may have.
pub const MAX_PARAMETERS: usize = 16;
