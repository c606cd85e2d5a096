//! The viscoelastic operator of 000_92d54b11128ea1ec.txt, section 2.
//!
//! With a Kelvin-Voigt Young's modulus $\tilde E = E(1 + \lambda^{-1} D)$, $D = d/dt$,
//! $\lambda = E/\eta$, and a constant bulk modulus $K = E/(3(1-2\nu))$, the Poisson operator is
//! $\tilde\nu = 1/2 - \tilde E/(6K)$, and the plate operator is the rational function of $D$
//! $$\frac{\tilde E}{1-\tilde\nu^2} = \frac{-4E\lambda^2 (1+D/\lambda)}{(1-2\nu)^2 (D+\alpha)(D+\gamma)} .$$
//! The paper prints
//! $$\frac{\tilde E}{1-\tilde\nu^2} = E\zeta\,[1+\tfrac{\eta}{E}D]\,[\tilde L(\alpha)-\tilde L(\gamma)],
//!   \quad \alpha = \frac{-2(\nu+1)\lambda}{1-2\nu},\ \gamma = \frac{-2(\nu-1)\lambda}{1-2\nu},
//!   \ \zeta = \frac{1-2\nu}{4\lambda},$$
//! where $\tilde L(\delta)$, acting on functions that vanish at $t = 0$, is the transfer function
//! $1/(D+\delta)$. Both sides are built here as exact rational functions of $D$, $E$, $\nu$,
//! $\lambda$ and compared: the poles, the constant, the elastic limit $D \to 0$ and the physical
//! dimension.

use super::dims::{self, Dim, DimIssue};
use super::poly::{Poly, Sym, q, qi};
use super::ratfunc::RatFunc;

/// Everything the comparison of the operator computes.
#[derive(Clone, Debug)]
pub struct OperatorCheck {
    /// $\tilde E/(1-\tilde\nu^2)$ derived, as a rational function of $D$.
    pub derived: RatFunc,
    /// The printed operator, with $\tilde L(\delta) \to 1/(D+\delta)$.
    pub printed: RatFunc,
    /// The printed $\alpha$ and $\gamma$ are poles of the derived operator ($D = -\alpha, -\gamma$).
    pub poles_agree: bool,
    /// $c$ with derived $= c\,(1+D/\lambda)[1/(D+\alpha) - 1/(D+\gamma)]$ (free of $D$).
    pub derived_constant: RatFunc,
    /// The printed constant $E\zeta$.
    pub printed_constant: RatFunc,
    /// derived / printed (free of $D$ when only the constant is wrong).
    pub ratio: RatFunc,
    /// Derived operator at $D = 0$ (must be $E/(1-\nu^2)$).
    pub derived_elastic: RatFunc,
    /// Printed operator at $D = 0$.
    pub printed_elastic: RatFunc,
    /// $E/(1-\nu^2)$.
    pub elastic: RatFunc,
    /// Dimension of the derived operator.
    pub derived_dim: Result<Dim, DimIssue>,
    /// Dimension of the printed operator.
    pub printed_dim: Result<Dim, DimIssue>,
    /// The printed $\alpha$ as a function of $\nu$, $\lambda$.
    pub alpha: RatFunc,
    /// The printed $\gamma$.
    pub gamma: RatFunc,
}

fn r(c: i64) -> RatFunc {
    RatFunc::from_q(qi(c))
}

/// $\alpha$, $\gamma$, $\zeta$ as printed, in $\nu$ and $\lambda$.
pub fn printed_rates() -> (RatFunc, RatFunc, RatFunc) {
    let nu = RatFunc::sym("nu");
    let lam = RatFunc::sym("lambda");
    let one_m_2nu = &r(1) - &nu.scale(&qi(2));
    let alpha = (&(&nu + &r(1)) * &lam)
        .scale(&qi(-2))
        .div(&one_m_2nu)
        .expect("nz");
    let gamma = (&(&nu - &r(1)) * &lam)
        .scale(&qi(-2))
        .div(&one_m_2nu)
        .expect("nz");
    let zeta = one_m_2nu.div(&lam.scale(&qi(4))).expect("nz");
    (alpha, gamma, zeta)
}

