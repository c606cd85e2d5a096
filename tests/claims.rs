//! Claims files as data: the formula parser (round trip, errors, a proptest fuzzer), each generic
//! kind on a case that holds and one that fails, and the bad-claims table (each bad claim stops
//! `verify` with exit 2, names the file, the claim and the key, and writes nothing).
//!
//! Reference values come from outside the code under test: identities done by hand (a binomial
//! square), the SI units of a force, and the Hertz constant tau = 3.2180654597 (the closed form
//! quoted in `src/models/hertz.rs`, an integral evaluated independently), against which the
//! rounded 3.2181 differs by 1.07e-5 relative.

use impactcheck::algebra::expr::{Expr, Op, parse, parse_inequality};
use impactcheck::verify::{Verdict, load_claims, run_all};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-claims-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// A claims file in a fresh folder, with the repository's Hertz scene beside it as `hertz.toml`.
fn claims_file(name: &str, body: &str) -> PathBuf {
    let d = temp_dir(name);
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hertz.toml");
    std::fs::copy(scene, d.join("hertz.toml")).expect("copy scene");
    let head = r#"paper = "t"
title = "test"
report = "t.md"
[symbols]
x = "m"
y = "m"
m = "kg"
k = "N/m^1.5"
v0 = "m/s"
alpha_hc = "s/m"
restitution = "1"
"contact.duration" = "s"
"#;
    let p = d.join("claims.toml");
    std::fs::write(&p, format!("{head}\n{body}")).expect("write claims");
    p
}

fn verdicts(path: &Path) -> Vec<(String, Verdict, String)> {
    let papers = load_claims(path).expect("claims load");
    let out = run_all(&papers, path.parent().expect("dir")).expect("claims run");
    out.into_iter()
        .map(|o| (o.id, o.verdict, o.detail))
        .collect()
}

#[test]
fn identity_holds_exactly_and_fails_with_the_difference() {
    // (x + y)^2 = x^2 + 2 x y + y^2 by hand; dropping 2 x y leaves exactly that difference
    let p = claims_file(
        "identity",
        r#"
[[claim]]
id = "t.square"
equation = "(1)"
quote = "(x + y)^2 = x^2 + 2 x y + y^2"
kind = "identity"
printed = "x^2 + 2*x*y + y^2"
derived = "(x + y)^2"

[[claim]]
id = "t.square-wrong"
equation = "(1)"
quote = "(x + y)^2 = x^2 + y^2"
kind = "identity"
printed = "x^2 + y^2"
derived = "(x + y)^2"
"#,
    );
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Holds, "{:?}", v[0]);
    assert_eq!(v[1].1, Verdict::Fails, "{:?}", v[1]);
    assert!(v[1].2.contains("derived - printed = 2*x*y"), "{}", v[1].2);
    // its size as a share of the derived value: 2xy/(x + y)^2 is at most 1/2 (x = y), and at
    // least 2*0.5*2/(2.5)^2 = 0.32 over [0.5, 2]^2
    let share: f64 = v[1]
        .2
        .split("(up to ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no share in {}", v[1].2));
    assert!((32.0..=50.0).contains(&share), "{share}: {}", v[1].2);
}

#[test]
fn dimension_holds_and_fails_naming_the_unit_found() {
    // k x^(3/2) with k in N/m^1.5 is a force, N = kg m s^-2; k x is kg m^(1/2) s^-2
    let p = claims_file(
        "dimension",
        r#"
[[claim]]
id = "t.force"
equation = "(2)"
quote = "k x^(3/2) is a force"
kind = "dimension"
printed = "k*x^(3/2)"
expect = "N"

[[claim]]
id = "t.force-wrong"
equation = "(2)"
quote = "k x is a force"
kind = "dimension"
printed = "k*x"
expect = "N"

[[claim]]
id = "t.sum"
equation = "(2)"
quote = "x + m is something"
kind = "dimension"
printed = "x + m"
expect = "m"
"#,
    );
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Holds, "{:?}", v[0]);
    assert_eq!(v[1].1, Verdict::Fails);
    assert!(
        v[1].2.contains("is kg m^(1/2) s^-2, not kg m s^-2"),
        "{}",
        v[1].2
    );
    assert_eq!(v[2].1, Verdict::Fails);
    assert!(v[2].2.contains("`x` is m but `m` is kg"), "{}", v[2].2);
}

#[test]
fn model_holds_within_rtol_and_fails_below_the_rounding_of_the_constant() {
    // the printed 3.2181 differs from tau = 3.2180654597 by 1.07e-5 relative: within 2e-5,
    // outside 5e-6
    let claim = |id: &str, rtol: &str| {
        format!(
            r#"
[[claim]]
id = "{id}"
equation = "(3)"
quote = "t_c = 3.2181 (m/k)^(2/5) v0^(-1/5)"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "3.2181*(m/k)^(2/5)*v0^(-1/5)"
bind = {{ m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }}
vary = ["impactor.v0=0.1:10:5:log"]
rtol = {rtol}
"#
        )
    };
    let p = claims_file(
        "model",
        &format!("{}{}", claim("t.a", "2e-5"), claim("t.b", "5e-6")),
    );
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Holds, "{:?}", v[0]);
    assert_eq!(v[1].1, Verdict::Fails, "{:?}", v[1]);
    assert!(
        v[1].2.contains("largest relative difference 1.07"),
        "{}",
        v[1].2
    );
}

