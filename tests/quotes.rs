//! Quotes are the paper's words: a claim's `quote` is checked against the paper's text when the
//! text is found (whitespace, `$`, braces and LaTeX spacing aside, `...` for words left out); a
//! quote that is not there stops validation with exit 2 naming the claim and `quote`, before any
//! claim runs. The claims file's own words are a `reading`, shown as such. The paper here is a
//! short text written by the test; the seeds' quotes are checked by `verify` itself (every run
//! with `../shared/seeds` present).

use std::path::PathBuf;
use std::process::Command;

const PAPER: &str = "Numerical computations  lead to the following result: the rebound velocity of the\nuncoming ball is about 96\\% of its initial velocity $V$, while the other ball stays.\n$$\nx = 2 \\, y \\tag{1}\n$$\n";

/// A claims file naming `paper.txt`, with the paper beside it, and one claim with `said`.
fn run(name: &str, said: &str) -> (Option<i32>, String, String) {
    let d = std::env::temp_dir().join(format!("impactcheck-quote-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    std::fs::write(d.join("paper.txt"), PAPER).expect("write");
    let claims = format!(
        "paper = \"900\"\ntitle = \"t\"\nfile = \"paper.txt\"\nreport = \"t.md\"\nequations = [\"1\"]\n[symbols]\ny = \"m\"\n[[claim]]\nid = \"q.one\"\nequation = \"(1)\"\n{said}\nkind = \"identity\"\nprinted = \"2*y\"\nderived = \"y + y\"\n"
    );
    let path: PathBuf = d.join("claims.toml");
    std::fs::write(&path, claims).expect("write");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args([
            "--claims",
            path.to_str().expect("utf-8"),
            "--out",
            d.join("out").to_str().expect("utf-8"),
        ])
        .output()
        .expect("runs");
    let report = std::fs::read_to_string(d.join("out/t.md")).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&d);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        report,
    )
}

#[test]
fn the_papers_words_pass_whatever_their_spacing() {
    // line break, double space and `$` differ from the text; `...` leaves words out
    let (code, err, report) = run(
        "found",
        "quote = \"the rebound velocity of the uncoming ball is about 96\\\\% ... initial velocity V\"",
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(
        report.contains("The paper: \"the rebound velocity"),
        "{report}"
    );
}

#[test]
fn a_quote_not_in_the_paper_stops_validation() {
    for (name, quote) in [
        // a paraphrase: the paper says "about 96%", not "96 percent"
        ("paraphrase", "the rebound velocity is 96 percent of V"),
        // the pieces around `...` are in the text, but not in this order
        ("order", "initial velocity ... the rebound velocity"),
    ] {
        let (code, err, report) = run(name, &format!("quote = \"{quote}\""));
        assert_eq!(code, Some(2), "{name}: {err}");
        assert!(
            err.contains("q.one") && err.contains("quote") && err.contains("not in the paper"),
            "{name}: {err}"
        );
        assert!(report.is_empty(), "{name}: a report was written");
    }
}

#[test]
fn a_reading_is_the_claims_files_words_and_shown_as_such() {
    let (code, err, report) = run("reading", "reading = \"x = 2 y, read as a product\"");
    assert_eq!(code, Some(0), "{err}");
    assert!(
        report.contains("Read as (the claims file's words): `x = 2 y, read as a product`")
            && !report.contains("The paper: "),
        "{report}"
    );
    let (code, err, _) = run("neither", "");
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("q.one") && err.contains("reading"), "{err}");
}
