//! `impact`: run one computation of impactcheck from the command line.

use clap::{Parser, Subcommand, ValueEnum};
use impactcheck::algebra::series::Viscous;
use impactcheck::cli::{self, Format};
use std::process::ExitCode;

/// mimalloc: small allocations (a sweep's rows and solver vectors, the algebra's big
/// integers) cost a fraction of glibc's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser)]
#[command(
    name = "impact",
    version,
    about = "Derive a paper's terms exactly, or run one scene",
    long_about = "impact: the per-computation front end of impactcheck.\n\n\
        `impact run` runs one scene (a model, its parameters in SI units, how to solve; \
        `impact describe MODEL` lists its keys), `impact sweep` runs it over a range of one \
        field. `impact series` builds the Adomian terms a0..aN of the cone equation (18)-(20) \
        of paper 000 (cone impact on a viscoelastic plate) exactly; `impact galerkin` derives \
        the plate coefficients A1..A7 of its (16) for a mode (m, n) and sets each beside the \
        printed one."
)]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq, Debug)]
enum Fmt {
    Text,
    Latex,
    Json,
    Csv,
}

#[derive(Clone, Copy, ValueEnum)]
enum DocFmt {
    Markdown,
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum Visc {
    /// B = d(z^2)/dt = 2 z z' (what the operator (eta/E) d/dt gives)
    #[value(name = "2zz")]
    TwoZZ,
    /// B = z z' (as printed in (18))
    #[value(name = "zz")]
    ZZ,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene (a TOML file naming a model, its parameters in SI units, how to solve).
    Run {
        /// The scene file.
        scene: std::path::PathBuf,
        /// Output format: text or json.
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
        /// Also draw the solution against time into this SVG file.
        #[arg(long)]
        plot: Option<std::path::PathBuf>,
        /// Also write the run's path into this file: the time of every accepted step (the
        /// normal impulse, for rigid-impact), the states there (each named with its SI unit,
        /// `z (m)`) and the events located, as JSON (FILE.json) or CSV (FILE.csv, one row per
        /// step and per event). Models: hertz, cone-plate, ode, pendulum-wall, rigid-impact,
        /// balls-wall (given its stiffness).
        #[arg(long, value_name = "FILE")]
        trace: Option<std::path::PathBuf>,
    },
    /// Run a scene over a range of one field, in parallel on all cores, e.g.
    /// `impact sweep scenes/pendulum_on_wall.toml --vary sigma=0.1:5:50 --format csv`. Every
    /// point is validated before any runs; a point whose solver fails keeps its row, with the
    /// error. A progress bar goes to stderr when it is a terminal.
    Sweep {
        /// The scene file.
        scene: std::path::PathBuf,
        /// KEY=START:STOP:COUNT, KEY a dotted scene path (`sigma`, `impactor.v0`).
        #[arg(long, conflicts_with_all = ["param", "values"])]
        vary: Option<String>,
        /// Space the --vary values geometrically (START, STOP > 0).
        #[arg(long, requires = "vary")]
        log: bool,
        /// Dotted field to vary (with --values; the older form of --vary).
        #[arg(long, requires = "values")]
        param: Option<String>,
        /// Comma-separated values for --param.
        #[arg(long, requires = "param")]
        values: Option<String>,
        /// Output format: text, json or csv.
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Run only shard K of N (0-based), a contiguous block of the points: N machines (or
        /// batch jobs) with K = 0..N-1 together run the sweep once; `impact merge` joins their
        /// JSON outputs.
        #[arg(long)]
        shard: Option<String>,
        /// Write the rows to FILE (through a temporary file renamed at the end: an interrupted
        /// or failed sweep leaves an existing FILE as it was) instead of stdout.
        #[arg(long)]
        out: Option<std::path::PathBuf>,
    },
    /// Every scene key of a model (unit, allowed range, default, meaning) and every outcome
    /// of its run (unit, meaning, sign convention), from the model's own documentation; without
    /// MODEL, every model (verify/MODELS.md is this output). E.g. `impact describe ode`.
    Describe {
        /// The model (`hertz`, `cone-plate`, `rigid-impact`, `pendulum-wall`, `balls-wall`,
        /// `disk-friction`, `ode`); all when absent
        model: Option<String>,
        /// Output format
        #[arg(long, value_enum, default_value = "markdown")]
        format: DocFmt,
    },
    /// Merge the JSON outputs of a sharded sweep (`sweep --shard K/N --format json`) into one,
    /// checking that every point is there exactly once.
    Merge {
        /// The shards' JSON files.
        #[arg(required = true)]
        files: Vec<std::path::PathBuf>,
        /// Output format: json or csv.
        #[arg(long, value_enum, default_value = "json")]
        format: Fmt,
    },
    /// Measure what the benchmark page reports (the peers' script calls these): `hertz`, `cone`,
    /// `pendulum` (work-precision of each method on the peer problems), `algebra` (series a0..a3
    /// symbolic, Galerkin (3,5)), `sweeps` (impacts per second on 1 and all threads), `effects`
    /// (the cost of effects that are off), `scaling` (modes up to (9,9), sweep points),
    /// `hertz-sweep` (the sweep path's integration alone: --repeats Hertz impacts on all threads).
    Bench {
        /// The measurement.
        problem: String,
        /// Tolerances (rtol = atol) for the integrator problems.
        #[arg(long, default_value = "1e-6,1e-9,1e-12")]
        tols: String,
        /// Repeats per point (the median is reported).
        #[arg(long, default_value_t = 301)]
        repeats: usize,
        /// Rigid impacts for `sweeps`.
        #[arg(long, default_value_t = 100_000)]
        rigid: usize,
        /// Cone impacts for `sweeps`.
        #[arg(long, default_value_t = 10_000)]
        cone: usize,
    },
    /// Print the Adomian terms a0..aN of (19)-(20), exactly.
    Series {
        /// Highest term index N (0..=8).
        #[arg(long, default_value_t = 2)]
        order: usize,
        /// How the viscous term of (18) is read.
        #[arg(long, value_enum, default_value = "2zz")]
        viscous: Visc,
        /// Exact values, e.g. `alpha=-3,gamma=5/2,v0=1,a8=0.25,a9=1e-3`; symbols not given stay symbolic.
        #[arg(long, default_value = "")]
        at: String,
        /// Times (s) at which to evaluate a0+...+aN stably in f64 (all symbols must be given).
        #[arg(long, default_value = "")]
        eval_t: String,
        /// Output format: text, latex or json.
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
    /// Derive A1..A7 of (16) and the load sign for mode (m, n), m and n odd.
    Galerkin {
        /// Mode number along x (odd).
        #[arg(long, default_value_t = 1)]
        m: u32,
        /// Mode number along y (odd).
        #[arg(long, default_value_t = 1)]
        n: u32,
        /// Values for numbers beside the exact forms, e.g. `E=2e9,eta=1e6,nu=0.3,a=0.2,b=0.3,h=0.01,rho=1200,Kw=1e6,KG=1e3,CT=10,p1=0,p2=0,tan_theta=1`.
        #[arg(long, default_value = "")]
        at: String,
        /// Output format: text or json.
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
}

/// The format `f` when the command writes it; else an error naming the formats it writes.
fn fmt_of(command: &str, f: Fmt, allowed: &[Fmt]) -> Result<Format, String> {
    if allowed.contains(&f) {
        return Ok(fmt(f));
    }
    let name = |f: &Fmt| format!("{f:?}").to_lowercase();
    Err(format!(
        "--format {}: `impact {command}` writes {}",
        name(&f),
        allowed.iter().map(name).collect::<Vec<_>>().join(" or ")
    ))
}

fn fmt(f: Fmt) -> Format {
    match f {
        Fmt::Text => Format::Text,
        Fmt::Latex => Format::Latex,
        Fmt::Json => Format::Json,
        Fmt::Csv => Format::Csv,
    }
}

fn run(args: Args) -> Result<String, Box<dyn std::error::Error>> {
    match args.command {
        Command::Bench {
            problem,
            tols,
            repeats,
            rigid,
            cone,
        } => {
            let v = match problem.as_str() {
                "algebra" => impactcheck::perf::bench_algebra(repeats),
                "sweeps" => impactcheck::perf::bench_sweeps(rigid, cone)?,
                "hertz-sweep" => impactcheck::perf::bench_hertz_sweep(repeats.max(1))?,
                "effects" => impactcheck::perf::bench_effects(repeats)?,
                "scaling" => impactcheck::perf::bench_scaling(repeats)?,
                p => impactcheck::perf::bench_problem(p, &cli::parse_times(&tols)?, repeats)?,
            };
            Ok(serde_json::to_string_pretty(&v)?)
        }
        Command::Describe { model, format } => {
            let docs = match &model {
                Some(m) => vec![impactcheck::scene::describe(m)?],
                None => impactcheck::scene::DOCS.to_vec(),
            };
            Ok(match format {
                DocFmt::Json if model.is_some() => serde_json::to_string_pretty(docs[0])? + "\n",
                DocFmt::Json => serde_json::to_string_pretty(&docs)? + "\n",
                DocFmt::Markdown if model.is_some() => {
                    impactcheck::models::doc::model_markdown(docs[0])
                }
                DocFmt::Markdown => impactcheck::models::doc::markdown(&docs),
            })
        }
        Command::Merge { files, format } => {
            let format = fmt_of("merge", format, &[Fmt::Json, Fmt::Csv])?;
            Ok(cli::merge(&files, format)?)
        }
        Command::Run {
            scene,
            format,
            plot,
            trace,
        } => {
            let format = fmt_of("run", format, &[Fmt::Text, Fmt::Json])?;
            Ok(cli::run_scene(
                &scene,
                format,
                plot.as_deref(),
                trace.as_deref(),
            )?)
        }
        Command::Sweep {
            scene,
            vary,
            log,
            param,
            values,
            format,
            quiet,
            threads,
            shard,
            out,
        } => {
            let format = fmt_of("sweep", format, &[Fmt::Text, Fmt::Json, Fmt::Csv])?;
            let sv = match (vary, param, values) {
                (Some(v), _, _) => cli::parse_vary(&v, log)?,
                (None, Some(p), Some(v)) => cli::parse_values(&p, &v)?,
                _ => {
                    return Err(
                        "give --vary KEY=START:STOP:COUNT (or --param FIELD --values V1,V2,...)"
                            .into(),
                    );
                }
            };
            let sv = match shard {
                Some(spec) => sv.shard(&spec)?,
                None => sv,
            };
            if let Some(n) = threads {
                if n == 0 {
                    return Err("--threads must be at least 1".into());
                }
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build_global()
                    .map_err(|e| format!("--threads: {e}"))?;
            }
            let progress = !quiet && std::io::IsTerminal::is_terminal(&std::io::stderr());
            let Some(path) = out else {
                // rows already written cannot be taken back: an interrupt ends the stream with
                // a line that says so (a comment line in CSV, not JSON in a JSON stream)
                #[cfg(unix)]
                {
                    impactcheck::interrupt::install(
                        "impact: sweep interrupted by a signal; the rows written to stdout are incomplete\n",
                        None,
                    );
                    impactcheck::interrupt::end_stdout_with(
                        "# impact: sweep interrupted by a signal; the rows above are incomplete",
                    );
                }
                let stdout = std::io::stdout();
                let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
                cli::sweep(&scene, &sv, format, progress, &mut out)?;
                return Ok(String::new());
            };
            // through a temporary beside the output, renamed at the end
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_else(|| "sweep".into());
            let tmp = path.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
            #[cfg(unix)]
            impactcheck::interrupt::install(
                &format!(
                    "impact: sweep interrupted by a signal; {} is as it was\n",
                    path.display()
                ),
                Some(&tmp),
            );
            let file = std::fs::File::create(&tmp)
                .map_err(|e| format!("--out {}: cannot write there: {e}", path.display()))?;
            let mut w = std::io::BufWriter::with_capacity(1 << 16, file);
            let run = cli::sweep(&scene, &sv, format, progress, &mut w).and_then(|()| {
                w.into_inner()
                    .map_err(|e| e.into_error())
                    .and_then(|f| f.sync_all())
                    .map_err(|e| impactcheck::models::RunError::BadArgument {
                        arg: "--out".into(),
                        message: format!("writing {}: {e}", tmp.display()),
                    })
            });
            if let Err(e) = run {
                let _ = std::fs::remove_file(&tmp);
                return Err(e.into());
            }
            let rename = || std::fs::rename(&tmp, &path);
            #[cfg(unix)]
            let renamed = impactcheck::interrupt::while_writing("impact", rename);
            #[cfg(not(unix))]
            let renamed = rename();
            renamed.map_err(|e| {
                let _ = std::fs::remove_file(&tmp);
                format!("--out {}: {e}", path.display())
            })?;
            Ok(String::new())
        }
        Command::Series {
            order,
            viscous,
            at,
            eval_t,
            format,
        } => {
            let visc = match viscous {
                Visc::TwoZZ => Viscous::TwoZZ,
                Visc::ZZ => Viscous::ZZ,
            };
            let at = cli::parse_assignments("--at", &at)?;
            let times = cli::parse_times(&eval_t)?;
            let format = fmt_of("series", format, &[Fmt::Text, Fmt::Latex, Fmt::Json])?;
            Ok(cli::series(order, visc, &at, &times, format)?)
        }
        Command::Galerkin { m, n, at, format } => {
            let format = fmt_of("galerkin", format, &[Fmt::Text, Fmt::Json])?;
            let at = cli::parse_assignments("--at", &at)?;
            Ok(cli::galerkin(m, n, &at, format)?)
        }
    }
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(s) => {
            // a sweep has written its rows already
            if !s.is_empty() {
                // a closed pipe (`impact run ... | head`) ends the output quietly, not in a panic
                use std::io::Write;
                let mut out = std::io::stdout().lock();
                let end = if s.ends_with('\n') { "" } else { "\n" };
                if out
                    .write_all(s.as_bytes())
                    .and_then(|()| out.write_all(end.as_bytes()))
                    .and_then(|()| out.flush())
                    .is_err()
                {
                    return ExitCode::SUCCESS;
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("impact: error: {e}");
            ExitCode::from(2)
        }
    }
}
