//! Which inconsistencies a paper's words decide (issue 52). With units from the words rather
//! than a units file, a relation the inference rejects may contradict only what other
//! relations gave: a letter used for two quantities, a misread elsewhere, an error in another
//! relation that came first. Such a relation is judged again against the named units and the
//! paper's definitions alone; a conflict that then vanishes is no finding.

use super::{Inference, Relation, Status, infer_ordered, unit_name};
use crate::algebra::expr::Expr;
use crate::algebra::units::Unit;
use std::collections::{BTreeMap, BTreeSet};

/// The relations the inference calls inconsistent that contradict only what other relations
/// gave, not the named units through the paper's definitions: judged again with the declared
/// and named units and the definitions alone (a bare symbol on the left, defined once), each
/// that then holds is a conflict between relations (a letter used for two quantities, a
/// misread elsewhere) that nothing declared or named decides.
pub fn weak_conflicts(
    inputs: &[Option<Relation>],
    inf: &Inference,
    declared: &BTreeMap<String, Unit>,
) -> std::collections::BTreeSet<usize> {
    // a definition claims nothing but its symbol's unit: one term on its right, or terms
    // of declared symbols only (`A_2 = \eta\zeta(..) + ab C_T/4` also says that C_T is
    // \eta\zeta(..)/ab: a relation, not a definition)
    let defined = |r: &Relation| match (r.sides.len(), r.sides.first()) {
        (2, Some(Expr::Sym(s))) if !declared.contains_key(&unit_name(s)) => {
            let terms = r.sides[1].terms();
            let known = |t: &Expr| {
                t.symbols()
                    .iter()
                    .all(|x| declared.contains_key(&unit_name(x)))
            };
            (terms.len() == 1 || terms.iter().all(|t| known(t))).then(|| unit_name(s))
        }
        _ => None,
    };
    let mut count: BTreeMap<String, usize> = BTreeMap::new();
    for r in inputs.iter().flatten() {
        if let Some(s) = defined(r) {
            *count.entry(s).or_insert(0) += 1;
        }
    }
    let core: Vec<usize> = (0..inputs.len())
        .filter(|&i| {
            inputs[i]
                .as_ref()
                .and_then(defined)
                .is_some_and(|s| count.get(&s) == Some(&1))
        })
        .collect();
    let mut weak = std::collections::BTreeSet::new();
    for (i, status) in inf.statuses.iter().enumerate() {
        if !matches!(status, Status::Inconsistent { .. }) {
            continue;
        }
        // a definition that makes a letter nothing names a pure number (a sigmoid's steepness
        // `e^{-M(\alpha - \alpha_0)}`) decides nothing of a relation that uses the letter: the
        // chapter reuses it (M a moment there)
        // (by the symbol a unit is that of: the sigmoid's `M(\alpha - \alpha_0)`, where the
        // chapter applies M elsewhere, is M's)
        // a letter the relation itself takes for a pure number (its own `\cos s`) is used as
        // the definition uses it: that definition still decides
        let pure_here: BTreeSet<String> = inputs[i]
            .iter()
            .flat_map(|r| r.sides.iter().flat_map(|e| forced_pure(e, declared)))
            .map(|x| unit_name(&x))
            .collect();
        let uses: BTreeSet<String> = inputs[i]
            .iter()
            .flat_map(|r| r.sides.iter().flat_map(Expr::symbols))
            .map(|x| unit_name(&x))
            .filter(|x| !declared.contains_key(x) && !pure_here.contains(x))
            .collect();
        let mut subset: Vec<Option<Relation>> = core
            .iter()
            .filter(|&&k| k != i)
            .filter(|&&k| {
                !inputs[k].iter().any(|r| {
                    r.sides.get(1).is_some_and(|rhs| {
                        forced_pure(rhs, declared)
                            .iter()
                            .any(|x| uses.contains(&unit_name(x)))
                    })
                })
            })
            .map(|&k| inputs[k].clone())
            .collect();
        subset.push(inputs[i].clone());
        let again = infer_ordered(&subset, declared, true);
        if !matches!(again.statuses.last(), Some(Status::Inconsistent { .. })) {
            weak.insert(i);
        }
    }
    weak
}

