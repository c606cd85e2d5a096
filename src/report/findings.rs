//! The distinct errors the claims show (findings), each with its claims and what its
//! correction, applied, made of them (`verify::correction`).

use super::{Outcome, Verdict, anchor, natural_cmp};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One distinct error of a paper, and every claim that shows it.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Finding {
    /// Its short name (a claim's `finding`, or the claim's id when it names none).
    pub name: String,
    /// The claims that show it (verdict `fails` or `holds-with-correction`).
    pub claims: Vec<String>,
    /// The claims that hold with the finding's correction applied.
    #[serde(default)]
    pub corrected_hold: Vec<String>,
    /// The claims that, with the correction applied, still do not hold.
    #[serde(default)]
    pub corrected_fail: Vec<String>,
    /// The claims with no correction applied (none stated, or not run in this report).
    #[serde(default)]
    pub uncorrected: Vec<String>,
}

impl Finding {
    /// Whether its correction, applied, turned every one of its claims to holding.
    pub fn correction_holds(&self) -> bool {
        self.corrected_fail.is_empty()
            && self.uncorrected.is_empty()
            && self.corrected_hold.len() == self.claims.len()
    }
}

/// The distinct errors the outcomes show: every claim that fails or holds only with a
/// correction, and does not extend the paper (`extends`), is in exactly one, grouped by its
/// `finding` (a claim naming none is a finding of its own), sorted by name.
pub fn findings(outcomes: &[Outcome]) -> Vec<Finding> {
    let mut by: BTreeMap<String, Vec<&Outcome>> = BTreeMap::new();
    for o in outcomes {
        if matches!(o.verdict, Verdict::Fails | Verdict::HoldsWithCorrection) && o.extends.is_none()
        {
            let name = o.finding.clone().unwrap_or_else(|| o.id.clone());
            by.entry(name).or_default().push(o);
        }
    }
    by.into_iter()
        .map(|(name, mut list)| {
            list.sort_by(|a, b| natural_cmp(&a.id, &b.id));
            let mut f = Finding {
                name,
                claims: list.iter().map(|o| o.id.clone()).collect(),
                corrected_hold: Vec::new(),
                corrected_fail: Vec::new(),
                uncorrected: Vec::new(),
            };
            for o in list {
                let to = match o.power.as_ref().and_then(|p| p.correction.as_ref()) {
                    Some(c) if c.holds => &mut f.corrected_hold,
                    Some(_) => &mut f.corrected_fail,
                    None => &mut f.uncorrected,
                };
                to.push(o.id.clone());
            }
            f
        })
        .collect()
}

/// What a finding's correction made of its claims, in words.
fn correction_text(f: &Finding) -> String {
    if f.correction_holds() {
        return match f.claims.len() {
            1 => "it holds".into(),
            n => format!("all {n} hold"),
        };
    }
    let mut parts = Vec::new();
    match f.corrected_hold.len() {
        0 => {}
        1 => parts.push("1 holds".into()),
        n => parts.push(format!("{n} hold")),
    }
    if !f.corrected_fail.is_empty() {
        parts.push(format!("still failing: {}", f.corrected_fail.join(", ")));
    }
    if !f.uncorrected.is_empty() {
        parts.push(format!("not applied: {}", f.uncorrected.join(", ")));
    }
    parts.join("; ")
}

/// A paper's distinct findings, each with the claims that show it and what its correction made
/// of them.
pub(super) fn findings_section(list: &[&Outcome]) -> String {
    let owned: Vec<Outcome> = list.iter().map(|o| (*o).clone()).collect();
    let found = findings(&owned);
    if found.is_empty() {
        return "No claim of this paper fails or needs a correction.\n\n".into();
    }
    let showing: usize = found.iter().map(|f| f.claims.len()).sum();
    let mut md = format!(
        "## Findings\n\n{showing} claims fail or hold only with a correction; they show {} distinct findings. Each claim is checked again with its finding's correction applied (its `correction`, or its `corrected` form): the last column says which then hold.\n\n| finding | claims | with the correction |\n|---|---|---|\n",
        found.len()
    );
    for f in &found {
        let links: Vec<String> = f
            .claims
            .iter()
            .map(|id| format!("[{id}](#{})", anchor(id)))
            .collect();
        md.push_str(&format!(
            "| {} | {} | {} |\n",
            f.name,
            links.join(", "),
            correction_text(f)
        ));
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Corrected, Power};

    fn o(id: &str, verdict: Verdict, finding: Option<&str>, fixed: Option<bool>) -> Outcome {
        Outcome {
            power: fixed.map(|holds| Power {
                correction: Some(Corrected {
                    holds,
                    verdict: if holds {
                        Verdict::Holds
                    } else {
                        Verdict::Fails
                    },
                    detail: String::new(),
                }),
                ..Power::default()
            }),
            finding: finding.map(str::to_string),
            ..Outcome::bare(id, verdict)
        }
    }

    #[test]
    fn every_error_is_in_one_finding_and_shared_names_group() {
        let out = [
            o("p.a", Verdict::Fails, Some("wrong-a1"), Some(true)),
            o("p.b", Verdict::Fails, Some("wrong-a1"), Some(true)),
            o("p.c", Verdict::HoldsWithCorrection, None, Some(true)),
            o("p.d", Verdict::Fails, None, None),
            o("p.e", Verdict::Holds, Some("wrong-a1"), None),
            o("p.f", Verdict::Fails, Some("half"), Some(true)),
            o("p.g", Verdict::Fails, Some("half"), Some(false)),
        ];
        let f = findings(&out);
        let got: Vec<(&str, Vec<&str>)> = f
            .iter()
            .map(|f| {
                (
                    f.name.as_str(),
                    f.claims.iter().map(String::as_str).collect(),
                )
            })
            .collect();
        assert_eq!(
            got,
            vec![
                ("half", vec!["p.f", "p.g"]),
                ("p.c", vec!["p.c"]),
                ("p.d", vec!["p.d"]),
                ("wrong-a1", vec!["p.a", "p.b"]),
            ]
        );
        // what the corrections made of them: by hand from the outcomes above
        let confirmed: Vec<bool> = f.iter().map(Finding::correction_holds).collect();
        assert_eq!(confirmed, [false, true, false, true]);
        assert_eq!(f[0].corrected_hold, ["p.f"]);
        assert_eq!(f[0].corrected_fail, ["p.g"]);
        assert_eq!(f[2].uncorrected, ["p.d"]);
        assert_eq!(correction_text(&f[0]), "1 holds; still failing: p.g");
        assert_eq!(correction_text(&f[1]), "it holds");
        assert_eq!(correction_text(&f[2]), "not applied: p.d");
        assert_eq!(correction_text(&f[3]), "all 2 hold");
        let md = findings_section(&out.iter().collect::<Vec<_>>());
        assert!(
            md.contains("| wrong-a1 | [p.a](#pa), [p.b](#pb) | all 2 hold |"),
            "{md}"
        );
    }
}
