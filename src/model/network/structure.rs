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

use std::borrow::Cow;
use std::fmt;

use super::supports::Constraints;
use crate::model::hinge::{Compliance, HingeLoads};
use crate::model::material::Material;
use crate::model::scalar::Scalar;

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
/// held at zero (a guide, a roller), held exactly ([`Constraints`]).
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

/// A pivot below this fraction of the largest diagonal entry is a free motion. The
/// stiffest and softest directions of a flexure network differ by about the ratio of a
/// hinge's axial to its rotational stiffness over a lever squared (1e6 to 1e9 for
/// notches of 0.1 to 1 mm over links of 10 mm); a free motion leaves round-off, 1e-16 of
/// the diagonal.
const FREE_PIVOT: f64 = 1e-13;

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

    /// [`Network::solve_cases`] in `buffers`, which a caller keeps from one design to the
    /// next: the evaluation of a small network is otherwise mostly its allocations. A
    /// case's bodies not read are left NaN: the substitutions stop short of them.
    pub fn solve_cases_in<'a>(
        &'a self,
        cases: &[Case<D>],
        buffers: &'a mut SolveBuffers<D>,
    ) -> Result<Solved<'a, D>, NetworkError> {
        let bodies = self.references.len();
        let SolveBuffers {
            index,
            k,
            f,
            moved,
            ends,
            stiffness,
            scaled,
            plan,
        } = buffers;
        // the free numbering is the plan's while the structure is the one it was formed for
        if !plan.fits(bodies, &self.held, &self.flexures) {
            let m = self.free_numbering(index);
            *plan = Plan::form(index, m, &self.held, &self.flexures);
        }
        let plan = &*plan;
        let (index, m) = (&plan.index[..], plan.m);
        k.clear();
        k.resize(m * m, D::from(0.0));
        if ends.len() != 2 {
            ends.clear();
            ends.resize_with(2, End::zero);
        }
        if let Some(i) = self.flexures.iter().position(|fl| fl.from == fl.to) {
            return Err(NetworkError::SelfJoined { flexure: i });
        }
        // every flexure's slot is written below: zeroed only when the count changes
        if stiffness.len() != self.flexures.len() {
            stiffness.clear();
            stiffness.resize(self.flexures.len(), [D::from(0.0); 4]);
        }
        for (i, (fl, kf)) in self.flexures.iter().zip(stiffness.iter_mut()).enumerate() {
            self.add_flexure_free(fl, index, k, ends, plan.terms(i), kf);
        }
        let spring = |k: &mut [D], body: usize, a: [D; 3], stiffness: D| {
            for p in 0..3 {
                for q in 0..=p {
                    let (i, j) = (index[3 * body + p], index[3 * body + q]);
                    if i != HELD && j != HELD {
                        let (i, j) = (i.max(j), i.min(j));
                        k[i * m + j] = k[i * m + j] + stiffness * a[p] * a[q];
                    }
                }
            }
        };
        for s in &self.springs {
            let a = along_row(&s.point, &self.references[s.body], &s.direction);
            spring(&mut k[..], s.body, a, s.stiffness);
        }
        // each guide a spring as stiff as the stiffest free degree of freedom: any stiffness
        // gives the same constrained motion, and this one keeps the factor's conditioning
        let stiffest = (0..m).fold(0.0f64, |s, i| s.max(k[i * m + i].re().abs()));
        let guides: Vec<Vec<(usize, D)>> = self
            .guides
            .iter()
            .map(|g| {
                let a = along_row(&g.point, &self.references[g.body], &g.direction);
                spring(
                    &mut k[..],
                    g.body,
                    a,
                    D::from(stiffest.max(f64::MIN_POSITIVE)),
                );
                (0..3)
                    .filter(|&p| index[3 * g.body + p] != HELD)
                    .map(|p| (index[3 * g.body + p], a[p]))
                    .collect()
            })
            .collect();
        factor(k, m, scaled).map_err(|free| {
            let dof = index.iter().position(|&i| i == free).unwrap_or(0);
            NetworkError::Free {
                body: dof / 3,
                direction: ["x", "y", "rotation"][dof % 3],
            }
        })?;
        let constraints = if guides.is_empty() {
            None
        } else {
            let factored: &[D] = k;
            let solve = |f: &mut [D]| substitute(factored, m, f, 0, 0);
            Some(
                Constraints::new(guides, m, solve)
                    .map_err(|guide| NetworkError::Redundant { guide })?,
            )
        };
        // written in place: a pushed [Jet<8>; 3] is a call to memcpy
        moved.clear();
        moved.resize(cases.len() * bodies, [D::from(0.0); 3]);
        for (case, moved) in cases.iter().zip(moved.chunks_exact_mut(bodies.max(1))) {
            f.clear();
            f.resize(m, D::from(0.0));
            // the first entry of `f` loaded, and the first read: the forward substitution
            // starts at the one (the entries before stay zero), the back substitution ends
            // at the other (those before feed only entries not read)
            let mut loaded = m;
            let first_read = match case.read {
                None => 0,
                Some(read) => read
                    .iter()
                    .flat_map(|&b| &index[3 * b..3 * b + 3])
                    .filter(|&&i| i != HELD)
                    .fold(m, |a, &i| a.min(i)),
            };
            for l in case.loads.iter() {
                let origin = &self.references[l.body];
                let r = [l.point[0] - origin[0], l.point[1] - origin[1]];
                let o = 3 * l.body;
                let moment = l.moment + (r[0] * l.force[1] - r[1] * l.force[0]);
                // read in place: a list of the three (dof, value) pairs was a copy
                for (dof, v) in [(o, &l.force[0]), (o + 1, &l.force[1]), (o + 2, &moment)] {
                    if index[dof] != HELD {
                        f[index[dof]] = f[index[dof]] + *v;
                        loaded = loaded.min(index[dof]);
                    }
                }
            }
            match &constraints {
                None => substitute(k, m, f, loaded, first_read),
                Some(c) => {
                    // the correction reads the guided bodies and writes every entry
                    substitute(k, m, f, loaded, 0);
                    c.correct(f);
                }
            }
            for (b, (u, index)) in moved.iter_mut().zip(index.chunks_exact(3)).enumerate() {
                if case.read.is_some_and(|read| !read.contains(&b)) {
                    *u = [D::from(f64::NAN); 3];
                    continue;
                }
                for (v, &i) in u.iter_mut().zip(index) {
                    if i != HELD {
                        *v = f[i];
                    }
                }
            }
        }
        Ok(Solved {
            moved,
            references: &self.references,
            index,
            stiffness,
        })
    }

    /// Each degree of freedom's place among those not held ([`HELD`] if held) into `index`,
    /// and their count.
    fn free_numbering(&self, index: &mut Vec<usize>) -> usize {
        index.clear();
        index.resize(3 * self.references.len(), 0);
        for &(body, dof) in &self.held {
            index[3 * body + dof as usize] = HELD;
        }
        let mut m = 0;
        for i in index.iter_mut().filter(|i| **i != HELD) {
            *i = m;
            m += 1;
        }
        m
    }

    /// Flexure `f`'s stiffness into the lower triangle of `k`, the free degrees of freedom
    /// numbered by `index`: each block `A_i^T K A_j` of the module's formula, with the maps'
    /// known zeros and ones skipped and each entry of the symmetric matrix formed once, by
    /// the flexure's [`Plan`] terms; and its own stiffness `K` into `stiffness` (written in
    /// place: returned, it was a `memcpy`).
    fn add_flexure_free(
        &self,
        f: &Flexure<D>,
        index: &[usize],
        k: &mut [D],
        ends: &mut [End<D>],
        terms: [&[Term]; 7],
        stiffness: &mut Stiffness<D>,
    ) {
        let c = &f.compliance;
        // K = C^-1: the axial entry, and the bending block's inverse, formed in its slot (formed
        // apart and then stored, the four were a `memcpy`)
        let det = c.c22 * c.c33 - c.c23 * c.c23;
        *stiffness = [c.c11.recip(), c.c33 / det, -(c.c23 / det), c.c22 / det];
        let [k11, k22, k23, k33] = &*stiffness;
        let (k11, k22, k23, k33) = (*k11, *k22, *k23, *k33);
        let (ex, ey) = (f.axis[0], f.axis[1]);
        // an end's map R T(r) from its body's reference motion to the end's motion in the
        // flexure's frame, by columns (u, v, theta); its third row is (0, 0, 1). The
        // clamped start's carries G (its v gains l theta) and enters with a minus sign.
        // Each end's map and K times it are written into the buffer's slot: an `End` (15
        // Jet<8>s) returned in an `Option` was copied twice. Only the columns of the degrees
        // of freedom not held are read, and formed.
        let end = |e: &mut End<D>, body: Body, point: &[D; 2], lever: Option<D>| {
            let Body::Rigid(b) = body else {
                e.body = None;
                return;
            };
            e.body = Some(b);
            let free = |q: usize| index[3 * b + q] != HELD;
            if free(0) {
                e.ka[0] = [k11 * ex, k22 * -ey, k23 * -ey];
            }
            if free(1) {
                e.ka[1] = [k11 * ey, k22 * ex, k23 * ex];
            }
            e.columns[0] = [ex, -ey];
            e.columns[1] = [ey, ex];
            if free(2) {
                let o = &self.references[b];
                let (rx, ry) = (point[0] - o[0], point[1] - o[1]);
                let t0 = ey * rx - ex * ry;
                let t1 = ey * ry + ex * rx;
                let t1 = match lever {
                    Some(l) => t1 + l,
                    None => t1,
                };
                e.ka[2] = [k11 * t0, k22 * t1 + k23, k23 * t1 + k33];
                e.columns[2] = [t0, t1];
            }
        };
        let (first, second) = ends.split_at_mut(1);
        end(&mut first[0], f.from, &f.start, Some(f.length));
        end(&mut second[0], f.to, &f.end, None);
        let ends: &[End<D>; 2] = (&*ends).try_into().expect("two ends");
        let dot = |t: &Term| dot(ends, t);
        let third = |t: &Term| ends[t.other & 1].ka[t.q.min(2)][2];
        let [pairs, same_moves, same, same_turn, across_moves, across, across_turn] = terms;
        // a translation's columns and `K A` are the same at both ends (`R`, and `K R`), so
        // each product of two translations is formed once for the flexure, bit for bit the
        // one each of its terms formed
        let mut moves = [[D::from(0.0); 2]; 2];
        for t in pairs {
            moves[t.p & 1][t.q & 1] = dot(t);
        }
        let moves = |t: &Term| moves[t.p & 1][t.q & 1];
        for t in same_moves {
            k[t.at] = k[t.at] + moves(t);
        }
        for t in same {
            k[t.at] = k[t.at] + dot(t);
        }
        for t in same_turn {
            k[t.at] = k[t.at] + (dot(t) + third(t));
        }
        for t in across_moves {
            k[t.at] = k[t.at] - moves(t);
        }
        for t in across {
            k[t.at] = k[t.at] - dot(t);
        }
        for t in across_turn {
            k[t.at] = k[t.at] - (dot(t) + third(t));
        }
    }
}

