//! Matrices as papers print them, read from LaTeX into a matrix of [`Expr`] cells.
//!
//! 002_b53e4779673eb6ed.txt prints its matrices four ways: `\begin{vmatrix} .. \end{vmatrix}`
//! (B* of (2.5), the B's of section 4: the translation's `||a_ij||`, a matrix, not a
//! determinant), `\left| \begin{array}{ccc} .. \end{array} \right|` (B~ after (3.9)),
//! `\operatorname{diag} \left\{ a, b, c \right\}` ((3.9), (3.10)) and the unit matrix
//! `\mathbf{E}_{2}`; and combines them with scalars: `m^{-1} \rho^{-2} \begin{vmatrix} ..`,
//! `(m_1^{-1} + m_2^{-1})\mathbf{E}_2 + ...`. [`read_matrix_display`] takes each matrix out of
//! a display, reads its cells with [`super`], lets it stand in the display as a symbol, and
//! [`matrix_value`] evaluates a side read that way: sums, differences, scalar multiples and
//! quotients, and products of matrices (`pmatrix`, `bmatrix`, `Bmatrix`, `Vmatrix` and `matrix`
//! read as `vmatrix` does).
//!
//! Written by hand: it extends this crate's own LaTeX reader; no crate reads LaTeX matrices into
//! expression trees.

use super::{TexError, TexRow, TexSymbols, read_formula};
use crate::algebra::expr::{Expr, Op};
use crate::algebra::poly::Q;
use crate::paper::source::display::{read_display, split_top};

/// A matrix of formulas, row by row.
pub type TexMatrix = Vec<Vec<Expr>>;

/// The symbol a matrix stands as in the display read (a name no paper prints).
fn placeholder(k: usize) -> String {
    format!("__matrix{k}")
}

/// The spelling a matrix is replaced by before the display is read.
fn spelling(k: usize) -> String {
    format!("\u{27e6}matrix{k}\u{27e7}")
}

const MATRIX_ENVS: &[&str] = &[
    "vmatrix", "Vmatrix", "pmatrix", "bmatrix", "Bmatrix", "matrix",
];

fn err(column: usize, construct: &str, found: &str) -> TexError {
    TexError {
        column,
        construct: construct.into(),
        found: found.chars().take(60).collect(),
    }
}

/// The cells of a matrix's body (`a & b \\ c & d`), read.
fn cells(body: &str, syms: &TexSymbols, at: usize) -> Result<TexMatrix, TexError> {
    let mut rows = Vec::new();
    for row in split_top(body, &["\\\\"]) {
        if row.trim().is_empty() {
            continue;
        }
        let mut cells = Vec::new();
        for cell in split_top(&row, &["&"]) {
            let cell = cell.trim();
            if cell.is_empty() {
                return Err(err(at, "a matrix cell (an empty cell between `&`)", &row));
            }
            cells.push(read_formula(cell, syms).map_err(|e| TexError {
                construct: format!("a matrix cell `{cell}`: {}", e.construct),
                ..e
            })?);
        }
        rows.push(cells);
    }
    if rows.is_empty() {
        return Err(err(at, "a matrix with at least one row", body));
    }
    if rows.iter().any(|r| r.len() != rows[0].len()) {
        return Err(err(at, "a matrix whose rows have equal lengths", body));
    }
    Ok(rows)
}

/// The diagonal matrix of the comma-separated entries.
fn diagonal(entries: &str, syms: &TexSymbols, at: usize) -> Result<TexMatrix, TexError> {
    let d: Vec<Expr> = split_top(entries, &[","])
        .iter()
        .map(|e| read_formula(e.trim(), syms))
        .collect::<Result<_, _>>()?;
    if d.is_empty() || entries.trim().is_empty() {
        return Err(err(at, "a diagonal with at least one entry", entries));
    }
    let n = d.len();
    Ok((0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { d[i].clone() } else { zero() })
                .collect()
        })
        .collect())
}

fn zero() -> Expr {
    Expr::Num(Q::from_integer(0.into()))
}

fn one() -> Expr {
    Expr::Num(Q::from_integer(1.into()))
}

/// The index just past the group closing the one opened at `open` (`open` is the index of the
/// opening text, `close` the closing text; nested pairs counted).
fn matching(text: &str, from: usize, open: &str, close: &str) -> Option<usize> {
    let mut depth = 1usize;
    let mut i = from;
    while i < text.len() {
        if text[i..].starts_with(close) {
            depth -= 1;
            if depth == 0 {
                return Some(i + close.len());
            }
            i += close.len();
        } else if text[i..].starts_with(open) {
            depth += 1;
            i += open.len();
        } else {
            i += text[i..].chars().next().map_or(1, char::len_utf8);
        }
    }
    None
}

