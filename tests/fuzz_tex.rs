//! The LaTeX reader never panics and always ends (issue 51): mangled LaTeX of every kind
//! (random bytes, pieces of displays glued at random, truncated displays, unbalanced braces and
//! environments, macros that expand into themselves, deep nesting, a large file) goes through
//! the whole paper pipeline (the document, its macros and `\input`s, the displays, the audit),
//! which must return, with whatever statuses, and never panic.
//!
//! A run that panics fails the test; one that loops is stopped by the harness's time limit
//! (each case is small, so a case that takes long is a fault too: the large-file case must end
//! within seconds).

use impactcheck::paper::audit::{Units, audit};
#[path = "support/scratch.rs"]
mod scratch;

use impactcheck::paper::source::blocks::{blocks_at, preamble_part, subfiles_main};
use impactcheck::paper::source::document::read_document_with;
use proptest::prelude::*;

/// Pieces papers are made of, and the pieces that break them.
const PIECES: &[&str] = &[
    "\\begin{align}",
    "\\end{align}",
    "\\begin{equation}",
    "\\end{equation}",
    "\\begin{cases}",
    "\\end{cases}",
    "\\begin{eqnarray}",
    "\\end{eqnarray}",
    "\\begin{subequations}",
    "\\end{subequations}",
    "\\begin{array}{cc}",
    "\\end{array}",
    "$$",
    "\\[",
    "\\]",
    "\\\\",
    "\\\\[2mm]",
    "&",
    "&=&",
    "=",
    "<",
    "\\le",
    "\\approx",
    "\\propto",
    "\\sim",
    "\\pm",
    "\\mp",
    "+",
    "-",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    "^",
    "_",
    "\\frac",
    "\\frac12",
    "\\sqrt",
    "\\left(",
    "\\right)",
    "\\left|",
    "\\right.",
    "\\|",
    "|",
    "\\langle",
    "\\rangle",
    "\\lVert",
    "\\rVert",
    "\\vert",
    "x",
    "y",
    "t",
    "d",
    "\\mathrm{d}",
    "{\\rm d}",
    "\\partial",
    "\\partial^2",
    "\\partial_t",
    "\\Delta",
    "\\delta",
    "\\dot{x}",
    "\\ddot{\\vec{p}}",
    "\\sum_{i=1}^{n}",
    "\\sum_{n=1,3,\\ldots}",
    "\\prod",
    "\\max_i",
    "\\min",
    "\\lim_{k \\to \\infty}",
    "\\infty",
    "\\ldots",
    "\\cdots",
    "\\int_0^1",
    "\\iint",
    "\\int_V",
    "E^{*2}",
    "v_{j+1}",
    "x^{(k)}",
    "\\mathcal{L}",
    "\\text{if}",
    "\\quad",
    "\\Rightarrow",
    "\\newcommand{\\a}{\\a x}",
    "\\newcommand{\\b}[2]{#1+#2}",
    "\\b",
    "\\def\\c#1{#1#1}",
    "\\c",
    "\\renewcommand",
    "\\DeclareMathOperator{\\op}{op}",
    "\\op",
    "#1",
    "#",
    "\\input{x}",
    "\\input{../../etc/passwd}",
    "\\include{/abs}",
    "\\label{a}",
    "\\tag{1}",
    "\\nonumber",
    "\\notag",
    "%",
    "\\%",
    "\n",
    " ",
    "\u{00e9}",
    "\u{221e}",
    "\u{1F600}",
    "\\",
    "\\{",
    "\\}",
    ":=",
    ",",
    ";",
    ".",
    "'",
    "\\prime",
    "\\section{A}",
    "\\numberwithin{equation}{section}",
];

/// The pipeline on `source`: displays (with a loader that reads nothing), then the audit.
fn run(source: &str) {
    let doc = read_document_with(source, &|name| Err(format!("no {name}")));
    let _ = doc.numbers.len();
    let dir = std::env::temp_dir();
    let (blocks, doc) = blocks_at(source, Some(&dir), "\\newcommand{\\p}{\\p}");
    let a = audit(&blocks, doc.as_ref(), &Units::default());
    for r in &a.relations {
        assert!(!r.status.is_empty());
    }
}

/// The pipeline on a paper of several files held in memory (`a`..`d`), `main` the first.
fn run_files(files: &[String]) {
    let load = |name: &str| {
        let key = name.trim_end_matches(".tex").trim_start_matches("./");
        ["a", "b", "c", "d"]
            .iter()
            .position(|n| *n == key)
            .and_then(|k| files.get(k + 1).cloned())
            .ok_or_else(|| format!("no {name}"))
    };
    let doc = read_document_with(&files[0], &load);
    let _ = (doc.numbers.len(), doc.place(doc.text.lines().count() + 3));
    let a = audit(&doc_blocks(&doc), Some(&doc), &Units::default());
    for r in &a.relations {
        assert!(!r.status.is_empty());
    }
}

/// How a file of [`main_files_on_disk`] opens: a `subfiles` chapter of another file (or of
/// itself, of a missing one, of a path out of the folder), a main file, or nothing.
const HEADS: &[&str] = &[
    "\\documentclass[a.tex]{subfiles}\n\\begin{document}\n",
    "\\documentclass[b]{subfiles}\n\\begin{document}\n",
    "\\documentclass[../a.tex]{subfiles}\n\\begin{document}\n",
    "\\documentclass[/etc/passwd]{subfiles}\n",
    "\\documentclass[gone]{subfiles}\n",
    "\\documentclass{article}\n\\newcommand{\\q}{q}\n\\begin{document}\n",
    "\\begin{document}\n",
    "",
];

