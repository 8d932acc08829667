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
//! consistent mass (degree 4) of a straight-sided element.

/// The 2D idealizations of a plate of width `w` loaded in its plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Idealization {
    /// No stress through the width: a thin plate.
    PlaneStress,
    /// No strain through the width: a wide one (a hinge 25 times wider than thick bends
    /// with `E / (1 - nu^2)`, as this gives).
    PlaneStrain,
}

impl Idealization {
    pub const BOTH: [Idealization; 2] = [Idealization::PlaneStress, Idealization::PlaneStrain];

    pub fn name(self) -> &'static str {
        match self {
            Idealization::PlaneStress => "plane stress",
            Idealization::PlaneStrain => "plane strain",
        }
    }
}

/// An isotropic linear elastic material, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub density: f64,
}

impl Elastic {
    /// The matrix `D` with `sigma = D epsilon`, for `(xx, yy, xy)` and engineering shear
    /// strain.
    pub fn d_matrix(&self, idealization: Idealization) -> [[f64; 3]; 3] {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        match idealization {
            Idealization::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                [
                    [c, c * nu, 0.0],
                    [c * nu, c, 0.0],
                    [0.0, 0.0, c * 0.5 * (1.0 - nu)],
                ]
            }
            Idealization::PlaneStrain => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                [
                    [c * (1.0 - nu), c * nu, 0.0],
                    [c * nu, c * (1.0 - nu), 0.0],
                    [0.0, 0.0, c * 0.5 * (1.0 - 2.0 * nu)],
                ]
            }
        }
    }

    /// The von Mises stress of the in-plane stresses `s = (xx, yy, xy)`: with `zz = 0` in
    /// plane stress and `zz = nu (xx + yy)` in plane strain.
    pub fn von_mises(&self, s: [f64; 3], idealization: Idealization) -> f64 {
        let zz = match idealization {
            Idealization::PlaneStress => 0.0,
            Idealization::PlaneStrain => self.poisson_ratio * (s[0] + s[1]),
        };
        let (a, b, c) = (s[0] - s[1], s[1] - zz, zz - s[0]);
        (0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]).sqrt()
    }
}

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
pub const NODE_COORDINATES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
];

/// The shape functions at area coordinates `l`.
pub fn shape(l: [f64; 3]) -> [f64; 6] {
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
pub fn gradients(x: &[[f64; 2]; 6], l: [f64; 3]) -> Option<([[f64; 6]; 2], f64)> {
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

/// The point of the element at area coordinates `l`.
pub fn point(x: &[[f64; 2]; 6], l: [f64; 3]) -> [f64; 2] {
    let n = shape(l);
    let mut p = [0.0; 2];
    for (ni, xi) in n.iter().zip(x) {
        p[0] += ni * xi[0];
        p[1] += ni * xi[1];
    }
    p
}

/// The element's stiffness matrix (12 x 12, degrees of freedom `(u0, v0, u1, v1, ...)`) for
/// the constitutive matrix `d` and the out-of-plane width `width`; `None` for an inverted
/// element.
pub fn stiffness(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], width: f64) -> Option<[[f64; 12]; 12]> {
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
pub fn mass(x: &[[f64; 2]; 6], rho: f64, width: f64) -> Option<[[f64; 6]; 6]> {
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

/// The element's area (its curved edges included).
pub fn area(x: &[[f64; 2]; 6]) -> f64 {
    GAUSS
        .iter()
        .map(|&(l, w)| gradients(x, l).map_or(0.0, |(_, det)| w * 0.5 * det))
        .sum()
}

/// The stresses `(xx, yy, xy)` at area coordinates `l` of an element with nodal
/// displacements `u` (12 values).
pub fn stress(x: &[[f64; 2]; 6], d: &[[f64; 3]; 3], u: &[f64; 12], l: [f64; 3]) -> [f64; 3] {
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
pub fn locate(x: &[[f64; 2]; 6], p: [f64; 2]) -> Option<[f64; 3]> {
    // the straight triangle's barycentric coordinates as the first guess
    let (a, b, c) = (x[0], x[1], x[2]);
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let mut xi = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    let mut eta = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    for _ in 0..20 {
        let l = [1.0 - xi - eta, xi, eta];
        let q = point(x, l);
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
