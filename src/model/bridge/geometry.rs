//! The design of a quarter bridge and where its parameters sit in the model's list.
//!
//! Hinges b and d are each a hinge of any kind ([`HingeKind`]) with the kind's own
//! dimensions, named after the hinge: a strip's length and thickness are `l2`, `t2` at b and
//! `l4`, `t4` at d. The parameter list is laid out as paper 004's Table 1 lists the strip
//! bridge: hinge b's first dimension (its length), `delta2`, b's other dimensions, `l3`,
//! `delta3`, hinge d's first dimension, `delta4`, d's other dimensions. For two strips that
//! is `l2, delta2, t2, l3, delta3, l4, delta4, t4`.

use std::borrow::Cow;

use serde::Serialize;

use crate::model::fit::FitLimit;
use crate::model::hinge::{Hinge, HingeKind, MAX_HINGE_DIMENSIONS};
use crate::model::scalar::{Jet, Scalar};
use crate::model::{check_parameters, Dimension, ParameterInfo};

/// A bridge design in SI units (m, rad): the two hinges, the middle link and the angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry<D> {
    /// Hinge b, from node 2 to node 3.
    pub b: Hinge<D>,
    pub delta2: D,
    /// Length of the rigid middle link c, node 3 to node 4.
    pub l3: D,
    pub delta3: D,
    /// Hinge d, from node 4 to node 5.
    pub d: Hinge<D>,
    pub delta4: D,
}

/// `sin` and `cos` of `delta2`, `delta3`, `delta4`.
#[derive(Debug, Clone, Copy)]
pub struct Trig<D> {
    pub s: [D; 3],
    pub c: [D; 3],
}

impl<D: Scalar> Trig<D> {
    #[inline]
    pub fn new(delta2: D, delta3: D, delta4: D) -> Self {
        let (s2, c2) = delta2.sin_cos();
        let (s3, c3) = delta3.sin_cos();
        let (s4, c4) = delta4.sin_cos();
        Trig {
            s: [s2, s3, s4],
            c: [c2, c3, c4],
        }
    }
}

impl<D: Scalar> Geometry<D> {
    /// The strip bridge of paper 004 from its eight parameters in Table 1's order
    /// `l2, delta2, t2, l3, delta3, l4, delta4, t4`.
    pub fn from_array(x: [D; 8]) -> Self {
        let [l2, delta2, t2, l3, delta3, l4, delta4, t4] = x;
        Geometry {
            b: Hinge::strip(l2, t2),
            delta2,
            l3,
            delta3,
            d: Hinge::strip(l4, t4),
            delta4,
        }
    }

    /// Length of hinge b along its centre line.
    pub fn l2(&self) -> D {
        self.b.length()
    }

    /// Length of hinge d along its centre line.
    pub fn l4(&self) -> D {
        self.d.length()
    }

    /// Sines and cosines of the three angles.
    #[inline]
    pub fn trig(&self) -> Trig<D> {
        Trig::new(self.delta2, self.delta3, self.delta4)
    }

    /// Extent of the quarter along `x` (Sec. 3 contour limits).
    pub fn span_x(&self) -> D {
        self.span_x_with(&self.trig())
    }

    /// Extent of the quarter along `y` (Sec. 3 contour limits).
    pub fn span_y(&self) -> D {
        self.span_y_with(&self.trig())
    }

    pub(crate) fn span_x_with(&self, t: &Trig<D>) -> D {
        self.l2() * t.c[0] + self.l3 * t.c[1] + self.l4() * t.c[2]
    }

    pub(crate) fn span_y_with(&self, t: &Trig<D>) -> D {
        self.l2() * t.s[0] + self.l3 * t.s[1] + self.l4() * t.s[2]
    }

    /// Node coordinates 2..=5 of the quarter (m), origin at node 2.
    pub fn nodes(&self) -> [[D; 2]; 4] {
        self.nodes_with(&self.trig())
    }

    /// [`Geometry::nodes`] from the angles' sines and cosines.
    pub fn nodes_with(&self, t: &Trig<D>) -> [[D; 2]; 4] {
        let zero = D::from(0.0);
        let mut p = [[zero, zero]; 4];
        for (i, l) in [self.l2(), self.l3, self.l4()].into_iter().enumerate() {
            p[i + 1] = [p[i][0] + l * t.c[i], p[i][1] + l * t.s[i]];
        }
        p
    }
}