/// Files `a`..`d` written to a folder of their own, each opened by one of [`HEADS`]: each read
/// as a `subfiles` chapter with its main file's preamble and given to another as a preamble.
fn main_files_on_disk(files: &[String], heads: &[usize]) {
    let dir = scratch::Scratch::new("fuzz-main-files");
    let names = ["a", "b", "c", "d"];
    for (k, name) in names.iter().enumerate() {
        let text = format!("{}{}", HEADS[heads[k]], files[k]);
        std::fs::write(dir.join(format!("{name}.tex")), text).unwrap();
    }
    for name in names {
        let path = dir.join(format!("{name}.tex"));
        let text = std::fs::read_to_string(&path).unwrap();
        if let Some(main) = subfiles_main(&text, &path) {
            assert!(
                main.starts_with(dir.parent().unwrap()),
                "{}",
                main.display()
            );
            let main_text = std::fs::read_to_string(&main).unwrap();
            let (pre, _) = preamble_part(&main_text, &main);
            let _ = blocks_at(&text, Some(&dir), &pre);
        }
        let (pre, _) = preamble_part(&text, &path);
        let _ = blocks_at(&files[0], Some(&dir), &pre);
    }
}

/// A document's displays as the audit takes them.
fn doc_blocks(
    doc: &impactcheck::paper::source::document::Document,
) -> Vec<(Option<String>, String)> {
    doc.displays
        .iter()
        .map(|d| (d.after.clone(), d.latex.clone()))
        .collect()
}

/// The commands that bring in another file of the paper, each naming one of `a`..`d`.
const INPUTS: &[&str] = &[
    "\\input{a}",
    "\\input{b}",
    "\\input c ",
    "\\include{d}",
    "\\subfile{a}",
    "\\import{./}{b}",
    "\\subimport{}{c}",
    "\\newcommand{\\inc}[1]{\\input{#1}}",
    "\\inc{d}",
    "\\input{a}\\input{a}",
];

fn file_body() -> impl Strategy<Value = String> {
    prop::collection::vec(
        prop_oneof![prop::sample::select(PIECES), prop::sample::select(INPUTS)],
        0..30,
    )
    .prop_map(|v| v.concat())
}

fn glued() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(PIECES), 0..60).prop_map(|v| v.concat())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn pieces_glued_at_random(body in glued()) {
        run(&body);
        run(&format!("\\begin{{align}}{body}\\end{{align}}"));
        run(&format!("$${body}$$"));
    }

    #[test]
    fn papers_of_several_files_input_at_random(files in prop::collection::vec(file_body(), 5)) {
        // cycles, files that input themselves, inputs twice over: no panic, no hang
        run_files(&files);
    }

    #[test]
    fn chapters_read_with_their_main_files_preamble(files in prop::collection::vec(file_body(), 4),
                                                    heads in prop::collection::vec(0usize..HEADS.len(), 4)) {
        // a chapter whose `subfiles` main is itself, another chapter or missing; a preamble given
        // by a main file that inputs the chapter back: no panic, no hang
        main_files_on_disk(&files, &heads);
    }

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        run(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn a_display_cut_anywhere(cut in 0usize..400) {
        let paper = "\\newcommand{\\pd}[2]{\\frac{\\partial #1}{\\partial #2}}\n\
            \\begin{align}\ny &= a + b \\nonumber \\\\\n &\\quad - \\pd{w}{t} \\label{e} \\\\\n\
            F &= \\begin{cases} k\\delta & \\delta > 0 \\\\ 0 & \\text{otherwise} \\end{cases}\n\
            \\end{align}\n$$ \\| F_t \\| \\le \\mu N , \\quad \\sum_{i=1}^{\\infty} a_i = \\max_j b_j $$";
        let cut = paper.char_indices().map(|(i, _)| i).nth(cut).unwrap_or(paper.len());
        run(&paper[..cut]);
        run(&paper[cut..]);
    }
}

#[test]
fn files_that_input_themselves_and_each_other_end_quickly() {
    // each file inputs the next twice and itself: without a stop, 2^depth copies
    let twice = |next: &str, me: &str| {
        format!("\\input{{{next}}}\\input{{{next}}}\\input{{{me}}}\n$$ x_{me} = y $$\n")
    };
    let files = vec![
        twice("a", "main"),
        twice("b", "a"),
        twice("c", "b"),
        twice("d", "c"),
        twice("a", "d"),
    ];
    let started = std::time::Instant::now();
    run_files(&files);
    assert!(started.elapsed().as_secs() < 30, "{:?}", started.elapsed());
}

#[test]
fn deep_nesting_and_a_large_file_end() {
    // 5,000 open braces, parentheses and \left( in a display: refused by the nesting limit
    for open in ["{", "(", "\\left(", "\\frac{", "\\sqrt{", "|", "\\|"] {
        run(&format!("$$ x = {} $$", open.repeat(5000)));
    }
    // a macro that doubles itself: stopped by the expansion limits, not the memory
    run("\\def\\a{\\a\\a}\n$$ \\a = 1 $$");
    run(
        "\\newcommand{\\b}[1]{#1#1#1#1}\n$$ x = \\b{\\b{\\b{\\b{\\b{\\b{\\b{\\b{\\b{\\b{y}}}}}}}}}} $$",
    );
    // 4,000 displays of a real relation: read in seconds
    let big: String = (0..4000)
        .map(|k| {
            format!("\\begin{{equation}} E_{{{k}}} = \\frac{{1}}{{2}} m v^2 \\end{{equation}}\n")
        })
        .collect();
    let started = std::time::Instant::now();
    run(&big);
    assert!(started.elapsed().as_secs() < 60, "{:?}", started.elapsed());
}
