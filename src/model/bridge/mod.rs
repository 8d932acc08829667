//! The general compliant bridge amplifier (paper 004: Wei et al., Micromachines 2017, 8, 238).
//!
//! - [`geometry`]: a design (hinges of any kind, the middle link, the angles) and the layout
//!   of its parameters;
//! - [`quarter`]: the quarter model of Sec. 2 and Appendix A, with the rebuilt equations;
//! - [`outputs`]: the named outputs and one evaluation of those a problem asks for;
//! - [`dynamics`]: the equivalent mass and natural frequency along the output;
//! - [`configuration`]: the names of configurations, and the drawing of a quarter;
//! - [`file`]: the bridge's sections of a problem file.
//!
//! The closed forms of the special configurations (Sec. 5) and an independent matrix
//! formulation live in [`crate::model::reference`], as checks.

pub mod configuration;
pub mod dynamics;
pub mod file;
pub mod geometry;
pub mod outputs;
pub mod part;
pub mod quarter;

use serde::Serialize;

pub use geometry::{Geometry, Layout, Trig};
pub use outputs::{BridgeOutput, OUTPUTS};
pub use quarter::QuarterBridge;

use super::entry::ModelEntry;
use super::hinge::HingeKind;
use super::material::Material;
use super::mechanism::ModulusScaling;
use super::part_rules::PartRule;
use super::scalar::Jet;
use super::{unseed, Depiction, Drawing, Model, OutputInfo, ParameterInfo, PartMaker, Skeleton};
use dynamics::DynamicsSettings;

/// `self.method::<N>(args)` with `N` the design's parameter count (8 to 10: two strips have
/// 8, notches up to 10) plus `plus`: one gradient size per count.
macro_rules! per_count {
    ($len:expr, $self:ident . $method:ident :: <+ $plus:literal> ($($arg:expr),*)) => {
        match $len {
            8 => $self.$method::<{ 8 + $plus }>($($arg),*),
            9 => $self.$method::<{ 9 + $plus }>($($arg),*),
            10 => $self.$method::<{ 10 + $plus }>($($arg),*),
            n => panic!("a bridge design has 8 to 10 parameters, got {n}"),
        }
    };
}

/// How a problem file selects the bridge (`model = "bridge"`).
pub const ENTRY: ModelEntry = ModelEntry {
    name: "bridge",
    sections: file::SECTIONS,
    build: file::build,
    schema: file::schema,
    template: include_str!("../templates/bridge.toml"),
    hinge_layout: Some(|kind| Layout::new(kind, kind).hinge_dimensions()),
    optional_outputs: None,
};

/// The actuator every mechanism shares, by the path the bridge's users name it.
pub use crate::model::actuator::Actuator;

/// Everything about a bridge that is not a design parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BridgeSettings {
    /// The kinds of hinges b and d, each with its own dimensions among the parameters.
    pub hinge_b: HingeKind,
    pub hinge_d: HingeKind,
    /// Width w of the mechanism (m).
    pub width: f64,
    pub material: Material,
    pub actuator: Actuator,
    /// Masses and damping for the dynamic outputs; `None` when the problem gives none.
    pub dynamics: Option<DynamicsSettings>,
    /// The part's sizes (`[part]`).
    pub part: part::PartSettings,
}

/// The general bridge model: settings plus the evaluation of named outputs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bridge {
    pub settings: BridgeSettings,
    #[serde(skip)]
    layout: Layout,
    /// The part's rules ([`part::rules`]).
    #[serde(skip)]
    rules: Vec<PartRule>,
}

impl Bridge {
    pub fn new(settings: BridgeSettings) -> Self {
        let layout = Layout::new(settings.hinge_b, settings.hinge_d);
        let rules = part::rules::rules(&settings.part);
        Bridge {
            settings,
            layout,
            rules,
        }
    }

    /// Where the parts of a design sit among the parameters.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The design whose parameters (model order) are `x`.
    pub fn geometry<D: super::scalar::Scalar>(&self, x: &[D]) -> Geometry<D> {
        self.layout.geometry(x)
    }

    /// Values and gradients of the outputs `wanted` at `x`, with `N` = the number of
    /// parameters.
    fn gradients<const N: usize>(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        // most problems name a few outputs (wei2017: 9, its stress limit on four node
        // stresses): keep them on the stack without zeroing much
        let mut small = [Jet::<N>::from(0.0); 12];
        let mut large = Vec::new();
        let y = if wanted.len() <= small.len() {
            &mut small[..wanted.len()]
        } else {
            large.resize(wanted.len(), Jet::from(0.0));
            &mut large[..]
        };
        self.evaluate(&self.layout.seeded::<N>(x), wanted, y);
        unseed(y, out, jacobian);
    }

