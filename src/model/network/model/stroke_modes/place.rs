//! One family of modes at the equilibrium at stroke: where each of its bodies stands, the
//! condensed tangent carried onto the bodies' images, their masses where they stand, and the
//! motions the family's holds leave them, each over the scalar of the design (a dual number
//! carries the derivatives of all of it by the design).

use nalgebra::{Matrix3, SymmetricEigen};

use super::super::stroke::Built;
use super::super::Family;
use crate::model::large::Dof;
use crate::model::network::modes::{DirectedMass, Inertia};
use crate::model::network::structure::{Body, Dof as NetDof, Network};
use crate::model::scalar::Scalar;

/// A `3 x 3` matrix in the scalar, by rows.
type M3<D> = [[D; 3]; 3];

/// The rows `[u, v, theta]` of a hold of `dof` at a point `r` from the body's master.
fn hold_row<D: Scalar>(dof: NetDof, r: [D; 2]) -> [D; 3] {
    let (zero, one) = (D::from(0.0), D::from(1.0));
    match dof {
        NetDof::X => [one, zero, -r[1]],
        NetDof::Y => [zero, one, r[0]],
        NetDof::Rotation => [zero, zero, one],
    }
}

/// The rigid transfer `[u_p, v_p, theta] = T [u, v, theta]` to a point `r` from the master.
fn transfer<D: Scalar>(r: [D; 2]) -> M3<D> {
    let (zero, one) = (D::from(0.0), D::from(1.0));
    [[one, zero, -r[1]], [zero, one, r[0]], [zero, zero, one]]
}

fn dot<D: Scalar>(a: [D; 3], b: [D; 3]) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// An orthonormal basis (real) of the motions of a body that its hold rows leave free: the
/// eigenvectors of `G^T G` of no eigenvalue, `3` columns at most.
fn free_motions(rows: &[[f64; 3]]) -> Vec<[f64; 3]> {
    if rows.is_empty() {
        return vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let g = Matrix3::from_fn(|i, j| rows.iter().map(|r| r[i] * r[j]).sum::<f64>());
    let eigen = SymmetricEigen::new(g);
    let scale = eigen.eigenvalues.amax().max(f64::MIN_POSITIVE);
    (0..3)
        .filter(|&i| eigen.eigenvalues[i] <= 1e-12 * scale)
        .map(|i| {
            let c = eigen.eigenvectors.column(i);
            [c[0], c[1], c[2]]
        })
        .collect()
}

/// The free motions of a body held by `rows` (in the scalar): the real basis of their real
/// parts ([`free_motions`]) projected on the motions the rows leave, `(I - E E^T) t` with `E`
/// the rows orthonormalized (Gram-Schmidt, a row dependent on those before it in its real
/// part left out). The real parts are the real basis; the derivatives keep each column free
/// of the rows as they move (the eigenvalues depend on the subspace alone, not its basis).
fn projected_free_motions<D: Scalar>(rows: &[[D; 3]]) -> Vec<[D; 3]> {
    let real: Vec<[f64; 3]> = rows.iter().map(|r| r.map(|v| v.re())).collect();
    let mut e: Vec<[D; 3]> = Vec::new();
    for r in rows {
        let size = dot(*r, *r).sqrt();
        let mut v = *r;
        for b in &e {
            let d = dot(v, *b);
            v = [0, 1, 2].map(|j| v[j] - d * b[j]);
        }
        let norm = dot(v, v).sqrt();
        if norm.re() > 1e-9 * size.re() {
            e.push(v.map(|x| x / norm));
        }
    }
    free_motions(&real)
        .into_iter()
        .map(|c| {
            let mut v = c.map(D::from);
            for b in &e {
                let d = dot(v, *b);
                v = [0, 1, 2].map(|j| v[j] - d * b[j]);
            }
            v
        })
        .collect()
}

/// Where each body of the family stands at the equilibrium: the described body it is, and
/// whether it is its image across the line `y = 0` (`Some(true)`) or `x = 0`.
pub(super) struct Placement<'a, D> {
    built: &'a Built<D>,
    u: &'a [D],
    /// Each body of the family: the described body, and whether it is its image.
    pub(super) source: Vec<(usize, bool)>,
    flip_y: Option<bool>,
}

impl<'a, D: Scalar> Placement<'a, D> {
    /// The family `f`'s bodies on the structure `built` moved by `u`: the described ones,
    /// then their images where the family is unfolded.
    pub(super) fn new(built: &'a Built<D>, u: &'a [D], f: &Family<D>) -> Self {
        let nb = built.masters.len();
        let mut source: Vec<(usize, bool)> = (0..nb).map(|b| (b, false)).collect();
        for (b, im) in f.images.iter().enumerate() {
            if let Body::Rigid(i) = *im {
                if i != b {
                    debug_assert_eq!(i, source.len());
                    source.push((b, true));
                }
            }
        }
        Placement {
            built,
            u,
            source,
            flip_y: f.unfolded,
        }
    }

    fn reflect(&self, p: [D; 2]) -> [D; 2] {
        match self.flip_y {
            Some(true) => [p[0], -p[1]],
            _ => [-p[0], p[1]],
        }
    }

    /// Where the point `p` of body `i` (at its reference) stands at the equilibrium.
    fn moved(&self, i: usize, p: [D; 2]) -> [D; 2] {
        let (b, image) = self.source[i];
        let m = self.built.masters[b];
        let xm = self.built.driven.nodes[m];
        let q = if image { self.reflect(p) } else { p };
        let (s, c) = self.u[3 * m + 2].sin_cos();
        let r = [q[0] - xm[0], q[1] - xm[1]];
        let at = [
            xm[0] + self.u[3 * m] + c * r[0] - s * r[1],
            xm[1] + self.u[3 * m + 1] + s * r[0] + c * r[1],
        ];
        if image {
            self.reflect(at)
        } else {
            at
        }
    }

