//! The global system: degrees of freedom with the fixed ones taken out, the sparse
//! stiffness and mass matrices (lower triangle, compressed columns, `faer`), and their
//! factorization by sparse Cholesky, whose symbolic part (ordering and structure) is
//! computed once per mesh and reused by every matrix and load case on it.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Conj, Mat, Par, Side};

use super::element::{Array, Elastic, Element, Idealization};
use super::mesh::Mesh;
use super::FeError;

/// The degrees of freedom of a mesh: two a node, `(u, v)`, numbered `2 n` and `2 n + 1`;
/// the free ones renumbered densely.
#[derive(Debug, Clone)]
pub struct Dofs {
    /// The free index of each degree of freedom, `None` for a fixed one.
    free: Vec<Option<usize>>,
    count: usize,
}

impl Dofs {
    /// `fixed[d]` tells whether degree of freedom `d` is held.
    pub fn new(fixed: &[bool]) -> Self {
        let mut count = 0;
        let free = fixed
            .iter()
            .map(|&f| {
                (!f).then(|| {
                    count += 1;
                    count - 1
                })
            })
            .collect();
        Dofs { free, count }
    }

    /// Number of free degrees of freedom.
    pub fn count(&self) -> usize {
        self.count
    }

    pub fn free(&self, dof: usize) -> Option<usize> {
        self.free[dof]
    }

    /// The full vector (every degree of freedom) of a free one; fixed ones take `fixed`.
    pub fn expand(&self, x: &[f64], fixed: &[f64]) -> Vec<f64> {
        self.free
            .iter()
            .enumerate()
            .map(|(d, f)| f.map_or(fixed[d], |i| x[i]))
            .collect()
    }
}

/// The structure of the global matrices of a mesh and its Cholesky factorization's
/// symbolic part.
///
/// The structure comes from the nodes' adjacency (two nodes are coupled when an element
/// holds both) and the fill-reducing ordering is computed on the nodes, a quarter of the
/// size of the degree-of-freedom graph, then expanded to their degrees of freedom: both
/// measured several times faster than sorting every element entry and ordering the full
/// graph (`docs/performance.md`).
pub struct Pattern {
    pub dofs: Dofs,
    symbolic: SymbolicSparseColMat<usize>,
    llt: SymbolicCholesky<usize>,
}

/// The element degrees of freedom of element `e`.
fn element_dofs<E: Element>(mesh: &Mesh<E>, e: usize) -> E::PerDof<usize> {
    let n = mesh.elements[e];
    E::PerDof::from_fn(|k| 2 * n[k / 2] + k % 2)
}

/// Each node's neighbours (itself included), sorted.
fn adjacency<E: Element>(mesh: &Mesh<E>) -> Vec<Vec<usize>> {
    adjacency_of(mesh.nodes.len(), mesh.elements.iter().map(|el| el.as_ref()))
}

