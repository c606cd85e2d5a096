//! `verify`: check every claim of every paper and write `reports/`, or with `--check` compare
//! with the committed `reports/summary.json` and write nothing.

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use impactcheck::{paper, report, verify};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// mimalloc: small allocations (a sweep's rows and solver vectors, the algebra's big
/// integers) cost a fraction of glibc's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum FailOn {
    /// Exit 0 whatever the verdicts (the default: a failing claim is a finding, not an error).
    Never,
    /// Exit 1 when a claim's verdict is `fails`.
    Fails,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Fmt {
    Text,
    Json,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum AuditFmt {
    Text,
    Json,
    Markdown,
    /// One row per paper (a folder's audit only).
    Csv,
}

#[derive(Subcommand)]
enum Command {
    /// The units of every relation of a paper: consistent, inconsistent (the terms that
    /// disagree and their units), undetermined (the symbols nothing fixes) or unreadable (the
    /// construct the LaTeX reader lacks); the units of the other symbols inferred from the
    /// relations.
    Audit {
        /// The paper: its LaTeX source (.tex), a text with display math ($$ ... $$), or a
        /// displays extract of `%% block N` sections (verify/tex/*.tex). A folder: every paper
        /// under it (a .tex with \documentclass, a .md with display math) audited, a row each
        /// and the totals (text, json, csv or markdown), progress on stderr.
        paper: PathBuf,
        /// A TOML file with [symbols] (name = "unit") and optionally [tex_symbols]; a claims
        /// file serves as it is.
        #[arg(long, value_name = "FILE")]
        units: Option<PathBuf>,
        /// A file of LaTeX macros the paper uses without holding them (a Markdown note's
        /// `\newcommand`s kept apart); repeat for more. The paper's own preamble and its
        /// `\input` files (inside its folder) are read without it. A main file given here (one
        /// with `\documentclass` or `\begin{document}`) gives its preamble, its inputs read from
        /// its own folder: a section read alone with the macros of the paper it belongs to.
        #[arg(long, value_name = "FILE")]
        preamble: Vec<PathBuf>,
        /// A vocabulary of quantities to add to the built-in one (TOML: a table per quantity
        /// with `words` and `unit`, as src/paper/words/vocabulary.toml); its words replace the
        /// built-in ones. The units the paper's prose gives its symbols ("where $\rho$ is the
        /// density") are read with it; --units overrides them.
        #[arg(long, value_name = "FILE")]
        vocabulary: Vec<PathBuf>,
        /// text (a line per relation), json or markdown (a report: the inconsistent first).
        #[arg(long, value_enum, default_value = "text")]
        format: AuditFmt,
        /// Also measure the audit's power: every relation it calls consistent misprinted the
        /// ways unit errors happen (its last term times or over a symbol with a unit, a factor
        /// with a unit dropped, a symbol squared, t^2 for t), the paper audited again, and the
        /// misprints called inconsistent counted, per relation and in all (json: `power`).
        #[arg(long)]
        power: bool,
        /// Print a units file to start from instead of the audit: the units declared and named
        /// in the paper's words, then the fewest symbols whose units, once given, decide every
        /// relation, each "?" with the relations it appears in (fill them in, then --units).
        #[arg(long, conflicts_with = "power")]
        suggest: bool,
    },
    /// Print a claims file to start from: the header with the paper's numbers, [symbols] with
    /// the declared and inferred units, and a dimension claim per readable numbered relation,
    /// its printed side read from the paper (save it beside the paper).
    Init {
        /// The paper (as for audit).
        paper: PathBuf,
        /// The units file (as for audit).
        #[arg(long, value_name = "FILE")]
        units: Option<PathBuf>,
        /// Files of LaTeX macros (as for audit).
        #[arg(long, value_name = "FILE")]
        preamble: Vec<PathBuf>,
        /// Vocabularies of quantities (as for audit).
        #[arg(long, value_name = "FILE")]
        vocabulary: Vec<PathBuf>,
        /// The paper's short name: the first part of every claim id.
        #[arg(long = "paper", value_name = "ID")]
        id: String,
    },
}

#[derive(Parser)]
#[command(
    name = "verify",
    args_conflicts_with_subcommands = true,
    version,
    about = "Check every claim of every paper; write reports/ (or compare with it: --check)",
    long_about = "verify: the main job of impactcheck.\n\n\
        Reads the claims in verify/*.toml, computes each verdict (exact algebra or numerics with a \
        stated error) and writes reports/README.md, one Markdown report per paper, \
        reports/timing/accuracy_cost.md (work-precision of every model: the only files that hold \
        measured times) and reports/summary.json. Reports \
        are written to a temporary folder first, so a failed run leaves the old ones untouched.\n\n\
        With --check nothing is written: the fresh verdicts are compared with the committed \
        summary (or --baseline PATH); a changed verdict, or a number in a detail that moved by more \
        than 1e-6 relative, exits with status 1 and names the claim.\n\n\
        With --only PAPER|PREFIX only those claims run (e.g. --only 002, --only 000.eq22); nothing \
        is written unless --check compares them.\n\n\
        With --claims PATH (a claims file or a folder of them) any paper's claims are checked: \
        formulas as text, kinds identity, dimension, model, bound, probability and map (see verify/README.md), scenes \
        relative to the claims file. A bad claim (syntax, unknown symbol or kind, missing scene, a \
        quantity the model does not produce) exits 2 before anything runs, naming the file, the \
        claim and the key. Reports are written only with --out DIR (or for the default claims); \
        without it the verdicts are printed.\n\n\
        Exit status: 0 when the run ended (a claim that fails is a finding, not an error); 1 when \
        --check found a change, or with --fail-on fails when a claim fails; 2 for bad input \
        (a claims file, a scene, an option), with nothing written."
)]
struct Args {
    #[command(subcommand)]
    command: Option<Command>,
    /// Compare with the committed summary instead of writing reports.
    #[arg(long)]
    check: bool,
    /// Baseline summary for --check (default: <out>/summary.json).
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Run only one paper ("000") or the claims whose id starts with this prefix.
    #[arg(long)]
    only: Option<String>,
    /// A claims file, or a folder of them (default: verify/).
    #[arg(long)]
    claims: Option<PathBuf>,
    /// Output folder for reports.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the summary on stdout: text (a line per claim) or json.
    #[arg(long, value_enum)]
    format: Option<Fmt>,
    /// Measure what accuracy costs in time: the work-precision diagrams of every model and
    /// method, written to <out>/timing/ (accuracy_cost.md and its SVGs). Off by default: they
    /// are the only files that hold measured times, which differ run to run, and the main job
    /// leaves a clean checkout clean.
    #[arg(long)]
    timing: bool,
    /// Solves per work-precision point of --timing (median reported).
    #[arg(long, default_value_t = 5)]
    repeats: usize,
    /// Measure the power of every claim's check: misprint its printed side (a coefficient x2,
    /// x1/2, +-10 %, an exponent +-1, a sign, a dropped term, a symbol swapped for another of
    /// the same unit) and rerun it; a misprint that keeps the verdict survives, and the claim
    /// is marked weak (summary.json: `power`, `weak`; reports/README.md: the weak claims).
    /// The default run (writing reports/) measures the claims whose power is not in the
    /// committed reports/summary.json under the same key (what they depend on changed);
    /// this flag measures every claim afresh; --check, --only and --claims measure none
    /// without it or --power-sample.
    #[arg(long)]
    power: bool,
    /// Measure the power of N claims only, picked by --power-seed (with --check: compared with
    /// the baseline's power of those claims).
    #[arg(long, value_name = "N")]
    power_sample: Option<usize>,
    /// The seed that picks the claims of --power-sample (CI gives the commit).
    #[arg(long, value_name = "TEXT", default_value = "0")]
    power_seed: String,
    /// Where the papers' texts are (each claims file's `file`), looked for before the folder of
    /// the claims file and ../shared/seeds/: its `equations` list is checked against their
    /// numbers, and `printed_from` reads a paper's `.tex` (or a text with `$$` displays, when
    /// there is no `tex/<paper>.tex` extract) from there. Coverage is counted from the lists.
    #[arg(long, value_name = "DIR")]
    papers: Option<PathBuf>,
    /// For CI use: `fails` exits with status 1 when any claim's verdict is `fails` (after
    /// writing or printing as usual), naming them on stderr; `never` (the default) exits 0
    /// whatever the verdicts.
    #[arg(long, value_enum, value_name = "WHEN", default_value = "never")]
    fail_on: FailOn,
}

