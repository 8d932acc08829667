//! The residual, tangent stiffness and load vector of a structure on its free degrees of
//! freedom. Slave nodes follow their master rigidly (`x_p = x_b + R(theta_b) (X_p - X_b)`,
//! `theta_p = theta_b`); their forces reach the master through the transpose of that map's
//! Jacobian, and the map's curvature adds `-(d . f_p)` to the master's rotational stiffness
//! (`d` the current offset, `f_p` the slave's net force), which keeps the tangent exact for
//! loads and springs on rigid bodies.

use faer::Mat;

use super::element::{beam, length, spring};
use super::{LargeError, StructureOf};
use crate::model::scalar::Scalar;

/// A validated structure with its degrees of freedom sorted: the free ones (solved for)
/// and the held ones (prescribed). Over a scalar `D` as its structure ([`System`] the real
/// one, which the paths solve).
#[derive(Debug, Clone)]
pub struct SystemOf<'a, D> {
    pub structure: &'a StructureOf<D>,
    /// The master of each node, if it is a slave.
    pub master: Vec<Option<usize>>,
    /// The indices into the full `3 * nodes` vector of the free degrees of freedom.
    pub free: Vec<usize>,
    /// The held degrees of freedom and their values at load factor 1.
    pub held: Vec<(usize, D)>,
}

/// The system of a structure in real numbers.
pub type System<'a> = SystemOf<'a, f64>;

/// The internal forces less the loads `r`, the tangent `dr/du` (row-major, `m x m`) and
/// `-dr/dlambda` before the prescribed displacements' share `q`, on every degree of
/// freedom with the slaves' moved onto their masters.
pub struct Full<D> {
    pub k: Vec<D>,
    pub r: Vec<D>,
    pub q: Vec<D>,
}

/// The residual `r = g(u, lambda) - lambda f`, the tangent `dr/du` and the load vector
/// `q = -dr/dlambda` (prescribed displacements moving with `lambda` included), all on the
/// free degrees of freedom.
pub struct Assembled {
    pub residual: Vec<f64>,
    pub tangent: Mat<f64>,
    pub load: Vec<f64>,
}

fn check(ok: bool, what: impl FnOnce() -> String) -> Result<(), LargeError> {
    if ok {
        Ok(())
    } else {
        Err(LargeError::Invalid(what()))
    }
}

impl<'a, D: Scalar> SystemOf<'a, D> {
    /// Checks `structure` and sorts its degrees of freedom.
    pub fn new(structure: &'a StructureOf<D>) -> Result<Self, LargeError> {
        let n = structure.nodes.len();
        check(n > 0, || "no nodes".into())?;
        check(
            structure.nodes.iter().flatten().all(|v| v.re().is_finite()),
            || "a node position is not finite".into(),
        )?;
        let node_ok = |i: usize| i < n;
        for (e, b) in structure.beams.iter().enumerate() {
            check(node_ok(b.a) && node_ok(b.b), || {
                format!("beam {e}: node out of range")
            })?;
            let (xa, xb) = (re2(structure.nodes[b.a]), re2(structure.nodes[b.b]));
            let l0 = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
            check(l0 > 0.0, || format!("beam {e}: zero length"))?;
            let s = b.local(D::from(l0));
            let [[k11, k12], [k21, k22]] = s.bending.map(|row| row.map(|v| v.re()));
            let axial = s.axial.re();
            let finite = [axial, k11, k12, k21, k22].iter().all(|v| v.is_finite());
            check(
                finite && axial > 0.0 && k11 > 0.0 && k11 * k22 - k12 * k21 > 0.0 && k12 == k21,
                || format!("beam {e}: local stiffness {s:?} not symmetric positive definite"),
            )?;
        }
        for (e, s) in structure.springs.iter().enumerate() {
            check(node_ok(s.a) && node_ok(s.b), || {
                format!("spring {e}: node out of range")
            })?;
            let (xa, xb) = (re2(structure.nodes[s.a]), re2(structure.nodes[s.b]));
            check((xb[0] - xa[0]).hypot(xb[1] - xa[1]) > 0.0, || {
                format!("spring {e}: zero length")
            })?;
            let finite = [s.stiffness, s.free_stroke, s.preload]
                .iter()
                .all(|v| v.re().is_finite());
            check(finite && s.stiffness.re() > 0.0, || {
                format!("spring {e}: stiffness {:?} not positive", s.stiffness)
            })?;
        }
        let mut master = vec![None; n];
        for s in &structure.slaves {
            check(
                node_ok(s.node) && node_ok(s.master) && s.node != s.master,
                || format!("slave {} of {}: bad node", s.node, s.master),
            )?;
            check(master[s.node].is_none(), || {
                format!("node {} has two masters", s.node)
            })?;
            master[s.node] = Some(s.master);
        }
        for s in &structure.slaves {
            check(master[s.master].is_none(), || {
                format!(
                    "node {} is the master of {} but itself a slave",
                    s.master, s.node
                )
            })?;
        }
        let mut held = Vec::new();
        for &(node, dof, value) in &structure.held {
            check(node_ok(node) && value.re().is_finite(), || {
                format!("held node {node}")
            })?;
            check(master[node].is_none(), || {
                format!("node {node} is a slave: hold its master instead")
            })?;
            let i = 3 * node + dof as usize;
            check(held.iter().all(|&(j, _)| j != i), || {
                format!("node {node}: {dof:?} held twice")
            })?;
            held.push((i, value));
        }
        for &(node, force) in &structure.loads {
            check(
                node_ok(node) && force.iter().all(|f| f.re().is_finite()),
                || format!("load at node {node}"),
            )?;
        }
        let free = (0..3 * n)
            .filter(|&i| master[i / 3].is_none() && held.iter().all(|&(j, _)| j != i))
            .collect();
        Ok(SystemOf {
            structure,
            master,
            free,
            held,
        })
    }

