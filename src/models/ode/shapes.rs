//! Right sides of a shape the compiler sees whole: a text model whose formulas are one of a few
//! common shapes runs with a right side written in Rust for that shape, its parameters folded to
//! constants and the states it reads known when the step is compiled.
//!
//! Why: measured on the Hertz model's sweep (20,000 impacts, DOP853), the right side behind any
//! boundary the compiler cannot see through (a call of a closure, a program interpreted inside
//! the step, even the same formula written in Rust behind one call) cost the same, and a formula
//! inlined into the step 0.64x of that; the state's index known when compiling, a further tenth.
//! So the shapes that dominate impact models, a position whose rate is the other state and a
//! contact force of it (`z' = v`, `v' = -k*max(z, 0)^(3/2)/m`), each get a stepper of their
//! own, and an event's formula of a known shape (the Hertz force's rate) a closure of its own.
//! Everything else runs as before ([`super::closures`]).
//!
//! The same operations in the same order as [`super::program::Program::eval`]: the same bits,
//! with a parameter read as the constant it is for the run.

use super::program::{Ins, Program, ramp};
use super::{EventFn, OdeScene};
use crate::integrate::{IntegrateError, Method, OdeSystem, Options, Solution};

/// What a run integrates: a system, its switches held, and the solver it runs with.
pub(super) trait Integrated: OdeSystem {
    /// Sets the held values (each switch's side) from `(t, y)`.
    fn set_held(&mut self, t: f64, y: &[f64]);
    /// Integrates from `(t0, y0)` to `t_end` (or a terminal event).
    fn solve(
        &self,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        opts: &Options,
    ) -> Result<Solution, IntegrateError>;
}

/// What runs a model once its system is built, for every system type (a generic method: Rust
/// has no generic closures).
pub(super) trait Runner {
    type Out;
    fn run<S: Integrated>(&self, sys: S) -> Self::Out;
}

/// A formula's instruction with the parameters folded in, reading (of two states) the one named.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Folded {
    Y(usize),
    Ramp(usize),
    RampSqrt(usize),
    RampPow32(usize),
    MulNeg(f64),
    Mul(f64),
    MulY(usize),
    Div(f64),
}

/// The `K` instructions of `code` over `n` states and the parameters `params`, folded (no
/// allocation: this runs for every run of a sweep); `None` when there are not `K` or one of them
/// reads `t` or a held value, or is not among [`Folded`]'s.
fn fold<const K: usize>(code: &[Ins], n: usize, params: &[f64]) -> Option<[Folded; K]> {
    let state = |i: u32| (1..=n).contains(&(i as usize)).then(|| i as usize - 1);
    let param = |i: u32| {
        (i as usize)
            .checked_sub(1 + n)
            .and_then(|j| params.get(j).copied())
    };
    if code.len() != K {
        return None;
    }
    let mut out = [Folded::Y(0); K];
    for (o, ins) in out.iter_mut().zip(code) {
        *o = match *ins {
            Ins::Var(i) => state(i).map(Folded::Y),
            Ins::RampV(i) => state(i).map(Folded::Ramp),
            Ins::RampSqrtV(i) => state(i).map(Folded::RampSqrt),
            Ins::RampPow32V(i) => state(i).map(Folded::RampPow32),
            Ins::MulNegV(i) => param(i).map(Folded::MulNeg),
            Ins::MulV(i) => state(i)
                .map(Folded::MulY)
                .or_else(|| param(i).map(Folded::Mul)),
            Ins::MulC(c) => Some(Folded::Mul(c)),
            Ins::DivV(i) => param(i).map(Folded::Div),
            _ => None,
        }?;
    }
    Some(out)
}

/// One instruction of a chain, its kind (and the state it reads) in the type.
trait Link: Copy {
    fn apply(self, acc: f64, y: &[f64]) -> f64;
}

