//! The formula language's unit tests.

use super::*;
use crate::algebra::poly::q;

#[test]
fn dotted_names_and_exponents_lex_as_written() {
    // a dotted path is one name; an index part too; `2e-3` is a number, `2e` at the end is
    // no number with an exponent (an error, not a panic), nor is `2e+`
    assert_eq!(
        parse("contact.duration").unwrap(),
        Expr::sym("contact.duration")
    );
    assert_eq!(parse("impulse.0").unwrap(), Expr::sym("impulse.0"));
    assert_eq!(parse("2e-3").unwrap(), Expr::Num(q(1, 500)));
    for bad in ["2e", "2e+", "x*3E"] {
        assert!(parse(bad).is_err(), "{bad}");
    }
}

#[test]
fn hyperbolic_functions_are_exact_where_the_algebra_has_them() {
    // rational values at 0 (and acosh at 1); none elsewhere
    let c = |s: &str| parse(s).unwrap().exact_constant();
    assert_eq!(
        c("cosh(0) + acosh(2 - 1) + sinh(0) + tanh(0) + asinh(0) + atanh(0)"),
        Some(q(1, 1))
    );
    for open in [
        "cosh(1)",
        "sinh(1)",
        "acosh(2)",
        "tanh(1)",
        "asinh(1)",
        "atanh(1/2)",
    ] {
        assert_eq!(c(open), None, "{open}");
    }
    // sinh, cosh of a multiple of t are exponential polynomials: cosh^2 - sinh^2 = 1 and
    // d/dt sinh(k t) = k cosh(k t), exactly
    let x = |s: &str| parse(s).unwrap().to_expo("t").unwrap();
    assert_eq!(x("cosh(2*a*t)^2 - sinh(2*a*t)^2"), x("1"));
    assert_eq!(x("sinh(k*t)").deriv(), x("k*cosh(k*t)"));
    assert_eq!(x("2*sinh(t)"), x("exp(t) - exp(-t)"));
    assert!(parse("tanh(t)").unwrap().to_expo("t").is_none());
}

#[test]
fn precedence_and_associativity() {
    // by hand from the grammar: ^ right-assoc above unary minus above * / above + -
    let e = parse("-x^2").unwrap();
    assert_eq!(
        e,
        Expr::Neg(Box::new(Expr::Bin(
            Op::Pow,
            Box::new(Expr::sym("x")),
            Box::new(Expr::Num(q(2, 1)))
        )))
    );
    assert_eq!(parse("a - b - c").unwrap().to_string(), "a - b - c");
    assert_eq!(parse("a - (b - c)").unwrap().to_string(), "a - (b - c)");
    assert_eq!(parse("a/(b*c)").unwrap().to_string(), "a/(b*c)");
    assert_eq!(parse("2^3^2").unwrap().exact_constant(), Some(q(512, 1)));
    assert_eq!(parse("(2^3)^2").unwrap().exact_constant(), Some(q(64, 1)));
    assert_eq!(parse("(m/k)^(2/5)").unwrap().to_string(), "(m/k)^(2/5)");
    assert_eq!(parse("x^-1/2").unwrap().to_string(), "x^-1/2");
}

#[test]
fn numbers_are_exact() {
    assert_eq!(parse("3.2181").unwrap(), Expr::Num(q(32181, 10000)));
    assert_eq!(parse("1e-3").unwrap(), Expr::Num(q(1, 1000)));
    assert_eq!(parse("1e-3").unwrap().to_string(), "0.001");
    assert_eq!(parse("2.5E2").unwrap().to_string(), "250");
    assert_eq!(parse("1e-9").unwrap().to_string(), "1e-9");
    assert_eq!(parse("0.0000015").unwrap().to_string(), "1.5e-6");
    assert_eq!(parse("2e9").unwrap().to_string(), "2e9");
    assert_eq!(parse("100").unwrap().to_string(), "100");
}

#[test]
fn dotted_names_and_functions() {
    let e = parse("contact.peak_force/sqrt(k*m)").unwrap();
    assert_eq!(e.symbols(), vec!["contact.peak_force", "k", "m"]);
    assert_eq!(e.to_string(), "contact.peak_force/sqrt(k*m)");
    let v = parse("exp(-zeta*pi/sqrt(1 - zeta^2))")
        .unwrap()
        .eval(&|s| (s == "zeta").then_some(0.1))
        .unwrap();
    // the linear spring-dashpot restitution at zeta = 0.1, by a second formula
    let want = (-0.1 * std::f64::consts::PI / (1.0f64 - 0.01).sqrt()).exp();
    assert!((v - want).abs() < 1e-15);
}