fn default_dir(name: &str) -> PathBuf {
    let here = PathBuf::from(name);
    if here.exists() {
        here
    } else {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(name)
    }
}

/// The folder that `check` claims name scenes from: the one above the claims folder (or above
/// the claims file's folder).
fn claims_root(claims_dir: &std::path::Path) -> PathBuf {
    claims_dir
        .canonicalize()
        .ok()
        .map(|p| {
            if p.is_file() {
                p.parent().map(|x| x.to_path_buf()).unwrap_or(p)
            } else {
                p
            }
        })
        .and_then(|p| p.parent().map(|x| x.to_path_buf()))
        .unwrap_or_else(|| PathBuf::from("."))
}

/// The claims whose power this run measures: a sample (--power-sample), every claim (--power,
/// or the default run that writes the project's reports), or none.
fn measured_claims(
    args: &Args,
    papers: &[verify::PaperClaims],
    write_reports: bool,
) -> std::collections::BTreeSet<String> {
    let ids: Vec<String> = papers
        .iter()
        .flat_map(|p| p.claim.iter().map(|c| c.id.clone()))
        .collect();
    let custom = args.claims.is_some();
    match args.power_sample {
        Some(n) => verify::power::pick(&ids, n, &args.power_seed),
        // the default reports always carry the power of every claim
        None if args.power || (write_reports && !custom && !args.check && args.only.is_none()) => {
            ids.iter().cloned().collect()
        }
        None => Default::default(),
    }
}

