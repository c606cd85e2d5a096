//! A compiled formula ([`Program`]) as nested closures, for a text model's right sides: each
//! instruction a closure that calls the ones of its operands, each variable read where it lives
//! (the time, an entry of the state, or one of the other variables: parameters, held values).
//! The same operations in the same order as [`Program::eval`], so the same bits.
//!
//! Why not the stack program itself: a right side is evaluated at every stage of a step, and
//! each stage waits for the one before. Measured on the Hertz model's DOP853 steps (20,000
//! impacts, one thread), the program's dispatch loop took 1.7-1.8x the time of the same formula
//! written in Rust, and so did the formula written in Rust when it read the state back from
//! the buffer it had just been copied into; nested closures that read the state in place took
//! 1.36x. Written here: it is the formula language of [`crate::algebra::expr`].

use super::program::{Ins, Program, powi, ramp};

/// A right side at `(t, y, rest)`: the time, the state, the other variables in slot order.
pub type Slope = Box<dyn Fn(f64, &[f64], &[f64]) -> f64 + Send + Sync>;

/// Where a variable of slot `i` lives, for a model of `n` states (slots: `t`, the states, the
/// rest).
#[derive(Clone, Copy)]
enum Src {
    T,
    Y(usize),
    Rest(usize),
}

impl Src {
    fn of(i: u32, n: usize) -> Src {
        let i = i as usize;
        if i == 0 {
            Src::T
        } else if i <= n {
            Src::Y(i - 1)
        } else {
            Src::Rest(i - 1 - n)
        }
    }
}

/// `f` of the variable `s`.
fn read(s: Src, f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Slope {
    match s {
        Src::T => Box::new(move |t, _, _| f(t)),
        Src::Y(j) => Box::new(move |_, y, _| f(y[j])),
        Src::Rest(j) => Box::new(move |_, _, r| f(r[j])),
    }
}

/// `op(a, x)` with `x` the variable `s`.
fn with_var(a: Slope, s: Src, op: impl Fn(f64, f64) -> f64 + Send + Sync + 'static) -> Slope {
    match s {
        Src::T => Box::new(move |t, y, r| op(a(t, y, r), t)),
        Src::Y(j) => Box::new(move |t, y, r| op(a(t, y, r), y[j])),
        Src::Rest(j) => Box::new(move |t, y, r| op(a(t, y, r), r[j])),
    }
}

fn unary(a: Slope, op: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Slope {
    Box::new(move |t, y, r| op(a(t, y, r)))
}

fn binary(a: Slope, b: Slope, op: impl Fn(f64, f64) -> f64 + Send + Sync + 'static) -> Slope {
    Box::new(move |t, y, r| {
        let x = a(t, y, r);
        op(x, b(t, y, r))
    })
}

impl Program {
    /// The formula as nested closures, for a model of `n` states: `(t, y, rest)` with `rest` the
    /// variables after the states, in slot order.
    pub fn slope(&self, n: usize) -> Slope {
        let mut st: Vec<Slope> = Vec::with_capacity(self.code.len());
        // the top of the stack, replaced by `f` of it
        fn top(st: &mut Vec<Slope>, f: impl FnOnce(Slope) -> Slope) {
            if let Some(a) = st.pop() {
                st.push(f(a));
            }
        }
        fn two(st: &mut Vec<Slope>, op: impl Fn(f64, f64) -> f64 + Send + Sync + 'static) {
            if let (Some(b), Some(a)) = (st.pop(), st.pop()) {
                st.push(binary(a, b, op));
            }
        }
        for &ins in &self.code {
            let s = |i: u32| Src::of(i, n);
            match ins {
                Ins::Const(c) => st.push(Box::new(move |_, _, _| c)),
                Ins::Var(i) => st.push(read(s(i), |x| x)),
                Ins::RampV(i) => st.push(read(s(i), ramp)),
                Ins::RampSqrtV(i) => st.push(read(s(i), |x| ramp(x).sqrt())),
                Ins::RampPow32V(i) => st.push(read(s(i), |x| {
                    let r = ramp(x);
                    r * r.sqrt()
                })),
                Ins::RampPowHalfV(i, k) => st.push(read(s(i), move |x| {
                    let r = ramp(x);
                    powi(r, k) * r.sqrt()
                })),
                Ins::Neg => top(&mut st, |a| unary(a, |x| -x)),
                Ins::Sqrt => top(&mut st, |a| unary(a, f64::sqrt)),
                Ins::Abs => top(&mut st, |a| unary(a, f64::abs)),
                Ins::Powi(k) => top(&mut st, |a| unary(a, move |x| powi(x, k))),
                Ins::PowHalf(k) => top(&mut st, |a| unary(a, move |x| powi(x, k) * x.sqrt())),
                Ins::PowC(c) => top(&mut st, |a| unary(a, move |x| x.powf(c))),
                Ins::Call(f) => top(&mut st, |a| unary(a, move |x| f.apply(x))),
                Ins::AddC(c) => top(&mut st, |a| unary(a, move |x| x + c)),
                Ins::MulC(c) => top(&mut st, |a| unary(a, move |x| x * c)),
                Ins::DivC(c) => top(&mut st, |a| unary(a, move |x| x / c)),
                Ins::RSubC(c) => top(&mut st, |a| unary(a, move |x| c - x)),
                Ins::RDivC(c) => top(&mut st, |a| unary(a, move |x| c / x)),
                Ins::AddV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| a + x)),
                Ins::SubV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| a - x)),
                Ins::MulV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| a * x)),
                Ins::DivV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| a / x)),
                Ins::RSubV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| x - a)),
                Ins::RDivV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| x / a)),
                Ins::MulNegV(i) => top(&mut st, |a| with_var(a, s(i), |a, x| -(a * x))),
                Ins::Add => two(&mut st, |a, b| a + b),
                Ins::Sub => two(&mut st, |a, b| a - b),
                Ins::Mul => two(&mut st, |a, b| a * b),
                Ins::Div => two(&mut st, |a, b| a / b),
                Ins::Pow => two(&mut st, f64::powf),
            }
        }
        st.pop().unwrap_or_else(|| Box::new(|_, _, _| f64::NAN))
    }
}

