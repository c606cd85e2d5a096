//! A formula compiled once to a flat stack program: the right-hand sides, events, jumps and
//! Jacobian entries of a text model ([`super`]) are evaluated millions of times, so they do not
//! walk a tree or allocate. Constant subtrees are folded when compiling (`2/pi`, `0*x` from a
//! symbolic derivative), powers with a constant exponent become `powi`, `sqrt` or `powi * sqrt`
//! (the Hertz force `z^(3/2)` is `z * sqrt(z)`, as the built-in model computes it), and the
//! stack lives on the Rust stack ([`MAX_DEPTH`] slots, checked when compiling).
//!
//! Written here: an expression-evaluator crate would bring its own parser and formula language;
//! ours is the claims files' ([`crate::algebra::expr`]), which the units check and the symbolic
//! Jacobian already read.

use crate::algebra::expr::{Calc, Expr, Func, Op};
use num_traits::ToPrimitive;

/// The deepest stack a compiled formula may need.
pub const MAX_DEPTH: usize = 48;

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Ins {
    Const(f64),
    Var(u32),
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    /// The top of the stack with a variable or a constant as the other operand (`x*k`: one
    /// instruction, not three); `R` when the operand is on the left (`k - x`, `k/x`).
    AddV(u32),
    SubV(u32),
    MulV(u32),
    DivV(u32),
    RSubV(u32),
    RDivV(u32),
    AddC(f64),
    MulC(f64),
    DivC(f64),
    RSubC(f64),
    RDivC(f64),
    /// `x^n`, integer `n`.
    Powi(i32),
    /// `x^(n + 1/2)` as `powi(x, n) * sqrt(x)`.
    PowHalf(i32),
    /// `x^c`, constant `c`.
    PowC(f64),
    /// `x^y`.
    Pow,
    Sqrt,
    Abs,
    Call(Func),
    /// `max(x, 0)` of a variable, as the reader writes it: `(x + |x|)/2` (one instruction for
    /// four, the same operations in the same order, so the same bits).
    RampV(u32),
    /// `max(x, 0)^(n + 1/2)` of a variable (the Hertz force's `max(z, 0)^(3/2)`).
    RampPowHalfV(u32, i32),
    /// `max(x, 0)^(1/2)` of a variable (the Hertz force's rate), and `max(x, 0)^(3/2)` (the
    /// force): the two powers evaluated with the power known, no choice among powers at run
    /// time.
    RampSqrtV(u32),
    RampPow32V(u32),
    /// `-(x*v)`: a product with a variable, negated (the `-k*F` of a restoring force: one
    /// instruction for two, the same operations in the same order).
    MulNegV(u32),
}

/// A compiled formula of the variables a slot map names.
#[derive(Clone, Debug)]
pub struct Program {
    pub(super) code: Vec<Ins>,
    /// The deepest stack it needs.
    depth: usize,
}

/// What a compiled subtree is: a constant (folded) or code.
enum Part {
    Const(f64),
    Code(Vec<Ins>, usize),
}

impl Part {
    fn into_code(self) -> (Vec<Ins>, usize) {
        match self {
            Part::Const(c) => (vec![Ins::Const(c)], 1),
            Part::Code(c, d) => (c, d),
        }
    }
}

/// The bits of 1.0 (a fold by an exact 1, not by a number near it).
const ONE: u64 = 0x3ff0_0000_0000_0000;

