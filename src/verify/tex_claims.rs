//! `printed_tex` and `printed_from`: a claim's printed side read from LaTeX, so that what is
//! judged is what the paper prints and not a retyped copy ([`crate::paper::formulas`]).
//!
//! `printed_tex = "..."` is LaTeX pasted from a paper. `printed_from = { tag = "(16)", lhs =
//! "A_{5}" }` is the relation of the display numbered (16) whose left side reads as `A_{5}` (its
//! right side); without `lhs`, the right side of the numbered equation; `{ label =
//! "eq:restitution" }` the relation with that `\label`; `{ display = 7 }` the paper's 7th
//! display, numbered or not (as `verify audit` counts them); `relation = 2` the second relation
//! of the row or display named (`a = b, \quad c = d`). The displays are those of the paper's own
//! LaTeX source when the file's `file` is a `.tex` beside the claims file, numbered as LaTeX
//! numbers them ([`read_document`](crate::paper::source::document::read_document)), else those of `tex/<paper>.tex` beside the claims file
//! (`verify/tex/`, copied once from the seeds' text, so that the reports do not depend on where
//! the papers lie). The file's `[tex_symbols]` maps any other spelling to a symbol (`"z(t)" =
//! "z"`). Either key becomes the claim's `printed` (as text, which the kinds read as before) and
//! the LaTeX read is kept for the report.

use super::{ClaimSpec, PaperClaims, VerifyError};
use crate::algebra::expr::Expr;
use crate::paper::formulas::matrix::{TexMatrix, factor_of, matrix_value, read_matrix_display};
use crate::paper::formulas::{TexSymbols, read_formula};
use crate::paper::source::blocks::{blocks_at, display_blocks};
use crate::paper::source::display::read_display;
use crate::paper::source::document::Document;

/// A paper's displays (each with the number printed after it, if any), its document when read
/// from its LaTeX source, and the path read.
pub type PaperDisplays = (
    Vec<(Option<String>, String)>,
    Option<Document>,
    std::path::PathBuf,
);

/// The displays a claims file's printed sides are read from: the paper's own LaTeX source when
/// its `file` is a `.tex` (read as LaTeX numbers it, [`read_document`](crate::paper::source::document::read_document)); else the extract
/// `tex/<paper>.tex` beside the claims file (the seeds' cache); else its `file`, a text with
/// display math (`$$ ... $$` with the number printed after each). A `file` is looked for in
/// `--papers DIR`, beside the claims file, then among the seeds
/// ([`super::coverage::text_path`]). With the document when there is one, and the path read.
pub fn paper_displays(file: &PaperClaims) -> Result<PaperDisplays, String> {
    let dir = file.source.parent().unwrap_or(std::path::Path::new("."));
    let source = || {
        let path = super::coverage::text_path(file, file.papers_dir.as_deref())?;
        Some(
            std::fs::read_to_string(&path)
                .map_err(|e| format!("the paper's source {}: {e}", path.display()))
                .map(|text| {
                    let (blocks, doc) = blocks_at(&text, path.parent(), "");
                    (blocks, doc, path)
                }),
        )
    };
    let extract = dir.join("tex").join(format!("{}.tex", file.paper));
    if !file.file.ends_with(".tex") && extract.is_file() {
        let text = std::fs::read_to_string(&extract)
            .map_err(|e| format!("the paper's displays {}: {e}", extract.display()))?;
        return Ok((display_blocks(&text), None, extract));
    }
    source().unwrap_or_else(|| {
        let tried = match &file.papers_dir {
            Some(d) => format!("{}, ", d.display()),
            None => String::new(),
        };
        Err(if file.file.is_empty() {
            format!(
                "no paper to read: no `file` in the claims file and no displays extract {}",
                extract.display()
            )
        } else {
            format!(
                "the paper's source `{}` is not in {tried}{} or the seeds, and there is no displays extract {}",
                file.file,
                dir.display(),
                extract.display()
            )
        })
    })
}