/// Term `t`'s `columns[p] . ka[q]`, the third row of `A` (0, 0, 1) left out. Inlined, its
/// indices masked to the arrays' sizes: a call per term, with its bounds checks, cost
/// about as much as the term's arithmetic.
#[inline(always)]
fn dot<D: Scalar>(ends: &[End<D>; 2], t: &Term) -> D {
    let a = &ends[t.one & 1].columns[t.p.min(2)];
    let kq = &ends[t.other & 1].ka[t.q.min(2)];
    a[0] * kq[0] + a[1] * kq[1]
}

/// Each flexure's terms of the stiffness among the free degrees of freedom: which of its
/// ends' columns meet in which entry of the lower triangle. They follow from the structure
/// alone (the free numbering, the bodies each flexure joins), so they are formed once for
/// a structure, not tested entry by entry at each design: those tests, on loops of zero to
/// three trips, were the assembly's unpredictable branches.
#[derive(Debug, Clone, Default)]
struct Plan {
    /// The structure the terms are for: its bodies' count, the degrees of freedom held,
    /// and the free numbering they give ([`Network::free_numbering`]), `m` of them free.
    count: usize,
    held: Vec<(usize, Dof)>,
    index: Vec<usize>,
    m: usize,
    bodies: Vec<(Body, Body)>,
    terms: Vec<Term>,
    /// Flexure `i`'s terms in seven groups, `terms[groups[i][g]..groups[i][g + 1]]`: the
    /// distinct pairs `(p, q)` of two translations among its terms (each once, `at`
    /// unused); then an end with itself (added): two translations, the others, the end's
    /// rotation as `p` (added with `K`'s third row); then one end with the other
    /// (subtracted), in the same three groups.
    groups: Vec<[usize; 8]>,
}

