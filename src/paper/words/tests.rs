//! The words reader on sentences written by hand, each with the unit a referee reads in it
//! (or none, where the words do not fix one).

use super::dimensionless::says_dimensionless;
use super::vocabulary::Vocabulary;
use super::*;

fn vocab() -> Vocabulary {
    Vocabulary::builtin().expect("the built-in vocabulary reads")
}

fn quantity(desc: &str) -> Option<String> {
    vocab().describe(desc).map(|h| h.quantity.name.clone())
}

fn before(text: &str) -> Option<String> {
    vocab().before_symbol(text).map(|h| h.quantity.name.clone())
}

#[test]
fn every_quantity_of_the_built_in_vocabulary_has_a_unit_that_parses_or_none() {
    let v = vocab();
    assert!(v.quantities().len() >= 30);
    let mass = v.quantities().iter().find(|q| q.name == "mass").unwrap();
    assert_eq!(mass.unit.map(|u| u.to_string()), Some("kg".into()));
    let law = v
        .quantities()
        .iter()
        .find(|q| q.name == "unit_from_law")
        .unwrap();
    assert_eq!(law.unit, None);
}

#[test]
fn a_description_names_its_head_quantity() {
    let cases = [
        ("the relaxed Young's modulus", Some("pressure")),
        ("the density of plate", Some("density")),
        ("the mass density of the ball", Some("density")),
        ("the disk angular velocity vector", Some("angular_velocity")),
        (
            "the projections of the velocity of the centre of mass",
            Some("velocity"),
        ),
        (
            "the absolute value of the tangential component of the relative velocity",
            Some("velocity"),
        ),
        ("the amplitude of the applied force", Some("force")),
        ("the amplitude of the vibration", Some("length")),
        (
            "the moment of inertia about the axis",
            Some("moment_of_inertia"),
        ),
        ("the radii of inertia of the base area", Some("length")),
        ("odd numbers", Some("count")),
        ("the penetration depths", Some("length")),
        ("the coefficient of sliding friction", Some("ratio")),
        ("the central inertia tensor", Some("moment_of_inertia")),
        ("the principal moment of the reactions", Some("moment")),
        // words that do not fix a unit, or fix another quantity than their head
        ("the Winkler modulus", None),
        ("the Damper modulus parameters", None),
        ("Airy function stress", None),
        ("the moments of inertia of the base area", None),
        ("the force per unit length", None),
        ("the force density", None),
        ("the dimensionless time", None),
        (
            "the principal moment of the friction forces referred to the normal reaction",
            None,
        ),
        ("the centre of mass of the body", None),
        ("the stiffness of the spring", None),
        ("the Laplace operator", None),
        ("the minimum eigenvalue of the matrix", None),
        ("negative", None),
    ];
    for (desc, want) in cases {
        assert_eq!(quantity(desc).as_deref(), want, "{desc}");
    }
}

#[test]
fn the_words_right_before_a_symbol_name_it() {
    let cases = [
        ("A ball of mass ", Some("mass")),
        ("the stiffness ", None),
        ("with the dimensions ", Some("length")),
        ("and of thickness ", Some("thickness_is_length")),
        ("at the moment ", None),
        ("the force density ", None),
        ("the velocity of the centre of mass ", None),
        ("the coefficient of restitution ", Some("ratio")),
    ];
    for (text, want) in cases {
        let want = want.map(|w| {
            if w == "thickness_is_length" {
                "length"
            } else {
                w
            }
        });
        assert_eq!(before(text).as_deref(), want, "{text}");
    }
    assert!(
        vocab()
            .before_symbol("with the dimensions ")
            .unwrap()
            .plural
    );
    assert!(!vocab().before_symbol("of mass ").unwrap().plural);
}

#[test]
fn a_unit_written_in_the_paper_is_read_as_written() {
    let u = |t: &str| written_unit(t).map(|u| u.to_string());
    assert_eq!(u("Pa").as_deref(), Some("kg m^-1 s^-2"));
    assert_eq!(u("kg m^{-3}").as_deref(), Some("kg m^-3"));
    assert_eq!(u("m s$^{-1}$").as_deref(), Some("m s^-1"));
    assert_eq!(u("\\mathrm{N\\,m}").as_deref(), Some("kg m^2 s^-2"));
    assert_eq!(u("N·m").as_deref(), Some("kg m^2 s^-2"));
    assert_eq!(u("m ^2").as_deref(), Some("m^2"));
    assert_eq!(u("-").as_deref(), Some("1"));
    // a citation, an equation's number, a variable: no unit
    for t in ["1", "1.3", "12, 14", "t", "x", "see Fig. 2"] {
        assert_eq!(u(t), None, "{t}");
    }
}