#[test]
fn runs_compare_two_runs_of_one_scene_in_one_formula() {
    // Hertz impact: the duration scales as m^(2/5) at fixed k and v0 (dimensional analysis:
    // (m/k)^(2/5) v0^(-1/5) is the only time), so run a (mass m) against run b (mass 1 kg)
    // is (m/1)^(2/5); the exponent misprinted as 1/2 is off by m^(1/10), 15 % at m = 4 kg
    let p = claims_file(
        "runs",
        r#"
[[claim]]
id = "t.runs"
equation = "(1)"
reading = "the duration scales as m^(2/5)"
kind = "model"
scene = "hertz.toml"
runs = { a = {}, b = { set = { "impactor.mass" = 1.0 } } }
quantity = "a.contact.duration"
printed = "(m/m1)^(2/5)*b.contact.duration"
where = { m1 = "1" }
bind = { m = "a.impactor.mass" }
vary = ["impactor.mass=0.25:4:3:log", "impactor.v0=0.5:2:2"]
rtol = 1e-7

[[claim]]
id = "t.runs-wrong"
equation = "(1)"
reading = "the duration scales as m^(1/2)"
kind = "model"
scene = "hertz.toml"
runs = { a = {}, b = { set = { "impactor.mass" = 1.0 } } }
quantity = "a.contact.duration"
printed = "(m/m1)^(1/2)*b.contact.duration"
where = { m1 = "1" }
bind = { m = "a.impactor.mass" }
vary = ["impactor.mass=0.25:4:3:log", "impactor.v0=0.5:2:2"]
rtol = 1e-7
"#,
    );
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Holds, "{}", v[0].2);
    assert!(v[0].2.contains("6 grid points"), "{}", v[0].2);
    assert_eq!(v[1].1, Verdict::Fails, "{}", v[1].2);
}

#[test]
fn bound_holds_and_fails_with_the_worst_sample() {
    // Hunt-Crossley damping dissipates (restitution < 1) but never below zero rebound speed
    // (restitution > 0): true for every sample; restitution > 0.99 is false once
    // alpha v0 > 0.015 (e ~ 1 - 2 alpha v0/3)
    let claim = |id: &str, req: &str| {
        format!(
            r#"
[[claim]]
id = "{id}"
equation = "(4)"
quote = "{req}"
kind = "bound"
scene = "hertz.toml"
sample = {{ "contact.damping" = "loguniform(0.01, 1)", "impactor.v0" = "uniform(0.5, 2)" }}
count = 40
seed = 3
require = "{req}"
"#
        )
    };
    let p = claims_file(
        "bound",
        &format!(
            "{}{}",
            claim("t.a", "restitution < 1"),
            claim("t.b", "restitution > 0.99")
        ),
    );
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Holds, "{:?}", v[0]);
    assert_eq!(v[1].1, Verdict::Fails, "{:?}", v[1]);
    assert!(
        v[1].2.contains("worst sample: contact.damping"),
        "{}",
        v[1].2
    );
}

/// Runs `verify --claims FILE --out DIR` and returns (exit code, stderr, whether DIR exists).
fn verify_bad(name: &str, body: &str) -> (i32, String, bool) {
    let p = claims_file(name, body);
    let out_dir = p.parent().expect("dir").join("out");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .arg("--claims")
        .arg(&p)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .expect("verify runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).to_string(),
        out_dir.exists(),
    )
}

#[test]
fn bad_claims_exit_2_naming_file_claim_and_key_and_write_nothing() {
    let identity = |printed: &str, derived: &str| {
        format!(
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"identity\"\nprinted = \"{printed}\"\nderived = \"{derived}\"\n"
        )
    };
    let model = |extra: &str| {
        format!(
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"model\"\nprinted = \"3.2181*(m/k)^(2/5)*v0^(-1/5)\"\nbind = {{ m = \"impactor.mass\", k = \"contact.k\", v0 = \"impactor.v0\" }}\nvary = [\"impactor.v0=0.1:10:3\"]\nrtol = 1e-4\n{extra}\n"
        )
    };
    // (case, claims body, what the message must say)
    let table: Vec<(&str, String, &str)> = vec![
        (
            "syntax",
            identity("x + * y", "x"),
            "claim t.bad: printed: `x + * y`: column 5: expected a number, a name, a function call or `(`",
        ),
        (
            "unknown symbol",
            identity("x + q", "x"),
            "claim t.bad: printed: unknown symbol `q`: give its unit in [symbols]",
        ),
        (
            "unknown kind",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"identiy\"\n".into(),
            "claim t.bad: kind: unknown kind `identiy`; allowed: identity, dimension, model, bound, probability, map, threshold, definition, not-checkable, check",
        ),
        (
            "unknown derivation",
            identity("x", "@galerkin.zz[m=1,n=1]"),
            "claim t.bad: derived: unknown derivation `@galerkin.zz`",
        ),
        (
            "missing key",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"dimension\"\nprinted = \"x\"\n".into(),
            "claim t.bad: expect: missing; kind `dimension` needs it",
        ),
        (
            "missing scene",
            model("scene = \"nope.toml\"\nquantity = \"contact.duration\""),
            "claim t.bad: scene: `nope.toml`: no such file",
        ),
        (
            "quantity not produced",
            model("scene = \"hertz.toml\"\nquantity = \"contact.nothing\""),
            "claim t.bad: quantity: `contact.nothing`: the model does not produce this number; it produces: atol_used, contact.duration, contact.ended,",
        ),
        (
            "bad grid",
            model("scene = \"hertz.toml\"\nquantity = \"contact.duration\"\nvary = [\"impactor.v0=1:2\"]").replace("vary = [\"impactor.v0=0.1:10:3\"]\n", ""),
            "claim t.bad: vary: --vary: `impactor.v0=1:2`: give START:STOP:COUNT",
        ),
        (
            "bad distribution",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"bound\"\nscene = \"hertz.toml\"\nsample = { \"impactor.v0\" = \"gauss(1, 2)\" }\ncount = 3\nseed = 1\nrequire = \"restitution <= 1\"\n".into(),
            "claim t.bad: sample.impactor.v0: `gauss(1, 2)`: expected uniform(a, b)",
        ),
        (
            "empty uniform range",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"bound\"\nscene = \"hertz.toml\"\nsample = { \"impactor.v0\" = \"uniform(2, 1)\" }\ncount = 3\nseed = 1\nrequire = \"restitution <= 1\"\n".into(),
            "claim t.bad: sample.impactor.v0: `uniform(2, 1)`: expected uniform(a, b)",
        ),
        (
            "inequality missing",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"bound\"\nscene = \"hertz.toml\"\nsample = { \"impactor.v0\" = \"uniform(1, 2)\" }\ncount = 3\nseed = 1\nrequire = \"restitution\"\n".into(),
            "claim t.bad: require: `restitution`: column 12: expected one of < <= > >=",
        ),
        (
            "unknown key",
            "[[claim]]\nid = \"t.bad\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"dimension\"\nprinted = \"x\"\nexpected = \"m\"\n".into(),
            "claim t.bad: expected: kind `dimension` does not take this key; allowed: `printed`, `expect`, `where`",
        ),
        (
            "where in the wrong unit",
            // y is m in [symbols]; a `where` that gives it kilograms is refused
            identity("x + y", "x + y").replace("derived = \"x + y\"\n", "derived = \"x + y\"\nwhere = { y = \"m*x/x\" }\n"),
            "claim t.bad: where.y: `m*x/x` is kg, but `y` is m in [symbols]",
        ),
        (
            "a key of another kind",
            model("scene = \"hertz.toml\"\nquantity = \"contact.duration\"\ncorrected = \"x\""),
            "claim t.bad: corrected: kind `model` does not take this key",
        ),
        (
            "taylor without a scene",
            identity("x", "@taylor.x[order=2]"),
            "claim t.bad: derived: `@taylor.x` is the Taylor series of a text model's solution: give the model as `scene`",
        ),
        (
            "taylor of a built-in model",
            identity("x", "@taylor.x[order=2]").replace("kind = \"identity\"\n", "kind = \"identity\"\nscene = \"hertz.toml\"\n"),
            "claim t.bad: scene: `hertz.toml` is not a text model",
        ),
        (
            "one run",
            model("scene = \"hertz.toml\"\nquantity = \"a.contact.duration\"\nruns = { a = {} }"),
            "claim t.bad: runs: one run given",
        ),
        (
            "a run's bad field",
            model("scene = \"hertz.toml\"\nquantity = \"a.contact.duration\"\nruns = { a = {}, b = { set = { \"impactor.mass\" = -1.0 } } }"),
            "claim t.bad: runs.b: run `b`: ",
        ),
        (
            "a run's bad name",
            model("scene = \"hertz.toml\"\nquantity = \"a.contact.duration\"\nruns = { a = {}, 2b = {} }"),
            "claim t.bad: runs.2b: a run's name is a letter",
        ),
    ];
    for (case, body, want) in &table {
        let (code, err, wrote) = verify_bad(&case.replace(' ', "-"), body);
        assert_eq!(code, 2, "{case}: exit {code}; {err}");
        assert!(err.contains(want), "{case}: expected `{want}` in: {err}");
        assert!(
            err.contains("claims.toml"),
            "{case}: the file is not named: {err}"
        );
        assert!(!wrote, "{case}: wrote a report");
    }
}

