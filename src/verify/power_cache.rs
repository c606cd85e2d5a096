//! The power of a claim measured once and reused while nothing it depends on changes (issue 45):
//! the main job measures only the claims whose key differs from the one `summary.json` holds.
//!
//! A claim's power ([`super::power`]) is a function of the code, the claim as written, its
//! file's other tables, the files its values name, and the paper it reads. Its key hashes each
//! ([`super::fnv`], FNV-1a 128):
//! - the code: every file under `src/` with `Cargo.toml`, `Cargo.lock` and `build.rs`, hashed
//!   by `build.rs` at compile time (any edit of the code, the misprint generators included,
//!   changes every key);
//! - the claim's table as parsed (`id`, its kind's keys, `where`, ...), and the claims file's
//!   tables other than `[[claim]]` (`[symbols]`, `[definitions]`, `[tex_symbols]`, ...);
//! - every file a string of the claim names, relative to the claims file (its scenes);
//! - the paper's displays as read (`printed_from` and `[definitions_from]` read them).
//!
//! What is not in the key cannot change the measurement: the misprints are generated from the
//! claim's printed side alone, with a fixed seed, and checked by the kinds' code. `verify
//! --power` measures every claim afresh, and CI's `verify --check --power-sample` measures a
//! sample against the committed numbers.

use super::PaperClaims;
use super::fnv::Fnv;
use std::collections::BTreeMap;
use std::path::Path;

/// The hash of the code this binary was built from (`build.rs`).
pub const CODE: &str = env!("IMPACTCHECK_CODE_HASH");

/// Every string inside `v`, depth first.
fn strings<'v>(v: &'v toml::Value, out: &mut Vec<&'v str>) {
    match v {
        toml::Value::String(s) => out.push(s),
        toml::Value::Array(a) => a.iter().for_each(|x| strings(x, out)),
        toml::Value::Table(t) => t.values().for_each(|x| strings(x, out)),
        _ => {}
    }
}

/// The key of each claim of `papers`, by id; a file that cannot be read again gives none (its
/// claims are then measured).
pub fn keys(papers: &[PaperClaims]) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for p in papers {
        let Ok(text) = std::fs::read_to_string(&p.source) else {
            continue;
        };
        let Ok(mut table) = toml::from_str::<toml::Table>(&text) else {
            continue;
        };
        let dir = p.source.parent().unwrap_or(Path::new("."));
        let claims = table.remove("claim");
        let mut file = Fnv::new();
        file.write(CODE.as_bytes());
        file.write(serde_json::to_string(&table).unwrap_or_default().as_bytes());
        if let Ok((blocks, _, source)) = super::tex_claims::paper_displays(p) {
            file.write(format!("{blocks:?}").as_bytes());
            file.write(&std::fs::read(source).unwrap_or_default());
        }
        let base = file.hex();
        let Some(toml::Value::Array(claims)) = claims else {
            continue;
        };
        for c in &claims {
            let Some(id) = c.get("id").and_then(toml::Value::as_str) else {
                continue;
            };
            let mut h = Fnv::new();
            h.write(base.as_bytes());
            h.write(serde_json::to_string(c).unwrap_or_default().as_bytes());
            let mut named = Vec::new();
            strings(c, &mut named);
            for s in named {
                let f = dir.join(s);
                if f.is_file() {
                    h.write(s.as_bytes());
                    h.write(&std::fs::read(&f).unwrap_or_default());
                }
            }
            out.insert(id.to_string(), h.hex());
        }
    }
    out
}

/// The measured power of `previous` (a `summary.json`) that this run can reuse: each claim of
/// `measured` whose power there carries the key `keys` gives it now, taken out of `measured`.
pub fn reuse(
    previous: &crate::report::Summary,
    keys: &BTreeMap<String, String>,
    measured: &mut std::collections::BTreeSet<String>,
) -> BTreeMap<String, crate::report::Power> {
    let mut out = BTreeMap::new();
    for c in &previous.claims {
        if let (Some(p), Some(k)) = (&c.power, keys.get(&c.id))
            && p.key.as_ref() == Some(k)
            && measured.remove(&c.id)
        {
            out.insert(c.id.clone(), p.clone());
        }
    }
    out
}
