//! Many [`Expression`]s compiled together into one flat list of operations over registers:
//! a mechanism's coordinates repeat the same terms (`l2*cos(delta2)` begins every point
//! past hinge b), so each distinct operation is computed once for all of them, without a
//! tree walk or a `Result` per node.
//!
//! The tape computes exactly what [`Expression::eval`] computes, operation for operation
//! (the same [`Scalar`] methods on the same operands; the constants folded only where `f64`
//! arithmetic gives the same number as the scalar's, by sums, differences and products), so
//! that a design's values do not depend on which of the two evaluated it. Where a value
//! leaves a function's domain, [`Tape::run`] only says so: the caller asks the tree which
//! expression and why ([`Expression::eval`]'s message), a path taken once per failing
//! design.

mod compile;

use super::{asin_or_acos, Expression, Function};
use crate::model::scalar::atan2;
use crate::model::scalar::{self, Scalar};
use compile::Compiler;

/// Expressions compiled together: registers `0..inputs` hold the names' values, each
/// operation appends one register (two for [`Code::SinCos`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Tape {
    inputs: usize,
    ops: Vec<Op>,
    registers: usize,
    /// The register of each expression, in the order compiled.
    outputs: Vec<u32>,
    /// What [`Tape::run_in`] executes, from `ops` and `outputs`.
    plan: Plan,
}

/// The tape as [`Tape::run_in`] runs it: the constants written first, out of the dispatch;
/// the other operations, each with its register, in an order of their dependencies that
/// runs operations of one code together (the dispatch's indirect jump then mostly goes
/// where it went the last time, which a branch predictor guesses); the outputs' registers
/// to check once each.
#[derive(Debug, Clone, PartialEq)]
struct Plan {
    constants: Vec<(u32, f64)>,
    steps: Vec<Step>,
    checked: Vec<u32>,
}

/// An operation as [`Tape::run_in`] runs it, into register `r`: its code a plain byte, the
/// function of a [`Code::Call`] apart in `f`. The dispatch on [`Code`], whose `Call` holds
/// a [`Function`] in the same byte, decoded that byte before its jump, five instructions
/// an operation.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Step {
    r: u32,
    a: u32,
    b: u32,
    run: Run,
    f: Function,
    c: f64,
}

/// [`Code`] without [`Code::Const`] (written before the steps) and without the function of
/// [`Code::Call`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Run {
    Neg,
    Add,
    AddC,
    Sub,
    SubC,
    SubFrom,
    Mul,
    MulC,
    Div,
    DivC,
    Powi,
    Powf,
    SinCos,
    Call,
}

impl Step {
    /// Whether `b` is a register the step reads ([`Op::reads_b`]).
    fn reads_b(&self) -> bool {
        matches!(
            self.run,
            Run::Add | Run::Sub | Run::Mul | Run::Div | Run::Call
        )
    }

    fn new(r: u32, op: Op) -> Self {
        let (run, f) = match op.code {
            Code::Const => unreachable!("constants are written before the steps"),
            Code::Neg => (Run::Neg, Function::Sin),
            Code::Add => (Run::Add, Function::Sin),
            Code::AddC => (Run::AddC, Function::Sin),
            Code::Sub => (Run::Sub, Function::Sin),
            Code::SubC => (Run::SubC, Function::Sin),
            Code::SubFrom => (Run::SubFrom, Function::Sin),
            Code::Mul => (Run::Mul, Function::Sin),
            Code::MulC => (Run::MulC, Function::Sin),
            Code::Div => (Run::Div, Function::Sin),
            Code::DivC => (Run::DivC, Function::Sin),
            Code::Powi => (Run::Powi, Function::Sin),
            Code::Powf => (Run::Powf, Function::Sin),
            Code::SinCos => (Run::SinCos, Function::Sin),
            Code::Call(f) => (Run::Call, f),
        };
        Step {
            r,
            a: op.a,
            b: op.b,
            run,
            f,
            c: op.c,
        }
    }
}

