//! `verify init`: a claims file to start from, written from a paper's audit ([`super`]):
//! every symbol with its unit and where it comes from, and for every relation the audit reads a
//! dimension claim on it (named by its tag, or by its display and place) or one line saying why
//! none.

use super::{Audit, AuditRelation, Units};
use crate::algebra::expr::Expr;
use crate::algebra::units::Unit;

/// A claims file to start from: the header (the `equations` list from the numbers found),
/// `[symbols]` with the declared and inferred units, and a `dimension` claim per relation the
/// audit reads whose units are all fixed, numbered or not, its printed side read from the paper;
/// for every other relation a line saying why it has none.
pub fn init_claims(
    a: &Audit,
    doc_numbers: &[String],
    id: &str,
    file: &str,
    title: &str,
    units: &Units,
) -> String {
    let q = |t: &str| format!("{t:?}");
    let mut s = format!(
        "# A claims file to start from, written by `verify init` from {file}: save it beside the paper\n# (printed_from reads the paper from this file's folder), then add the model and identity claims.\npaper = {}\ntitle = {}\nfile = {}\nreport = {}\nequations = [{}]\n\n[symbols]\n",
        q(id),
        q(title),
        q(file),
        q(&format!("{id}.md")),
        doc_numbers
            .iter()
            .map(|n| q(n))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for y in &a.symbols {
        if y.name.starts_with('{') {
            continue;
        }
        match (&y.unit, y.source) {
            (Some(_), "declared") => {
                let written = units.texts.get(&y.name).cloned().unwrap_or_default();
                s.push_str(&format!(
                    "{} = {}    # declared\n",
                    key(&y.name),
                    q(&written)
                ));
            }
            (Some(u), "words") => s.push_str(&format!(
                "{} = {}    # from the words ({}), {}: {}\n",
                key(&y.name),
                q(u),
                y.quantity.as_deref().unwrap_or(""),
                match &y.file {
                    Some(f) => format!("{f}:{}", y.line.unwrap_or(0)),
                    None => format!("line {}", y.line.unwrap_or(0)),
                },
                q(y.quote.as_deref().unwrap_or(""))
            )),
            (Some(u), _) => s.push_str(&format!(
                "{} = {}    # inferred from {}\n",
                key(&y.name),
                q(u),
                y.from.join(", ")
            )),
            (None, _) => s.push_str(&format!(
                "# {} = ?    # nothing fixes its unit\n",
                key(&y.name)
            )),
        }
    }
    if !units.tex_symbols.is_empty() {
        s.push_str("\n[tex_symbols]\n");
        for (k, v) in &units.tex_symbols {
            s.push_str(&format!("{} = {}\n", q(k), q(v)));
        }
    }
    // the first row of each number: a claim names it by its tag; another row of the same
    // number, and an unnumbered relation, by its display and place (`display = K, relation = m`)
    let mut first_row: std::collections::BTreeMap<&str, &str> = std::collections::BTreeMap::new();
    for r in &a.relations {
        let first = r
            .number
            .as_deref()
            .is_some_and(|n| *first_row.entry(n).or_insert(r.latex.as_str()) == r.latex);
        let (here, reference, slug) = match &r.number {
            Some(n) => {
                let slug: String = n
                    .chars()
                    .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
                    .collect();
                let tag = q(&format!("({n})"));
                match (first, r.index_in_row) {
                    (true, 0) => (
                        format!("({n})"),
                        format!("tag = {tag}"),
                        format!("eq{slug}"),
                    ),
                    (true, j) => (
                        format!("({n}), relation {}", j + 1),
                        format!("tag = {tag}, relation = {}", j + 1),
                        format!("eq{slug}-{}", j + 1),
                    ),
                    (false, _) => (
                        format!("({n}), display {} relation {}", r.display, r.in_display),
                        format!("display = {}, relation = {}", r.display, r.in_display),
                        format!("eq{slug}-d{}-{}", r.display, r.in_display),
                    ),
                }
            }
            None => (
                format!(
                    "display {} (unnumbered), relation {}",
                    r.display, r.in_display
                ),
                format!("display = {}, relation = {}", r.display, r.in_display),
                format!("display{}-{}", r.display, r.in_display),
            ),
        };
        // a chain (`0 \le x \le L`, `a = b = c`): one claim per link, each a relation of its own
        let links: Vec<Option<usize>> = if r.sides.len() > 2 {
            (1..r.sides.len()).map(Some).collect()
        } else {
            vec![None]
        };
        for link in links {
            let (here, reference, slug) = match link {
                None => (here.clone(), reference.clone(), slug.clone()),
                Some(j) => (
                    format!(
                        "{here}, link {j} (`{} {} {}`)",
                        r.sides[j - 1],
                        r.rels.get(j - 1).copied().unwrap_or("="),
                        r.sides[j]
                    ),
                    format!("{reference}, link = {j}"),
                    format!("{slug}-link{j}"),
                ),
            };
            match init_claim(a, r, link) {
                Err(w) => s.push_str(&format!("\n# {here}: no claim: {w}\n")),
                Ok(expect) => s.push_str(&format!(
                    "\n[[claim]]\nid = {}\nequation = {}\nreading = {}\nkind = \"dimension\"\nprinted_from = {{ {reference}, form = \"difference\" }}\nexpect = {}\n",
                    q(&format!("{id}.{slug}.units")),
                    q(&here),
                    q(&format!(
                        "{here} has one unit on both sides, {expect} (the audit found it {})",
                        r.status
                    )),
                    q(&expect)
                )),
            }
        }
    }
    s
}

/// The unit a dimension claim on the relation `r` (on its link `link` of a chain) expects, or
/// why `verify init` writes none.
fn init_claim(a: &Audit, r: &AuditRelation, link: Option<usize>) -> Result<String, String> {
    let unit = |n: &str| {
        let n = crate::paper::units::unit_name(n);
        a.symbols
            .iter()
            .find(|y| y.name == n)
            .and_then(|y| y.unit.as_deref())
            .and_then(|u| Unit::parse(u).ok())
    };
    let no_unit: Vec<&str> = r
        .names
        .iter()
        .filter(|n| unit(n).is_none())
        .map(String::as_str)
        .collect();
    // a pair or scalar product `{(F, n)}` has no function whose unit a claim could take
    if let Some(pair) = r
        .names
        .iter()
        .find(|n| n.starts_with('{') && crate::paper::units::unit_name(n) == **n)
    {
        return Err(format!(
            "reads `{pair}` (a pair or a product of vectors) as one symbol the formula language has no name for; map its spelling in [tex_symbols]"
        ));
    }
    match r.status {
        "unreadable" => return Err(format!("unreadable: {}", r.detail)),
        "undetermined" => return Err(r.detail.clone()),
        _ if !no_unit.is_empty() => {
            return Err(format!(
                "nothing fixes the unit of {} ({})",
                no_unit.join(", "),
                r.detail
            ));
        }
        _ => {}
    }
    // an ellipsis stands for terms left out: no formula a claim can hold
    if let Some(side) = r.sides.iter().find(|e| {
        e.symbols()
            .iter()
            .any(|x| x == crate::algebra::units::ELLIPSIS)
    }) {
        return Err(format!(
            "its side `{side}` leaves terms out (`...`): no formula to check"
        ));
    }
    let sides = match link {
        Some(j) => &r.sides[j - 1..=j],
        None => &r.sides[..],
    };
    // what the dimension kind will compute: a consistent relation it cannot judge (a symbolic
    // power of a dimensional base) would fail for the kind's sake, not the paper's
    for pair in sides.windows(2) {
        let diff = Expr::Bin(
            crate::algebra::expr::Op::Sub,
            Box::new(pair[0].clone()),
            Box::new(pair[1].clone()),
        );
        if let Err(e) = crate::algebra::units::dimension(&diff, &unit)
            && r.status == "consistent"
        {
            return Err(format!(
                "consistent, but a dimension claim cannot judge it: {e}"
            ));
        }
    }
    // a consistent relation: the unit its sides share (a chain's links too, `0 <= x <= L` in
    // m, though its first side is a bare 0)
    if let Some(u) = r.unit.as_deref().filter(|_| r.status == "consistent") {
        return Ok(u.to_string());
    }
    if let Some(j) = link {
        let of = |e: &Expr| {
            (!crate::algebra::units::every_unit(e))
                .then(|| crate::algebra::units::dimension(e, &unit).ok())
                .flatten()
        };
        return Ok(of(&r.sides[j - 1])
            .or_else(|| of(&r.sides[j]))
            .map_or_else(|| "1".to_string(), |u| u.to_string()));
    }
    // an inconsistent relation whose left side has no single unit: its right side's unit (the
    // claim fails either way; the unit must only be one)
    Ok(r.side_unit
        .or(r.right_unit)
        .map_or_else(|| "1".to_string(), |u| u.to_string()))
}

/// A TOML key: bare when it can be, quoted otherwise.
pub(super) fn key(name: &str) -> String {
    if !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        name.to_string()
    } else {
        format!("{name:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::units;
    use super::super::{audit, paper_blocks};
    use super::*;

    #[test]
    fn a_symbol_is_a_bare_key_when_it_can_be() {
        assert_eq!(key("omega_n"), "omega_n");
        assert_eq!(key("x-1"), "x-1");
        assert_eq!(key("{op L(w,F)}"), "\"{op L(w,F)}\"");
        assert_eq!(key("v.x"), "\"v.x\"");
        assert_eq!(key(""), "\"\"");
    }

    #[test]
    fn a_left_side_without_a_unit_gives_a_claim_that_fails_on_the_right_sides_unit() {
        // a + b = c with a in m and b in s: the left side has no unit; the claim expects c's
        let text = "\\begin{equation} a + b = c \\end{equation}";
        let (blocks, doc) = paper_blocks(text);
        let u = units(&[("a", "m"), ("b", "s"), ("c", "m")]);
        let a = audit(&blocks, doc.as_ref(), &u);
        assert_eq!(a.relations[0].status, "inconsistent");
        assert_eq!(a.relations[0].detail, "in m: `a`, `c`; in s: `b`");
        let init = init_claims(&a, &["1".into()], "p", "p.tex", "T", &u);
        assert!(init.contains("expect = \"m\""), "{init}");
    }

    #[test]
    fn an_undetermined_relation_gets_no_claim_and_says_why() {
        // a = b c with only a declared: b and c stay free, the relation undetermined
        let (blocks, doc) = paper_blocks("\\begin{equation} a = b c \\end{equation}");
        let u = units(&[("a", "m")]);
        let a = audit(&blocks, doc.as_ref(), &u);
        assert_eq!(a.relations[0].status, "undetermined");
        let init = init_claims(&a, &["1".into()], "p", "p.tex", "T", &u);
        let want = format!("# (1): no claim: {}\n", a.relations[0].detail);
        assert!(init.contains(&want), "{init}");
        assert!(!init.contains("[[claim]]"), "{init}");
    }
}