#[test]
fn parse_errors_and_round_trips_of_paper_formulas() {
    for text in [
        "E*zeta*(m^2/a^2 + n^2/b^2)^2*h^3*a*b*pi^4/48",
        "3.2181*(m/k)^(2/5)*v0^(-1/5)",
        "exp(-zeta*pi/sqrt(1 - zeta^2))",
        "-x^2 - -y",
        "a/(b*c)/d",
        "(a^b)^c",
        "contact.peak_force*2",
    ] {
        let e = parse(text).expect(text);
        assert_eq!(e.to_string(), text, "printing gives the text back");
        assert_eq!(parse(&e.to_string()).expect("reparse"), e);
    }
    let i = parse_inequality("energy_lost >= 0").expect("inequality");
    assert_eq!(i.to_string(), "energy_lost >= 0");
}

fn arb_expr() -> impl Strategy<Value = Expr> {
    let names = prop::sample::select(vec![
        "x",
        "y",
        "alpha",
        "v0",
        "E",
        "m_s",
        "contact.duration",
        "a.b_c",
        "_t",
    ]);
    let leaf = prop_oneof![
        (0u64..100_000, 0u32..4).prop_map(|(n, d)| Expr::Num(num_rational::BigRational::new(
            n.into(),
            num_bigint::BigInt::from(10u32.pow(d))
        ))),
        names.prop_map(Expr::sym),
        Just(Expr::Pi),
    ];
    leaf.prop_recursive(6, 64, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|e| Expr::Neg(Box::new(e))),
            (
                prop::sample::select(vec![Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Pow]),
                inner.clone(),
                inner.clone()
            )
                .prop_map(|(op, a, b)| Expr::Bin(op, Box::new(a), Box::new(b))),
            (
                prop::sample::select(vec![
                    impactcheck::algebra::expr::Func::Sqrt,
                    impactcheck::algebra::expr::Func::Exp,
                    impactcheck::algebra::expr::Func::Sin,
                ]),
                inner
            )
                .prop_map(|(f, a)| Expr::Call(f, Box::new(a))),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// parse(print(e)) == e for every tree the grammar can express.
    #[test]
    fn print_then_parse_is_the_identity(e in arb_expr()) {
        let text = e.to_string();
        let back = parse(&text);
        prop_assert_eq!(back, Ok(e), "text: {}", text);
    }

    /// Arbitrary text never panics: a tree or an error with a column inside the text (+1 for
    /// the end).
    #[test]
    fn arbitrary_text_gives_a_tree_or_a_located_error(s in "[ -~]{0,60}") {
        match parse(&s) {
            Ok(e) => prop_assert_eq!(parse(&e.to_string()), Ok(e)),
            Err(err) => prop_assert!(err.column >= 1 && err.column <= s.chars().count() + 1),
        }
        let _ = parse_inequality(&s);
    }

    /// Formula-like text (the grammar's tokens in any order) never panics either.
    #[test]
    fn token_soup_gives_a_tree_or_an_error(toks in prop::collection::vec(
        prop::sample::select(vec!["x", "2", "0.5", "1e-3", "+", "-", "*", "/", "^", "(", ")", "sqrt(", "pi", "a.b", "<=", " "]), 0..30)) {
        let s: String = toks.concat();
        if let Ok(e) = parse(&s) {
            prop_assert_eq!(parse(&e.to_string()), Ok(e));
        }
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let s = format!("{}x{}", "(".repeat(5000), ")".repeat(5000));
    assert!(parse(&s).is_err());
    let s = format!("{}x", "-".repeat(5000));
    assert!(parse(&s).is_err());
    let s = format!("x{}", "^x".repeat(5000));
    assert!(parse(&s).is_err());
}

#[test]
fn clopper_pearson_matches_published_intervals() {
    // 95 % exact intervals for n = 10, k = 0..10, as tabulated (e.g. R's binom.test; k = 0 and
    // k = n have the closed forms 1 - 0.025^(1/10) = 0.3085 and 0.025^(1/10) = 0.6915)
    let table = [
        (0, 0.0, 0.30850),
        (1, 0.00253, 0.44502),
        (2, 0.02521, 0.55610),
        (3, 0.06674, 0.65245),
        (4, 0.12155, 0.73762),
        (5, 0.18708, 0.81292),
        (6, 0.26238, 0.87845),
        (7, 0.34755, 0.93326),
        (8, 0.44390, 0.97479),
        (9, 0.55498, 0.99747),
        (10, 0.69150, 1.0),
    ];
    for (k, lo, hi) in table {
        let (l, h) = impactcheck::verify::kinds::clopper_pearson(k, 10, 0.95);
        assert!(
            (l - lo).abs() < 2e-5 && (h - hi).abs() < 2e-5,
            "k = {k}: [{l}, {h}] against [{lo}, {hi}]"
        );
    }
}

/// The linear spring-dashpot scene of the repository beside a claims file.
fn spring_claims(name: &str, body: &str) -> PathBuf {
    let p = claims_file(name, body);
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spring_dashpot.toml");
    std::fs::copy(scene, p.parent().expect("dir").join("spring.toml")).expect("copy scene");
    p
}

#[test]
fn map_share_matches_the_closed_form_region() {
    // e = exp(-zeta pi/sqrt(1 - zeta^2)) >= 1/2 exactly when zeta <= ln 2/sqrt(pi^2 + ln^2 2), i.e.
    // c <= 2 zeta* sqrt(k m) (k = 1e4 N/m in the scene): count the grid points by that closed form
    let p = spring_claims(
        "map",
        r#"
[[claim]]
id = "t.map"
equation = "(5)"
quote = "e >= 1/2"
kind = "map"
scene = "spring.toml"
require = "restitution >= 0.5"
vary = ["contact.damping=1:120:13", "impactor.mass=0.1:2:11"]
"#,
    );
    let papers = load_claims(&p).expect("claims");
    let out = run_all(&papers, p.parent().expect("dir")).expect("run");
    let share = out[0].extra["valid_fraction"].as_f64().expect("share");
    let ln2 = std::f64::consts::LN_2;
    let zeta_star = ln2 / (std::f64::consts::PI.powi(2) + ln2 * ln2).sqrt();
    let mut inside = 0;
    for i in 0..13 {
        let c = 1.0 + 119.0 * i as f64 / 12.0;
        for j in 0..11 {
            let m = 0.1 + 1.9 * j as f64 / 10.0;
            let bound = 2.0 * zeta_star * (1e4 * m).sqrt();
            assert!(
                (c - bound).abs() > 1e-6 * bound,
                "a grid point sits on the boundary"
            );
            inside += usize::from(c <= bound);
        }
    }
    assert_eq!(share, inside as f64 / 143.0, "{}", out[0].detail);
    assert_eq!(out[0].verdict, Verdict::Fails);
    assert!(out[0].files[0].1.contains("<svg"));
    // the figure's data: every grid point with its own state, by the same closed form
    let csv = &out[0].files[1].1;
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 143, "{csv}");
    assert!(csv.starts_with("contact.damping,impactor.mass,left,right,left_minus_right,inside\n"));
    for row in rows {
        let f: Vec<&str> = row.split(',').collect();
        let (c, m): (f64, f64) = (f[0].parse().expect("c"), f[1].parse().expect("m"));
        let want = if c <= 2.0 * zeta_star * (1e4 * m).sqrt() {
            "1"
        } else {
            "0"
        };
        assert_eq!(f[5], want, "{row}");
        // the model's restitution beside the bound, and their difference
        let zeta = c / (2.0 * (1e4 * m).sqrt());
        // (overdamped, zeta >= 1: the body creeps back and never leaves with any speed)
        let e = if zeta < 1.0 {
            (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp()
        } else {
            0.0
        };
        let (l, r, d): (f64, f64, f64) = (
            f[2].parse().expect("left"),
            f[3].parse().expect("right"),
            f[4].parse().expect("difference"),
        );
        assert!((l - e).abs() < 1e-6, "{row}: {e}");
        assert_eq!((r, d), (0.5, l - 0.5), "{row}");
    }
    // where the boundary lies: the first damping whose column changes, by the closed form, and
    // the two masses it changes between (inside from m = (c/(2 zeta*))^2/1e4 on)
    let (c, j) = (0..13)
        .find_map(|i| {
            let c = 1.0 + 119.0 * i as f64 / 12.0;
            let m_star = (c / (2.0 * zeta_star)).powi(2) / 1e4;
            let j = (1..11).find(|j| {
                let (a, b) = (0.1 + 0.19 * (*j - 1) as f64, 0.1 + 0.19 * *j as f64);
                a < m_star && m_star <= b
            })?;
            Some((c, j))
        })
        .expect("a column crosses");
    let (a, b) = (0.1 + 0.19 * (j - 1) as f64, 0.1 + 0.19 * j as f64);
    let d = &out[0].detail;
    let at = d
        .find("the boundary along impactor.mass: at contact.damping = ")
        .unwrap_or_else(|| panic!("no boundary in {d}"));
    // "at contact.damping = X: enters between A and B": the numbers as printed (4 digits)
    let words: Vec<&str> = d[at..]
        .split([' ', ':', ';'])
        .filter(|w| !w.is_empty())
        .collect();
    let num = |k: usize| -> f64 { words[k].parse().unwrap_or_else(|_| panic!("{k} in {d}")) };
    assert_eq!((words[8], words[9]), ("enters", "between"), "{d}");
    for (got, want) in [(num(7), c), (num(10), a), (num(12), b)] {
        assert!((got - want).abs() < 1e-3 * want, "{got} vs {want} in {d}");
    }
}

#[test]
fn a_model_claim_draws_the_model_and_the_printed_curve() {
    // the figure's data: one row per grid point, the model's duration and the printed formula;
    // the printed column is the formula at the m and k of the scene beside the claims
    let p = claims_file(
        "model-plot",
        r#"
[[claim]]
id = "t.plot"
equation = "(3)"
quote = "t_c = 3.2181 (m/k)^(2/5) v0^(-1/5)"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "3.2181*(m/k)^(2/5)*v0^(-1/5)"
bind = { m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }
vary = ["impactor.v0=0.1:10:5:log"]
rtol = 2e-5
"#,
    );
    let papers = load_claims(&p).expect("claims");
    let out = run_all(&papers, p.parent().expect("dir")).expect("run");
    let svg = out[0]
        .files
        .iter()
        .find(|f| f.0.ends_with(".svg"))
        .expect("a figure");
    assert!(svg.1.contains("<svg"));
    let csv = &out[0]
        .files
        .iter()
        .find(|f| f.0.ends_with(".csv"))
        .expect("its data")
        .1;
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().expect("number")).collect())
        .collect();
    assert_eq!(rows.len(), 5, "{csv}");
    let scene =
        std::fs::read_to_string(p.parent().expect("dir").join("hertz.toml")).expect("scene");
    let value = |key: &str| -> f64 {
        scene
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{key} ")))
            .and_then(|l| l.split('=').nth(1))
            .and_then(|v| v.split('#').next())
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or_else(|| panic!("{key} in the scene:\n{scene}"))
    };
    let (m, k) = (value("mass"), value("k"));
    for r in rows {
        let printed = 3.2181 * (m / k).powf(0.4) * r[0].powf(-0.2);
        assert!(
            (r[2] - printed).abs() <= 1e-12 * printed,
            "{r:?} vs {printed}"
        );
        assert!((r[1] - printed).abs() <= 2e-5 * printed, "{r:?}");
    }
}

