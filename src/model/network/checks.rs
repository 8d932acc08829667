//! The checks of a network's description that are not the reading of one key (issue 50):
//! points and pairs of exactly two, names the expression language or the model's own outputs
//! keep, sizes that a constant makes non-positive, and outlines that are no polygon.

use std::fmt;

use geo::{Coord, Intersects, Line};
use serde::de::{self, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::Deserialize;

use super::file::{Description, Keyed};
use crate::model::expression;
use crate::model::scalar::Jet;
use crate::model::{Dimension, ParameterInfo};
use crate::vocab::error::Segment;
use crate::vocab::reader::k;

/// A point `[x, y]` or a parameter's `[name, dimension]`: exactly two strings. An array of
/// three read into `[String; 2]` is taken without a word, its third value never looked at.
#[derive(Debug, Clone)]
pub struct Two(pub [String; 2]);

impl<'de> Deserialize<'de> for Two {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Pair;
        impl<'de> Visitor<'de> for Pair {
            type Value = Two;

            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a list of exactly two strings: [x, y] for a point, [name, dimension] for a parameter")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Two, A::Error> {
                let first: String = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(0, &self))?;
                let second: String = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(1, &self))?;
                let mut count = 2;
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    count += 1;
                }
                if count > 2 {
                    return Err(de::Error::invalid_length(count, &self));
                }
                Ok(Two([first, second]))
            }
        }
        d.deserialize_seq(Pair)
    }
}

/// Why `name` cannot name a parameter of the expressions: `deg` and what the expression
/// language reserves (`pi`, its functions), or a text that is no name.
pub fn parameter_name_error(name: &str) -> Option<String> {
    let why = if name == super::file::DEG {
        "the expressions read `deg` as pi / 180"
    } else if let Some(why) = expression::reserved(name) {
        why
    } else if expression::Expression::parse(name, &[name]).is_err() {
        "a name is a letter or `_` followed by letters, digits or `_`"
    } else {
        return None;
    };
    Some(format!(
        "\"{name}\" cannot name a parameter: {why}; choose another name"
    ))
}

/// The key and message of a size written as a constant that is not positive (a link's
/// width, a beam's thickness, a hinge's length dimension): refused at reading, where a size
/// that depends on the design is checked at each design.
pub fn constant_size_error(size: &Keyed, what: &str) -> Option<String> {
    if !size.expression.names_used().is_empty() {
        return None;
    }
    let value = size.expression.eval::<f64>(&[]).ok()?;
    (value <= 0.0).then(|| {
        format!(
            "{what} is \"{}\" = {}, not positive: give it a positive value",
            size.expression.source(),
            crate::vocab::units::short(value)
        )
    })
}

/// A name the model's outputs hold twice (a measure named `k_in`, a hinge `p` beside a
/// hinge `p_to` whose `stress_p_to` both give), and the key of the later one to blame: a
/// measure, else the hinge or beam, else the output port.
pub fn output_clash(names: &[&str], d: &Description) -> Option<(Vec<Segment>, String)> {
    let (_, name) = names
        .iter()
        .enumerate()
        .find(|&(i, n)| names[..i].contains(n))?;
    let net = |table: &str, i: usize| vec![k("network"), k(table), Segment::Index(i), k("name")];
    if let Some(m) = d.measures.iter().position(|m| m.name == *name) {
        return Some((
            net("measures", m),
            format!(
                "measure \"{name}\" has the name of an output the network gives already: name \
                 it otherwise (the network's outputs: `flexopt outputs`)"
            ),
        ));
    }
    let member = |m: &str| {
        [
            format!("stress_{m}"),
            format!("stress_{m}_from"),
            format!("stress_{m}_to"),
            format!("rotation_{m}"),
        ]
        .contains(&name.to_string())
    };
    let mut flexures = d
        .hinges
        .iter()
        .map(|h| ("hinges", h.name.as_str()))
        .enumerate()
        .chain(
            d.beams
                .iter()
                .enumerate()
                .map(|(i, b)| (i, ("beams", b.name.as_str()))),
        );
    if let Some((i, (table, m))) = flexures.rfind(|(_, (_, m))| member(m)) {
        return Some((
            net(table, i),
            format!(
                "\"{m}\" gives the output \"{name}\", which another hinge's or beam's name gives \
                 too: rename one of them"
            ),
        ));
    }
    let port = d
        .outputs
        .iter()
        .rposition(|p| *name == format!("amplification_{}", p.name))?;
    Some((
        net("outputs", port),
        format!("output \"{name}\" is named twice among the network's outputs: rename the port"),
    ))
}

/// The first expression of `all` whose derivative by a parameter is not finite at `x` (SI),
/// though its value is (`0*sqrt(l - l)`): the solver's gradient would be NaN at every
/// design, and every start fail with no word of why.
pub fn derivative_error(
    all: &[&Keyed],
    parameters: &[ParameterInfo],
    unit: f64,
    x: &[f64],
) -> Option<String> {
    let mut values: Vec<Jet<1>> = parameters
        .iter()
        .zip(x)
        .map(|(p, &v)| {
            Jet::from(if p.dimension == Dimension::Length {
                v / unit
            } else {
                v
            })
        })
        .chain([Jet::from(std::f64::consts::PI / 180.0)])
        .collect();
    for (j, p) in parameters.iter().enumerate() {
        let re = values[j].re;
        values[j] = Jet::variable(re, 0);
        let bad = all.iter().find(|e| {
            e.expression.names_used().contains(&j)
                && e.expression
                    .eval(&values)
                    .is_ok_and(|v| !v.grad[0].is_finite())
        });
        if let Some(e) = bad {
            return Some(format!(
                "`{}` ({}) has no finite derivative by {} at this design: the solver needs \
                 one; write it without a function at the edge of its domain (a square root \
                 of zero)",
                e.expression.source(),
                e.key,
                p.name
            ));
        }
        values[j] = Jet::from(re);
    }
    None
}

/// The first two edges of the closed polygon `points` that cross or touch, not being
/// neighbours: an outline that crosses itself is no solid.
pub fn crossing(points: &[[f64; 2]]) -> Option<(usize, usize)> {
    let n = points.len();
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            if segments_meet(edge(i), edge(j)) {
                return Some((i, j));
            }
        }
    }
    None
}

/// Whether two segments cross or touch (geo's exact predicates: a vertex on the other edge
/// counts, as does a collinear overlap).
fn segments_meet((a, b): ([f64; 2], [f64; 2]), (c, d): ([f64; 2], [f64; 2])) -> bool {
    let line = |p: [f64; 2], q: [f64; 2]| Line::new(Coord::from(p), Coord::from(q));
    line(a, b).intersects(&line(c, d))
}

#[cfg(test)]
mod tests {
    use super::crossing;

    #[test]
    fn a_bow_tie_crosses_and_a_square_does_not() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(crossing(&square), None);
        let bow = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        assert_eq!(crossing(&bow), Some((0, 2)));
        // a vertex on a far edge: touching is crossing
        let touch = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        assert!(crossing(&touch).is_some());
    }
}
