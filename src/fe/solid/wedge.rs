//! The fifteen-node wedge (CalculiX's C3D15): the six-node triangle extruded through the
//! width with quadratic variation along it, isoparametric, three degrees of freedom a node.
//!
//! Reference coordinates: the triangle's `xi, eta` (area coordinates `L1 = 1 - xi - eta`,
//! `L2 = xi`, `L3 = eta`) and `zeta` in [-1, 1] through the width. Nodes in CalculiX's order:
//! corners 0-2 at `zeta = -1`, 3-5 at `zeta = +1`, midsides of the bottom triangle 6-8 (of
//! 0-1, 1-2, 2-0), of the top 9-11, and the midsides of the vertical edges 12-14. The
//! shape functions (Zienkiewicz, Taylor and Zhu, "The Finite Element Method: Its Basis and
//! Fundamentals", 7th ed., 2013, Sec. 6.7; the serendipity wedge):
//!
//! - bottom corner `i`: `L_i (1 - zeta) (2 L_i - 2 - zeta) / 2`, top corner:
//!   `L_i (1 + zeta) (2 L_i - 2 + zeta) / 2`;
//! - bottom midside of `i-j`: `2 L_i L_j (1 - zeta)`, top: `2 L_i L_j (1 + zeta)`;
//! - vertical midside at `i`: `L_i (1 - zeta^2)`.
//!
//! The stiffness is integrated with CalculiX's own rule for this element (the three-point
//! triangle rule at `(1/6, 1/6)`, `(2/3, 1/6)`, `(1/6, 2/3)` times three Gauss points through
//! the width: nine points), so that the two programs compute the same matrix on the same
//! mesh, and it is exact for an element with straight sides (its integrand is of degree two
//! in the triangle, four through the width).

/// Nodes of one element.
pub const NODES: usize = 15;
/// Degrees of freedom of one element.
pub const DOFS: usize = 3 * NODES;

/// The midside nodes of the triangle: the corners each joins.
const MIDSIDES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// A point of the reference element: area coordinates and `zeta`.
pub type Reference = ([f64; 3], f64);

/// The nine-point rule: points and weights summing to one.
fn quadrature() -> [(Reference, f64); 9] {
    let a = 1.0 / 6.0;
    let b = 2.0 / 3.0;
    let tri = [[b, a, a], [a, b, a], [a, a, b]];
    let g = (0.6f64).sqrt();
    let line = [(-g, 5.0 / 18.0), (0.0, 8.0 / 18.0), (g, 5.0 / 18.0)];
    let mut rule = [(([0.0; 3], 0.0), 0.0); 9];
    for (i, &(z, wz)) in line.iter().enumerate() {
        for (j, &l) in tri.iter().enumerate() {
            rule[3 * i + j] = ((l, z), wz / 3.0);
        }
    }
    rule
}

/// The reference element's volume: the triangle's half times the width's two.
const REFERENCE_VOLUME: f64 = 1.0;

/// The reference coordinates of the nodes.
pub fn node_coordinates() -> [Reference; NODES] {
    let corner = |i: usize| {
        let mut l = [0.0; 3];
        l[i] = 1.0;
        l
    };
    let mid = |(i, j): (usize, usize)| {
        let mut l = [0.0; 3];
        l[i] = 0.5;
        l[j] = 0.5;
        l
    };
    std::array::from_fn(|k| match k {
        0..=2 => (corner(k), -1.0),
        3..=5 => (corner(k - 3), 1.0),
        6..=8 => (mid(MIDSIDES[k - 6]), -1.0),
        9..=11 => (mid(MIDSIDES[k - 9]), 1.0),
        _ => (corner(k - 12), 0.0),
    })
}

/// The shape functions at `(l, z)`.
pub fn shape((l, z): Reference) -> [f64; NODES] {
    std::array::from_fn(|k| match k {
        0..=2 => 0.5 * l[k] * (1.0 - z) * (2.0 * l[k] - 2.0 - z),
        3..=5 => 0.5 * l[k - 3] * (1.0 + z) * (2.0 * l[k - 3] - 2.0 + z),
        6..=8 => {
            let (i, j) = MIDSIDES[k - 6];
            2.0 * l[i] * l[j] * (1.0 - z)
        }
        9..=11 => {
            let (i, j) = MIDSIDES[k - 9];
            2.0 * l[i] * l[j] * (1.0 + z)
        }
        _ => l[k - 12] * (1.0 - z * z),
    })
}

