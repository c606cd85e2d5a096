//! The lexer's tables read one entry at a time (every function name, accent, Greek spelling
//! and written unit it knows), each against the reading typed by hand, and its tokens on the
//! spellings that only it sees (spaces, one-character commands, numbers, ellipses, empty
//! groups, a spelling of the paper's own).

use super::lex::{Tok, lex};
use super::*;
use crate::algebra::expr::parse;

fn read(tex: &str) -> String {
    read_formula(tex, &TexSymbols::default())
        .unwrap_or_else(|e| panic!("{tex}: {e}"))
        .to_string()
}

#[test]
fn every_function_name_is_its_function() {
    for (cmd, f) in [
        ("sin", "sin"),
        ("cos", "cos"),
        ("tan", "tan"),
        ("exp", "exp"),
        ("ln", "ln"),
        ("arcsin", "asin"),
        ("arccos", "acos"),
        ("arctan", "atan"),
        ("sinh", "sinh"),
        ("cosh", "cosh"),
        ("tanh", "tanh"),
        ("arsinh", "asinh"),
        ("arcsinh", "asinh"),
        ("arcosh", "acosh"),
        ("arccosh", "acosh"),
        ("artanh", "atanh"),
        ("arctanh", "atanh"),
    ] {
        let want = parse(&format!("{f}(x)")).unwrap().to_string();
        assert_eq!(read(&format!("\\{cmd} x")), want, "\\{cmd}");
    }
}

#[test]
fn every_accent_and_font_names_its_letter() {
    for (cmd, suffix) in [
        ("tilde", "t"),
        ("widetilde", "t"),
        ("hat", "h"),
        ("widehat", "h"),
        ("bar", "b"),
        ("overline", "b"),
        ("dot", "d"),
        ("ddot", "dd"),
        ("dddot", "ddd"),
        ("mathbf", ""),
        ("boldsymbol", ""),
        ("mathit", ""),
        ("vec", ""),
        ("bm", ""),
        ("pmb", ""),
        ("textbf", ""),
        ("textit", ""),
        ("mathnormal", ""),
        ("overrightarrow", ""),
        ("vb", ""),
        ("textnormal", ""),
        ("textup", ""),
        ("texttt", ""),
        ("textsf", ""),
        ("mathtt", ""),
        ("bold", ""),
        ("vv", ""),
        ("mathsf", ""),
        ("symbf", ""),
        ("symbfit", ""),
        ("mathbfit", ""),
        ("mathcal", "cal"),
        ("mathscr", "scr"),
        ("mathbb", "bb"),
        ("mathfrak", "frak"),
        ("check", "c"),
        ("breve", "br"),
        ("underline", "u"),
    ] {
        assert_eq!(
            read(&format!("\\{cmd}{{E}} + y")),
            format!("E{suffix} + y"),
            "\\{cmd}"
        );
    }
}

#[test]
fn every_greek_spelling_is_its_letter() {
    for (cmd, name) in [
        ("varepsilon", "epsilon"),
        ("varphi", "phi"),
        ("vartheta", "theta"),
        ("varrho", "rho"),
        ("varsigma", "sigma"),
        ("varkappa", "kappa"),
        ("ell", "l"),
        ("hbar", "hbar"),
        ("upalpha", "alpha"),
        ("upOmega", "Omega"),
        ("varOmega", "Omega"),
        ("varGamma", "Gamma"),
        ("omega", "omega"),
        ("Psi", "Psi"),
    ] {
        assert_eq!(
            read(&format!("\\{cmd} + y")),
            format!("{name} + y"),
            "\\{cmd}"
        );
    }
    // a command that only starts like a Greek letter is none
    assert!(read_formula("\\upsilonx + y", &TexSymbols::default()).is_err());
    assert!(read_formula("\\varfoo + y", &TexSymbols::default()).is_err());
}

/// The tokens of `tex` without their columns.
fn toks(tex: &str) -> Vec<Tok> {
    lex(tex, &TexSymbols::default())
        .into_iter()
        .map(|(t, _)| t)
        .collect()
}

