//! The six-node quadratic triangle (T6) for plane elasticity: isoparametric, so that a node
//! placed on an arc curves the element's edge with it.
//!
//! Nodes: corners 0, 1, 2 counterclockwise, then the midside nodes 3 (of 0-1), 4 (of 1-2) and
//! 5 (of 2-0). With area coordinates `L1 = 1 - xi - eta`, `L2 = xi`, `L3 = eta` the shape
//! functions are `N_i = L_i (2 L_i - 1)` at the corners and `4 L_i L_j` at the midsides
//! (Zienkiewicz, Taylor and Zhu, "The Finite Element Method: Its Basis and Fundamentals",
//! 7th ed., 2013, Sec. 6.4, Eq. 6.30). Integrals use the six-point rule of degree 4 (Dunavant,
//! "High degree efficient symmetrical Gaussian quadrature rules for the triangle", Int. J.
//! Numer. Meth. Eng. 21, 1985, Table I, p = 4), exact for the stiffness (degree 2) and the
//! consistent mass (degree 4) of a straight-sided element. Its edges are quadratic, its
//! CalculiX names CPS6 and CPE6, and its extrusion through the width the 15-node wedge
//! C3D15, in the node order [`Element::EXTRUSION`] gives.

use super::{quadratic_edge_shape, Element, Idealization, QUADRATIC_EDGE_GAUSS};

/// The six-node triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tri6;

/// The six-point rule: `(L1, L2, L3)` and weights summing to one.
const GAUSS: [([f64; 3], f64); 6] = {
    const A: f64 = 0.445_948_490_915_965;
    const B: f64 = 0.108_103_018_168_070;
    const C: f64 = 0.091_576_213_509_771;
    const D: f64 = 0.816_847_572_980_459;
    const WA: f64 = 0.223_381_589_678_011;
    const WC: f64 = 0.109_951_743_655_322;
    [
        ([B, A, A], WA),
        ([A, B, A], WA),
        ([A, A, B], WA),
        ([D, C, C], WC),
        ([C, D, C], WC),
        ([C, C, D], WC),
    ]
};

/// Area coordinates of the six nodes.
const NODE_COORDINATES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
];

/// The shape functions at area coordinates `l`.
fn shape(l: [f64; 3]) -> [f64; 6] {
    [
        l[0] * (2.0 * l[0] - 1.0),
        l[1] * (2.0 * l[1] - 1.0),
        l[2] * (2.0 * l[2] - 1.0),
        4.0 * l[0] * l[1],
        4.0 * l[1] * l[2],
        4.0 * l[2] * l[0],
    ]
}

/// The derivatives of the shape functions with respect to `xi` and `eta` at `l`.
fn shape_derivatives(l: [f64; 3]) -> [[f64; 6]; 2] {
    let [l1, l2, l3] = l;
    // d/dxi: dL1 = -1, dL2 = 1; d/deta: dL1 = -1, dL3 = 1
    [
        [
            -(4.0 * l1 - 1.0),
            4.0 * l2 - 1.0,
            0.0,
            4.0 * (l1 - l2),
            4.0 * l3,
            -4.0 * l3,
        ],
        [
            -(4.0 * l1 - 1.0),
            0.0,
            4.0 * l3 - 1.0,
            -4.0 * l2,
            4.0 * l2,
            4.0 * (l1 - l3),
        ],
    ]
}

