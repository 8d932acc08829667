//! The quarter bridge solved as a small linear elastic system, as a check on the closed
//! form of [`super::bridge`].
//!
//! The quarter is a serial chain clamped to the input link at node 2: hinge b, the rigid
//! middle link, hinge d, ending at node 5 on the output link. Each hinge's 3x3 compliance
//! in its own frame, `diag(c11, [[c22, c23], [c23, c33]])`, is carried to node 5 and to the
//! global axes by the adjoint map `T` (rotation by the hinge angle, then the lever arm
//! from the hinge's free end to node 5) and summed: `C = sum T C_local T^T`. The output
//! link does not rotate relative to the input link, so the moment at node 5 is the
//! reaction that makes the rotation zero, and the 2x2 translational compliance is the
//! Schur complement `K = C_ff - C_fm C_mm^-1 C_mf`.
//!
//! Nothing here comes from the paper's Eq. 3-9: only the hinge compliances (Eq. 2) and
//! plane statics. The paper's coefficients relate to `K` by `[a11 a12; a21 a22] =
//! diag(1, -1) K`, which is the sign convention stated in [`crate::model::bridge`].

use nalgebra::{Matrix2, Matrix3, Vector2};

use crate::model::bridge::Geometry;
use crate::model::hinge::Compliance;
use crate::model::material::Material;

/// `[[a11, a12], [a21, a22]]` of the quarter, solved as a linear elastic system.
pub fn coefficients(g: &Geometry<f64>, width: f64, material: &Material) -> Matrix2<f64> {
    let b = g.b.compliance(width, material);
    let d = g.d.compliance(width, material);
    coefficients_from(g, &b, &d)
}

/// As [`coefficients`], for given hinge compliances.
pub fn coefficients_from(
    g: &Geometry<f64>,
    b: &Compliance<f64>,
    d: &Compliance<f64>,
) -> Matrix2<f64> {
    coefficients_and_condition(g, b, d).0
}

/// The coefficients and the cancellation factor of the condensation: the largest entry of
/// the translational block `C_ff` over the largest entry of the result. The Schur
/// complement subtracts terms that size from each other, so the result's normwise error is
/// about `eps` times this factor. With a long middle link on a compliant hinge, `C_ff`
/// grows like `c33 l3^2` while the result does not, and this formulation loses digits that
/// the closed form (built on the moments at nodes 3 and 4) keeps.
pub fn coefficients_and_condition(
    g: &Geometry<f64>,
    b: &Compliance<f64>,
    d: &Compliance<f64>,
) -> (Matrix2<f64>, f64) {
    let nodes = g.nodes().map(|[x, y]| Vector2::new(x, y));
    let node5 = nodes[3];
    let mut c = Matrix3::zeros();
    for (h, angle, free_end) in [(b, g.delta2, nodes[1]), (d, g.delta4, node5)] {
        let local = Matrix3::new(h.c11, 0.0, 0.0, 0.0, h.c22, h.c23, 0.0, h.c23, h.c33);
        let arm = node5 - free_end;
        let (s, co) = angle.sin_cos();
        // local (u, v, theta) at the hinge's free end -> (dx, dy, theta) at node 5
        let t = Matrix3::new(co, -s, -arm.y, s, co, arm.x, 0.0, 0.0, 1.0);
        c += t * local * t.transpose();
    }
    let cff = c.fixed_view::<2, 2>(0, 0).into_owned();
    let cfm = c.fixed_view::<2, 1>(0, 2).into_owned();
    let k = cff - cfm * cfm.transpose() / c[(2, 2)];
    let condition = cff.amax() / k.amax();
    (
        Matrix2::new(k[(0, 0)], k[(0, 1)], -k[(1, 0)], -k[(1, 1)]),
        condition,
    )
}