/// Derives $\tilde E/(1-\tilde\nu^2)$ for the constant-bulk-modulus Kelvin-Voigt law.
pub fn derived_operator() -> RatFunc {
    let e = RatFunc::sym("E");
    let nu = RatFunc::sym("nu");
    let lam = RatFunc::sym("lambda");
    let d = RatFunc::sym("D");
    let e_tilde = &e * &(&r(1) + &d.div(&lam).expect("nz"));
    let bulk = e
        .div(&(&r(1) - &nu.scale(&qi(2))).scale(&qi(3)))
        .expect("nz");
    let nu_tilde = &RatFunc::from_q(q(1, 2)) - &e_tilde.div(&bulk.scale(&qi(6))).expect("nz");
    let denom = &r(1) - &(&nu_tilde * &nu_tilde);
    e_tilde
        .div(&denom)
        .expect("1 - nu~^2 is not identically zero")
}

/// Builds both operators and compares them.
pub fn check() -> OperatorCheck {
    let (alpha, gamma, zeta) = printed_rates();
    let e = RatFunc::sym("E");
    let lam = RatFunc::sym("lambda");
    let nu = RatFunc::sym("nu");
    let d = RatFunc::sym("D");
    let dsym = Sym::new("D");
    let kelvin = &r(1) + &d.div(&lam).expect("nz");
    let l_alpha = (&d + &alpha).inv().expect("nz");
    let l_gamma = (&d + &gamma).inv().expect("nz");
    let shape = &kelvin * &(&l_alpha - &l_gamma);
    let printed_constant = &e * &zeta;
    let printed = &printed_constant * &shape;
    let derived = derived_operator();
    let den = derived.denom();
    let at = |p: &Poly, v: &RatFunc| {
        RatFunc::from_poly(p.clone())
            .subst(dsym, v)
            .is_some_and(|x| x.is_zero())
    };
    let poles_agree = at(&den, &-&alpha) && at(&den, &-&gamma);
    let mut derived_constant = derived.div(&shape).expect("shape is non-zero");
    if !derived_constant.depends_on(dsym) {
        // an equal, visibly D-free form
        derived_constant = derived_constant
            .subst(dsym, &RatFunc::zero())
            .expect("finite");
    }
    let mut ratio = derived.div(&printed).expect("printed is non-zero");
    if !ratio.depends_on(dsym) {
        ratio = ratio.subst(dsym, &RatFunc::zero()).expect("finite");
    }
    let zero = RatFunc::zero();
    let derived_elastic = derived.subst(dsym, &zero).expect("finite at D = 0");
    let printed_elastic = printed.subst(dsym, &zero).expect("finite at D = 0");
    let elastic = e.div(&(&r(1) - &(&nu * &nu))).expect("nz");
    OperatorCheck {
        derived_dim: dims::dimension(&derived),
        printed_dim: dims::dimension(&printed),
        derived,
        printed,
        poles_agree,
        derived_constant,
        printed_constant,
        ratio,
        derived_elastic,
        printed_elastic,
        elastic,
        alpha,
        gamma,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_operator_has_elastic_limit_and_pressure_dimension() {
        // Independent reference: at D = 0 the operator is the elastic E/(1 - nu^2).
        let c = check();
        assert_eq!(c.derived_elastic, c.elastic);
        assert_eq!(c.derived_dim, Ok(Dim::PRESSURE));
        assert!(c.poles_agree);
        assert!(!c.derived_constant.depends_on(Sym::new("D")));
        assert!(c.derived.depends_on(Sym::new("D")));
    }

    #[test]
    fn derived_constant_is_minus_e_lambda_over_one_minus_two_nu() {
        // Closed form by hand: -4 E lambda^2/(1-2nu)^2 divided by (gamma - alpha) = 4 lambda/(1-2nu).
        let c = check();
        let nu = RatFunc::sym("nu");
        let expect = (&RatFunc::sym("E") * &RatFunc::sym("lambda"))
            .scale(&qi(-1))
            .div(&(&r(1) - &nu.scale(&qi(2))))
            .expect("nz");
        assert_eq!(c.derived_constant, expect);
    }
}
