//! Markdown writers.