#[test]
fn a_unit_written_after_a_number_is_one_token() {
    let unit = || Tok::Sym(crate::algebra::units::WRITTEN_UNIT.into());
    let num = |n: &str| Tok::Num(n.into());
    for space in ["", " ", "\\,", "\\;", "\\ ", "~", "\\!", "\\, ~"] {
        for open in ["\\text{", "\\mathrm{", "\\textrm{", "\\rm{", "\\mbox{"] {
            for u in [
                "m/s",
                "kg",
                "mm",
                "km",
                "g",
                "mg",
                "h",
                "min",
                "deg",
                "rpm",
                "l",
                "L",
                "eV",
                "mph",
                "°",
                "MPa",
                "GPa",
                "kN",
                "μm",
                "cm",
                "dm",
                "N m",
                "kg\\,m^{-3}",
            ] {
                let tex = format!("12.5{space}{open}{u}}} + x");
                assert_eq!(
                    toks(&tex),
                    [num("12.5"), unit(), Tok::Ch('+'), Tok::Ch('x'), Tok::End],
                    "{tex}"
                );
            }
        }
    }
    // its power belongs to it
    for p in ["^{2}", "^2", "^{-1}"] {
        let tex = format!("3\\,\\mathrm{{m}}{p} + x");
        assert_eq!(
            toks(&tex),
            [num("3"), unit(), Tok::Ch('+'), Tok::Ch('x'), Tok::End],
            "{tex}"
        );
    }
    // words that are no units, and a unit not in a text group, stay what they are
    for tex in [
        "3\\,\\text{apples}",
        "3\\,\\text{m and s}",
        "3 m",
        "3\\,\\textbf{m}",
        "3\\,\\text{m",
    ] {
        assert!(!toks(tex).contains(&unit()), "{tex}: {:?}", toks(tex));
    }
    // `xm` is no prefix: only k, m, c, u, n, M, G, d, μ are
    assert!(!toks("3\\,\\text{xm}").contains(&unit()));
}

#[test]
fn the_lexer_on_what_only_it_sees() {
    let cmd = |c: &str| Tok::Cmd(c.into());
    // spaces dropped; a command of letters, or of one other character
    assert_eq!(
        toks(" \\alpha \\, x\t\\\\"),
        [cmd("alpha"), cmd(","), Tok::Ch('x'), cmd("\\"), Tok::End]
    );
    // a trailing backslash is a command with no name
    assert_eq!(toks("x\\"), [Tok::Ch('x'), cmd(""), Tok::End]);
    // numbers with a point, and a point that starts one
    assert_eq!(
        toks("1.25 + .5 - 3."),
        [
            Tok::Num("1.25".into()),
            Tok::Ch('+'),
            Tok::Num(".5".into()),
            Tok::Ch('-'),
            Tok::Num("3.".into()),
            Tok::End
        ]
    );
    // three dots are an ellipsis; a point alone a character
    assert_eq!(
        toks("a + ... + b."),
        [
            Tok::Ch('a'),
            Tok::Ch('+'),
            cmd("ldots"),
            Tok::Ch('+'),
            Tok::Ch('b'),
            Tok::Ch('.'),
            Tok::End
        ]
    );
    // an empty group only separates, and an empty script is none
    assert_eq!(
        toks("x{ }^2 + d^{}y"),
        [
            Tok::Ch('x'),
            Tok::Ch('^'),
            Tok::Num("2".into()),
            Tok::Ch('+'),
            Tok::Ch('d'),
            Tok::Ch('y'),
            Tok::End
        ]
    );
    assert_eq!(toks("{a}"), [Tok::Open, Tok::Ch('a'), Tok::Close, Tok::End]);
    // a spelling of the paper's own is one symbol, wherever it stands; columns count characters
    let syms = TexSymbols::new([("\\tilde{E}".to_string(), "Et".to_string())]);
    let t = lex("μ \\tilde{E}2", &syms);
    assert_eq!(
        t,
        [
            (Tok::Ch('μ'), 1),
            (Tok::Sym("Et".into()), 3),
            (Tok::Num("2".into()), 12),
            (Tok::End, 13)
        ]
    );
}

