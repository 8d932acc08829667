//! Matrix structural analysis of a planar flexure network: rigid bodies joined to each other
//! and to the ground by flexures, each flexure known by its 3x3 compliance at its free end
//! with the other end clamped (the hinge library's [`Compliance`], paper 004 Eq. 1), in its
//! own frame. Written over [`Scalar`], so the displacements come with their exact
//! derivatives.
//!
//! The direct stiffness method (Przemieniecki, "Theory of Matrix Structural Analysis",
//! McGraw-Hill 1968, Ch. 6; McGuire, Gallagher and Ziemian, "Matrix Structural Analysis",
//! 2nd ed., Wiley 2000, Sec. 4.3-4.5), with each flexure's stiffness from its compliance as
//! in the compliance-matrix method of flexure mechanisms (Lobontiu, "Compliant Mechanisms:
//! Design of Flexure Hinges", CRC Press 2002, Ch. 4; Ling, Cao, Zeng, Lin and Inman, Smart
//! Mater. Struct. 25 (2016) 075022, Eq. 1-9). Each body has three degrees of freedom at its
//! reference point, `(u, v, theta)`; the ground has none. A flexure from point `P` (on its
//! first body) along the unit axis `e` to `Q = P + l e` (on its second) gives, in its frame
//! (`x` along `e`),
//!
//! ```text
//! K = C^-1,   C = [c11 0 0; 0 c22 c23; 0 c23 c33]     free end Q, end P clamped
//! d = u_Q - G u_P,   G = [1 0 0; 0 1 l; 0 0 1]          Q's motion relative to P's rigid one
//! f_Q = K d,   f_P = -G^T f_Q                           equilibrium of the flexure
//! ```
//!
//! each end's motion carried from its body's reference point `O` by the rigid transfer
//! `u_P = T(P - O) u_O`, `T(r) = [1 0 -r_y; 0 1 r_x; 0 0 1]`, and the frame's rotation `R`
//! (`theta` unchanged), so that the body's stiffness gathers `T^T R^T [G^T K G, -G^T K;
//! -K G, K] R T`. A load `F` at a point `P` of a body is `T(P - O)^T F` at its reference
//! point; a spring to the ground along a unit direction `n` at `P` (an actuator's
//! stiffness) adds `k T^T (n n^T) T`.
//!
//! The stiffness is solved by `L D L^T` without pivoting (symmetric positive definite when
//! every body is held): a pivot that vanishes against the diagonal's scale is a motion
//! that nothing resists, reported with the body and the direction it moves in.
//!
//! This file says what a network is and reads its displacements; the solve on the free
//! degrees of freedom, which a design's evaluation runs, is the child `solve.rs`, and the
//! tests are the child `tests.rs`.

mod solve;
#[cfg(test)]
mod tests;

use std::borrow::Cow;
use std::fmt;

use crate::model::hinge::{Compliance, HingeLoads};
use crate::model::material::Material;
use crate::model::scalar::Scalar;
use solve::{End, Plan, HELD};

/// The compliance at the free end of a uniform straight beam `length` long, of rectangular
/// section `thickness` (in plane) by `width`, clamped at its start: the Timoshenko
/// cantilever (Timoshenko and Gere, "Mechanics of Materials", 1972, Sec. 9.10 for the
/// shear deflection; Przemieniecki, "Theory of Matrix Structural Analysis", 1968, Sec. 5.4,
/// Eq. 5.112 for the frame element with shear), with `A = w t`, `I = w t^3 / 12`:
///
/// ```text
/// c11 = L / (E A)
/// c22 = L^3 / (3 E I) + L / (kappa G A)
/// c23 = L^2 / (2 E I)
/// c33 = L / (E I)
/// ```
///
/// and the shear coefficient of a rectangle `kappa = 10 (1 + nu) / (12 + 11 nu)` (Cowper,
/// J. Appl. Mech. 33 (1966) 335, Table 1). The strip hinge's is the same beam with
/// `kappa = 1`, paper 004's Eq. 2: a network's frame member is long, where the shear term
/// is small and Cowper's is the better one, while the strip keeps the paper's.
pub fn beam_compliance<D: Scalar>(
    length: D,
    thickness: D,
    width: f64,
    material: &Material,
) -> Compliance<D> {
    let nu = material.poisson_ratio;
    let inv = (thickness * thickness * thickness * (material.youngs_modulus * width)).recip();
    let l_inv = length * inv;
    let t2 = thickness * thickness;
    // E / (kappa G) = 2 (1 + nu) / kappa = (12 + 11 nu) / 5
    Compliance {
        c11: l_inv * t2,
        c22: l_inv * (length * length * 4.0 + t2 * ((12.0 + 11.0 * nu) / 5.0)),
        c23: l_inv * length * 6.0,
        c33: l_inv * 12.0,
    }
}