/// The derivatives of the shape functions with respect to `xi`, `eta` and `zeta`.
fn shape_derivatives((l, z): Reference) -> [[f64; NODES]; 3] {
    // with respect to L1, L2, L3 (independent) and zeta; then d/dxi = d/dL2 - d/dL1 and
    // d/deta = d/dL3 - d/dL1
    let mut dl = [[0.0; NODES]; 3];
    let mut dz = [0.0; NODES];
    for i in 0..3 {
        dl[i][i] = 0.5 * (1.0 - z) * (4.0 * l[i] - 2.0 - z);
        dz[i] = 0.5 * l[i] * (-2.0 * l[i] + 1.0 + 2.0 * z);
        dl[i][i + 3] = 0.5 * (1.0 + z) * (4.0 * l[i] - 2.0 + z);
        dz[i + 3] = 0.5 * l[i] * (2.0 * l[i] - 1.0 + 2.0 * z);
        dl[i][i + 12] = 1.0 - z * z;
        dz[i + 12] = -2.0 * z * l[i];
    }
    for (m, &(i, j)) in MIDSIDES.iter().enumerate() {
        dl[i][6 + m] = 2.0 * l[j] * (1.0 - z);
        dl[j][6 + m] = 2.0 * l[i] * (1.0 - z);
        dz[6 + m] = -2.0 * l[i] * l[j];
        dl[i][9 + m] = 2.0 * l[j] * (1.0 + z);
        dl[j][9 + m] = 2.0 * l[i] * (1.0 + z);
        dz[9 + m] = 2.0 * l[i] * l[j];
    }
    let mut d = [[0.0; NODES]; 3];
    for k in 0..NODES {
        d[0][k] = dl[1][k] - dl[0][k];
        d[1][k] = dl[2][k] - dl[0][k];
        d[2][k] = dz[k];
    }
    d
}

/// The derivatives of the shape functions with respect to x, y and z at `r`, and the
/// Jacobian's determinant; `None` where the element is inverted.
pub fn gradients(x: &[[f64; 3]; NODES], r: Reference) -> Option<([[f64; NODES]; 3], f64)> {
    let d = shape_derivatives(r);
    let mut j = [[0.0; 3]; 3];
    for (k, p) in x.iter().enumerate() {
        for (row, dr) in j.iter_mut().zip(&d) {
            for c in 0..3 {
                row[c] += dr[k] * p[c];
            }
        }
    }
    let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
    if det <= 0.0 || !det.is_finite() {
        return None;
    }
    // J^-1 by cofactors; [d/dx; d/dy; d/dz] = J^-1 [d/dxi; d/deta; d/dzeta]
    let c =
        |r0: usize, c0: usize, r1: usize, c1: usize| j[r0][c0] * j[r1][c1] - j[r0][c1] * j[r1][c0];
    let inv = [
        [
            c(1, 1, 2, 2) / det,
            -c(0, 1, 2, 2) / det,
            c(0, 1, 1, 2) / det,
        ],
        [
            -c(1, 0, 2, 2) / det,
            c(0, 0, 2, 2) / det,
            -c(0, 0, 1, 2) / det,
        ],
        [
            c(1, 0, 2, 1) / det,
            -c(0, 0, 2, 1) / det,
            c(0, 0, 1, 1) / det,
        ],
    ];
    let mut g = [[0.0; NODES]; 3];
    for k in 0..NODES {
        for (gr, ir) in g.iter_mut().zip(&inv) {
            gr[k] = ir[0] * d[0][k] + ir[1] * d[1][k] + ir[2] * d[2][k];
        }
    }
    Some((g, det))
}

/// Lamé's constants `(lambda, mu)` of Young's modulus `e` and Poisson's ratio `nu`.
pub fn lame(e: f64, nu: f64) -> (f64, f64) {
    (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        0.5 * e / (1.0 + nu),
    )
}

