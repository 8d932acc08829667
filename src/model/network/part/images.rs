//! The images of a network's described part about its mirror axes.

use super::super::description::Axis;
use super::plane::P;
use crate::model::scalar::Scalar;

/// One of the images the mirror axes make of the described part: `flip_x` maps x to -x
/// (the axis `y`, the line x = 0), `flip_y` maps y to -y (the axis `x`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Image {
    pub(super) flip_x: bool,
    pub(super) flip_y: bool,
}

impl Image {
    pub(super) const IDENTITY: Image = Image {
        flip_x: false,
        flip_y: false,
    };

    /// The identity first, then the image about each axis and about both.
    pub(super) fn all(mirror: &[Axis]) -> Vec<Image> {
        let y = mirror.contains(&Axis::Y);
        let x = mirror.contains(&Axis::X);
        let mut out = vec![Image::IDENTITY];
        for (flip_x, flip_y) in [(false, true), (true, false), (true, true)] {
            if (!flip_x || y) && (!flip_y || x) {
                out.push(Image { flip_x, flip_y });
            }
        }
        out
    }

    pub(super) fn across(axis: Axis) -> Image {
        Image {
            flip_x: axis == Axis::Y,
            flip_y: axis == Axis::X,
        }
    }

    /// A point's image, over any scalar (the part's rules place the images over dual
    /// numbers).
    pub(super) fn point<D: Scalar>(self, p: [D; 2]) -> [D; 2] {
        [
            if self.flip_x { -p[0] } else { p[0] },
            if self.flip_y { -p[1] } else { p[1] },
        ]
    }

    /// A counterclockwise polygon's image, counterclockwise.
    pub(super) fn polygon(self, points: &[P]) -> Vec<P> {
        let mut out: Vec<P> = points.iter().map(|&p| self.point(p)).collect();
        if self.flip_x != self.flip_y {
            out.reverse();
        }
        out
    }

    /// The same image of a body that lies across `own`: the flips about those axes map the
    /// body onto itself.
    pub(super) fn of_body(self, own: &[Axis]) -> Image {
        Image {
            flip_x: self.flip_x && !own.contains(&Axis::Y),
            flip_y: self.flip_y && !own.contains(&Axis::X),
        }
    }

    /// This image after `other`: their flips composed.
    pub(super) fn then(self, other: Image) -> Image {
        Image {
            flip_x: self.flip_x != other.flip_x,
            flip_y: self.flip_y != other.flip_y,
        }
    }

    pub(super) fn suffix(self) -> &'static str {
        match (self.flip_x, self.flip_y) {
            (false, false) => "",
            (false, true) => " (mirror x)",
            (true, false) => " (mirror y)",
            (true, true) => " (mirror x, y)",
        }
    }
}