    /// The full displacement vector from the free values and the load factor.
    pub fn expand(&self, free: &[D], lambda: f64) -> Vec<D> {
        let mut u = vec![D::from(0.0); 3 * self.structure.nodes.len()];
        for (&i, &v) in self.free.iter().zip(free) {
            u[i] = v;
        }
        for &(i, value) in &self.held {
            u[i] = value * lambda;
        }
        self.place_slaves(&mut u);
        u
    }

    fn offset(&self, node: usize, master: usize, theta: D) -> ([D; 2], [D; 2]) {
        let (xp, xb) = (self.structure.nodes[node], self.structure.nodes[master]);
        let r0 = [xp[0] - xb[0], xp[1] - xb[1]];
        let (s, c) = theta.sin_cos();
        (r0, [c * r0[0] - s * r0[1], s * r0[0] + c * r0[1]])
    }

    fn place_slaves(&self, u: &mut [D]) {
        for (p, m) in self.master.iter().enumerate() {
            if let Some(b) = *m {
                let (r0, d) = self.offset(p, b, u[3 * b + 2]);
                u[3 * p] = u[3 * b] + d[0] - r0[0];
                u[3 * p + 1] = u[3 * b + 1] + d[1] - r0[1];
                u[3 * p + 2] = u[3 * b + 2];
            }
        }
    }

    /// The internal forces, tangent and load on every degree of freedom at the full
    /// displacement `u` (from [`Self::expand`]) and load factor `lambda`.
    pub fn assemble_full(&self, u: &[D], lambda: f64) -> Full<D> {
        let st = self.structure;
        let m = u.len();
        let zero = D::from(0.0);
        let mut k = vec![zero; m * m];
        let mut r = vec![zero; m];
        // -dr/dlambda before the prescribed displacements' share
        let mut q = vec![zero; m];
        for b in &st.beams {
            let idx = [0, 1, 2].map(|j| 3 * b.a + j);
            let idx = [idx[0], idx[1], idx[2], 3 * b.b, 3 * b.b + 1, 3 * b.b + 2];
            let d = idx.map(|i| u[i]);
            let (xa, xb) = (st.nodes[b.a], st.nodes[b.b]);
            let c = beam(xa, xb, b.local(length(xa, xb)), &d);
            for (x, &i) in idx.iter().enumerate() {
                r[i] = r[i] + c.force[x];
                for (y, &j) in idx.iter().enumerate() {
                    k[i * m + j] = k[i * m + j] + c.stiffness[x][y];
                }
            }
        }
        for s in &st.springs {
            let idx = [3 * s.a, 3 * s.a + 1, 3 * s.b, 3 * s.b + 1];
            let d = idx.map(|i| u[i]);
            let per_lambda = s.free_stroke + s.preload / s.stiffness;
            let (c, by_extension) = spring(
                st.nodes[s.a],
                st.nodes[s.b],
                s.stiffness,
                per_lambda * lambda,
                &d,
            );
            for (x, &i) in idx.iter().enumerate() {
                r[i] = r[i] + c.force[x];
                q[i] = q[i] - by_extension[x] * per_lambda;
                for (y, &j) in idx.iter().enumerate() {
                    k[i * m + j] = k[i * m + j] + c.stiffness[x][y];
                }
            }
        }
        for &(node, force) in &st.loads {
            for j in 0..3 {
                r[3 * node + j] = r[3 * node + j] - force[j] * lambda;
                q[3 * node + j] = q[3 * node + j] + force[j];
            }
        }
        self.condense(u, &mut k, &mut r, &mut q);
        Full { k, r, q }
    }