/// The power the main job reuses, and the keys it measured from (`verify::power_cache`).
struct Reused {
    power: BTreeMap<String, report::Power>,
    keys: BTreeMap<String, String>,
}

impl Reused {
    fn get(&self, id: &str) -> Option<&report::Power> {
        self.power.get(id)
    }
    fn key(&self, id: &str) -> Option<String> {
        self.keys.get(id).cloned()
    }
}

/// The default run (every claim's power, the project's reports): the power of each claim whose
/// key is the one `summary.json` in the output folder holds (else the committed
/// `reports/summary.json`: a key is the same wherever it was written) is reused, and the claim is taken
/// out of `measured`. `--power` measures every claim afresh; other runs reuse nothing.
fn reusable_power(
    args: &Args,
    papers: &[verify::PaperClaims],
    out_dir: &std::path::Path,
    measured: &mut std::collections::BTreeSet<String>,
) -> Reused {
    let mut r = Reused {
        power: BTreeMap::new(),
        keys: BTreeMap::new(),
    };
    if measured.is_empty() {
        return r;
    }
    r.keys = verify::power_cache::keys(papers);
    let mut from_file = PathBuf::new();
    if args.power || args.power_sample.is_some() || args.check {
        return r;
    }
    // the output folder's summary, else the committed one: a key names what a power depends
    // on, so a power under the same key is the same wherever it was written
    let read = |p: PathBuf| -> Option<(report::Summary, PathBuf)> {
        let t = std::fs::read_to_string(&p).ok()?;
        Some((serde_json::from_str(&t).ok()?, p))
    };
    let previous = read(out_dir.join("summary.json"))
        .or_else(|| read(default_dir("reports").join("summary.json")));
    if let Some((previous, from)) = previous {
        from_file = from;
        r.power = verify::power_cache::reuse(&previous, &r.keys, measured);
    }
    if !r.power.is_empty() {
        eprintln!(
            "verify: the power of {} claims reused (nothing they depend on changed since {}), {} measured; --power measures all",
            r.power.len(),
            from_file.display(),
            measured.len()
        );
    }
    r
}

