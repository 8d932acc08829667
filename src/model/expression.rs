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

mod tape;
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
        let mut p = Parser {
            text,
            tokens: tokenize(text)?,
            at: 0,
            names,
            nodes: Vec::new(),
        };
        if p.tokens.is_empty() {
            return Err(ParseError {
                position: 0,
                message: "empty: write a number or an expression of the design".into(),
            });
        }
        let root = p.sum()?;
        if let Some(t) = p.tokens.get(p.at) {
            return Err(ParseError {
                position: t.start,
                message: format!(
                    "`{}` follows a complete expression: an operator is missing before it",
                    &text[t.start..t.end]
                ),
            });
        }
        Ok(Expression {
            source: text.to_string(),
            nodes: p.nodes,
            root,
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
        let v = self.node(self.root, values)?;
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

    fn node<D: Scalar>(&self, i: usize, values: &[D]) -> Result<D, EvalError> {
        let value = |j| self.node(j, values);
        Ok(match self.nodes[i].kind {
            Kind::Constant(c) => D::from(c),
            Kind::Name(k) => values[k],
            Kind::Neg(a) => -value(a)?,
            Kind::Add(a, b) => value(a)? + value(b)?,
            Kind::Sub(a, b) => value(a)? - value(b)?,
            Kind::Mul(a, b) => value(a)? * value(b)?,
            Kind::Div(a, b) => {
                let d = value(b)?;
                if d.re() == 0.0 {
                    return Err(self.error(b, "is zero, a division by zero,"));
                }
                value(a)? / d
            }
            Kind::Powi(a, n) => {
                let base = value(a)?;
                if n < 0 && base.re() == 0.0 {
                    return Err(self.error(a, "is zero under a negative power"));
                }
                base.powi(n)
            }
            Kind::Powf(a, y) => {
                let base = value(a)?;
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
            Kind::Call(f, a, b) => {
                let x = value(a)?;
                let second = || value(b.expect("two-argument functions have two"));
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
                        let y = x;
                        let x = second()?;
                        if x.re() == 0.0 && y.re() == 0.0 {
                            return Err(self.error(i, "has both arguments zero"));
                        }
                        atan2(y, x)
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
                        let y = second()?;
                        if x.re() == 0.0 && y.re() == 0.0 {
                            return Err(self
                                .error(i, "has both arguments zero, where it has no derivative,"));
                        }
                        (x * x + y * y).sqrt()
                    }
                    Function::Min => scalar::min(x, second()?),
                    Function::Max => scalar::max(x, second()?),
                }
            }
        })
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

/// The angle of `(x, y)` in `(-pi, pi]`, from `atan` of the smaller ratio so that neither
/// division is by a number near zero; its derivatives are atan's, the branch constants
/// having none.
fn atan2<D: Scalar>(y: D, x: D) -> D {
    if x.re().abs() >= y.re().abs() {
        let a = (y / x).atan();
        if x.re() > 0.0 {
            a
        } else if y.re() >= 0.0 {
            a + PI
        } else {
            a - PI
        }
    } else {
        let half = if y.re() > 0.0 { FRAC_PI_2 } else { -FRAC_PI_2 };
        -(x / y).atan() + half
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Token {
    Number(f64),
    Word,
    Symbol(char),
}

#[derive(Debug, Clone, Copy)]
struct Spanned {
    token: Token,
    start: usize,
    end: usize,
}

fn tokenize(text: &str) -> Result<Vec<Spanned>, ParseError> {
    let bytes = text.as_bytes();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let token = if c.is_ascii_digit() || c == b'.' {
            while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
                i += 1;
            }
            // an exponent: e or E, a sign, digits
            if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
                let mut j = i + 1;
                if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
                    j += 1;
                }
                if j < bytes.len() && bytes[j].is_ascii_digit() {
                    while j < bytes.len() && bytes[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let s = &text[start..i];
            match s.parse::<f64>() {
                Ok(v) => Token::Number(v),
                Err(_) => {
                    return Err(ParseError {
                        position: start,
                        message: format!("`{s}` is not a number"),
                    })
                }
            }
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            Token::Word
        } else if b"+-*/^(),".contains(&c) {
            i += 1;
            Token::Symbol(c as char)
        } else {
            let ch = text[start..].chars().next().unwrap_or('?');
            return Err(ParseError {
                position: start,
                message: format!(
                    "`{ch}` is not part of an expression (numbers, names, + - * / ^, \
                     parentheses and functions)"
                ),
            });
        };
        tokens.push(Spanned {
            token,
            start,
            end: i,
        });
    }
    Ok(tokens)
}

struct Parser<'a> {
    text: &'a str,
    tokens: Vec<Spanned>,
    at: usize,
    names: &'a [&'a str],
    nodes: Vec<Node>,
}

impl Parser<'_> {
    fn push(&mut self, kind: Kind, span: (usize, usize)) -> usize {
        self.nodes.push(Node { kind, span });
        self.nodes.len() - 1
    }

    fn span(&self, node: usize) -> (usize, usize) {
        self.nodes[node].span
    }

    fn peek_symbol(&self) -> Option<char> {
        match self.tokens.get(self.at)?.token {
            Token::Symbol(c) => Some(c),
            _ => None,
        }
    }

    /// Where the next token starts, or the end of the text.
    fn here(&self) -> usize {
        self.tokens
            .get(self.at)
            .map_or(self.text.len(), |t| t.start)
    }

    fn expected(&self, what: &str) -> ParseError {
        let found = match self.tokens.get(self.at) {
            Some(t) => format!("`{}`", &self.text[t.start..t.end]),
            None => "the end".to_string(),
        };
        ParseError {
            position: self.here(),
            message: format!("expected {what}, found {found}"),
        }
    }

    fn sum(&mut self) -> Result<usize, ParseError> {
        self.left_to_right(['+', '-'], Self::product)
    }

    fn product(&mut self) -> Result<usize, ParseError> {
        self.left_to_right(['*', '/'], Self::signed)
    }

    /// Operands of `operand` joined by the two operators `ops`, from the left.
    fn left_to_right(
        &mut self,
        ops: [char; 2],
        operand: fn(&mut Self) -> Result<usize, ParseError>,
    ) -> Result<usize, ParseError> {
        let mut left = operand(self)?;
        while let Some(op) = self.peek_symbol().filter(|c| ops.contains(c)) {
            self.at += 1;
            let right = operand(self)?;
            let span = (self.span(left).0, self.span(right).1);
            let kind = match op {
                '+' => Kind::Add(left, right),
                '-' => Kind::Sub(left, right),
                '*' => Kind::Mul(left, right),
                _ => Kind::Div(left, right),
            };
            left = self.push(kind, span);
        }
        Ok(left)
    }

    fn signed(&mut self) -> Result<usize, ParseError> {
        match self.peek_symbol() {
            Some(sign @ ('+' | '-')) => {
                let start = self.here();
                self.at += 1;
                let operand = self.signed()?;
                if sign == '+' {
                    return Ok(operand);
                }
                let span = (start, self.span(operand).1);
                Ok(self.push(Kind::Neg(operand), span))
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<usize, ParseError> {
        let base = self.primary()?;
        if self.peek_symbol() != Some('^') {
            return Ok(base);
        }
        self.at += 1;
        let exponent = self.signed()?;
        let span = (self.span(base).0, self.span(exponent).1);
        // the exponent must be a number: fold it
        let Some(y) = self.constant(exponent) else {
            let (a, b) = self.span(exponent);
            return Err(ParseError {
                position: a,
                message: format!(
                    "the exponent `{}` depends on the design: an exponent must be a number",
                    &self.text[a..b]
                ),
            });
        };
        let kind = if y.fract() == 0.0 && y.abs() <= i32::MAX as f64 {
            Kind::Powi(base, y as i32)
        } else {
            Kind::Powf(base, y)
        };
        Ok(self.push(kind, span))
    }

    /// The value of a sub-expression of numbers alone.
    fn constant(&self, node: usize) -> Option<f64> {
        let c = |n| self.constant(n);
        Some(match self.nodes[node].kind {
            Kind::Constant(v) => v,
            Kind::Name(_) | Kind::Call(..) => return None,
            Kind::Neg(a) => -c(a)?,
            Kind::Add(a, b) => c(a)? + c(b)?,
            Kind::Sub(a, b) => c(a)? - c(b)?,
            Kind::Mul(a, b) => c(a)? * c(b)?,
            Kind::Div(a, b) => c(a)? / c(b)?,
            Kind::Powi(a, n) => c(a)?.powi(n),
            Kind::Powf(a, y) => c(a)?.powf(y),
        })
        .filter(|v| v.is_finite())
    }

    fn primary(&mut self) -> Result<usize, ParseError> {
        let Some(&t) = self.tokens.get(self.at) else {
            return Err(self.expected("a number, a name or `(`"));
        };
        match t.token {
            Token::Number(v) => {
                self.at += 1;
                Ok(self.push(Kind::Constant(v), (t.start, t.end)))
            }
            Token::Symbol('(') => {
                self.at += 1;
                let inner = self.sum()?;
                if self.peek_symbol() != Some(')') {
                    return Err(self.expected("`)`"));
                }
                let end = self.tokens[self.at].end;
                self.at += 1;
                // the parentheses belong to the node's text, for errors
                self.nodes[inner].span = (t.start, end);
                Ok(inner)
            }
            Token::Word => {
                self.at += 1;
                let word = &self.text[t.start..t.end];
                if self.peek_symbol() == Some('(') {
                    return self.call(word, t.start);
                }
                if word == "pi" {
                    return Ok(self.push(Kind::Constant(PI), (t.start, t.end)));
                }
                match self.names.iter().position(|n| *n == word) {
                    Some(k) => Ok(self.push(Kind::Name(k), (t.start, t.end))),
                    None => Err(ParseError {
                        position: t.start,
                        message: if FUNCTIONS.iter().any(|(n, ..)| *n == word) {
                            format!("`{word}` is a function: write `{word}(...)`")
                        } else {
                            format!(
                                "unknown name `{word}`: the names here are {}",
                                list(self.names.iter().copied().chain(["pi"]))
                            )
                        },
                    }),
                }
            }
            Token::Symbol(_) => Err(self.expected("a number, a name or `(`")),
        }
    }

    fn call(&mut self, word: &str, start: usize) -> Result<usize, ParseError> {
        let Some(&(_, function, arity)) = FUNCTIONS.iter().find(|(n, ..)| *n == word) else {
            return Err(ParseError {
                position: start,
                message: format!(
                    "unknown function `{word}`: the functions are {}",
                    list(FUNCTIONS.iter().map(|(n, ..)| *n))
                ),
            });
        };
        self.at += 1; // (
        let mut args = vec![self.sum()?];
        while self.peek_symbol() == Some(',') {
            self.at += 1;
            args.push(self.sum()?);
        }
        if self.peek_symbol() != Some(')') {
            return Err(self.expected("`,` or `)`"));
        }
        let end = self.tokens[self.at].end;
        self.at += 1;
        if args.len() != arity {
            return Err(ParseError {
                position: start,
                message: format!(
                    "`{word}` takes {arity} argument{}, not {}",
                    if arity == 1 { "" } else { "s" },
                    args.len()
                ),
            });
        }
        Ok(self.push(
            Kind::Call(function, args[0], args.get(1).copied()),
            (start, end),
        ))
    }
}

fn list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scalar::Jet;
    use num_dual::Dual2SVec64;

    pub(super) const NAMES: [&str; 3] = ["l2", "delta2", "t"];

    fn value(text: &str, x: [f64; 3]) -> f64 {
        Expression::parse(text, &NAMES)
            .unwrap_or_else(|e| panic!("{text}: {e}"))
            .eval(&x)
            .unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    #[test]
    fn values_follow_the_usual_precedence() {
        let x = [2.0, 0.3, 0.5];
        let (l, d, t) = (x[0], x[1], x[2]);
        for (text, expected) in [
            ("1 + 2*3", 7.0),
            ("(1 + 2)*3", 9.0),
            ("-2^2", -4.0),
            ("2^3^2", 512.0),
            ("2^-1", 0.5),
            ("10 - 4 - 3", 3.0),
            ("12 / 3 / 2", 2.0),
            ("- -3", 3.0),
            ("+3 * -2", -6.0),
            ("1e-3 + .5 + 2.5E+2", 250.501),
            ("pi", PI),
            ("l2*cos(delta2)", l * d.cos()),
            ("l2 * sin(delta2) - t/2", l * d.sin() - t / 2.0),
            ("sqrt(l2^2 + t^2)", (l * l + t * t).sqrt()),
            ("hypot(l2, t)", l.hypot(t)),
            ("l2^0.5", l.sqrt()),
            ("t^(1/3)", t.cbrt()),
            ("tan(delta2)", d.tan()),
            ("asin(t) + acos(t)", FRAC_PI_2),
            ("atan(l2)", l.atan()),
            ("abs(t - l2)", (t - l).abs()),
            ("min(l2, t) + 10*max(l2, t)", t + 10.0 * l),
        ] {
            let v = value(text, x);
            assert!(
                (v - expected).abs() <= 1e-14 * expected.abs().max(1.0),
                "{text}: {v} against {expected}"
            );
        }
    }

    #[test]
    fn atan2_takes_each_quadrant() {
        for k in 0..72 {
            let angle = -PI + (k as f64 + 0.5) * PI / 36.0;
            for r in [1e-3, 1.0, 7.0] {
                let (y, x) = (r * angle.sin(), r * angle.cos());
                let v = value("atan2(l2, delta2)", [y, x, 0.0]);
                assert!((v - y.atan2(x)).abs() < 1e-14, "{angle}: {v}");
            }
        }
        // the axes
        for (y, x) in [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)] {
            assert_eq!(value("atan2(l2, delta2)", [y, x, 0.0]), f64::atan2(y, x));
        }
    }

    pub(super) const SMOOTH: [&str; 8] = [
        "l2*cos(delta2) - t/2",
        "sqrt(l2^2 + t^2) * sin(delta2)",
        "t^(1/3) / (l2 + 1)",
        "atan2(l2*sin(delta2), l2*cos(delta2) + t)",
        "hypot(l2 - t, 2*delta2) + tan(delta2)^2",
        "asin(t/l2) - acos(delta2)",
        "(l2 - t)^-2 * abs(delta2 - 1)",
        "max(l2, 3*t) * min(delta2, t)",
    ];

    /// Gradients by `Jet<3>` against central differences of the `f64` values, and
    /// Hessians by num-dual's second-order numbers against central differences of the
    /// gradients: one tree, every order.
    #[test]
    fn derivatives_of_every_order_agree_with_differences() {
        let x = [1.7, 0.4, 0.55];
        for text in SMOOTH {
            let e = Expression::parse(text, &NAMES).unwrap();
            let jet = |x: [f64; 3]| {
                let v: Vec<Jet<3>> = (0..3).map(|i| Jet::variable(x[i], i)).collect();
                e.eval(&v).unwrap()
            };
            let g = jet(x);
            assert_eq!(g.re, e.eval(&x).unwrap(), "{text}");
            let seeded: Vec<Dual2SVec64<3>> = (0..3)
                .map(|i| Dual2SVec64::from_re(x[i]).derivative(i))
                .collect();
            let second = e.eval(&seeded).unwrap();
            let first = second.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
            let hessian = second
                .v2
                .unwrap_generic(nalgebra::Const::<3>, nalgebra::Const::<3>);
            for i in 0..3 {
                let h = 1e-6 * x[i].abs().max(1.0);
                let (mut up, mut down) = (x, x);
                up[i] += h;
                down[i] -= h;
                let fd = (e.eval(&up).unwrap() - e.eval(&down).unwrap()) / (2.0 * h);
                let scale = g.grad[i].abs().max(1.0);
                assert!(
                    (g.grad[i] - fd).abs() < 1e-7 * scale,
                    "{text} d/d{i}: {} {fd}",
                    g.grad[i]
                );
                assert!((first[i] - g.grad[i]).abs() < 1e-12 * scale, "{text}");
                let (gu, gd) = (jet(up), jet(down));
                for j in 0..3 {
                    let fd2 = (gu.grad[j] - gd.grad[j]) / (2.0 * h);
                    let s = hessian[(i, j)].abs().max(1.0);
                    assert!(
                        (hessian[(i, j)] - fd2).abs() < 1e-6 * s,
                        "{text} d2/d{i}d{j}: {} {fd2}",
                        hessian[(i, j)]
                    );
                }
            }
        }
    }

    #[test]
    fn names_used_are_listed_once() {
        let e = Expression::parse("t*l2 + t^2 - pi", &NAMES).unwrap();
        assert_eq!(e.names_used(), [0, 2]);
        assert_eq!(e.source(), "t*l2 + t^2 - pi");
    }

    fn parse_error(text: &str) -> ParseError {
        Expression::parse(text, &NAMES).expect_err(text)
    }

    #[test]
    fn bad_text_is_refused_where_it_goes_wrong() {
        for (text, position, words) in [
            ("", 0, "empty"),
            ("   ", 0, "empty"),
            (
                "l3 * 2",
                0,
                "unknown name `l3`: the names here are `l2`, `delta2`, `t`, `pi`",
            ),
            ("2 * cosh(t)", 4, "unknown function `cosh`"),
            ("2 * sqrt", 4, "`sqrt` is a function"),
            ("(l2 + t", 7, "expected `)`, found the end"),
            ("l2 + * t", 5, "expected a number, a name or `(`, found `*`"),
            ("l2 t", 3, "`t` follows a complete expression"),
            ("l2 +", 4, "found the end"),
            ("2^t", 2, "the exponent `t` depends on the design"),
            ("atan2(l2)", 0, "`atan2` takes 2 arguments, not 1"),
            ("sin(l2, t)", 0, "`sin` takes 1 argument, not 2"),
            ("1.2.3", 0, "`1.2.3` is not a number"),
            ("l2 # 2", 3, "`#` is not part of an expression"),
            ("l2 = 2", 3, "`=` is not part of an expression"),
        ] {
            let e = parse_error(text);
            assert_eq!(e.position, position, "{text}: {e}");
            assert!(e.message.contains(words), "{text}: {e}");
        }
    }

    #[test]
    fn values_outside_a_functions_domain_name_the_sub_expression() {
        let at = |text: &str, x: [f64; 3]| -> String {
            Expression::parse(text, &NAMES)
                .unwrap()
                .eval(&x)
                .expect_err(text)
                .message
        };
        let x = [2.0, 0.5, 2.0];
        for (text, words) in [
            (
                "1 / (l2 - t)",
                "`(l2 - t)` is zero, a division by zero, at this design",
            ),
            ("(l2 - t)^-1", "`(l2 - t)` is zero under a negative power"),
            (
                "sqrt(delta2 - l2)",
                "`delta2 - l2` is -1.5, and a square root needs it at least 0",
            ),
            (
                "(delta2 - t)^0.5",
                "`(delta2 - t)` is -1.5 under the power 0.5",
            ),
            (
                "asin(l2)",
                "`l2` is 2, where asin needs it strictly between -1 and 1",
            ),
            (
                "atan2(l2 - t, 0)",
                "`atan2(l2 - t, 0)` has both arguments zero",
            ),
            ("10^400 * l2", "`10^400 * l2` is not a finite number"),
        ] {
            let m = at(text, x);
            assert!(m.contains(words), "{text}: {m}");
        }
        // the same through a dual number: the domain is the value's
        let e = Expression::parse("1 / (l2 - t)", &NAMES).unwrap();
        let v: Vec<Jet<3>> = (0..3).map(|i| Jet::variable(x[i], i)).collect();
        assert!(e.eval(&v).is_err());
    }
}