fn binary(op: Ins, a: Part, b: Part) -> Part {
    if let (Part::Const(x), Part::Const(y)) = (&a, &b) {
        return Part::Const(apply_bin(op, *x, *y));
    }
    // the folds a symbolic derivative needs (0*x, 1*x, x + 0); 0*x is 0 even where x is not
    // finite, as the derivative of a term that does not depend on the variable is
    match (op, &a, &b) {
        (Ins::Mul, Part::Const(z), _) | (Ins::Mul, _, Part::Const(z)) if *z == 0.0 => {
            return Part::Const(0.0);
        }
        (Ins::Mul, Part::Const(o), _) if o.to_bits() == ONE => return b,
        (Ins::Mul | Ins::Div, _, Part::Const(o)) if o.to_bits() == ONE => return a,
        (Ins::Add, Part::Const(z), _) if *z == 0.0 => return b,
        (Ins::Add | Ins::Sub, _, Part::Const(z)) if *z == 0.0 => return a,
        (Ins::Div, Part::Const(z), _) if *z == 0.0 => return Part::Const(0.0),
        _ => {}
    }
    let single = |p: &Part| match p {
        Part::Const(c) => Some(Ins::Const(*c)),
        Part::Code(c, _) if c.len() == 1 && matches!(c[0], Ins::Var(_)) => Some(c[0]),
        _ => None,
    };
    // the right operand a variable or a constant: one fused instruction after the left's code
    let fused = |op: Ins, x: Ins| -> Option<Ins> {
        Some(match (op, x) {
            (Ins::Add, Ins::Var(i)) => Ins::AddV(i),
            (Ins::Sub, Ins::Var(i)) => Ins::SubV(i),
            (Ins::Mul, Ins::Var(i)) => Ins::MulV(i),
            (Ins::Div, Ins::Var(i)) => Ins::DivV(i),
            (Ins::Add, Ins::Const(c)) => Ins::AddC(c),
            (Ins::Sub, Ins::Const(c)) => Ins::AddC(-c),
            (Ins::Mul, Ins::Const(c)) => Ins::MulC(c),
            (Ins::Div, Ins::Const(c)) => Ins::DivC(c),
            _ => return None,
        })
    };
    // the left operand a variable or a constant: the right's code, then the reversed form
    let reversed = |op: Ins, x: Ins| -> Option<Ins> {
        Some(match (op, x) {
            (Ins::Add, Ins::Var(i)) => Ins::AddV(i),
            (Ins::Mul, Ins::Var(i)) => Ins::MulV(i),
            (Ins::Sub, Ins::Var(i)) => Ins::RSubV(i),
            (Ins::Div, Ins::Var(i)) => Ins::RDivV(i),
            (Ins::Add, Ins::Const(c)) => Ins::AddC(c),
            (Ins::Mul, Ins::Const(c)) => Ins::MulC(c),
            (Ins::Sub, Ins::Const(c)) => Ins::RSubC(c),
            (Ins::Div, Ins::Const(c)) => Ins::RDivC(c),
            _ => return None,
        })
    };
    if let Some(f) = single(&b).and_then(|x| fused(op, x)) {
        let (mut ca, da) = a.into_code();
        ca.push(f);
        return Part::Code(ca, da);
    }
    if let Some(f) = single(&a).and_then(|x| reversed(op, x)) {
        let (mut cb, db) = b.into_code();
        cb.push(f);
        return Part::Code(cb, db);
    }
    // a negated variable times a formula (`-k*F`): the formula's code, then `*k` and the sign
    // (exact: a product does not depend on its order, a negation is exact)
    if let (Ins::Mul, Part::Code(ca, _)) = (op, &a)
        && let [Ins::Var(i), Ins::Neg] = ca.as_slice()
    {
        let i = *i;
        let (mut cb, db) = b.into_code();
        cb.extend([Ins::MulV(i), Ins::Neg]);
        return Part::Code(cb, db);
    }
    let (mut ca, da) = a.into_code();
    let (cb, db) = b.into_code();
    ca.extend(cb);
    ca.push(op);
    Part::Code(ca, da.max(db + 1))
}

/// Common forms fused into one instruction each, in place: `max(x, 0)` of a variable (as the
/// reader writes it, `(x + |x|)/2`), its half-integer powers, and a product with a variable
/// negated.
fn fuse(code: &mut Vec<Ins>) {
    let mut out: Vec<Ins> = Vec::with_capacity(code.len());
    for ins in code.drain(..) {
        out.push(ins);
        loop {
            let n = out.len();
            let fused = match out.as_slice() {
                [.., Ins::Var(i), Ins::Abs, Ins::AddV(j), Ins::DivC(two)]
                    if i == j && two.to_bits() == 2.0f64.to_bits() =>
                {
                    Some((4, Ins::RampV(*i)))
                }
                [.., Ins::RampV(i), Ins::PowHalf(k)] => Some((2, ramp_power(*i, *k))),
                [.., Ins::MulV(i), Ins::Neg] => Some((2, Ins::MulNegV(*i))),
                _ => None,
            };
            let Some((len, f)) = fused else { break };
            out.truncate(n - len);
            out.push(f);
        }
    }
    *code = out;
}

fn unary(ins: Ins, a: Part) -> Part {
    match a {
        Part::Const(x) => Part::Const(apply_un(ins, x)),
        Part::Code(mut c, d) => {
            c.push(ins);
            Part::Code(c, d)
        }
    }
}

impl Ins {
    /// The variable's slot the instruction reads, if it reads one.
    #[inline(always)]
    fn slot(self) -> Option<u32> {
        match self {
            Ins::Var(i)
            | Ins::AddV(i)
            | Ins::SubV(i)
            | Ins::MulV(i)
            | Ins::MulNegV(i)
            | Ins::DivV(i)
            | Ins::RSubV(i)
            | Ins::RDivV(i)
            | Ins::RampV(i)
            | Ins::RampPowHalfV(i, _)
            | Ins::RampSqrtV(i)
            | Ins::RampPow32V(i) => Some(i),
            _ => None,
        }
    }
}