#[test]
fn errors_name_the_column() {
    let e = parse("a + * b").unwrap_err();
    assert_eq!(e.column, 5);
    assert!(e.expected.contains("a number"), "{e}");
    let e = parse("2 x").unwrap_err();
    assert_eq!(e.column, 3);
    assert!(e.expected.contains("`*`"), "{e}");
    let e = parse("sqrt x").unwrap_err();
    assert!(e.expected.contains("`(` after the function `sqrt`"), "{e}");
    let e = parse("(a + b").unwrap_err();
    assert_eq!(e.column, 7);
    let e = parse("a # b").unwrap_err();
    assert_eq!((e.column, e.found.as_str()), (3, "`#`"));
    assert!(parse("a < b").is_err());
    assert!(parse_inequality("a + b").is_err());
    assert_eq!(
        parse_inequality("v_out <= 1.0*v0").unwrap().to_string(),
        "v_out <= 1*v0"
    );
}

#[test]
fn rational_and_exponential_forms() {
    let r = parse("(x^2 - 1)/(x - 1)").unwrap().to_ratfunc().unwrap();
    assert_eq!(r, parse("x + 1").unwrap().to_ratfunc().unwrap());
    assert!(parse("x^(1/2)").unwrap().to_ratfunc().is_none());
    // int_0^t exp(-a s) ds = (1 - exp(-a t))/a, an exponential polynomial in t
    let e = parse("(1 - exp(-a*t))/a").unwrap().to_expo("t").unwrap();
    assert_eq!(e.len(), 2);
    assert!(parse("exp(-a*t^2)").unwrap().to_expo("t").is_none());
    assert!(parse("1/t").unwrap().to_expo("t").is_none());
}

#[test]
fn sines_at_rational_multiples_of_pi_are_exact() {
    // by hand: sin(3 pi/2) = -1, cos(pi) = -1, sin(pi/6) = 1/2, sin(m pi x/a) at x = a, m = 3
    let v = |t: &str| parse(t).unwrap().to_ratfunc().map(|r| r.to_text());
    assert_eq!(v("sin(3*pi/2)").as_deref(), Some("-1"));
    assert_eq!(v("cos(pi)").as_deref(), Some("-1"));
    assert_eq!(v("sin(pi/6)*2").as_deref(), Some("1"));
    assert_eq!(v("at(sin(3*pi*x/a), x, a)").as_deref(), Some("0"));
    assert_eq!(v("sin(pi/4)"), None);
    assert_eq!(v("sin(x)"), None);
}

#[test]
fn a_prepared_formula_evaluates_to_the_same_bits() {
    // `prepared` takes the derivatives, substitutions and products once; `eval` of it must be
    // `eval` of the formula as written, to the bit, at every point (the reference is the
    // unprepared formula, lowered by `eval` itself at each call)
    let texts = [
        "diff(x^3*sin(x), x) + y^2",
        "at(diff(x^2*y, x), x, 2*y) - y^(3/2)",
        "sum(k*x^k, k, 1, 4) / (1 + x^(1/3))",
        "diff(x^2*y, y) * (x + 1)^2 + int(s^2*x, s, 0, y)",
        "max(x, y) + x^2^2 + (x + y)^(0 - 2)",
    ];
    for text in texts {
        let e = parse(text).unwrap();
        let p = e.prepared();
        assert!(!format!("{p}").contains("diff"), "{text}: {p}");
        for (x, y) in [(0.3, 1.7), (2.5, 0.2), (1.0, 4.0)] {
            let v = |s: &str| match s {
                "x" => Some(x),
                "y" => Some(y),
                _ => None,
            };
            let (a, b) = (e.eval(&v).unwrap(), p.eval(&v).unwrap());
            assert_eq!(
                a.to_bits(),
                b.to_bits(),
                "{text} at x = {x}, y = {y}: {a} vs {b}"
            );
        }
    }
    // a lowering that fails stays, so that `eval` says why as before
    let mean = Expr::Calc(Calc::Mean, Box::new(Expr::sym("x")), "x".into(), vec![]);
    let v = |_: &str| Some(0.0);
    assert_eq!(mean.prepared(), mean);
    let why = mean
        .prepared()
        .eval(&v)
        .expect_err("a mean is not computed");
    assert!(why.contains("mean"), "{why}");
}

#[test]
fn small_integer_powers_are_found_as_eval_raises_to_them() {
    let p = |s: &str| small_power(&parse(s).unwrap());
    assert_eq!(p("3"), Some(3));
    assert_eq!(p("6/2"), Some(3));
    assert_eq!(p("0 - 63"), Some(-63));
    assert_eq!(p("64"), None, "64 and over is powf");
    assert_eq!(p("3/2"), None);
    assert_eq!(p("x"), None);
    // the power of a number is `powi` of it (2^10 = 1024 exactly either way; 3^-2 by powi)
    let e = parse("x^(0 - 2)").unwrap();
    let v = |_: &str| Some(3.0);
    assert_eq!(e.eval(&v).unwrap().to_bits(), 3f64.powi(-2).to_bits());
}