/// Where each part of a [`Geometry`] sits in the model's parameter list, for a choice of
/// hinge kinds at b and d.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layout {
    pub hinge_b: HingeKind,
    pub hinge_d: HingeKind,
    #[serde(skip)]
    parameters: Vec<ParameterInfo>,
    /// Parameter index of each dimension of hinge b, of hinge d, and of
    /// `delta2, l3, delta3, delta4`.
    #[serde(skip)]
    b: Vec<usize>,
    #[serde(skip)]
    d: Vec<usize>,
    #[serde(skip)]
    link: [usize; 4],
    /// Two strips: the parameters are Table 1's eight.
    #[serde(skip)]
    strips: bool,
    /// Each hinge's ranges of fit over the parameters.
    #[serde(skip)]
    fit: Vec<FitLimit>,
}

impl Layout {
    pub fn new(hinge_b: HingeKind, hinge_d: HingeKind) -> Self {
        let angle = |name: &'static str, description: &'static str| {
            ParameterInfo::new(name, Dimension::Angle, description)
        };
        let mut parameters = Vec::new();
        let mut b = Vec::new();
        let mut d = Vec::new();
        // each hinge: its first dimension, its angle, its other dimensions
        for (kind, number, letter, slots, delta) in [
            (
                hinge_b,
                '2',
                'b',
                &mut b,
                angle("delta2", "angle of hinge b"),
            ),
            (
                hinge_d,
                '4',
                'd',
                &mut d,
                angle("delta4", "angle of hinge d"),
            ),
        ] {
            if letter == 'd' {
                parameters.push(ParameterInfo::new(
                    "l3",
                    Dimension::Length,
                    "length of the middle link c",
                ));
                parameters.push(angle("delta3", "angle of the middle link c"));
            }
            for (k, dim) in kind.dimensions().iter().enumerate() {
                if k == 1 {
                    parameters.push(delta.clone());
                }
                slots.push(parameters.len());
                parameters.push(ParameterInfo {
                    name: Cow::Owned(format!("{}{number}", dim.stem)),
                    dimension: dim.dimension,
                    description: Cow::Owned(format!("{} of hinge {letter}", dim.description)),
                });
            }
            if kind.dimensions().len() == 1 {
                parameters.push(delta);
            }
        }
        let position = |name: &str| parameters.iter().position(|p| p.name == name).unwrap();
        let link = ["delta2", "l3", "delta3", "delta4"].map(position);
        let mut fit = Vec::new();
        for (kind, letter, slots) in [(hinge_b, 'b', &b), (hinge_d, 'd', &d)] {
            let names: Vec<&str> = slots.iter().map(|&i| parameters[i].name.as_ref()).collect();
            let owner = format!("hinge {letter} ({})", kind.name());
            fit.extend(kind.fit_limits(&owner, slots, &names));
        }
        Layout {
            hinge_b,
            hinge_d,
            parameters,
            b,
            d,
            link,
            strips: hinge_b == HingeKind::Strip && hinge_d == HingeKind::Strip,
            fit,
        }
    }

    /// Each hinge's ranges of fit over the parameters ([`HingeKind::fit_limits`]).
    pub fn fit_limits(&self) -> &[FitLimit] {
        &self.fit
    }

    /// The parameter index of each dimension of hinge b, of each of hinge d, and of
    /// `delta2, l3, delta3, delta4`.
    pub(crate) fn slots(&self) -> (&[usize], &[usize], [usize; 4]) {
        (&self.b, &self.d, self.link)
    }

    /// The model's parameters, in order.
    pub fn parameters(&self) -> &[ParameterInfo] {
        &self.parameters
    }