/// One instruction of a program that never holds two values, on the value `acc`, with `var`
/// reading a variable's slot.
#[inline(always)]
fn apply1(ins: Ins, acc: f64, var: impl Fn(u32) -> f64) -> f64 {
    match ins {
        Ins::Const(c) => c,
        Ins::Var(i) => var(i),
        Ins::RampV(i) => ramp(var(i)),
        // `powi(r, 0) * sqrt(r)` and `powi(r, 1) * sqrt(r)` to the bit (`1 * s` is `s`)
        Ins::RampSqrtV(i) => ramp(var(i)).sqrt(),
        Ins::RampPow32V(i) => {
            let r = ramp(var(i));
            r * r.sqrt()
        }
        Ins::RampPowHalfV(i, n) => {
            let r = ramp(var(i));
            powi(r, n) * r.sqrt()
        }
        Ins::AddV(i) => acc + var(i),
        Ins::SubV(i) => acc - var(i),
        Ins::MulV(i) => acc * var(i),
        Ins::MulNegV(i) => -(acc * var(i)),
        Ins::DivV(i) => acc / var(i),
        Ins::RSubV(i) => var(i) - acc,
        Ins::RDivV(i) => var(i) / acc,
        Ins::AddC(c) => acc + c,
        Ins::MulC(c) => acc * c,
        Ins::DivC(c) => acc / c,
        Ins::RSubC(c) => c - acc,
        Ins::RDivC(c) => c / acc,
        Ins::Neg => -acc,
        Ins::Sqrt => acc.sqrt(),
        Ins::Abs => acc.abs(),
        Ins::Powi(n) => powi(acc, n),
        Ins::PowHalf(n) => powi(acc, n) * acc.sqrt(),
        other => apply_un(other, acc),
    }
}

/// One instruction of a one-register program at every point: `acc[p]` and the variable `x(p)`
/// ([`Program::eval_batch`]). One loop per common instruction (the match inside [`apply1`] then
/// folds away), the others through the same loop with the match inside.
#[inline(always)]
fn each_point(ins: Ins, acc: &mut [f64], x: impl Fn(usize) -> f64) {
    macro_rules! each {
        () => {
            for (p, a) in acc.iter_mut().enumerate() {
                *a = apply1(ins, *a, |_| x(p));
            }
        };
    }
    // every instruction named (no arm for "the rest"), each its own loop
    match ins {
        Ins::RampSqrtV(_) => each!(),
        Ins::RampPow32V(_) => each!(),
        Ins::RampPowHalfV(..) => each!(),
        Ins::RampV(_) => each!(),
        Ins::MulV(_) => each!(),
        Ins::MulNegV(_) => each!(),
        Ins::DivV(_) => each!(),
        Ins::AddV(_) => each!(),
        Ins::SubV(_) => each!(),
        Ins::RSubV(_) => each!(),
        Ins::RDivV(_) => each!(),
        Ins::MulC(_) => each!(),
        Ins::AddC(_) => each!(),
        Ins::DivC(_) => each!(),
        Ins::RSubC(_) => each!(),
        Ins::RDivC(_) => each!(),
        Ins::Neg => each!(),
        Ins::Sqrt => each!(),
        Ins::Abs => each!(),
        Ins::Powi(_) => each!(),
        Ins::PowHalf(_) => each!(),
        Ins::PowC(_) => each!(),
        Ins::Call(_) => each!(),
        Ins::Const(_) => each!(),
        Ins::Var(_) => each!(),
        // never in a one-register program (they take two values)
        Ins::Add | Ins::Sub | Ins::Mul | Ins::Div | Ins::Pow => each!(),
    }
}

fn apply_bin(op: Ins, x: f64, y: f64) -> f64 {
    match op {
        Ins::Add => x + y,
        Ins::Sub => x - y,
        Ins::Mul => x * y,
        Ins::Div => x / y,
        _ => x.powf(y),
    }
}

/// `max(x, 0)` as the reader writes it, `(x + |x|)/2`, to the bit, by cases: `x` itself for
/// `0 < x < 2^1023` (`x + x` and its half are exact there), infinity above (the sum
/// overflows), `+0` for zero of either sign and below, NaN for NaN and for `-inf` (`-inf + inf`).
/// On the chain of a step's stages, where each right side waits for the one before, the three
/// operations of the formula were a tenth of a Hertz step's time; a comparison is not on it.
#[inline(always)]
pub(super) fn ramp(x: f64) -> f64 {
    if x > 0.0 {
        if x < RAMP_OVERFLOW { x } else { f64::INFINITY }
    } else if x > f64::NEG_INFINITY {
        0.0
    } else {
        x + x.abs()
    }
}

