//! A claims file may come from anyone: it never makes `verify` write outside the folder named by
//! `--out`. A claim's id names its plot and data files and the file's `report` names its report;
//! both are validated as plain names (letters, digits, `.`, `-`, `_`, not starting with `.`)
//! before anything runs, and the writer refuses any path that is not a plain relative one. Each
//! escape below was possible (an absolute id wrote `pwned.svg` and `.csv` in that folder; a
//! `report` of `../escape.md` wrote beside the output folder) and is now exit 2 with nothing
//! written.
use std::path::{Path, PathBuf};
use std::process::Command;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-paths-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// A claims file in its own folder with one `model` claim over the Hertz scene (a plotted kind:
/// it writes `<id>.svg` and `.csv`), with the given `report` and claim `id`; runs `verify
/// --claims FILE --out DIR` and returns (exit code, stderr, the folder).
fn run(name: &str, report: &str, id: &str) -> (i32, String, PathBuf) {
    let d = temp_dir(name);
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hertz.toml"),
        d.join("hertz.toml"),
    )
    .expect("scene");
    let text = format!(
        "paper = \"t\"\ntitle = \"test\"\nreport = {report:?}\n[symbols]\nm = \"kg\"\nk = \"N/m^1.5\"\nv0 = \"m/s\"\n\"contact.duration\" = \"s\"\n\n[[claim]]\nid = {id:?}\nequation = \"(1)\"\nquote = \"q\"\nkind = \"model\"\nscene = \"hertz.toml\"\nquantity = \"contact.duration\"\nprinted = \"3.2181*(m/k)^(2/5)*v0^(-1/5)\"\nbind = {{ m = \"impactor.mass\", k = \"contact.k\", v0 = \"impactor.v0\" }}\nvary = [\"impactor.v0=0.5:2:3\"]\nrtol = 1e-3\n"
    );
    let claims = d.join("claims.toml");
    std::fs::write(&claims, text).expect("claims");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .arg("--claims")
        .arg(&claims)
        .arg("--out")
        .arg(d.join("out"))
        .output()
        .expect("verify runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).to_string(),
        d,
    )
}

#[test]
fn a_plain_claims_file_writes_under_out() {
    let (code, err, d) = run("plain", "t.md", "t.eq1");
    assert_eq!(code, 0, "{err}");
    assert!(d.join("out/t.md").exists() && d.join("out/t_eq1.svg").exists());
}

#[test]
fn an_absolute_or_climbing_id_is_refused_with_nothing_written() {
    let target = temp_dir("target");
    let absolute = target.join("pwned").display().to_string();
    for (case, id) in [
        ("abs", absolute.as_str()),
        ("up", "../pwned"),
        ("slash", "t/eq1"),
        ("dot", ".hidden"),
    ] {
        let (code, err, d) = run(case, "t.md", id);
        assert_eq!(code, 2, "{case}: {err}");
        assert!(
            err.contains("id") && err.contains("allowed"),
            "{case}: {err}"
        );
        assert!(!d.join("out").exists(), "{case}: out/ written");
        assert!(
            !d.join("pwned.svg").exists() && !d.join("pwned.csv").exists(),
            "{case}"
        );
    }
    assert!(!target.join("pwned.svg").exists() && !target.join("pwned.csv").exists());
}

#[test]
fn a_report_outside_the_output_folder_is_refused_with_nothing_written() {
    let target = temp_dir("report-target");
    let absolute = target.join("escape.md").display().to_string();
    for (case, report) in [
        ("rep-up", "../escape.md"),
        ("rep-abs", absolute.as_str()),
        ("rep-sub", "sub/escape.md"),
        ("rep-ext", "escape.sh"),
    ] {
        let (code, err, d) = run(case, report, "t.eq1");
        assert_eq!(code, 2, "{case}: {err}");
        assert!(
            err.contains("report") && err.contains("allowed"),
            "{case}: {err}"
        );
        assert!(
            !d.join("out").exists() && !d.join("escape.md").exists(),
            "{case}"
        );
    }
    assert!(!target.join("escape.md").exists());
}

/// The writer's own guard, under any caller: a path with `..` or a root is refused before any
/// file is written.
#[test]
fn the_writer_refuses_paths_that_leave_its_folder() {
    let d = temp_dir("writer");
    for bad in ["../x.md", "/tmp/x.md", "a/../../x.md", ""] {
        let files = vec![
            ("ok.md".to_string(), "fine".to_string()),
            (bad.to_string(), "bad".to_string()),
        ];
        let r = impactcheck::report::write_atomically(&d.join("out"), &files);
        assert!(r.is_err(), "{bad:?} accepted");
        assert!(
            !d.join("out/ok.md").exists(),
            "{bad:?}: something was written"
        );
    }
}

/// The relative link targets (file part) of a Markdown text: `[text](target)`, `![alt](target)`.
fn link_targets(md: &str) -> Vec<String> {
    md.split("](")
        .skip(1)
        .filter_map(|after| after.split(')').next())
        .map(|t| t.split('#').next().unwrap_or("").to_string())
        .filter(|t| !t.is_empty() && !t.contains("://") && !t.contains(char::is_whitespace))
        .collect()
}

#[test]
fn a_report_under_out_links_only_files_that_are_there() {
    // the index of the project's reports links the work-precision page and the peers'
    // benchmark page, which a claims file's run under --out does not write
    let (code, err, d) = run("links", "t.md", "t.eq1");
    assert_eq!(code, 0, "{err}");
    let out = d.join("out");
    let mut checked = 0;
    for entry in std::fs::read_dir(&out).expect("out") {
        let p = entry.expect("entry").path();
        if p.extension().is_some_and(|e| e == "md") {
            let text = std::fs::read_to_string(&p).expect("md");
            for t in link_targets(&text) {
                assert!(
                    out.join(&t).exists(),
                    "{} links {t}, which is not in {}",
                    p.display(),
                    out.display()
                );
                checked += 1;
            }
        }
    }
    // the claim's figure and data are linked (and there): the check above saw links
    assert!(checked >= 2, "only {checked} links seen");
    let readme = std::fs::read_to_string(out.join("README.md")).expect("README");
    assert!(
        readme.contains("what accuracy costs in time") && !readme.contains("accuracy_cost.md"),
        "the unwritten page keeps its words without its link"
    );
}
