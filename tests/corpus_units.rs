//! No false alarm on LaTeX written by others (issue 51): a hand-checked sample of relations
//! from public lecture notes, papers and theses (tests/data/corpus_units.toml; each entry names
//! its repository, commit, file and line), each correct as printed, with the units its text
//! gives every symbol. The audit must call none of them `inconsistent`, and must call each
//! `planted` twin (the same relation with a unit error written by hand) `inconsistent`.
//!
//! The reference is independent of the code under test: the units were read from the prose
//! around each relation, and each relation's correctness and each planted error's were checked
//! by hand. A spelling's unit is given to the name the reader gives that spelling alone
//! (`v_{j+1}` and `\vec{F}` read alone), so that the test does not restate the naming rules.

use impactcheck::algebra::expr::Expr;
use impactcheck::algebra::units::Unit;
use impactcheck::paper::audit::{Units, audit, paper_blocks};
use impactcheck::paper::formulas::{TexSymbols, read_formula};

#[derive(serde::Deserialize)]
struct Sample {
    relation: Vec<Entry>,
}

#[derive(serde::Deserialize)]
struct Entry {
    source: String,
    latex: String,
    planted: String,
    units: std::collections::BTreeMap<String, String>,
    /// Every relation of `latex` must be consistent (all units fixed), not only none
    /// inconsistent.
    #[serde(default)]
    all_consistent: bool,
}

fn sample(file: &str) -> Vec<Entry> {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).expect("the sample is there");
    toml::from_str::<Sample>(&text)
        .expect("the sample parses")
        .relation
}

/// The units of an entry, each on the name the reader gives its spelling; or the spelling
/// that reads as no name.
fn units_of(e: &Entry) -> Result<Units, String> {
    let mut units = Units::default();
    for (spelling, unit) in &e.units {
        let name = match read_formula(spelling, &TexSymbols::default()) {
            Ok(Expr::Sym(s)) => s,
            other => return Err(format!("{}: `{spelling}` reads as {other:?}", e.source)),
        };
        let u = Unit::parse(unit).unwrap_or_else(|m| panic!("{}: {unit}: {m}", e.source));
        units.symbols.insert(name.clone(), u);
        units.texts.insert(name, unit.clone());
    }
    Ok(units)
}

/// The statuses the audit gives the relations of one display holding `latex` (or of `latex`
/// itself, when it is a document: it starts with `\begin` or a macro definition).
fn statuses(latex: &str, units: &Units) -> Vec<(&'static str, String)> {
    let t = latex.trim_start();
    let doc = if t.starts_with("\\begin") || t.starts_with("\\newcommand") {
        latex.to_string()
    } else {
        format!("\\begin{{equation*}}\n{latex}\n\\end{{equation*}}")
    };
    let (blocks, doc) = paper_blocks(&doc);
    audit(&blocks, doc.as_ref(), units)
        .relations
        .into_iter()
        .map(|r| (r.status, r.detail))
        .collect()
}

#[test]
fn no_false_alarm_on_relations_others_wrote_and_every_planted_error_found() {
    let sample = sample("corpus_units.toml");
    assert!(sample.len() >= 100, "at least 100 relations");
    check(&sample);
}

/// Each construct of the issue (tests/data/constructs.toml, written by hand): the correct
/// relation read and consistent, its twin with a unit error inconsistent.
#[test]
fn every_construct_is_read_with_its_unit_rule() {
    let sample = sample("constructs.toml");
    assert!(sample.len() >= 30);
    check(&sample);
}

/// No relation of a correct entry unread or inconsistent (and all consistent where the entry
/// says so); some relation of each planted twin inconsistent.
fn check(sample: &[Entry]) {
    let (mut alarms, mut missed, mut unread) = (Vec::new(), Vec::new(), Vec::new());
    let mut consistent = 0;
    for e in sample {
        let units = match units_of(e) {
            Ok(u) => u,
            Err(m) => {
                unread.push(m);
                missed.push(e.source.clone());
                continue;
            }
        };
        let correct = statuses(&e.latex, &units);
        for (status, detail) in &correct {
            match *status {
                "inconsistent" => alarms.push(format!("{}: `{}`: {detail}", e.source, e.latex)),
                "unreadable" => unread.push(format!("{}: {detail}", e.source)),
                "consistent" => consistent += 1,
                other if e.all_consistent => {
                    alarms.push(format!("{}: {other}: {detail}", e.source))
                }
                _ => {}
            }
        }
        if correct.is_empty() {
            unread.push(format!("{}: no relation read", e.source));
        }
        let planted = statuses(&e.planted, &units);
        if !planted.iter().any(|(s, _)| *s == "inconsistent") {
            missed.push(format!("{}: `{}`: {planted:?}", e.source, e.planted));
        }
    }
    println!(
        "{} relations: {consistent} consistent, {} unread, {} false alarms, {} planted errors missed",
        sample.len(),
        unread.len(),
        alarms.len(),
        missed.len()
    );
    for u in &unread {
        println!("unread: {u}");
    }
    assert!(unread.is_empty(), "unread:\n{}", unread.join("\n"));
    assert!(alarms.is_empty(), "false alarms:\n{}", alarms.join("\n"));
    assert!(
        missed.is_empty(),
        "planted errors missed:\n{}",
        missed.join("\n")
    );
}