/// Entry `at` of the stiffness gains `columns[p] . ka[q]` of ends `one` and `other`
/// ([`End`]; end 0 on `from`, 1 on `to`).
#[derive(Debug, Clone, Copy)]
struct Term {
    at: usize,
    one: usize,
    p: usize,
    other: usize,
    q: usize,
}

impl Plan {
    fn fits<D>(&self, count: usize, held: &[(usize, Dof)], flexures: &[Flexure<D>]) -> bool {
        self.count == count
            && self.held == held
            && self.bodies.len() == flexures.len()
            && self
                .bodies
                .iter()
                .zip(flexures)
                .all(|(&(from, to), f)| from == f.from && to == f.to)
    }

    fn form<D>(index: &[usize], m: usize, held: &[(usize, Dof)], flexures: &[Flexure<D>]) -> Plan {
        let mut plan = Plan {
            count: index.len() / 3,
            held: held.to_vec(),
            index: index.to_vec(),
            m,
            bodies: flexures.iter().map(|f| (f.from, f.to)).collect(),
            terms: Vec::new(),
            groups: Vec::with_capacity(flexures.len()),
        };
        for f in flexures {
            let mut groups: [Vec<Term>; 7] = Default::default();
            let ends = [f.from, f.to];
            for (one, bi) in ends.iter().enumerate() {
                let Body::Rigid(bi) = *bi else { continue };
                for (other, bj) in ends.iter().enumerate() {
                    let Body::Rigid(bj) = *bj else { continue };
                    for p in 0..3 {
                        let gi = index[3 * bi + p];
                        if gi == HELD {
                            continue;
                        }
                        for q in 0..3 {
                            let gj = index[3 * bj + q];
                            if gj == HELD || gj > gi {
                                continue;
                            }
                            let term = Term {
                                at: gi * m + gj,
                                one,
                                p,
                                other,
                                q,
                            };
                            let moves = p < 2 && q < 2;
                            if moves && !groups[0].iter().any(|t| (t.p, t.q) == (p, q)) {
                                groups[0].push(term);
                            }
                            let kind = if moves {
                                0
                            } else if p == 2 {
                                2
                            } else {
                                1
                            };
                            groups[1 + 3 * usize::from(one != other) + kind].push(term);
                        }
                    }
                }
            }
            let mut bounds = [plan.terms.len(); 8];
            for (g, terms) in groups.into_iter().enumerate() {
                plan.terms.extend(terms);
                bounds[g + 1] = plan.terms.len();
            }
            plan.groups.push(bounds);
        }
        plan
    }