/// 2^1023: from here on `x + x` overflows.
const RAMP_OVERFLOW: f64 = f64::from_bits(0x7fe0_0000_0000_0000);

/// The fused `max(x, 0)^(n + 1/2)` of variable `i`: its own instruction for the powers 1/2
/// and 3/2.
fn ramp_power(i: u32, n: i32) -> Ins {
    match n {
        0 => Ins::RampSqrtV(i),
        1 => Ins::RampPow32V(i),
        _ => Ins::RampPowHalfV(i, n),
    }
}

/// `x^n` by products for the small powers formulas use (no library call), `powi` beyond.
#[inline]
pub(super) fn powi(x: f64, n: i32) -> f64 {
    match n {
        0 => 1.0,
        1 => x,
        2 => x * x,
        3 => x * x * x,
        4 => {
            let x2 = x * x;
            x2 * x2
        }
        -1 => 1.0 / x,
        -2 => 1.0 / (x * x),
        _ => x.powi(n),
    }
}

fn apply_un(ins: Ins, x: f64) -> f64 {
    match ins {
        Ins::Neg => -x,
        Ins::Powi(n) => powi(x, n),
        Ins::PowHalf(n) => powi(x, n) * x.sqrt(),
        Ins::Sqrt => x.sqrt(),
        Ins::Abs => x.abs(),
        Ins::PowC(c) => x.powf(c),
        Ins::Call(f) => f.apply(x),
        _ => x,
    }
}

fn compile_part(e: &Expr, slot: &dyn Fn(&str) -> Option<usize>) -> Result<Part, String> {
    Ok(match e {
        Expr::Num(q) => Part::Const(q.to_f64().unwrap_or(f64::NAN)),
        Expr::Pi => Part::Const(std::f64::consts::PI),
        Expr::Sym(s) => {
            let i = slot(s).ok_or_else(|| format!("`{s}` is not a parameter, state or `t`"))?;
            Part::Code(vec![Ins::Var(i as u32)], 1)
        }
        Expr::Neg(a) => unary(Ins::Neg, compile_part(a, slot)?),
        Expr::Call(f, a) => {
            let ins = match f {
                Func::Sqrt => Ins::Sqrt,
                Func::Abs => Ins::Abs,
                f => Ins::Call(*f),
            };
            unary(ins, compile_part(a, slot)?)
        }
        Expr::Bin(Op::Pow, a, b) => {
            let base = compile_part(a, slot)?;
            match b.exact_constant() {
                Some(k) => {
                    let two_k = &k * crate::algebra::poly::Q::from_integer(2.into());
                    let small = |v: &crate::algebra::poly::Q| {
                        v.is_integer() && v.to_integer().to_i32().is_some_and(|n| n.abs() <= 64)
                    };
                    if small(&k) {
                        unary(Ins::Powi(k.to_integer().to_i32().unwrap_or(0)), base)
                    } else if small(&two_k) {
                        // k = n + 1/2 with n = (2k - 1)/2
                        let n = (two_k.to_integer().to_i32().unwrap_or(0) - 1) / 2;
                        unary(Ins::PowHalf(n), base)
                    } else {
                        unary(Ins::PowC(k.to_f64().unwrap_or(f64::NAN)), base)
                    }
                }
                None => binary(Ins::Pow, base, compile_part(b, slot)?),
            }
        }
        Expr::Bin(op, a, b) => {
            let ins = match op {
                Op::Add => Ins::Add,
                Op::Sub => Ins::Sub,
                Op::Mul => Ins::Mul,
                _ => Ins::Div,
            };
            binary(ins, compile_part(a, slot)?, compile_part(b, slot)?)
        }
        Expr::Calc(
            Calc::Diff
            | Calc::At
            | Calc::Sum
            | Calc::Prod
            | Calc::Max
            | Calc::Min
            | Calc::Lim
            | Calc::Mean
            | Calc::Region
            | Calc::Marked,
            ..,
        ) => compile_part(&e.lower()?, slot)?,
        Expr::Calc(Calc::Int, ..) => {
            return Err(format!(
                "`{e}`: `int` is not allowed in a model's formulas (write the integral as a state)"
            ));
        }
    })
}

impl Program {
    /// Compiles `e`; `slot` gives each name's index in the variables [`Program::eval`] reads.
    pub fn compile(e: &Expr, slot: &dyn Fn(&str) -> Option<usize>) -> Result<Program, String> {
        let (mut code, depth) = compile_part(e, slot)?.into_code();
        fuse(&mut code);
        if depth > MAX_DEPTH {
            return Err(format!(
                "`{e}` nests too deeply for a compiled formula ({depth} > {MAX_DEPTH} stack slots): name a part of it in [definitions]"
            ));
        }
        Ok(Program { code, depth })
    }