/// A body of the network, or the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body {
    Ground,
    /// The body of this index among the network's bodies.
    Rigid(usize),
}

/// A flexure from `start` on `from` along `axis` (a unit vector) for `length`, ending on
/// `to` at `end`; `compliance` is at its end on `to` with its start clamped, in its own
/// frame.
#[derive(Debug, Clone, Copy)]
pub struct Flexure<D> {
    pub from: Body,
    pub to: Body,
    pub start: [D; 2],
    pub axis: [D; 2],
    pub length: D,
    /// `start + length * axis`, kept: the build, the assembly and the end loads each read
    /// it, and formed at each read it cost about 100 instructions a time over `Jet<8>`.
    pub end: [D; 2],
    pub compliance: Compliance<D>,
}

/// A spring between a point of a body and the ground, along a unit direction: an
/// actuator's stiffness, or a load's.
#[derive(Debug, Clone, Copy)]
pub struct Spring<D> {
    pub body: usize,
    pub point: [D; 2],
    pub direction: [D; 2],
    pub stiffness: D,
}

/// A support in one direction: the motion of `point` of `body` along the unit `direction`
/// held at zero (a guide, a roller), held exactly
/// ([`Constraints`](super::supports::Constraints)).
#[derive(Debug, Clone, Copy)]
pub struct Guide<D> {
    pub body: usize,
    pub point: [D; 2],
    pub direction: [D; 2],
}

/// A force and moment applied at a point of a body.
#[derive(Debug, Clone, Copy)]
pub struct Load<D> {
    pub body: usize,
    pub point: [D; 2],
    pub force: [D; 2],
    pub moment: D,
}

/// One of a body's degrees of freedom at its reference point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    X,
    Y,
    Rotation,
}

/// The network: its bodies' reference points, the flexures and the springs, and the
/// degrees of freedom held (a body on a mirror axis of a symmetric mechanism keeps its
/// motion across the axis and its rotation at zero).
#[derive(Debug, Clone)]
pub struct Network<D> {
    pub references: Vec<[D; 2]>,
    pub flexures: Vec<Flexure<D>>,
    pub springs: Vec<Spring<D>>,
    pub held: Vec<(usize, Dof)>,
    pub guides: Vec<Guide<D>>,
}

/// What keeps a network from being solved.
#[derive(Debug, Clone, PartialEq)]
pub enum NetworkError {
    /// Flexure `flexure` joins a body (or the ground) to itself.
    SelfJoined { flexure: usize },
    /// Nothing resists the motion of `body` in `direction` (`"x"`, `"y"` or `"rotation"`,
    /// with the bodies before it held).
    Free {
        body: usize,
        direction: &'static str,
    },
    /// Guide `guide` holds a motion that the ones before it, or the held degrees of
    /// freedom, hold already.
    Redundant { guide: usize },
}

impl fmt::Display for NetworkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NetworkError::SelfJoined { flexure } => {
                write!(f, "flexure {flexure} joins a body to itself")
            }
            NetworkError::Free { body, direction } => write!(
                f,
                "body {body} is free to move ({direction}): nothing holds it against the ground"
            ),
            NetworkError::Redundant { guide } => {
                write!(f, "guide {guide} holds a motion already held")
            }
        }
    }
}

/// The displacements of each body's reference point, `(u, v, theta)`.
#[derive(Debug, Clone)]
pub struct Displacements<'a, D: Clone> {
    pub bodies: Cow<'a, [[D; 3]]>,
    references: &'a [[D; 2]],
    /// Each degree of freedom's place in the free numbering, [`HELD`] where it is held: the
    /// terms a held one would give are left out (the same numbers, but for the sign of a
    /// zero). A lookup, where a search of the held list cost about the terms it saved.
    index: Cow<'a, [usize]>,
    /// Each flexure's stiffness in its own frame, as the solve formed it.
    stiffness: Cow<'a, [Stiffness<D>]>,
}

/// A flexure's stiffness in its own frame, `K = C^-1`: `[k11, k22, k23, k33]`, its axial
/// entry and its bending block `[k22 k23; k23 k33]`.
pub type Stiffness<D> = [D; 4];