#[test]
fn probability_interval_contains_the_closed_form() {
    // c ~ uniform(0, 100), k = 1e4, m = 0.5: P(e >= 1/2) = 2 zeta* sqrt(k m)/100 = 0.3047
    let p = spring_claims(
        "probability",
        r#"
[[claim]]
id = "t.p"
equation = "(6)"
quote = "P(e >= 1/2)"
kind = "probability"
scene = "spring.toml"
sample = { "contact.damping" = "uniform(0, 100)" }
count = 400
seed = 11
event = "restitution >= 0.5"
expect = ">= 0.2"
"#,
    );
    let papers = load_claims(&p).expect("claims");
    let out = run_all(&papers, p.parent().expect("dir")).expect("run");
    let pr = &out[0].extra["probability"];
    let (lo, hi) = (
        pr["lo"].as_f64().unwrap_or(1.0),
        pr["hi"].as_f64().unwrap_or(0.0),
    );
    let ln2 = std::f64::consts::LN_2;
    let exact = 2.0 * ln2 / (std::f64::consts::PI.powi(2) + ln2 * ln2).sqrt()
        * (1e4f64 * 0.5).sqrt()
        / 100.0;
    assert!(lo <= exact && exact <= hi, "[{lo}, {hi}] misses {exact}");
    assert_eq!(out[0].verdict, Verdict::Holds, "{}", out[0].detail);
}

