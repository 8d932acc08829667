//! The physics: closed-form mechanism models, pure functions of a design, SI units.
//!
//! Each model is written once, generic over [`scalar::Scalar`], and exposed through the
//! object-safe [`Model`] trait, which speaks `f64` at its boundary and uses dual numbers
//! inside for exact gradients.

pub mod bridge;
pub mod bridge_dynamics;
pub mod bridge_lagrange;
pub mod bridge_matrix;
pub mod hinge;
pub mod material;
pub mod platform6;
pub mod prr3;
pub mod pss3;
pub mod scalar;

use serde::Serialize;

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

/// A design parameter of a model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ParameterInfo {
    pub name: &'static str,
    pub dimension: Dimension,
    pub description: &'static str,
}

impl ParameterInfo {
    pub const fn new(name: &'static str, dimension: Dimension, description: &'static str) -> Self {
        ParameterInfo {
            name,
            dimension,
            description,
        }
    }
}

/// A named output of a model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OutputInfo {
    pub name: &'static str,
    pub dimension: Dimension,
    pub description: &'static str,
}

impl OutputInfo {
    pub const fn new(name: &'static str, dimension: Dimension, description: &'static str) -> Self {
        OutputInfo {
            name,
            dimension,
            description,
        }
    }
}

/// A mechanism model as the problem layer and the optimizer see it.
///
/// `x` holds every parameter of [`Model::parameters`] in SI units; `wanted` lists indices
/// into [`Model::outputs`]; only those outputs are computed.
pub trait Model: Send + Sync {
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
    ($model:ty, $parameters:expr, $outputs:expr, $domain_error:expr) => {
        impl $crate::model::Model for $model {
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
fn unseed<const N: usize>(y: &[Jet<N>], out: &mut [f64], jacobian: &mut [f64]) {
    for (i, yi) in y.iter().enumerate() {
        out[i] = yi.re;
        jacobian[i * N..(i + 1) * N].copy_from_slice(&yi.grad);
    }
}

/// Largest number of outputs one evaluation may ask for.
pub const MAX_WANTED: usize = 32;

/// Largest number of parameters a model may have.
pub const MAX_PARAMETERS: usize = 16;

impl Model for bridge::Bridge {
    fn parameters(&self) -> &[ParameterInfo] {
        &bridge::PARAMETERS
    }

    fn outputs(&self) -> &[OutputInfo] {
        &bridge::OUTPUTS
    }

    fn max_of(&self, output: usize) -> Option<&[usize]> {
        use bridge::BridgeOutput::*;
        // the stresses at nodes 2, 3, 4, 5 (BridgeOutput::ALL lists the variants in order)
        const ALL_NODES: [usize; 4] = [
            StressNode2 as usize,
            StressNode3 as usize,
            StressNode4 as usize,
            StressNode5 as usize,
        ];
        match bridge::BridgeOutput::ALL[output] {
            StressMax => Some(&ALL_NODES),
            StressB => Some(&ALL_NODES[..2]),
            StressD => Some(&ALL_NODES[2..]),
            _ => None,
        }
    }

    fn unavailable(&self, output: usize) -> Option<String> {
        let o = bridge::BridgeOutput::ALL[output];
        (o.needs_dynamics() && self.settings.dynamics.is_none()).then(|| {
            format!(
                "output \"{}\" needs the masses and damping of a [dynamics] section",
                bridge::OUTPUTS[output].name
            )
        })
    }

    fn domain_error(&self, x: &[f64]) -> Option<String> {
        match <[f64; 8]>::try_from(x) {
            Ok(x) => bridge::Geometry::from_array(x).domain_error(),
            Err(_) => Some(format!("a bridge design has 8 parameters, got {}", x.len())),
        }
    }

    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        let x: [f64; 8] = x.try_into().expect("a bridge design has 8 parameters");
        bridge::Bridge::evaluate(self, &bridge::Geometry::from_array(x), wanted, out);
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        // most problems name a few outputs (wei2017: 9, its stress limit on four node
        // stresses): keep them on the stack without zeroing much
        let mut small = [Jet::<8>::from(0.0); 12];
        let mut large = Vec::new();
        let y = if wanted.len() <= small.len() {
            &mut small[..wanted.len()]
        } else {
            large.resize(wanted.len(), Jet::from(0.0));
            &mut large[..]
        };
        bridge::Bridge::evaluate(self, &bridge::Geometry::seeded(x), wanted, y);
        unseed(y, out, jacobian);
    }
}
