//! A geometrically nonlinear planar flexure structure (issue 48): flexures as chains of
//! corotational Euler-Bernoulli beam elements, rigid bodies as master nodes carrying slave
//! nodes at fixed offsets, supports as held degrees of freedom (with a prescribed value
//! that grows with the load factor), applied forces and moments of fixed direction, and a
//! linear spring between two points (a piezo stack with its free stroke and preload).
//!
//! Equilibrium is found by Newton's method with load continuation ([`solve::continuation`]),
//! by Crisfield's cylindrical arc length where the path turns back ([`solve::arc_length`]),
//! and the critical load factor, where the tangent stiffness stops being positive definite,
//! by a secant search on the path ([`critical::critical_load_factor`]).
//!
//! The element is Crisfield's (M. A. Crisfield, *Non-linear Finite Element Analysis of
//! Solids and Structures*, vol. 1, Wiley 1991, ch. 7, the co-rotational beam with the
//! shallow-arch local strain): an Euler-Bernoulli beam in a frame that follows the chord, so the
//! kinematics are exact for any rigid rotation and the only approximation is the element's
//! local strain, which vanishes as the elements get shorter. See [`element`].
//!
//! Units are the caller's (SI throughout flexopt). Nothing here reads a problem file.

pub mod assemble;
pub mod critical;
pub mod element;
pub mod report;
pub mod sensitivity;
pub mod solve;

use std::fmt;

use crate::model::scalar::Scalar;

/// A degree of freedom of a node: its displacement along x or y, or its rotation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    X = 0,
    Y = 1,
    Rotation = 2,
}

/// A beam element's section: its axial stiffness `E A` and bending stiffness `E I`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    pub ea: f64,
    pub ei: f64,
}

impl Section {
    /// The uniform Euler-Bernoulli beam's local stiffness over a length `l0`.
    pub fn local<D: Scalar>(self, l0: D) -> LocalOf<D> {
        let k = D::from(self.ei) / l0;
        LocalOf {
            axial: D::from(self.ea) / l0,
            bending: [[k * 4.0, k * 2.0], [k * 2.0, k * 4.0]],
        }
    }
}

/// A beam element's local linear stiffness: `axial` the force over the chord's stretch,
/// `bending` the end moments over the end rotations against the chord, `(theta_a,
/// theta_b)` (symmetric, positive definite). Over a scalar `D` (a dual number carries the
/// derivatives by the design; [`Local`] is the real one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalOf<D> {
    pub axial: D,
    pub bending: [[D; 2]; 2],
}

/// A local stiffness in real numbers.
pub type Local = LocalOf<f64>;

impl<D: Scalar> LocalOf<D> {
    /// From the compliance at a segment's end `b` with its end `a` clamped, in its frame
    /// (`c11` axial, `[c22 c23; c23 c33]` the transverse motion and rotation): its inverse
    /// carried to the end rotations against the chord, `v = -l theta_a`, `phi_b = theta_b
    /// - theta_a` (the clamped end's rotation against the chord is minus the chord's turn).
    pub fn from_compliance(l0: D, c11: D, c22: D, c23: D, c33: D) -> LocalOf<D> {
        let det = c22 * c33 - c23 * c23;
        let kc = [[c33 / det, -c23 / det], [-c23 / det, c22 / det]];
        let zero = D::from(0.0);
        let m = [[-l0, zero], [D::from(-1.0), D::from(1.0)]];
        let mut bending = [[zero; 2]; 2];
        for (i, row) in bending.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let mut sum = zero;
                for p in 0..2 {
                    for q in 0..2 {
                        sum = sum + m[p][i] * kc[p][q] * m[q][j];
                    }
                }
                *v = sum;
            }
        }
        LocalOf {
            axial: c11.recip(),
            bending,
        }
    }
}

/// A linear spring between two nodes whose natural length grows by `lambda * (free_stroke +
/// preload / stiffness)` at load factor `lambda`: a piezo stack that at full load has
/// extended by its free stroke and carries its preload (the force it would push with if
/// held at its unloaded length), both applied along the load factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringOf<D> {
    pub a: usize,
    pub b: usize,
    pub stiffness: D,
    pub free_stroke: D,
    pub preload: D,
}

/// A spring in real numbers.
pub type Spring = SpringOf<f64>;

/// A beam element between two nodes: its section, or a local stiffness of its own in its
/// place (`local`, a segment of a flexure's exact compliance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamOf<D> {
    pub a: usize,
    pub b: usize,
    pub section: Section,
    pub local: Option<LocalOf<D>>,
}

/// A beam in real numbers.
pub type Beam = BeamOf<f64>;

impl<D: Scalar> BeamOf<D> {
    /// The local stiffness over the reference length `l0`.
    pub fn local(&self, l0: D) -> LocalOf<D> {
        self.local.unwrap_or_else(|| self.section.local(l0))
    }
}

/// A node held rigidly to a master node: its offset from the master in the reference
/// configuration turns with the master's rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slave {
    pub node: usize,
    pub master: usize,
}

/// A planar structure of nodes (reference positions), beams, springs, rigid attachments,
/// held degrees of freedom and applied loads (all at load factor 1), over a scalar `D`: in
/// real numbers ([`Structure`]) it is solved; in dual numbers it carries the derivatives of
/// its data by a design, from which the gradients at an equilibrium follow
/// ([`assemble::SystemOf::residual_by_design`]).
#[derive(Debug, Clone)]
pub struct StructureOf<D> {
    pub nodes: Vec<[D; 2]>,
    pub beams: Vec<BeamOf<D>>,
    pub springs: Vec<SpringOf<D>>,
    pub slaves: Vec<Slave>,
    /// Held degrees of freedom and their prescribed displacement at load factor 1.
    pub held: Vec<(usize, Dof, D)>,
    /// Applied forces `(fx, fy, m)` at a node at load factor 1, fixed in direction.
    pub loads: Vec<(usize, [D; 3])>,
}