fn bad(file: &PaperClaims, id: &str, field: &str, message: String) -> VerifyError {
    VerifyError::BadClaim {
        id: id.to_string(),
        message: format!("{}: {field}: {message}", file.source.display()),
    }
}

/// The LaTeX of `printed_from` (or of an entry of `printed_equations_from`,
/// `[definitions_from]`, named by `field`): the row of the tagged relation, or with `after`
/// (`after = "(2.9)"`, `lhs` required) of the untagged displays between the tagged one and the
/// next tagged one (where papers print the definitions that go with an equation); and the left
/// side asked for.
fn from_paper(
    file: &PaperClaims,
    id: &str,
    field: &str,
    spec: &toml::Table,
    syms: &TexSymbols,
    matrix: bool,
) -> Result<(String, Option<String>), VerifyError> {
    let err = |m: String| bad(file, id, field, m);
    let label = |key: &str| {
        spec.get(key).map(|t| {
            t.as_str()
                .map(|t| {
                    t.trim()
                        .trim_start_matches('(')
                        .trim_end_matches(')')
                        .to_string()
                })
                .ok_or_else(|| err(format!("`{key}` is the equation's label, \"(16)\"")))
        })
    };
    let (blocks, doc, path) = paper_displays(file).map_err(&err)?;
    if let Some(v) = spec.get("display") {
        return by_display(&blocks, v, spec)
            .map(|tex| (tex, None))
            .map_err(&err);
    }
    let by_label = match spec.get("label") {
        None => None,
        Some(v) => {
            let name = v.as_str().ok_or_else(|| {
                err("`label` is the name of a \\label{..}, \"eq:restitution\"".into())
            })?;
            let doc = doc.as_ref().ok_or_else(|| {
                err(format!(
                    "label = \"{name}\" needs the paper's LaTeX source (`file = \"paper.tex\"` beside the claims file); {} holds displays only",
                    path.display()
                ))
            })?;
            let labels: Vec<&str> = doc.labels.iter().map(|(l, _)| l.as_str()).collect();
            Some(
                doc.number_of(name)
                    .ok_or_else(|| {
                        err(format!(
                            "no numbered relation has \\label{{{name}}} in {}; its labels: {}",
                            path.display(),
                            if labels.is_empty() {
                                "none".to_string()
                            } else {
                                labels.join(", ")
                            }
                        ))
                    })?
                    .to_string(),
            )
        }
    };
    let (tag, after) = match (
        label("tag").transpose()?,
        label("after").transpose()?,
        by_label,
    ) {
        (Some(t), None, None) | (None, None, Some(t)) => (t, false),
        (None, Some(a), None) => (a, true),
        _ => {
            return Err(err(
                "needs one of `tag` (the equation's number, \"(16)\"), `label` (its \\label, \"eq:restitution\") or `after` (the untagged displays after it), and only one: not both of any two".into(),
            ));
        }
    };
    let lhs = match spec.get("lhs") {
        Some(v) => Some(
            v.as_str()
                .ok_or_else(|| err("`lhs` is LaTeX text".into()))
                .and_then(|t| read_formula(t, syms).map_err(|e| err(format!("lhs: {e}"))))?
                .to_string(),
        ),
        None if after => {
            return Err(err(
                "`after` needs `lhs` (the left side of the relation read)".into(),
            ));
        }
        None => None,
    };
    if let Some(k) = spec.keys().find(|k| {
        ![
            "tag", "label", "after", "lhs", "at", "form", "relation", "link",
        ]
        .contains(&k.as_str())
    }) {
        return Err(err(format!(
            "unknown key `{k}`; allowed: tag, label, after, lhs, at, form, relation, link, display"
        )));
    }
    if spec.contains_key("relation") && spec.contains_key("lhs") {
        return Err(err(
            "give `lhs` (the relation's left side) or `relation` (its place in the row), not both"
                .into(),
        ));
    }
    let tagged = |tex: &str, after_tag: &Option<String>| {
        tex.contains(&format!("\\tag{{{tag}}}")) || after_tag.as_deref() == Some(tag.as_str())
    };
    let mut chosen: Vec<&(Option<String>, String)> = Vec::new();
    if after {
        // the untagged blocks after the tagged one, up to the next tagged block
        let start = blocks.iter().position(|(a, tex)| tagged(tex, a));
        if let Some(k) = start {
            chosen.extend(
                blocks[k + 1..]
                    .iter()
                    .take_while(|(a, tex)| a.is_none() && !tex.contains("\\tag{")),
            );
        }
    } else {
        chosen = blocks.iter().collect();
    }
    let mut lefts = Vec::new();
    let mut found_tag = false;
    // the first relation of the tagged rows the reader could not read, with where it stands
    let mut unread: Option<String> = None;
    // a left side equal to `lhs` first; then one that is `lhs` times a factor (`m_2 B_A`)
    for exact in [true, false] {
        for (block_after, tex) in &chosen {
            let in_block = after || tex.contains(&format!("\\tag{{{tag}}}"));
            // a matrix's rows are not the display's: the display is read with its matrices
            // taken out, and the whole block is what the claim shows
            let rows = if matrix {
                match read_matrix_display(tex, syms) {
                    Ok((rows, _)) => rows,
                    // a display that holds the tag asked for must read; another is passed over
                    Err(e) if in_block || block_after.as_deref() == Some(tag.as_str()) => {
                        return Err(err(format!("`{}`: {e}", tex.trim())));
                    }
                    Err(_) => continue,
                }
            } else {
                read_display(tex, syms)
            };
            for row in rows {
                if !after
                    && row.tag.as_deref().or(block_after.as_deref()) != Some(tag.as_str())
                    && !in_block
                {
                    continue;
                }
                found_tag = true;
                let shown = if matrix {
                    tex.trim().to_string()
                } else {
                    row.tex.trim().to_string()
                };
                if let Some(Err(e)) = row.relations.iter().find(|r| r.is_err()) {
                    unread.get_or_insert_with(|| format!("`{shown}`: {e}"));
                }
                for rel in row.relations.iter().flatten() {
                    let left = rel.sides[0].to_string();
                    match &lhs {
                        Some(l) if exact && *l == left && rel.sides.len() > 1 => {
                            return Ok((shown, lhs.clone()));
                        }
                        Some(l)
                            if !exact
                                && rel.sides.len() > 1
                                && factor_of(&rel.sides[0], l).is_some() =>
                        {
                            return Ok((shown, lhs.clone()));
                        }
                        None if exact
                            && row.tag.as_deref().or(block_after.as_deref())
                                == Some(tag.as_str())
                            && rel.sides.len() > 1 =>
                        {
                            return Ok((shown, None));
                        }
                        _ if exact => lefts.push(left),
                        _ => {}
                    }
                }
            }
        }
    }
    Err(err(not_found(
        &tag,
        after,
        found_tag,
        (lhs.unwrap_or_default(), &lefts),
        unread.as_deref(),
        &path,
    )))
}

