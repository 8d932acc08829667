//! Arithmetic expressions of named quantities, evaluated generically over [`Scalar`]: a
//! coordinate or dimension of a mechanism described in the problem file
//! (`"l2*cos(delta2)"`) gives its value with `f64` and its exact derivatives with a dual
//! number, from the one tree.
//!
//! Why our own and not a crate: expression crates fix the operand type when they parse
//! (exmex's `FlatEx<T, _>` takes `T: FromStr` and operators as `fn(T, T) -> T` pointers,
//! and `meval`/`evalexpr` evaluate `f64` only), so evaluating one expression over `f64`,
//! `Jet<N>` for every `N` and num-dual's second-order numbers would need a parse per type,
//! or their symbolic partial derivatives composed by hand for every order. A tree walked
//! by one generic function is about 300 lines and gives every order from the model's own
//! [`Scalar`] operations; it also lets an error name the sub-expression at fault.
//!
//! The language: numbers (`2`, `0.5`, `.5`, `1e-3`), `pi`, names, `+ - * /`, `^` (right
//! associative, binding tighter than a sign: `-2^2 = -4`; its exponent a constant, so that a
//! power is `powi` or `powf` and never `exp(y ln x)`), parentheses, and the functions `sin`,
//! `cos`, `tan`, `asin`, `acos`, `atan`, `atan2(y, x)`, `sqrt`, `abs`, `hypot(a, b)`,
//! `min(a, b)`, `max(a, b)`. Angles are in radians. A value outside a function's domain at
//! the design (a division by zero, the root of a negative number, `asin` beyond one) is an
//! [`EvalError`] naming the sub-expression, never a NaN.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;

use super::scalar::{self, Scalar};

mod parse;
mod tape;
pub use parse::MAX_NESTING;
pub use tape::Tape;

/// A parsed expression; its names are indices into the list it was parsed against.
#[derive(Debug, Clone, PartialEq)]
pub struct Expression {
    source: String,
    nodes: Vec<Node>,
    root: usize,
}

#[derive(Debug, Clone, PartialEq)]
struct Node {
    kind: Kind,
    /// Byte range of the node's text in the source, for errors.
    span: (usize, usize),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Constant(f64),
    Name(usize),
    Neg(usize),
    Add(usize, usize),
    Sub(usize, usize),
    Mul(usize, usize),
    Div(usize, usize),
    Powi(usize, i32),
    Powf(usize, f64),
    Call(Function, usize, Option<usize>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Function {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Sqrt,
    Abs,
    Hypot,
    Min,
    Max,
}

/// Each function's name and its number of arguments.
const FUNCTIONS: [(&str, Function, usize); 12] = [
    ("sin", Function::Sin, 1),
    ("cos", Function::Cos, 1),
    ("tan", Function::Tan, 1),
    ("asin", Function::Asin, 1),
    ("acos", Function::Acos, 1),
    ("atan", Function::Atan, 1),
    ("atan2", Function::Atan2, 2),
    ("sqrt", Function::Sqrt, 1),
    ("abs", Function::Abs, 1),
    ("hypot", Function::Hypot, 2),
    ("min", Function::Min, 2),
    ("max", Function::Max, 2),
];

/// Why `name` cannot name a quantity of the expressions, where the language keeps it for
/// itself: a name beside `pi` or a function would be read as the constant, or shadow it.
pub fn reserved(name: &str) -> Option<&'static str> {
    if name == "pi" {
        Some("the expressions read `pi` as the constant π")
    } else if FUNCTIONS.iter().any(|(n, ..)| *n == name) {
        Some("it is a function of the expressions")
    } else {
        None
    }
}

/// What is wrong with an expression's text, and where (a byte offset into it).
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub position: usize,
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at character {}: {}", self.position + 1, self.message)
    }
}