/// The letters `e` makes pure numbers on their own: in the argument of a function that takes a
/// pure number (`exp`, `ln`, `sin`, ...: not `sqrt`, `abs`, `sign`, Heaviside's step) or in an
/// exponent, a lone symbol no unit is declared for, beside symbols declared pure numbers only
/// (the steepness M of `e^{-M(\alpha - \alpha_0)}`, the s of `\sin s`); a product of two unknown
/// letters there (`e^{-d t}` with d and t unknown) makes neither pure alone.
fn forced_pure(e: &Expr, declared: &BTreeMap<String, Unit>) -> Vec<String> {
    use crate::algebra::expr::{Func, Op};
    let lone = |arg: &Expr| -> Vec<String> {
        let symbols = arg.symbols();
        let unknown: Vec<&String> = symbols
            .iter()
            .filter(|x| !declared.contains_key(&unit_name(x)))
            .collect();
        let others_pure = symbols
            .iter()
            .filter_map(|x| declared.get(&unit_name(x)))
            .all(Unit::is_one);
        match unknown.as_slice() {
            [one] if others_pure => vec![(*one).clone()],
            _ => Vec::new(),
        }
    };
    match e {
        Expr::Num(_) | Expr::Sym(_) | Expr::Pi => Vec::new(),
        Expr::Neg(a) => forced_pure(a, declared),
        Expr::Bin(Op::Pow, a, b) => {
            let mut out = forced_pure(a, declared);
            out.extend(lone(b));
            out
        }
        Expr::Bin(_, a, b) => {
            let mut out = forced_pure(a, declared);
            out.extend(forced_pure(b, declared));
            out
        }
        Expr::Call(Func::Sqrt | Func::Abs | Func::Sign | Func::Heaviside, a) => {
            forced_pure(a, declared)
        }
        Expr::Call(_, a) => lone(a),
        Expr::Calc(_, a, _, rest) => {
            let mut out = forced_pure(a, declared);
            for r in rest {
                out.extend(forced_pure(r, declared));
            }
            out
        }
    }
}

/// The inference with the units of the words: relations taken in the order that trusts known
/// terms ([`infer_ordered`]), the conflicts that only other relations make set apart
/// ([`weak_conflicts`]), and each unit from the words that more relations contradict than
/// hold with it set aside (`against >= 2`, `against >= for`): in a long text a letter named
/// once ("at time $t$") often stands for another quantity elsewhere (a time made
/// dimensionless, an angle called q). `words` are the names whose unit the words gave;
/// `names` each relation's symbols. Returns the inference, the weak conflicts and, for each
/// unit set aside, how many relations contradicted it and how many held.
pub fn infer_with_words(
    inputs: &[Option<Relation>],
    names: &[Vec<String>],
    declared: &BTreeMap<String, Unit>,
    words: &std::collections::BTreeSet<String>,
) -> (
    Inference,
    std::collections::BTreeSet<usize>,
    BTreeMap<String, (usize, usize)>,
) {
    let mut declared = declared.clone();
    let mut aside = BTreeMap::new();
    loop {
        let inf = infer_ordered(inputs, &declared, true);
        let weak = weak_conflicts(inputs, &inf, &declared);
        let mut tally: BTreeMap<String, (usize, usize)> = BTreeMap::new();
        for (i, status) in inf.statuses.iter().enumerate() {
            let Some(ns) = names.get(i) else { continue };
            let ns: std::collections::BTreeSet<String> = ns.iter().map(|n| unit_name(n)).collect();
            for n in ns
                .iter()
                .filter(|n| words.contains(*n) && declared.contains_key(*n))
            {
                let t = tally.entry(n.clone()).or_insert((0, 0));
                match status {
                    Status::Inconsistent { .. } if !weak.contains(&i) => t.0 += 1,
                    Status::Consistent => t.1 += 1,
                    _ => {}
                }
            }
        }
        let drop: Vec<(String, (usize, usize))> = tally
            .into_iter()
            .filter(|(_, (against, holds))| *against >= 2 && against >= holds)
            .collect();
        if drop.is_empty() {
            return (inf, weak, aside);
        }
        for (n, t) in drop {
            declared.remove(&n);
            aside.insert(n, t);
        }
    }
}