/// Why `from_paper` found no relation: the tagged row unread (where it stands in the paper and
/// the reader's error), no relation with the left side asked for, or no display at all.
fn not_found(
    tag: &str,
    after: bool,
    found_tag: bool,
    (lhs, lefts): (String, &[String]),
    unread: Option<&str>,
    path: &std::path::Path,
) -> String {
    let place = if after {
        format!("the untagged displays after ({tag})")
    } else {
        format!("({tag})")
    };
    if let (true, Some(why)) = (lefts.is_empty(), unread) {
        let at = unread_at(path, why);
        format!("{at}{place} is not read: {why}")
    } else if found_tag {
        format!(
            "no relation of {place} has the left side {lhs}; its left sides: {}",
            lefts.join(", ")
        )
    } else if after {
        format!(
            "no untagged display follows the one tagged ({tag}) in {}",
            path.display()
        )
    } else {
        format!("no display is tagged ({tag}) in {}", path.display())
    }
}

/// `display = K`: the LaTeX of the paper's K-th display, numbered or not, as the audit counts
/// them (`relation` then picks within it; `tag`, `label`, `after` and `lhs` do not go with it).
fn by_display(
    blocks: &[(Option<String>, String)],
    v: &toml::Value,
    spec: &toml::Table,
) -> Result<String, String> {
    let n = blocks.len();
    let k = v
        .as_integer()
        .filter(|k| *k >= 1 && *k as usize <= n)
        .ok_or_else(|| {
            format!(
                "`display` is a display's place in the paper, 1 to {n} (as `verify audit` counts them)"
            )
        })? as usize;
    if let Some(other) = ["tag", "label", "after", "lhs"]
        .iter()
        .find(|o| spec.contains_key(**o))
    {
        return Err(format!(
            "`display` names the display: give `relation` (its place in it), not `{other}`"
        ));
    }
    Ok(blocks[k - 1].1.trim().to_string())
}