#[test]
fn symbols_written_without_dollars_are_read_in_a_translated_paper() {
    assert_eq!(bare_symbol("Ω").as_deref(), Some("\\Omega "));
    assert_eq!(bare_symbol("M_F").as_deref(), Some("M_F"));
    assert_eq!(bare_symbol("**n**").as_deref(), Some("\\mathbf{n}"));
    assert_eq!(bare_symbol("F^*").as_deref(), Some("F^*"));
    assert_eq!(bare_symbol("ρ_0").as_deref(), Some("\\rho _0"));
    for w in ["the", "is", "mass", "(1.2)", "G'"] {
        assert_eq!(bare_symbol(w), None, "{w}");
    }
    let syms = TexSymbols::default();
    let w = read_words(
        "where m is the mass, J is the central inertia tensor, V is the velocity of the centre of mass G and Ω is the angular velocity of the body. Let Q and M_Q denote the principal vector and principal moment of the active forces.",
        &syms,
        &vocab(),
    );
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("m").as_deref(), Some("kg"));
    assert_eq!(unit("J").as_deref(), Some("kg m^2"));
    assert_eq!(unit("V").as_deref(), Some("m s^-1"));
    assert_eq!(unit("Omega").as_deref(), Some("s^-1"));
    assert_eq!(unit("MQ").as_deref(), Some("kg m^2 s^-2"));
    // the point G takes no unit from the angular velocity after it, nor Q from a "vector"
    assert_eq!(unit("G"), None);
    assert_eq!(unit("Q"), None);
}

#[test]
fn a_symbol_the_words_give_two_units_gets_none() {
    let w = read_words(
        "A ball of mass $m$ hits the wall. Here $m$ is the mode number.",
        &TexSymbols::default(),
        &vocab(),
    );
    assert!(!w.units.contains_key("m"));
    assert_eq!(w.notes.len(), 1, "{:?}", w.notes);
    assert!(
        w.notes[0].contains("`m`") && w.notes[0].contains("kg"),
        "{:?}",
        w.notes
    );
}

#[test]
fn lists_respectively_plurals_and_a_verb_in_the_singular() {
    let w = read_words(
        "where $E, \\nu, \\eta$ are the relaxed Young's modulus, Poisson's ratio and viscosity, respectively, and $d$, $z$ are the penetration depths; the radius $R$ and $J$ is its moment of inertia.",
        &TexSymbols::default(),
        &vocab(),
    );
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("E").as_deref(), Some("kg m^-1 s^-2"));
    assert_eq!(unit("nu").as_deref(), Some("1"));
    assert_eq!(unit("eta").as_deref(), Some("kg m^-1 s^-1"));
    assert_eq!(unit("d").as_deref(), Some("m"));
    assert_eq!(unit("z").as_deref(), Some("m"));
    assert_eq!(unit("R").as_deref(), Some("m"));
    assert_eq!(unit("J").as_deref(), Some("kg m^2"));
}

#[test]
fn a_nomenclature_line_and_a_chain_of_names() {
    let text = "\\begin{tabular}{ll}\n$E$ & Young's modulus [Pa] \\\\\n$\\rho$ & density [kg m$^{-3}$] \\\\\n$A$ & section (m$^2$) \\\\\n\\end{tabular}\n\nwhere $\\tau=\\lambda^{-1}$ is the creep time and $\\delta(x - a)$ is the Dirac delta function.";
    let w = read_words(text, &TexSymbols::default(), &vocab());
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("E").as_deref(), Some("kg m^-1 s^-2"));
    assert_eq!(unit("rho").as_deref(), Some("kg m^-3"));
    assert_eq!(unit("A").as_deref(), Some("m^2"));
    assert_eq!(w.units["A"].quantity, "written");
    assert_eq!(w.units["A"].line, 4);
    assert_eq!(unit("tau").as_deref(), Some("s"));
    assert_eq!(unit("lambda").as_deref(), Some("s^-1"));
    assert!(w.dirac.contains("delta"));
}