/// Each of `nodes` nodes' neighbours (itself included), sorted, for elements given by
/// their nodes.
pub fn adjacency_of<'a>(
    nodes: usize,
    elements: impl Iterator<Item = &'a [usize]>,
) -> Vec<Vec<usize>> {
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for el in elements {
        for &a in el {
            adj[a].extend_from_slice(el);
        }
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    adj
}

fn solve_error(what: &str, e: impl std::fmt::Debug) -> FeError {
    FeError::Solve(format!("{what}: {e:?}"))
}

impl Pattern {
    /// The pattern of `mesh` with the degrees of freedom `fixed` held.
    pub fn new<E: Element>(mesh: &Mesh<E>, fixed: &[bool]) -> Result<Self, FeError> {
        Self::of_graph(&adjacency(mesh), 2, fixed)
    }

    /// The pattern of a mesh whose nodes are coupled as `adj` says (each node's neighbours,
    /// itself included, sorted), with `per_node` degrees of freedom a node numbered
    /// `per_node * node + k`, the degrees of freedom `fixed` held.
    pub fn of_graph(adj: &[Vec<usize>], per_node: usize, fixed: &[bool]) -> Result<Self, FeError> {
        let dofs = Dofs::new(fixed);
        let n = dofs.count();
        // the lower triangle, column by column: a free degree of freedom's column holds the
        // free ones of its node's neighbours numbered at or after it (the numbering follows
        // the nodes, so sorted neighbours give sorted rows)
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (node, neighbours) in adj.iter().enumerate() {
            for k in 0..per_node {
                let Some(c) = dofs.free(per_node * node + k) else {
                    continue;
                };
                for &m in neighbours {
                    for j in 0..per_node {
                        if let Some(r) = dofs.free(per_node * m + j) {
                            if r >= c {
                                row_idx.push(r);
                            }
                        }
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        // the ordering of the nodes, expanded to their free degrees of freedom
        let nodes = adj.len();
        let mut node_ptr = Vec::with_capacity(nodes + 1);
        let mut node_idx = Vec::new();
        node_ptr.push(0);
        for neighbours in adj {
            node_idx.extend_from_slice(neighbours);
            node_ptr.push(node_idx.len());
        }
        let graph = SymbolicSparseColMat::new_checked(nodes, nodes, node_ptr, None, node_idx);
        let (mut perm, mut perm_inv) = (vec![0usize; nodes], vec![0usize; nodes]);
        let mut mem = MemBuffer::new(amd::order_scratch::<usize>(nodes, graph.compute_nnz()));
        amd::order(
            &mut perm,
            &mut perm_inv,
            graph.as_ref(),
            amd::Control::default(),
            MemStack::new(&mut mem),
        )
        .map_err(|e| solve_error("the ordering failed", e))?;
        let mut fwd = Vec::with_capacity(n);
        for &node in &perm {
            for k in 0..per_node {
                if let Some(d) = dofs.free(per_node * node + k) {
                    fwd.push(d);
                }
            }
        }
        let mut inv = vec![0usize; n];
        for (new, &old) in fwd.iter().enumerate() {
            inv[old] = new;
        }
        let ordering = PermRef::new_checked(&fwd, &inv, n);
        let llt = factorize_symbolic_cholesky(
            symbolic.as_ref(),
            Side::Lower,
            SymmetricOrdering::Custom(ordering),
            Default::default(),
        )
        .map_err(|e| solve_error("the symbolic factorization failed", e))?;
        Ok(Pattern {
            dofs,
            symbolic,
            llt,
        })
    }

    /// The global matrix from element matrices `element(e)` (one row and column a degree of
    /// freedom of the element), plus `diagonal`:
    /// `(degree of freedom, value)` added on the diagonal (springs, point masses); those on
    /// fixed degrees of freedom are dropped.
    fn assemble<E: Element>(
        &self,
        mesh: &Mesh<E>,
        element: impl Fn(usize) -> Result<E::PerDof<E::PerDof<f64>>, FeError>,
        diagonal: &[(usize, f64)],
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        let s = self.symbolic.as_ref();
        let mut values = vec![0.0; s.compute_nnz()];
        for &(dof, v) in diagonal {
            if let Some(c) = self.dofs.free(dof) {
                // the columns hold rows at or below the diagonal, sorted: the diagonal first
                values[s.col_ptr()[c]] += v;
            }
        }
        for e in 0..mesh.elements.len() {
            let k = element(e)?;
            let ed = element_dofs(mesh, e);
            self.scatter(&mut values, ed.as_ref(), |a, b| k[a][b])?;
        }
        Ok(SparseColMat::new(self.symbolic.clone(), values))
    }

    /// Adds an element matrix `k(a, b)` (one row and column a degree of freedom of `dofs`)
    /// into `values`, the entries of a matrix on this pattern; rows and columns of fixed
    /// degrees of freedom are dropped.
    pub fn scatter(
        &self,
        values: &mut [f64],
        dofs: &[usize],
        k: impl Fn(usize, usize) -> f64,
    ) -> Result<(), FeError> {
        let s = self.symbolic.as_ref();
        for (b, &db) in dofs.iter().enumerate() {
            let Some(c) = self.dofs.free(db) else {
                continue;
            };
            let rows = s.row_idx_of_col_raw(c);
            let start = s.col_ptr()[c];
            for (a, &da) in dofs.iter().enumerate() {
                if let Some(r) = self.dofs.free(da).filter(|&r| r >= c) {
                    let at = rows.binary_search(&r).map_err(|_| {
                        FeError::Solve("an entry is missing from the pattern".into())
                    })?;
                    values[start + at] += k(a, b);
                }
            }
        }
        Ok(())
    }

    /// A matrix on this pattern from its entries (as [`Pattern::scatter`] fills them).
    pub fn matrix(&self, values: Vec<f64>) -> SparseColMat<usize, f64> {
        SparseColMat::new(self.symbolic.clone(), values)
    }

    /// The number of entries of a matrix on this pattern (its lower triangle).
    pub fn entries(&self) -> usize {
        self.symbolic.compute_nnz()
    }

    /// The stiffness matrix for `material` and `width` in `idealization`.
    pub fn stiffness<E: Element>(
        &self,
        mesh: &Mesh<E>,
        material: &Elastic,
        width: f64,
        idealization: Idealization,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.stiffness_with(mesh, material, width, idealization, &[])
    }

    /// The stiffness matrix with springs to ground, `(degree of freedom, stiffness)`.
    pub fn stiffness_with<E: Element>(
        &self,
        mesh: &Mesh<E>,
        material: &Elastic,
        width: f64,
        idealization: Idealization,
        springs: &[(usize, f64)],
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.stiffness_scaled(mesh, material, width, idealization, springs, &|_| 1.0)
    }

    /// [`Pattern::stiffness_with`], each element's stiffness times `factor(element)` (to
    /// make parts of a mesh nearly rigid, for a measurement).
    pub fn stiffness_scaled<E: Element>(
        &self,
        mesh: &Mesh<E>,
        material: &Elastic,
        width: f64,
        idealization: Idealization,
        springs: &[(usize, f64)],
        factor: &dyn Fn(usize) -> f64,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        let d = material.d_matrix(idealization);
        self.assemble(
            mesh,
            |e| {
                let f = factor(e);
                element_stiffness(mesh, e, &d, width)
                    .map(|k| E::PerDof::from_fn(|a| E::PerDof::from_fn(|b| f * k[a][b])))
            },
            springs,
        )
    }

    /// The consistent mass matrix for density `material.density` and `width`.
    pub fn mass<E: Element>(
        &self,
        mesh: &Mesh<E>,
        material: &Elastic,
        width: f64,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.mass_with(mesh, material, width, &[])
    }

    /// The mass matrix with point masses, `(degree of freedom, mass)`.
    pub fn mass_with<E: Element>(
        &self,
        mesh: &Mesh<E>,
        material: &Elastic,
        width: f64,
        points: &[(usize, f64)],
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.assemble(
            mesh,
            |e| {
                let m = E::mass(&mesh.element_nodes(e), material.density, width)
                    .ok_or_else(|| inverted(mesh, e))?;
                let mut full = E::PerDof::from_fn(|_| E::PerDof::from_fn(|_| 0.0));
                for a in 0..E::NODES {
                    for b in 0..E::NODES {
                        full[2 * a][2 * b] = m[a][b];
                        full[2 * a + 1][2 * b + 1] = m[a][b];
                    }
                }
                Ok(full)
            },
            points,
        )
    }

    /// `matrix` (built on this pattern) with `diagonal`, `(degree of freedom, value)`,
    /// added on its diagonal (springs to ground; those on fixed degrees of freedom are
    /// dropped).
    pub fn with_diagonal(
        &self,
        matrix: &SparseColMat<usize, f64>,
        diagonal: &[(usize, f64)],
    ) -> SparseColMat<usize, f64> {
        let mut values = matrix.val().to_vec();
        for &(dof, v) in diagonal {
            if let Some(c) = self.dofs.free(dof) {
                values[self.symbolic.col_ptr()[c]] += v;
            }
        }
        SparseColMat::new(self.symbolic.clone(), values)
    }

    /// The largest diagonal entry of `matrix`.
    pub fn largest_diagonal(&self, matrix: &SparseColMat<usize, f64>) -> f64 {
        let values = matrix.val();
        (0..self.dofs.count())
            .map(|c| values[self.symbolic.col_ptr()[c]])
            .fold(0.0, f64::max)
    }

    /// The Cholesky factor of `matrix` (built on this pattern).
    pub fn factor<'a>(&'a self, matrix: &SparseColMat<usize, f64>) -> Result<Factor<'a>, FeError> {
        let mut values = vec![0.0; self.llt.len_val()];
        let par = Par::Seq;
        let mut mem = MemBuffer::new(
            self.llt
                .factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        );
        self.llt
            .factorize_numeric_llt(
                &mut values,
                matrix.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| {
                FeError::Solve(format!(
                    "the stiffness matrix is not positive definite ({e:?}): the part is not held \
                     against every rigid motion"
                ))
            })?;
        Ok(Factor {
            symbolic: &self.llt,
            values,
        })
    }
}

fn inverted<E: Element>(mesh: &Mesh<E>, e: usize) -> FeError {
    let p = mesh.nodes[mesh.elements[e][0]];
    FeError::Mesh(format!(
        "element {e} near ({:.4}, {:.4}) mm is inverted",
        p[0] * 1e3,
        p[1] * 1e3
    ))
}

/// The stiffness matrix of element `e`.
pub fn element_stiffness<E: Element>(
    mesh: &Mesh<E>,
    e: usize,
    d: &[[f64; 3]; 3],
    width: f64,
) -> Result<E::PerDof<E::PerDof<f64>>, FeError> {
    E::stiffness(&mesh.element_nodes(e), d, width).ok_or_else(|| inverted(mesh, e))
}

/// A Cholesky factorization, on the symbolic factorization of its [`Pattern`].
pub struct Factor<'a> {
    symbolic: &'a SymbolicCholesky<usize>,
    values: Vec<f64>,
}

impl Factor<'_> {
    /// Solves for every column of `rhs` (free degrees of freedom) in place.
    pub fn solve(&self, rhs: &mut Mat<f64>) {
        let par = Par::Seq;
        let mut mem = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), par),
        );
        LltRef::<'_, usize, f64>::new(self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
    }
}

