//! Checks of 000_92d54b11128ea1ec.txt: the operator of section 2, (13), (15)-(18), (21)-(23).
//!
//! Every verdict is the outcome of an exact comparison in [`crate::algebra`]; the detail quotes
//! the derived and printed expressions and their difference.

use super::kinds::NamedCheck;
use super::{NamedFn, Outcome, PaperClaims, VerifyError, holds, outcome};
use crate::algebra::identity21;
use crate::algebra::operator::{self, OperatorCheck};
use crate::algebra::poly::{Poly, Sym, q};
use crate::algebra::ratfunc::RatFunc;

/// Expensive exact results shared between claims.
pub struct Context {
    root: std::path::PathBuf,
    operator: Option<OperatorCheck>,
}

impl Context {
    /// A context reading scenes relative to `root`.
    pub fn new(root: &std::path::Path) -> Self {
        Context {
            root: root.to_path_buf(),
            operator: None,
        }
    }

    fn operator(&mut self) -> &OperatorCheck {
        self.operator.get_or_insert_with(operator::check)
    }
}

/// The named checks of paper 000, by the name a claim's `check` gives.
pub const CHECKS: &[(&str, NamedFn)] = &[
    ("operator-poles", |n, p, c| {
        operator_poles(&mut n.paper000, p, c)
    }),
    ("operator-growing-mode", |n, p, c| {
        operator_growing_mode(&mut n.paper000, p, c)
    }),
    ("identity21", |_, p, c| identity_21(p, c)),
    ("series-vs-numerics", |n, p, c| {
        series_vs_numerics(&n.paper000, p, c)
    }),
    ("passivity", |n, p, c| passivity(&n.paper000, p, c)),
];

fn bad(c: &NamedCheck, message: &str) -> VerifyError {
    VerifyError::BadClaim {
        id: c.id.clone(),
        message: message.into(),
    }
}

/// The derived operator's poles are at D = -alpha and D = -gamma.
fn operator_poles(
    ctx: &mut Context,
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    Ok({
        let op = ctx.operator();
        let mut o = outcome(
            paper,
            c,
            holds(op.poles_agree),
            format!(
                "the derived operator's denominator {} vanishes at D = -alpha and D = -gamma: {}",
                op.derived.denom(),
                op.poles_agree
            ),
        );
        o.derived_latex = Some(format!(
            "\\frac{{\\tilde E}}{{1-\\tilde\\nu^2}} = {}",
            op.derived.to_latex()
        ));
        o
    })
}

/// alpha as printed has one sign on nu in (-1, 1/2): L(alpha) grows.
fn operator_growing_mode(
    ctx: &mut Context,
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    Ok({
        // alpha as printed, as a function of nu at lambda = 1: its sign over nu in (-1, 1/2)
        let op = ctx.operator();
        let at = |nu: Poly| {
            op.alpha
                .subst(Sym::new("nu"), &RatFunc::from_poly(nu))
                .and_then(|r| r.subst(Sym::new("lambda"), &RatFunc::one()))
                .and_then(|r| r.as_constant())
        };
        // alpha(nu) = -2(1+nu)/(1-2nu) * lambda has no zero or pole inside (-1, 1/2): its
        // numerator vanishes only at nu = -1 and its denominator only at nu = 1/2, so the
        // sign at one interior point is the sign everywhere.
        let num_roots_outside = op
            .alpha
            .subst(Sym::new("nu"), &RatFunc::from_q(q(-1, 1)))
            .is_some_and(|r| r.is_zero());
        let sample = at(Poly::constant(q(3, 10)));
        let negative = sample.as_ref().is_some_and(|v| *v < q(0, 1));
        outcome(
            paper,
            c,
            holds(!negative),
            format!(
                "alpha = {} is {} for every nu in (-1, 1/2) (zero only at nu = -1: {num_roots_outside}; alpha = {} at nu = 3/10, lambda = 1), so L(alpha) contains exp(|alpha| t): the constant-bulk-modulus law as printed has a growing mode of rate |alpha| = 2(1+nu)lambda/(1-2nu)",
                op.alpha,
                if negative { "negative" } else { "not negative" },
                sample
                    .map(|v| crate::algebra::poly::q_text(&v))
                    .unwrap_or_default()
            ),
        )
    })
}

/// (21) for k = 0..k_max, both sides built independently.
fn identity_21(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    Ok({
        let kmax = c.k_max.unwrap_or(12);
        let results: Vec<_> = (0..=kmax).map(identity21::check).collect();
        let ok = results.iter().all(|r| r.holds && r.solves_ode);
        let failed: Vec<String> = results
            .iter()
            .filter(|r| !r.holds)
            .map(|r| r.k.to_string())
            .collect();
        outcome(
            paper,
            c,
            holds(ok),
            if ok {
                format!(
                    "both sides built independently agree exactly for k = 0..{kmax}, and the left side solves y' + alpha y = t^k, y(0) = 0"
                )
            } else {
                format!("differs for k in {}", failed.join(", "))
            },
        )
    })
}

/// The Adomian series against the integrated model of the claim's scene.
fn series_vs_numerics(
    ctx: &Context,
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    Ok({
        let scene = c.scene.clone().ok_or_else(|| bad(c, "needs `scene`"))?;
        super::series_numeric::check(paper, c, &ctx.root.join(scene))?
    })
}

/// The viscoelastic operator does no negative work over the claim's scene.
fn passivity(ctx: &Context, paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    Ok({
        let scene = c.scene.clone().ok_or_else(|| bad(c, "needs `scene`"))?;
        super::series_numeric::passivity(paper, c, &ctx.root.join(scene))?
    })
}