/// A progress bar over `total` steps on a terminal, hidden elsewhere.
fn progress_bar(total: u64, progress: bool) -> indicatif::ProgressBar {
    if !progress {
        return indicatif::ProgressBar::hidden();
    }
    let b = indicatif::ProgressBar::new(total);
    b.set_style(
        indicatif::ProgressStyle::with_template("verify [{bar:30}] {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    b
}

/// What the progress says after `done` of `checked` verdicts and `powered` of `measured`
/// powers, and the claim just finished.
fn progress_message(checked: (u64, u64), powered: (u64, u64), id: &str) -> String {
    if checked.0 < checked.1 || powered.1 == 0 {
        format!("verdicts: {}/{} claims, last {id}", checked.0, checked.1)
    } else {
        format!("power: {}/{} claims, last {id}", powered.0, powered.1)
    }
}

/// Every verdict, then the power of the `measured` claims, in one run over all papers; sorted
/// by claim id. The progress moves per claim: a bar on a terminal, elsewhere a line at every
/// tenth of the power measured (it is the long part: about a minute for every claim).
fn check_claims(
    papers: &[verify::PaperClaims],
    root: &std::path::Path,
    measured: &std::collections::BTreeSet<String>,
    progress: bool,
    slowest: usize,
) -> Result<Vec<verify::Outcome>> {
    use std::sync::atomic::{AtomicU64, Ordering};
    let claims: u64 = papers.iter().map(|p| p.claim.len() as u64).sum();
    let powers = measured.len() as u64;
    let bar = progress_bar(claims + powers, progress);
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let (checked, powered) = (AtomicU64::new(0), AtomicU64::new(0));
    let start = std::time::Instant::now();
    // each verdict's wall clock (the time since the one before it), for --timing
    let last = std::sync::Mutex::new((std::time::Instant::now(), Vec::<(String, f64)>::new()));
    let tick = |id: &str, power: bool| {
        if !power && let Ok(mut l) = last.lock() {
            let now = std::time::Instant::now();
            let t = (now - l.0).as_secs_f64();
            l.1.push((id.to_string(), t));
            l.0 = now;
        }
        let c = if power { &powered } else { &checked };
        c.fetch_add(1, Ordering::Relaxed);
        let (c, p) = (
            checked.load(Ordering::Relaxed),
            powered.load(Ordering::Relaxed),
        );
        bar.set_position(c + p);
        bar.set_message(progress_message((c, claims), (p, powers), id));
        let tenth = powers.div_ceil(10).max(1);
        if !progress && power && powers >= 10 && (p % tenth == 0 || p == powers) {
            eprintln!(
                "verify: power {p}/{powers} claims measured, {:.0} s",
                start.elapsed().as_secs_f64()
            );
        }
    };
    let mut outcomes = verify::run_with_progress(
        papers,
        root,
        verify::kinds::BUILTIN,
        &|id| measured.contains(id),
        &tick,
    )?;
    bar.finish_and_clear();
    if slowest > 0
        && let Ok(l) = last.lock()
    {
        eprint!("verify: {}", verify::phases::slowest(&l.1, slowest));
    }
    outcomes.sort_by(|a, b| report::natural_cmp(&a.id, &b.id));
    Ok(outcomes)
}

/// The summary on stdout, as --format asks (text when nothing is written and no format given).
fn print_summary(format: Option<Fmt>, fresh: &report::Summary) -> Result<()> {
    match format {
        Some(Fmt::Json) => println!("{}", serde_json::to_string_pretty(fresh)?),
        Some(Fmt::Text) => {
            for c in &fresh.claims {
                println!(
                    "{}  {}  {}  {}",
                    c.id,
                    c.equation,
                    c.verdict.as_str(),
                    c.detail
                );
            }
        }
        None => {}
    }
    Ok(())
}

/// --fail-on: whether the run passes its gate (false, naming them, when it fails on failing
/// claims and some fail).
fn gate(fail_on: FailOn, outcomes: &[verify::Outcome]) -> bool {
    let failing: Vec<&str> = outcomes
        .iter()
        .filter(|o| o.verdict == report::Verdict::Fails)
        .map(|o| o.id.as_str())
        .collect();
    if fail_on == FailOn::Fails && !failing.is_empty() {
        eprintln!(
            "verify --fail-on fails: {} claim(s) fail: {}",
            failing.len(),
            failing.join(", ")
        );
        false
    } else {
        true
    }
}

/// --check: the fresh summary against the baseline; false, naming each change, when one moved.
fn compare_with_baseline(
    path: &std::path::Path,
    fresh: &report::Summary,
    partial: bool,
) -> Result<bool> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("reading baseline {}", path.display()))?;
    let baseline: report::Summary = serde_json::from_str(&text)
        .with_context(|| format!("parsing baseline {}", path.display()))?;
    let changes = report::diff(&baseline, fresh, partial);
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
    Ok(false)
}