#[derive(Clone, Copy)]
struct Ramp<const I: usize>;
#[derive(Clone, Copy)]
struct RampSqrt<const I: usize>;
#[derive(Clone, Copy)]
struct RampPow32<const I: usize>;
#[derive(Clone, Copy)]
struct MulY<const I: usize>;
#[derive(Clone, Copy)]
struct MulNeg(f64);
#[derive(Clone, Copy)]
struct Mul(f64);
#[derive(Clone, Copy)]
struct Div(f64);

impl<const I: usize> Link for Ramp<I> {
    #[inline(always)]
    fn apply(self, _: f64, y: &[f64]) -> f64 {
        ramp(y[I])
    }
}
impl<const I: usize> Link for RampSqrt<I> {
    #[inline(always)]
    fn apply(self, _: f64, y: &[f64]) -> f64 {
        ramp(y[I]).sqrt()
    }
}
impl<const I: usize> Link for RampPow32<I> {
    #[inline(always)]
    fn apply(self, _: f64, y: &[f64]) -> f64 {
        let r = ramp(y[I]);
        r * r.sqrt()
    }
}
impl<const I: usize> Link for MulY<I> {
    #[inline(always)]
    fn apply(self, acc: f64, y: &[f64]) -> f64 {
        acc * y[I]
    }
}
impl Link for MulNeg {
    #[inline(always)]
    fn apply(self, acc: f64, _: &[f64]) -> f64 {
        -(acc * self.0)
    }
}
impl Link for Mul {
    #[inline(always)]
    fn apply(self, acc: f64, _: &[f64]) -> f64 {
        acc * self.0
    }
}
impl Link for Div {
    #[inline(always)]
    fn apply(self, acc: f64, _: &[f64]) -> f64 {
        acc / self.0
    }
}

/// Three instructions, one after the other on one value.
#[derive(Clone, Copy)]
struct Chain<A, B, C>(A, B, C);

impl<A: Link, B: Link, C: Link> Chain<A, B, C> {
    #[inline(always)]
    fn eval(self, y: &[f64]) -> f64 {
        let a = self.0.apply(0.0, y);
        let b = self.1.apply(a, y);
        self.2.apply(b, y)
    }
}

/// `y[Z]' = y[1 - Z]` (a position whose rate is the other state) and `y[1 - Z]' = f(y)`.
struct Oscillator<'a, const Z: usize, A, B, C> {
    f: Chain<A, B, C>,
    m: &'a OdeScene,
}

impl<const Z: usize, A: Link, B: Link, C: Link> OdeSystem for Oscillator<'_, Z, A, B, C> {
    fn dim(&self) -> usize {
        2
    }
    #[inline(always)]
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[Z] = y[1 - Z];
        dy[1 - Z] = self.f.eval(y);
    }
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        self.m.jacobian_held(&[], t, y, jac)
    }
}

impl<const Z: usize, A: Link, B: Link, C: Link> Integrated for Oscillator<'_, Z, A, B, C> {
    /// No switch: nothing held.
    fn set_held(&mut self, _t: f64, _y: &[f64]) {}
    fn solve(
        &self,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        opts: &Options,
    ) -> Result<Solution, IntegrateError> {
        crate::integrate::solve_dop853_pair(self, t0, y0, t_end, opts)
    }
}

/// The force laws of the catalogue, as folded instructions: `(law, position, constants)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Shape {
    /// `-k*max(z, 0)^(3/2)/m`: the Hertz contact.
    Hertz { z: usize, k: f64, m: f64 },
    /// `-k*max(z, 0)/m`: a linear contact spring.
    Linear { z: usize, k: f64, m: f64 },
}