#[test]
fn every_conjugate_and_transpose_mark_keeps_the_unit() {
    // each spelling of a conjugate or a transpose after a bracket reads as the same mark
    let plain = read("(a + b)^{*} + c");
    for mark in [
        "^*",
        "^\\ast",
        "^{\\ast}",
        "^\\dagger",
        "^{\\dagger}",
        "^\\star",
        "^{\\top}",
        "^\\intercal",
        "^{\\mathrm{T}}",
        "^{\\mathrm T}",
        "^{\\rm T}",
        "^{\\mathsf{T}}",
        "^{\\mathrm{H}}",
    ] {
        assert_eq!(read(&format!("(a + b){mark} + c")), plain, "{mark}");
    }
    // a power is none of them, nor a letter in a font that is not T or H
    assert_ne!(read("(a + b)^{2} + c"), plain);
    assert_ne!(read("(a + b)^{\\mathrm{T}2} + c"), plain);
    assert!(!read("(a + b)^{\\mathrm{K}} + c").contains(&plain));
}

#[test]
fn a_comma_at_the_top_of_a_superscript_makes_a_label() {
    // `p^{a,b}`: a label of p, not a power; `p^{a}` is a power
    assert!(
        !read("p^{a,b} + q").contains('^'),
        "{}",
        read("p^{a,b} + q")
    );
    assert!(read("p^{a} + q").contains('^'));
}

#[test]
fn an_upright_partial_or_infinity_is_the_operator_itself() {
    // by hand: `\mathrm{\partial}` is `\partial` (a macro `\pd` made upright), and so on
    for font in ["mathrm", "mathit", "text", "boldsymbol"] {
        for c in ["partial", "infty", "nabla"] {
            let tex = format!("\\{font}{{\\{c}}} x");
            assert_eq!(toks(&tex)[0], Tok::Cmd(c.into()), "{tex}");
        }
    }
    // a letter in a font stays a letter in a font
    assert_eq!(toks("\\mathrm{d} x")[0], Tok::Cmd("mathrm".into()));
    // the derivative it writes reads as the one with `\partial`
    assert_eq!(
        read("\\frac{\\mathrm{\\partial} T}{\\mathrm{\\partial} t}"),
        read("\\frac{\\partial T}{\\partial t}")
    );
}

#[test]
fn limits_only_place_the_bounds() {
    // by hand: the same integral and sum with and without `\limits`
    assert_eq!(
        read("\\int\\limits_{0}^{x} t^{2} dt"),
        read("\\int_{0}^{x} t^{2} dt")
    );
    assert_eq!(
        read("\\sum\\nolimits_{i=0}^{n} a_i"),
        read("\\sum_{i=0}^{n} a_i")
    );
}

#[test]
fn a_kern_and_its_length_are_a_space() {
    // by hand: `a\mkern-3mu b` is `a b`; the length's unit is two letters (mu, pt, em)
    assert_eq!(read("a \\mkern-3mu b"), read("a b"));
    assert_eq!(read("a \\kern 0.2em b"), read("a b"));
    assert_eq!(read("x\\mskip 2mu+y"), read("x+y"));
}

#[test]
fn punctuation_in_text_is_no_part_of_the_formula() {
    // by hand: `a + b\text{,}` is `a + b`; a word in text is kept (and read as before)
    assert_eq!(read("a + b\\text{,}"), read("a + b"));
    assert_eq!(read("a + b \\mbox{ .}"), read("a + b"));
    assert_ne!(toks("\\text{if} x").len(), toks("x").len());
}

#[test]
fn a_backslash_before_a_line_break_is_a_space() {
    assert_eq!(read("a +\\\n b"), read("a + b"));
    assert_eq!(read("a +\\\t b"), read("a + b"));
}

#[test]
fn an_upper_bound_written_first_is_the_same_bound() {
    // by hand: TeX's `\sum^n_{i=1}` is `\sum_{i=1}^n`
    assert_eq!(read("\\sum^n_{i=1} a_i"), read("\\sum_{i=1}^n a_i"));
    assert_eq!(read("\\int^{b}_{a} x dx"), read("\\int_{a}^{b} x dx"));
}

#[test]
fn a_script_of_nothing_alone_in_a_superscript_is_its_label() {
    // by hand: `q^{{}_{(4)}}` prints the label (4) set low in the superscript (a textbook's
    // homogeneous coordinates): the same name as `q^{(4)}`; a frame before a name is not this
    assert_eq!(read("q^{{}_{(4)}} + p"), read("q^{(4)} + p"));
    assert_eq!(read("f^{{}_{(3)}}_b"), read("f^{(3)}_b"));
    assert_ne!(read("{}^N\\omega"), read("N\\omega"));
}

