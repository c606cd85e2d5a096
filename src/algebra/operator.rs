//! The viscoelastic operator of 000_92d54b11128ea1ec.txt, section 2.
//!
//! With a Kelvin-Voigt Young's modulus $\tilde E = E(1 + \lambda^{-1} D)$, $D = d/dt$,
//! $\lambda = E/\eta$, and a constant bulk modulus $K = E/(3(1-2\nu))$, the Poisson operator is
//! $\tilde\nu = 1/2 - \tilde E/(6K)$, and the plate operator is the rational function of $D$
//! $$\frac{\tilde E}{1-\tilde\nu^2} = \frac{-4E\lambda^2 (1+D/\lambda)}{(1-2\nu)^2 (D+\alpha)(D+\gamma)} .$$
//! The paper prints $\tilde E/(1-\tilde\nu^2) = E\zeta\,[1+\tfrac{\eta}{E}D]\,[\tilde L(\alpha)-\tilde
//! L(\gamma)]$ with $\alpha$, $\gamma$, $\zeta$ in $\nu$ and $\lambda$, where $\tilde L(\delta)$, acting
//! on functions that vanish at $t = 0$, is the transfer function $1/(D+\delta)$. What it prints is
//! read from `verify/000_cone_plate.toml` (the claims of section 2); this module derives, as exact
//! rational functions of $D$, $E$, $\nu$, $\lambda$, what those claims compare it with: the
//! operator, its rates (the zeros of $1 \pm \tilde\nu$, each linear in $D$) and the constant $c$
//! of $c\,[1 + D/\lambda][\tilde L(\alpha) - \tilde L(\gamma)]$ at the derived rates.

use super::poly::{Sym, q, qi};
use super::ratfunc::RatFunc;

fn r(c: i64) -> RatFunc {
    RatFunc::from_q(qi(c))
}

/// $\tilde\nu = 1/2 - \tilde E/(6K)$ for the constant-bulk-modulus Kelvin-Voigt law, linear in $D$.
fn nu_tilde() -> RatFunc {
    let e = RatFunc::sym("E");
    let nu = RatFunc::sym("nu");
    let lam = RatFunc::sym("lambda");
    let d = RatFunc::sym("D");
    let e_tilde = &e * &(&r(1) + &d.div(&lam).expect("nz"));
    let bulk = e
        .div(&(&r(1) - &nu.scale(&qi(2))).scale(&qi(3)))
        .expect("nz");
    &RatFunc::from_q(q(1, 2)) - &e_tilde.div(&bulk.scale(&qi(6))).expect("nz")
}

/// Derives $\tilde E/(1-\tilde\nu^2)$ for the constant-bulk-modulus Kelvin-Voigt law.
pub fn derived_operator() -> RatFunc {
    let e = RatFunc::sym("E");
    let lam = RatFunc::sym("lambda");
    let d = RatFunc::sym("D");
    let e_tilde = &e * &(&r(1) + &d.div(&lam).expect("nz"));
    let nt = nu_tilde();
    let denom = &r(1) - &(&nt * &nt);
    e_tilde
        .div(&denom)
        .expect("1 - nu~^2 is not identically zero")
}

/// The rates $(\alpha, \gamma)$ of the derived operator: its poles are $D = -\alpha$, where
/// $1 + \tilde\nu = 0$, and $D = -\gamma$, where $1 - \tilde\nu = 0$ (the paper's naming: $\alpha$
/// carries $\nu + 1$). $\tilde\nu = u + vD$ is linear in $D$, so each zero is $-(u \pm 1)/v$.
pub fn derived_rates() -> (RatFunc, RatFunc) {
    let dsym = Sym::new("D");
    let nt = nu_tilde();
    let u = nt.subst(dsym, &RatFunc::zero()).expect("finite at D = 0");
    let v = &nt.subst(dsym, &r(1)).expect("finite at D = 1") - &u;
    debug_assert!(!v.depends_on(dsym), "nu~ is linear in D");
    // 1 + nu~ = 0 at D = -(1 + u)/v, so alpha = (1 + u)/v; 1 - nu~ = 0 at D = (1 - u)/v
    let alpha = (&r(1) + &u).div(&v).expect("nu~ depends on D");
    let gamma = (&u - &r(1)).div(&v).expect("nu~ depends on D");
    (alpha, gamma)
}