/// The model's shape, if it is one of the catalogue: two states, a position whose rate is the
/// other state and a force law of the position; no switch; DOP853.
pub(super) fn shape(m: &OdeScene) -> Option<Shape> {
    if m.rhs.len() != 2 || !m.switches.is_empty() || m.solve.method != Method::Dop853 {
        return None;
    }
    let copy = |i: usize| fold::<1>(&m.rhs[i].code, 2, &m.params);
    // the position: its equation reads the other state
    let (z, f) = match (copy(0), copy(1)) {
        (Some([Folded::Y(1)]), _) => (0, 1),
        (_, Some([Folded::Y(0)])) => (1, 0),
        _ => return None,
    };
    let force = fold::<3>(&m.rhs[f].code, 2, &m.params)?;
    match force {
        [Folded::RampPow32(i), Folded::MulNeg(k), Folded::Div(m)] if i == z => {
            Some(Shape::Hertz { z, k, m })
        }
        [Folded::Ramp(i), Folded::MulNeg(k), Folded::Div(m)] if i == z => {
            Some(Shape::Linear { z, k, m })
        }
        _ => None,
    }
}

/// Runs `r` with the model's system of its shape ([`shape`]), if it has one.
pub(super) fn run_shaped<R: Runner>(m: &OdeScene, r: &R) -> Option<R::Out> {
    fn osc<const Z: usize, A: Link, B: Link, C: Link>(
        m: &OdeScene,
        f: Chain<A, B, C>,
    ) -> Oscillator<'_, Z, A, B, C> {
        Oscillator { f, m }
    }
    Some(match shape(m)? {
        Shape::Hertz { z: 0, k, m: mass } => r.run(osc::<0, _, _, _>(
            m,
            Chain(RampPow32::<0>, MulNeg(k), Div(mass)),
        )),
        Shape::Hertz { k, m: mass, .. } => r.run(osc::<1, _, _, _>(
            m,
            Chain(RampPow32::<1>, MulNeg(k), Div(mass)),
        )),
        Shape::Linear { z: 0, k, m: mass } => {
            r.run(osc::<0, _, _, _>(m, Chain(Ramp::<0>, MulNeg(k), Div(mass))))
        }
        Shape::Linear { k, m: mass, .. } => {
            r.run(osc::<1, _, _, _>(m, Chain(Ramp::<1>, MulNeg(k), Div(mass))))
        }
    })
}