/// Renders the reports (the coverage table in the index; for the project's own claims the
/// work-precision diagrams) and writes them to `out_dir` atomically.
fn write_reports(
    args: &Args,
    papers: &[verify::PaperClaims],
    outcomes: &[verify::Outcome],
    out_dir: &std::path::Path,
    progress: bool,
    phases: &mut verify::phases::Phases,
) -> Result<()> {
    let custom = args.claims.is_some();
    let mut files = report::render(&verify::paper_infos(papers), outcomes);
    phases.mark("the reports rendered (Markdown, figures, summary.json)");
    // the coverage table opens the index, after its first paragraphs
    let coverage = verify::coverage::table(
        &verify::coverage::compute(papers, args.papers.as_deref()),
        outcomes,
    );
    phases.mark("the coverage of each paper's equations");
    if let Some((_, readme)) = files.iter_mut().find(|(n, _)| n == "README.md") {
        let at = readme
            .find("## Power of the checks")
            .or_else(|| readme.find("## Every claim"))
            .unwrap_or(readme.len());
        let audits = if custom {
            String::new()
        } else {
            verify::audit_reports::index_section(papers)
                + &verify::audit_reports::words_section(papers, out_dir)
        };
        readme.insert_str(at, &format!("{coverage}{audits}"));
    }
    phases.mark("the audits' index and the audits from the papers' words");
    if !custom {
        // the units of every relation of each paper, from its LaTeX and its claims' units
        files.extend(verify::audit_reports::paper_audits(papers));
        phases.mark("each paper's units audit");
        if args.timing {
            if progress {
                eprintln!("verify: work-precision diagrams ...");
            }
            files.extend(
                verify::accuracy::render(args.repeats.max(1)).context("work-precision runs")?,
            );
            phases.mark("the work-precision diagrams (--timing)");
            // where the main job's time goes, measured in this run: a file of timing/, the only
            // folder that holds measured times
            files.push((
                "timing/main_job.md".into(),
                format!(
                    "# Where the main job's time goes\n\nThe wall clock of each part of one `verify --timing` run (the last part, writing, is not in it), on this machine; the work-precision diagrams are made only under --timing.\n\n{}",
                    phases.table()
                ),
            ));
        }
    }
    // the reports link only files that are there: those written now, and for the project's
    // own reports the benchmark pages kept beside them (performance*, written by benches/peers)
    let kept: Vec<String> = if custom {
        Vec::new()
    } else {
        std::fs::read_dir(out_dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .filter(|n| n.starts_with("performance"))
            .chain(
                // the work-precision page of an earlier --timing run
                out_dir
                    .join("timing/accuracy_cost.md")
                    .is_file()
                    .then(|| "timing/accuracy_cost.md".to_string()),
            )
            .chain(
                // the audits from the papers' words an earlier run wrote, kept where the
                // papers' texts are missing (verify::audit_reports::words_section)
                std::fs::read_dir(out_dir.join("audit"))
                    .into_iter()
                    .flatten()
                    .flatten()
                    .map(|e| e.file_name().to_string_lossy().to_string())
                    .filter(|n| n.ends_with("-words.md"))
                    .map(|n| format!("audit/{n}")),
            )
            .collect()
    };
    report::keep_written_links(&mut files, &kept);
    let write = || report::write_atomically(out_dir, &files);
    #[cfg(unix)]
    let written = impactcheck::interrupt::while_writing("verify", write);
    #[cfg(not(unix))]
    let written = write();
    written.with_context(|| format!("writing {}", out_dir.display()))?;
    phases.mark("the reports written");
    if args.timing {
        eprintln!("verify: where the time went:\n{}", phases.table());
    }
    let mut counts = std::collections::BTreeMap::new();
    for o in outcomes {
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
    Ok(())
}

/// The run, in its steps: read and select the claims, validate every file, check every claim
/// (and the power of those measured), print the summary, then compare it with the baseline
/// (--check), stop (--only, or custom claims without --out), or write the reports.
/// `verify audit` and `verify init`: the paper read, its units audited, the audit or a claims
/// file printed.
fn run_paper(command: &Command) -> Result<bool> {
    let (paper, units, preamble, vocabulary) = match command {
        Command::Audit {
            paper,
            units,
            preamble,
            vocabulary,
            ..
        }
        | Command::Init {
            paper,
            units,
            preamble,
            vocabulary,
            ..
        } => (paper, units, preamble, vocabulary),
    };
    if paper.is_dir()
        && let Command::Audit {
            format,
            power: false,
            suggest: false,
            ..
        } = command
    {
        return audit_folder(paper, units.as_deref(), preamble, vocabulary, *format);
    }
    let p = paper::audit::paper::audit_paper(
        paper,
        units.as_deref(),
        preamble,
        vocabulary,
        matches!(command, Command::Init { .. }),
        &mut |line| eprintln!("verify: {line}"),
    )?;
    let (a, name) = (&p.audit, &p.name);
    match command {
        Command::Audit { suggest: true, .. } => print!("{}", p.suggest()),
        Command::Audit { format, power, .. } => {
            let power = power.then(|| p.power());
            match format {
                AuditFmt::Text => {
                    print!("{}", paper::audit::to_text(a));
                    if let Some(pw) = &power {
                        print!("{}", paper::audit::power::to_text(pw));
                    }
                }
                AuditFmt::Json => match &power {
                    None => println!("{}", serde_json::to_string_pretty(a)?),
                    Some(pw) => println!(
                        "{}",
                        serde_json::to_string_pretty(&paper::audit::power::WithPower {
                            audit: a,
                            power: pw
                        })?
                    ),
                },
                AuditFmt::Csv => anyhow::bail!(
                    "--format csv gives a row per paper of a folder: give a folder, or json for one paper"
                ),
                AuditFmt::Markdown => {
                    print!("{}", paper::audit::to_markdown(a, name));
                    if let Some(pw) = &power {
                        print!("{}", paper::audit::power::to_markdown(pw));
                    }
                }
            }
        }
        Command::Init { id, .. } => print!("{}", paper::audit::paper::init_claims(&p, id)),
    }
    Ok(true)
}

/// `verify audit DIR`: every paper under the folder audited (two at a time), a row each, the
/// totals last; a paper that cannot be read a row with its error.
fn audit_folder(
    dir: &Path,
    units: Option<&Path>,
    preamble: &[PathBuf],
    vocabulary: &[PathBuf],
    format: AuditFmt,
) -> Result<bool> {
    use paper::audit::shelf;
    use rayon::prelude::*;
    let papers =
        shelf::papers_in(dir).with_context(|| format!("reading the folder {}", dir.display()))?;
    if papers.is_empty() {
        anyhow::bail!(
            "{}: no paper (a .tex with \\documentclass or a .md with display math)",
            dir.display()
        );
    }
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<shelf::ShelfRow> = papers
        .par_iter()
        .map(|p| {
            let name = p
                .strip_prefix(dir)
                .unwrap_or(p)
                .to_string_lossy()
                .to_string();
            let row = match paper::audit::paper::audit_paper(
                p,
                units,
                preamble,
                vocabulary,
                false,
                &mut |_| {},
            ) {
                Ok(a) => shelf::row_of(name.clone(), &a.audit),
                Err(e) => shelf::ShelfRow {
                    paper: name.clone(),
                    error: Some(format!("{e:#}")),
                    ..Default::default()
                },
            };
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            eprintln!("verify: [{k}/{}] {name}", papers.len());
            row
        })
        .collect();
    match format {
        AuditFmt::Text => print!("{}", shelf::to_text(&rows)),
        AuditFmt::Json => println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({
                "papers": rows,
                "total": shelf::total(&rows),
            }))?
        ),
        AuditFmt::Csv => print!("{}", shelf::table(&rows, false)),
        AuditFmt::Markdown => print!("{}", shelf::table(&rows, true)),
    }
    Ok(true)
}

