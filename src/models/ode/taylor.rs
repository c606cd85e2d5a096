//! The exact Taylor series at t = 0 of a text model's solution.

use super::OdeScene;
use crate::algebra::expr::Expr;
use crate::algebra::ratfunc::RatFunc;

impl OdeScene {
    /// The Taylor polynomial at t = 0 of the solution's `state` to degree `order`, exact, in
    /// the parameters as symbols (their values play no part): the coefficients come from
    /// substituting the partial sums into the right sides, $a_{k+1} = [t^k] f(x(t), t)/(k+1)$,
    /// which is exact when every right side is a polynomial in the states and t with
    /// coefficients rational in the parameters, and every initial value rational in them.
    /// Anything else (a square root of a state, a state in a denominator, `heaviside`) is an
    /// error that says so: such a solution has no Taylor series of this kind at t = 0 in
    /// general.
    pub fn taylor(&self, state: &str, order: u32) -> Result<RatFunc, String> {
        use crate::algebra::poly::{Q, Sym};
        let c = &self.c;
        let which = c.states.iter().position(|s| s == state).ok_or_else(|| {
            format!(
                "`{state}` is not a state of this model; its states: {}",
                c.states.join(", ")
            )
        })?;
        if order > 24 {
            return Err(format!("order {order}: at most 24"));
        }
        let t = Sym::new("t");
        let rational = |e: &Expr, what: &str| -> Result<RatFunc, String> {
            e.lower()
                .ok()
                .and_then(|l| l.to_ratfunc())
                .ok_or_else(|| format!("{what} `{e}` is not rational in the states, t and the parameters: its Taylor series at t = 0 is not computed exactly"))
        };
        let mut x: Vec<RatFunc> = c
            .init_exprs
            .iter()
            .zip(&c.states)
            .map(|(e, s)| rational(e, &format!("the initial value of {s}")))
            .collect::<Result<_, _>>()?;
        let f: Vec<RatFunc> = c
            .rhs_exprs
            .iter()
            .zip(&c.states)
            .map(|(e, s)| rational(e, &format!("the equation of {s}")))
            .collect::<Result<_, _>>()?;
        for (rhs, s) in f.iter().zip(&c.states) {
            let poly_in = |v: Sym| rhs.denom().degree_in(v) == 0;
            if !poly_in(t) || !c.states.iter().all(|x| poly_in(Sym::new(x))) {
                return Err(format!(
                    "the equation of {s} has a state or t in a denominator: its Taylor series at t = 0 is not computed exactly"
                ));
            }
        }
        for k in 0..order {
            // f at the partial sums (degree k), to degree k in t: its t^k coefficient
            let mut next = Vec::with_capacity(x.len());
            for rhs in &f {
                let mut g = rhs.clone();
                for (s, xs) in c.states.iter().zip(&x) {
                    g = g
                        .subst(Sym::new(s), xs)
                        .ok_or_else(|| "a denominator vanishes".to_string())?;
                }
                let coeff = RatFunc::from_poly(g.numer().coeff_of(t, k))
                    .div(&RatFunc::from_poly(g.denom()))
                    .ok_or_else(|| "a denominator vanishes".to_string())?;
                let scale = Q::from_integer((i64::from(k) + 1).into()).recip();
                let power = RatFunc::sym("t")
                    .powi(i32::try_from(k + 1).unwrap_or(i32::MAX))
                    .ok_or_else(|| "a power of t".to_string())?;
                next.push(&coeff.scale(&scale) * &power);
            }
            for (xs, add) in x.iter_mut().zip(next) {
                *xs = &*xs + &add;
            }
        }
        Ok(x.swap_remove(which))
    }
}