#[test]
fn never_and_always_are_decided_by_a_counterexample_or_its_absence() {
    // a linear spring-dashpot never rebounds faster than it came (e <= 1 for c >= 0, by
    // energy): "p <= 0" of e > 1 holds, no interval of finite samples being needed; e >= 1/2
    // happens for c below 30.5 N s/m (the closed form above), so "never" of it fails on the
    // samples that show it, and "always" of it fails too
    let body = |id: &str, event: &str, expect: &str| {
        format!(
            r#"
[[claim]]
id = "{id}"
equation = "(6)"
quote = "never"
kind = "probability"
scene = "spring.toml"
sample = {{ "contact.damping" = "uniform(0, 100)" }}
count = 200
seed = 11
event = "{event}"
expect = "{expect}"
"#
        )
    };
    let p = spring_claims(
        "never",
        &[
            body("t.never", "restitution > 1 + 1e-9", "<= 0"),
            body("t.never-broken", "restitution >= 0.5", "<= 0"),
            body("t.always", "restitution <= 1 + 1e-9", ">= 1"),
            body("t.always-broken", "restitution < 0.5", ">= 1"),
        ]
        .concat(),
    );
    let papers = load_claims(&p).expect("claims");
    let out = run_all(&papers, p.parent().expect("dir")).expect("run");
    let verdict = |id: &str| {
        let o = out.iter().find(|o| o.id == id).expect(id);
        (o.verdict, o.detail.clone())
    };
    assert_eq!(
        verdict("t.never").0,
        Verdict::Holds,
        "{}",
        verdict("t.never").1
    );
    assert_eq!(
        verdict("t.always").0,
        Verdict::Holds,
        "{}",
        verdict("t.always").1
    );
    for id in ["t.never-broken", "t.always-broken"] {
        let (v, d) = verdict(id);
        assert_eq!(v, Verdict::Fails, "{d}");
        assert!(d.contains("computed counterexample"), "{d}");
    }
}

#[test]
fn definitions_are_checked_for_units_and_uses() {
    // by hand: the area of [0, x] x [0, y] is x y, its polar moment int int (s^2) over it is
    // x^3 y/3; a unit mismatch (m^2 against m) and a wrong use (x y/2) must fail
    let p = claims_file(
        "definition",
        r#"
[[claim]]
id = "t.area"
equation = "(1)"
quote = "A = x y"
kind = "definition"
printed = "x*y"
defines = "A"
agrees = [["A", "int(int(1, s, 0, y), u, 0, x)"], ["int(int(u^2, s, 0, y), u, 0, x)", "A*x^2/3"]]

[[claim]]
id = "t.area-unit"
equation = "(1)"
quote = "A = x"
kind = "definition"
printed = "x"
defines = "A"

[[claim]]
id = "t.area-use"
equation = "(1)"
quote = "A = x y, used as x y/2"
kind = "definition"
printed = "x*y"
defines = "A"
agrees = [["A", "int(int(1, s, 0, y/2), u, 0, x)"]]

[[claim]]
id = "t.missing"
equation = "(2)"
quote = "the text stops"
kind = "not-checkable"
reason = "the page is missing"
"#,
    );
    // the symbols of this test
    let text = std::fs::read_to_string(&p).unwrap().replace(
        "[symbols]\n",
        "[symbols]\nA = \"m^2\"\ns = \"m\"\nu = \"m\"\n",
    );
    std::fs::write(&p, text).unwrap();
    let v = verdicts(&p);
    let get = |id: &str| v.iter().find(|(i, ..)| i == id).expect(id).clone();
    assert_eq!(get("t.area").1, Verdict::Definition, "{}", get("t.area").2);
    let unit = get("t.area-unit");
    assert_eq!(unit.1, Verdict::Fails);
    assert!(unit.2.contains("`A` is m^2 but `x` is m"), "{}", unit.2);
    let used = get("t.area-use");
    assert_eq!(used.1, Verdict::Fails);
    assert!(used.2.contains("!="), "{}", used.2);
    let nc = get("t.missing");
    assert_eq!(
        (nc.1, nc.2.as_str()),
        (Verdict::NotCheckable, "the page is missing")
    );

    // a use that does not read the printed formula (no `A` in it) checks nothing: refused
    let text = std::fs::read_to_string(&p).unwrap().replace(
        r#"["int(int(u^2, s, 0, y), u, 0, x)", "A*x^2/3"]"#,
        r#"["int(int(u^2, s, 0, y), u, 0, x)", "x^3*y/3"]"#,
    );
    std::fs::write(&p, text).unwrap();
    let papers = load_claims(&p).expect("loads");
    let err = impactcheck::verify::validate_all(&papers)
        .expect_err("a use without the defined symbol")
        .to_string();
    assert!(
        err.contains("claim t.area: agrees[1]: the use does not contain `A`"),
        "{err}"
    );
}

