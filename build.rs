//! The code's hash, for the reuse of measured power (src/verify/power_cache.rs): every file
//! under `src/`, with `Cargo.toml`, `Cargo.lock` and this file, in path order, hashed into the
//! environment variable `IMPACTCHECK_CODE_HASH`.

use std::path::{Path, PathBuf};

include!("src/verify/fnv.rs");

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn main() {
    let mut all = Vec::new();
    files(Path::new("src"), &mut all);
    all.extend(["Cargo.toml", "Cargo.lock", "build.rs"].map(PathBuf::from));
    all.sort();
    let mut h = Fnv::new();
    for p in &all {
        h.write(p.to_string_lossy().replace('\\', "/").as_bytes());
        h.write(&std::fs::read(p).unwrap_or_default());
    }
    println!("cargo:rustc-env=IMPACTCHECK_CODE_HASH={}", h.hex());
    for p in ["src", "Cargo.toml", "Cargo.lock", "build.rs"] {
        println!("cargo:rerun-if-changed={p}");
    }
}