#[test]
fn a_bad_vocabulary_is_refused_naming_what() {
    let e = Vocabulary::parse("[a]\nwords = [\"x\"]\nunit = \"parsec\"\n", "v.toml").unwrap_err();
    assert!(e.contains("v.toml: [a] unit = \"parsec\""), "{e}");
    let e = Vocabulary::parse(
        "[a]\nwords = [\"hold\"]\nunit = \"N\"\n[b]\nwords = [\"holds\"]\n",
        "v.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("the words \"holds\" are given twice, in [a] and [b]"),
        "{e}"
    );
    let e = Vocabulary::parse("[a]\nwords = []\n", "v.toml").unwrap_err();
    assert!(e.contains("[a] has no words"), "{e}");
    let e = Vocabulary::parse("[a]\nwords = [\"x\"]\nunits = \"N\"\n", "v.toml").unwrap_err();
    assert!(e.contains("units"), "{e}");
    let e = Vocabulary::parse(
        "[a]\nwords = [\"x\"]\nunit = \"N\"\ndescription_only = [\"y\"]\n",
        "v.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("description_only = \"y\" is not one of its words"),
        "{e}"
    );
    // a user's words replace the built-in ones
    let mine = Vocabulary::parse(
        "[spring_rate]\nwords = [\"stiffness\"]\nunit = \"N/m\"\n",
        "v",
    )
    .unwrap();
    let v = vocab().extended(mine);
    assert_eq!(
        v.describe("the stiffness of the spring")
            .map(|h| h.quantity.name.clone())
            .as_deref(),
        Some("spring_rate")
    );
}

#[test]
fn an_escaped_dollar_in_the_prose_opens_no_math() {
    // the math spans of the prose, by hand: `m` and `v_0`; `\$5` is a price, and a `$` at the
    // very start opens math
    let math = |p: &str| -> Vec<String> {
        items(p)
            .into_iter()
            .filter_map(|(_, i)| match i {
                Item::Math(m) => Some(m),
                Item::Text(_) => None,
            })
            .collect()
    };
    assert_eq!(
        math("a ball worth \\$5 of mass $m$ at the speed $v_0$"),
        vec!["m".to_string(), "v_0".to_string()]
    );
    assert_eq!(math("$m$ is the mass"), vec!["m".to_string()]);
    assert_eq!(math("\\(x\\) and \\$ alone"), vec!["x".to_string()]);
}

#[test]
fn a_section_that_says_it_is_dimensionless_is_a_span_to_its_end() {
    // by hand: the words of each line, and the spans of a three-section text
    for yes in [
        "Choosing units so that $m = \\alpha = 1$, we thus have",
        "Non-dimensionalizations are the same as in the previous section.",
        "the problem in non-dimensional form reads",
        "All quantities are non-dimensional.",
        "with the dimensionless variables $\\xi = x/L$",
        "the scaled equations",
        "with the 1D non dimensional Reynolds equation",
    ] {
        assert!(says_dimensionless(yes), "{yes}");
    }
    for no in [
        "where $\\zeta$ is the dimensionless damping ratio",
        "a non-dimensional number",
        "where $\\zeta$ is dimensionless",
        "$\\zeta$ and $\\mu$ are dimensionless",
        "the dimensionless damping ratio of the model, as in the equation",
        "the mass $m$ of the ball",
    ] {
        assert!(!says_dimensionless(no), "{no}");
    }
    // (text, its sections, its spans), by hand: the second section of the first text from its
    // sentence (line 6) to the third's heading (line 8), the third from the first of its two
    // mentions (line 9) to the end; in the second, a heading that says so opens its own
    // section's span, not the one before, in a text that opens with a heading
    type Case = (&'static str, Vec<usize>, Vec<(usize, usize)>);
    let cases: [Case; 2] = [
        (
            "intro\n\\section{Model}\nthe mass $m$\n\\section{Scaled}\nx\nin non-dimensional form\ny\n\\section{Two}\nthe dimensionless time\nz\nthe dimensionless speed\n",
            vec![2, 4, 8],
            vec![(6, 8), (9, usize::MAX)],
        ),
        (
            "\\section{Model}\nthe mass $m$\n\\section{The non-dimensional form}\nx\n\\section{Two}\nthe dimensionless time\nz\nthe dimensionless speed\n",
            vec![1, 3, 5],
            vec![(3, 5), (6, usize::MAX)],
        ),
    ];
    for (text, sections, spans) in cases {
        assert_eq!(section_starts(text), sections, "{text}");
        assert_eq!(dimensionless_spans(text, &sections), spans, "{text}");
    }
    // one mention alone is no span
    assert_eq!(dimensionless_spans("the dimensionless time\n", &[]), vec![]);
}

#[test]
fn a_paragraph_that_calls_its_energy_specific_gives_its_energies_no_unit() {
    // the shape of a set of orbital-mechanics notes: the energies that make the specific
    // orbital energy are per unit mass; a later paragraph's kinetic energy is a plain one
    let text = "The third constant is the specific orbital energy $\\varepsilon$. It is defined \
                using the kinetic energy $\\varepsilon_k$ and potential energy $\\varepsilon_u$.\n\n\
                A ball of mass $m$ has the kinetic energy $E$.";
    let w = read_words(text, &TexSymbols::default(), &vocab());
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("epsilonk"), None);
    assert_eq!(unit("epsilonu"), None);
    assert_eq!(unit("epsilon"), None);
    assert_eq!(unit("E").as_deref(), Some("kg m^2 s^-2"));
    assert_eq!(unit("m").as_deref(), Some("kg"));
}