#[test]
fn bounds_on_formulas_alone_and_assumptions() {
    // by hand: x^2 + 1 > 2 x fails only at x = 1 (never drawn exactly), x^2 >= 2 x fails on
    // (0, 2); an assumption turns a holds into holds-with-assumption and a fail stays a fail
    let p = claims_file(
        "formula-bound",
        r#"
[[claim]]
id = "t.am-gm"
equation = "(1)"
quote = "x^2 + 1 > 2 x"
kind = "bound"
sample = { x = "uniform(-3, 3)" }
count = 500
seed = 3
require = "x^2 + 1 > 2*x"
assumption = "x is real"

[[claim]]
id = "t.wrong"
equation = "(2)"
quote = "x^2 >= 2 x"
kind = "bound"
sample = { x = "uniform(-3, 3)" }
count = 500
seed = 3
require = "x^2 >= 2*x"
assumption = "x is real"
"#,
    );
    let v = verdicts(&p);
    let get = |id: &str| v.iter().find(|(i, ..)| i == id).expect(id).clone();
    let ok = get("t.am-gm");
    assert_eq!(ok.1, Verdict::HoldsWithAssumption, "{}", ok.2);
    assert!(
        ok.2.starts_with("assuming x is real: 500 of 500"),
        "{}",
        ok.2
    );
    let bad = get("t.wrong");
    assert_eq!(bad.1, Verdict::Fails, "{}", bad.2);
}

#[test]
fn bounds_search_for_their_extreme_and_sharp_asks_it_to_be_attained() {
    // by hand: q (1 - q) on [0, 1] peaks at 1/4 (q = 1/2). Three samples miss the peak; the
    // search from them finds it: q (1 - q) <= 0.24 fails there though no sample violates it;
    // <= 1/4 holds and is sharp; <= 0.3 holds but is not sharp
    let claim = |id: &str, rhs: &str, sharp: bool| {
        format!(
            "[[claim]]\nid = \"{id}\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"bound\"\nsample = {{ q = \"uniform(0, 0.2)\" }}\ncount = 3\nseed = 5\nrequire = \"q*(1 - q) <= {rhs}\"\nsharp = {sharp}\n"
        )
    };
    let body = [
        claim("t.tight", "0.24", false),
        claim("t.peak", "0.25", true),
        claim("t.loose", "0.3", true),
    ]
    .concat()
    .replace("uniform(0, 0.2)", "uniform(0, 1)");
    let p = claims_file("extreme", &body);
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replace("[symbols]\n", "[symbols]\nq = \"1\"\n");
    std::fs::write(&p, text).unwrap();
    let v = verdicts(&p);
    let get = |id: &str| v.iter().find(|(i, ..)| i == id).expect(id).clone();
    let tight = get("t.tight");
    assert_eq!(tight.1, Verdict::Fails, "{}", tight.2);
    assert!(
        tight.2.contains("0 violate"),
        "no sample violates: {}",
        tight.2
    );
    assert!(tight.2.contains("found a violation"), "{}", tight.2);
    let peak = get("t.peak");
    assert_eq!(peak.1, Verdict::Holds, "{}", peak.2);
    assert!(
        peak.2.contains("sharp: the bound is attained"),
        "{}",
        peak.2
    );
    let loose = get("t.loose");
    assert_eq!(loose.1, Verdict::Fails, "{}", loose.2);
    assert!(loose.2.contains("NOT sharp"), "{}", loose.2);
}

#[test]
fn an_identity_undefined_at_its_points_does_not_hold() {
    // by hand: sqrt(q - 3) is not a real number for q in [0.5, 2], where identities are
    // compared; NaN = NaN must not count as agreement (f64::max drops a NaN)
    let p = claims_file(
        "undefined",
        "[[claim]]\nid = \"t.nan\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"identity\"\nprinted = \"sqrt(q - 3)\"\nderived = \"sqrt(q - 3)*exp(0*q)\"\n",
    );
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replace("[symbols]\n", "[symbols]\nq = \"1\"\n");
    std::fs::write(&p, text).unwrap();
    let v = verdicts(&p);
    assert_eq!(v[0].1, Verdict::Fails, "{}", v[0].2);
    assert!(v[0].2.contains("not a finite number"), "{}", v[0].2);
}

