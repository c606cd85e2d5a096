//! The audits the main job writes (`reports/audit/`): each paper's audit under its declared
//! units (its claims' units, and over them the referee's units file beside its displays,
//! `tex/<paper>.units.toml`, every symbol's unit from its meaning in the paper), and (issue
//! 52) the same paper audited from its own words, with no units file, beside it: how many
//! relations the words decide, and any relation they call inconsistent that the declared
//! units do not.

use crate::algebra::units::Unit;
use crate::paper::audit::power::{self, AuditPower, WithPower};
use crate::paper::audit::{
    Audit, Units, audit, audit_with_power, paper_words, read_units, to_markdown,
};
use crate::paper::source::blocks::blocks_at;
use crate::paper::words::vocabulary::Vocabulary;
use std::collections::BTreeMap;
use std::sync::Mutex;

/// The units a claims file declares (`[symbols]` that parse as units, `[tex_symbols]`).
pub fn units_of_claims(p: &super::PaperClaims) -> Units {
    let mut u = Units {
        tex_symbols: p.tex_symbols.clone(),
        ..Units::default()
    };
    for (k, t) in p.symbols.iter().chain(&p.audit_symbols) {
        if let Ok(unit) = Unit::parse(t) {
            u.symbols.insert(k.clone(), unit);
            u.texts.insert(k.clone(), t.clone());
        }
    }
    u
}

/// The units a paper is audited with in the main job: its claims' units, and over them those of
/// the units file beside its displays (`tex/000.tex`: `tex/000.units.toml`), when there is one.
pub fn units_of_paper(
    p: &super::PaperClaims,
    displays: &std::path::Path,
) -> Result<Units, crate::paper::PaperError> {
    let mut u = units_of_claims(p);
    let file = displays.with_extension("units.toml");
    if file.is_file() {
        let f = read_units(&file)?;
        u.symbols.extend(f.symbols);
        u.texts.extend(f.texts);
        u.tex_symbols.extend(f.tex_symbols);
    }
    Ok(u)
}

/// Each paper's audit under its declared units, with the audit's power, computed once per run
/// (the index and the paper's own report both show them).
fn audited(p: &super::PaperClaims) -> Option<(Audit, AuditPower)> {
    static DONE: Mutex<BTreeMap<(String, std::path::PathBuf), (Audit, AuditPower)>> =
        Mutex::new(BTreeMap::new());
    let key = (p.paper.clone(), p.source.clone());
    if let Some(hit) = DONE.lock().ok()?.get(&key) {
        return Some(hit.clone());
    }
    let (blocks, doc, path) = super::tex_claims::paper_displays(p).ok()?;
    let out = audit_with_power(&blocks, doc.as_ref(), &units_of_paper(p, &path).ok()?);
    DONE.lock().ok()?.insert(key, out.clone());
    Some(out)
}

/// The index's paragraph on the audits: each paper's counts per status, the consistent
/// relations decided in a physical unit, the audit's power, and its report.
pub fn index_section(papers: &[super::PaperClaims]) -> String {
    let mut rows = Vec::new();
    for p in papers {
        let Some((a, pw)) = audited(p) else {
            continue;
        };
        let c = a.counts();
        let n = |k: &str| c.get(k).copied().unwrap_or(0);
        rows.push(format!(
            "| [{}](audit/{}.md) | {} | {} | {} | {} | {} | {} | {} of {} ({:.0} %) |",
            p.paper,
            p.paper,
            a.relations.len(),
            n("consistent"),
            a.consistent_in_a_unit,
            n("inconsistent"),
            n("undetermined"),
            n("unreadable"),
            pw.caught,
            pw.misprints,
            100.0 * pw.share()
        ));
    }
    if rows.is_empty() {
        return String::new();
    }
    format!(
        "## Units of every relation\n\nEach paper's displays read from its LaTeX and every relation's units checked, the units of the symbols neither its claims file nor its units file (`verify/tex/<paper>.units.toml`) declares inferred from the relations (`verify audit`; a relation is inconsistent when it contradicts what the declared units and the other relations fix).\n\n| paper | relations | consistent | of them in a physical unit | inconsistent | undetermined | unreadable | misprints caught (the audit's power) |\n|---|---|---|---|---|---|---|---|\n{}\n\nThe audit's power: each relation it calls consistent misprinted with a unit error (its last term times or over a symbol with a unit, a factor with a unit dropped, a symbol squared, `t^2` for `t`), the paper audited again, and the misprints it calls inconsistent counted (`verify audit --power`; each paper's report lists the misprints that survive and why).\n\n",
        rows.join("\n")
    )
}

