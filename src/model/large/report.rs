//! A mechanism's outputs at its working stroke, beside the linear model's: what a mechanism
//! that can be solved with large deflections ([`LargeDeflection`]) reports, over the
//! stroke and at its end.

use serde::Serialize;

/// How a structure at stroke is solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeOptions {
    /// Beam elements per flexure (the convergence check solves with twice as many too).
    pub elements: usize,
    /// Load steps from the unloaded part to the full stroke: the points of the curves.
    pub steps: usize,
    /// The critical load factor is looked for up to this multiple of the full stroke.
    pub critical_up_to: f64,
    /// Drive the input by this force of fixed direction (N, the whole mechanism's) in the
    /// actuator's place; `None` the actuator at its full free stroke and preload.
    pub force: Option<f64>,
}

impl Default for StrokeOptions {
    fn default() -> Self {
        StrokeOptions {
            elements: 8,
            steps: 10,
            critical_up_to: 4.0,
            force: None,
        }
    }
}

/// An output port's motion apart from its own direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ParasiticOf<D> {
    /// The port's displacement across its direction (m).
    pub across: D,
    /// Its body's rotation (rad).
    pub rotation: D,
}

/// A port's parasitic motion in real numbers.
pub type Parasitic = ParasiticOf<f64>;

/// The outputs at one point of the stroke (SI), over a scalar `D` (a dual number carries
/// their derivatives by the design; [`StrokePoint`] is the real one).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrokePointOf<D> {
    /// The load factor: the fraction of the full stroke (of the stack's free stroke and
    /// preload, or of the force that drives it).
    pub fraction: f64,
    /// The input's motion along its direction, the whole mechanism's (a port across a
    /// mirror axis: the change of distance to its image).
    pub stroke_in: D,
    /// The first output's, likewise.
    pub stroke_out: D,
    /// `stroke_out / stroke_in` (the tangent at the unloaded point).
    pub amplification: D,
    /// The tangent ratio: the output's motion over the input's under a small added load at
    /// the input.
    pub amplification_tangent: D,
    /// Tangent stiffness at the input, the input free of its actuator.
    pub k_in: D,
    /// Tangent stiffness at the first output, the input free.
    pub k_out: D,
    /// Each hinge's and beam's largest stress, as the linear model states it from its loads.
    pub stresses: Vec<D>,
    pub stress_max: D,
    /// Each output port's motion apart from its direction.
    pub parasitic: Vec<ParasiticOf<D>>,
    /// The lowest natural frequencies (Hz) about the equilibrium, as many as the linear
    /// model has (none where it has none, or where a force drives the input in the stack's
    /// place); not-a-number at a point where they cannot be found (past a critical point).
    pub frequencies: Vec<D>,
}

/// The outputs at one point of the stroke in real numbers.
pub type StrokePoint = StrokePointOf<f64>;

/// A mechanism solved over its stroke.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrokeReport {
    /// Beam elements per flexure.
    pub elements: usize,
    /// The hinges' and beams' names, in the order of [`StrokePoint::stresses`].
    pub flexures: Vec<String>,
    /// The output ports' names, in the order of [`StrokePoint::parasitic`].
    pub outputs: Vec<String>,
    /// The equilibrium path from the unloaded part to the full stroke, one point a step.
    pub curve: Vec<StrokePoint>,
    /// The linear solution of the same load at the full stroke (its curve is this point
    /// scaled by the fraction, its stiffnesses constant).
    pub linear: StrokePoint,
    /// The load factor at which the tangent stiffness stops being positive definite
    /// (buckling, a limit point), if below [`StrokeOptions::critical_up_to`].
    pub critical_load_factor: Option<f64>,
    /// The same at the full stroke with twice the elements: the convergence estimate.
    pub finer: Option<StrokePoint>,
}

impl StrokeReport {
    /// The outputs at the full stroke.
    pub fn at_stroke(&self) -> &StrokePoint {
        self.curve.last().expect("a path has its unloaded point")
    }
}

/// A mechanism solved with its flexures' large deflections at its working stroke.
pub trait LargeDeflection: Send + Sync + std::fmt::Debug {
    /// The outputs over the stroke at the design `x` (SI), or why there are none.
    fn at_stroke(&self, x: &[f64], options: &StrokeOptions) -> Result<StrokeReport, String>;
}