/// The map of an element at `l`: the derivatives of the shape functions with respect to x
/// and y, and the Jacobian's determinant; `None` where the element is inverted.
fn gradients(x: &[[f64; 2]; 6], l: [f64; 3]) -> Option<([[f64; 6]; 2], f64)> {
    let d = shape_derivatives(l);
    let mut j = [[0.0; 2]; 2];
    for (k, p) in x.iter().enumerate() {
        for r in 0..2 {
            j[r][0] += d[r][k] * p[0];
            j[r][1] += d[r][k] * p[1];
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det <= 0.0 || !det.is_finite() {
        return None;
    }
    // [d/dx; d/dy] = J^-1 [d/dxi; d/deta]
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut g = [[0.0; 6]; 2];
    for k in 0..6 {
        g[0][k] = inv[0][0] * d[0][k] + inv[0][1] * d[1][k];
        g[1][k] = inv[1][0] * d[0][k] + inv[1][1] * d[1][k];
    }
    Some((g, det))
}

/// The element's stiffness matrix (12 x 12, degrees of freedom `(u0, v0, u1, v1, ...)`) for
/// the constitutive matrix `d` and the out-of-plane width `width`; `None` for an inverted
/// element.
fn stiffness(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], width: f64) -> Option<[[f64; 12]; 12]> {
    let mut k = [[0.0; 12]; 12];
    for (l, w) in GAUSS {
        let (g, det) = gradients(x, l)?;
        let f = w * 0.5 * det * width;
        // D B column by column: B's column 2a is (dNa/dx, 0, dNa/dy), 2a+1 is (0, dNa/dy, dNa/dx)
        let mut db = [[0.0; 12]; 3];
        for a in 0..6 {
            let (gx, gy) = (g[0][a], g[1][a]);
            for r in 0..3 {
                db[r][2 * a] = d[r][0] * gx + d[r][2] * gy;
                db[r][2 * a + 1] = d[r][1] * gy + d[r][2] * gx;
            }
        }
        for a in 0..6 {
            let (gx, gy) = (g[0][a], g[1][a]);
            for c in 0..12 {
                k[2 * a][c] += f * (gx * db[0][c] + gy * db[2][c]);
                k[2 * a + 1][c] += f * (gy * db[1][c] + gx * db[2][c]);
            }
        }
    }
    Some(k)
}

/// The element's consistent mass matrix per direction (6 x 6; the same for u and v) for
/// density `rho` and width `width`.
fn mass(x: &[[f64; 2]; 6], rho: f64, width: f64) -> Option<[[f64; 6]; 6]> {
    let mut m = [[0.0; 6]; 6];
    for (l, w) in GAUSS {
        let (_, det) = gradients(x, l)?;
        let n = shape(l);
        let f = w * 0.5 * det * rho * width;
        for a in 0..6 {
            for b in 0..6 {
                m[a][b] += f * n[a] * n[b];
            }
        }
    }
    Some(m)
}

/// The stresses `(xx, yy, xy)` at area coordinates `l` of an element with nodal
/// displacements `u` (12 values).
fn stress(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], u: &[f64; 12], l: [f64; 3]) -> [f64; 3] {
    let Some((g, _)) = gradients(x, l) else {
        return [f64::NAN; 3];
    };
    let mut e = [0.0; 3];
    for a in 0..6 {
        e[0] += g[0][a] * u[2 * a];
        e[1] += g[1][a] * u[2 * a + 1];
        e[2] += g[1][a] * u[2 * a] + g[0][a] * u[2 * a + 1];
    }
    [
        d[0][0] * e[0] + d[0][1] * e[1] + d[0][2] * e[2],
        d[1][0] * e[0] + d[1][1] * e[1] + d[1][2] * e[2],
        d[2][0] * e[0] + d[2][1] * e[1] + d[2][2] * e[2],
    ]
}