/// `printed_equations_from`: each entry read from the paper (or, as text, a formula printed in
/// prose) into `printed_equations`, a `form = "difference"` entry marked as a condition.
fn equations_from(
    snapshot: &PaperClaims,
    c: &mut ClaimSpec,
    list: toml::Value,
    syms: &TexSymbols,
) -> Result<(), VerifyError> {
    let field = "printed_equations_from";
    if c.keys.contains_key("printed_equations") {
        return Err(bad(
            snapshot,
            &c.head.id,
            field,
            "give printed_equations or printed_equations_from, not both".into(),
        ));
    }
    let specs = list.as_array().cloned().ok_or_else(|| {
            bad(
                snapshot,
                &c.head.id,
                field,
                "is a list of { tag = ..., lhs = ... } (or { after = ..., lhs = ... }, or a formula printed in prose, retyped as text)".into(),
            )
        })?;
    let mut texts = Vec::new();
    let mut rows: Vec<String> = Vec::new();
    for (k, spec) in specs.iter().enumerate() {
        // a formula the paper prints in prose, retyped, stands in the list as text
        if let Some(text) = spec.as_str() {
            texts.push(toml::Value::String(text.to_string()));
            continue;
        }
        let (e, latex) =
            formula_from_paper(snapshot, &c.head.id, &format!("{field}[{k}]"), spec, syms)?;
        if spec.get("form").and_then(|f| f.as_str()) == Some("difference") {
            c.head.conditions.push(format!("printed_equations[{k}]"));
        }
        texts.push(toml::Value::String(e.to_string()));
        if !rows.contains(&latex) {
            rows.push(latex);
        }
    }
    c.keys
        .insert("printed_equations".into(), toml::Value::Array(texts));
    c.head.tex = Some(rows.join(" \\\\ "));
    Ok(())
}

/// `form = "difference"`: the relation read as `left - right` (a condition printed `... = 0`
/// or `2(rho^2 + c^2) = a^2`, judged as its difference); `"right"` (the default) its right side.
fn difference_form(
    file: &PaperClaims,
    id: &str,
    field: &str,
    spec: &toml::Table,
) -> Result<bool, VerifyError> {
    match spec.get("form").map(|v| v.as_str()) {
        None | Some(Some("right")) => Ok(false),
        Some(Some("difference")) => Ok(true),
        Some(other) => Err(bad(
            file,
            id,
            field,
            format!(
                "form = {}: allowed \"right\" (the right side, the default) or \"difference\" (left - right)",
                other.map_or("(not text)".to_string(), |t| format!("\"{t}\""))
            ),
        )),
    }
}