#[test]
fn a_value_written_with_its_unit_gives_its_symbol_the_unit() {
    use super::written::value_unit;
    let unit =
        |m: &str, after: &str| value_unit(m, after).map(|(s, u)| (s.to_string(), u.to_string()));
    // by hand: GPa is a pressure, kg/m^3 a density, 2 mm a length, 1.5 kN a force
    assert_eq!(
        unit("E^* = 115.4\\,\\mathrm{GPa}", ""),
        Some(("E^*".into(), "kg m^-1 s^-2".into()))
    );
    assert_eq!(
        unit("\\rho \\approx 7.8\\times10^{3}\\,\\text{kg/m^3},", ""),
        Some(("\\rho".into(), "kg m^-3".into()))
    );
    assert_eq!(unit("L = 2", " mm and"), Some(("L".into(), "m".into())));
    assert_eq!(
        unit("F=1.5", "~kN."),
        Some(("F".into(), "kg m s^-2".into()))
    );
    assert_eq!(
        unit("m = 3\\,\\mathrm{g}", ""),
        Some(("m".into(), "kg".into()))
    );
    // no unit apart from the number: a product of symbols, a bare number, a number and words
    assert_eq!(unit("F = 2 m g", ""), None);
    assert_eq!(unit("x = 2\\pi", ""), None);
    assert_eq!(unit("n = 3", " is odd"), None);
    assert_eq!(unit("t = 0", ""), None);
    assert_eq!(unit("a = b", " m"), None);
    // and in a paper's words, with the quote
    let w = read_words(
        "The modulus is $E = \\SI{200}{\\giga\\pascal}$ and the rod is long, $L = 2$ m.",
        &TexSymbols::default(),
        &vocab(),
    );
    assert_eq!(
        w.units.get("L").map(|u| u.unit.to_string()).as_deref(),
        Some("m")
    );
    assert_eq!(w.units["L"].quote, "$L = 2$ m");
}

#[test]
fn written_units_with_prefixes_and_units_outside_si() {
    let u = |t: &str| written_unit(t).map(|u| u.to_string());
    assert_eq!(u("GPa").as_deref(), Some("kg m^-1 s^-2"));
    assert_eq!(u("mm").as_deref(), Some("m"));
    assert_eq!(u("um").as_deref(), Some("m"));
    assert_eq!(u("kN m").as_deref(), Some("kg m^2 s^-2"));
    assert_eq!(u("g/cm^3").as_deref(), Some("kg m^-3"));
    assert_eq!(u("daN").as_deref(), Some("kg m s^-2"));
    assert_eq!(u("min").as_deref(), Some("s"));
    assert_eq!(u("L").as_deref(), None, "one letter is a symbol");
    assert_eq!(u("mL").as_deref(), Some("m^3"));
    // no prefix on a unit outside SI but the gram, the litre, the bar and the electronvolt
    assert_eq!(u("kmin"), None);
    assert_eq!(u("xm"), None);
}

#[test]
fn an_empty_math_span_in_the_prose_names_nothing() {
    for text in [
        "where $ $ is",
        "a $\\,$ b",
        "the mass $,$ of",
        "$$ $$ and $m$ is the mass",
    ] {
        let w = read_words(text, &TexSymbols::default(), &vocab());
        assert!(w.units.len() <= 1, "{text}: {:?}", w.units);
    }
}

#[test]
fn the_entries_of_the_nomencl_package_are_rows_of_a_nomenclature() {
    let text = "\\nomenclature{$p$}{Roll rate [rad/s]}\n\\nomenclature[A]{$m$}{Mass of the rider\\nomunit{kg}}\n\\nomenclature{$V$}{Forward\n speed}\n\\nomenclature{$x$}{Position}";
    let w = read_words(text, &TexSymbols::default(), &vocab());
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("p").as_deref(), Some("s^-1"));
    assert_eq!(unit("m").as_deref(), Some("kg"));
    assert_eq!(unit("V").as_deref(), Some("m s^-1"));
    assert_eq!(unit("x").as_deref(), Some("m"));
    // its lines kept: the speed's entry opens on the third line, the position's on the fifth
    assert_eq!(w.units["V"].line, 3);
    assert_eq!(w.units["x"].line, 5);
}

