//! The power of the checks per printed formula, across every claim that reads it: a misprint
//! of a formula is caught when any claim on it catches it (issue 53).
//!
//! A claim whose measured printed side is one formula (its misprints all of `printed`) reads
//! the formula it prints; claims of one paper printing the same formula are one formula here.
//! Their misprints are the same ones (`verify::power` draws them from the formula's text, not the
//! claim's id), so a misprint survives the formula when it survives every one of its claims.
//! A claim misprinted in one text that is not `printed` (its `require`) reads that text, and
//! claims with the same text are one formula as well; a claim misprinted in several (a list of
//! equations) is a formula of its own.
//! No physics and no claim types here: outcomes in, rows and Markdown out.

use super::{Outcome, Power, anchor, escape_cell, first_three};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One printed formula and the power of the claims that read it.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct FormulaPower {
    /// The paper.
    pub paper: String,
    /// The formula as the claims check it (the formula language), or the claim's id for one
    /// measured on other keys.
    pub formula: String,
    /// The paper's LaTeX it was read from, when read from the paper.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub latex: Option<String>,
    /// The claims that read it.
    pub claims: Vec<String>,
    /// The misprints run on it.
    pub mutants: usize,
    /// The misprints no claim catches.
    pub survivors: Vec<String>,
    /// What its claims cannot see, as they state it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blind: Vec<String>,
}

impl FormulaPower {
    /// Whether a misprint survives every claim on it.
    pub fn weak(&self) -> bool {
        !self.survivors.is_empty()
    }
}

/// The misprint a survivor names, without the key it was made in (`printed: coefficient 2 x2`
/// is `coefficient 2 x2`), and whether it was made in `printed`.
fn misprint(survivor: &str) -> (&str, bool) {
    match survivor.split_once(": ") {
        Some((key, what)) => (what, key == "printed"),
        None => (survivor, false),
    }
}

/// Every printed formula with a measured claim, by paper and then formula.
pub fn formula_power(outcomes: &[Outcome]) -> Vec<FormulaPower> {
    let mut groups: BTreeMap<(String, String), Vec<(&Outcome, &Power)>> = BTreeMap::new();
    for o in outcomes {
        let Some(p) = o.power.as_ref().filter(|p| p.not_measured.is_none()) else {
            continue;
        };
        let of_printed = p.survivors.iter().all(|s| misprint(s).1);
        let formula = match (&o.printed, &p.formula) {
            (Some(text), _) if of_printed => text.clone(),
            // a claim misprinted in one text (its `require`): claims with the same text meet
            // the same misprints of it
            (_, Some(text)) => text.clone(),
            _ => o.id.clone(),
        };
        groups
            .entry((o.paper.clone(), formula))
            .or_default()
            .push((o, p));
    }
    let mut out = groups
        .into_iter()
        .map(|((paper, formula), claims)| {
            // a misprint some claim let through, unless another claim killed it, or found it the
            // same statement or a weaker true one (each claim's misprints are the formula's,
            // named alike)
            let caught: Vec<&str> = claims
                .iter()
                .flat_map(|(_, p)| p.killed_names.iter().chain(&p.equivalent).chain(&p.weaker))
                .map(|s| misprint(s).0)
                .collect();
            let mut survivors: Vec<String> = Vec::new();
            for (_, p) in &claims {
                for s in p.survivors.iter().map(|s| misprint(s).0) {
                    if !caught.contains(&s) && !survivors.iter().any(|x| x == s) {
                        survivors.push(s.to_string());
                    }
                }
            }
            let mut blind: Vec<String> = Vec::new();
            for (_, p) in &claims {
                if let Some(b) = &p.blind
                    && !blind.contains(b)
                {
                    blind.push(b.clone());
                }
            }
            FormulaPower {
                paper,
                latex: claims.iter().find_map(|(o, _)| o.printed_latex.clone()),
                claims: claims.iter().map(|(o, _)| o.id.clone()).collect(),
                mutants: claims.iter().map(|(_, p)| p.mutants).max().unwrap_or(0),
                survivors: if formula_is_claim(&formula, &claims) {
                    claims[0].1.survivors.clone()
                } else {
                    survivors
                },
                blind,
                formula,
            }
        })
        .collect::<Vec<_>>();
    // in the order of their first claims, as every list of the reports (000.eq6 before
    // 000.eq23), not of the formulas' texts
    let first = |f: &FormulaPower| f.claims.first().cloned().unwrap_or_default();
    out.sort_by(|a, b| {
        a.paper
            .cmp(&b.paper)
            .then_with(|| super::natural_cmp(&first(a), &first(b)))
    });
    out
}

/// Whether the group is one claim measured on other keys (its survivors keep their keys).
fn formula_is_claim(formula: &str, claims: &[(&Outcome, &Power)]) -> bool {
    claims.len() == 1 && claims[0].0.id == formula
}