/// A structure in real numbers: the one the equilibrium paths are solved on.
pub type Structure = StructureOf<f64>;

impl<D> Default for StructureOf<D> {
    fn default() -> Self {
        StructureOf {
            nodes: Vec::new(),
            beams: Vec::new(),
            springs: Vec::new(),
            slaves: Vec::new(),
            held: Vec::new(),
            loads: Vec::new(),
        }
    }
}

impl<D: Scalar> StructureOf<D> {
    /// A new node at `(x, y)`; its index.
    pub fn node(&mut self, x: D, y: D) -> usize {
        self.nodes.push([x, y]);
        self.nodes.len() - 1
    }

    /// A flexure from node `a` to node `b` in `elements` beam elements, the section of each
    /// sampled at its middle from `section(s)`, `s` in (0, 1) the fraction of the way from
    /// `a` to `b` (so a notch's varying profile is followed). Returns the nodes along it,
    /// `a` and `b` included.
    pub fn flexure(
        &mut self,
        a: usize,
        b: usize,
        elements: usize,
        section: impl Fn(f64) -> Section,
    ) -> Vec<usize> {
        let n = elements.max(1);
        let (pa, pb) = (self.nodes[a], self.nodes[b]);
        let mut chain = vec![a];
        for i in 1..n {
            let s = i as f64 / n as f64;
            let p = [pa[0] + (pb[0] - pa[0]) * s, pa[1] + (pb[1] - pa[1]) * s];
            chain.push(self.node(p[0], p[1]));
        }
        chain.push(b);
        for (i, pair) in chain.windows(2).enumerate() {
            let s = (i as f64 + 0.5) / n as f64;
            self.beams.push(BeamOf {
                a: pair[0],
                b: pair[1],
                section: section(s),
                local: None,
            });
        }
        chain
    }

    /// Makes `node` a point of the rigid body whose reference node is `master`.
    pub fn attach(&mut self, node: usize, master: usize) {
        self.slaves.push(Slave { node, master });
    }

    /// Holds `dof` of `node` at zero.
    pub fn hold(&mut self, node: usize, dof: Dof) {
        self.held.push((node, dof, D::from(0.0)));
    }

    /// Holds all three degrees of freedom of `node` at zero (a clamp).
    pub fn fix(&mut self, node: usize) {
        for dof in [Dof::X, Dof::Y, Dof::Rotation] {
            self.hold(node, dof);
        }
    }

    /// Prescribes `dof` of `node` to reach `value` at load factor 1 (in proportion below).
    pub fn prescribe(&mut self, node: usize, dof: Dof, value: D) {
        self.held.push((node, dof, value));
    }

    /// Applies `(fx, fy, m)` at `node` at load factor 1.
    pub fn load(&mut self, node: usize, force: [D; 3]) {
        self.loads.push((node, force));
    }
}

/// Why a structure could not be solved.
#[derive(Debug, Clone, PartialEq)]
pub enum LargeError {
    /// The structure is malformed: a node index out of range, a zero-length beam, a
    /// non-positive or non-finite section, a slave of a slave, a held slave.
    Invalid(String),
    /// Newton's method did not converge at load factor `lambda` within its iterations even
    /// after the step was cut `cuts` times; `residual` is the last residual norm.
    NotConverged {
        lambda: f64,
        residual: f64,
        cuts: usize,
    },
    /// The tangent stiffness could not be solved (a free motion, or a non-finite result)
    /// at load factor `lambda`.
    Singular { lambda: f64 },
    /// The arc-length path took its most steps before reaching the target load factor.
    PathTooLong { steps: usize, lambda: f64 },
    /// The tangent stiffness stays positive definite up to `lambda_max`.
    NoCriticalPoint { lambda_max: f64 },
    /// The eigenvalue decomposition of the tangent stiffness failed.
    Eigen,
}

impl fmt::Display for LargeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LargeError::Invalid(what) => write!(f, "invalid structure: {what}"),
            LargeError::NotConverged {
                lambda,
                residual,
                cuts,
            } => write!(
                f,
                "no equilibrium at load factor {lambda}: residual {residual:e} after {cuts} step cuts"
            ),
            LargeError::Singular { lambda } => {
                write!(f, "singular tangent stiffness at load factor {lambda}")
            }
            LargeError::PathTooLong { steps, lambda } => write!(
                f,
                "the arc-length path reached load factor {lambda} only in {steps} steps"
            ),
            LargeError::NoCriticalPoint { lambda_max } => write!(
                f,
                "the tangent stiffness stays positive definite up to load factor {lambda_max}"
            ),
            LargeError::Eigen => write!(f, "eigenvalue decomposition failed"),
        }
    }
}

impl std::error::Error for LargeError {}

/// One converged point of an equilibrium path: its load factor and every node's
/// displacement `(u, v, theta)` (slaves included), `3 * nodes` values.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    pub lambda: f64,
    pub displacement: Vec<f64>,
}

impl PathPoint {
    /// The displacement `dof` of `node`.
    pub fn at(&self, node: usize, dof: Dof) -> f64 {
        self.displacement[3 * node + dof as usize]
    }
}
