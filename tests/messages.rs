//! Every message points (issue 54): each test runs a front end on one bad input and checks that
//! the message names what is wrong as it is (missing as missing, an unknown unit as unknown with
//! the nearest known one, one OS error, a TOML error with its line and a caret on lines of their
//! own, a LaTeX error with the line in the paper), and fails on the text the tool printed before.

use std::path::Path;
use std::process::{Command, Output, Stdio};

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

fn impact(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .output()
        .expect("impact runs")
}

fn verify(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("verify runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

fn repo(p: &str) -> String {
    format!("{}/{p}", env!("CARGO_MANIFEST_DIR"))
}

/// The oscillator scene with `from` replaced by `to`, written into `dir`.
fn oscillator_with(dir: &Path, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(repo("scenes/oscillator_wall.toml")).expect("scene");
    assert!(text.contains(from), "the scene has `{from}`");
    let p = dir.join("scene.toml");
    std::fs::write(&p, text.replacen(from, to, 1)).expect("written");
    p.display().to_string()
}

#[test]
fn an_unknown_unit_is_unknown_with_the_nearest_known_one() {
    let d = Scratch::new("msg-unit");
    let o = impact(&["run", &oscillator_with(&d, "w = \"Hz\"", "w = \"Hzz\"")]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("units.w = \"Hzz\""), "{e}");
    assert!(
        e.contains("unknown unit `Hzz` (nearest known: `Hz`)"),
        "{e}"
    );
    assert!(!e.contains("out of range"), "{e}");
}

#[test]
fn a_parameter_missing_from_its_table_is_called_missing() {
    let d = Scratch::new("msg-param");
    let o = impact(&["run", &oscillator_with(&d, "zeta = 0.05", "")]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("`zeta` is not t, a state or a parameter"), "{e}");
    assert!(e.contains("missing from [parameters]"), "{e}");
    assert!(!e.contains("out of range"), "{e}");
}

#[test]
fn a_value_that_is_no_number_is_not_a_number() {
    let d = Scratch::new("msg-number");
    let p = d.join("s.toml");
    std::fs::write(
        &p,
        "model = \"hertz\"\n[impactor]\nmass = \"1 kg\"\nv0 = 1.0\n[contact]\nk = 1.0\n",
    )
    .expect("written");
    let o = impact(&["run", &p.display().to_string()]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("impactor.mass = \"1 kg\": not a number"), "{e}");
    assert!(e.contains("no unit is written"), "{e}");
    assert!(!e.contains("out of range"), "{e}");
}

#[test]
fn a_missing_file_says_its_os_error_once() {
    let d = Scratch::new("msg-missing");
    let o = verify(&d, &["--claims", "nofile.toml"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.matches("os error 2").count(), 1, "{e}");
    assert!(e.contains("nofile.toml: cannot read"), "{e}");
}

#[test]
fn a_toml_error_gives_its_line_and_a_caret_on_lines_of_their_own() {
    let d = Scratch::new("msg-toml");
    std::fs::write(d.join("bad.toml"), "paper = \"x\"\ntitle = 3 3\n").expect("written");
    let o = verify(&d, &["--claims", "bad.toml"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    let lines: Vec<&str> = e.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.contains("bad.toml: line 2, column 9:"))
        .unwrap_or_else(|| panic!("the line and column: {e}"));
    assert_eq!(
        lines.get(at + 1).map(|l| l.trim()),
        Some("2 | title = 3 3"),
        "{e}"
    );
    let caret = lines.get(at + 2).copied().unwrap_or_default();
    assert_eq!(
        caret.trim_start().trim_start_matches('|').trim(),
        "^^^",
        "{e}"
    );
    // the caret stands under the `3 3`, as the source line above it is indented
    assert_eq!(caret.find('^'), lines[at + 1].find("3 3"), "{e}");

    // an empty claims file: what is missing, at line 1
    std::fs::write(d.join("empty.toml"), "").expect("written");
    let e = stderr(&verify(&d, &["--claims", "empty.toml"]));
    assert!(
        e.contains("empty.toml: line 1, column 1: missing field `paper`\n"),
        "{e}"
    );
}

#[test]
fn a_scene_toml_error_gives_its_line_and_caret() {
    let d = Scratch::new("msg-scene-toml");
    let p = d.join("s.toml");
    std::fs::write(&p, "model = \"hertz\"\n[impactor\nmass = 1\n").expect("written");
    let e = stderr(&impact(&["run", &p.display().to_string()]));
    assert!(e.contains("not valid TOML: line 2, column 10: "), "{e}");
    assert!(e.contains("\n  2 | [impactor\n"), "{e}");
    assert!(e.contains("|          ^\n"), "{e}");
}

/// A paper whose display (1) holds a construct the reader lacks, and a claim that reads it.
fn paper_with_unread_display(d: &Path, file: &str) {
    std::fs::write(
        d.join("paper.tex"),
        "\\documentclass{article}\n\\begin{document}\nA ball of mass $m$.\n\\begin{equation}\ne = \\frac{v_1}{v_0} \\mathbin{\\star} \\big) \\label{eq:e}\n\\end{equation}\n\\end{document}\n",
    )
    .expect("written");
    std::fs::write(
        d.join("claims.toml"),
        format!(
            "paper = \"lt\"\ntitle = \"a test\"\nfile = \"{file}\"\nreport = \"lt.md\"\nequations = [\"1\"]\n[symbols]\ne = \"1\"\nv1 = \"m/s\"\nv0 = \"m/s\"\n[[claim]]\nid = \"lt.eq1\"\nequation = \"(1)\"\nreading = \"e\"\nkind = \"dimension\"\nprinted_from = {{ label = \"eq:e\" }}\nexpect = \"1\"\n"
        ),
    )
    .expect("written");
}

#[test]
fn a_latex_error_names_the_line_in_the_paper() {
    let d = Scratch::new("msg-latex");
    paper_with_unread_display(&d, "paper.tex");
    let o = verify(&d, &["--claims", "claims.toml"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("printed_from: line 5 of "), "{e}");
    assert!(e.contains("paper.tex: (1) is not read: "), "{e}");
    assert!(e.contains("the command `\\mathbin`"), "{e}");
}

#[test]
fn a_missing_paper_is_said_once_with_where_it_was_looked_for() {
    let d = Scratch::new("msg-no-paper");
    std::fs::write(
        d.join("claims.toml"),
        "paper = \"np\"\ntitle = \"t\"\nfile = \"nothere.txt\"\nreport = \"np.md\"\nequations = []\n[symbols]\nx = \"m\"\n[[claim]]\nid = \"np.a\"\nequation = \"(1)\"\nreading = \"x is a length\"\nkind = \"dimension\"\nprinted = \"x\"\nexpect = \"m\"\n",
    )
    .expect("written");
    let o = verify(&d, &["--claims", "claims.toml"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{e}");
    assert_eq!(e.matches("was not found").count(), 1, "{e}");
    assert!(e.contains("(nothere.txt; looked in "), "{e}");
    let here = d.canonicalize().expect("a folder").display().to_string();
    assert!(e.contains(&here), "the claims' folder is named: {e}");
}

#[test]
fn the_help_names_no_internal_file_and_no_old_promise() {
    let h = String::from_utf8_lossy(&impact(&["--help"]).stdout).to_string();
    assert!(h.contains("impact run"), "{h}");
    for internal in ["000_92d54b11128ea1ec.txt", "peers.py", "benches/"] {
        assert!(!h.contains(internal), "{internal}: {h}");
    }
    let d = Scratch::new("msg-help");
    let h = String::from_utf8_lossy(&verify(&d, &["--help"]).stdout).to_string();
    assert!(h.contains("--timing"), "{h}");
    assert!(!h.contains("always measures"), "{h}");
}

#[test]
fn a_format_a_command_does_not_write_is_refused() {
    for (args, says) in [
        (
            vec!["run", "scenes/hertz.toml", "--format", "latex"],
            "`impact run` writes text or json",
        ),
        (
            vec![
                "sweep",
                "scenes/hertz.toml",
                "--vary",
                "impactor.v0=1:2:2",
                "--format",
                "latex",
            ],
            "`impact sweep` writes text or json or csv",
        ),
        (
            vec!["series", "--format", "csv"],
            "`impact series` writes text or latex or json",
        ),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_impact"))
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(&args)
            .output()
            .expect("runs");
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.contains(says), "{args:?}: {e}");
        assert!(o.stdout.is_empty(), "{args:?}: nothing printed");
    }
}

#[test]
fn a_sweep_csv_has_each_column_once_and_a_common_warning_in_full_once() {
    let o = impact(&[
        "sweep",
        &repo("scenes/balls_wall.toml"),
        "--vary",
        "wall_stiffness_ratio=1:100:3",
        "--format",
        "csv",
        "--quiet",
    ]);
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    let header: Vec<&str> = out.lines().next().unwrap_or_default().split(',').collect();
    let mut seen = std::collections::BTreeSet::new();
    for h in &header {
        assert!(seen.insert(*h), "column {h} twice: {header:?}");
    }
    assert_eq!(header[0], "wall_stiffness_ratio");

    // small speeds: every row's atol is tightened, each by its own numbers
    let o = impact(&[
        "sweep",
        &repo("scenes/hertz.toml"),
        "--vary",
        "impactor.v0=1e-6:1e-4:5",
        "--log",
        "--format",
        "csv",
        "--quiet",
    ]);
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    assert_eq!(out.matches("atol tightened from").count(), 1, "{out}");
    assert_eq!(out.matches("like row 0: 1e-9 ").count(), 4, "{out}");
    // the last row keeps its own numbers: the atol asked, the atol used, its scale 1e-4 m
    let last = out.lines().last().unwrap_or_default();
    assert!(
        last.contains(",like row 0: 1e-9 1.0000000000000002e-13 1e-4,,4"),
        "{last}"
    );
    let e = stderr(&o);
    assert!(e.contains("5 rows warn `atol tightened from # to #"), "{e}");
}

#[test]
#[cfg(unix)]
fn a_sweep_to_stdout_ended_by_a_signal_ends_with_a_line_saying_so() {
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args([
            "sweep",
            &repo("scenes/hertz.toml"),
            "--vary",
            "impactor.v0=0.1:10:3000000",
            "--format",
            "csv",
            "--quiet",
            "--threads",
            "1",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdout = child.stdout.take().expect("stdout");
    // rows are coming: then the signal
    let mut first = [0u8; 4096];
    stdout.read_exact(&mut first).expect("rows");
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    let mut rest = Vec::new();
    stdout.read_to_end(&mut rest).expect("the rest");
    let code = child.wait().expect("ends").code();
    assert_eq!(
        code,
        Some(128 + 15),
        "ended by SIGTERM, with a non-zero exit"
    );
    let all = String::from_utf8_lossy(&[&first[..], &rest[..]].concat()).to_string();
    assert_eq!(
        all.lines().last(),
        Some("# impact: sweep interrupted by a signal; the rows above are incomplete"),
        "{}",
        &all[all.len().saturating_sub(300)..]
    );
}