/// `relation = k`: the k-th relation (1-based) of the row named (of the display with
/// `display`), where a row holds several (`a = b, \quad c = d`).
fn nth_relation(
    file: &PaperClaims,
    id: &str,
    field: &str,
    spec: &toml::Table,
) -> Result<Option<usize>, VerifyError> {
    match spec.get("relation") {
        None => Ok(None),
        Some(v) => v
            .as_integer()
            .filter(|k| *k >= 1)
            .map(|k| Some(k as usize - 1))
            .ok_or_else(|| {
                bad(
                    file,
                    id,
                    field,
                    "`relation` is a relation's place in its row, 1 for the first".into(),
                )
            }),
    }
}

/// `link = j`: of a chain `a <= b <= c`, the j-th link (1-based: `a <= b` is 1), read alone.
fn link_of(
    file: &PaperClaims,
    id: &str,
    field: &str,
    spec: &toml::Table,
) -> Result<Option<usize>, VerifyError> {
    match spec.get("link") {
        None => Ok(None),
        Some(v) => v.as_integer().filter(|k| *k >= 1).map(|k| Some(k as usize)).ok_or_else(|| {
            bad(
                file,
                id,
                field,
                "`link` is a link's place in a chain of relations, 1 for the first (`a` to `b` of `a <= b <= c`)".into(),
            )
        }),
    }
}

/// A formula read from the paper: the side asked for (`lhs`, or the right side of the tagged
/// equation), as text of the formula language, and the LaTeX it was read from.
fn formula_from_paper(
    file: &PaperClaims,
    id: &str,
    field: &str,
    spec: &toml::Value,
    syms: &TexSymbols,
) -> Result<(Expr, String), VerifyError> {
    let spec = spec.as_table().ok_or_else(|| {
        bad(
            file,
            id,
            field,
            "is a table { tag = \"(16)\", lhs = \"A_{5}\" } (or { after = \"(2.9)\", lhs = ... })"
                .into(),
        )
    })?;
    let (latex, lhs) = from_paper(file, id, field, spec, syms, false)?;
    let difference = difference_form(file, id, field, spec)?;
    let nth = nth_relation(file, id, field, spec)?;
    let link = link_of(file, id, field, spec)?;
    let mut e = read_side(&latex, lhs.as_deref(), (nth, link), syms, difference).map_err(|e| {
        let at = where_in_paper(file, &latex);
        bad(file, id, field, format!("{at}`{latex}`: {e}"))
    })?;
    // `at = { k = "k1" }`: the formula at other arguments (f1(k) of (2.3) read as f1(k1))
    if let Some(at) = spec.get("at") {
        let at = at
            .as_table()
            .ok_or_else(|| bad(file, id, field, "`at` is a table { k = \"k1\" }".into()))?;
        let mut with = Vec::new();
        for (name, v) in at {
            let text = v.as_str().unwrap_or_default();
            let f = crate::algebra::expr::parse(text)
                .map_err(|err| bad(file, id, field, format!("at.{name}: `{text}`: {err}")))?;
            if !e.symbols().contains(name) {
                return Err(bad(
                    file,
                    id,
                    field,
                    format!("at.{name}: the formula read does not use `{name}`"),
                ));
            }
            with.push((name.clone(), f));
        }
        e = e.substitute(&|s| with.iter().find(|(n, _)| n == s).map(|(_, f)| f.clone()));
    }
    no_opaque(file, id, field, &e)?;
    Ok((e, latex))
}

/// For a dimension claim, which judges units only: each application `{z(t)}` as its function
/// `z`, whose unit it has (as in the audit, [`crate::paper::units::unit_name`]).
fn applications_as_functions(e: &Expr) -> Expr {
    e.substitute(&|s| {
        let f = crate::paper::units::unit_name(s);
        (f != s).then_some(Expr::Sym(f))
    })
}

/// Refuses a formula that kept an opaque function application (`{w(x,y,t)}`).
fn no_opaque(file: &PaperClaims, id: &str, field: &str, e: &Expr) -> Result<(), VerifyError> {
    match e.symbols().into_iter().find(|s| s.starts_with('{')) {
        Some(s) => Err(bad(
            file,
            id,
            field,
            format!(
                "`{s}` is a function application or a tuple the formula language has no name for: map its spelling to a symbol in [tex_symbols]"
            ),
        )),
        None => Ok(()),
    }
}

