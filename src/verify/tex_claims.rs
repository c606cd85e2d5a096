//! `printed_tex` and `printed_from`: a claim's printed side read from LaTeX, so that what is
//! judged is what the paper prints and not a retyped copy ([`crate::algebra::tex`]).
//!
//! `printed_tex = "..."` is LaTeX pasted from a paper. `printed_from = { tag = "(16)", lhs =
//! "A_{5}" }` is the relation of the display tagged (16) whose left side reads as `A_{5}` (its
//! right side); without `lhs`, the right side of the tagged equation. The displays are those of
//! `tex/<paper>.tex` beside the claims file (`verify/tex/`, copied once from the paper's text, so
//! that the reports do not depend on where the papers lie). The file's `[tex_symbols]` maps any
//! other spelling to a symbol (`"z(t)" = "z"`). Either key becomes the claim's `printed` (as
//! text, which the kinds read as before) and the LaTeX read is kept for the report.

use super::{PaperClaims, VerifyError};
use crate::algebra::expr::Expr;
use crate::algebra::tex::{TexSymbols, read_display, read_formula};

/// The blocks of a displays file: (the tag printed after the block, the LaTeX).
fn display_blocks(text: &str) -> Vec<(Option<String>, String)> {
    let mut out: Vec<(Option<String>, String)> = Vec::new();
    for line in text.lines() {
        if let Some(head) = line.strip_prefix("%% block ") {
            out.push((
                head.split(" tag=").nth(1).map(str::to_string),
                String::new(),
            ));
        } else if !line.starts_with('%')
            && let Some(last) = out.last_mut()
        {
            last.1.push_str(line);
            last.1.push('\n');
        }
    }
    out
}

fn bad(file: &PaperClaims, id: &str, field: &str, message: String) -> VerifyError {
    VerifyError::BadClaim {
        id: id.to_string(),
        message: format!("{}: {field}: {message}", file.source.display()),
    }
}

/// The LaTeX of `printed_from`: the side of the tagged relation.
fn from_paper(
    file: &PaperClaims,
    id: &str,
    spec: &toml::Table,
    syms: &TexSymbols,
) -> Result<String, VerifyError> {
    let err = |m: String| bad(file, id, "printed_from", m);
    let tag = spec
        .get("tag")
        .and_then(|t| t.as_str())
        .ok_or_else(|| err("needs `tag` (the equation's label, \"(16)\")".into()))?;
    let tag = tag
        .trim()
        .trim_start_matches('(')
        .trim_end_matches(')')
        .to_string();
    let lhs = match spec.get("lhs") {
        Some(v) => Some(
            v.as_str()
                .ok_or_else(|| err("`lhs` is LaTeX text".into()))
                .and_then(|t| read_formula(t, syms).map_err(|e| err(format!("lhs: {e}"))))?
                .to_string(),
        ),
        None => None,
    };
    if let Some(k) = spec.keys().find(|k| *k != "tag" && *k != "lhs") {
        return Err(err(format!("unknown key `{k}`; allowed: tag, lhs")));
    }
    let dir = file.source.parent().unwrap_or(std::path::Path::new("."));
    let path = dir.join("tex").join(format!("{}.tex", file.paper));
    let text = std::fs::read_to_string(&path)
        .map_err(|e| err(format!("the paper's displays {}: {e}", path.display())))?;
    let mut lefts = Vec::new();
    let mut found_tag = false;
    for (after, tex) in display_blocks(&text) {
        let in_block = tex.contains(&format!("\\tag{{{tag}}}"));
        for row in read_display(&tex, syms) {
            if row.tag.as_deref().or(after.as_deref()) != Some(tag.as_str()) && !in_block {
                continue;
            }
            found_tag = true;
            for rel in row.relations.iter().flatten() {
                let left = rel.sides[0].to_string();
                match &lhs {
                    Some(l) if *l == left && rel.sides.len() > 1 => {
                        return Ok(row_side(&row.tex, l));
                    }
                    None if row.tag.as_deref() == Some(tag.as_str()) && rel.sides.len() > 1 => {
                        return Ok(row.tex.clone());
                    }
                    _ => lefts.push(left),
                }
            }
        }
    }
    Err(err(if found_tag {
        format!(
            "no relation of ({tag}) has the left side {}; its left sides: {}",
            lhs.unwrap_or_default(),
            lefts.join(", ")
        )
    } else {
        format!("no display is tagged ({tag}) in {}", path.display())
    }))
}

