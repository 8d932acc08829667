//! The expressions' reader: the text cut into numbers, words and symbols, then parsed by
//! recursive descent into the nodes of an [`Expression`], each sub-expression's span kept
//! for the messages.

use super::*;

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

/// The nodes of `text` in the order the parser pushed them, and the root's index; its names
/// must be among `names`.
pub(super) fn nodes(text: &str, names: &[&str]) -> Result<(Vec<Node>, usize), ParseError> {
    let mut p = Parser {
        text,
        tokens: tokenize(text)?,
        at: 0,
        names,
        nodes: Vec::new(),
        constants: Vec::new(),
        nesting: 0,
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
    Ok((p.nodes, root))
}

/// How many parentheses, calls, signs and exponents may stand one inside another: the
/// parser recurses once for each, on the reading thread's stack; a coordinate written by hand
/// nests a dozen. A long sum or product is read by a loop and evaluated by one pass over the
/// tree in post-order, so its length has no limit but the file's size.
pub const MAX_NESTING: usize = 100;

struct Parser<'a> {
    text: &'a str,
    tokens: Vec<Spanned>,
    at: usize,
    names: &'a [&'a str],
    nodes: Vec<Node>,
    /// Each node's value where it is made of numbers alone (finite), for an exponent.
    constants: Vec<Option<f64>>,
    /// How many parentheses, calls, signs and exponents the parser is inside.
    nesting: usize,
}

impl Parser<'_> {
    fn push(&mut self, kind: Kind, span: (usize, usize)) -> usize {
        let c = |n: usize| self.constants[n];
        let constant = match kind {
            Kind::Constant(v) => Some(v),
            Kind::Name(_) | Kind::Call(..) => None,
            Kind::Neg(a) => c(a).map(|x| -x),
            Kind::Add(a, b) => c(a).zip(c(b)).map(|(x, y)| x + y),
            Kind::Sub(a, b) => c(a).zip(c(b)).map(|(x, y)| x - y),
            Kind::Mul(a, b) => c(a).zip(c(b)).map(|(x, y)| x * y),
            Kind::Div(a, b) => c(a).zip(c(b)).map(|(x, y)| x / y),
            Kind::Powi(a, n) => c(a).map(|x| x.powi(n)),
            Kind::Powf(a, y) => c(a).map(|x| x.powf(y)),
        };
        self.constants.push(constant.filter(|v| v.is_finite()));
        self.nodes.push(Node { kind, span });
        self.nodes.len() - 1
    }

    fn too_deep(&self, position: usize) -> ParseError {
        ParseError {
            position,
            message: format!(
                "the expression nests too deep: at most {MAX_NESTING} parentheses, calls, \
                 signs and exponents one inside another"
            ),
        }
    }

    /// `f` one level deeper among the parentheses, calls, signs and exponents.
    fn nested<T>(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<T, ParseError>,
    ) -> Result<T, ParseError> {
        if self.nesting >= MAX_NESTING {
            return Err(self.too_deep(self.here()));
        }
        self.nesting += 1;
        let r = f(self);
        self.nesting -= 1;
        r
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
                let operand = self.nested(Self::signed)?;
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
        let exponent = self.nested(Self::signed)?;
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
        self.constants[node]
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
                let inner = self.nested(Self::sum)?;
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
                    return self.nested(|p| p.call(word, t.start));
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
