//! The Python package's tests, run by `cargo test` (issue 55), so that the README's one test
//! command runs them too: the wheel of `python/` built and installed with pip into a virtual
//! environment under `target/pyvenv` (made on the first run; pandas, pytest, dask, distributed,
//! nbclient, nbformat, ipykernel and matplotlib from PyPI beside it), then `pytest python/tests`:
//! each function against its command-line twin (the binaries this `cargo test` built, named to
//! pytest by `IMPACTCHECK_BIN`), the Dask sweeps on a `LocalCluster` with a worker killed, and
//! `examples/quickstart.ipynb` executed. Needs `python3` with `venv` and pip's registry; without
//! them it fails saying which step could not run.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What the package's tests import beside the package.
const TEST_DEPENDENCIES: &[&str] = &[
    "pandas",
    "pytest",
    "dask",
    "distributed",
    "nbclient",
    "nbformat",
    "ipykernel",
    "matplotlib",
];

/// A command in the repository's root, without the variables cargo sets for this test (a
/// nested cargo, maturin's, must see the workspace as a user's shell does); fails naming the
/// step with its output.
fn step(what: &str, program: &Path, args: &[&str], bin: &Path) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cmd = Command::new(program);
    cmd.current_dir(root).args(args);
    for (key, _) in std::env::vars_os() {
        let k = key.to_string_lossy();
        let cargo_set = k.starts_with("CARGO_PKG_")
            || k.starts_with("CARGO_BIN_EXE_")
            || [
                "CARGO_MANIFEST_DIR",
                "CARGO_MANIFEST_PATH",
                "CARGO_CRATE_NAME",
                "CARGO_PRIMARY_PACKAGE",
                "CARGO_TARGET_TMPDIR",
            ]
            .contains(&k.as_ref());
        if cargo_set {
            cmd.env_remove(&key);
        }
    }
    cmd.env("IMPACTCHECK_BIN", bin);
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: {} could not start: {e}", program.display()));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    eprintln!("{what}: done");
}

#[test]
fn the_python_package_passes_its_tests() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_impact"))
        .parent()
        .expect("the binaries' folder")
        .to_path_buf();
    let venv = root.join("target").join("pyvenv");
    let python = venv.join("bin").join("python");
    if !python.exists() {
        let venv_arg = venv.to_string_lossy().into_owned();
        step(
            "making the virtual environment target/pyvenv",
            Path::new("python3"),
            &["-m", "venv", &venv_arg],
            &bin,
        );
    }
    let mut install = vec![
        "-m",
        "pip",
        "install",
        "--quiet",
        "--disable-pip-version-check",
        "./python",
    ];
    install.extend(TEST_DEPENDENCIES);
    step(
        "pip install ./python (the wheel, built by maturin) and the tests' dependencies",
        &python,
        &install,
        &bin,
    );
    step(
        "pytest python/tests",
        &python,
        &[
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            "python/tests",
        ],
        &bin,
    );
}
