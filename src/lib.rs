//! impactcheck: checks published impact-mechanics results the way a careful referee would.
//!
//! The data flows one way: paper claim -> exact term ([`algebra`]) -> comparison ([`verify`]) ->
//! report ([`report`]). See README.md for the tour.

#![deny(clippy::float_cmp)]

pub mod algebra;
pub mod cli;
pub mod report;
pub mod verify;
