//! `verify`: check every claim of every paper and write `reports/`, or with `--check` compare
//! with the committed `reports/summary.json` and write nothing.

use anyhow::{Context, Result, bail};
use clap::Parser;
use impactcheck::{report, verify};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "verify",
    version,
    about = "Check every claim of every paper; write reports/ (or compare with it: --check)",
    long_about = "verify: the main job of impactcheck.\n\n\
        Reads the claims in verify/*.toml, computes each verdict (exact algebra or numerics with a \
        stated error) and writes reports/README.md, one Markdown report per paper and \
        reports/summary.json. Reports are written to a temporary folder first, so a failed run \
        leaves the old ones untouched.\n\n\
        With --check nothing is written: the fresh verdicts are compared with the committed \
        summary (or --baseline PATH) and the exit status is 1 if any verdict or value changed."
)]
struct Args {
    /// Compare with the committed summary instead of writing reports.
    #[arg(long)]
    check: bool,
    /// Baseline summary for --check (default: <out>/summary.json).
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Folder of claim files.
    #[arg(long)]
    claims: Option<PathBuf>,
    /// Output folder for reports.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the summary as JSON on stdout as well.
    #[arg(long)]
    json: bool,
}

fn default_dir(name: &str) -> PathBuf {
    let here = PathBuf::from(name);
    if here.exists() {
        here
    } else {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(name)
    }
}

fn run(args: Args) -> Result<bool> {
    let claims_dir = args.claims.unwrap_or_else(|| default_dir("verify"));
    let out_dir = args.out.unwrap_or_else(|| default_dir("reports"));
    let papers = verify::load_claims(&claims_dir)
        .with_context(|| format!("reading claims from {}", claims_dir.display()))?;
    let root = claims_dir
        .canonicalize()
        .ok()
        .and_then(|p| p.parent().map(|x| x.to_path_buf()))
        .unwrap_or_else(|| PathBuf::from("."));
    let outcomes = verify::run_all(&papers, &root)?;
    let fresh = report::summary(&outcomes);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&fresh)?);
    }
    if args.check {
        let path = args
            .baseline
            .unwrap_or_else(|| out_dir.join("summary.json"));
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading baseline {}", path.display()))?;
        let baseline: report::Summary = serde_json::from_str(&text)
            .with_context(|| format!("parsing baseline {}", path.display()))?;
        let changes = report::diff(&baseline, &fresh);
        if changes.is_empty() {
            eprintln!(
                "verify --check: {} claims, no verdict or value changed against {}",
                fresh.claims.len(),
                path.display()
            );
            return Ok(true);
        }
        eprintln!(
            "verify --check: {} change(s) against {}:",
            changes.len(),
            path.display()
        );
        for (id, what) in &changes {
            eprintln!("  {id}: {what}");
        }
        eprintln!(
            "run `cargo run --release --bin verify` and commit reports/ if the change is intended"
        );
        return Ok(false);
    }
    let files = report::render(&papers, &outcomes);
    report::write_atomically(&out_dir, &files)
        .with_context(|| format!("writing {}", out_dir.display()))?;
    let mut counts = std::collections::BTreeMap::new();
    for o in &outcomes {
        *counts.entry(o.verdict.as_str()).or_insert(0) += 1;
    }
    eprintln!(
        "verify: {} claims ({}); reports written to {}",
        outcomes.len(),
        counts
            .iter()
            .map(|(k, v)| format!("{v} {k}"))
            .collect::<Vec<_>>()
            .join(", "),
        out_dir.display()
    );
    if outcomes.is_empty() {
        bail!("no claims found in {}", claims_dir.display());
    }
    Ok(true)
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("verify: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
