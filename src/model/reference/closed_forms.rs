//! The paper's closed forms for the special configurations of the general bridge (paper
//! 004, Sec. 5): the parallel, rhombic and aligned bridges. The tests hold the general
//! quarter model to them in each limit.

use crate::model::hinge::Compliance;
use crate::model::scalar::Scalar;

/// Eq. 23, parallel bridge (`l2 = l4 = l`, `delta2 = delta4 = 0`):
///
/// ```text
/// da = sin d3 (c33 cos d3 l3^2 + 2 c23 l3) / (c33 l3^2 sin^2 d3 + 4 c11)
/// ```
///
/// The extracted text reads `cos^2 d3` in the denominator; the derivation from Eq. 9
/// gives `sin^2 d3`, which is also the only form that tends to the ideal lever
/// `cot d3` for rigid hinges and vanishes for `d3 = 0`.
pub fn parallel<D: Scalar>(h: &Compliance<D>, l3: D, delta3: D) -> D {
    let (s, c) = delta3.sin_cos();
    s * (h.c33 * c * l3 * l3 + h.c23 * l3 * 2.0) / (h.c33 * l3 * l3 * s * s + h.c11 * 4.0)
}

/// Eq. 25, rhombic bridge (`l2 = l3 = delta2 = delta3 = 0`, `l4 = L`, `delta4 = delta`):
///
/// ```text
/// da = -sin(2 d) (2 c11 - c22/2) / (c22 + 4 c11 cos^2 d - c22 cos^2 d)
/// ```
///
/// The paper reaches it with the strip identities `c33 = 3 c22 / L^2` and
/// `c23 = 6 c22 / (4 L)`, which hold for the bending part of `c22` only, so Eq. 25 is
/// exact for a hinge without shear compliance. [`rhombic_general`] is the same limit
/// for any hinge.
pub fn rhombic<D: Scalar>(h: &Compliance<D>, delta: D) -> D {
    let c = delta.cos();
    -(delta * 2.0).sin() * (h.c11 * 2.0 - h.c22 * 0.5)
        / (h.c22 + h.c11 * 4.0 * c * c - h.c22 * c * c)
}

/// The rhombic limit of Eq. 9 before the strip identities are applied:
/// `da = sin(2 d) (k - c11) / (2 (k sin^2 d + c11 cos^2 d))` with `k = c22 - c23^2/c33`.
pub fn rhombic_general<D: Scalar>(h: &Compliance<D>, delta: D) -> D {
    let (s, c) = delta.sin_cos();
    let k = h.c22 - h.c23 * h.c23 / h.c33;
    (delta * 2.0).sin() * (k - h.c11) / ((k * s * s + h.c11 * c * c) * 2.0)
}

/// Eq. 27, aligned bridge (`delta2 = delta3 = delta4 = delta`, `l2 = l4 = l`):
///
/// ```text
/// da = sin d cos d (4 c22 - 4 c11 + 2 c23 l3 + 2 c32 l3 + c33 l3^2)
///      / (4 c22 sin^2 d + 4 c11 cos^2 d + 2 l3 c23 sin^2 d + 2 l3 c32 sin^2 d + l3^2 c33 sin^2 d)
/// ```
pub fn aligned<D: Scalar>(h: &Compliance<D>, l3: D, delta: D) -> D {
    let (s, c) = delta.sin_cos();
    let (s2, c2) = (s * s, c * c);
    s * c * (h.c22 * 4.0 - h.c11 * 4.0 + h.c23 * l3 * 4.0 + h.c33 * l3 * l3)
        / (h.c22 * 4.0 * s2 + h.c11 * 4.0 * c2 + l3 * h.c23 * 4.0 * s2 + l3 * l3 * h.c33 * s2)
}