/// `line L of PATH: ` for the row quoted first in `why` (between backticks), found in the file
/// at `path`; empty when it is not found as written.
fn unread_at(path: &std::path::Path, why: &str) -> String {
    let row = why.split('`').nth(1).unwrap_or_default();
    let Ok(text) = std::fs::read_to_string(path) else {
        return String::new();
    };
    line_of(&text, row)
        .map(|l| format!("line {l} of {}: ", path.display()))
        .unwrap_or_default()
}

/// The line (from 1) of `text` where the first non-blank line of `latex` stands.
fn line_of(text: &str, latex: &str) -> Option<usize> {
    let first = latex.lines().map(str::trim).find(|l| !l.is_empty())?;
    text.lines().position(|l| l.contains(first)).map(|i| i + 1)
}

/// Where the display `latex` stands in the file it was read from (`line L of PATH: `), for a
/// message about it; empty when it is not found as written (a display split over rows).
fn where_in_paper(file: &PaperClaims, latex: &str) -> String {
    let Ok((_, _, path)) = paper_displays(file) else {
        return String::new();
    };
    let Ok(text) = std::fs::read_to_string(&path) else {
        return String::new();
    };
    line_of(&text, latex)
        .map(|l| format!("line {l} of {}: ", path.display()))
        .unwrap_or_default()
}

/// The side an equation's LaTeX gives: the right side of the relation whose left side is `lhs`
/// (or of the first relation); failing that, of the one whose left side is `lhs` times a factor,
/// divided by the factor (`m_2 \rho_2^2 \beta = ...` read for `\beta`). With `nth`, the
/// relation at that place (0-based) among all those of `tex`.
fn read_side(
    tex: &str,
    lhs: Option<&str>,
    (nth, link): (Option<usize>, Option<usize>),
    syms: &TexSymbols,
    difference: bool,
) -> Result<Expr, crate::paper::formulas::TexError> {
    let pieces = read_display(tex, syms);
    let mut first_err = None;
    let side = |r: &crate::paper::formulas::TexRelation| {
        // one link of a chain, as a relation of its own
        let sides = match link {
            Some(j) if j < r.sides.len() => &r.sides[j - 1..=j],
            Some(j) => {
                return Err(crate::paper::formulas::TexError {
                    column: 1,
                    construct: format!(
                        "a link {j} of a chain (the relation has {} side(s))",
                        r.sides.len()
                    ),
                    found: tex.into(),
                });
            }
            None => &r.sides[..],
        };
        let r = crate::paper::formulas::TexRelation {
            sides: sides.to_vec(),
            ..r.clone()
        };
        let last = r.sides.last().cloned().unwrap_or(Expr::Pi);
        let zero = Expr::Num(crate::algebra::poly::Q::from_integer(0.into()));
        let minus = |a: &Expr, b: &Expr| {
            Expr::Bin(
                crate::algebra::expr::Op::Sub,
                Box::new(a.clone()),
                Box::new(b.clone()),
            )
        };
        Ok(if difference && r.sides.len() == 2 && last == zero {
            r.sides[0].clone()
        } else if difference && r.sides.len() > 1 {
            // a chain `a = b = c` as `(a - b) + (b - c)`: the value of `a - c`, with every side
            // in it (a unit check sees each equality)
            r.sides
                .windows(2)
                .map(|p| minus(&p[0], &p[1]))
                .reduce(|acc, d| {
                    Expr::Bin(crate::algebra::expr::Op::Add, Box::new(acc), Box::new(d))
                })
                .unwrap_or(last)
        } else {
            last
        })
    };
    if let Some(k) = nth {
        let all: Vec<_> = pieces.iter().flat_map(|row| &row.relations).collect();
        return match all.get(k) {
            Some(Ok(r)) if r.sides.len() > 1 => side(r),
            Some(Err(e)) => Err(e.clone()),
            _ => Err(crate::paper::formulas::TexError {
                column: 1,
                construct: format!(
                    "a relation at place {} (the LaTeX holds {} formula(s))",
                    k + 1,
                    all.len()
                ),
                found: tex.into(),
            }),
        };
    }
    for exact in [true, false] {
        for row in &pieces {
            for rel in &row.relations {
                match (rel, lhs) {
                    (Ok(r), None) if exact => return side(r),
                    (Ok(r), Some(l)) if exact && r.sides[0].to_string() == l => {
                        return side(r);
                    }
                    (Ok(r), Some(l)) if !exact && !difference && r.sides.len() > 1 => {
                        if let Some(f) = factor_of(&r.sides[0], l) {
                            return side(r).map(|s| divided(s, f));
                        }
                    }
                    (Err(e), _) => {
                        first_err.get_or_insert(e.clone());
                    }
                    _ => {}
                }
            }
        }
    }
    Err(first_err.unwrap_or(crate::paper::formulas::TexError {
        column: 1,
        construct: "a relation with that left side".into(),
        found: tex.into(),
    }))
}