/// The README's section: per paper, how many printed formulas some claim's misprint survives,
/// and each weak formula with its claims, what survives and what they cannot see.
pub fn section(formulas: &[FormulaPower], report_of: &dyn Fn(&str) -> String) -> String {
    if formulas.is_empty() {
        return String::new();
    }
    let mut md = String::from(
        "## Power per printed formula\n\nThe claims of one paper that print the same formula are checked against the same \
         misprints of it; a misprint is caught when any of them catches it (a formula printed in a claim's \
         inequality, such as (1.12)'s `energy_change <= 0`, is one formula for all the claims that state it). A formula \
         is weak when a misprint survives every claim on it.\n\n| paper | formulas measured | read by more than one claim | weak | share weak |\n|---|---|---|---|---|\n",
    );
    let mut by_paper: BTreeMap<&str, Vec<&FormulaPower>> = BTreeMap::new();
    for f in formulas {
        by_paper.entry(f.paper.as_str()).or_default().push(f);
    }
    for (paper, fs) in &by_paper {
        let weak = fs.iter().filter(|f| f.weak()).count();
        md.push_str(&format!(
            "| {paper} | {} | {} | {weak} | {:.0} % |\n",
            fs.len(),
            fs.iter().filter(|f| f.claims.len() > 1).count(),
            100.0 * weak as f64 / fs.len().max(1) as f64
        ));
    }
    md.push_str(
        "\n| weak formula | its claims | surviving misprints (first 3) | what its claims cannot see |\n|---|---|---|---|\n",
    );
    for f in formulas.iter().filter(|f| f.weak()) {
        let claims: Vec<String> = f
            .claims
            .iter()
            .map(|id| format!("[{id}]({}#{})", report_of(&f.paper), anchor(id)))
            .collect();
        let shown = if f.claims.len() == 1 && f.claims[0] == f.formula {
            "(its claim's inequality or equations)".to_string()
        } else {
            format!("`{}`", f.formula)
        };
        md.push_str(&format!(
            "| {} | {} | {} of {}: {} | {} |\n",
            escape_cell(&shown),
            claims.join(", "),
            f.survivors.len(),
            f.mutants,
            escape_cell(&first_three(&f.survivors)),
            escape_cell(&if f.blind.is_empty() {
                "**not stated**".to_string()
            } else {
                f.blind.join("; ")
            })
        ));
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::Verdict;

    fn claim(id: &str, printed: &str, survivors: &[&str]) -> Outcome {
        Outcome {
            printed: Some(printed.into()),
            kind: "identity".into(),
            power: Some(Power {
                mutants: 10,
                killed: 10 - survivors.len(),
                survivors: survivors.iter().map(|s| s.to_string()).collect(),
                ..Power::default()
            }),
            ..Outcome::bare(id, Verdict::Holds)
        }
    }

    #[test]
    fn a_misprint_is_caught_when_any_claim_on_the_formula_catches_it() {
        // two claims on a*b: one blind to x2, the other to x2 and the sign; a third formula
        let out = [
            killing(
                claim("p.a", "a*b", &["printed: the whole side x2"]),
                &["printed: sign of the term a*b"],
            ),
            claim(
                "p.b",
                "a*b",
                &[
                    "printed: the whole side x2",
                    "printed: sign of the term a*b",
                ],
            ),
            claim("p.c", "c", &["printed: sign of the term c"]),
            claim("p.d", "d", &[]),
        ];
        let f = formula_power(&out);
        assert_eq!(f.len(), 3);
        assert_eq!(f[0].formula, "a*b");
        assert_eq!(f[0].claims, ["p.a", "p.b"]);
        assert_eq!(f[0].survivors, ["the whole side x2"]);
        assert_eq!(f[1].survivors, ["sign of the term c"]);
        assert!(!f[2].weak());
        let md = section(&f, &|_| "p.md".into());
        assert!(md.contains("| p | 3 | 1 | 2 | 67 % |"), "{md}");
    }

    fn killing(mut o: Outcome, killed: &[&str]) -> Outcome {
        if let Some(p) = o.power.as_mut() {
            p.killed_names = killed.iter().map(|s| s.to_string()).collect();
        }
        o
    }

    #[test]
    fn a_misprint_no_claim_ran_or_killed_survives_and_one_stating_the_same_does_not() {
        // p.e did not draw `x1.1` (not among its killed), so p.f's survivor stands; p.f's
        // `x2` was judged the same statement by p.e (`equivalent`), so it is not a survivor
        let mut e = claim("p.e", "e", &[]);
        if let Some(p) = e.power.as_mut() {
            p.equivalent = vec!["printed: the whole side x2".into()];
        }
        let e = killing(e, &["printed: sign of the term e"]);
        let f = claim(
            "p.f",
            "e",
            &["printed: the whole side x1.1", "printed: the whole side x2"],
        );
        let out = formula_power(&[e, f]);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].survivors, ["the whole side x1.1"]);
    }

    #[test]
    fn a_claim_measured_on_other_keys_is_a_formula_of_its_own() {
        let mut c = claim("p.bound", "x", &["require: sign of the term x"]);
        c.printed = None;
        let f = formula_power(&[c]);
        assert_eq!(f[0].formula, "p.bound");
        assert_eq!(f[0].survivors, ["require: sign of the term x"]);
    }
}