/// The stiffness matrix (45 x 45, degrees of freedom `(u0, v0, w0, u1, ...)`) of an
/// isotropic material with Lamé's constants `(lambda, mu)`: `K_ai,bj = integral of lambda
/// dNa/dx_i dNb/dx_j + mu (delta_ij grad Na . grad Nb + dNa/dx_j dNb/dx_i)`, the product
/// `B^T D B` written out; `None` for an inverted element.
pub fn stiffness(
    x: &[[f64; 3]; NODES],
    (lambda, mu): (f64, f64),
) -> Option<Box<[[f64; DOFS]; DOFS]>> {
    let mut k = Box::new([[0.0; DOFS]; DOFS]);
    for (r, w) in quadrature() {
        let (g, det) = gradients(x, r)?;
        let f = w * REFERENCE_VOLUME * det;
        for a in 0..NODES {
            let ga = [g[0][a], g[1][a], g[2][a]];
            for b in 0..NODES {
                let gb = [g[0][b], g[1][b], g[2][b]];
                let dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
                for i in 0..3 {
                    let row = &mut k[3 * a + i];
                    for j in 0..3 {
                        let mut v = lambda * ga[i] * gb[j] + mu * ga[j] * gb[i];
                        if i == j {
                            v += mu * dot;
                        }
                        row[3 * b + j] += f * v;
                    }
                }
            }
        }
    }
    Some(k)
}

/// The stresses `(xx, yy, zz, xy, yz, zx)` at `r` for nodal displacements `u`.
pub fn stress(
    x: &[[f64; 3]; NODES],
    (lambda, mu): (f64, f64),
    u: &[f64; DOFS],
    r: Reference,
) -> [f64; 6] {
    let Some((g, _)) = gradients(x, r) else {
        return [f64::NAN; 6];
    };
    // the displacement gradient h[i][j] = du_i / dx_j
    let mut h = [[0.0; 3]; 3];
    for a in 0..NODES {
        for (i, hi) in h.iter_mut().enumerate() {
            for (j, hij) in hi.iter_mut().enumerate() {
                *hij += u[3 * a + i] * g[j][a];
            }
        }
    }
    let trace = h[0][0] + h[1][1] + h[2][2];
    [
        lambda * trace + 2.0 * mu * h[0][0],
        lambda * trace + 2.0 * mu * h[1][1],
        lambda * trace + 2.0 * mu * h[2][2],
        mu * (h[0][1] + h[1][0]),
        mu * (h[1][2] + h[2][1]),
        mu * (h[2][0] + h[0][2]),
    ]
}