#[test]
fn fail_on_fails_exits_1_naming_the_failing_claims() {
    // (x + y)^2 = x^2 + y^2 fails (by hand: 2 x y is missing); (x + y)^2 expanded holds
    let p = claims_file(
        "fail-on",
        r#"
[[claim]]
id = "t.square"
equation = "(1)"
reading = "(x + y)^2 = x^2 + 2 x y + y^2"
kind = "identity"
printed = "x^2 + 2*x*y + y^2"
derived = "(x + y)^2"

[[claim]]
id = "t.square-wrong"
equation = "(1)"
reading = "(x + y)^2 = x^2 + y^2"
kind = "identity"
printed = "x^2 + y^2"
derived = "(x + y)^2"
"#,
    );
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_verify"))
            .arg("--claims")
            .arg(&p)
            .args(extra)
            .output()
            .expect("verify runs");
        (
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    let (code, err) = run(&[]);
    assert_eq!(code, 0, "a failing claim is a finding by default: {err}");
    let (code, err) = run(&["--fail-on", "fails"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("1 claim(s) fail: t.square-wrong"),
        "the failing claim is named: {err}"
    );
    let (code, err) = run(&["--fail-on", "fails", "--only", "t.square-wrong"]);
    assert_eq!(code, 1, "{err}");
    let (code, err) = run(&["--fail-on", "fails", "--only", "t.nothing"]);
    assert_eq!(code, 2, "no claim matches: bad input, {err}");
    let (code, err) = run(&["--fail-on", "sometimes"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("never") && err.contains("fails"), "{err}");
}

#[test]
fn integrals_over_a_square_root_endpoint_are_judged_with_their_error_estimate() {
    // closed forms: int_0^a sqrt(a^2 - x^2) dx = pi a^2/4 (a quarter disc); int_-a^a
    // 1/sqrt(a^2 - x^2) dx = pi (the arcsine). The second's nodes round onto +-a within 1e-16,
    // so its quadrature is good to about 1e-8: the verdict widens its tolerance by the estimate
    // and says so; a printed constant 1e-6 off still fails
    let p = claims_file(
        "int",
        r#"
[[claim]]
id = "t.quarter-disc"
equation = "(1)"
reading = "the quarter disc"
kind = "identity"
printed = "pi*x^2/4"
derived = "int(sqrt(x^2 - y^2), y, 0, x)"

[[claim]]
id = "t.arcsine"
equation = "(1)"
reading = "the arcsine integral"
kind = "identity"
printed = "pi"
derived = "int(1/sqrt(x^2 - y^2), y, -x, x)"

[[claim]]
id = "t.arcsine-misprint"
equation = "(1)"
reading = "the arcsine integral, misprinted"
kind = "identity"
printed = "pi*(1 + 1e-6)"
derived = "int(1/sqrt(x^2 - y^2), y, -x, x)"
"#,
    );
    let v = verdicts(&p);
    let get = |id: &str| v.iter().find(|c| c.0 == id).expect("claim ran");
    for id in ["t.quarter-disc", "t.arcsine"] {
        let (_, verdict, detail) = get(id);
        assert_eq!(*verdict, Verdict::Holds, "{id}: {detail}");
        assert!(
            detail.contains("tanh-sinh quadrature, largest estimated relative error"),
            "{id}: the detail names the quadrature: {detail}"
        );
    }
    let (_, verdict, detail) = get("t.arcsine-misprint");
    assert_eq!(*verdict, Verdict::Fails, "{detail}");
}

#[test]
fn a_constant_ratio_between_the_sides_is_named_a_constant_factor() {
    // by hand: 2 x^2 against x^2 is a factor 1/2 (derived/printed); -sqrt(x y) against
    // sqrt(x y) the opposite sign; the Hertz duration with the constant doubled is 1/2 of the
    // model's at every grid point; x^2 + y against x^2 is no constant factor
    let p = claims_file(
        "factor",
        r#"
[[claim]]
id = "t.exact"
equation = "(1)"
reading = "x^2, misprinted 2 x^2"
kind = "identity"
printed = "2*x^2"
derived = "x^2"

[[claim]]
id = "t.not-constant"
equation = "(1)"
reading = "x^2, misprinted x^2 + x*y"
kind = "identity"
printed = "x^2 + x*y"
derived = "x^2"

[[claim]]
id = "t.numeric-sign"
equation = "(1)"
reading = "sqrt(x y), misprinted with a minus"
kind = "identity"
printed = "-sqrt(x*y)"
derived = "sqrt(x*y)"

[[claim]]
id = "t.model"
equation = "(1)"
reading = "the Hertz duration, its constant doubled"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "2*3.2180654597*(m/k)^(2/5)*v0^(-1/5)"
bind = { m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }
vary = ["impactor.v0=0.5:2:3"]
rtol = 1e-6
"#,
    );
    let v = verdicts(&p);
    let get = |id: &str| v.iter().find(|c| c.0 == id).expect("claim ran");
    for (id, want) in [
        ("t.exact", "derived/printed = 1/2: a constant factor of 1/2"),
        ("t.numeric-sign", "the opposite sign"),
        ("t.model", "a constant factor of 0.5000"),
    ] {
        let (_, verdict, detail) = get(id);
        assert_eq!(*verdict, Verdict::Fails, "{id}: {detail}");
        assert!(detail.contains(want), "{id}: `{want}` not in {detail}");
    }
    let (_, verdict, detail) = get("t.not-constant");
    assert_eq!(*verdict, Verdict::Fails, "{detail}");
    assert!(!detail.contains("constant factor"), "{detail}");
}

#[test]
fn the_guide_lists_every_key_of_every_kind() {
    // the keys each kind takes, as its own error lists them (a claim with an unknown key), and
    // the head's keys; each must be a row `| kind | key |` of the guide's table, and the table
    // has no row for a key a kind does not take
    let guide =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("verify/README.md"))
            .expect("guide");
    let mut rows = std::collections::BTreeSet::new();
    for line in guide.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() > 3 && cells[1].starts_with('`') && cells[2].starts_with('`') {
            rows.insert((
                cells[1].trim_matches('`').to_string(),
                cells[2].trim_matches('`').to_string(),
            ));
        }
    }
    let mut want = std::collections::BTreeSet::new();
    for kind in [
        "identity",
        "dimension",
        "model",
        "bound",
        "probability",
        "map",
        "definition",
        "not-checkable",
        "check",
    ] {
        let (code, err, _) = verify_bad(
            &format!("keys-{kind}"),
            &format!(
                "[[claim]]\nid = \"t.a\"\nequation = \"(1)\"\nreading = \"q\"\nkind = \"{kind}\"\nno_such_key = 1\n"
            ),
        );
        assert_eq!(code, 2, "{kind}: {err}");
        let allowed = err
            .split("allowed: ")
            .nth(1)
            .unwrap_or_else(|| panic!("{kind}: no list of keys in {err}"));
        for key in allowed
            .split(',')
            .map(|k| k.trim().trim_matches('`').trim())
        {
            if !key.is_empty() {
                want.insert((kind.to_string(), key.to_string()));
            }
        }
    }
    for key in [
        "id",
        "equation",
        "quote",
        "reading",
        "kind",
        "assumption",
        "blind",
        "finding",
        "extends",
        "printed_from",
        "printed_tex",
        "printed_equations_from",
        "printed_matrix_from",
        "retyped",
        "correction",
        "printed_where",
    ] {
        want.insert(("every kind".to_string(), key.to_string()));
    }
    let missing: Vec<_> = want.difference(&rows).collect();
    assert!(
        missing.is_empty(),
        "keys not in the guide's table: {missing:?}"
    );
    let kinds: std::collections::BTreeSet<&String> = want.iter().map(|(k, _)| k).collect();
    let extra: Vec<_> = rows
        .iter()
        .filter(|r| kinds.contains(&r.0) && !want.contains(*r))
        .collect();
    assert!(extra.is_empty(), "rows for keys no kind takes: {extra:?}");
}

#[test]
fn a_model_formula_in_another_unit_than_its_quantity_says_so() {
    // the Hertz duration formula (s) compared with the peak force (N): the detail names both
    // units beside the verdict
    let p = claims_file(
        "units-note",
        r#"
[[claim]]
id = "t.units"
equation = "(1)"
reading = "a time against a force"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "3.2181*(m/k)^(2/5)*v0^(-1/5)*k/k*m/m*v0/v0*k*m"
bind = { m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }
vary = ["impactor.v0=0.5:2:2"]
rtol = 1e-3
"#,
    );
    let v = verdicts(&p);
    assert!(
        v[0].2.contains("; units: the formula is") && v[0].2.contains("the quantity s"),
        "{}",
        v[0].2
    );
}

/// Every key a claim must have is in the guide's list (verify/README.md), and a claim without
/// it is exit 2 naming it, with nothing written.
#[test]
fn every_required_key_is_in_the_guide_and_named_when_missing() {
    let guide =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("verify/README.md"))
            .expect("the guide");
    let at = guide
        .find("Required in every claim:")
        .expect("the guide lists the required keys");
    let list = &guide[at..at + guide[at..].find("\n\n").expect("a paragraph")];
    let full = "[[claim]]\nid = \"t.req\"\nequation = \"(1)\"\nreading = \"r\"\nkind = \"identity\"\nprinted = \"x\"\nderived = \"x\"";
    let (code, err, _) = verify_bad("req-none", full);
    assert_eq!(code, 0, "the full claim is valid: {err}");
    for (key, says) in [
        ("id", "id"),
        ("equation", "equation"),
        ("kind", "kind"),
        ("reading", "reading"),
    ] {
        assert!(list.contains(&format!("`{key}`")), "{key} not in: {list}");
        let body: Vec<&str> = full
            .lines()
            .filter(|l| !l.starts_with(&format!("{key} =")))
            .collect();
        let (code, err, wrote) = verify_bad(&format!("req-{key}"), &body.join("\n"));
        assert_eq!(code, 2, "{key}: {err}");
        assert!(err.contains(says), "{key}: {err}");
        assert!(!wrote, "{key}");
    }
    for key in ["paper", "title", "report"] {
        assert!(list.contains(&format!("`{key}`")), "{key} not in: {list}");
    }
}