#[test]
fn the_symbols_of_the_glossaries_package_are_rows_of_a_nomenclature() {
    // the symbol's math in `name` (its unit in `symbol` or `unit`) or in `symbol`, and the
    // `glossaries-extra` form; a term of words (no math) names nothing
    let text = "\\newglossaryentry{sym:m}{name={\\ensuremath{m}}, description={mass of the ball},\n symbol={\\si{\\kilo\\gram}}}\n\\newglossaryentry{k}{name=stiffness, symbol={$k$}, unit={N/m}, description={the spring's stiffness}}\n\\glsxtrnewsymbol[description={contact time}]{tc}{$t_c$}\n\\newglossaryentry{fem}{name=FEM, description={finite element method}}\n\\newglossaryentry{v}{name={$v$}, description={speed}}";
    let w = read_words(text, &TexSymbols::default(), &vocab());
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("m").as_deref(), Some("kg"));
    assert_eq!(unit("k").as_deref(), Some("kg s^-2"));
    assert_eq!(unit("tc").as_deref(), Some("s"));
    assert_eq!(unit("v").as_deref(), Some("m s^-1"));
    // each on its entry's line (the mass's entry takes two)
    assert_eq!(w.units["k"].line, 3);
    assert_eq!(w.units["tc"].line, 4);
    assert_eq!(w.units["v"].line, 6);
}

#[test]
fn a_list_that_says_its_verb_once_names_every_symbol() {
    let w = read_words(
        "where $E^*$ is the effective modulus, $R^*$ the effective radius and $m^*$ the effective mass. Then $x$, the force $F$ and $y$ follow.",
        &TexSymbols::default(),
        &vocab(),
    );
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("Estar").as_deref(), Some("kg m^-1 s^-2"));
    assert_eq!(unit("Rstar").as_deref(), Some("m"));
    assert_eq!(unit("mstar").as_deref(), Some("kg"));
    // a new sentence says no verb for the symbols after it
    assert_eq!(unit("x"), None);
    assert_eq!(unit("y"), None);
}

#[test]
fn a_row_of_a_nomenclature_names_nothing_of_the_next_row() {
    // by hand: T is the temperature; gamma, the ratio of specific heats, gets no kelvin from
    // the row before it
    let w = read_words(
        "\\begin{tabular}{ll}\n$T$ & Fluid temperature\\\\\n$\\gamma$ & Specific heat ratio\\\\\n\\end{tabular}\n",
        &TexSymbols::default(),
        &vocab(),
    );
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("T").as_deref(), Some("K"));
    // (a ratio, or nothing: never a temperature nor a specific heat)
    assert!(
        matches!(unit("gamma").as_deref(), None | Some("1")),
        "{:?}",
        unit("gamma")
    );
}

#[test]
fn a_unit_said_after_in_is_the_symbol_s_unit() {
    // by hand: "measured in K", "given in W/(m K)" (one unit, not W/ and (m K))
    let w = read_words(
        "The temperature $T$ is measured in K and $k$ is given in W/(m K).",
        &TexSymbols::default(),
        &vocab(),
    );
    let unit = |s: &str| w.units.get(s).map(|u| u.unit.to_string());
    assert_eq!(unit("T").as_deref(), Some("K"));
    assert_eq!(unit("k").as_deref(), Some("kg m s^-3 K^-1"));
}

#[test]
fn a_word_takes_its_sense_from_the_words_around_it_as_the_vocabulary_says() {
    // by hand: the amplitude of a force is a force, an amplitude alone a displacement; an
    // array's length counts its elements
    assert_eq!(
        quantity("the amplitude of the applied force").as_deref(),
        Some("force")
    );
    assert_eq!(quantity("the amplitude").as_deref(), Some("length"));
    assert_eq!(
        quantity("the length of the array").as_deref(),
        Some("count")
    );
    assert_eq!(
        quantity("the length of the beam").as_deref(),
        Some("length")
    );
    // the senses are data: a user's file adds a qualifying word
    assert_eq!(quantity("the peak of the applied force"), None);
    let more = Vocabulary::parse("[senses]\nqualifying = [\"peak\"]\n", "v.toml").unwrap();
    let v = vocab().extended(more);
    assert_eq!(
        v.describe("the peak of the applied force")
            .map(|h| h.quantity.name.clone())
            .as_deref(),
        Some("force")
    );
    // a key [senses] does not know is named
    let e = Vocabulary::parse("[senses]\nqualifyng = [\"peak\"]\n", "v.toml").unwrap_err();
    assert!(e.contains("v.toml") && e.contains("senses"), "{e}");
}
