//! The tape's compiler: each expression's nodes in post-order, constants folded where `f64`
//! gives the scalar's number, and each distinct operation emitted once.

use std::collections::HashMap;

use super::super::{operands, pop, Expression, Function, Kind};
use super::{Code, Op};

/// A compiled sub-expression: a register, or a constant not yet placed in one.
#[derive(Debug, Clone, Copy)]
enum Value {
    Register(u32),
    Constant(f64),
}

pub(super) struct Compiler {
    pub(super) ops: Vec<Op>,
    pub(super) registers: u32,
    /// Each operation's register, by its code, operands and the constant's bits.
    seen: HashMap<(Code, u32, u32, u64), u32>,
}

impl Compiler {
    /// A compiler whose first `inputs` registers hold the names' values.
    pub(super) fn new(inputs: usize) -> Self {
        Compiler {
            ops: Vec::new(),
            registers: inputs as u32,
            seen: HashMap::new(),
        }
    }

    /// The register of an expression's value, compiled onto the tape.
    pub(super) fn output(&mut self, e: &Expression) -> u32 {
        let v = self.expression(e);
        self.register(v)
    }

    fn emit(&mut self, code: Code, a: u32, b: u32, c: f64) -> u32 {
        let key = (code, a, b, c.to_bits());
        if let Some(&r) = self.seen.get(&key) {
            return r;
        }
        let r = self.registers;
        self.ops.push(Op { code, a, b, c });
        self.registers += if code == Code::SinCos { 2 } else { 1 };
        self.seen.insert(key, r);
        r
    }

    fn register(&mut self, v: Value) -> u32 {
        match v {
            Value::Register(r) => r,
            Value::Constant(c) => self.emit(Code::Const, 0, 0, c),
        }
    }

    /// The expression's value: its nodes compiled in post-order, each operand's value taken
    /// from a stack, so the tree's depth never recurses.
    fn expression(&mut self, e: &Expression) -> Value {
        let mut stack = Vec::new();
        for node in &e.nodes {
            let (first, second) = operands(node.kind);
            // an operand the node lacks is never read
            let y = second.map_or(Value::Constant(0.0), |_| pop(&mut stack));
            let x = first.map_or(Value::Constant(0.0), |_| pop(&mut stack));
            let v = self.node(node.kind, x, y);
            stack.push(v);
        }
        pop(&mut stack)
    }

    /// A node of `kind` whose operands' values are `x` and `y`.
    fn node(&mut self, kind: Kind, x: Value, y: Value) -> Value {
        use Value::{Constant as C, Register as R};
        let (code, a, b, c) = match kind {
            Kind::Constant(c) => return C(c),
            Kind::Name(k) => return R(k as u32),
            Kind::Neg(_) => match x {
                C(x) => return C(-x),
                R(a) => (Code::Neg, a, 0, 0.0),
            },
            Kind::Add(..) => match (x, y) {
                (C(x), C(y)) => return C(x + y),
                (R(a), C(y)) | (C(y), R(a)) => (Code::AddC, a, 0, y),
                (R(a), R(b)) => (Code::Add, a, b, 0.0),
            },
            Kind::Sub(..) => match (x, y) {
                (C(x), C(y)) => return C(x - y),
                (R(a), C(y)) => (Code::SubC, a, 0, y),
                (C(x), R(b)) => (Code::SubFrom, b, 0, x),
                (x, y) => {
                    let (a, b) = (self.register(x), self.register(y));
                    (Code::Sub, a, b, 0.0)
                }
            },
            Kind::Mul(..) => match (x, y) {
                (C(x), C(y)) => return C(x * y),
                (R(a), C(y)) | (C(y), R(a)) => (Code::MulC, a, 0, y),
                (R(a), R(b)) => (Code::Mul, a, b, 0.0),
            },
            // a quotient of constants is left to the scalar: a dual number divides by
            // multiplying with the reciprocal, which `f64` division does not round alike
            Kind::Div(..) => match (x, y) {
                (R(a), C(y)) if y != 0.0 => (Code::DivC, a, 0, y),
                (x, y) => {
                    let (a, b) = (self.register(x), self.register(y));
                    (Code::Div, a, b, 0.0)
                }
            },
            Kind::Powi(_, n) => (Code::Powi, self.register(x), n as u32, 0.0),
            Kind::Powf(_, y) => (Code::Powf, self.register(x), 0, y),
            Kind::Call(f, _, b) => {
                let x = self.register(x);
                let y = match b {
                    Some(_) => self.register(y),
                    None => 0,
                };
                match f {
                    Function::Sin => return R(self.emit(Code::SinCos, x, 0, 0.0)),
                    Function::Cos => return R(self.emit(Code::SinCos, x, 0, 0.0) + 1),
                    _ => (Code::Call(f), x, y, 0.0),
                }
            }
        };
        R(self.emit(code, a, b, c))
    }
}
