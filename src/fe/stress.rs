//! Stresses from a displacement field: nodal values (each node the mean of its elements'),
//! the stress at any point, the peak von Mises stress, and the resultants across a section
//! of a hinge, from which the beam stress `|N| / (w t) + 6 |M| / (w t^2)` that paper 004's
//! Eq. 12-17 predict.

use super::element::{Array, Elastic, Element, Idealization};
use super::mesh::Mesh;

/// The element stresses `(xx, yy, xy)` at the nodes, averaged over the elements that share
/// each node.
pub fn nodal_stresses<E: Element>(mesh: &Mesh<E>, d: &[[f64; 3]; 3], u: &[f64]) -> Vec<[f64; 3]> {
    let mut sum = vec![[0.0; 3]; mesh.nodes.len()];
    let mut count = vec![0u32; mesh.nodes.len()];
    for (e, el) in mesh.elements.iter().enumerate() {
        let x = mesh.element_nodes(e);
        let ue = displacements::<E>(el, u);
        for (k, s) in E::nodal_stresses(&x, d, &ue).as_ref().iter().enumerate() {
            for c in 0..3 {
                sum[el[k]][c] += s[c];
            }
            count[el[k]] += 1;
        }
    }
    sum.iter()
        .zip(&count)
        .map(|(s, &c)| s.map(|v| v / c.max(1) as f64))
        .collect()
}

/// The largest nodal von Mises stress and its node.
pub fn peak_von_mises(
    stresses: &[[f64; 3]],
    material: &Elastic,
    idealization: Idealization,
) -> (f64, usize) {
    stresses
        .iter()
        .enumerate()
        .map(|(i, s)| (material.von_mises(*s, idealization), i))
        .fold((f64::NEG_INFINITY, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// Finds the element that holds a point: a grid of cells over the mesh, each listing the
/// elements whose bounding boxes reach into it.
pub struct Locator {
    origin: [f64; 2],
    cell: f64,
    columns: usize,
    rows: usize,
    cells: Vec<Vec<usize>>,
}

impl Locator {
    pub fn new<E: Element>(mesh: &Mesh<E>) -> Self {
        let mut bb = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &mesh.nodes {
            bb = [
                bb[0].min(p[0]),
                bb[1].min(p[1]),
                bb[2].max(p[0]),
                bb[3].max(p[1]),
            ];
        }
        let (w, h) = (bb[2] - bb[0], bb[3] - bb[1]);
        // about one element a cell
        let cell = ((w * h) / mesh.elements.len().max(1) as f64)
            .sqrt()
            .max(1e-12);
        let columns = ((w / cell).ceil() as usize).max(1);
        let rows = ((h / cell).ceil() as usize).max(1);
        let mut cells = vec![Vec::new(); columns * rows];
        for e in 0..mesh.elements.len() {
            let x = mesh.element_nodes(e);
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for p in x.as_ref() {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            let c =
                |v: f64, o: f64, n: usize| (((v - o) / cell).floor().max(0.0) as usize).min(n - 1);
            for r in c(lo[1], bb[1], rows)..=c(hi[1], bb[1], rows) {
                for col in c(lo[0], bb[0], columns)..=c(hi[0], bb[0], columns) {
                    cells[r * columns + col].push(e);
                }
            }
        }
        Locator {
            origin: [bb[0], bb[1]],
            cell,
            columns,
            rows,
            cells,
        }
    }

    /// The element holding `p` and `p`'s reference coordinates in it.
    pub fn find<E: Element>(&self, mesh: &Mesh<E>, p: [f64; 2]) -> Option<(usize, E::Reference)> {
        let c = |v: f64, o: f64, n: usize| {
            let k = ((v - o) / self.cell).floor();
            (k >= -1.0 && k <= n as f64).then(|| (k.max(0.0) as usize).min(n - 1))
        };
        let col = c(p[0], self.origin[0], self.columns)?;
        let row = c(p[1], self.origin[1], self.rows)?;
        let tol = 1e-9;
        self.cells[row * self.columns + col]
            .iter()
            .filter_map(|&e| {
                let l = E::locate(&mesh.element_nodes(e), p)?;
                E::contains(l, tol).then_some((e, l))
            })
            .next()
    }
}

/// The stress `(xx, yy, xy)` at `p`, if `p` lies in the mesh.
pub fn stress_at<E: Element>(
    mesh: &Mesh<E>,
    locator: &Locator,
    d: &[[f64; 3]; 3],
    u: &[f64],
    p: [f64; 2],
) -> Option<[f64; 3]> {
    let (e, l) = locator.find(mesh, p)?;
    let ue = displacements::<E>(&mesh.elements[e], u);
    Some(E::stress(&mesh.element_nodes(e), d, &ue, l))
}

/// The displacements of an element's degrees of freedom, from the full vector `u`.
fn displacements<E: Element>(el: &E::PerNode<usize>, u: &[f64]) -> E::PerDof<f64> {
    E::PerDof::from_fn(|k| u[2 * el[k / 2] + k % 2])
}

/// The section resultants across a line: the axial force `N` and the bending moment `M`
/// (about the line's middle) of the stress normal to it, per unit width, and the beam
/// stress they give.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    pub axial: f64,
    pub moment: f64,
    /// `|N| / t + 6 |M| / t^2` (Pa): the largest normal stress of a beam section carrying
    /// them.
    pub beam_stress: f64,
}

/// The resultants across the section through `centre` normal to the unit vector `axis` (a
/// hinge's direction), `thickness` wide. The integral is composite Gauss (16 pieces of three
/// points), accurate to the element field's own error.
#[allow(clippy::too_many_arguments)]
pub fn section<E: Element>(
    mesh: &Mesh<E>,
    locator: &Locator,
    d: &[[f64; 3]; 3],
    u: &[f64],
    centre: [f64; 2],
    axis: [f64; 2],
    thickness: f64,
) -> Option<Section> {
    let across = [-axis[1], axis[0]];
    let pieces = 16;
    let h = thickness / pieces as f64;
    let g = [
        (-(0.6f64).sqrt(), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        ((0.6f64).sqrt(), 5.0 / 9.0),
    ];
    let (mut n, mut m) = (0.0, 0.0);
    for k in 0..pieces {
        let mid = -0.5 * thickness + (k as f64 + 0.5) * h;
        for (xi, w) in g {
            let s = mid + 0.5 * h * xi;
            let p = [centre[0] + s * across[0], centre[1] + s * across[1]];
            let st = stress_at(mesh, locator, d, u, p)?;
            // the normal stress on the section: axis^T sigma axis
            let snn = st[0] * axis[0] * axis[0]
                + st[1] * axis[1] * axis[1]
                + 2.0 * st[2] * axis[0] * axis[1];
            n += 0.5 * h * w * snn;
            m += 0.5 * h * w * snn * s;
        }
    }
    Some(Section {
        axial: n,
        moment: m,
        beam_stress: n.abs() / thickness + 6.0 * m.abs() / (thickness * thickness),
    })
}