/// `side / factor`, or `side` when the factor is exactly 1.
fn divided(side: Expr, factor: Expr) -> Expr {
    // compared as a tree: an exact evaluation would intern the symbols (whose order the
    // printed polynomials of every later claim follow)
    if factor == Expr::Num(crate::algebra::poly::Q::from_integer(1.into())) {
        side
    } else {
        Expr::Bin(
            crate::algebra::expr::Op::Div,
            Box::new(side),
            Box::new(factor),
        )
    }
}

/// The matrix a display gives for the left side `lhs` (or `lhs` times a factor, divided out).
fn read_matrix_side(tex: &str, lhs: &str, syms: &TexSymbols) -> Result<TexMatrix, String> {
    let (rows, mats) = read_matrix_display(tex, syms).map_err(|e| e.to_string())?;
    for exact in [true, false] {
        for rel in rows.iter().flat_map(|r| r.relations.iter().flatten()) {
            if rel.sides.len() < 2 {
                continue;
            }
            let factor = if exact {
                (rel.sides[0].to_string() == lhs)
                    .then(|| Expr::Num(crate::algebra::poly::Q::from_integer(1.into())))
            } else {
                factor_of(&rel.sides[0], lhs)
            };
            if let Some(f) = factor {
                let m = matrix_value(rel.sides.last().unwrap_or(&Expr::Pi), &mats)?;
                return Ok(m
                    .into_iter()
                    .map(|r| r.into_iter().map(|c| divided(c, f.clone())).collect())
                    .collect());
            }
        }
    }
    Err(format!("no relation has the left side {lhs}"))
}