/// A load case of [`Network::solve_cases_in`]: its loads, and the bodies whose
/// displacements are read (`None`: every body's).
#[derive(Debug, Clone, Copy)]
pub struct Case<'a, D> {
    pub loads: &'a [Load<D>],
    pub read: Option<&'a [usize]>,
}

/// The buffers of [`Network::solve_cases_in`]: the free numbering, the stiffness (and its
/// factor), a load vector, the displacements of every case.
#[derive(Debug, Clone)]
pub struct SolveBuffers<D> {
    index: Vec<usize>,
    k: Vec<D>,
    f: Vec<D>,
    moved: Vec<[D; 3]>,
    /// A flexure's two ends, written in place for each flexure in turn.
    ends: Vec<End<D>>,
    stiffness: Vec<Stiffness<D>>,
    /// The factor's row `j` times the pivots, `L_jp D_p`.
    scaled: Vec<D>,
    /// Each flexure's terms of the stiffness: formed once per structure.
    plan: Plan,
}

impl<D> Default for SolveBuffers<D> {
    fn default() -> Self {
        SolveBuffers {
            index: Vec::new(),
            k: Vec::new(),
            f: Vec::new(),
            moved: Vec::new(),
            ends: Vec::new(),
            stiffness: Vec::new(),
            scaled: Vec::new(),
            plan: Plan::default(),
        }
    }
}

/// The displacements of [`Network::solve_cases_in`]'s cases, in its buffers.
pub struct Solved<'a, D> {
    moved: &'a [[D; 3]],
    references: &'a [[D; 2]],
    index: &'a [usize],
    stiffness: &'a [Stiffness<D>],
}

impl<'a, D: Clone> Solved<'a, D> {
    /// Case `c`'s displacements.
    pub fn case(&self, c: usize) -> Displacements<'a, D> {
        let n = self.references.len();
        Displacements {
            bodies: Cow::Borrowed(&self.moved[c * n..(c + 1) * n]),
            references: self.references,
            index: Cow::Borrowed(self.index),
            stiffness: Cow::Borrowed(self.stiffness),
        }
    }
}

impl<D: Scalar> Displacements<'_, D> {
    /// Whether `body` moves in `dof` (the ground does not).
    pub fn moves(&self, body: Body, dof: Dof) -> bool {
        match body {
            Body::Ground => false,
            Body::Rigid(b) => self.index[3 * b + dof as usize] != HELD,
        }
    }

    /// Whether a point of `body` can move along `axis` ([`Dof::X`] or [`Dof::Y`]): the body
    /// moves so, or turns.
    pub fn point_moves(&self, body: Body, axis: Dof) -> bool {
        self.moves(body, axis) || self.moves(body, Dof::Rotation)
    }

    /// The motion of `point` of `body`: `(u, v, theta)` there (a body that does not turn
    /// moves the same everywhere).
    #[inline]
    pub fn at(&self, body: Body, point: [D; 2]) -> [D; 3] {
        match body {
            Body::Ground => [D::from(0.0); 3],
            Body::Rigid(b) if !self.moves(body, Dof::Rotation) => self.bodies[b],
            Body::Rigid(b) => transfer(sub(point, self.references[b]), self.bodies[b]),
        }
    }

    /// The translation of `point` of body `b`, `T(r) u` without its `theta` (a body that
    /// does not turn moves the same everywhere).
    #[inline(always)]
    fn translation(&self, b: usize, point: &[D; 2]) -> (D, D) {
        let m = &self.bodies[b];
        if self.moves(Body::Rigid(b), Dof::Rotation) {
            let o = &self.references[b];
            let (rx, ry) = (point[0] - o[0], point[1] - o[1]);
            (m[0] - ry * m[2], m[1] + rx * m[2])
        } else {
            (m[0], m[1])
        }
    }

    /// The motion of `point` of `body` in the frame whose `x` axis is the unit `(ex, ey)`,
    /// without the terms of a motion held: [`Displacements::at`] turned, read in place (its
    /// `[D; 3]`s passed by value were copies, `memcpy` for a `Jet<8>`).
    #[inline(always)]
    pub fn in_frame(&self, body: Body, point: &[D; 2], ex: D, ey: D) -> [D; 3] {
        let zero = D::from(0.0);
        let Body::Rigid(b) = body else {
            return [zero; 3];
        };
        let m = &self.bodies[b];
        let (mx, my) = self.translation(b, point);
        match (
            self.point_moves(body, Dof::X),
            self.point_moves(body, Dof::Y),
        ) {
            (true, true) => [ex * mx + ey * my, -ey * mx + ex * my, m[2]],
            (true, false) => [ex * mx, -ey * mx, m[2]],
            (false, true) => [ey * my, ex * my, m[2]],
            (false, false) => [zero, zero, m[2]],
        }
    }

    /// The motion of `point` of `body` along the unit `direction`, read in place.
    #[inline(always)]
    pub fn along_ref(&self, body: Body, point: &[D; 2], direction: &[D; 2]) -> D {
        let zero = D::from(0.0);
        let Body::Rigid(b) = body else {
            return zero;
        };
        let (mx, my) = self.translation(b, point);
        match (
            self.point_moves(body, Dof::X),
            self.point_moves(body, Dof::Y),
        ) {
            (true, true) => mx * direction[0] + my * direction[1],
            (true, false) => mx * direction[0],
            (false, true) => my * direction[1],
            (false, false) => zero,
        }
    }

    /// The motion of `point` of `body` along the unit `direction`.
    #[inline]
    pub fn along(&self, body: Body, point: [D; 2], direction: [D; 2]) -> D {
        self.along_ref(body, &point, &direction)
    }
}

