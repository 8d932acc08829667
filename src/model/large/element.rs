//! The corotational beam element and the spring, each giving its internal force and
//! tangent stiffness in the global degrees of freedom of its two nodes,
//! `(u_a, v_a, theta_a, u_b, v_b, theta_b)`.
//!
//! The beam follows Crisfield's co-rotational planar beam (see the end of this paragraph):
//! the chord's current length `l` and angle `beta` give the local axial
//! displacement `u_l = l - l0` and the local end rotations `theta_i - (beta - beta0)`;
//! the local forces are the Euler-Bernoulli beam's with the shallow-arch axial strain
//! (Crisfield's local law, [`local_law`], which gives the straight beam the consistent
//! cubic geometric stiffness and so Euler's load converging as the fourth power of the
//! element length); the global internal force is `B^T (N, M_a, M_b)` with `B` the derivative of the local
//! displacements, and the tangent stiffness
//! `K_t = B^T D B + (N / l) z z^T + (M_a + M_b) / l^2 (r z^T + z r^T)`
//! with `r = (-c, -s, 0, c, s, 0)` and `z = (s, -c, 0, -s, c, 0)`, `c, s` the cosine and
//! sine of `beta` (Crisfield 1991, vol. 1, ch. 7, the co-rotational planar beam, in this
//! notation; Battini and Pacoste, Comput. Methods Appl. Mech. Engrg. 191 (2002) 1755-1789,
//! write the same element in three dimensions).

use super::LocalOf;
use crate::model::scalar::{atan2, Scalar};

/// The internal force and tangent stiffness of an element.
pub struct Contribution<D, const N: usize> {
    pub force: [D; N],
    pub stiffness: [[D; N]; N],
}

/// `sqrt(x^2 + y^2)`.
fn hypot<D: Scalar>(x: D, y: D) -> D {
    (x * x + y * y).sqrt()
}

/// The distance from `xa` to `xb`: an element's reference length.
pub fn length<D: Scalar>(xa: [D; 2], xb: [D; 2]) -> D {
    hypot(xb[0] - xa[0], xb[1] - xa[1])
}

/// The beam from reference positions `xa, xb` under displacements `d` (6 values), of
/// local linear stiffness `local`. Generic over the scalar so that the derivatives of the
/// internal force by the design (through the positions and the local stiffness) come from
/// the same code as its values ([`crate::model::network`]'s gradients at stroke).
pub fn beam<D: Scalar>(
    xa: [D; 2],
    xb: [D; 2],
    local: LocalOf<D>,
    d: &[D; 6],
) -> Contribution<D, 6> {
    let chord0 = [xb[0] - xa[0], xb[1] - xa[1]];
    let l0 = hypot(chord0[0], chord0[1]);
    // the chord's change apart from the chord, so that a small stretch keeps its digits
    let change = [d[3] - d[0], d[4] - d[1]];
    let chord = [chord0[0] + change[0], chord0[1] + change[1]];
    let l = hypot(chord[0], chord[1]);
    let (c, s) = (chord[0] / l, chord[1] / l);
    let turn = atan2(
        chord0[0] * change[1] - chord0[1] * change[0],
        l0 * l0 + chord0[0] * change[0] + chord0[1] * change[1],
    );
    // l - l0 as (l^2 - l0^2) / (l + l0)
    let stretch = (change[0] * (chord0[0] * 2.0 + change[0])
        + change[1] * (chord0[1] * 2.0 + change[1]))
        / (l + l0);
    let (ta, tb) = (d[2] - turn, d[5] - turn);
    let (local, dmat) = local_law(local, l0, stretch, ta, tb);
    let zero = D::from(0.0);
    let r = [-c, -s, zero, c, s, zero];
    let z = [s, -c, zero, -s, c, zero];
    let mut rows = [r, [zero; 6], [zero; 6]];
    for j in 0..6 {
        rows[1][j] = -z[j] / l;
        rows[2][j] = -z[j] / l;
    }
    rows[1][2] = rows[1][2] + 1.0;
    rows[2][5] = rows[2][5] + 1.0;
    let [n, ma, mb] = local;
    let mut force = [zero; 6];
    let mut stiffness = [[zero; 6]; 6];
    let (n_l, m_l2) = (n / l, (ma + mb) / (l * l));
    for i in 0..6 {
        force[i] = rows[0][i] * local[0] + rows[1][i] * local[1] + rows[2][i] * local[2];
        for j in 0..6 {
            let mut kij = zero;
            for p in 0..3 {
                for q in 0..3 {
                    kij = kij + rows[p][i] * dmat[p][q] * rows[q][j];
                }
            }
            stiffness[i][j] = kij + n_l * z[i] * z[j] + m_l2 * (r[i] * z[j] + z[i] * r[j]);
        }
    }
    Contribution { force, stiffness }
}