fn run(args: Args) -> Result<bool> {
    if let Some(command) = &args.command {
        return run_paper(command);
    }
    // claims other than the project's own write a report only where --out says
    let custom = args.claims.is_some();
    let write = !custom || args.out.is_some();
    let claims_dir = args.claims.clone().unwrap_or_else(|| default_dir("verify"));
    let out_dir = args.out.clone().unwrap_or_else(|| default_dir("reports"));
    // an interrupt before the final write leaves the reports as they were, and says so
    #[cfg(unix)]
    if write && !args.check {
        impactcheck::interrupt::install(
            &format!(
                "verify: interrupted by a signal before writing; {} is as it was\n",
                out_dir.display()
            ),
            None,
        );
    }
    let mut phases = verify::phases::Phases::new();
    let all = verify::load_claims_with(&claims_dir, args.papers.as_deref())
        .with_context(|| format!("reading claims from {}", claims_dir.display()))?;
    let papers = verify::select(&all, args.only.as_deref());
    if papers.is_empty() {
        bail!(
            "no claims match --only {}; papers: {}",
            args.only.clone().unwrap_or_default(),
            all.iter()
                .map(|p| p.paper.clone())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    // `check` claims name scenes relative to the folder above the claims folder
    let root = claims_root(&claims_dir);
    let progress = std::io::stderr().is_terminal();
    // every file checked before any claim runs: a bad claim exits 2 with nothing run or written
    verify::validate_all(&papers)?;
    if let Some(missing) = verify::coverage::missing_texts(&papers, args.papers.as_deref()) {
        eprintln!("verify: {missing}");
    }
    for p in &papers {
        verify::coverage::check_equations(p, args.papers.as_deref())?;
        verify::coverage::check_quotes(p, args.papers.as_deref())?;
    }
    phases.mark("the claims read, validated, their equations and quotes found in the papers");
    let mut measured = measured_claims(&args, &papers, write);
    let reused = reusable_power(&args, &papers, &out_dir, &mut measured);
    phases.mark("the power keys (what each claim's power depends on, hashed)");
    let slowest = if args.timing { 12 } else { 0 };
    let mut outcomes = check_claims(&papers, &root, &measured, progress, slowest)?;
    phases.mark("every verdict, and the power of the claims measured");
    for o in &mut outcomes {
        match (reused.get(&o.id), o.power.as_mut()) {
            (Some(p), _) => o.power = Some(p.clone()),
            (None, Some(p)) => p.key = reused.key(&o.id),
            (None, None) => {}
        }
    }
    let fresh = report::summary(&outcomes);
    print_summary(
        match args.format {
            None if !write && !args.check => Some(Fmt::Text),
            f => f,
        },
        &fresh,
    )?;
    // --fail-on fails: the run goes on as usual, and its exit says whether a claim failed
    let partial = args.only.is_some();
    if args.check {
        let path = args
            .baseline
            .clone()
            .unwrap_or_else(|| out_dir.join("summary.json"));
        return Ok(compare_with_baseline(&path, &fresh, partial)? && gate(args.fail_on, &outcomes));
    }
    if partial {
        eprintln!(
            "verify: --only ran {} claims; reports are written only by a full run",
            outcomes.len()
        );
        return Ok(gate(args.fail_on, &outcomes));
    }
    if !write {
        eprintln!(
            "verify: {} claims checked; give --out DIR to write their report",
            outcomes.len()
        );
        return Ok(gate(args.fail_on, &outcomes));
    }
    write_reports(&args, &papers, &outcomes, &out_dir, progress, &mut phases)?;
    Ok(gate(args.fail_on, &outcomes))
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
