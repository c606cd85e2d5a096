//! The source of a paper: its files and its displays, before any formula is read.
//!
//! [`files`] assembles a paper across its files (`\input`, `\include`, `\import`, the paper's
//! macros that wrap them) with a map back to each file's lines; [`document`] reads a LaTeX
//! source as LaTeX numbers it (its `\input` files from its folder, comments and verbatim dropped, every display with its number, `\tag` and `\label`);
//! [`macros`] expands the paper's own macros (`\newcommand`, `\def`, `\DeclareMathOperator`)
//! before anything is parsed, [`packages`] those of the packages it loads (`physics`,
//! `commath`); [`display`] cuts a display into rows and each row into the
//! relations the formula reader reads; [`blocks`] is the entry point: a paper's text (a LaTeX
//! source or a displays extract of `%% block N` sections) into its displays and numbers.

pub mod blocks;
pub mod display;
pub mod document;
pub mod files;
pub mod macros;
pub mod packages;
pub mod siunitx;