/// The area coordinates of the point `p` in the element, by Newton's method on the
/// isoparametric map from the straight triangle's guess; `None` if it does not converge.
fn locate(x: &[[f64; 2]; 6], p: [f64; 2]) -> Option<[f64; 3]> {
    // the straight triangle's barycentric coordinates as the first guess
    let (a, b, c) = (x[0], x[1], x[2]);
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let mut xi = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    let mut eta = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    for _ in 0..20 {
        let l = [1.0 - xi - eta, xi, eta];
        let q = Tri6::point(x, l);
        let r = [p[0] - q[0], p[1] - q[1]];
        let d = shape_derivatives(l);
        let mut j = [[0.0; 2]; 2];
        for (k, pk) in x.iter().enumerate() {
            for s in 0..2 {
                j[0][s] += d[s][k] * pk[0];
                j[1][s] += d[s][k] * pk[1];
            }
        }
        let dj = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let dxi = (j[1][1] * r[0] - j[0][1] * r[1]) / dj;
        let deta = (-j[1][0] * r[0] + j[0][0] * r[1]) / dj;
        xi += dxi;
        eta += deta;
        // the coordinates carry the rounding of the absolute positions (a part a few cm
        // across, elements a tenth of a mm): 1e-11 is at that level
        if dxi.abs() + deta.abs() < 1e-11 {
            return Some([1.0 - xi - eta, xi, eta]);
        }
    }
    None
}

impl Element for Tri6 {
    const NODES: usize = 6;
    const EDGE_NODES: usize = 3;
    type PerNode<T: super::Item> = [T; 6];
    type PerDof<T: super::Item> = [T; 12];
    type PerEdge<T: super::Item> = [T; 3];
    type Reference = [f64; 3];
    const REFERENCE_AREA: f64 = 0.5;
    const CENTRE: [f64; 3] = [1.0 / 3.0; 3];
    const SIDES: &'static [(usize, usize)] = &[(0, 1), (1, 2), (2, 0)];
    const CALCULIX_EXTRUDED: &'static str = "C3D15";
    // corners of the bottom, of the top, midsides of the bottom, of the top, and the
    // corners again on the middle plane
    const EXTRUSION: &'static [(usize, usize)] = &[
        (0, 0),
        (0, 1),
        (0, 2),
        (2, 0),
        (2, 1),
        (2, 2),
        (0, 3),
        (0, 4),
        (0, 5),
        (2, 3),
        (2, 4),
        (2, 5),
        (1, 0),
        (1, 1),
        (1, 2),
    ];
    // the wedge's faces 3, 4, 5 stand on the triangle's sides 1-2, 2-3, 3-1
    const EXTRUDED_FACES: &'static [usize] = &[3, 4, 5];

    fn node_coordinates() -> [[f64; 3]; 6] {
        NODE_COORDINATES
    }

    fn quadrature() -> &'static [([f64; 3], f64)] {
        &GAUSS
    }

    fn shape(l: [f64; 3]) -> [f64; 6] {
        shape(l)
    }

    fn gradients(x: &[[f64; 2]; 6], l: [f64; 3]) -> Option<([[f64; 6]; 2], f64)> {
        gradients(x, l)
    }

    fn stiffness(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], width: f64) -> Option<[[f64; 12]; 12]> {
        stiffness(x, d, width)
    }

    fn mass(x: &[[f64; 2]; 6], rho: f64, width: f64) -> Option<[[f64; 6]; 6]> {
        mass(x, rho, width)
    }

    fn stress(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], u: &[f64; 12], l: [f64; 3]) -> [f64; 3] {
        stress(x, d, u, l)
    }

    fn locate(x: &[[f64; 2]; 6], p: [f64; 2]) -> Option<[f64; 3]> {
        locate(x, p)
    }

    fn contains(l: [f64; 3], tol: f64) -> bool {
        l.iter().all(|&v| v >= -tol)
    }

    fn mirror_order() -> [usize; 6] {
        [0, 2, 1, 5, 4, 3]
    }

    fn edge_shape(s: f64) -> ([f64; 3], [f64; 3]) {
        quadratic_edge_shape(s)
    }

    fn edge_quadrature() -> &'static [(f64, f64)] {
        &QUADRATIC_EDGE_GAUSS
    }

    fn calculix_name(idealization: Idealization) -> &'static str {
        match idealization {
            Idealization::PlaneStress => "CPS6",
            Idealization::PlaneStrain => "CPE6",
        }
    }
}