/// A symbol the words name in passing ("at time $t$", "a ball of mass $m$"), in a paper of
/// several sections, is that quantity in its own section: there its name becomes `x_secK` (K the
/// section), with the unit of the words; elsewhere `x` keeps no unit from them (a long text
/// reuses its letters). A key to a display ("where $x$ is", a nomenclature) holds everywhere.
pub fn scope_passing(
    inputs: &mut [Option<Relation>],
    lines: &[Option<usize>],
    names: &mut [Vec<String>],
    units: &crate::paper::units::declared::Units,
) -> crate::paper::units::declared::Units {
    let mut out = units.clone();
    // the paper's time `t`, every dot's variable, named in passing ("at time $t = 0$"): no
    // anchor (a text that says it in passing often makes it dimensionless elsewhere)
    if units.words.get("t").is_some_and(|w| !w.key) {
        out.symbols.remove("t");
        out.words.remove("t");
    }
    if units.sections.is_empty() {
        return out;
    }
    let section = |line: usize| crate::paper::words::section_of(&units.sections, line);
    // one section with displays: nothing to scope
    let with_displays: std::collections::BTreeSet<usize> =
        lines.iter().flatten().map(|&l| section(l)).collect();
    if with_displays.len() < 2 {
        return out;
    }
    for (x, w) in units.words.iter().filter(|(x, w)| !w.key && *x != "t") {
        let s = section(w.line);
        let local = format!("{x}_sec{s}");
        for (i, r) in relations_at(inputs, lines, |line| section(line) == s) {
            // the symbol, its applications `{x(t)}`, and its dotted names `xd`
            let mut renamed: BTreeMap<String, String> = BTreeMap::new();
            renamed.insert(x.clone(), local.clone());
            for (dotted, base, _) in &r.dots {
                if base == x {
                    renamed.insert(dotted.clone(), format!("{dotted}_sec{s}"));
                }
            }
            let rename = |n: &str| -> Option<String> {
                let base = unit_name(n);
                let new = renamed.get(&base)?;
                Some(if n == base {
                    new.clone()
                } else {
                    n.replacen(&base, new, 1)
                })
            };
            rename_relation(r, &mut names[i], &rename);
        }
        out.symbols.remove(x);
        out.words.remove(x);
        out.symbols.insert(local.clone(), w.unit);
        out.words.insert(
            local.clone(),
            crate::paper::words::WordUnit {
                symbol: local,
                ..w.clone()
            },
        );
    }
    out
}

/// A letter the words' key ("where $c$ is", a nomenclature) gives a unit in one section and a
/// later section's display defines anew
/// (`c = \cos\frac{2\pi x}{L}` for shorthand, where `c` was the speed of sound): from that
/// section on to its end the letter is the section's own (`c_secK`), with no unit from the
/// words (a letter named in passing is its section's own already, [`scope_passing`]; a unit
/// written out, as a nomenclature gives it, holds for the whole paper). A definition is a
/// relation of two sides whose left side is the letter alone.
pub fn scope_redefined(
    inputs: &mut [Option<Relation>],
    lines: &[Option<usize>],
    names: &mut [Vec<String>],
    units: &crate::paper::units::declared::Units,
) {
    if units.sections.is_empty() {
        return;
    }
    let section = |line: usize| crate::paper::words::section_of(&units.sections, line);
    // (letter, section) of each redefinition
    let mut redefined: BTreeSet<(String, usize)> = BTreeSet::new();
    for (i, r) in inputs.iter().enumerate() {
        let (Some(r), Some(line)) = (r, lines[i]) else {
            continue;
        };
        if let (2, Some(Expr::Sym(x))) = (r.sides.len(), r.sides.first())
            && let Some(w) = units.words.get(x)
            && w.key
            && w.quantity != "written"
            && section(w.line) != section(line)
        {
            redefined.insert((x.clone(), section(line)));
        }
    }
    for (x, s) in redefined {
        let local = format!("{x}_sec{s}");
        let rename = |n: &str| (unit_name(n) == x).then(|| n.replacen(&x, &local, 1));
        for (i, r) in relations_at(inputs, lines, |line| section(line) == s) {
            rename_relation(r, &mut names[i], &rename);
        }
    }
}

