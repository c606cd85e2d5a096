//! Benchmarks of the exact algebra: the Adomian terms a0..a4 of 000_92d54b11128ea1ec.txt with
//! every symbol free (target: under a second), the Galerkin coefficients for (m, n) = (3, 5), and
//! identity (21) up to k = 12.

use criterion::{Criterion, criterion_group, criterion_main};
use impactcheck::algebra::series::{self, SeriesParams, Viscous};
use impactcheck::algebra::{galerkin, identity21};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("algebra");
    g.sample_size(10);
    g.bench_function("series a0..a4 symbolic (2zz)", |b| {
        b.iter(|| series::adomian_terms(black_box(&SeriesParams::symbolic()), 4, Viscous::TwoZZ))
    });
    g.bench_function("series a0..a3 symbolic (2zz)", |b| {
        b.iter(|| series::adomian_terms(black_box(&SeriesParams::symbolic()), 3, Viscous::TwoZZ))
    });
    g.bench_function("galerkin (3,5)", |b| {
        b.iter(|| galerkin::derive(black_box(3), 5))
    });
    g.bench_function("identity (21) k=0..12", |b| {
        b.iter(|| (0..=12).map(identity21::check).all(|r| r.holds))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