/// A matrix in `text`: (start, end, the matrix), or why one could not be read.
fn next_matrix(
    text: &str,
    syms: &TexSymbols,
) -> Option<Result<(usize, usize, TexMatrix), TexError>> {
    let col = |at: usize| text[..at].chars().count() + 1;
    // one matrix of each kind found (matrices do not nest: a cell is a formula, so the order in
    // which they are taken out does not matter); an error first
    let mut found: Vec<Result<(usize, usize, TexMatrix), TexError>> = Vec::new();
    let mut consider = |r| found.push(r);
    for env in MATRIX_ENVS {
        let open = format!("\\begin{{{env}}}");
        let close = format!("\\end{{{env}}}");
        if let Some(at) = text.find(&open) {
            let body_at = at + open.len();
            consider(match matching(text, body_at, &open, &close) {
                Some(end) => {
                    cells(&text[body_at..end - close.len()], syms, col(at)).map(|m| (at, end, m))
                }
                None => Err(err(col(at), &format!("`{close}`"), &text[at..])),
            });
        }
    }
    if let Some(at) = text.find("\\begin{array}") {
        let mut body_at = at + "\\begin{array}".len();
        // the column specification `{ccc}`
        if text[body_at..].trim_start().starts_with('{') {
            let brace = body_at + text[body_at..].find('{').unwrap_or(0);
            body_at = text[brace..].find('}').map_or(brace, |k| brace + k + 1);
        }
        let r = match matching(text, body_at, "\\begin{array}", "\\end{array}") {
            Some(end) => {
                cells(&text[body_at..end - "\\end{array}".len()], syms, col(at)).map(|m| {
                    // the bars or brackets that size it: `\left| ... \right|`
                    let before = text[..at].trim_end();
                    let after = &text[end..];
                    let (mut s, mut e) = (at, end);
                    for (l, r) in [
                        ("\\left|", "\\right|"),
                        ("\\left\\|", "\\right\\|"),
                        ("\\left(", "\\right)"),
                        ("\\left[", "\\right]"),
                    ] {
                        if before.ends_with(l) && after.trim_start().starts_with(r) {
                            s = before.len() - l.len();
                            e = end + (after.len() - after.trim_start().len()) + r.len();
                            break;
                        }
                    }
                    (s, e, m)
                })
            }
            None => Err(err(col(at), "`\\end{array}`", &text[at..])),
        };
        consider(r);
    }
    for cmd in ["\\operatorname{diag}", "\\mathrm{diag}", "\\text{diag}"] {
        if let Some(at) = text.find(cmd) {
            let rest_at = at + cmd.len();
            let rest = &text[rest_at..];
            let lead = rest.len() - rest.trim_start().len();
            let inner_at = rest_at + lead;
            let mut r = Err(err(
                col(at),
                "a diagonal's entries in `\\left\\{ \\right\\}`, `\\{ \\}` or `( )`",
                rest,
            ));
            for (l, c) in [
                ("\\left\\{", "\\right\\}"),
                ("\\{", "\\}"),
                ("\\left(", "\\right)"),
                ("(", ")"),
            ] {
                if text[inner_at..].starts_with(l) {
                    let body = inner_at + l.len();
                    r = match matching(text, body, l, c) {
                        Some(end) => diagonal(&text[body..end - c.len()], syms, col(at))
                            .map(|m| (at, end, m)),
                        None => Err(err(col(at), &format!("`{c}`"), &text[at..])),
                    };
                    break;
                }
            }
            consider(r);
        }
    }
    // the unit matrix, as 002 prints it: \mathbf{E}_{2}, \mathbf{E}_2
    if let Some(at) = text.find("\\mathbf{E}_") {
        let rest = &text[at + "\\mathbf{E}_".len()..];
        let (digits, len) = match rest.strip_prefix('{') {
            Some(r) => {
                let d: String = r.chars().take_while(char::is_ascii_digit).collect();
                let ok = r[d.len()..].starts_with('}');
                (if ok { d.clone() } else { String::new() }, d.len() + 2)
            }
            None => {
                let d: String = rest.chars().take(1).filter(char::is_ascii_digit).collect();
                (d.clone(), d.len())
            }
        };
        let r = match digits.parse::<usize>() {
            Ok(n) if (1..=64).contains(&n) => Ok((
                at,
                at + "\\mathbf{E}_".len() + len,
                (0..n)
                    .map(|i| {
                        (0..n)
                            .map(|j| if i == j { one() } else { zero() })
                            .collect()
                    })
                    .collect(),
            )),
            _ => Err(err(
                col(at),
                "the unit matrix's size as a digit (`\\mathbf{E}_{2}`, 1 to 64)",
                rest,
            )),
        };
        consider(r);
    }
    found.into_iter().min_by_key(Result::is_ok)
}