/// The von Mises stress of `s = (xx, yy, zz, xy, yz, zx)`.
pub fn von_mises(s: [f64; 6]) -> f64 {
    let (a, b, c) = (s[0] - s[1], s[1] - s[2], s[2] - s[0]);
    (0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}

/// The reference point on the element's side face standing on the triangle's side `side`
/// (its corners `SIDES[side]`) at `s` in [0, 1] along it and `zeta` through the width.
pub fn on_side(side: (usize, usize), s: f64, zeta: f64) -> Reference {
    let mut l = [0.0; 3];
    l[side.0] = 1.0 - s;
    l[side.1] = s;
    (l, zeta)
}

/// The tangents of the side face standing on `side` at `s` along it and `zeta` through
/// the width: `dx/ds` and `dx/dzeta`.
pub fn side_tangents(
    x: &[[f64; 3]; NODES],
    side: (usize, usize),
    s: f64,
    zeta: f64,
) -> ([f64; 3], [f64; 3]) {
    let d = shape_derivatives(on_side(side, s, zeta));
    // d/dL_k - d/dL_1 for k = 1, 2, 3 is 0, d/dxi, d/deta; along the side L_i falls and
    // L_j rises
    let relative = |k: usize, n: usize| match k {
        0 => 0.0,
        1 => d[0][n],
        _ => d[1][n],
    };
    let (mut ts, mut tz) = ([0.0; 3], [0.0; 3]);
    for (n, p) in x.iter().enumerate() {
        let along = relative(side.1, n) - relative(side.0, n);
        for c in 0..3 {
            ts[c] += along * p[c];
            tz[c] += d[2][n] * p[c];
        }
    }
    (ts, tz)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wedge with a curved side, its nodes at the reference positions mapped by a smooth
    /// map: a general element.
    fn element() -> [[f64; 3]; NODES] {
        let refs = node_coordinates();
        std::array::from_fn(|k| {
            let (z, (xi, eta)) = (refs[k].1, (refs[k].0[1], refs[k].0[2]));
            [
                1.3 * xi + 0.2 * eta + 0.05 * xi * eta,
                0.1 * xi + 0.9 * eta - 0.04 * xi * xi,
                0.7 + 0.4 * z + 0.01 * xi,
            ]
        })
    }

    #[test]
    fn shape_functions_interpolate_their_nodes_and_sum_to_one() {
        let refs = node_coordinates();
        for (k, &r) in refs.iter().enumerate() {
            let n = shape(r);
            for (m, v) in n.iter().enumerate() {
                assert!((v - f64::from(u8::from(k == m))).abs() < 1e-15, "{k} {m}");
            }
        }
        let n = shape(([0.2, 0.3, 0.5], 0.37));
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn derivatives_match_central_differences() {
        let (l, z) = ([0.2, 0.3, 0.5], 0.37);
        let d = shape_derivatives((l, z));
        let h = 1e-6;
        let moved = |dxi: f64, deta: f64, dz: f64| {
            shape(([l[0] - dxi - deta, l[1] + dxi, l[2] + deta], z + dz))
        };
        for k in 0..NODES {
            let fd = [
                (moved(h, 0.0, 0.0)[k] - moved(-h, 0.0, 0.0)[k]) / (2.0 * h),
                (moved(0.0, h, 0.0)[k] - moved(0.0, -h, 0.0)[k]) / (2.0 * h),
                (moved(0.0, 0.0, h)[k] - moved(0.0, 0.0, -h)[k]) / (2.0 * h),
            ];
            for (c, (dc, f)) in d.iter().zip(fd).enumerate() {
                assert!((dc[k] - f).abs() < 1e-9, "node {k} direction {c}");
            }
        }
    }

    #[test]
    fn a_linear_field_gives_its_constant_stress_and_rigid_motions_none() {
        let x = element();
        let lame = lame(200e9, 0.3);
        // u = A x with a symmetric A: a uniform strain; with a skew A: a rotation
        let strain = [
            [1e-3, 2e-4, -3e-4],
            [2e-4, -5e-4, 1e-4],
            [-3e-4, 1e-4, 7e-4],
        ];
        let field = |a: [[f64; 3]; 3]| -> [f64; DOFS] {
            std::array::from_fn(|d| {
                let p = x[d / 3];
                a[d % 3][0] * p[0] + a[d % 3][1] * p[1] + a[d % 3][2] * p[2]
            })
        };
        let s = stress(&x, lame, &field(strain), ([0.1, 0.6, 0.3], -0.4));
        let (l, m) = lame;
        let tr = strain[0][0] + strain[1][1] + strain[2][2];
        let want = [
            l * tr + 2.0 * m * strain[0][0],
            l * tr + 2.0 * m * strain[1][1],
            l * tr + 2.0 * m * strain[2][2],
            2.0 * m * strain[0][1],
            2.0 * m * strain[1][2],
            2.0 * m * strain[2][0],
        ];
        for c in 0..6 {
            assert!((s[c] - want[c]).abs() < 1e-6 * want[0].abs(), "{c}");
        }
        let k = stiffness(&x, lame).unwrap();
        let rotation = field([[0.0, 1e-3, -2e-3], [-1e-3, 0.0, 5e-4], [2e-3, -5e-4, 0.0]]);
        let scale = k[0][0] * 1e-3;
        for row in k.iter() {
            let f: f64 = row.iter().zip(&rotation).map(|(a, b)| a * b).sum();
            assert!(f.abs() < 1e-9 * scale);
        }
        // symmetric, and the energy of the uniform strain is its volume times 1/2 s:e
        let u = field(strain);
        let mut energy = 0.0;
        for a in 0..DOFS {
            for b in 0..DOFS {
                assert!((k[a][b] - k[b][a]).abs() <= 1e-12 * k[0][0]);
                energy += 0.5 * u[a] * k[a][b] * u[b];
            }
        }
        let volume: f64 = quadrature()
            .iter()
            .map(|&(r, w)| w * gradients(&x, r).unwrap().1)
            .sum();
        let density = 0.5
            * (want[0] * strain[0][0] + want[1] * strain[1][1] + want[2] * strain[2][2])
            + want[3] * strain[0][1]
            + want[4] * strain[1][2]
            + want[5] * strain[2][0];
        assert!((energy - density * volume).abs() < 1e-9 * energy);
    }
}
