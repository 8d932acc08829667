//! A mechanism: its physics ([`Model`]) and what else it can do, each capability a trait of
//! its own: pictures of a design ([`Depiction`]), the part that is cut and the finite-element
//! check of it ([`PartMaker`]).
//!
//! The capabilities are held beside the physics in a [`Mechanism`] rather than as defaulted
//! methods of one trait, so that a wrapper which changes the physics (the refinement's
//! corrected model) replaces the physics alone ([`Mechanism::with_physics`]) and keeps every
//! capability of the mechanism it wraps without forwarding a method.

use std::sync::Arc;

use super::large::report::LargeDeflection;
use super::part_rules::{PartRule, Witness};
use super::{Drawing, Model, Skeleton};
use crate::part::analysis::FeCounterpart;
use crate::part::{Part, PartError, PartSpec};

/// What a design report and the study's pictures show of a design besides its outputs.
pub trait Depiction: Send + Sync + std::fmt::Debug {
    /// The kind of configuration the design `x` (SI) is, by
    /// [`Depiction::configuration_rule`]; `-` for a model whose topology does not change.
    fn configuration(&self, _x: &[f64]) -> &'static str {
        "-"
    }

    /// The rule by which [`Depiction::configuration`] names designs, for readers of the
    /// results.
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

    /// Whether the mirror image of `x` ([`Model::mirror`]) is the orientation to report: a
    /// study that merges mirror images reports its optimum in the orientation a designer
    /// draws (the bridge: output blocks outward, as paper 004's Fig. 1 and 3 draw them).
    fn prefers_mirror(&self, _x: &[f64]) -> bool {
        false
    }
}

/// A mechanism that is cut as one part: its solids, faces and the finite-element check the
/// part states ([`crate::part`]).
pub trait PartMaker: Send + Sync + std::fmt::Debug {
    /// The solids of the design `x` (SI) as a part, or what makes the part impossible.
    fn part(&self, x: &[f64]) -> Result<PartSpec, Vec<String>>;

    /// What of the finite-element check its part states ([`crate::part::analysis`])
    /// measures what the model's output `output` computes, if anything does: what `flexopt
    /// verify` compares it with and `run --refine fe` corrects it by.
    fn fe_counterpart(&self, output: usize) -> Option<FeCounterpart>;

    /// Whether the model's output `output` is a size of the part as drawn (a span, a
    /// described measure): the part has it exactly, and no finite element need measure it.
    fn drawn(&self, _output: usize) -> bool {
        false
    }

    /// The part's manufacturability rules this model states as functions of the design
    /// ([`super::part_rules`]); none by default, and then the part is only checked after the
    /// study.
    fn rules(&self) -> &[PartRule] {
        &[]
    }

    /// How many of [`PartMaker::rules`], the first ones, the study keeps to from every start;
    /// the others, which may be costly or kinked where the part is far from made (solids
    /// overlapping), it adds once a start has ended, and continues from there
    /// ([`crate::optim::staged`]). All of them by default.
    fn first_rules(&self) -> usize {
        self.rules().len()
    }

    /// Whether the study keeps to [`PartMaker::rules`] (`[part] enforce`, on by default).
    fn enforces_rules(&self) -> bool {
        !self.rules().is_empty()
    }

    /// Each rule's margin (m) at the design `x` (SI), into `out`: the first `out.len()`
    /// rules.
    fn rule_margins(&self, _x: &[f64], _out: &mut [f64]) {}

    /// As [`PartMaker::rule_margins`], with their exact gradients over every parameter,
    /// row-major (`jacobian[i * x.len() + p]`).
    fn rule_margins_with_gradient(&self, _x: &[f64], _out: &mut [f64], _jacobian: &mut [f64]) {}

    /// Whether the part gives its rules' Hessians ([`PartMaker::rule_margins_with_hessian`]):
    /// a robust study keeps each rule inside by its spread only where it does.
    fn rule_hessians(&self) -> bool {
        false
    }

    /// As [`PartMaker::rule_margins_with_gradient`], and each margin's Hessian over every
    /// parameter into `hessian` (`out.len()` blocks of `x.len()^2`, row-major): the
    /// gradient of a rule's first-order spread under the tolerances needs them.
    fn rule_margins_with_hessian(
        &self,
        _x: &[f64],
        _out: &mut [f64],
        _jacobian: &mut [f64],
        _hessian: &mut [f64],
    ) {
    }

    /// Where each rule is measured at the design `x` (SI), into `out` (one per rule, in
    /// their order): `None` where the model does not say.
    fn rule_witnesses(&self, _x: &[f64], _out: &mut [Option<Witness>]) {}
}

/// A mechanism: its physics and the capabilities it has.
/// The physics with the material's stiffness as one more input: the outputs at a design
/// whose material has Young's and shear moduli `modulus` times the nominal ones (Poisson's
/// ratio kept), for a tolerance on `E` ([`crate::problem::tolerances`]). A model gives it
/// where every output that depends on the material does so through its stiffness alone.
pub trait ModulusScaling: Send + Sync + std::fmt::Debug {
    /// Why output `output` cannot be differentiated twice, where it cannot (an output whose
    /// derivatives come from first-order ones alone): a robust study is refused for it.
    fn first_order_only(&self, output: usize) -> Option<String> {
        let _ = output;
        None
    }