/// A display whose relations hold matrices: each matrix taken out and read cell by cell, the
/// display read with the matrix standing as a symbol ([`matrix_value`] evaluates a side).
/// Returns the rows and the matrices, in the order the symbols number them.
pub fn read_matrix_display(
    block: &str,
    syms: &TexSymbols,
) -> Result<(Vec<TexRow>, Vec<TexMatrix>), TexError> {
    let mut text = block.to_string();
    let mut mats = Vec::new();
    while let Some(found) = next_matrix(&text, syms) {
        let (start, end, m) = found?;
        text.replace_range(start..end, &format!(" {} ", spelling(mats.len())));
        mats.push(m);
    }
    let with = syms.with((0..mats.len()).map(|k| (spelling(k), placeholder(k))));
    Ok((read_display(&text, &with), mats))
}

/// A side read by [`read_matrix_display`] as a matrix: sums and differences of matrices of one
/// size, scalar multiples and quotients, products of matrices. Refuses a scalar added to a
/// matrix, a matrix in a function or an exponent, a division by a matrix, and a side with no
/// matrix.
pub fn matrix_value(e: &Expr, mats: &[TexMatrix]) -> Result<TexMatrix, String> {
    match value(e, mats)? {
        Value::Matrix(m) => Ok(m),
        Value::Scalar(s) => Err(format!("`{s}` is a scalar, not a matrix")),
    }
}

enum Value {
    Scalar(Expr),
    Matrix(TexMatrix),
}

fn bin(op: Op, a: Expr, b: Expr) -> Expr {
    Expr::Bin(op, Box::new(a), Box::new(b))
}

fn map(m: &TexMatrix, f: &dyn Fn(&Expr) -> Expr) -> TexMatrix {
    m.iter().map(|r| r.iter().map(f).collect()).collect()
}