/// The audit of every paper whose displays are found (its `.tex` source, or the extract
/// `tex/<paper>.tex` beside its claims file) with the units of its claims file:
/// `audit/<paper>.md` and `audit/<paper>.json` under the reports folder.
pub fn paper_audits(papers: &[super::PaperClaims]) -> Vec<(String, String)> {
    let mut files = Vec::new();
    for p in papers {
        let Some((a, pw)) = audited(p) else {
            continue;
        };
        files.push((
            format!("audit/{}.md", p.paper),
            to_markdown(&a, &format!("{} ({})", p.title, p.paper)) + &power::to_markdown(&pw),
        ));
        let with = WithPower {
            audit: &a,
            power: &pw,
        };
        files.push((
            format!("audit/{}.json", p.paper),
            serde_json::to_string_pretty(&with).unwrap_or_default() + "\n",
        ));
        if let Some(w) = words_audit(p) {
            files.push((
                format!("audit/{}-words.md", p.paper),
                to_markdown(&w, &format!("{} ({}), from its words", p.title, p.paper)),
            ));
            files.push((
                format!("audit/{}-words.json", p.paper),
                serde_json::to_string_pretty(&w).unwrap_or_default() + "\n",
            ));
        }
    }
    files
}

/// A paper's audit from its words alone (its text, no units file), when its text is here.
fn words_audit(p: &super::PaperClaims) -> Option<Audit> {
    let path = super::coverage::text_path(p, p.papers_dir.as_deref())?;
    let text = std::fs::read_to_string(&path).ok()?;
    let (blocks, doc) = blocks_at(&text, path.parent(), "");
    let doc = doc?;
    let vocab = Vocabulary::builtin().ok()?;
    let units = Units::default();
    let words = paper_words(&text, &blocks, &units, &vocab);
    Some(audit(&blocks, Some(&doc), &units.with_words(words)))
}

/// What the index's row needs of an audit from the words: the symbols named in words and
/// each relation's status, in order.
struct WordsCounts {
    named: usize,
    statuses: Vec<String>,
}

/// The counts of the paper's audit from its words: computed when its text is here, else read
/// from the `audit/<paper>-words.json` an earlier run wrote into `out` (kept, as the text is
/// needed to remake it).
fn words_counts(p: &super::PaperClaims, out: &std::path::Path) -> Option<WordsCounts> {
    if let Some(w) = words_audit(p) {
        return Some(WordsCounts {
            named: w.symbols.iter().filter(|s| s.source == "words").count(),
            statuses: w.relations.iter().map(|r| r.status.to_string()).collect(),
        });
    }
    let text = std::fs::read_to_string(out.join(format!("audit/{}-words.json", p.paper))).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    let field = |list: &str, key: &str| -> Option<Vec<String>> {
        v.get(list)?
            .as_array()?
            .iter()
            .map(|x| x.get(key).and_then(|s| s.as_str()).map(str::to_string))
            .collect()
    };
    Some(WordsCounts {
        named: field("symbols", "source")?
            .iter()
            .filter(|s| *s == "words")
            .count(),
        statuses: field("relations", "status")?,
    })
}