    /// Flexure `i`'s seven groups of terms. Inlined: called, the seven slices cost about a
    /// hundred instructions a flexure.
    #[inline(always)]
    fn terms(&self, i: usize) -> [&[Term]; 7] {
        let g = &self.groups[i];
        std::array::from_fn(|j| &self.terms[g[j]..g[j + 1]])
    }
}

/// A flexure's end on a body: the body, the map `A` from its reference motion to the end's
/// motion in the flexure's frame by columns (the third row `(0, 0, 1)` left out), and the
/// flexure's stiffness times it, `K A`, by columns.
/// `body` is `None` on the ground; the columns of a held degree of freedom are stale.
#[derive(Debug, Clone)]
struct End<D> {
    body: Option<usize>,
    columns: [[D; 2]; 3],
    ka: [[D; 3]; 3],
}

impl<D: Scalar> End<D> {
    fn zero() -> Self {
        let zero = D::from(0.0);
        End {
            body: None,
            columns: [[zero; 2]; 3],
            ka: [[zero; 3]; 3],
        }
    }
}

/// [`Network::free_numbering`]'s mark of a held degree of freedom.
const HELD: usize = usize::MAX;

impl<D: Scalar> Network<D> {
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

/// The row `T(P - O)^T n` that gives the motion of `point` along the unit `direction` from
/// its body's reference motion (its reference point `reference`).
fn along_row<D: Scalar>(point: &[D; 2], reference: &[D; 2], direction: &[D; 2]) -> [D; 3] {
    let r = [point[0] - reference[0], point[1] - reference[1]];
    let [nx, ny] = *direction;
    [nx, ny, -r[1] * nx + r[0] * ny]
}

/// The motion at `r` from a point moving by `u`: `T(r) u`.
fn transfer<D: Scalar>(r: [D; 2], u: [D; 3]) -> [D; 3] {
    [u[0] - r[1] * u[2], u[1] + r[0] * u[2], u[2]]
}

/// `L D L^T` of the symmetric `k` in place (`L` below the diagonal, `D` on it; the upper
/// triangle is not read), or the first pivot that vanishes. Row `j` and each row below it
/// are read as slices, whose entries are read in place: indexed into the whole matrix,
/// every `Jet<8>` term was a bounds check and a copy, about a third of the factor's count.
/// Row `j` times the pivots, `w_p = L_jp D_p`, is formed once into `scaled` for the pivot
/// and every row below (Golub and Van Loan, "Matrix Computations", 3rd ed., Johns Hopkins
/// 1996, Sec. 4.1.2, Alg. 4.1.2): each term one product, where `L_ip L_jp D_p` was two.
fn factor<D: Scalar>(k: &mut [D], n: usize, scaled: &mut Vec<D>) -> Result<(), usize> {
    let scale = (0..n).map(|i| k[i * n + i].re().abs()).fold(0.0, f64::max);
    scaled.clear();
    scaled.resize(n, D::from(0.0));
    for j in 0..n {
        let (above, rest) = k.split_at_mut(j * n);
        let (row_j, below) = rest.split_at_mut(n);
        let w = &mut scaled[..j];
        let mut d = row_j[j];
        for (p, (w, l)) in w.iter_mut().zip(&row_j[..j]).enumerate() {
            *w = *l * above[p * n + p];
            d = d - *l * *w;
        }
        if d.re().is_nan() || d.re() <= FREE_PIVOT * scale {
            return Err(j);
        }
        row_j[j] = d;
        let w = &scaled[..j];
        for row_i in below.chunks_exact_mut(n) {
            let mut s = row_i[j];
            for (a, b) in row_i[..j].iter().zip(w) {
                s = s - *a * *b;
            }
            row_i[j] = s / d;
        }
    }
    Ok(())
}

/// `x` overwritten by `K^-1 x` from entry `from` on, `l` the factor of [`factor`], where
/// the entries of `x` before `loaded` are zero: `L^-1` keeps them zero, and the terms they
/// give are skipped (the same numbers: `a - l 0` is `a`); the entries before `from` are
/// left unfinished (the back substitution's last rows, which no entry from `from` on reads).
fn substitute<D: Scalar>(l: &[D], n: usize, x: &mut [D], loaded: usize, from: usize) {
    // each entry summed in a local from slices, in the same order as by index
    for i in loaded..n {
        let (done, rest) = x.split_at_mut(i);
        let mut xi = rest[0];
        for (a, b) in l[i * n + loaded..i * n + i].iter().zip(&done[loaded..]) {
            xi = xi - *a * *b;
        }
        rest[0] = xi;
    }
    for i in loaded.max(from)..n {
        x[i] = x[i] / l[i * n + i];
    }
    for i in (from..n).rev() {
        let (head, tail) = x.split_at_mut(i + 1);
        let mut xi = head[i];
        // column i of L below row i (none below the last)
        let column = l.get((i + 1) * n + i..).unwrap_or_default();
        for (a, b) in column.iter().step_by(n).zip(tail.iter()) {
            xi = xi - *a * *b;
        }
        head[i] = xi;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::hinge::HingeKind;
    use crate::model::material::Material;
    use crate::model::scalar::Jet;

    fn strip<D: Scalar>(length: D, thickness: D) -> Compliance<D> {
        HingeKind::Strip.compliance(&[length, thickness], 0.01, &Material::al7075_t6())
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs())
    }

    /// One flexure from the ground: its free end moves by its compliance, turned into the
    /// flexure's frame and back, at every orientation.
    #[test]
    fn a_cantilever_moves_by_its_compliance_at_any_angle() {
        let c = strip(0.004, 0.0005);
        for k in 0..12 {
            let phi = -3.0 + 0.5 * k as f64;
            let (s, co) = phi.sin_cos();
            let start = [0.003, -0.002];
            let f = Flexure::new(Body::Ground, Body::Rigid(0), start, [co, s], 0.004, c);
            let end = f.end;
            let net = Network {
                references: vec![end],
                flexures: vec![f],
                springs: vec![],
                guides: vec![],
                held: vec![],
            };
            let (fx, fy, m) = (3.0, -2.0, 0.01);
            let u = net
                .solve(&[Load {
                    body: 0,
                    point: end,
                    force: [fx, fy],
                    moment: m,
                }])
                .unwrap();
            let (n, v) = (co * fx + s * fy, -s * fx + co * fy);
            let (dx, dy, th) = (c.c11 * n, c.c22 * v + c.c23 * m, c.c23 * v + c.c33 * m);
            let expected = [co * dx - s * dy, s * dx + co * dy, th];
            for (got, want) in u.bodies[0].iter().zip(expected) {
                assert!(close(*got, want, 1e-9), "{phi}: {got} against {want}");
            }
            // the flexure carries the load, turned into its frame
            let loads = net.flexure_loads(0, &u);
            for (got, want) in [(loads.axial, n), (loads.shear, v), (loads.moment, m)] {
                assert!(close(got, want, 1e-9), "{phi}: {got} against {want}");
            }
        }
    }

    /// Two parallel strips from the ground to a stage (a parallelogram guide), loaded
    /// sideways at the middle of their ends: the matrix method against the guide's closed
    /// form, with the strips' axial compliance letting the stage tilt,
    /// `F / v = 2 (a - b^2 / (c + k_a h^2 / 4))`, `[a b; b c]` the strips' bending block
    /// inverted and `k_a` their axial stiffness; and against beam theory's guided beams,
    /// `24 E I / l^3`, which leaves out the strips' shear and axial give.
    #[test]
    fn a_parallelogram_guide_has_the_guided_beams_stiffness() {
        let (l, t, h) = (0.01, 0.0003, 0.02);
        let c = strip(l, t);
        let leaf = |y: f64| Flexure::new(Body::Ground, Body::Rigid(0), [0.0, y], [1.0, 0.0], l, c);
        let net = Network {
            references: vec![[l, 0.0]],
            flexures: vec![leaf(-h / 2.0), leaf(h / 2.0)],
            springs: vec![],
            guides: vec![],
            held: vec![],
        };
        let force = 1.0;
        let u = net
            .solve(&[Load {
                body: 0,
                point: [l, 0.0],
                force: [0.0, force],
                moment: 0.0,
            }])
            .unwrap();
        let det = c.c22 * c.c33 - c.c23 * c.c23;
        let (a, b, cc) = (c.c33 / det, -c.c23 / det, c.c22 / det);
        let ka = 1.0 / c.c11;
        let closed = 2.0 * (a - b * b / (cc + ka * h * h / 4.0));
        let k = force / u.bodies[0][1];
        assert!(close(k, closed, 1e-10), "{k} against {closed}");
        // the shears carry the load; about the stage's reference point, the strips' end
        // moments and the couple of their axial forces across the guide balance
        let theta = u.bodies[0][2];
        for (i, y) in [(0, -h / 2.0), (1, h / 2.0)] {
            let loads = net.flexure_loads(i, &u);
            let axial = -ka * theta * y;
            assert!(close(loads.axial, axial, 1e-6), "{} {axial}", loads.axial);
            let (v, th) = (u.bodies[0][1], theta);
            assert!(close(loads.shear, a * v + b * th, 1e-9));
            assert!(close(loads.moment, b * v + cc * th, 1e-9));
        }
        let (l0, l1) = (net.flexure_loads(0, &u), net.flexure_loads(1, &u));
        assert!(
            close(l0.shear + l1.shear, force, 1e-9),
            "the shears carry the load"
        );
        let arm = l0.moment + l1.moment + (l0.axial - l1.axial) * h / 2.0;
        assert!(arm.abs() < 1e-9 * force * l, "the moments balance: {arm}");
        assert!(
            u.bodies[0][0].abs() < 1e-12 * u.bodies[0][1].abs(),
            "no axial motion"
        );
        // beam theory: Euler-Bernoulli, 24 E I / l^3; with the strips' shear (the strip's
        // c22 takes the shear deflection l / (G w t)), 2 / (l^3 / (12 E I) + l / (G w t));
        // the stage's tilt on the strips' axial give is left, 3 (t/h)^2 / 4 of the bending
        // block's coupling (2e-4 here)
        let m = Material::al7075_t6();
        let ei = m.youngs_modulus * (0.01 * t.powi(3) / 12.0);
        let beam = 24.0 * ei / l.powi(3);
        let shear = l / (m.shear_modulus() * 0.01 * t);
        let timoshenko = 2.0 / (l.powi(3) / (12.0 * ei) + shear);
        assert!(close(k, timoshenko, 3e-4), "{k} against {timoshenko}");
        assert!(k < timoshenko && k < beam, "{k} against {beam}");
    }

    /// The stiffness is symmetric and positive definite; by Maxwell-Betti, the motion at
    /// one point along one direction under a unit force at another equals the converse.
    #[test]
    fn the_stiffness_is_symmetric_and_reciprocal() {
        let net = two_stage(0.0004);
        let k = net.stiffness().unwrap();
        let n = 6;
        for i in 0..n {
            for j in 0..n {
                assert!(close(k[i * n + j], k[j * n + i], 1e-12) || k[i * n + j].abs() < 1e-6);
            }
        }
        let (p, q) = ([0.012, 0.003], [0.02, -0.004]);
        let (dp, dq) = ([0.6, 0.8], [0.0, 1.0]);
        let unit = |body, point: [f64; 2], dir: [f64; 2]| Load {
            body,
            point,
            force: dir,
            moment: 0.0,
        };
        let a = net
            .solve(&[unit(0, p, dp)])
            .unwrap()
            .along(Body::Rigid(1), q, dq);
        let b = net
            .solve(&[unit(1, q, dq)])
            .unwrap()
            .along(Body::Rigid(0), p, dp);
        assert!(close(a, b, 1e-9), "{a} {b}");
    }

    /// Two bodies: the first held by two strips from the ground, the second joined to it
    /// and to the ground by one strip each, with an actuator's spring on the first.
    fn two_stage<D: Scalar>(t: D) -> Network<D> {
        let c = |l: f64| strip(D::from(l), t);
        let flexure = |from, to, start: [f64; 2], axis: [f64; 2], l: f64| {
            Flexure::new(
                from,
                to,
                start.map(D::from),
                axis.map(D::from),
                D::from(l),
                c(l),
            )
        };
        Network {
            references: vec![[D::from(0.01), D::from(0.0)], [D::from(0.02), D::from(0.0)]],
            flexures: vec![
                flexure(
                    Body::Ground,
                    Body::Rigid(0),
                    [0.0, 0.002],
                    [1.0, 0.0],
                    0.004,
                ),
                flexure(
                    Body::Ground,
                    Body::Rigid(0),
                    [0.0, -0.002],
                    [0.8, -0.6],
                    0.003,
                ),
                flexure(
                    Body::Rigid(0),
                    Body::Rigid(1),
                    [0.012, 0.0],
                    [0.6, 0.8],
                    0.002,
                ),
                flexure(
                    Body::Ground,
                    Body::Rigid(1),
                    [0.03, 0.01],
                    [-0.6, -0.8],
                    0.005,
                ),
            ],
            springs: vec![Spring {
                body: 0,
                point: [D::from(0.01), D::from(0.001)],
                direction: [D::from(1.0), D::from(0.0)],
                stiffness: D::from(2e6),
            }],
            held: vec![],
            guides: vec![],
        }
    }

    /// Exact derivatives through the solve: a `Jet` over the hinges' thickness against
    /// central differences.
    #[test]
    fn displacements_have_exact_derivatives() {
        let t = 0.0004;
        let load = |body| Load {
            body,
            point: [0.01, 0.001],
            force: [1.0, 0.5],
            moment: 0.0,
        };
        let motion = |t: f64| {
            let net = two_stage(t);
            let u = net.solve(&[load(0)]).unwrap();
            u.along(Body::Rigid(1), [0.02, 0.0], [0.0, 1.0])
        };
        let jet = {
            let net = two_stage(Jet::<1>::variable(t, 0));
            let loads = [Load {
                body: 0,
                point: [0.01, 0.001].map(Jet::from),
                force: [1.0, 0.5].map(Jet::from),
                moment: Jet::from(0.0),
            }];
            let u = net.solve(&loads).unwrap();
            u.along(
                Body::Rigid(1),
                [0.02, 0.0].map(Jet::from),
                [0.0, 1.0].map(Jet::from),
            )
        };
        let h = 1e-9;
        let fd = (motion(t + h) - motion(t - h)) / (2.0 * h);
        // the same solve, its operations grouped differently in the dual number
        assert!(close(jet.re, motion(t), 1e-12));
        assert!(close(jet.grad[0], fd, 1e-6), "{} against {fd}", jet.grad[0]);
    }

    #[test]
    fn a_free_body_and_a_self_joined_flexure_are_named() {
        let mut net = two_stage(0.0004);
        net.references.push([0.05, 0.0]);
        assert_eq!(
            net.stiffness().map(|_| ()),
            Ok(()),
            "the matrix is built; the solve finds the free body"
        );
        let err = net.solve(&[]).unwrap_err();
        assert_eq!(
            err,
            NetworkError::Free {
                body: 2,
                direction: "x"
            }
        );
        assert!(err.to_string().contains("body 2 is free to move (x)"));
        // a body held by one strip along its axis only, hinged at the ground: it turns
        let mut hinged = two_stage(0.0004);
        hinged.flexures.truncate(1);
        hinged.flexures[0].compliance.c33 = 1e12;
        hinged.flexures[0].compliance.c23 = 0.0;
        hinged.flexures[0].compliance.c22 = 1e12;
        hinged.springs.clear();
        hinged.references.truncate(1);
        let err = hinged.solve(&[]).unwrap_err();
        assert!(matches!(err, NetworkError::Free { body: 0, .. }), "{err:?}");
        let mut joined = two_stage(0.0004);
        joined.flexures[2].to = Body::Rigid(0);
        assert_eq!(
            joined.stiffness().map(|_| ()),
            Err(NetworkError::SelfJoined { flexure: 2 })
        );
    }

    /// The solve's buffers, kept from one network to the next (a thread evaluates several
    /// models with them), form their plan of the assembly again when the structure changes:
    /// the same flexures with a degree of freedom held, or the flexures joining other
    /// bodies, solve as with fresh buffers, in any order.
    #[test]
    fn buffers_kept_across_structures_solve_as_fresh_ones() {
        let free = two_stage(0.0004);
        let mut held = two_stage(0.0004);
        held.held = vec![(1, Dof::Rotation)];
        let mut rejoined = two_stage(0.0004);
        rejoined.flexures[1].to = Body::Rigid(1);
        let loads = [Load {
            body: 1,
            point: [0.02, 0.001],
            force: [0.3, -1.0],
            moment: 0.002,
        }];
        let cases = [Case {
            loads: &loads,
            read: None,
        }];
        let mut buffers = SolveBuffers::default();
        let mut solutions = Vec::new();
        for net in [&free, &held, &rejoined, &free, &rejoined, &held, &held] {
            let fresh = net.solve(&loads).unwrap();
            let solved = net.solve_cases_in(&cases, &mut buffers).unwrap();
            let kept = solved.case(0);
            assert_eq!(&*kept.bodies, &*fresh.bodies);
            for i in 0..net.flexures.len() {
                assert_eq!(net.flexure_loads(i, &kept), net.flexure_loads(i, &fresh));
            }
            solutions.push(fresh.bodies[1]);
        }
        // the three structures differ, so a stale plan would show
        assert_eq!(solutions[1][2], 0.0, "held");
        assert!(solutions[0][2] != 0.0);
        assert!(solutions[0][0] != solutions[2][0]);
    }

    /// A quarter of a rhombic bridge: one hinge from the input block (held on the output's
    /// mirror axis: no vertical motion, no rotation) to the output block (on the input's
    /// axis: no horizontal motion, no rotation). Its amplification is paper 004's rhombic
    /// limit of Eq. 9 for any hinge, and Eq. 25 as printed for a hinge without shear
    /// compliance ([`crate::model::reference::closed_forms`]).
    #[test]
    fn a_quarter_rhombus_amplifies_as_paper_004s_closed_form() {
        use crate::model::reference::closed_forms::{rhombic, rhombic_general};
        let mut worst = [0.0f64; 2];
        for k in 0..40 {
            let delta = 0.01 + 0.02 * k as f64;
            let (length, t) = (0.004 + 0.0002 * k as f64, 0.0003 + 0.00001 * k as f64);
            let mut bending_only = strip(length, t);
            for (i, c) in [strip(length, t), {
                bending_only.c22 = 4.0 * length.powi(3) / (72e9 * 0.01 * t.powi(3));
                bending_only
            }]
            .into_iter()
            .enumerate()
            {
                let (s, co) = delta.sin_cos();
                let end = [length * co, length * s];
                let net = Network {
                    references: vec![[0.0, 0.0], end],
                    flexures: vec![Flexure::new(
                        Body::Rigid(0),
                        Body::Rigid(1),
                        [0.0, 0.0],
                        [co, s],
                        length,
                        c,
                    )],
                    springs: vec![],
                    guides: vec![],
                    held: vec![
                        (0, Dof::Y),
                        (0, Dof::Rotation),
                        (1, Dof::X),
                        (1, Dof::Rotation),
                    ],
                };
                let u = net
                    .solve(&[Load {
                        body: 0,
                        point: [0.0, 0.0],
                        force: [1.0, 0.0],
                        moment: 0.0,
                    }])
                    .unwrap();
                let da = u.bodies[1][1] / u.bodies[0][0];
                let expected = if i == 0 {
                    rhombic_general(&c, delta)
                } else {
                    rhombic(&c, delta)
                };
                worst[i] = worst[i].max((da - expected).abs() / expected.abs());
            }
        }
        assert!(worst[0] < 1e-12 && worst[1] < 1e-12, "{worst:?}");
    }
}