fn value(e: &Expr, mats: &[TexMatrix]) -> Result<Value, String> {
    let index = |s: &str| {
        s.strip_prefix("__matrix")
            .and_then(|k| k.parse::<usize>().ok())
            .and_then(|k| mats.get(k))
    };
    Ok(match e {
        Expr::Sym(s) => match index(s) {
            Some(m) => Value::Matrix(m.clone()),
            None => Value::Scalar(e.clone()),
        },
        Expr::Num(_) | Expr::Pi => Value::Scalar(e.clone()),
        Expr::Neg(a) => match value(a, mats)? {
            Value::Scalar(s) => Value::Scalar(Expr::Neg(Box::new(s))),
            Value::Matrix(m) => Value::Matrix(map(&m, &|c| Expr::Neg(Box::new(c.clone())))),
        },
        Expr::Call(..) | Expr::Calc(..) => {
            if e.symbols().iter().any(|s| index(s).is_some()) {
                return Err(format!("`{e}` applies a function to a matrix"));
            }
            Value::Scalar(e.clone())
        }
        Expr::Bin(op, a, b) => match (*op, value(a, mats)?, value(b, mats)?) {
            (op, Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(bin(op, x, y)),
            (Op::Add | Op::Sub, Value::Matrix(x), Value::Matrix(y)) => {
                if x.len() != y.len() || x[0].len() != y[0].len() {
                    return Err(format!(
                        "`{e}` adds a {}x{} and a {}x{} matrix",
                        x.len(),
                        x[0].len(),
                        y.len(),
                        y[0].len()
                    ));
                }
                Value::Matrix(
                    x.iter()
                        .zip(&y)
                        .map(|(r, s)| {
                            r.iter()
                                .zip(s)
                                .map(|(p, q)| bin(*op, p.clone(), q.clone()))
                                .collect()
                        })
                        .collect(),
                )
            }
            (Op::Add | Op::Sub, _, _) => {
                return Err(format!("`{e}` adds a scalar and a matrix"));
            }
            (Op::Mul, Value::Scalar(s), Value::Matrix(m)) => {
                Value::Matrix(map(&m, &|c| bin(Op::Mul, s.clone(), c.clone())))
            }
            (Op::Mul | Op::Div, Value::Matrix(m), Value::Scalar(s)) => {
                Value::Matrix(map(&m, &|c| bin(*op, c.clone(), s.clone())))
            }
            (Op::Mul, Value::Matrix(x), Value::Matrix(y)) => {
                if x[0].len() != y.len() {
                    return Err(format!(
                        "`{e}` multiplies a {}x{} by a {}x{} matrix",
                        x.len(),
                        x[0].len(),
                        y.len(),
                        y[0].len()
                    ));
                }
                Value::Matrix(
                    (0..x.len())
                        .map(|i| {
                            (0..y[0].len())
                                .map(|j| {
                                    (0..y.len())
                                        .map(|k| bin(Op::Mul, x[i][k].clone(), y[k][j].clone()))
                                        .reduce(|p, q| bin(Op::Add, p, q))
                                        .unwrap_or_else(zero)
                                })
                                .collect()
                        })
                        .collect(),
                )
            }
            (Op::Div, _, Value::Matrix(_)) => {
                return Err(format!("`{e}` divides by a matrix"));
            }
            (Op::Pow, _, _) => return Err(format!("`{e}` raises a matrix to a power")),
        },
    })
}

/// When `left` is `name` times a factor free of `name` (`m_2 B_A` for `B_A`, `m_2 \rho_2^2
/// \beta` for `beta`): that factor. `Some(1)` when `left` is `name` itself.
pub fn factor_of(left: &Expr, name: &str) -> Option<Expr> {
    let free = |e: &Expr| !e.symbols().iter().any(|s| s == name);
    match left {
        Expr::Sym(s) if s == name => Some(one()),
        Expr::Neg(a) => factor_of(a, name).map(|f| Expr::Neg(Box::new(f))),
        Expr::Bin(Op::Mul, a, b) if free(a) => factor_of(b, name).map(|f| times(a, f)),
        Expr::Bin(Op::Mul, a, b) if free(b) => factor_of(a, name).map(|f| times(b, f)),
        Expr::Bin(Op::Div, a, b) if free(b) => {
            factor_of(a, name).map(|f| bin(Op::Div, f, *b.clone()))
        }
        _ => None,
    }
}

/// `a * f`, or `a` when `f` is the literal 1.
fn times(a: &Expr, f: Expr) -> Expr {
    if f == one() {
        a.clone()
    } else {
        bin(Op::Mul, a.clone(), f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    fn read(tex: &str) -> TexMatrix {
        let syms = TexSymbols::default();
        let (rows, mats) = read_matrix_display(tex, &syms).expect("reads");
        let rel = rows[0].relations[0].as_ref().expect("a relation");
        matrix_value(rel.sides.last().expect("a side"), &mats).expect("a matrix")
    }

    /// Each cell equals the formula at a point (the entries as a reader would write them).
    fn same(m: &TexMatrix, want: &[&[&str]]) {
        assert_eq!(m.len(), want.len());
        let at = |s: &str| {
            Some(1.0 + s.len() as f64 * 0.37 + s.bytes().map(f64::from).sum::<f64>() * 1e-3)
        };
        for (r, w) in m.iter().zip(want) {
            assert_eq!(r.len(), w.len());
            for (c, t) in r.iter().zip(*w) {
                let (x, y) = (c.eval(&at).unwrap(), parse(t).unwrap().eval(&at).unwrap());
                assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{c} vs {t}");
            }
        }
    }

    #[test]
    fn an_array_sized_only_on_one_side_is_not_taken_with_its_brackets() {
        // `\left( 2 [array] \right)`: the brackets belong to the product, not to the array (a
        // bracket is the array's own only when it closes right after it and opens right before)
        let m = read(r"\mathbf{C} = \left( 2 \begin{array}{cc} a & 0 \\ 0 & b \end{array} \right)");
        same(&m, &[&["2*a", "0"], &["0", "2*b"]]);
        let m = read(r"\mathbf{C} = \left( \begin{array}{cc} a & 0 \\ 0 & b \end{array} \right)");
        same(&m, &[&["a", "0"], &["0", "b"]]);
    }

    #[test]
    fn vmatrix_times_scalars() {
        let m = read(
            r"\mathbf{B}^{*} = m^{-1} \rho^{-2} \begin{vmatrix} a_{1}^{2} & a_{1} a_{2} \\ a_{1} a_{2} & a_{2}^{2} \end{vmatrix}",
        );
        same(
            &m,
            &[
                &["a1^2/(m*rho^2)", "a1*a2/(m*rho^2)"],
                &["a1*a2/(m*rho^2)", "a2^2/(m*rho^2)"],
            ],
        );
    }

    #[test]
    fn diag_array_and_unit_matrix() {
        let m =
            read(r"B = \frac{2}{m} \operatorname{diag} \left\{ 1, \frac{R^2}{\rho^2} + 1 \right\}");
        same(&m, &[&["2/m", "0"], &["0", "2/m*(R^2/rho^2 + 1)"]]);
        let m = read(
            r"B = \frac{2}{m} \left| \begin{array}{cc} 1 & -R^2 / \rho^2 \\ 0 & 1 \end{array} \right|",
        );
        same(&m, &[&["2/m", "-2/m*R^2/rho^2"], &["0", "2/m"]]);
        let m = read(r"B = (a + b)\mathbf{E}_2 + c \begin{vmatrix} x & y \\ z & w \end{vmatrix}");
        same(&m, &[&["a + b + c*x", "c*y"], &["c*z", "a + b + c*w"]]);
        // braced, as 002 prints it: the braces are part of the unit matrix, not left behind
        let m = read(r"B = (a + b)\mathbf{E}_{2} + c \begin{vmatrix} x & y \\ z & w \end{vmatrix}");
        same(&m, &[&["a + b + c*x", "c*y"], &["c*z", "a + b + c*w"]]);
    }

    #[test]
    fn products_of_matrices() {
        let m = read(
            r"P = \begin{pmatrix} 1 & 2 \\ 3 & 4 \end{pmatrix} \begin{pmatrix} x \\ y \end{pmatrix}",
        );
        same(&m, &[&["x + 2*y"], &["3*x + 4*y"]]);
    }

    #[test]
    fn what_is_not_a_matrix_is_refused() {
        let syms = TexSymbols::default();
        let refuse = |tex: &str, words: &str| {
            let e = match read_matrix_display(tex, &syms) {
                Err(e) => e.construct,
                Ok((rows, mats)) => {
                    let rel = rows[0].relations[0].as_ref().expect("a relation");
                    matrix_value(rel.sides.last().unwrap(), &mats).unwrap_err()
                }
            };
            assert!(e.contains(words), "{tex}: {e}");
        };
        refuse(
            r"B = 1 + \begin{vmatrix} x & y \\ z & w \end{vmatrix}",
            "adds a scalar",
        );
        refuse(
            r"B = \mathbf{E}_3 + \begin{vmatrix} x & y \\ z & w \end{vmatrix}",
            "adds a 3x3 and a 2x2",
        );
        // as many rows but not as many columns (the row count alone does not decide)
        refuse(
            r"B = \begin{vmatrix} x & y \\ z & w \end{vmatrix} + \begin{vmatrix} x & y & u \\ z & w & v \end{vmatrix}",
            "adds a 2x2 and a 2x3",
        );
        refuse(
            r"B = \begin{vmatrix} x & y \\ z \end{vmatrix}",
            "equal lengths",
        );
        refuse(r"B = \begin{vmatrix} x & y \\ z & w", "\\end{vmatrix}");
        refuse(r"B = a + b", "a scalar, not a matrix");
        refuse(
            r"B = \sin \begin{vmatrix} x \end{vmatrix}",
            "applies a function",
        );
        refuse(
            r"B = 1 / \begin{vmatrix} x \end{vmatrix}",
            "divides by a matrix",
        );
        refuse(r"B = \operatorname{diag} x", "a diagonal's entries");
        refuse(r"B = \mathbf{E}_{0} + C", "the unit matrix's size");
        refuse(r"B = \mathbf{E}_{65}", "the unit matrix's size");
    }

    #[test]
    fn a_factor_of_the_left_side() {
        let f = |l: &str, n: &str| factor_of(&parse(l).unwrap(), n).map(|e| e.to_string());
        assert_eq!(f("BA", "BA").as_deref(), Some("1"));
        assert_eq!(f("m2*rho2^2*beta", "beta").as_deref(), Some("m2*rho2^2"));
        assert_eq!(f("-x/2", "x").as_deref(), Some("-1/2"));
        assert_eq!(f("x*x", "x"), None);
        assert_eq!(f("x + 1", "x"), None);
        assert_eq!(f("y", "x"), None);
    }
}