/// The index's paragraph on the audits from the words: per paper, the relations each audit
/// decides, and the relations the words call inconsistent that the declared units do not. A
/// paper whose text is missing keeps the audit an earlier run wrote into `out`.
pub fn words_section(papers: &[super::PaperClaims], out: &std::path::Path) -> String {
    let mut rows = Vec::new();
    for p in papers {
        let Ok((blocks, doc, path)) = super::tex_claims::paper_displays(p) else {
            continue;
        };
        let Ok(units) = units_of_paper(p, &path) else {
            continue;
        };
        let declared = audit(&blocks, doc.as_ref(), &units);
        let Some(words) = words_counts(p, out) else {
            rows.push(format!(
                "| {} | the paper's text is not here | | | |",
                p.paper
            ));
            continue;
        };
        let decided = |statuses: &mut dyn Iterator<Item = &str>| {
            statuses
                .filter(|s| matches!(*s, "consistent" | "inconsistent"))
                .count()
        };
        let dw = decided(&mut words.statuses.iter().map(String::as_str));
        let dd = decided(&mut declared.relations.iter().map(|r| r.status));
        let named = words.named;
        // the two audits pair up relation by relation (one reader, one paper)
        let new_findings = if words.statuses.len() == declared.relations.len() {
            words
                .statuses
                .iter()
                .zip(&declared.relations)
                .filter(|(w, d)| *w == "inconsistent" && d.status != "inconsistent")
                .count()
                .to_string()
        } else {
            "not paired".into()
        };
        rows.push(format!(
            "| [{}](audit/{}-words.md) | {named} | {dw} | {dd} | {:.0} % | {new_findings} |",
            p.paper,
            p.paper,
            if dd == 0 {
                100.0
            } else {
                100.0 * dw as f64 / dd as f64
            }
        ));
    }
    if rows.is_empty() {
        return String::new();
    }
    format!(
        "## Units from the paper's words

Each paper audited again from its text alone, with no units file: the units of its symbols taken from the sentences that name them (\"where $\\rho$ is the density\", \"a ball of mass $m$\", a nomenclature), each with its sentence quoted (`verify audit PAPER`).\n\n| paper | symbols named in words | relations decided from the words | decided with the declared units | share | inconsistent from the words, not under the declared units |\n|---|---|---|---|---|---|\n{}\n\n",
        rows.join("\n")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_index_counts_each_seeds_relations_by_status() {
        // the counts of tests/audit.rs's the_seeds_audit_with_their_units_files (each
        // inconsistent relation checked by hand)
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("verify");
        let papers = crate::verify::load_claims(&dir).expect("loads");
        let s = index_section(&papers);
        // relations, consistent; (of them in a physical unit); inconsistent, undetermined,
        // unreadable; the power
        for (head, tail) in [
            ("| [000](audit/000.md) | 51 | 35 | ", " | 13 | 0 | 3 | "),
            ("| [001](audit/001.md) | 97 | 93 | ", " | 2 | 1 | 1 | "),
            ("| [002](audit/002.md) | 141 | 124 | ", " | 13 | 2 | 2 | "),
        ] {
            let row = s.lines().find(|l| l.starts_with(head)).expect(head);
            assert!(row.contains(tail), "{row}");
            let in_unit: usize = row[head.len()..]
                .split(' ')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            let consistent: usize = head.split(" | ").nth(2).unwrap().trim().parse().unwrap();
            assert!(in_unit <= consistent, "{row}");
            assert!(row.ends_with(" %) |"), "{row}");
        }
        assert!(s.starts_with("## Units of every relation"));
        assert_eq!(index_section(&[]), "");
    }

    #[test]
    fn a_units_file_beside_the_displays_is_laid_over_the_claims_units() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("verify");
        let p = crate::verify::load_claims(&dir.join("000_cone_plate.toml")).expect("loads");
        // the claims' a8 is the printed definition's unit; the units file's, A8's meaning in (20)
        let claims = units_of_claims(&p[0]);
        assert_eq!(claims.texts.get("a8").map(String::as_str), Some("1/(m s)"));
        let both = units_of_paper(&p[0], &dir.join("tex/000.tex")).expect("reads");
        assert_eq!(
            both.symbols.get("a8"),
            Unit::parse("1/(m s^3)").ok().as_ref()
        );
        // a symbol only the units file declares, and one only the claims declare
        assert!(!claims.symbols.contains_key("A1") && both.symbols.contains_key("A1"));
        for k in claims.symbols.keys() {
            assert!(both.symbols.contains_key(k), "{k}");
        }
        // no units file: the claims' units alone
        let none = units_of_paper(&p[0], &dir.join("tex/none.tex")).expect("reads");
        assert_eq!(none.symbols, claims.symbols);
    }

    #[test]
    fn a_claims_file_gives_the_units_a_units_file_reads_from_it() {
        // the seeds' claims files, read as claims and as units files: the same units and the
        // same LaTeX spellings (000's `[tex_symbols]` among them)
        for f in ["000_cone_plate", "001_disk", "002_constrained_impact"] {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("verify/{f}.toml"));
            let papers = crate::verify::load_claims(&path).expect("loads");
            let from_claims = units_of_claims(&papers[0]);
            let from_file = read_units(&path).expect("reads");
            assert_eq!(from_claims.symbols, from_file.symbols, "{f}");
            assert_eq!(from_claims.texts, from_file.texts, "{f}");
            assert_eq!(from_claims.tex_symbols, from_file.tex_symbols, "{f}");
        }
        let p = crate::verify::load_claims(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("verify/000_cone_plate.toml"),
        )
        .expect("loads");
        assert!(!units_of_claims(&p[0]).tex_symbols.is_empty());
    }
}