impl<D: Scalar> Network<D> {
    /// The stiffness matrix of the bodies' degrees of freedom, row-major, `3n x 3n`.
    pub fn stiffness(&self) -> Result<Vec<D>, NetworkError> {
        let n = 3 * self.references.len();
        let mut k = vec![D::from(0.0); n * n];
        for (i, f) in self.flexures.iter().enumerate() {
            if f.from == f.to {
                return Err(NetworkError::SelfJoined { flexure: i });
            }
            self.add_flexure(f, &mut k, n);
        }
        for s in &self.springs {
            // the spring's force along n at the point, carried to the reference point:
            // the row a = T^T n (3 entries), stiffness k a a^T
            let r = sub(s.point, self.references[s.body]);
            let [nx, ny] = s.direction;
            let a = [nx, ny, -r[1] * nx + r[0] * ny];
            let o = 3 * s.body;
            for p in 0..3 {
                for q in 0..3 {
                    k[(o + p) * n + o + q] = k[(o + p) * n + o + q] + s.stiffness * a[p] * a[q];
                }
            }
        }
        Ok(k)
    }

    fn add_flexure(&self, f: &Flexure<D>, k: &mut [D], n: usize) {
        let c = &f.compliance;
        // K = C^-1: the axial entry, and the bending block's inverse
        let det = c.c22 * c.c33 - c.c23 * c.c23;
        let kb = [[c.c33 / det, -c.c23 / det], [-c.c23 / det, c.c22 / det]];
        let local = [
            [c.c11.recip(), D::from(0.0), D::from(0.0)],
            [D::from(0.0), kb[0][0], kb[0][1]],
            [D::from(0.0), kb[1][0], kb[1][1]],
        ];
        // each end's map from its body's reference motion to the end's motion in the
        // flexure's frame, with the clamped end's rigid transfer G folded into the start
        let [ex, ey] = f.axis;
        let rotate = |m: [[D; 3]; 3]| -> [[D; 3]; 3] {
            // R m, R = [ex ey 0; -ey ex 0; 0 0 1]
            let mut out = m;
            for j in 0..3 {
                out[0][j] = ex * m[0][j] + ey * m[1][j];
                out[1][j] = -ey * m[0][j] + ex * m[1][j];
            }
            out
        };
        let end = f.end;
        let map = |body: Body, point: [D; 2]| -> Option<(usize, [[D; 3]; 3])> {
            let Body::Rigid(b) = body else { return None };
            let r = sub(point, self.references[b]);
            let one = D::from(1.0);
            let zero = D::from(0.0);
            Some((
                b,
                rotate([[one, zero, -r[1]], [zero, one, r[0]], [zero, zero, one]]),
            ))
        };
        // d = A_to u_to - G A_from u_from: the two ends' maps with their signs
        let mut ends: Vec<(usize, [[D; 3]; 3])> = Vec::with_capacity(2);
        if let Some((b, m)) = map(f.from, f.start) {
            // -G m, G = [1 0 0; 0 1 l; 0 0 1]
            let mut g = m;
            for j in 0..3 {
                g[1][j] = m[1][j] + f.length * m[2][j];
            }
            ends.push((b, g.map(|row| row.map(|x| -x))));
        }
        if let Some(e) = map(f.to, end) {
            ends.push(e);
        }
        for &(bi, ai) in &ends {
            for &(bj, aj) in &ends {
                let block = product(transpose(ai), product(local, aj));
                for (p, row) in block.iter().enumerate() {
                    for (q, &v) in row.iter().enumerate() {
                        let idx = (3 * bi + p) * n + 3 * bj + q;
                        k[idx] = k[idx] + v;
                    }
                }
            }
        }
    }