#[test]
fn a_period_between_operands_is_a_dot_product_and_set_operations_join() {
    // by hand: `\mathbf{v}.\mathbf{n}` is v . n; a decimal point stays
    assert_eq!(
        read("\\mathbf{v}.\\mathbf{n}"),
        read("\\mathbf{v} \\cdot \\mathbf{n}")
    );
    assert_eq!(read("(u.\\nabla) u"), read("(u \\cdot \\nabla) u"));
    // a period in words (`\text{s.t.}`, `\mathrm{c.c.}`) is punctuation
    assert_eq!(read("a + \\mathrm{c.c.}"), "a + cc");
    assert_eq!(read("1.5 a"), "1.5*a");
    // `\setminus`, `\cap`, `\cup` join sets as a sum joins terms of one unit
    assert_eq!(
        read("\\Omega \\setminus \\omega"),
        read("\\Omega + \\omega")
    );
    assert_eq!(read("A \\cap B \\cup C"), read("A + B + C"));
    // `h(\cdot, t)`: a placeholder alone in its place; `\nabla(\nabla \cdot v)` is no application
    assert_eq!(read("h(\\cdot, t)"), "{h(cdot,t)}");
    assert_eq!(
        read("\\nabla(\\nabla \\cdot v)"),
        read("\\nabla (\\nabla \\cdot v)")
    );
    assert_ne!(read("\\nabla(\\nabla \\cdot v)"), "{nabla(nablacdotv)}");
}

#[test]
fn a_volume_element_in_a_numerator_and_a_repeated_integral_sign() {
    // by hand: `\int \frac{d^3 k}{8\pi^3} f` integrates over k three times (a volume in k);
    // `\int\int u dx dy` is `\iint u dx dy`
    assert_eq!(
        read("\\int \\frac{d^3 k}{8\\pi^3} f"),
        "region(region(region(1/(8*pi^3)*f, k), k), k)"
    );
    assert_eq!(
        read("\\int \\frac{d k}{8\\pi^3} f"),
        "region(1/(8*pi^3)*f, k)"
    );
    assert_eq!(
        read("\\int\\int u \\mathrm{d}x\\mathrm{d}y"),
        read("\\iint u \\mathrm{d}x\\mathrm{d}y")
    );
    assert_eq!(read("\\int \\int\\int Q d V"), read("\\iiint Q d V"));
}

#[test]
fn labels_infinity_quasi_velocities_and_omitted_arguments_are_names() {
    // by hand: `\partial e^{pl}` differentiates by the plastic strain e^pl (a label, no order);
    // `v_\infty` is the speed at infinity; `\dot{\pi}_\nu` a quasi-velocity (no constant pi);
    // `M(\sim)` is M with its arguments omitted
    assert_eq!(
        read("\\frac{\\partial q}{\\partial e^{pl}}"),
        "diff(q, epl)"
    );
    assert_eq!(read("m v_\\infty^2"), read("m v_{\\infty}^2"));
    assert_eq!(read("m v_\\infty^2"), "m*vinf^2");
    assert_eq!(read("\\dot{\\pi}_\\nu"), "pidnu");
    assert_eq!(read("M(\\sim)"), "{M(sim)}");
    // a number's superscript is still an order
    assert_eq!(
        read("\\frac{\\partial^2 q}{\\partial x^2}"),
        "diff(diff(q, x), x)"
    );
}

#[test]
fn a_bracket_s_prime_is_its_derivative_as_a_symbol_of_its_own() {
    // by hand: `(u v)'` is the derivative of u v by a variable left unsaid: one opaque symbol;
    // a name's prime stays in the name
    assert_eq!(read("(u v)' + w"), "{(u*v)'} + w");
    assert_eq!(read("\\left(a\\right)'' + b'"), "{(a)''} + bp");
}

#[test]
fn a_sized_set_builder_is_a_set_of_its_elements() {
    // by hand: `\left\{ x \in D \,|\, x > 0 \right\}` is the set builder of `\{x \in D : x > 0\}`
    assert_eq!(
        read("\\left\\{ x \\in D \\,|\\, 0 < x < \\lambda \\right\\}"),
        read("\\{ x \\in D : 0 < x < \\lambda \\}")
    );
    assert_eq!(
        read("\\left\\{v \\in H(\\Omega): v \\geq \\psi \\right\\} + w"),
        read("\\{v \\in H(\\Omega): v \\geq \\psi \\} + w")
    );
}