/// Resolves `printed_tex` and `printed_from` of every claim of `file` into `printed`.
pub fn resolve(file: &mut PaperClaims) -> Result<(), VerifyError> {
    let mut syms = TexSymbols::new(file.tex_symbols.clone());
    // the paper's functions and lone increment letters, as the audit reads them
    if let Ok((blocks, _, _)) = paper_displays(file) {
        syms = syms.with_functions_of(blocks.iter().map(|(_, tex)| tex.as_str()));
    }
    let snapshot = file.clone();
    // the file's definitions read from the paper (`[definitions_from]`)
    for (name, spec) in std::mem::take(&mut file.definitions_from) {
        let field = format!("definitions_from.{name}");
        if file.definitions.contains_key(&name) {
            return Err(bad(
                &snapshot,
                "(file)",
                &field,
                format!("`{name}` is also in [definitions]: define it once"),
            ));
        }
        let (e, latex) = formula_from_paper(&snapshot, "(file)", &field, &spec, &syms)?;
        file.definitions.insert(name.clone(), e.to_string());
        file.definitions_latex.insert(name, latex);
    }
    for c in &mut file.claim {
        if c.head.retyped.is_some()
            && let Some(k) = ["printed_from", "printed_tex", "printed_matrix_from"]
                .into_iter()
                .find(|k| c.keys.contains_key(*k))
        {
            return Err(bad(
                &snapshot,
                &c.head.id,
                "retyped",
                format!(
                    "the printed side is read from the paper (`{k}`): nothing is typed by hand"
                ),
            ));
        }
        if let Some(list) = c.keys.remove("printed_equations_from") {
            equations_from(&snapshot, c, list, &syms)?;
        }
        if let Some(spec) = c.keys.remove("printed_matrix_from") {
            let field = "printed_matrix_from";
            if c.keys.contains_key("printed_matrix") {
                return Err(bad(
                    &snapshot,
                    &c.head.id,
                    field,
                    "give printed_matrix or printed_matrix_from, not both".into(),
                ));
            }
            let spec = spec.as_table().cloned().ok_or_else(|| {
                bad(
                    &snapshot,
                    &c.head.id,
                    field,
                    "is a table { tag = \"(3.9)\", lhs = \"\\\\mathbf{B}\" } (or { after = ..., lhs = ... })".into(),
                )
            })?;
            if !spec.contains_key("lhs") {
                return Err(bad(
                    &snapshot,
                    &c.head.id,
                    field,
                    "needs `lhs`, the matrix's name as printed (\"\\\\mathbf{B}_A\")".into(),
                ));
            }
            let (latex, lhs) = from_paper(&snapshot, &c.head.id, field, &spec, &syms, true)?;
            let m = read_matrix_side(&latex, lhs.as_deref().unwrap_or_default(), &syms)
                .map_err(|e| bad(&snapshot, &c.head.id, field, format!("`{latex}`: {e}")))?;
            let mut rows = Vec::new();
            for r in &m {
                let mut cells = Vec::new();
                for e in r {
                    no_opaque(&snapshot, &c.head.id, field, e)?;
                    cells.push(toml::Value::String(e.to_string()));
                }
                rows.push(toml::Value::Array(cells));
            }
            c.keys
                .insert("printed_matrix".into(), toml::Value::Array(rows));
            c.head.tex = Some(latex);
        }
        let tex = c.keys.remove("printed_tex");
        let from = c.keys.remove("printed_from");
        let (field, latex, lhs, difference, nth) = match (tex, from) {
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
                ("printed_tex", t, None, false, (None, None))
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
                let (latex, lhs) =
                    from_paper(&snapshot, &c.head.id, "printed_from", &spec, &syms, false)?;
                let difference = difference_form(&snapshot, &c.head.id, "printed_from", &spec)?;
                let nth = nth_relation(&snapshot, &c.head.id, "printed_from", &spec)?;
                let link = link_of(&snapshot, &c.head.id, "printed_from", &spec)?;
                ("printed_from", latex, lhs, difference, (nth, link))
            }
        };
        let e = read_side(&latex, lhs.as_deref(), nth, &syms, difference).map_err(|e| {
            let at = if field == "printed_from" {
                where_in_paper(&snapshot, &latex)
            } else {
                String::new()
            };
            bad(&snapshot, &c.head.id, field, format!("{at}`{latex}`: {e}"))
        })?;
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
        // a kind that judges units alone takes a function applied for its value (the registry
        // says which kinds do)
        let units_only = super::kinds::BUILTIN
            .iter()
            .any(|k| k.name == c.kind && k.units_only);
        let e = if units_only {
            applications_as_functions(&e)
        } else {
            e
        };
        no_opaque(&snapshot, &c.head.id, field, &e)?;
        c.keys
            .insert("printed".into(), toml::Value::String(e.to_string()));
        c.head.tex = Some(latex);
        if difference {
            c.head.conditions.push("printed".into());
        }
    }
    Ok(())
}
