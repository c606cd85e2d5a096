//! `verify`: check every claim, write `reports/`.
fn main() {}