#[cfg(test)]
mod tests {
    use crate::algebra::expr::parse;
    use crate::models::ode::program::Program;

    /// The closures give the stack program's bits (the reference: [`Program::eval`] on the
    /// variables written in one buffer) on formulas of every instruction, at points on both
    /// sides of zero, at zero of either sign and at NaN; a variable read from `t`, the state
    /// and the rest alike.
    #[test]
    fn the_closures_give_the_programs_bits() {
        // slots: t, the states z and v, the rest m and k
        let names = ["t", "z", "v", "m", "k"];
        let slot = |s: &str| names.iter().position(|n| *n == s);
        let texts = [
            "-k*max(z, 0)^(3/2)/m",
            "k*max(z, 0)^(1/2)*v",
            "max(z, 0)^(5/2) - max(v, 0)",
            "v",
            "t",
            "k",
            "1.5",
            "-z*(m + v) + t",
            "(z + v)*(t - m)/(k - z)",
            "k - z + (3 - v) - 2/(t + 1) + m/v",
            "(v + 1)/3 + 2*(z - t) + t*4 - z/k",
            "sqrt(abs(z))^3*0.25 - z^2 + v^(-1) + z^(3/2) + (z + 1)^0.3",
            "sin(z)*exp(-v) + (v/3)^1.7 + z^v + t^z",
            "-(z*v) + 1 - (k + m)*-(z*t)",
            "heaviside(z - 0.5) + sign(v)",
            "m - (z*v) + m/(z + v) - (2 - z*v) - (z + v) + -z",
        ];
        let points = [
            [0.25, 0.3, -1.25, 0.05, 3.0],
            [0.0, -2.0, 0.7, 2.0, 1.0e3],
            [1.5, 0.0, -0.0, 0.5, -7.0],
            [-0.5, -0.0, 2.5e-5, 1.0, 0.1],
            [0.1, f64::NAN, 1.0, 1.0, 1.0],
        ];
        let mut kinds = std::collections::BTreeSet::new();
        for text in texts {
            let p = Program::compile(&parse(text).expect("parses"), &slot).expect("compiles");
            kinds.extend(p.code.iter().map(|i| {
                let name = format!("{i:?}");
                name.split('(').next().unwrap_or_default().to_string()
            }));
            let f = p.slope(2);
            for vars in points {
                let want = p.eval(&vars);
                let got = f(vars[0], &vars[1..3], &vars[3..]);
                assert!(
                    got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                    "{text} at {vars:?}: {got} against {want}"
                );
            }
        }
        // every instruction the compiler makes is among the formulas above
        assert_eq!(kinds.len(), 30, "{kinds:?}");
    }
}