    /// Each body's master point at the equilibrium, where its motions are measured.
    pub(super) fn masters(&self) -> Vec<[D; 2]> {
        (0..self.source.len())
            .map(|i| {
                let (b, image) = self.source[i];
                let xm = self.built.driven.nodes[self.built.masters[b]];
                self.moved(i, if image { self.reflect(xm) } else { xm })
            })
            .collect()
    }

    /// The condensed tangent `k` (row-major, `3` rows a described body) on the family's
    /// bodies: the described part's, and on a part unfolded its image's, `S K S` (the
    /// reflection's signs) carried to each image's master. Row-major, `3` rows a body.
    // the congruence's four indices run over three small matrices at once
    #[allow(clippy::needless_range_loop)]
    pub(super) fn unfold(&self, f: &Family<D>, k: &[D], masters: &[[D; 2]]) -> Vec<D> {
        let (nb, n) = (self.built.masters.len(), self.source.len());
        let (kn, size) = (3 * nb, 3 * n);
        let mut out = vec![D::from(0.0); size * size];
        for r in 0..kn {
            out[r * size..r * size + kn].copy_from_slice(&k[r * kn..(r + 1) * kn]);
        }
        let Some(flip_y) = f.unfolded else {
            return out;
        };
        let signs = if flip_y {
            [1.0, -1.0, -1.0]
        } else {
            [-1.0, 1.0, -1.0]
        };
        // each described body's image and the map from its motions to the image copy's
        let maps: Vec<Option<(usize, M3<D>)>> = (0..nb)
            .map(|b| match f.images[b] {
                Body::Ground => None,
                Body::Rigid(i) => {
                    let at = self.reflect(masters[b]);
                    let t = transfer([at[0] - masters[i][0], at[1] - masters[i][1]]);
                    Some((i, std::array::from_fn(|a| t[a].map(|v| v * signs[a]))))
                }
            })
            .collect();
        for (b, mb) in maps.iter().enumerate() {
            for (c, mc) in maps.iter().enumerate() {
                let (Some((i, ti)), Some((j, tj))) = (mb, mc) else {
                    continue;
                };
                // ti^T block tj into the images' block
                for p in 0..3 {
                    for q in 0..3 {
                        let mut sum = D::from(0.0);
                        for a in 0..3 {
                            for e in 0..3 {
                                let block = k[(3 * b + a) * kn + 3 * c + e];
                                sum = sum + ti[a][p] * block * tj[e][q];
                            }
                        }
                        let at = (3 * i + p) * size + 3 * j + q;
                        out[at] = out[at] + sum;
                    }
                }
            }
        }
        out
    }

    /// The family's mass matrix on its bodies' masters (row-major, `3` rows a body): the
    /// linear model's masses ([`Network::mass_matrix_with`]), each carried with its body to
    /// where it stands.
    pub(super) fn mass(&self, f: &Family<D>, masters: &[[D; 2]]) -> Vec<D> {
        let inertia: Vec<Inertia<D>> = (f.inertia.iter().enumerate())
            .map(|(i, m)| Inertia {
                centroid: self.moved(i, m.centroid),
                ..*m
            })
            .collect();
        let directed: Vec<DirectedMass<D>> = (f.directed.iter())
            .map(|d| DirectedMass {
                point: self.moved(d.body, d.point),
                ..*d
            })
            .collect();
        let at = Network {
            references: masters.to_vec(),
            flexures: Vec::new(),
            springs: Vec::new(),
            held: Vec::new(),
            guides: Vec::new(),
        };
        at.mass_matrix_with(&inertia, &directed)
    }

    /// The motions the family's holds leave, as columns of `3` rows a body: each body's
    /// free motions at its master ([`projected_free_motions`]). The family's holds at their
    /// points as they stand; a stack without a stiffness holds its input (and the input's
    /// image) along the stack where it is stretched.
    pub(super) fn free_basis(&self, f: &Family<D>, masters: &[[D; 2]]) -> Vec<Vec<D>> {
        let n = masters.len();
        let mut rows: Vec<Vec<[D; 3]>> = vec![Vec::new(); n];
        for &(i, dof) in &f.network.held {
            let p = self.moved(i, f.network.references[i]);
            rows[i].push(hold_row(dof, [p[0] - masters[i][0], p[1] - masters[i][1]]));
        }
        let built = self.built;
        let input = built.ports[0].node;
        let driven = built
            .driven
            .held
            .iter()
            .filter(|h| h.0 == input && h.2.re() != 0.0);
        for &(_, dof, _) in driven.filter(|_| f.stretched) {
            let dof = match dof {
                Dof::X => NetDof::X,
                Dof::Y => NetDof::Y,
                Dof::Rotation => NetDof::Rotation,
            };
            let b = built.masters.iter().position(|&m| m == input);
            let image = b.and_then(|b| match f.images.get(b) {
                Some(&Body::Rigid(i)) => Some(i),
                _ => None,
            });
            for i in b.into_iter().chain(image) {
                rows[i].push(hold_row(dof, [D::from(0.0); 2]));
            }
        }
        let mut columns = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            for c in projected_free_motions(r) {
                let mut column = vec![D::from(0.0); 3 * n];
                column[3 * i..3 * i + 3].copy_from_slice(&c);
                columns.push(column);
            }
        }
        columns
    }
}