    /// Moves the slaves' rows and columns onto their masters (`T^T K T` and `T^T r`).
    fn condense(&self, u: &[D], k: &mut [D], r: &mut [D], q: &mut [D]) {
        let m = u.len();
        let slaves: Vec<(usize, usize, [D; 2])> = (0..self.master.len())
            .filter_map(|p| {
                let b = self.master[p]?;
                Some((p, b, self.offset(p, b, u[3 * b + 2]).1))
            })
            .collect();
        let map = |d: [D; 2], v: [D; 3]| [v[0], v[1], v[2] - d[1] * v[0] + d[0] * v[1]];
        for &(p, b, d) in &slaves {
            for row in 0..m {
                let v = [0, 1, 2].map(|j| k[row * m + 3 * p + j]);
                let t = map(d, v);
                for j in 0..3 {
                    k[row * m + 3 * b + j] = k[row * m + 3 * b + j] + t[j];
                }
            }
        }
        for &(p, b, d) in &slaves {
            for col in 0..m {
                let v = [0, 1, 2].map(|j| k[(3 * p + j) * m + col]);
                let t = map(d, v);
                for j in 0..3 {
                    k[(3 * b + j) * m + col] = k[(3 * b + j) * m + col] + t[j];
                }
            }
            let rp = [0, 1, 2].map(|j| r[3 * p + j]);
            let at = (3 * b + 2) * m + 3 * b + 2;
            k[at] = k[at] - (d[0] * rp[0] + d[1] * rp[1]);
            for vector in [&mut *r, &mut *q] {
                let t = map(d, [0, 1, 2].map(|j| vector[3 * p + j]));
                for j in 0..3 {
                    vector[3 * b + j] = vector[3 * b + j] + t[j];
                }
            }
        }
    }

    /// The residual on the free degrees of freedom at their values `free` and load factor
    /// `lambda`.
    pub fn residual(&self, free: &[D], lambda: f64) -> Vec<D> {
        let full = self.assemble_full(&self.expand(free, lambda), lambda);
        self.free.iter().map(|&i| full.r[i]).collect()
    }

    /// The tangent on the free degrees of freedom at the full displacement `u`, row-major,
    /// with no load: a structure without springs or loads on rigid bodies has it at any
    /// load factor ([`Self::tangent_at`] otherwise).
    pub fn tangent(&self, u: &[D]) -> Vec<D> {
        self.tangent_at(u, 0.0)
    }

    /// The tangent on the free degrees of freedom at the full displacement `u` and load
    /// factor `lambda` (a spring's natural length and a rigid body's loads move it),
    /// row-major.
    pub fn tangent_at(&self, u: &[D], lambda: f64) -> Vec<D> {
        let full = self.assemble_full(u, lambda);
        let (m, f) = (u.len(), &self.free);
        f.iter()
            .flat_map(|&i| f.iter().map(move |&j| (i, j)))
            .map(|(i, j)| full.k[i * m + j])
            .collect()
    }
}

/// The real parts of a point.
fn re2<D: Scalar>(p: [D; 2]) -> [f64; 2] {
    p.map(|v| v.re())
}

impl System<'_> {
    /// Residual, tangent and load vector at the full displacement `u` (from [`Self::expand`]).
    pub fn assemble(&self, u: &[f64], lambda: f64) -> Assembled {
        let Full { k, r, q } = self.assemble_full(u, lambda);
        self.select(&k, &r, &q)
    }

    fn select(&self, k: &[f64], r: &[f64], q: &[f64]) -> Assembled {
        let m = r.len();
        let f = &self.free;
        let tangent = Mat::from_fn(f.len(), f.len(), |i, j| k[f[i] * m + f[j]]);
        let residual = f.iter().map(|&i| r[i]).collect();
        let load = f
            .iter()
            .map(|&i| {
                q[i] - self
                    .held
                    .iter()
                    .map(|&(j, v)| k[i * m + j] * v)
                    .sum::<f64>()
            })
            .collect();
        Assembled {
            residual,
            tangent,
            load,
        }
    }
}
