//! A paper as read: its files and macros, its displays, the formulas in them, the words around
//! them, the units of its relations, and the audit that judges them.
//!
//! The stages follow the way TeX and LaTeXML read a document (`design/paper_pipeline.md` in
//! the shared notes), each a folder:
//! - [`source`]: the paper's files (`\input` confined to its folder), its macros expanded, its
//!   displays cut into rows and relations, numbered as LaTeX numbers them;
//! - [`formulas`]: LaTeX math into the [`Expr`](crate::algebra::expr::Expr) of the exact
//!   algebra, one reader file per family of constructs, and matrices;
//! - [`words`]: the prose around the displays (mentions, lists, nomenclature) into units, with
//!   the vocabulary of quantity words as data;
//! - [`units`]: the units of every relation inferred from the declared and named ones, and the
//!   conflicts between them;
//! - [`audit`]: the judgement of every relation (`verify audit`) and the claims file to start
//!   from (`verify init`).
//!
//! The room sits above [`algebra`](crate::algebra) (it builds `Expr` and uses `Unit`) and
//! below `verify` (claims read their printed formulas through it): it never imports `verify`,
//! `models`, `scene`, `report` or a front end (tests/architecture.rs).

pub mod audit;
pub mod formulas;
pub mod source;
pub mod units;
pub mod words;

/// Why a file a paper's audit needs (a units file, a vocabulary) could not be used.
#[derive(Debug, thiserror::Error)]
pub enum PaperError {
    /// The file is unreadable or malformed.
    #[error("{path}: {message}")]
    BadFile {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong.
        message: String,
    },
}
