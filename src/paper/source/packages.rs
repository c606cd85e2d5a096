//! The macros of the packages papers load for their math (issue 66): `physics`, `commath`,
//! `esdiff`, `derivative`, `cancel` and the like define `\dv{f}{x}`, `\od{f}{x}`, `\abs{x}`,
//! `\norm{v}` and others that a paper then uses as if they were LaTeX's own. A paper that loads
//! one of them (`\usepackage{physics}`, or in a list of packages) has their definitions made
//! first, as macros of the paper's own in the forms the formula reader takes; a definition of
//! the paper's own with the same name replaces the package's, as in LaTeX.
//!
//! Written here as data, not read from the packages: their sources are TeX programs (`xparse`
//! argument specifications, delimiters chosen at run time) that only a TeX engine runs; what a
//! referee needs is what each command means in a formula.

/// LaTeX's and amsmath's commands that are spellings of what the reader knows (`\hdots` of
/// `\ldots`, `\cfrac` of `\frac`, `\underset{x}{\min}` of `\min_{x}`, `\overset{!}{=}` of `=`),
/// or only lay out the page (`\noindent`, `\small`): every paper has them.
const LATEX: &str = r"\newcommand{\underset}[2]{#2_{#1}}
\newcommand{\overset}[2]{#2}
\newcommand{\stackrel}[2]{#2}
\newcommand{\substack}[1]{#1}
\newcommand{\hdots}{\ldots}
\newcommand{\triangledown}{\nabla}
\newcommand{\cfrac}[2]{\frac{#1}{#2}}
\newcommand{\cdotp}{\cdot}
\newcommand{\coloneqq}{=}
\newcommand{\coloneq}{=}
\newcommand{\eqqcolon}{=}
\newcommand{\Vec}[1]{\vec{#1}}
\newcommand{\Bar}[1]{\bar{#1}}
\newcommand{\Dot}[1]{\dot{#1}}
\newcommand{\Ddot}[1]{\ddot{#1}}
\newcommand{\Hat}[1]{\hat{#1}}
\newcommand{\Tilde}[1]{\tilde{#1}}
\newcommand{\hbox}[1]{\text{#1}}
\newcommand{\hspace}[1]{\,}
\newcommand{\vspace}[1]{}
\newcommand{\space}{ }
\newcommand{\noindent}{}
\newcommand{\tiny}{}
\newcommand{\scriptsize}{}
\newcommand{\footnotesize}{}
\newcommand{\small}{}
\newcommand{\normalsize}{}
\newcommand{\large}{}
\newcommand{\Large}{}
\newcommand{\LARGE}{}
\newcommand{\huge}{}
\newcommand{\Huge}{}
\newcommand{\blacksquare}{}";

/// The Greek letters of `textgreek` (`\texttau`) and `upgreek` (`\uptau`, upright): each the
/// letter of the formula reader (`\tau`).
pub(super) const GREEK: &[&str] = &[
    "alpha",
    "pi",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "zeta",
    "eta",
    "theta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "chi",
    "psi",
    "omega",
    "varepsilon",
    "vartheta",
    "varphi",
    "varrho",
    "varsigma",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Pi",
    "Sigma",
    "Upsilon",
    "Phi",
    "Psi",
    "Omega",
];

/// Each package with the definitions it brings (LaTeX, as a paper's preamble would hold them).
const PACKAGES: &[(&str, &str)] = &[
    (
        "physics",
        r"\newcommand{\dv}[3][]{\frac{\mathrm{d}^{#1} #2}{\mathrm{d} #3^{#1}}}
\newcommand{\pdv}[3][]{\frac{\partial^{#1} #2}{\partial #3^{#1}}}
\newcommand{\dd}{\mathrm{d}}
\newcommand{\abs}[1]{\left| #1 \right|}
\newcommand{\norm}[1]{\left| #1 \right|}
\newcommand{\vb}[1]{\mathbf{#1}}
\newcommand{\va}[1]{\vec{#1}}
\newcommand{\vu}[1]{\hat{\mathbf{#1}}}
\newcommand{\vdot}{\cdot}
\newcommand{\cross}{\times}
\newcommand{\cp}{\times}
\newcommand{\grad}{\nabla}
\newcommand{\curl}{\nabla\times}
\newcommand{\laplacian}{\nabla^{2}}
\newcommand{\innerproduct}[2]{\left( #1 \cdot #2 \right)}
\newcommand{\ip}[2]{\left( #1 \cdot #2 \right)}
\newcommand{\tr}{\operatorname{tr}}
\newcommand{\Tr}{\operatorname{tr}}
\newcommand{\order}[1]{O\left( #1 \right)}",
    ),
    (
        "commath",
        r"\newcommand{\od}[3][]{\frac{\mathrm{d}^{#1} #2}{\mathrm{d} #3^{#1}}}
\newcommand{\pd}[3][]{\frac{\partial^{#1} #2}{\partial #3^{#1}}}
\newcommand{\dif}{\mathrm{d}}
\newcommand{\Dif}{\Delta}
\newcommand{\abs}[1]{\left| #1 \right|}
\newcommand{\norm}[1]{\left| #1 \right|}
\newcommand{\del}[1]{\left( #1 \right)}
\newcommand{\sbr}[1]{\left[ #1 \right]}",
    ),
    (
        "esdiff",
        r"\newcommand{\diff}[3][]{\frac{\mathrm{d}^{#1} #2}{\mathrm{d} #3^{#1}}}
\newcommand{\diffp}[3][]{\frac{\partial^{#1} #2}{\partial #3^{#1}}}",
    ),
    (
        "derivative",
        r"\newcommand{\odv}[3][]{\frac{\mathrm{d}^{#1} #2}{\mathrm{d} #3^{#1}}}
\newcommand{\pdv}[3][]{\frac{\partial^{#1} #2}{\partial #3^{#1}}}",
    ),
    // a cancelled term is the term (its value, as printed, is what the paper says is zero)
    (
        "cancel",
        r"\newcommand{\cancel}[1]{#1}
\newcommand{\bcancel}[1]{#1}
\newcommand{\xcancel}[1]{#1}
\newcommand{\cancelto}[2]{#2}",
    ),
];

/// The packages `text` loads (`\usepackage[opts]{a, b}`, `\RequirePackage{c}`), in order.
fn loaded(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for cmd in ["\\usepackage", "\\RequirePackage"] {
        let mut from = 0;
        while let Some(k) = text[from..].find(cmd) {
            let mut at = from + k + cmd.len();
            from = at;
            let rest = &text[at..];
            let trimmed = rest.trim_start();
            if trimmed.starts_with('[') {
                let Some(close) = trimmed.find(']') else {
                    continue;
                };
                at += rest.len() - trimmed.len() + close + 1;
            }
            if let Some((names, _)) = super::files::braced(text, at) {
                out.extend(names.split(',').map(|n| n.trim().to_string()));
            }
        }
    }
    out
}

/// LaTeX's own spellings, then the definitions of the packages `text` loads that this module
/// knows, one package after another.
pub fn preamble_of(text: &str) -> String {
    let used = loaded(text);
    let mut out = format!("{LATEX}\n");
    for (name, defs) in PACKAGES {
        if used.iter().any(|u| u == name) {
            out.push_str(defs);
            out.push('\n');
        }
    }
    for (package, prefix) in [("textgreek", "text"), ("upgreek", "up")] {
        if used.iter().any(|u| u == package) {
            for g in GREEK {
                out.push_str(&format!("\\newcommand{{\\{prefix}{g}}}{{\\{g}}}\n"));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paper::source::macros::expand_with;

    fn expanded(src: &str) -> String {
        let pre = preamble_of(src);
        expand_with(src, &pre).expect("expands").0
    }

    #[test]
    fn greek_letters_of_textgreek_and_upgreek_are_the_letters() {
        let with = expanded("\\usepackage{textgreek,upgreek}\n$\\texttau = \\uppi \\upTheta$");
        assert!(with.contains("$\\tau = \\pi \\Theta$"), "{with}");
        let without = expanded("$\\texttau$");
        assert!(without.contains("\\texttau"), "{without}");
        // amssymb's end-of-proof box, used as a row marker, is nothing of the formula
        assert!(expanded("$\\blacksquare\\, a = b$").contains("$\\, a = b$"));
    }

    #[test]
    fn a_package_s_commands_expand_only_where_it_is_loaded() {
        let use_of = "$\\dv{x}{t} + \\pdv[2]{u}{x}$";
        // by hand: physics' derivatives are LaTeX's fractions
        let with = expanded(&format!(
            "\\usepackage[arrowdel]{{amsmath, physics}}\n{use_of}"
        ));
        assert!(
            with.contains("\\frac{\\mathrm{d}^{} x}{\\mathrm{d} t^{}}"),
            "{with}"
        );
        assert!(
            with.contains("\\frac{\\partial^{2} u}{\\partial x^{2}}"),
            "{with}"
        );
        // without the package the commands stay (and the reader names them)
        let without = expanded(&format!("\\usepackage{{amsmath}}\n{use_of}"));
        assert!(without.contains("\\dv{x}{t}"), "{without}");
        // LaTeX's own spellings everywhere: `\underset{x}{\min}` is `\min_{x}`
        let base = expanded("$\\underset{x \\in D}{\\min} f \\overset{!}{=} 0 \\small$");
        assert_eq!(base.trim(), "$\\min_{x \\in D} f = 0 $");
        // a definition of the paper's own wins
        let own = expanded("\\usepackage{commath}\n\\newcommand{\\pd}{\\partial}\n$\\pd x$");
        assert!(own.trim_end().ends_with("$\\partial x$"), "{own}");
    }

    #[test]
    fn every_package_s_definitions_are_read_as_definitions() {
        // each table's text holds only definitions: expanded alone it leaves no text
        for (name, defs) in PACKAGES.iter().chain([&("latex", LATEX)]) {
            let (rest, names, problems) = expand_with(defs, "").expect("expands");
            assert!(rest.trim().is_empty(), "{name}: {rest:?}");
            assert!(problems.is_empty(), "{name}: {problems:?}");
            assert_eq!(
                names.len(),
                defs.matches("\\newcommand").count(),
                "{name}: {names:?}"
            );
        }
    }
}
