//! The description's expressions at a design: apart from the part's making so that the spec
//! and the rules both evaluate through it without importing each other.

use super::super::description::{Description, Keyed, Point};
use crate::model::scalar::Scalar;
use crate::model::Dimension;

/// The description's expressions evaluated at `x` (SI), over `f64` for the spec and over
/// dual numbers for the rules ([`super::rules`]).
pub(super) struct Values<'a, D = f64> {
    d: &'a Description,
    pub(super) values: Vec<D>,
}

impl<'a, D: Scalar> Values<'a, D> {
    pub(super) fn new(d: &'a Description, x: &[D]) -> Self {
        let mut values: Vec<D> = Vec::with_capacity(x.len() + 1);
        values.extend(x.iter().zip(&d.parameters).map(|(&v, p)| {
            if p.dimension == Dimension::Length {
                v / d.unit
            } else {
                v
            }
        }));
        values.push(D::from(std::f64::consts::PI / 180.0));
        Values { d, values }
    }

    pub(super) fn eval(&self, e: &Keyed) -> Result<D, String> {
        e.expression
            .eval(&self.values)
            .map_err(|err| format!("{} = \"{}\": {err}", e.key, e.expression.source()))
    }

    pub(super) fn length(&self, e: &Keyed) -> Result<D, String> {
        Ok(self.eval(e)? * self.d.unit)
    }

    pub(super) fn point(&self, p: &Point) -> Result<[D; 2], String> {
        Ok([self.length(&p[0])?, self.length(&p[1])?])
    }

    pub(super) fn points(&self, ps: &[Point]) -> Result<Vec<[D; 2]>, String> {
        ps.iter().map(|p| self.point(p)).collect()
    }
}
