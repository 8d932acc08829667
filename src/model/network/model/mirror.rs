//! The network's mirror images: each expression's role (a point's coordinate, a dimension,
//! an angle, a direction), and whether the design with its angles negated reflects the
//! described mechanism about the `x` axis, expression by expression or as a mechanism, so
//! that the study merges an optimum with its image.

use super::*;

/// What an expression of the description is, for [`NetworkModel::mirror`]: how its value
/// changes when the mechanism is reflected about the `x` axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Role {
    /// A point's `x`, kept; its `y` (the next expression), negated.
    PointX,
    PointY,
    /// A hinge's dimension, kept.
    Dimension,
    /// A hinge's angle, negated (its sine negated, its cosine kept).
    Angle,
    /// A port's direction `(x, y)`: reflected, or reflected and reversed (the port then
    /// reads its motion with the other sign, an output up to sign).
    DirectionX,
    DirectionY,
    /// A measure: kept or negated (an output up to sign).
    Measure,
}

/// Every expression [`NetworkModel::at`] evaluates, with its [`Role`].
pub(super) fn expressions(d: &mut Description) -> Vec<(&mut Keyed, Role)> {
    let mut all = Vec::new();
    fn point<'a>(all: &mut Vec<(&'a mut Keyed, Role)>, p: &'a mut Point) {
        let [x, y] = p;
        all.push((x, Role::PointX));
        all.push((y, Role::PointY));
    }
    let mut widths = Vec::new();
    for b in &mut d.bodies {
        for p in &mut b.points {
            point(&mut all, p);
        }
        widths.extend(b.link_width.iter_mut());
    }
    for p in &mut d.ground {
        point(&mut all, p);
    }
    for h in &mut d.hinges {
        all.extend(h.dimensions.iter_mut().map(|e| (e, Role::Dimension)));
        point(&mut all, &mut h.start);
        all.push((&mut h.angle, Role::Angle));
    }
    for p in std::iter::once(&mut d.input).chain(&mut d.outputs) {
        point(&mut all, &mut p.at);
        let [x, y] = &mut p.direction;
        all.push((x, Role::DirectionX));
        all.push((y, Role::DirectionY));
    }
    for m in &mut d.measures {
        all.push((&mut m.value, Role::Measure));
    }
    // the links' widths, for the bodies' masses: last, so that the others keep their slots
    all.extend(widths.into_iter().map(|e| (e, Role::Dimension)));
    // the beams after them, for the same reason, and the supports after the beams
    for b in &mut d.beams {
        point(&mut all, &mut b.start);
        point(&mut all, &mut b.end);
        all.push((&mut b.thickness, Role::Dimension));
    }
    for g in &mut d.supports {
        point(&mut all, &mut g.at);
        let [x, y] = &mut g.direction;
        all.push((x, Role::DirectionX));
        all.push((y, Role::DirectionY));
    }
    all
}

impl NetworkModel {
    /// Whether every output at `m` is the one at `x` up to sign (relative 1e-10): the test of
    /// a mirror image for a description that is no reflection of itself expression by
    /// expression but is one as a mechanism, such as a body across an axis drawn off it (its
    /// place along the axis changes nothing, as it neither turns nor moves across it).
    /// The available outputs but those whose quantity `skip` tells.
    pub(super) fn available_but(&self, skip: impl Fn(Quantity) -> bool) -> Vec<usize> {
        let available = self.available_outputs().into_iter();
        available.filter(|&i| !skip(self.quantities[i])).collect()
    }

    pub(super) fn same_outputs(&self, x: &[f64], m: &[f64]) -> bool {
        // not the part's box: a body across an axis drawn off it moves the outline but not
        // the mechanism (wei2017's network has such images, which the study merges)
        let all = self.available_but(|q| matches!(q, Quantity::PartWidth | Quantity::PartHeight));
        let (mut a, mut b) = (vec![0.0; all.len()], vec![0.0; all.len()]);
        self.evaluate(x, &all, &mut a);
        self.evaluate(m, &all, &mut b);
        a.iter().zip(&b).all(|(&a, &b)| {
            let (a, b) = (a.abs(), b.abs());
            a == b || (a - b).abs() <= 1e-10 * a.max(b)
        })
    }

    /// Every angle negated, as the bridge's, where that reflects the described mechanism
    /// about the `x` axis at this design: each point's `y` and each hinge's angle negated,
    /// the rest kept, each port's direction reflected (or reflected and reversed: the port
    /// reads its motion with the other sign) and each measure kept up to sign, so that the
    /// outputs are the same up to sign. A description written so (wei2017's, with
    /// `l2*sin(delta2)`) has its mirror image at every design; one that is not (a point at
    /// `l2*sin(delta2) + 1`) has none, and the study keeps its mirror images apart.
    pub(super) fn reflect(&self, x: &mut [f64]) -> bool {
        let mut m = x.to_vec();
        if !crate::model::negate_angles(&self.description.parameters, &mut m) {
            return false;
        }
        let (Some(values), Some(mirrored)) =
            (self.expression_values(x), self.expression_values(&m))
        else {
            return false;
        };
        if !reflects(&self.roles, &values, &mirrored) && !self.same_outputs(x, &m) {
            return false;
        }
        x.copy_from_slice(&m);
        true
    }
}

/// Whether `mirrored`, the values of the description's expressions at the design with its
/// angles negated, are those of `values` reflected about the `x` axis, each by its role
/// (relative 1e-12; a point's coordinates against the largest of them).
fn reflects(roles: &[Role], values: &[f64], mirrored: &[f64]) -> bool {
    let size = roles
        .iter()
        .zip(values)
        .filter(|(r, _)| matches!(r, Role::PointX | Role::PointY))
        .fold(0.0f64, |m, (_, v)| m.max(v.abs()));
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
    let mut i = 0;
    while i < roles.len() {
        let (a, b) = (values[i], mirrored[i]);
        let fine = match roles[i] {
            Role::PointX => close(b, a, size),
            Role::PointY => close(b, -a, size),
            Role::Dimension => close(b, a, a.abs()),
            Role::Angle => {
                let ((s, c), (sm, cm)) = (a.sin_cos(), b.sin_cos());
                close(sm, -s, 1.0) && close(cm, c, 1.0)
            }
            Role::DirectionX => {
                let (ay, by) = (values[i + 1], mirrored[i + 1]);
                let norm = a.hypot(ay);
                i += 1;
                (close(b, a, norm) && close(by, -ay, norm))
                    || (close(b, -a, norm) && close(by, ay, norm))
            }
            Role::DirectionY => unreachable!("read with its DirectionX"),
            Role::Measure => close(b, a, a.abs()) || close(b, -a, a.abs()),
        };
        if !fine {
            return false;
        }
        i += 1;
    }
    true
}
