//! Claims and checks.