/// An event's formula of two states as a closure of its shape, if it has one of the
/// catalogue's: `k*max(z, 0)^(1/2)*v` (the Hertz force's rate, over 3/2).
pub(super) fn event_fn<'a>(p: &Program, n: usize, params: &[f64]) -> Option<EventFn<'a>> {
    if n != 2 {
        return None;
    }
    fn boxed<'a, A: Link + 'a, B: Link + 'a, C: Link + 'a>(c: Chain<A, B, C>) -> EventFn<'a> {
        Box::new(move |_t, y| c.eval(y))
    }
    match fold::<3>(&p.code, n, params)? {
        [Folded::RampSqrt(0), Folded::Mul(k), Folded::MulY(1)] => {
            Some(boxed(Chain(RampSqrt::<0>, Mul(k), MulY::<1>)))
        }
        [Folded::RampSqrt(1), Folded::Mul(k), Folded::MulY(0)] => {
            Some(boxed(Chain(RampSqrt::<1>, Mul(k), MulY::<0>)))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::ode::Held;

    /// An impact scene: the position `x`, its rate `u`, the force `force`, the method; the
    /// stiffness `k` of a Hertz contact (N/m^1.5) unless the force has no power 3/2 (N/m).
    fn scene(x: &str, u: &str, force: &str, method: &str, v0: f64) -> OdeScene {
        let k_unit = if force.contains("3/2") {
            "N/m^1.5"
        } else {
            "N/m"
        };
        let text = format!(
            r#"model = "ode"
[parameters]
m = 0.05
k = 3e8
c = 2.0
[units]
t = "s"
m = "kg"
k = "{k_unit}"
c = "N*s/m"
{x} = "m"
{u} = "m/s"
[state]
{x} = 0.0
{u} = {v0:e}
[equations]
{x} = "{u}"
{u} = "{force}"
[[event]]
name = "contact-end"
when = "{x}"
direction = "down"
action = "stop"
[[event]]
name = "peak-force"
when = "k*max({x}, 0)^(1/2)*{u}"
direction = "down"
[outcome]
duration = "t@contact-end"
peak = "k*max({x}, 0)^(3/2)@peak-force"
[solve]
method = "{method}"
rtol = 1e-10
atol = 1e-16
t_end = 1.0
"#
        );
        let table: toml::Table = toml::from_str(&text).expect("toml");
        <OdeScene as crate::models::Model>::from_table(&table, "s.toml")
            .unwrap_or_else(|e| panic!("{e}\n{text}"))
    }

    /// Runs with the system it is given: the system's type and the outcome's JSON.
    struct Probe<'a>(&'a OdeScene);
    impl Runner for Probe<'_> {
        type Out = (String, String);
        fn run<S: Integrated>(&self, sys: S) -> (String, String) {
            let out = self.0.go_with(false, sys).expect("runs").0;
            let json = serde_json::to_string(&out).expect("serializes");
            (std::any::type_name::<S>().to_string(), json)
        }
    }

    /// `(2/5) B(2/5, 1/2)`: the Hertz impact's duration is `2 z_max/v0` times this
    /// (`z_max = (5 m v0^2/(4 k))^(2/5)`), from the energy integral.
    fn hertz_factor() -> f64 {
        use statrs::function::gamma::gamma;
        0.4 * gamma(0.4) * gamma(0.5) / gamma(0.9)
    }

    /// The Hertz and the linear contact, the position first and second among the states (the
    /// states are in the order of their names), the outcome of the shape's own stepper is the
    /// general run's to the bit (the same formula's closures and [`crate::integrate::solve`]),
    /// and the contact's duration is the closed form's: `pi sqrt(m/k)` for the spring, the
    /// energy integral for Hertz. The degenerate start (no speed: no contact, no event) too.
    #[test]
    fn a_shaped_run_is_the_general_runs_to_the_bit() {
        let (m, k) = (0.05, 3e8);
        let hertz = "-k*max({x}, 0)^(3/2)/m";
        let linear = "-k*max({x}, 0)/m";
        // names: x before u sorts the position first; z after v, second
        for (x, u, z) in [("q", "w", 0), ("z", "v", 1)] {
            for (law, v0) in [(hertz, 1.0), (hertz, 0.0), (linear, 2.0), (linear, 0.0)] {
                let force = law.replace("{x}", x);
                let s = scene(x, u, &force, "dop853", v0);
                let want = if law != linear {
                    Shape::Hertz { z, k, m }
                } else {
                    Shape::Linear { z, k, m }
                };
                assert_eq!(shape(&s), Some(want), "{force}");
                let (ty, shaped) = run_shaped(&s, &Probe(&s)).expect("a shape");
                assert!(ty.contains("Oscillator"), "{ty}");
                let (ty, general) = Probe(&s).run(Held::new(&s));
                assert!(ty.contains("Held"), "{ty}");
                assert_eq!(shaped, general, "{force}, v0 = {v0}");
                let out: serde_json::Value = serde_json::from_str(&shaped).expect("json");
                let duration = out["outcome"]["duration"].as_f64();
                if v0 == 0.0 {
                    assert_eq!(duration, None, "{shaped}");
                    continue;
                }
                let exact = if law != linear {
                    let zmax = (5.0 * m * v0 * v0 / (4.0 * k)).powf(0.4);
                    2.0 * zmax / v0 * hertz_factor()
                } else {
                    std::f64::consts::PI * (m / k).sqrt()
                };
                let d = duration.expect("the contact ends");
                assert!((d - exact).abs() < 1e-8 * exact, "{d} against {exact}");
                // no damping: e = 1, the rebound at the speed it came in with (energy
                // conserved); the outcome `peak` is k z^(3/2) where the rate is zero, at the
                // largest indentation z_max: (5 m v0^2/(4 k))^(2/5) for Hertz, v0 sqrt(m/k)
                // for the spring
                let out_speed = out["state"][u].as_f64().expect("the rate at the end");
                assert!(
                    (out_speed + v0).abs() < 1e-7 * v0,
                    "{out_speed} against -{v0}"
                );
                let peak = out["outcome"]["peak"].as_f64().expect("the peak fires");
                let zmax = if law != linear {
                    (5.0 * m * v0 * v0 / (4.0 * k)).powf(0.4)
                } else {
                    v0 * (m / k).sqrt()
                };
                let force = k * zmax.powf(1.5);
                assert!(
                    zmax > 0.0 && (peak - force).abs() < 1e-7 * force,
                    "{peak} against {force}"
                );
            }
        }
    }

    /// Not of the catalogue, each for one reason: a damper (a second register), a switch, an
    /// implicit method, the force of the rate, a law of time.
    #[test]
    fn other_models_run_as_before() {
        for (force, method) in [
            ("-(k*max(z, 0) + c*v)/m", "dop853"),
            ("-k*z*sign(z)/m", "dop853"),
            ("-k*max(z, 0)^(3/2)/m", "radau5"),
            ("-c*max(v, 0)/m", "dop853"),
            ("-k*max(z, 0)^(3/2)/m*(t*c/m + 1)", "dop853"),
        ] {
            let s = scene("z", "v", force, method, 1.0);
            assert_eq!(shape(&s), None, "{force} {method}");
            assert!(run_shaped(&s, &Probe(&s)).is_none(), "{force} {method}");
        }
    }

    /// The event of the Hertz force's rate as a closure of its shape gives the program's bits
    /// (the reference: [`Program::eval`] on the variables in one buffer) on both sides of zero,
    /// at zero of either sign and at NaN, in either order of the states; other formulas, and
    /// three states, have none.
    #[test]
    fn a_shaped_event_gives_the_programs_bits() {
        use crate::algebra::expr::parse;
        // slots: t, two states, then k
        let compile = |text: &str, names: &[&str]| {
            let slot = |s: &str| names.iter().position(|n| *n == s);
            Program::compile(&parse(text).expect("parses"), &slot).expect("compiles")
        };
        let k = 3e8;
        for names in [["t", "z", "v", "k"], ["t", "v", "z", "k"]] {
            let p = compile("k*max(z, 0)^(1/2)*v", &names);
            let g = event_fn(&p, 2, &[k]).expect("a shape");
            for (a, b) in [
                (1e-4, -2.0),
                (-1e-4, 3.0),
                (0.0, 1.0),
                (-0.0, -1.0),
                (2.5, 0.0),
                (f64::NAN, 1.0),
                (1.0, f64::NAN),
            ] {
                let (t, y) = (0.5, [a, b]);
                let want = p.eval(&[t, y[0], y[1], k]);
                let got = g(t, &y);
                assert!(
                    got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                    "{names:?} at {y:?}: {got} against {want}"
                );
            }
        }
        // a constant written in the formula is folded as a parameter is
        let names = ["t", "z", "v", "k"];
        let p = compile("3e8*max(z, 0)^(1/2)*v", &names);
        let g = event_fn(&p, 2, &[k]).expect("a shape");
        let y = [2e-5, -0.75];
        assert_eq!(
            g(0.0, &y).to_bits(),
            p.eval(&[0.0, y[0], y[1], k]).to_bits()
        );
        for text in ["k*max(z, 0)^(3/2)*v", "k*max(z, 0)^(1/2)*z", "k*z*v", "z"] {
            let p = compile(text, &["t", "z", "v", "k"]);
            assert!(event_fn(&p, 2, &[k]).is_none(), "{text}");
        }
        let p = compile("k*max(z, 0)^(1/2)*v", &["t", "z", "v", "w", "k"]);
        assert!(event_fn(&p, 3, &[k]).is_none());
    }
}