/// The LaTeX of a row (kept whole: the report shows the row the side was read from).
fn row_side(row: &str, _lhs: &str) -> String {
    row.trim().to_string()
}

/// The side an equation's LaTeX gives: the right side of the relation whose left side is `lhs`
/// (or of the first relation).
fn read_side(
    tex: &str,
    lhs: Option<&str>,
    syms: &TexSymbols,
) -> Result<Expr, crate::algebra::tex::TexError> {
    let pieces = read_display(tex, syms);
    let mut first_err = None;
    for row in pieces {
        for rel in row.relations {
            match rel {
                Ok(r) if lhs.is_none_or(|l| r.sides[0].to_string() == l) => {
                    return Ok(r.sides.into_iter().last().unwrap_or(Expr::Pi));
                }
                Ok(_) => {}
                Err(e) => {
                    first_err.get_or_insert(e);
                }
            }
        }
    }
    Err(first_err.unwrap_or(crate::algebra::tex::TexError {
        column: 1,
        construct: "a relation with that left side".into(),
        found: tex.into(),
    }))
}

/// Resolves `printed_tex` and `printed_from` of every claim of `file` into `printed`.
pub fn resolve(file: &mut PaperClaims) -> Result<(), VerifyError> {
    let syms = TexSymbols::new(file.tex_symbols.clone());
    let snapshot = file.clone();
    for c in &mut file.claim {
        let tex = c.keys.remove("printed_tex");
        let from = c.keys.remove("printed_from");
        let (field, latex, lhs) = match (tex, from) {
            (None, None) => continue,
            (Some(_), Some(_)) => {
                return Err(bad(
                    &snapshot,
                    &c.head.id,
                    "printed_tex",
                    "give printed_tex or printed_from, not both".into(),
                ));
            }
            (Some(t), None) => {
                let t = t.as_str().map(str::to_string).ok_or_else(|| {
                    bad(&snapshot, &c.head.id, "printed_tex", "is LaTeX text".into())
                })?;
                ("printed_tex", t, None)
            }
            (None, Some(f)) => {
                let spec = f.as_table().cloned().ok_or_else(|| {
                    bad(
                        &snapshot,
                        &c.head.id,
                        "printed_from",
                        "is a table { tag = \"(16)\", lhs = \"A_{5}\" }".into(),
                    )
                })?;
                let latex = from_paper(&snapshot, &c.head.id, &spec, &syms)?;
                let lhs = spec
                    .get("lhs")
                    .and_then(|v| v.as_str())
                    .and_then(|t| read_formula(t, &syms).ok())
                    .map(|e| e.to_string());
                ("printed_from", latex, lhs)
            }
        };
        let e = read_side(&latex, lhs.as_deref(), &syms)
            .map_err(|e| bad(&snapshot, &c.head.id, field, format!("`{latex}`: {e}")))?;
        // with `printed` beside `printed_from` and its `lhs`, the side read stands for the
        // left side's symbol in `printed` (A2 of (16) in `A2*Lop*fd`, a term of (15))
        let e = match (c.keys.get("printed"), &lhs) {
            (None, _) => e,
            (Some(p), Some(name)) if field == "printed_from" => {
                let text = p.as_str().unwrap_or_default();
                let outer = crate::algebra::expr::parse(text).map_err(|err| {
                    bad(&snapshot, &c.head.id, "printed", format!("`{text}`: {err}"))
                })?;
                if !outer.symbols().contains(name) {
                    return Err(bad(
                        &snapshot,
                        &c.head.id,
                        "printed",
                        format!(
                            "`{text}` does not use `{name}`, the left side printed_from reads: with printed_from, printed is a formula of that symbol"
                        ),
                    ));
                }
                outer.substitute(&|s| (s == name.as_str()).then(|| e.clone()))
            }
            (Some(_), _) => {
                return Err(bad(
                    &snapshot,
                    &c.head.id,
                    field,
                    "give printed or printed_tex/printed_from, not both (printed beside printed_from needs its lhs: the symbol printed uses)".into(),
                ));
            }
        };
        if let Some(s) = e.symbols().into_iter().find(|s| s.starts_with('{')) {
            return Err(bad(
                &snapshot,
                &c.head.id,
                field,
                format!(
                    "`{s}` is a function application or a tuple the formula language has no name for: map its spelling to a symbol in [tex_symbols]"
                ),
            ));
        }
        c.keys
            .insert("printed".into(), toml::Value::String(e.to_string()));
        c.head.tex = Some(latex);
    }
    Ok(())
}
