//! Faults: a `verify` or `impact sweep --out` interrupted (SIGINT, SIGTERM) or unable to write (a
//! full disk simulated by an output path under a regular file: as root, permissions do not stop
//! a write) leaves the previous reports and outputs intact and says what happened.

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-faults-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn read_all(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).expect("dir").flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(read_all(&p));
        } else {
            out.push((p.clone(), std::fs::read(&p).expect("read")));
        }
    }
    out.sort();
    out
}

/// Starts `cmd`, sends `sig` after `after`, returns (exit code, stderr).
fn interrupt(mut cmd: Command, sig: &str, after: Duration) -> (Option<i32>, String) {
    let child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    std::thread::sleep(after);
    let _ = Command::new("kill")
        .args([&format!("-{sig}"), &child.id().to_string()])
        .status();
    let out = child.wait_with_output().expect("waits");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

#[test]
fn verify_interrupted_leaves_the_reports_as_they_were() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = temp("verify");
    let reports = d.join("reports");
    std::fs::create_dir_all(&reports).expect("dir");
    std::fs::write(reports.join("summary.json"), "{\"previous\": true}\n").expect("write");
    std::fs::write(reports.join("README.md"), "previous\n").expect("write");
    let before = read_all(&reports);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_verify"));
    cmd.args(["--claims"])
        .arg(root.join("verify"))
        .arg("--out")
        .arg(&reports);
    let (code, err) = interrupt(cmd, "INT", Duration::from_millis(400));
    assert_eq!(code, Some(130), "{err}");
    assert!(
        err.contains("interrupted by a signal before writing"),
        "{err}"
    );
    assert_eq!(read_all(&reports), before);
    // no temporary folder left beside it
    let names: Vec<String> = std::fs::read_dir(&d)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    assert_eq!(names, vec!["reports".to_string()]);
}

#[test]
fn sweep_terminated_leaves_its_output_as_it_was() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = temp("sweep");
    let out = d.join("rows.csv");
    std::fs::write(&out, "previous rows\n").expect("write");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_impact"));
    cmd.arg("sweep")
        .arg(root.join("scenes/hertz.toml"))
        .args([
            "--vary",
            "impactor.v0=0.5:2:3000000",
            "--format",
            "csv",
            "--out",
        ])
        .arg(&out);
    let (code, err) = interrupt(cmd, "TERM", Duration::from_millis(400));
    assert_eq!(code, Some(143), "{err}");
    assert!(err.contains("sweep interrupted by a signal"), "{err}");
    assert_eq!(
        std::fs::read_to_string(&out).expect("read"),
        "previous rows\n"
    );
    let left: Vec<_> = std::fs::read_dir(&d).expect("dir").flatten().collect();
    assert_eq!(left.len(), 1, "the temporary file was not removed");
}

#[test]
fn an_output_that_cannot_be_written_is_an_error_that_writes_nothing() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = temp("unwritable");
    let blocker = d.join("a-file");
    std::fs::write(&blocker, "x").expect("write");
    let sweep = Command::new(env!("CARGO_BIN_EXE_impact"))
        .arg("sweep")
        .arg(root.join("scenes/hertz.toml"))
        .args(["--vary", "impactor.v0=0.5:2:10", "--out"])
        .arg(blocker.join("rows.csv"))
        .output()
        .expect("runs");
    assert_eq!(sweep.status.code(), Some(2));
    let err = String::from_utf8_lossy(&sweep.stderr);
    assert!(err.contains("cannot write there"), "{err}");
    let verify = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["--claims"])
        .arg(root.join("verify/classics.toml"))
        .arg("--out")
        .arg(blocker.join("reports"))
        .output()
        .expect("runs");
    assert!(!verify.status.success());
    let err = String::from_utf8_lossy(&verify.stderr);
    assert!(
        err.contains("Not a directory") || err.contains("writing"),
        "{err}"
    );
    assert_eq!(std::fs::read_dir(&d).expect("dir").count(), 1);
}