/// A value outside a function's domain at the design.
#[derive(Debug, Clone, PartialEq)]
pub struct EvalError {
    pub message: String,
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl Expression {
    /// Parses `text`, whose names must be among `names` (they become indices into it).
    pub fn parse(text: &str, names: &[&str]) -> Result<Self, ParseError> {
        let (nodes, root) = parse::nodes(text, names)?;
        let nodes = post_order(nodes, root);
        Ok(Expression {
            source: text.to_string(),
            root: nodes.len() - 1,
            nodes,
        })
    }

    pub fn source(&self) -> &str {
        &self.source
    }

    /// The indices of the names it uses, ascending, each once.
    pub fn names_used(&self) -> Vec<usize> {
        let mut used: Vec<usize> = self
            .nodes
            .iter()
            .filter_map(|n| match n.kind {
                Kind::Name(i) => Some(i),
                _ => None,
            })
            .collect();
        used.sort_unstable();
        used.dedup();
        used
    }

    /// Its value with the names bound to `values` (indexed as the names it was parsed
    /// against).
    pub fn eval<D: Scalar>(&self, values: &[D]) -> Result<D, EvalError> {
        // the nodes are in post-order: each node's operands are the last values computed, so
        // one pass with a stack evaluates the tree at any depth without recursion
        let mut stack: Vec<D> = Vec::new();
        for i in 0..self.nodes.len() {
            let v = self.node(i, values, &mut stack)?;
            stack.push(v);
        }
        let v = stack.pop().expect("an expression has a root");
        if v.re().is_finite() {
            Ok(v)
        } else {
            Err(self.error(self.root, "is not a finite number"))
        }
    }

    fn text(&self, node: usize) -> &str {
        let (a, b) = self.nodes[node].span;
        &self.source[a..b]
    }

    fn error(&self, node: usize, what: &str) -> EvalError {
        EvalError {
            message: format!("`{}` {what} at this design", self.text(node)),
        }
    }

    /// Node `i`'s value, its operands popped from `stack` (the second on top).
    fn node<D: Scalar>(&self, i: usize, values: &[D], stack: &mut Vec<D>) -> Result<D, EvalError> {
        let kind = self.nodes[i].kind;
        let (first, second) = operands(kind);
        let y = second.map_or(D::from(0.0), |_| pop(stack));
        let x = first.map_or(D::from(0.0), |_| pop(stack));
        Ok(match kind {
            Kind::Constant(c) => D::from(c),
            Kind::Name(k) => values[k],
            Kind::Neg(_) => -x,
            Kind::Add(..) => x + y,
            Kind::Sub(..) => x - y,
            Kind::Mul(..) => x * y,
            Kind::Div(_, b) => {
                if y.re() == 0.0 {
                    return Err(self.error(b, "is zero, a division by zero,"));
                }
                x / y
            }
            Kind::Powi(a, n) => {
                let base = x;
                if n < 0 && base.re() == 0.0 {
                    return Err(self.error(a, "is zero under a negative power"));
                }
                base.powi(n)
            }
            Kind::Powf(a, y) => {
                let base = x;
                if base.re() < 0.0 || (base.re() == 0.0 && y < 1.0) {
                    return Err(self.error(
                        a,
                        &format!(
                            "is {} under the power {y}, which needs it positive",
                            base.re()
                        ),
                    ));
                }
                base.powf(y)
            }
            Kind::Call(f, a, _) => {
                let second = y;
                match f {
                    Function::Sin => x.sin(),
                    Function::Cos => x.cos(),
                    Function::Tan => {
                        let (s, c) = x.sin_cos();
                        if c.re() == 0.0 {
                            return Err(self.error(a, "is a right angle, where tan is infinite,"));
                        }
                        s / c
                    }
                    Function::Asin | Function::Acos => {
                        if x.re().abs() >= 1.0 {
                            return Err(self.error(
                                a,
                                &format!(
                                    "is {}, where {} needs it strictly between -1 and 1",
                                    x.re(),
                                    if f == Function::Asin { "asin" } else { "acos" }
                                ),
                            ));
                        }
                        asin_or_acos(x, f)
                    }
                    Function::Atan => x.atan(),
                    Function::Atan2 => {
                        let (y, x) = (x, second);
                        if x.re() == 0.0 && y.re() == 0.0 {
                            return Err(self.error(i, "has both arguments zero"));
                        }
                        scalar::atan2(y, x)
                    }
                    Function::Sqrt => {
                        if x.re() < 0.0 {
                            return Err(self.error(
                                a,
                                &format!("is {}, and a square root needs it at least 0", x.re()),
                            ));
                        }
                        x.sqrt()
                    }
                    Function::Abs => x.abs(),
                    Function::Hypot => {
                        let y = second;
                        if x.re() == 0.0 && y.re() == 0.0 {
                            return Err(self
                                .error(i, "has both arguments zero, where it has no derivative,"));
                        }
                        (x * x + y * y).sqrt()
                    }
                    Function::Min => scalar::min(x, second),
                    Function::Max => scalar::max(x, second),
                }
            }
        })
    }
}

/// The operand on top of the evaluation's stack: the post-order puts it there.
fn pop<D>(stack: &mut Vec<D>) -> D {
    stack
        .pop()
        .expect("a node's operands precede it in post-order")
}

/// The nodes the root reaches, renumbered in post-order (each node after its operands, the
/// first operand's nodes before the second's, the root last): the order the parser pushed
/// them in, without the exponents' nodes that were folded into constants. Found in one
/// descending pass, as an operand always precedes its node, so no depth recurses.
fn post_order(nodes: Vec<Node>, root: usize) -> Vec<Node> {
    let mut live = vec![false; nodes.len()];
    live[root] = true;
    for i in (0..=root).rev() {
        if live[i] {
            let (a, b) = operands(nodes[i].kind);
            for j in a.into_iter().chain(b) {
                live[j] = true;
            }
        }
    }
    let mut renamed = vec![usize::MAX; nodes.len()];
    let mut kept = Vec::with_capacity(nodes.len());
    for (i, mut node) in nodes.into_iter().enumerate().filter(|(i, _)| live[*i]) {
        let r = |j: usize| renamed[j];
        node.kind = match node.kind {
            Kind::Neg(a) => Kind::Neg(r(a)),
            Kind::Add(a, b) => Kind::Add(r(a), r(b)),
            Kind::Sub(a, b) => Kind::Sub(r(a), r(b)),
            Kind::Mul(a, b) => Kind::Mul(r(a), r(b)),
            Kind::Div(a, b) => Kind::Div(r(a), r(b)),
            Kind::Powi(a, n) => Kind::Powi(r(a), n),
            Kind::Powf(a, y) => Kind::Powf(r(a), y),
            Kind::Call(f, a, b) => Kind::Call(f, r(a), b.map(r)),
            leaf => leaf,
        };
        renamed[i] = kept.len();
        kept.push(node);
    }
    kept
}

/// A node's operands, the first and the second.
fn operands(kind: Kind) -> (Option<usize>, Option<usize>) {
    match kind {
        Kind::Constant(_) | Kind::Name(_) => (None, None),
        Kind::Neg(a) | Kind::Powi(a, _) | Kind::Powf(a, _) => (Some(a), None),
        Kind::Add(a, b) | Kind::Sub(a, b) | Kind::Mul(a, b) | Kind::Div(a, b) => (Some(a), Some(b)),
        Kind::Call(_, a, b) => (Some(a), b),
    }
}

/// `asin x` or `acos x` (`f`), `|x| < 1`: asin x = atan(x / sqrt(1 - x^2)), acos x =
/// pi/2 - asin x.
fn asin_or_acos<D: Scalar>(x: D, f: Function) -> D {
    let asin = (x / (-(x * x) + 1.0).sqrt()).atan();
    if f == Function::Asin {
        asin
    } else {
        -asin + FRAC_PI_2
    }
}

#[cfg(test)]
mod tests;