impl Plan {
    fn new(inputs: usize, ops: &[Op], outputs: &[u32], registers: usize) -> Self {
        let mut constants = Vec::new();
        // each operation's register, and the operation that fills each register
        let mut filled_by = vec![usize::MAX; inputs];
        let mut at = Vec::with_capacity(ops.len());
        for (i, op) in ops.iter().enumerate() {
            at.push(filled_by.len() as u32);
            if op.code == Code::Const {
                constants.push((filled_by.len() as u32, op.c));
            }
            let width = if op.code == Code::SinCos { 2 } else { 1 };
            filled_by.extend(std::iter::repeat_n(i, width));
        }
        // the operations not yet placed, and how many of their operands are not yet filled
        let operands = |op: &Op| {
            let b = op.reads_b().then_some(op.b);
            [Some(op.a), b]
                .into_iter()
                .flatten()
                .map(|r| filled_by[r as usize])
                .filter(|&i| i != usize::MAX && ops[i].code != Code::Const)
        };
        let mut waiting: Vec<usize> = ops.iter().map(|op| operands(op).count()).collect();
        let mut readers = vec![Vec::new(); ops.len()];
        for (i, op) in ops.iter().enumerate() {
            for j in operands(op) {
                readers[j].push(i);
            }
        }
        let mut ready: Vec<usize> = (0..ops.len())
            .filter(|&i| waiting[i] == 0 && ops[i].code != Code::Const)
            .collect();
        let mut steps = Vec::with_capacity(ops.len());
        let mut last = None;
        while !ready.is_empty() {
            // the first ready operation of the last one's code, else the first ready one:
            // the compiled order where the codes allow nothing better
            let k = ready
                .iter()
                .position(|&i| Some(ops[i].code) == last)
                .unwrap_or(0);
            let i = ready.remove(k);
            last = Some(ops[i].code);
            steps.push(Step::new(at[i], ops[i]));
            for &j in &readers[i] {
                waiting[j] -= 1;
                if waiting[j] == 0 {
                    let place = ready.partition_point(|&r| r < j);
                    ready.insert(place, j);
                }
            }
        }
        // what `run_in` reads unchecked: every operand a register filled before its step, each
        // step's registers within the tape's (`registers`, the count `run_in` asserts its
        // buffer has: the compiler's, which must be the one the operations fill)
        assert_eq!(filled_by.len(), registers);
        for op in &steps {
            let width = if op.run == Run::SinCos { 2 } else { 1 };
            assert!(op.r as usize + width <= registers);
            assert!(op.a < op.r && (!op.reads_b() || op.b < op.r));
        }
        let mut checked: Vec<u32> = outputs.iter().copied().filter(|&o| o != DROPPED).collect();
        checked.sort_unstable();
        checked.dedup();
        Plan {
            constants,
            steps,
            checked,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Code {
    Const,
    Neg,
    Add,
    /// `a + c`
    AddC,
    Sub,
    /// `a - c`
    SubC,
    /// `c - a`
    SubFrom,
    Mul,
    /// `a * c`
    MulC,
    Div,
    /// `a / c`, `c` not zero
    DivC,
    /// `a^b`, `b` the exponent as `i32` bits
    Powi,
    /// `a^c`
    Powf,
    /// `sin a`, then `cos a` in the next register
    SinCos,
    /// Any other function of `a` (and `b`)
    Call(Function),
}

/// One operation: its code, its register operands `a`, `b` and its constant `c`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Op {
    code: Code,
    a: u32,
    b: u32,
    c: f64,
}

impl Op {
    /// Whether `b` is a register this operation reads (for [`Code::Powi`] it is the
    /// exponent; a function of one argument reads register 0 there, which is an input).
    fn reads_b(&self) -> bool {
        matches!(
            self.code,
            Code::Add | Code::Sub | Code::Mul | Code::Div | Code::Call(_)
        )
    }
}

/// [`Tape::only`]'s output of an expression it dropped.
const DROPPED: u32 = u32::MAX;

impl Tape {
    /// The expressions, each parsed against the same `inputs` names, compiled into one tape.
    pub fn compile<'a>(
        expressions: impl IntoIterator<Item = &'a Expression>,
        inputs: usize,
    ) -> Self {
        let mut c = Compiler::new(inputs);
        let outputs: Vec<u32> = expressions.into_iter().map(|e| c.output(e)).collect();
        let plan = Plan::new(inputs, &c.ops, &outputs, c.registers as usize);
        Tape {
            inputs,
            ops: c.ops,
            registers: c.registers as usize,
            outputs,
            plan,
        }
    }

    /// The tape of the expressions `keep` selects alone: the operations none of them reads
    /// dropped, the rest in their order (so each kept expression's value is the one the whole
    /// tape gives, bit for bit). A dropped expression's [`Tape::output`] is no register: an
    /// evaluation that needs only some of the expressions (a network's statics, not its
    /// outline) runs this one.
    pub fn only(&self, keep: impl Fn(usize) -> bool) -> Tape {
        // the operation that fills each register (inputs: none)
        let mut filled_by = vec![usize::MAX; self.registers];
        let mut r = self.inputs;
        for (i, op) in self.ops.iter().enumerate() {
            let width = if op.code == Code::SinCos { 2 } else { 1 };
            filled_by[r..r + width].fill(i);
            r += width;
        }
        let mut live = vec![false; self.ops.len()];
        let mark = |register: u32, live: &mut Vec<bool>| {
            if let Some(&i) = filled_by
                .get(register as usize)
                .filter(|&&i| i != usize::MAX)
            {
                live[i] = true;
            }
        };
        for (k, &o) in self.outputs.iter().enumerate() {
            if keep(k) {
                mark(o, &mut live);
            }
        }
        // the operands precede their operations: one sweep from the end marks them all
        for i in (0..self.ops.len()).rev() {
            if live[i] {
                let op = self.ops[i];
                mark(op.a, &mut live);
                if op.reads_b() {
                    mark(op.b, &mut live);
                }
            }
        }
        let mut renamed: Vec<u32> = (0..self.registers as u32).collect();
        let (mut ops, mut registers) = (Vec::new(), self.inputs as u32);
        let mut r = self.inputs;
        for (op, &live) in self.ops.iter().zip(&live) {
            let width = if op.code == Code::SinCos { 2 } else { 1 };
            if live {
                let mut kept = *op;
                kept.a = renamed[op.a as usize];
                if op.reads_b() {
                    kept.b = renamed[op.b as usize];
                }
                for w in 0..width {
                    renamed[r + w] = registers + w as u32;
                }
                registers += width as u32;
                ops.push(kept);
            }
            r += width;
        }
        let outputs: Vec<u32> = self
            .outputs
            .iter()
            .enumerate()
            .map(|(k, &o)| {
                if keep(k) {
                    renamed[o as usize]
                } else {
                    DROPPED
                }
            })
            .collect();
        let plan = Plan::new(self.inputs, &ops, &outputs, registers as usize);
        Tape {
            inputs: self.inputs,
            ops,
            registers: registers as usize,
            outputs,
            plan,
        }
    }

    /// The value of the `k`-th expression compiled where it is a constant.
    pub fn constant(&self, k: usize) -> Option<f64> {
        let mut r = self.inputs;
        let target = self.outputs[k] as usize;
        for op in &self.ops {
            if r == target {
                return (op.code == Code::Const).then_some(op.c);
            }
            r += if op.code == Code::SinCos { 2 } else { 1 };
        }
        None
    }

    /// The registers of the sine and the cosine of the `k`-th expression where the tape
    /// computes them (another expression takes them): a caller that needs them too reads
    /// them there, the same numbers, rather than forming them again.
    pub fn sin_cos_of(&self, k: usize) -> Option<(usize, usize)> {
        let target = *self.outputs.get(k)?;
        let mut r = self.inputs;
        for op in &self.ops {
            if op.code == Code::SinCos && op.a == target {
                return Some((r, r + 1));
            }
            r += if op.code == Code::SinCos { 2 } else { 1 };
        }
        None
    }

    /// How many registers [`Tape::run`] fills.
    pub fn registers(&self) -> usize {
        self.registers
    }

    /// The register of the `k`-th expression compiled.
    pub fn output(&self, k: usize) -> usize {
        self.outputs[k] as usize
    }

    /// Every register from the names' `values` into `registers`; false if a value left a
    /// function's domain or an expression's value is not finite, where
    /// [`Expression::eval`] tells which and why.
    pub fn run<D: Scalar>(&self, values: &[D], registers: &mut Vec<D>) -> bool {
        debug_assert_eq!(values.len(), self.inputs);
        self.inputs_mut(registers).copy_from_slice(values);
        self.run_in(registers)
    }

    /// The names' registers of `registers`, sized for this tape first (kept from one run to
    /// the next, so that a caller writes the names' values there in place, and the
    /// operations write theirs by index, without a push's capacity check or a copy).
    pub fn inputs_mut<'a, D: Scalar>(&self, registers: &'a mut Vec<D>) -> &'a mut [D] {
        if registers.len() != self.registers {
            registers.clear();
            registers.resize(self.registers, D::from(0.0));
        }
        &mut registers[..self.inputs]
    }

    /// [`Tape::run`] with the names' values already in [`Tape::inputs_mut`]. Each operation
    /// writes its register in place: built as a value and pushed, each `Jet<8>` was moved
    /// twice, and the moves and the push cost more than the operation's arithmetic.
    pub fn run_in<D: Scalar>(&self, registers: &mut [D]) -> bool {
        assert_eq!(registers.len(), self.registers);
        for &(r, c) in &self.plan.constants {
            registers[r as usize] = D::from(c);
        }
        let mut fine = true;
        for op in &self.plan.steps {
            // every operand's register is below the operation's own. Unchecked: `Plan::new`
            // asserts each operand read below the step's register and the step's registers
            // within the tape's, whose count `registers` has (asserted above). Checked, the
            // split and the reads cost about five instructions an operation, 160 an
            // evaluation of wei2017's network with gradients.
            // SAFETY: `op.r + 1 <= registers.len()` (`Plan::new`, and the assert above).
            let (done, rest) = unsafe { registers.split_at_mut_unchecked(op.r as usize) };
            // SAFETY: `op.a < op.r` and, where `b` is read, `op.b < op.r` (`Plan::new`), and
            // `done` holds the registers below `op.r`.
            let a = || unsafe { *done.get_unchecked(op.a as usize) };
            // SAFETY: as for `a`; `b` is called only by the codes `Step::reads_b` lists.
            let b = || unsafe { *done.get_unchecked(op.b as usize) };
            // each arm writes its register itself: a value the match returned went through a
            // temporary, one more copy of a `Jet<8>` per operation
            // SAFETY: `op.r + 1 <= registers.len()` (`Plan::new`), so `rest` is not empty.
            let out = unsafe { rest.get_unchecked_mut(0) };
            match op.run {
                Run::Neg => *out = -a(),
                Run::Add => *out = a() + b(),
                Run::AddC => *out = a() + op.c,
                Run::Sub => *out = a() - b(),
                Run::SubC => *out = a() - op.c,
                // as the tree computes it: the constant a scalar, a zero's sign kept
                Run::SubFrom => *out = D::from(op.c) - a(),
                Run::Mul => *out = a() * b(),
                Run::MulC => *out = a() * op.c,
                Run::Div => {
                    let d = b();
                    fine &= d.re() != 0.0;
                    *out = a() / d;
                }
                Run::DivC => *out = a() / op.c,
                Run::Powi => {
                    let (x, n) = (a(), op.b as i32);
                    fine &= !(n < 0 && x.re() == 0.0);
                    *out = x.powi(n);
                }
                Run::Powf => {
                    let x = a();
                    fine &= !(x.re() < 0.0 || (x.re() == 0.0 && op.c < 1.0));
                    *out = x.powf(op.c);
                }
                Run::SinCos => {
                    let (s, c) = a().sin_cos();
                    *out = s;
                    rest[1] = c;
                }
                Run::Call => *out = call(op.f, a(), b, &mut fine),
            }
        }
        // without a branch per output: each is checked, as all are finite but on failure
        self.plan
            .checked
            .iter()
            .fold(fine, |f, &o| f & registers[o as usize].re().is_finite())
    }

    /// How many names' values [`Tape::run`] reads.
    pub fn inputs(&self) -> usize {
        self.inputs
    }
}