    /// The constant value, if the formula folded to one.
    pub fn constant(&self) -> Option<f64> {
        match self.code.as_slice() {
            [Ins::Const(c)] => Some(*c),
            _ => None,
        }
    }

    /// The variable's slot, if the formula is a bare variable (an event `when = "z"`).
    #[inline]
    pub fn variable(&self) -> Option<usize> {
        match self.code.as_slice() {
            [Ins::Var(i)] => usize::try_from(*i).ok(),
            _ => None,
        }
    }

    /// A program that is the constant `c`.
    pub fn from_constant(c: f64) -> Program {
        Program {
            code: vec![Ins::Const(c)],
            depth: 1,
        }
    }

    /// The value at `vars` (indexed as the slot map of [`Program::compile`] said). The stack is
    /// an array on the Rust stack sized to the program (no allocation, and no long array to
    /// clear for a short formula).
    #[inline(always)]
    pub fn eval(&self, vars: &[f64]) -> f64 {
        // a bare variable or constant (`z' = v`) without the stack machine
        match self.code.as_slice() {
            [Ins::Var(i)] => return vars[*i as usize],
            [Ins::Const(c)] => return *c,
            _ => {}
        }
        match self.depth {
            0 | 1 => self.run1(vars),
            2..=8 => self.run::<8>(vars),
            9..=16 => self.run::<16>(vars),
            _ => self.run::<MAX_DEPTH>(vars),
        }
    }

    /// A program that never holds two values (a value, then operations on it with variables
    /// and constants: `k*max(z, 0)^(3/2)/m`) in one register, without the stack.
    #[inline(always)]
    fn run1(&self, vars: &[f64]) -> f64 {
        let mut acc = 0.0;
        for ins in &self.code {
            acc = apply1(*ins, acc, |i| vars[i as usize]);
        }
        acc
    }

    /// Whether [`Program::eval_batch`] takes this program (one that never holds two values).
    pub fn batchable(&self) -> bool {
        self.depth <= 1
    }

    /// The values at several points at once, each instruction applied to every point before the
    /// next (one pass of the dispatch for all points): point `p` has `t = ts[p]`, the state
    /// `ys[p n .. (p + 1) n]`, and the other variables (parameters) of `base` (the slots of
    /// [`Program::compile`]: `t`, then the `n` states, then the rest). The same operations in
    /// the same order as [`Program::eval`] at each point, so the same bits. Only for a
    /// [`Program::batchable`] program.
    pub fn eval_batch(&self, base: &[f64], n: usize, ts: &[f64], ys: &[f64], out: &mut [f64]) {
        debug_assert!(self.batchable() && ys.len() == ts.len() * n && out.len() == ts.len());
        out.fill(0.0);
        for &ins in &self.code {
            // the variable an instruction reads, from where it lives: `t`, every n-th entry of
            // the states (no gathering into a column first), or a parameter (one number)
            match ins.slot().map(|i| i as usize) {
                Some(0) => each_point(ins, out, |p| ts[p]),
                Some(i) if i <= n => each_point(ins, out, |p| ys[p * n + i - 1]),
                Some(i) => {
                    let x = base[i];
                    each_point(ins, out, |_| x);
                }
                None => each_point(ins, out, |_| 0.0),
            }
        }
    }

