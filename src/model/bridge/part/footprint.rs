//! The bridge part's footprint as outputs of the design (issue 51): the outline's width
//! along the actuator (x) and its height along the output (y), and the length of the pocket
//! between the faces the actuator pushes, each a function of the design over [`Scalar`], so
//! that "fits in 60 x 40 mm" and "holds an 18 mm stack" are constraints with exact
//! gradients.
//!
//! The outline is the union of the solids [`super::spec`] places, which
//! [`super::pieces`] states over [`Scalar`] as convex pieces; the fillets at the hinges'
//! roots are concave and lie inside the pieces' hull, so the outline's bounding box is the
//! pieces' vertices' box. The part is symmetric about both axes: the width is twice the
//! largest x of a vertex, the height twice the largest y. Each is a maximum over vertices,
//! continuous, with the gradient of the vertex that attains it.

use super::pieces::{pieces, SOLID_PIECES};
use super::PartSettings;
use crate::model::bridge::{Geometry, Layout};
use crate::model::scalar::{max, Scalar};

/// The part's overall width along x and height along y (m).
pub fn extent<D: Scalar>(s: &PartSettings, layout: &Layout, g: &Geometry<D>) -> [D; 2] {
    let pieces = pieces(s, layout, g);
    let mut far = pieces[0][0];
    for piece in &pieces[..SOLID_PIECES] {
        for p in piece {
            far = [max(far[0], p[0]), max(far[1], p[1])];
        }
    }
    [far[0] * 2.0, far[1] * 2.0]
}

/// The length between the input blocks' pushed faces (m): the room the actuator has.
pub fn pocket_length<D: Scalar>(s: &PartSettings, layout: &Layout, g: &Geometry<D>) -> D {
    // the left input block's middle piece ends at the pushed face, at x < 0
    -pieces(s, layout, g)[1][1][0] * 2.0
}