/// Function `f` of `x` (and of `b()`, its second argument), `fine` cleared where a value
/// leaves its domain: the tape's rarer operations, out of its loop.
fn call<D: Scalar>(f: Function, x: D, b: impl Fn() -> D, fine: &mut bool) -> D {
    match f {
        // emitted as SinCos
        Function::Sin => x.sin(),
        Function::Cos => x.cos(),
        Function::Tan => {
            let (s, c) = x.sin_cos();
            *fine &= c.re() != 0.0;
            s / c
        }
        Function::Asin | Function::Acos => {
            *fine &= x.re().abs() < 1.0;
            asin_or_acos(x, f)
        }
        Function::Atan => x.atan(),
        Function::Atan2 => {
            let y = b();
            *fine &= !(x.re() == 0.0 && y.re() == 0.0);
            // the first argument is the ordinate
            atan2(x, y)
        }
        Function::Sqrt => {
            *fine &= x.re() >= 0.0;
            x.sqrt()
        }
        Function::Abs => x.abs(),
        Function::Hypot => {
            let y = b();
            *fine &= !(x.re() == 0.0 && y.re() == 0.0);
            (x * x + y * y).sqrt()
        }
        Function::Min => scalar::min(x, b()),
        Function::Max => scalar::max(x, b()),
    }
}

#[cfg(test)]
mod tests;