    /// Values and gradients of the outputs `wanted` at `x` and the moduli `modulus` times
    /// the nominal ones, with `N` = the number of parameters plus one, the modulus last.
    fn scaled_gradients<const N: usize>(
        &self,
        x: &[f64],
        modulus: f64,
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        let mut y = vec![Jet::<N>::from(0.0); wanted.len()];
        let m = Jet::variable(modulus, N - 1);
        self.evaluate_with_modulus(&self.layout.seeded::<N>(x), Some(m), wanted, &mut y);
        unseed(&y, out, jacobian);
    }

    /// Values, gradients and Hessians of the outputs `wanted` at `x` and the nominal moduli,
    /// with `N` = the number of parameters plus one, the modulus last: second-order numbers
    /// ([`super::jet2::Jet2`]) through the same generic code.
    fn hessians<const N: usize>(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        use super::jet2::{seeded_with_modulus, unseed2, Jet2};
        let seeded = seeded_with_modulus::<N>(x);
        let mut y = vec![Jet2::<N>::from(0.0); wanted.len()];
        let modulus = seeded[N - 1];
        self.evaluate_with_modulus(
            &self.layout.geometry(&seeded[..N - 1]),
            Some(modulus),
            wanted,
            &mut y,
        );
        unseed2(&y, out, jacobian, hessian);
    }

    /// Values and gradients of the part's rules at `x`, with `N` = the number of
    /// parameters ([`part::rules::margins_with_gradient`]).
    fn rule_gradients<const N: usize>(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        part::rules::margins_with_gradient::<N>(
            &self.settings.part,
            &self.layout,
            x,
            out,
            jacobian,
        );
    }

    /// Values, gradients and Hessians of the part's rules at `x`, with `N` = the number
    /// of parameters ([`part::rules::margins_with_hessian`]).
    fn rule_second_derivatives<const N: usize>(
        &self,
        x: &[f64],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        part::rules::margins_with_hessian::<N>(
            &self.settings.part,
            &self.layout,
            x,
            out,
            jacobian,
            hessian,
        );
    }
}

impl Model for Bridge {
    fn name(&self) -> &'static str {
        "bridge"
    }

    fn parameters(&self) -> &[ParameterInfo] {
        self.layout.parameters()
    }

    fn outputs(&self) -> &[OutputInfo] {
        &OUTPUTS
    }

    fn max_of(&self, output: usize) -> Option<&[usize]> {
        use BridgeOutput::*;
        // the stresses at nodes 2, 3, 4, 5 (BridgeOutput::ALL lists the variants in order)
        const ALL_NODES: [usize; 4] = [
            StressNode2 as usize,
            StressNode3 as usize,
            StressNode4 as usize,
            StressNode5 as usize,
        ];
        match BridgeOutput::ALL[output] {
            StressMax => Some(&ALL_NODES),
            StressB => Some(&ALL_NODES[..2]),
            StressD => Some(&ALL_NODES[2..]),
            _ => None,
        }
    }

    fn unavailable(&self, output: usize) -> Option<String> {
        let o = BridgeOutput::ALL[output];
        (o.needs_dynamics() && self.settings.dynamics.is_none()).then(|| {
            format!(
                "output \"{}\" needs the masses and damping of a [dynamics] section",
                OUTPUTS[output].name
            )
        })
    }

    fn domain_error(&self, x: &[f64]) -> Option<String> {
        self.layout.domain_error(x)
    }

    fn box_error(&self, lower: &[f64], upper: &[f64]) -> Option<(usize, String)> {
        self.layout.box_error(lower, upper)
    }

    fn evaluate(&self, x: &[f64], wanted: &[usize], out: &mut [f64]) {
        Bridge::evaluate(self, &self.layout.geometry(x), wanted, out);
    }

    fn evaluate_with_gradient(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        per_count!(x.len(), self.gradients::<+0>(x, wanted, out, jacobian))
    }

    fn material(&self) -> Option<&Material> {
        Some(&self.settings.material)
    }

    fn angle_limit(&self) -> Option<f64> {
        // the quarter model's angles stay within a right angle (Layout::domain_error)
        Some(std::f64::consts::FRAC_PI_2)
    }

    /// Every angle negated: the arms mirrored about the actuator's axis.
    fn mirror(&self, x: &mut [f64]) -> bool {
        super::negate_angles(self.layout.parameters(), x)
    }

    fn fit_limits(&self) -> &[super::fit::FitLimit] {
        self.layout.fit_limits()
    }
}