/// The constant $c$ with derived $= c\,(1+D/\lambda)[1/(D+\alpha) - 1/(D+\gamma)]$ at the derived
/// rates, by partial fractions (free of $D$).
pub fn derived_constant() -> RatFunc {
    let dsym = Sym::new("D");
    let (alpha, gamma) = derived_rates();
    let d = RatFunc::sym("D");
    let kelvin = &r(1) + &d.div(&RatFunc::sym("lambda")).expect("nz");
    let l_alpha = (&d + &alpha).inv().expect("nz");
    let l_gamma = (&d + &gamma).inv().expect("nz");
    let c = derived_operator()
        .div(&(&kelvin * &(&l_alpha - &l_gamma)))
        .expect("the shape is non-zero");
    debug_assert!(!c.depends_on(dsym), "the derived rates are the poles");
    // an equal, visibly D-free form
    c.subst(dsym, &RatFunc::zero()).expect("finite")
}

/// Whether the derived operator's poles are $D = -\alpha$ and $D = -\gamma$ for the given (printed)
/// rates: its denominator is $(D+\alpha)(D+\gamma)$ times a factor free of $D$ (so one rate
/// printed twice, a double pole, is not both).
pub fn poles_at(alpha: &RatFunc, gamma: &RatFunc) -> bool {
    let dsym = Sym::new("D");
    let d = RatFunc::sym("D");
    let den = RatFunc::from_poly(derived_operator().denom());
    den.div(&(&(&d + alpha) * &(&d + gamma)))
        .is_some_and(|rest| !rest.depends_on(dsym))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::dims::{self, Dim};

    fn nu() -> RatFunc {
        RatFunc::sym("nu")
    }

    fn one_m_2nu() -> RatFunc {
        &r(1) - &nu().scale(&qi(2))
    }

    #[test]
    fn derived_operator_has_elastic_limit_and_pressure_dimension() {
        // Independent reference: at D = 0 the operator is the elastic E/(1 - nu^2).
        let d = derived_operator();
        let at0 = d.subst(Sym::new("D"), &RatFunc::zero()).expect("finite");
        let elastic = RatFunc::sym("E")
            .div(&(&r(1) - &(&nu() * &nu())))
            .expect("nz");
        assert_eq!(at0, elastic);
        assert_eq!(dims::dimension(&d), Ok(Dim::PRESSURE));
        assert!(d.depends_on(Sym::new("D")));
    }

    #[test]
    fn derived_rates_are_the_hand_solved_zeros_of_one_plus_minus_nu_tilde() {
        // By hand: nu~ = [1 - (1-2nu)(1 + D/lambda)]/2, so 1 + nu~ = 0 at
        // D = 2(1+nu) lambda/(1-2nu) and 1 - nu~ = 0 at D = -2(1-nu) lambda/(1-2nu).
        let lam = RatFunc::sym("lambda");
        let (alpha, gamma) = derived_rates();
        let want_alpha = (&(&nu() + &r(1)) * &lam)
            .scale(&qi(-2))
            .div(&one_m_2nu())
            .expect("nz");
        let want_gamma = (&(&r(1) - &nu()) * &lam)
            .scale(&qi(2))
            .div(&one_m_2nu())
            .expect("nz");
        assert_eq!(alpha, want_alpha);
        assert_eq!(gamma, want_gamma);
        assert!(poles_at(&want_alpha, &want_gamma));
        // a misprinted rate (the sign of nu flipped) is not a pole
        let wrong = (&(&r(1) - &nu()) * &lam)
            .scale(&qi(-2))
            .div(&one_m_2nu())
            .expect("nz");
        assert!(!poles_at(&wrong, &want_gamma));
        assert!(!poles_at(&want_alpha, &want_alpha.scale(&qi(2))));
        // one pole printed twice is not both
        assert!(!poles_at(&want_alpha, &want_alpha));
    }

    #[test]
    fn derived_constant_is_minus_e_lambda_over_one_minus_two_nu() {
        // Closed form by hand: -4 E lambda^2/(1-2nu)^2 divided by (gamma - alpha) = 4 lambda/(1-2nu).
        let expect = (&RatFunc::sym("E") * &RatFunc::sym("lambda"))
            .scale(&qi(-1))
            .div(&one_m_2nu())
            .expect("nz");
        assert_eq!(derived_constant(), expect);
    }
}