/// The local forces `(N, M_a, M_b)` and their derivatives by `(u_l, theta_a, theta_b)` from
/// the energy `k l0^2 eps^2 / 2 + theta^T K_b theta / 2`, `theta = (ta, tb)`, with the
/// shallow-arch strain `eps = u_l / l0 + (2 ta^2 - ta tb + 2 tb^2) / 30` (Crisfield 1991,
/// ch. 7, whose uniform beam has `k = EA / l0` and `K_b = EI / l0 [4 2; 2 4]`). A general
/// `k` and symmetric `K_b` (a segment of a notch's profile, a beam with its shear
/// compliance) keep the element's linear stiffness exactly theirs at the unloaded state;
/// the arch term, the geometric coupling of stretch and end rotations, is the cubic
/// shape's, which the element's shortening makes exact in the limit.
fn local_law<D: Scalar>(
    local: LocalOf<D>,
    l0: D,
    stretch: D,
    ta: D,
    tb: D,
) -> ([D; 3], [[D; 3]; 3]) {
    let eps = stretch / l0 + (ta * ta * 2.0 - ta * tb + tb * tb * 2.0) / 30.0;
    // EA of the uniform beam: N = k l0 eps
    let ea = local.axial * l0;
    let n = ea * eps;
    let g = [l0.recip(), (ta * 4.0 - tb) / 30.0, (tb * 4.0 - ta) / 30.0];
    let kb = local.bending;
    let ma = kb[0][0] * ta + kb[0][1] * tb + n * l0 * g[1];
    let mb = kb[1][0] * ta + kb[1][1] * tb + n * l0 * g[2];
    let zero = D::from(0.0);
    let bend = [
        [zero; 3],
        [zero, kb[0][0], kb[0][1]],
        [zero, kb[1][0], kb[1][1]],
    ];
    let arch = [[0.0; 3], [0.0, 4.0, -1.0], [0.0, -1.0, 4.0]];
    let mut dmat = [[zero; 3]; 3];
    let (eal0, nl0) = (ea * l0, n * l0 / 30.0);
    for p in 0..3 {
        for q in 0..3 {
            dmat[p][q] = eal0 * g[p] * g[q] + bend[p][q] + nl0 * arch[p][q];
        }
    }
    ([n, ma, mb], dmat)
}

/// The spring between reference positions `xa, xb` under translations `d`
/// `(u_a, v_a, u_b, v_b)`, its natural length `l0 + extension`: internal force, tangent
/// stiffness, and the derivative of the internal force by `extension`.
pub fn spring<D: Scalar>(
    xa: [D; 2],
    xb: [D; 2],
    stiffness: D,
    extension: D,
    d: &[D; 4],
) -> (Contribution<D, 4>, [D; 4]) {
    let l0 = length(xa, xb);
    let chord = [xb[0] - xa[0] + d[2] - d[0], xb[1] - xa[1] + d[3] - d[1]];
    let l = hypot(chord[0], chord[1]);
    let e = [chord[0] / l, chord[1] / l];
    let tension = stiffness * (l - l0 - extension);
    let g = [-e[0], -e[1], e[0], e[1]];
    let zero = D::from(0.0);
    let mut k2 = [[zero; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            let delta = if i == j { 1.0 } else { 0.0 };
            k2[i][j] = stiffness * e[i] * e[j] + tension / l * (-(e[i] * e[j]) + delta);
        }
    }
    let mut k = [[zero; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            let sign = if (i < 2) == (j < 2) { 1.0 } else { -1.0 };
            k[i][j] = k2[i % 2][j % 2] * sign;
        }
    }
    let force = g.map(|gi| tension * gi);
    let by_extension = g.map(|gi| -(stiffness * gi));
    (
        Contribution {
            force,
            stiffness: k,
        },
        by_extension,
    )
}