impl ModulusScaling for Bridge {
    fn evaluate_scaled(&self, x: &[f64], modulus: f64, wanted: &[usize], out: &mut [f64]) {
        self.evaluate_with_modulus(&self.layout.geometry(x), Some(modulus), wanted, out);
    }

    fn evaluate_scaled_with_gradient(
        &self,
        x: &[f64],
        modulus: f64,
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
    ) {
        per_count!(x.len(), self.scaled_gradients::<+1>(x, modulus, wanted, out, jacobian))
    }

    fn evaluate_with_hessian(
        &self,
        x: &[f64],
        wanted: &[usize],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        per_count!(x.len(), self.hessians::<+1>(x, wanted, out, jacobian, hessian))
    }
}

impl Depiction for Bridge {
    fn configuration(&self, x: &[f64]) -> &'static str {
        configuration::configuration(&self.layout.geometry(x))
    }

    fn configuration_rule(&self) -> Option<&'static str> {
        Some(configuration::RULE)
    }

    fn drawing(&self, x: &[f64]) -> Drawing {
        let g = self.layout.geometry(x);
        Drawing {
            nodes_mm: Some(g.nodes().iter().map(|p| [p[0] * 1e3, p[1] * 1e3]).collect()),
            mode_shapes: None,
        }
    }

    fn skeleton(&self, x: &[f64]) -> Option<Skeleton> {
        (x.len() == self.layout.parameters().len())
            .then(|| configuration::skeleton(&self.layout.geometry(x)))
    }

    fn skeleton_legend(&self) -> &'static str {
        configuration::SKELETON_LEGEND
    }

    /// The span along the output negative: the arm runs from the input block towards the
    /// actuator's axis and the output blocks sit inward, pinching the actuator's pocket.
    fn prefers_mirror(&self, x: &[f64]) -> bool {
        x.len() == self.layout.parameters().len() && self.layout.geometry(x).span_y() < 0.0
    }
}

impl PartMaker for Bridge {
    fn part(&self, x: &[f64]) -> Result<crate::part::PartSpec, Vec<String>> {
        if x.len() != self.layout.parameters().len() {
            return Err(vec![format!(
                "a bridge design has {} parameters, got {}",
                self.layout.parameters().len(),
                x.len()
            )]);
        }
        part::spec(&self.settings, &self.layout, x)
    }

    fn fe_counterpart(&self, output: usize) -> Option<crate::part::analysis::FeCounterpart> {
        part::fe_cases::counterpart(BridgeOutput::ALL[output])
    }

    fn drawn(&self, output: usize) -> bool {
        matches!(
            BridgeOutput::ALL.get(output),
            Some(
                BridgeOutput::SpanX
                    | BridgeOutput::SpanY
                    | BridgeOutput::PartWidth
                    | BridgeOutput::PartHeight
                    | BridgeOutput::PocketLength
            )
        )
    }

    fn rules(&self) -> &[PartRule] {
        &self.rules
    }

    fn enforces_rules(&self) -> bool {
        self.settings.part.enforce
    }

    fn first_rules(&self) -> usize {
        part::rules::first_rules(&self.settings.part)
    }

    fn rule_margins(&self, x: &[f64], out: &mut [f64]) {
        part::rules::margins(
            &self.settings.part,
            &self.layout,
            &self.layout.geometry(x),
            out,
        );
    }

    fn rule_margins_with_gradient(&self, x: &[f64], out: &mut [f64], jacobian: &mut [f64]) {
        per_count!(x.len(), self.rule_gradients::<+0>(x, out, jacobian))
    }

    fn rule_hessians(&self) -> bool {
        true
    }

    fn rule_margins_with_hessian(
        &self,
        x: &[f64],
        out: &mut [f64],
        jacobian: &mut [f64],
        hessian: &mut [f64],
    ) {
        per_count!(x.len(), self.rule_second_derivatives::<+0>(x, out, jacobian, hessian))
    }

    fn rule_witnesses(&self, x: &[f64], out: &mut [Option<crate::model::part_rules::Witness>]) {
        part::rules::witnesses(
            &self.settings.part,
            &self.layout,
            &self.layout.geometry(x),
            out,
        );
    }
}