    /// Each parameter and, for a hinge's dimension, its index in the hinge kind's
    /// dimensions (`r2` of a circular notch at b: 0).
    pub fn hinge_dimensions(&self) -> Vec<(ParameterInfo, Option<usize>)> {
        self.parameters
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let at = |slots: &[usize]| slots.iter().position(|&s| s == i);
                (p.clone(), at(&self.b).or_else(|| at(&self.d)))
            })
            .collect()
    }

    /// The design whose parameters (in the order of [`Layout::parameters`]) are `x`.
    pub fn geometry<D: Scalar>(&self, x: &[D]) -> Geometry<D> {
        if let (true, Ok(x)) = (self.strips, <[D; 8]>::try_from(x)) {
            return Geometry::from_array(x);
        }
        let pick = |idx: &[usize]| {
            let mut dims = [D::from(0.0); MAX_HINGE_DIMENSIONS];
            for (v, &i) in dims.iter_mut().zip(idx) {
                *v = x[i];
            }
            dims
        };
        let [delta2, l3, delta3, delta4] = self.link.map(|i| x[i]);
        Geometry {
            b: Hinge {
                kind: self.hinge_b,
                dims: pick(&self.b),
            },
            delta2,
            l3,
            delta3,
            d: Hinge {
                kind: self.hinge_d,
                dims: pick(&self.d),
            },
            delta4,
        }
    }

    /// The design `x`, each parameter an independent variable of the gradient. Built in
    /// place, not through [`Layout::geometry`] on a seeded copy of `x`: the copies of the
    /// gradients showed in the instruction count of the study (2 %).
    pub fn seeded<const N: usize>(&self, x: &[f64]) -> Geometry<Jet<N>> {
        let v = |i: usize| Jet::variable(x[i], i);
        if self.strips {
            // paper 004's layout, with its indices known to the compiler
            return Geometry::from_array(std::array::from_fn(v));
        }
        let hinge = |kind: HingeKind, idx: &[usize]| {
            let mut dims = [Jet::from(0.0); MAX_HINGE_DIMENSIONS];
            for (d, &i) in dims.iter_mut().zip(idx) {
                *d = v(i);
            }
            Hinge { kind, dims }
        };
        let [delta2, l3, delta3, delta4] = self.link;
        Geometry {
            b: hinge(self.hinge_b, &self.b),
            delta2: v(delta2),
            l3: v(l3),
            delta3: v(delta3),
            d: hinge(self.hinge_d, &self.d),
            delta4: v(delta4),
        }
    }

    /// Why some design between `lower` and `upper` lies outside the domain though its
    /// bounds are valid each: a hinge kind whose dimensions constrain each other (a
    /// corner-filleted leaf's fillets at most half its length).
    pub fn box_error(&self, lower: &[f64], upper: &[f64]) -> Option<(usize, String)> {
        let names: Vec<&str> = self.parameters.iter().map(|p| p.name.as_ref()).collect();
        for (kind, idx) in [(self.hinge_b, &self.b), (self.hinge_d, &self.d)] {
            let lo: Vec<f64> = idx.iter().map(|&i| lower[i]).collect();
            let hi: Vec<f64> = idx.iter().map(|&i| upper[i]).collect();
            let own: Vec<&str> = idx.iter().map(|&i| names[i]).collect();
            if let Some((k, why)) = kind.box_error(&lo, &hi, &own) {
                return Some((idx[k], why));
            }
        }
        None
    }

    /// Why the design `x` (SI) lies outside the model's domain, if it does: every value
    /// finite, each hinge valid for its kind (a strip's length not negative, its thickness
    /// positive), `l3` not negative, at least one hinge of some length (else
    /// `c33b + c33d = 0` and nothing bends), angles strictly between -90 and 90 deg.
    pub fn domain_error(&self, x: &[f64]) -> Option<String> {
        if let Some(why) = check_parameters("bridge", &self.parameters, x, &[], &[]) {
            return Some(why);
        }
        let names: Vec<&str> = self.parameters.iter().map(|p| p.name.as_ref()).collect();
        let hinge = |kind: HingeKind, idx: &[usize]| {
            let dims: Vec<f64> = idx.iter().map(|&i| x[i]).collect();
            let own: Vec<&str> = idx.iter().map(|&i| names[i]).collect();
            kind.domain_error(&dims, &own)
        };
        let l3 = x[self.link[1]];
        let l3_error = (l3 < 0.0).then(|| format!("l3 = {l3} m is negative"));
        if let Some(e) = hinge(self.hinge_b, &self.b)
            .or(l3_error)
            .or_else(|| hinge(self.hinge_d, &self.d))
        {
            return Some(e);
        }
        let g = self.geometry(x);
        if g.l2() + g.l4() == 0.0 {
            return Some(format!(
                "{} = {} = 0: a bridge without hinges does not deform",
                names[self.b[0]], names[self.d[0]]
            ));
        }
        let right = std::f64::consts::FRAC_PI_2;
        for i in [self.link[0], self.link[2], self.link[3]] {
            if x[i].abs() >= right {
                return Some(format!(
                    "{} = {} deg is not strictly between -90 and 90 deg",
                    names[i],
                    crate::vocab::units::short(x[i].to_degrees())
                ));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_strip_layout_is_table_1s_order() {
        let layout = Layout::new(HingeKind::Strip, HingeKind::Strip);
        let names: Vec<&str> = layout
            .parameters()
            .iter()
            .map(|p| p.name.as_ref())
            .collect();
        assert_eq!(
            names,
            ["l2", "delta2", "t2", "l3", "delta3", "l4", "delta4", "t4"]
        );
        // the general path and the strips' shortcut give the same design
        let x = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
        let mut general = layout.clone();
        general.strips = false;
        assert_eq!(general.geometry(&x), Geometry::from_array(x));
        assert_eq!(layout.geometry(&x), Geometry::from_array(x));
        let (s, g) = (layout.seeded::<8>(&x), general.seeded::<8>(&x));
        assert_eq!(s.d.dims[1].grad, g.d.dims[1].grad);
        assert_eq!(s.delta4.grad[6], 1.0);
        assert_eq!(g.delta4.grad[6], 1.0);
    }
}