/// A number in a claim's `where` is a value in the unit [symbols] gives that name, as a number
/// in a text model's `[state]` is (issue 44): `where = { x = "2" }` with x in m is 2 m, so the
/// units of the formula are those of x, and a unit the formula does not have still fails.
#[test]
fn a_number_in_where_is_a_value_in_the_names_unit() {
    let p = claims_file(
        "where-number",
        r#"
[[claim]]
id = "t.sum"
equation = "(1)"
reading = "x + y with x = 2 m is a length"
kind = "dimension"
printed = "x + y"
expect = "m"
where = { x = "2" }

[[claim]]
id = "t.power"
equation = "(1)"
reading = "k x^(3/2) with x = 2.5 m is a force"
kind = "dimension"
printed = "k*x^(3/2)"
expect = "N"
where = { x = "2.5" }

[[claim]]
id = "t.wrong"
equation = "(1)"
reading = "k x with x = 2.5 m is not a force"
kind = "dimension"
printed = "k*x"
expect = "N"
where = { x = "2.5" }

[[claim]]
id = "t.value"
equation = "(1)"
reading = "the number is still the value: x + y = y + 2"
kind = "identity"
printed = "x + y"
derived = "y + 2"
where = { x = "2" }

[[claim]]
id = "t.defines"
equation = "(1)"
reading = "a definition of y by a number and x: y = x + 3, with x = 1 m"
kind = "definition"
defines = "y"
printed = "x + 3*x"
agrees = [["y", "4*x"]]
where = { x = "1" }

[[claim]]
id = "t.model"
equation = "(1)"
reading = "the Hertz duration times x = 1 m is a length times a time, not the duration's unit"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "3.2181*(m/k)^(2/5)*v0^(-1/5)*x"
bind = { m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }
vary = ["impactor.v0=0.5:2:2"]
rtol = 1e-3
where = { x = "1" }
"#,
    );
    let v = verdicts(&p);
    let by = |id: &str| v.iter().find(|o| o.0 == id).expect(id).clone();
    let model = by("t.model");
    assert!(
        model
            .2
            .contains("; units: the formula is m s, the quantity s"),
        "{model:?}"
    );
    assert_eq!(by("t.sum").1, Verdict::Holds, "{:?}", by("t.sum"));
    assert_eq!(by("t.power").1, Verdict::Holds, "{:?}", by("t.power"));
    let wrong = by("t.wrong");
    assert_eq!(wrong.1, Verdict::Fails, "{wrong:?}");
    // k x: (N/m^1.5) m = kg m^(1/2) s^-2, worked by hand
    assert!(wrong.2.contains("kg m^(1/2) s^-2"), "{}", wrong.2);
    assert_eq!(by("t.value").1, Verdict::Holds, "{:?}", by("t.value"));
    assert_eq!(
        by("t.defines").1,
        Verdict::Definition,
        "{:?}",
        by("t.defines")
    );
}
