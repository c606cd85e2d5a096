//! impactcheck: checks published impact-mechanics results the way a careful referee would.
//!
//! The data flows one way: paper claim -> exact term ([`algebra`]) -> comparison ([`verify`]) ->
//! report ([`report`]). See README.md for the tour.
//!
//! ```
//! use impactcheck::algebra::series::{adomian_terms, printed_a1, compare_parts, SeriesParams, Viscous};
//! // a1 of 000_92d54b11128ea1ec.txt (22), derived with B = d(z^2)/dt, against the printed one
//! let p = SeriesParams::symbolic();
//! let a1 = adomian_terms(&p, 1, Viscous::TwoZZ).remove(1);
//! let parts = compare_parts(&a1, &printed_a1(&p).unwrap());
//! let t4 = parts.iter().find(|c| c.t_power == 4).unwrap();
//! assert!(t4.agrees);
//! assert!(parts.iter().any(|c| !c.agrees));
//! ```

#![deny(clippy::float_cmp)]

pub mod algebra;
pub mod cli;
pub mod integrate;
#[cfg(unix)]
pub mod interrupt;
pub mod models;
pub mod perf;
pub mod report;
pub mod rng;
pub mod scene;
pub mod verify;