/// `y = A x` for a symmetric matrix stored by its lower triangle.
pub fn symmetric_product(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    let a = a.as_ref();
    for j in 0..a.ncols() {
        for (i, v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            y[i] += v * x[j];
            if i != j {
                y[j] += v * x[i];
            }
        }
    }
}

/// The right-hand side of the free degrees of freedom from a full force vector `forces`
/// and the prescribed displacements `prescribed` of the fixed ones: `f_free - K_fc u_c`.
pub fn reduced_rhs<E: Element>(
    mesh: &Mesh<E>,
    dofs: &Dofs,
    material: &Elastic,
    width: f64,
    idealization: Idealization,
    forces: &[f64],
    prescribed: &[f64],
) -> Result<Vec<f64>, FeError> {
    let mut rhs = vec![0.0; dofs.count()];
    for (d, &f) in forces.iter().enumerate() {
        if let Some(i) = dofs.free(d) {
            rhs[i] += f;
        }
    }
    if prescribed.iter().any(|&u| u != 0.0) {
        let dm = material.d_matrix(idealization);
        for e in 0..mesh.elements.len() {
            let ed = element_dofs(mesh, e);
            if !ed
                .as_ref()
                .iter()
                .any(|&d| dofs.free(d).is_none() && prescribed[d] != 0.0)
            {
                continue;
            }
            let k = element_stiffness(mesh, e, &dm, width)?;
            for a in 0..2 * E::NODES {
                let Some(r) = dofs.free(ed[a]) else { continue };
                for b in 0..2 * E::NODES {
                    if dofs.free(ed[b]).is_none() {
                        rhs[r] -= k[a][b] * prescribed[ed[b]];
                    }
                }
            }
        }
    }
    Ok(rhs)
}