    /// The bodies' displacements under `loads`.
    pub fn solve(&self, loads: &[Load<D>]) -> Result<Displacements<'_, D>, NetworkError> {
        let mut all = self.solve_cases(&[loads])?;
        Ok(all.remove(0))
    }

    /// The bodies' displacements under each of `cases`, from one factorization of the
    /// stiffness of the degrees of freedom not held (a held one's row and column drop out:
    /// the factor of the rest is the one the whole matrix with a unit pivot there would
    /// give, at the cost of the free ones alone).
    pub fn solve_cases(
        &self,
        cases: &[&[Load<D>]],
    ) -> Result<Vec<Displacements<'_, D>>, NetworkError> {
        let mut buffers = SolveBuffers::default();
        let cases: Vec<Case<D>> = cases
            .iter()
            .map(|&loads| Case { loads, read: None })
            .collect();
        let solved = self.solve_cases_in(&cases, &mut buffers)?;
        Ok((0..cases.len())
            .map(|c| Displacements {
                bodies: Cow::Owned(solved.case(c).bodies.into_owned()),
                references: &self.references,
                index: Cow::Owned(solved.index.to_vec()),
                stiffness: Cow::Owned(solved.stiffness.to_vec()),
            })
            .collect())
    }

    /// The loads at flexure `i`'s end on its second body, in its own frame, under the
    /// displacements `u`: `K (u_Q - G u_P)`, the axial force, shear and moment its
    /// compliance relates to its deformation ([`crate::model::hinge::HingeLoads`], whose
    /// stresses the hinge library gives). `K` is the one the solve formed: inverting the
    /// compliance again cost three quotients of dual numbers per flexure.
    pub fn flexure_loads(&self, i: usize, u: &Displacements<D>) -> HingeLoads<D> {
        let f = &self.flexures[i];
        let (ex, ey) = (f.axis[0], f.axis[1]);
        let p = u.in_frame(f.from, &f.start, ex, ey);
        let q = u.in_frame(f.to, &f.end, ex, ey);
        // Q's motion relative to the rigid motion of P carried along the flexure
        let d = [q[0] - p[0], q[1] - (p[1] + f.length * p[2]), q[2] - p[2]];
        let [k11, k22, k23, k33] = u.stiffness[i];
        HingeLoads {
            axial: k11 * d[0],
            shear: k22 * d[1] + k23 * d[2],
            moment: k23 * d[1] + k33 * d[2],
        }
    }
}

impl<D: Scalar> Flexure<D> {
    /// The flexure from `start` on `from` along the unit `axis` for `length` to `to`.
    pub fn new(
        from: Body,
        to: Body,
        start: [D; 2],
        axis: [D; 2],
        length: D,
        compliance: Compliance<D>,
    ) -> Self {
        Flexure {
            from,
            to,
            start,
            axis,
            length,
            end: end_of(&start, &axis, length),
            compliance,
        }
    }
}

/// `start + length * axis`: a flexure's end on `to`.
#[inline(always)]
pub fn end_of<D: Scalar>(start: &[D; 2], axis: &[D; 2], length: D) -> [D; 2] {
    [start[0] + axis[0] * length, start[1] + axis[1] * length]
}

fn product<D: Scalar>(a: [[D; 3]; 3], b: [[D; 3]; 3]) -> [[D; 3]; 3] {
    std::array::from_fn(|p| {
        std::array::from_fn(|q| a[p][0] * b[0][q] + a[p][1] * b[1][q] + a[p][2] * b[2][q])
    })
}

fn transpose<D: Scalar>(a: [[D; 3]; 3]) -> [[D; 3]; 3] {
    std::array::from_fn(|p| std::array::from_fn(|q| a[q][p]))
}

fn sub<D: Scalar>(a: [D; 2], b: [D; 2]) -> [D; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The motion at `r` from a point moving by `u`: `T(r) u`.
fn transfer<D: Scalar>(r: [D; 2], u: [D; 3]) -> [D; 3] {
    [u[0] - r[1] * u[2], u[1] + r[0] * u[2], u[2]]
}