    /// As [`Model::evaluate`], at the moduli `modulus` times the nominal ones.
    fn evaluate_scaled(&self, x: &[f64], modulus: f64, wanted: &[usize], out: &mut [f64]);

    /// As [`Model::evaluate_with_gradient`], at the moduli `modulus` times the nominal
    /// ones; `jacobian` has one column more than the parameters, the last the derivative
    /// by `modulus`.
    fn evaluate_scaled_with_gradient(
        &self,
        x: &[f64],
        modulus: f64,
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    );

    /// As [`ModulusScaling::evaluate_scaled_with_gradient`] at the nominal moduli, and each
    /// output's Hessian over the same inputs into `hessian` (`m` blocks of `(n + 1)^2`,
    /// row-major): the gradient of an output's first-order spread needs them.
    fn evaluate_with_hessian(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    );
}

#[derive(Debug, Clone)]
pub struct Mechanism {
    pub physics: Arc<dyn Model>,
    pub depiction: Option<Arc<dyn Depiction>>,
    pub part_maker: Option<Arc<dyn PartMaker>>,
    /// The physics with the material's moduli as an input, where the model has it.
    pub modulus: Option<Arc<dyn ModulusScaling>>,
    /// The mechanism solved with large deflections at its stroke, where the model has it.
    pub large: Option<Arc<dyn LargeDeflection>>,
}

/// The depiction of a mechanism without one: every default.
#[derive(Debug)]
struct Plain;

impl Depiction for Plain {}

impl Mechanism {
    /// A mechanism with physics alone.
    pub fn physics_only(physics: Arc<dyn Model>) -> Self {
        Mechanism {
            physics,
            depiction: None,
            part_maker: None,
            modulus: None,
            large: None,
        }
    }

    /// A model that brings every capability itself.
    pub fn complete<M: Model + Depiction + PartMaker + 'static>(model: M) -> Self {
        let model = Arc::new(model);
        Mechanism {
            physics: model.clone(),
            depiction: Some(model.clone()),
            part_maker: Some(model),
            modulus: None,
            large: None,
        }
    }

    /// A model with pictures but no part.
    pub fn depicted<M: Model + Depiction + 'static>(model: M) -> Self {
        let model = Arc::new(model);
        Mechanism {
            physics: model.clone(),
            depiction: Some(model),
            part_maker: None,
            modulus: None,
            large: None,
        }
    }

    /// The same mechanism with other physics (the same parameters and outputs): its
    /// pictures and part are the wrapped mechanism's; the evaluation at other moduli was
    /// the old physics', so it goes.
    pub fn with_physics(&self, physics: Arc<dyn Model>) -> Self {
        Mechanism {
            physics,
            modulus: None,
            ..self.clone()
        }
    }

    /// The same mechanism, evaluated at other moduli by `modulus`.
    pub fn with_modulus_scaling(self, modulus: Arc<dyn ModulusScaling>) -> Self {
        Mechanism {
            modulus: Some(modulus),
            ..self
        }
    }

    /// The depiction, every default where the mechanism has none.
    pub fn depiction(&self) -> &dyn Depiction {
        self.depiction.as_deref().unwrap_or(&Plain)
    }

    /// The part's spec at the design `x` (SI); `None` for a mechanism without a part.
    pub fn part_spec(&self, x: &[f64]) -> Option<Result<PartSpec, Vec<String>>> {
        Some(self.part_maker.as_ref()?.part(x))
    }

    /// The part at the design `x` (SI), joined, rounded and checked; `None` for a mechanism
    /// without a part.
    pub fn part(&self, x: &[f64]) -> Option<Result<Part, PartError>> {
        Some(build_part(self.part_maker.as_deref()?, x))
    }

    /// As [`Mechanism::part`], a mechanism without a part being an error.
    pub fn part_or_error(&self, x: &[f64]) -> Result<Part, PartError> {
        self.part(x).unwrap_or_else(|| {
            Err(PartError {
                problems: vec![format!(
                    "the {} model has no part to draw",
                    self.physics.name()
                )],
            })
        })
    }

    /// The finite-element counterpart of the model's output `output`
    /// ([`PartMaker::fe_counterpart`]).
    pub fn fe_counterpart(&self, output: usize) -> Option<FeCounterpart> {
        self.part_maker.as_ref()?.fe_counterpart(output)
    }

    /// Whether the model's output `output` is a size of the part as drawn
    /// ([`PartMaker::drawn`]).
    pub fn drawn(&self, output: usize) -> bool {
        self.part_maker.as_ref().is_some_and(|p| p.drawn(output))
    }
}

/// The part of `maker` at the design `x` (SI), joined, rounded and checked.
pub fn build_part(maker: &dyn PartMaker, x: &[f64]) -> Result<Part, PartError> {
    match maker.part(x) {
        Err(problems) => Err(PartError { problems }),
        Ok(spec) => Part::build(&spec),
    }
}
