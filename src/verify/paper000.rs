//! Checks of 000_92d54b11128ea1ec.txt: the operator of section 2, (13), (15)-(18), (21)-(23).
//!
//! Every verdict is the outcome of an exact comparison in [`crate::algebra`]; the detail quotes
//! the derived and printed expressions and their difference.

use super::kinds::NamedCheck;
use super::{NamedFn, Outcome, PaperClaims, VerifyError, holds, outcome};
use crate::algebra::identity21;
use crate::algebra::operator;
use crate::algebra::poly::{Sym, q};
use crate::algebra::ratfunc::RatFunc;

/// Expensive exact results shared between claims.
pub struct Context {
    root: std::path::PathBuf,
}

impl Context {
    /// A context reading scenes relative to `root`.
    pub fn new(root: &std::path::Path) -> Self {
        Context {
            root: root.to_path_buf(),
        }
    }
}

/// The named checks of paper 000, by the name a claim's `check` gives.
pub const CHECKS: &[(&str, NamedFn)] = &[
    ("operator-poles", |_, p, c| operator_poles(p, c)),
    ("operator-growing-mode", |_, p, c| {
        operator_growing_mode(p, c)
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

/// The derived operator's poles are at D = -alpha and D = -gamma, alpha and gamma as printed
/// (`printed_equations`, exact rational functions of nu and lambda).
fn operator_poles(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let rates = c.printed_exacts(2, "alpha and gamma as printed, in nu and lambda")?;
    let (alpha, gamma) = (&rates[0], &rates[1]);
    let derived = operator::derived_operator();
    let agree = operator::poles_at(alpha, gamma);
    let (d_alpha, d_gamma) = operator::derived_rates();
    let mut o = outcome(
        paper,
        c,
        holds(agree),
        format!(
            "the derived operator's denominator {} vanishes at D = -alpha and D = -gamma with the printed alpha = {alpha}, gamma = {gamma}: {agree} (derived: alpha = {d_alpha}, gamma = {d_gamma}, from the zeros D = -alpha of 1 + nu~ and D = -gamma of 1 - nu~)",
            derived.denom(),
        ),
    );
    o.derived_latex = Some(format!(
        "\\frac{{\\tilde E}}{{1-\\tilde\\nu^2}} = {}",
        derived.to_latex()
    ));
    Ok(o)
}

/// The sign of alpha as printed (`printed`, in nu and lambda) over nu in (-1, 1/2), lambda > 0:
/// where it is negative, L(alpha) grows as exp(|alpha| t).
fn operator_growing_mode(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let alpha = c.printed_exact("alpha as printed, in nu and lambda")?;
    let (nu, lam) = (Sym::new("nu"), Sym::new("lambda"));
    // a grid of exact points: nu = -1 + 3k/80 (k = 1..39) inside (-1, 1/2), lambda in {1/10, 1, 10}
    let mut negative = Vec::new();
    let (mut points, mut neg_points) = (0, 0);
    for k in 1..40 {
        let nu_k = q(-80 + 3 * k, 80);
        for l in [q(1, 10), q(1, 1), q(10, 1)] {
            points += 1;
            let at = |l: crate::algebra::poly::Q| {
                alpha
                    .subst(nu, &RatFunc::from_q(nu_k.clone()))
                    .and_then(|r| r.subst(lam, &RatFunc::from_q(l)))
                    .and_then(|r| r.as_constant())
            };
            // a rate that is not a number there (a symbol besides nu and lambda, a pole) is no
            // rate: refused, never counted as "not negative"
            let v = at(l.clone()).ok_or_else(|| {
                bad(
                    c,
                    &format!(
                        "printed: alpha = {alpha} is not a number at nu = {}, lambda = {} (a rate in nu and lambda only)",
                        crate::algebra::poly::q_text(&nu_k),
                        crate::algebra::poly::q_text(&l)
                    ),
                )
            })?;
            if v < q(0, 1) {
                neg_points += 1;
                negative.push(nu_k.clone());
            }
        }
    }
    negative.dedup();
    let grows = !negative.is_empty();
    let nu_text = |v: &crate::algebra::poly::Q| crate::algebra::poly::q_text(v);
    Ok(outcome(
        paper,
        c,
        holds(!grows),
        if grows {
            format!(
                "alpha = {alpha} is negative at {neg_points} of the {points} exact points (nu = -1 + 3k/80, k = 1..39, lambda = 1/10, 1, 10), nu from {} to {}: there L(alpha) contains exp(|alpha| t), a growing mode, and the law as printed is not dissipative",
                negative.first().map(nu_text).unwrap_or_default(),
                negative.last().map(nu_text).unwrap_or_default(),
            )
        } else {
            format!(
                "alpha = {alpha} is not negative at any of the {points} exact points (nu = -1 + 3k/80, k = 1..39, lambda = 1/10, 1, 10): no growing mode found"
            )
        },
    ))
}

/// (21) for k = 0..k_max: the left side built by the operator, the right side the claim's
/// `printed` (in `t`, `alpha`, `k`) with `k` put in; both exactly.
fn identity_21(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let kmax = c.k_max.unwrap_or(12);
    let rhs = c
        .printed
        .as_deref()
        .ok_or_else(|| bad(c, "needs `printed`: the right side of (21), in t, alpha, k"))
        .and_then(|t| {
            crate::algebra::expr::parse(t).map_err(|e| bad(c, &format!("printed: {e}")))
        })?;
    let results = (0..=kmax)
        .map(|k| {
            identity21::printed_at(&rhs, k)
                .map(|p| identity21::check(k, &p))
                .map_err(|e| bad(c, &format!("printed: {e}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let ok = results.iter().all(|r| r.holds && r.solves_ode);
    let failed: Vec<String> = results
        .iter()
        .filter(|r| !r.holds)
        .map(|r| r.k.to_string())
        .collect();
    Ok(outcome(
        paper,
        c,
        holds(ok),
        if ok {
            format!(
                "the left side built by the operator L(alpha) and the printed right side agree exactly for k = 0..{kmax}, and the left side solves y' + alpha y = t^k, y(0) = 0"
            )
        } else {
            format!(
                "the printed right side differs from the left side built by the operator for k in {}",
                failed.join(", ")
            )
        },
    ))
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

#[cfg(test)]
mod tests {
    use crate::verify::{Verdict, run_all, test_claims};

    /// Runs `operator-growing-mode` on each printed rate, from a claims file of paper 000.
    fn rates(printed: &[&str]) -> Vec<Result<Verdict, String>> {
        printed
            .iter()
            .map(|p| {
                let (papers, d) = test_claims(
                    "000",
                    &format!(
                        "[symbols]\nnu = \"1\"\nlambda = \"1/s\"\nE = \"Pa\"\n[[claim]]\nid = \"000.t\"\nequation = \"(1)\"\nreading = \"q\"\nkind = \"check\"\ncheck = \"operator-growing-mode\"\nprinted = \"{p}\"\n"
                    ),
                )?;
                run_all(&papers, &d)
                    .map(|o| o[0].verdict)
                    .map_err(|e| e.to_string())
            })
            .collect()
    }

    #[test]
    fn a_rate_grows_where_it_is_negative_and_a_rate_that_is_no_number_is_refused() {
        // by hand: lambda > 0 never grows; -lambda always does; the printed
        // -2 (nu + 1) lambda/(1 - 2 nu) is negative for every nu in (-1, 1/2); E lambda is no
        // rate in nu and lambda alone
        let r = rates(&[
            "lambda",
            "-lambda",
            "-2*(nu + 1)*lambda/(1 - 2*nu)",
            "E*lambda",
        ]);
        assert_eq!(r[0], Ok(Verdict::Holds));
        assert_eq!(r[1], Ok(Verdict::Fails));
        assert_eq!(r[2], Ok(Verdict::Fails));
        let e = r[3].clone().unwrap_err();
        assert!(e.contains("is not a number at nu"), "{e}");
    }
}