    #[inline]
    fn run<const D: usize>(&self, vars: &[f64]) -> f64 {
        let mut st = [0.0f64; D];
        let mut sp = 0usize;
        for ins in &self.code {
            match *ins {
                Ins::Const(c) => {
                    st[sp] = c;
                    sp += 1;
                }
                Ins::Var(i) => {
                    st[sp] = vars[i as usize];
                    sp += 1;
                }
                Ins::Add => {
                    sp -= 1;
                    st[sp - 1] += st[sp];
                }
                Ins::Sub => {
                    sp -= 1;
                    st[sp - 1] -= st[sp];
                }
                Ins::Mul => {
                    sp -= 1;
                    st[sp - 1] *= st[sp];
                }
                Ins::Div => {
                    sp -= 1;
                    st[sp - 1] /= st[sp];
                }
                Ins::Pow => {
                    sp -= 1;
                    st[sp - 1] = st[sp - 1].powf(st[sp]);
                }
                Ins::AddV(i) => st[sp - 1] += vars[i as usize],
                Ins::SubV(i) => st[sp - 1] -= vars[i as usize],
                Ins::MulV(i) => st[sp - 1] *= vars[i as usize],
                Ins::MulNegV(i) => st[sp - 1] = -(st[sp - 1] * vars[i as usize]),
                Ins::DivV(i) => st[sp - 1] /= vars[i as usize],
                Ins::RSubV(i) => st[sp - 1] = vars[i as usize] - st[sp - 1],
                Ins::RDivV(i) => st[sp - 1] = vars[i as usize] / st[sp - 1],
                Ins::AddC(c) => st[sp - 1] += c,
                Ins::MulC(c) => st[sp - 1] *= c,
                Ins::DivC(c) => st[sp - 1] /= c,
                Ins::RSubC(c) => st[sp - 1] = c - st[sp - 1],
                Ins::RDivC(c) => st[sp - 1] = c / st[sp - 1],
                Ins::Neg => st[sp - 1] = -st[sp - 1],
                Ins::Sqrt => st[sp - 1] = st[sp - 1].sqrt(),
                Ins::Abs => st[sp - 1] = st[sp - 1].abs(),
                Ins::Powi(n) => st[sp - 1] = powi(st[sp - 1], n),
                Ins::PowHalf(n) => {
                    let x = st[sp - 1];
                    st[sp - 1] = powi(x, n) * x.sqrt();
                }
                Ins::RampV(i) => {
                    st[sp] = ramp(vars[i as usize]);
                    sp += 1;
                }
                Ins::RampSqrtV(i) => {
                    st[sp] = ramp(vars[i as usize]).sqrt();
                    sp += 1;
                }
                Ins::RampPow32V(i) => {
                    let r = ramp(vars[i as usize]);
                    st[sp] = r * r.sqrt();
                    sp += 1;
                }
                Ins::RampPowHalfV(i, n) => {
                    let r = ramp(vars[i as usize]);
                    st[sp] = powi(r, n) * r.sqrt();
                    sp += 1;
                }
                _ => st[sp - 1] = apply_un(*ins, st[sp - 1]),
            }
        }
        st[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    fn run(text: &str, vars: &[f64]) -> f64 {
        let names = ["x", "y", "z"];
        let e = parse(text).expect("parses");
        let p = Program::compile(&e, &|s| names.iter().position(|n| *n == s)).expect("compiles");
        p.eval(vars)
    }

    /// A bare variable is one (the event tracker then reads the state itself); a constant or
    /// a formula with any operation on the variable is not.
    #[test]
    fn a_bare_variable_names_its_slot_and_nothing_else_does() {
        let names = ["t", "z", "v"];
        let slot = |s: &str| names.iter().position(|n| *n == s);
        let prog =
            |text: &str| Program::compile(&parse(text).expect("parses"), &slot).expect("compiles");
        assert_eq!(prog("z").variable(), Some(1));
        assert_eq!(prog("v").variable(), Some(2));
        for text in ["-z", "z - 0.5", "2*v", "1.5", "max(z, 0)", "z + v"] {
            assert_eq!(prog(text).variable(), None, "{text}");
        }
        // a bare variable and a constant evaluate without the stack machine, to the same bits
        let vars = [0.25, -3.5e-17, 7.0];
        assert_eq!(prog("v").eval(&vars).to_bits(), 7.0f64.to_bits());
        assert_eq!(prog("z").eval(&vars).to_bits(), (-3.5e-17f64).to_bits());
        assert_eq!(prog("1.5").eval(&vars).to_bits(), 1.5f64.to_bits());
        assert_eq!(prog("t*2").eval(&vars).to_bits(), 0.5f64.to_bits());
    }

    /// The Hertz force and the peak-force event compile to the fused instructions, in one
    /// register (depth 1), with the values of the forms they replace, to the bit.
    #[test]
    fn the_hertz_forms_fuse_to_one_instruction_each() {
        let names = ["t", "z", "v", "m", "k"];
        let slot = |s: &str| names.iter().position(|n| *n == s);
        let prog =
            |text: &str| Program::compile(&parse(text).expect("parses"), &slot).expect("compiles");
        let force = prog("-k*max(z, 0)^(3/2)/m");
        assert_eq!(
            force.code,
            [Ins::RampPow32V(1), Ins::MulNegV(4), Ins::DivV(3)]
        );
        assert_eq!(force.depth, 1);
        let rate = prog("k*max(z, 0)^(1/2)*v");
        assert_eq!(rate.code, [Ins::RampSqrtV(1), Ins::MulV(4), Ins::MulV(2)]);
        assert_eq!(prog("max(z, 0)").code, [Ins::RampV(1)]);
        for z in [0.3f64, 2.5e-5, 0.0, -0.0, -1e-9, 7.0] {
            let vars = [0.0, z, -1.25, 0.05, 3e8];
            // by hand: (z + |z|)/2 is max(z, 0); the power as z*sqrt(z)
            let r = (z + z.abs()) / 2.0;
            let want = -(r * r.sqrt() * 3e8) / 0.05;
            assert_eq!(force.eval(&vars).to_bits(), want.to_bits(), "z = {z}");
            let want = r.sqrt() * 3e8 * -1.25;
            assert_eq!(rate.eval(&vars).to_bits(), want.to_bits(), "z = {z}");
        }
        assert!(force.eval(&[0.0, f64::NAN, 1.0, 1.0, 1.0]).is_nan());
    }

    #[test]
    fn a_program_gives_the_trees_value() {
        // the reference is the tree walk of the same formula (Expr::eval)
        let vars = [0.7, -1.3, 2.5];
        for text in [
            "x + y*z - x/z",
            "-x^2 + z^(3/2) - z^(-1/2) + z^(5/2) + x^0.3",
            "max(y, 0) + min(x, z) + abs(y) + sign(y) + heaviside(x - 1)",
            "sin(x)*exp(-y) + sqrt(z)/(1 + x^2)^3 + z^x",
            "2/pi*x + 0*y + 1*z - (y - 0)",
            "gamma(z) + erf(x) + beta(x, z)",
            "3/(x + y) - 2/(z*x) + 5 - (x + z)",
            // the fused forms: max(., 0) of a variable, its half-integer powers, a negated
            // variable times a formula (one register, no stack)
            "-x*max(z, 0)^(3/2)/y + x*max(y, 0)^(1/2)*z",
            "max(z, 0)^(5/2) - max(y, 0)^(3/2) + max(x, 0)",
            "-z*(x + y)",
            // a negated product with a variable, alone and inside a two-value program
            "-(z*y) + 1",
            "(x + y)*-(z*y) - x",
        ] {
            let e = parse(text).expect("parses");
            let names = ["x", "y", "z"];
            let tree = e
                .eval(&|s| names.iter().position(|n| *n == s).map(|i| vars[i]))
                .expect("evaluates");
            let flat = run(text, &vars);
            assert!(
                (flat - tree).abs() <= 1e-14 * tree.abs().max(1.0),
                "{text}: {flat} vs {tree}"
            );
        }
    }

    /// The ramp is `(x + |x|)/2` to the bit everywhere (the reference: that formula itself),
    /// at the ends of its short cut (`MAX/2`, the next number above it, `MAX`, the smallest
    /// subnormal), at zero of either sign, below zero, at the infinities and at NaN.
    #[test]
    fn the_ramp_is_the_readers_formula_to_the_bit() {
        let half = f64::MAX / 2.0;
        let above = f64::from_bits(half.to_bits() + 1);
        for x in [
            0.3,
            2.5e-5,
            half,
            above,
            f64::MAX,
            5e-324,
            f64::MIN_POSITIVE,
            0.0,
            -0.0,
            -1e-9,
            -5e-324,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let want = (x + x.abs()) / 2.0;
            assert_eq!(ramp(x).to_bits(), want.to_bits(), "x = {x:e}");
        }
        assert!(ramp(f64::NAN).is_nan());
        // above MAX/2 the sum overflows: the formula's infinity, not x
        assert_eq!(ramp(f64::MAX).to_bits(), f64::INFINITY.to_bits());
        assert_eq!(ramp(half).to_bits(), half.to_bits());
    }

    #[test]
    fn the_hertz_power_is_exact_and_max_with_zero_is_exact() {
        // z^(3/2) as z*sqrt(z), bit for bit as the built-in model computes it
        let z = 1.234_567e-4_f64;
        assert_eq!(
            run("z^(3/2)", &[0.0, 0.0, z]).to_bits(),
            (z * z.sqrt()).to_bits()
        );
        // max(-y, 0) is exactly -y for y < 0 and exactly 0 for y > 0
        assert_eq!(
            run("max(-y, 0)", &[0.0, -3.3e-17, 0.0]).to_bits(),
            3.3e-17_f64.to_bits()
        );
        assert_eq!(
            run("max(-y, 0)", &[0.0, 3.3e-17, 0.0]).to_bits(),
            0.0_f64.to_bits()
        );
    }

    #[test]
    fn folds_and_fused_instructions_leave_the_fewest_instructions() {
        // by hand: a product by 1, a quotient by 1, a sum with 0 are the bare variable; a
        // product or quotient by a constant, and with a variable, is one fused instruction after
        // the left operand; constants fold, in every operation and integer power
        let names = ["x", "y", "z"];
        let prog = |text: &str| {
            Program::compile(&parse(text).expect("parses"), &|s| {
                names.iter().position(|n| *n == s)
            })
            .expect("compiles")
        };
        for text in ["1*z", "z*1", "z/1", "z + 0", "0 + z", "z - 0"] {
            assert_eq!(prog(text).variable(), Some(2), "{text}");
        }
        assert_eq!(prog("z*2.5").code, vec![Ins::Var(2), Ins::MulC(2.5)]);
        assert_eq!(prog("z/4").code, vec![Ins::Var(2), Ins::DivC(4.0)]);
        assert_eq!(prog("2.5*z").code, vec![Ins::Const(2.5), Ins::MulV(2)]);
        assert_eq!(prog("z*x").code, vec![Ins::Var(2), Ins::MulV(0)]);
        assert_eq!(prog("z - 3").code, vec![Ins::Var(2), Ins::AddC(-3.0)]);
        for (text, value) in [
            ("7 - 3", 4.0),
            ("7/2", 3.5),
            ("7*3", 21.0),
            ("2^3", 8.0),
            ("3^2", 9.0),
            ("2^4", 16.0),
            ("2^(-2)", 0.25),
            ("2^(-1)", 0.5),
            ("2^5", 32.0),
            ("(5 - 3)^3", 8.0),
        ] {
            assert_eq!(prog(text).constant(), Some(value), "{text}");
        }
        // the integer powers of a variable, by products
        let vars = [1.5, -2.0, 3.0];
        for (text, value) in [
            ("z^2", 9.0),
            ("z^3", 27.0),
            ("z^4", 81.0),
            ("z^(-1)", 1.0 / 3.0),
            ("z^(-2)", 1.0 / 9.0),
            ("z^5", 243.0),
            ("z^0", 1.0),
            ("z^1", 3.0),
        ] {
            assert!((prog(text).eval(&vars) - value).abs() < 1e-13, "{text}");
        }
    }

    #[test]
    fn unknown_names_and_deep_formulas_are_refused() {
        let e = parse("x + q").expect("parses");
        let err = Program::compile(&e, &|s| (s == "x").then_some(0)).unwrap_err();
        assert!(err.contains("`q`"), "{err}");
        let deep = (0..60).fold("x".to_string(), |acc, _| format!("x + (x*{acc})"));
        let e = parse(&deep).expect("parses");
        let err = Program::compile(&e, &|s| (s == "x").then_some(0)).unwrap_err();
        assert!(err.contains("nests too deeply"), "{err}");
        // a constant formula folds to its value
        let e = parse("2/pi*3").expect("parses");
        let p = Program::compile(&e, &|_| None).expect("compiles");
        assert_eq!(p.constant(), Some(6.0 / std::f64::consts::PI));
    }

    /// A batch gives, at each point, the bits `eval` gives there (the reference: one point at a
    /// time through `eval`, with t, the state and the parameters written into the variables),
    /// for a program of every instruction a one-register program can hold, at more points than
    /// one chunk and with the state on both sides of zero; a two-value program is not batchable.
    #[test]
    fn a_batch_gives_the_bits_of_one_point_at_a_time() {
        let names = ["t", "z", "v", "m", "k"];
        let slot = |s: &str| names.iter().position(|n| *n == s);
        let prog =
            |text: &str| Program::compile(&parse(text).expect("parses"), &slot).expect("compiles");
        let texts = [
            "k*max(z, 0)^(1/2)*v",
            "-k*max(z, 0)^(3/2)/m",
            "max(z, 0) - t",
            "((z + m)*t - k)/v",
            "2.5 - 3/(v + 1)",
            "(1 - t)/z + 0.5",
            "sqrt(abs(z))^3*0.25",
            "sin((k - z)^(5/2))",
            "(v/3)^1.7",
            "t",
            "1.25",
        ];
        let (n, points) = (2, 21);
        let ts: Vec<f64> = (0..points).map(|p| 0.1 * p as f64 - 0.7).collect();
        let ys: Vec<f64> = (0..points)
            .flat_map(|p| [0.3 * (p as f64 - 9.5), 1.0 + 0.05 * p as f64])
            .collect();
        let base = [f64::NAN, f64::NAN, f64::NAN, 0.05, 3.0];
        for text in texts {
            let p = prog(text);
            assert!(p.batchable(), "{text}");
            let mut out = vec![f64::NAN; points];
            p.eval_batch(&base, n, &ts, &ys, &mut out);
            for q in 0..points {
                let vars = [ts[q], ys[2 * q], ys[2 * q + 1], base[3], base[4]];
                let one = p.eval(&vars);
                assert_eq!(
                    out[q].to_bits(),
                    one.to_bits(),
                    "{text} at point {q}: {one}"
                );
            }
        }
        assert!(!prog("(z + v)*(t - m)").batchable());
    }
}
