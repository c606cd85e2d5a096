//! impactcheck: checks published impact-mechanics results the way a careful referee would.
//!
//! The data flows one way: paper claim -> exact term ([`algebra`]) -> comparison ([`verify`]) ->
//! report ([`report`]). See README.md for the tour.
//!
//! ```
//! use impactcheck::algebra::expr::parse;
//! use impactcheck::algebra::series::{adomian_terms, compare_parts, SeriesParams, Viscous};
//! // a1 of 000_92d54b11128ea1ec.txt (22), derived with B = d(z^2)/dt, against the t^4 part of
//! // the printed one (the whole printed a1 is `a1_22` in verify/000_cone_plate.toml)
//! let p = SeriesParams::symbolic();
//! let a1 = adomian_terms(&p, 1, Viscous::TwoZZ).remove(1);
//! let printed = parse("-v0^2*a8/12*(1/alpha - 1/gamma)*t^4").unwrap().to_expo("t").unwrap();
//! let parts = compare_parts(&a1, &printed);
//! let t4 = parts.iter().find(|c| c.t_power == 4).unwrap();
//! assert!(t4.agrees);
//! // the other parts of the derived a1 are absent from this printed one
//! assert!(parts.iter().any(|c| !c.agrees));
//! ```

#![deny(clippy::float_cmp)]

pub mod algebra;
pub mod cli;
pub mod integrate;
#[cfg(unix)]
pub mod interrupt;
pub mod models;
pub mod paper;
pub mod perf;
pub mod report;
pub mod rng;
pub mod scene;
pub mod verify;