/// The relations of a part the paper says is dimensionless (`units.dimensionless`), each
/// symbol renamed `x_dimL` (L the part's first line): the letters there are the part's own, not
/// the quantities they name elsewhere, and no unit reaches them from outside (a units file's
/// or the words'); only the part's own relations tie them.
pub fn scope_dimensionless(
    inputs: &mut [Option<Relation>],
    lines: &[Option<usize>],
    names: &mut [Vec<String>],
    units: &crate::paper::units::declared::Units,
) {
    let span = |line: usize| crate::paper::units::declared::span_of(&units.dimensionless, line);
    for (i, r) in relations_at(inputs, lines, |line| span(line).is_some()) {
        let from = r_line(lines, i).and_then(span).unwrap_or_default();
        rename_relation(r, &mut names[i], &every_letter(format!("_dim{from}")));
    }
}

/// A thesis's numbered chapters each have their own notation (`\rho` a density in one, a
/// radial coordinate in another): from the first chapter on, every letter of a relation is
/// its chapter's own (`x_ch3`), with the unit a units file declares for the letter, or the
/// words give it in that chapter or before the first (a nomenclature, the front matter); the
/// relations before the first chapter keep their letters. A text with fewer than two chapters
/// is left as it is.
pub fn scope_chapters(
    inputs: &mut [Option<Relation>],
    lines: &[Option<usize>],
    names: &mut [Vec<String>],
    units: &crate::paper::units::declared::Units,
) -> crate::paper::units::declared::Units {
    let mut out = units.clone();
    let chapters = &units.chapters;
    let Some(&first) = chapters.first() else {
        return out;
    };
    if chapters.len() < 2 {
        return out;
    }
    let chapter = |line: usize| chapters.iter().rposition(|&c| c <= line);
    for (i, r) in relations_at(inputs, lines, |line| line >= first) {
        let Some(k) = r_line(lines, i).and_then(chapter) else {
            continue;
        };
        rename_relation(r, &mut names[i], &every_letter(format!("_ch{}", k + 1)));
        for n in names[i].clone() {
            let Some(base) = n.strip_suffix(&format!("_ch{}", k + 1)) else {
                continue;
            };
            let Some(&unit) = units.symbols.get(base) else {
                continue;
            };
            match units.words.get(base) {
                // the words' unit holds in their chapter and from before the first
                Some(w) if w.line < first || chapter(w.line) == Some(k) => {
                    out.words.insert(
                        n.clone(),
                        crate::paper::words::WordUnit {
                            symbol: n.clone(),
                            ..w.clone()
                        },
                    );
                }
                Some(_) => continue,
                None => {}
            }
            out.symbols.insert(n, unit);
        }
    }
    out
}

/// A renaming of every letter to its own with `suffix` (`x` to `x_ch3`, `xd` to `x_ch3d`); the
/// reader's own marks keep their meaning.
fn every_letter(suffix: String) -> impl Fn(&str) -> Option<String> {
    move |n: &str| {
        use crate::algebra::units::{ELLIPSIS, INFINITY, OPERAND, WRITTEN_UNIT};
        if [ELLIPSIS, INFINITY, OPERAND, WRITTEN_UNIT].contains(&n) {
            return None;
        }
        let base = unit_name(n);
        let new = format!("{base}{suffix}");
        Some(if n == base {
            new
        } else {
            n.replacen(&base, &new, 1)
        })
    }
}

/// The line of relation `i`.
fn r_line(lines: &[Option<usize>], i: usize) -> Option<usize> {
    lines.get(i).copied().flatten()
}

/// The relations read whose line `pick` accepts, with their indices.
fn relations_at<'a>(
    inputs: &'a mut [Option<Relation>],
    lines: &'a [Option<usize>],
    pick: impl Fn(usize) -> bool + 'a,
) -> impl Iterator<Item = (usize, &'a mut Relation)> + 'a {
    inputs.iter_mut().enumerate().filter_map(move |(i, r)| {
        let line = r_line(lines, i)?;
        let r = r.as_mut()?;
        pick(line).then_some((i, r))
    })
}

/// `r` and its `names` with each name `rename` gives a new one renamed: its sides, its dotted
/// names and their bases.
fn rename_relation(
    r: &mut Relation,
    names: &mut [String],
    rename: &dyn Fn(&str) -> Option<String>,
) {
    for side in r.sides.iter_mut() {
        *side = renamed_in(side, rename);
    }
    for (dotted, base, _) in r.dots.iter_mut() {
        if let Some(d) = rename(dotted) {
            *dotted = d;
        }
        if let Some(b) = rename(base) {
            *base = b;
        }
    }
    for n in names.iter_mut() {
        if let Some(m) = rename(n) {
            *n = m;
        }
    }
}

/// `e` with its symbols renamed by `rename`, a variable of a derivative or an integral too (`\int
/// z\,d\sigma` is over the area named in the words).
fn renamed_in(e: &Expr, rename: &dyn Fn(&str) -> Option<String>) -> Expr {
    match e {
        Expr::Sym(s) => rename(s).map_or_else(|| e.clone(), Expr::Sym),
        Expr::Num(_) | Expr::Pi => e.clone(),
        Expr::Neg(a) => Expr::Neg(Box::new(renamed_in(a, rename))),
        Expr::Call(f, a) => Expr::Call(*f, Box::new(renamed_in(a, rename))),
        Expr::Bin(op, a, b) => Expr::Bin(
            *op,
            Box::new(renamed_in(a, rename)),
            Box::new(renamed_in(b, rename)),
        ),
        Expr::Calc(c, body, var, extra) => Expr::Calc(
            *c,
            Box::new(renamed_in(body, rename)),
            rename(var).unwrap_or_else(|| var.clone()),
            extra.iter().map(|x| renamed_in(x, rename)).collect(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    fn rel(text: &str) -> Option<Relation> {
        Some(Relation {
            sides: text.split('=').map(|s| parse(s).expect("parses")).collect(),
            dots: vec![],
            rels: vec![],
        })
    }

    #[test]
    fn a_definition_that_makes_an_unnamed_letter_a_pure_number_decides_nothing_else() {
        // by hand: a chapter's sigmoid `sig = 1/(1 + exp(-M (a - a0)))` makes its steepness M a
        // pure number (a, a0 angles); the same chapter's `thdd = M/J` (thdd in 1/s^2, J in kg m^2)
        // takes M for a moment. Nothing names M: the two relations conflict, and neither is the finding
        let declared: BTreeMap<String, Unit> = [
            ("thdd", Unit::parse("s^-2").unwrap()),
            ("J", Unit::parse("kg m^2").unwrap()),
            ("a", Unit::one()),
            ("a0", Unit::one()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        let inputs = vec![rel("sig = 1/(1 + exp(-M*(a - a0)))"), rel("thdd = M/J")];
        let inf = infer_ordered(&inputs, &declared, true);
        assert!(
            matches!(inf.statuses[1], Status::Inconsistent { .. }),
            "{:?}",
            inf.statuses
        );
        assert!(weak_conflicts(&inputs, &inf, &declared).contains(&1));
        // a sigmoid of a named steepness (M declared a pure number) still decides; so does a
        // definition whose pure letter the relation does not use (`L(d) = exp(-d t) ..` for
        // `E = L(a)`, issue 66's seed 000)
        let mut named = declared.clone();
        named.insert("M".into(), Unit::one());
        let inf = infer_ordered(&inputs, &named, true);
        assert!(!weak_conflicts(&inputs, &inf, &named).contains(&1));
        let declared: BTreeMap<String, Unit> = [
            ("t".to_string(), Unit::parse("s").unwrap()),
            ("P".to_string(), Unit::parse("kg").unwrap()),
        ]
        .into_iter()
        .collect();
        let inputs = vec![rel("L = exp(-d*t)*t"), rel("P = L")];
        let inf = infer_ordered(&inputs, &declared, true);
        assert!(matches!(inf.statuses[1], Status::Inconsistent { .. }));
        assert!(!weak_conflicts(&inputs, &inf, &declared).contains(&1));
        // the steepness read as a function applied (`M(a - a0)`, M applied elsewhere in the
        // chapter): the same letter
        let applied = |name: &str| (name == "X").then(|| Expr::Sym("{M(a - a0)}".into()));
        let mut sigmoid = rel("sig = 1/(1 + exp(-X))").unwrap();
        sigmoid.sides[1] = sigmoid.sides[1].substitute(&applied);
        let inputs = vec![Some(sigmoid), rel("thdd = M/J")];
        let declared: BTreeMap<String, Unit> = [
            ("thdd".to_string(), Unit::parse("s^-2").unwrap()),
            ("J".to_string(), Unit::parse("kg m^2").unwrap()),
            ("a".to_string(), Unit::one()),
            ("a0".to_string(), Unit::one()),
        ]
        .into_iter()
        .collect();
        let inf = infer_ordered(&inputs, &declared, true);
        assert!(
            matches!(inf.statuses[1], Status::Inconsistent { .. }),
            "{:?}",
            inf.statuses
        );
        assert!(weak_conflicts(&inputs, &inf, &declared).contains(&1));
        // what the rule reads: a function's argument and an exponent, not a root's argument;
        // a lone unknown letter, beside letters declared pure numbers only
        let none = BTreeMap::new();
        let pure = forced_pure(&parse("sqrt(x) + exp(y) + z^w + abs(v)").unwrap(), &none);
        assert_eq!(pure, ["y", "w"]);
        let pure = forced_pure(&parse("exp(-d*t) + sin(q*a)").unwrap(), &declared);
        assert_eq!(pure, ["q"]);
        assert!(forced_pure(&parse("exp(d*J)").unwrap(), &declared).is_empty());
    }

    #[test]
    fn a_relation_that_takes_the_letter_for_a_pure_number_too_is_still_decided() {
        // by hand: `y = R sin(s)` makes s a pure number and y a length (R in m); `x = y cos(s) R`
        // (x in m) takes s for a pure number as well, so the definition decides it: m = m^2, a
        // conflict that stays (a misprint of the relation, caught)
        let declared: BTreeMap<String, Unit> = [
            ("x".to_string(), Unit::parse("m").unwrap()),
            ("R".to_string(), Unit::parse("m").unwrap()),
        ]
        .into_iter()
        .collect();
        let inputs = vec![rel("y = R*sin(s)"), rel("x = y*cos(s)*R")];
        let inf = infer_ordered(&inputs, &declared, true);
        assert!(
            matches!(inf.statuses[1], Status::Inconsistent { .. }),
            "{:?}",
            inf.statuses
        );
        assert!(!weak_conflicts(&inputs, &inf, &declared).contains(&1));
        // the same relation taking s for a length (`x = y s`): the definition's pure s is
        // another letter there, and decides nothing of it
        let inputs = vec![rel("y = R*sin(s)"), rel("x = y*s*R")];
        let inf = infer_ordered(&inputs, &declared, true);
        assert!(matches!(inf.statuses[1], Status::Inconsistent { .. }));
        assert!(weak_conflicts(&inputs, &inf, &declared).contains(&1));
    }
}
