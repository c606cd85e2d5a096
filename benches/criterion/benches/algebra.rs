//! Benchmarks of the exact algebra: the Adomian terms a0..a4 and a0..a8 of
//! 000_92d54b11128ea1ec.txt with every symbol free (targets: under a second, and under two), the
//! Galerkin coefficients for (m, n) = (3, 5), and identity (21) up to k = 12; and the main job's
//! verdicts (every claim of verify/, the power reused: nothing measured).

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
    g.bench_function("series a0..a8 symbolic (2zz)", |b| {
        b.iter(|| series::adomian_terms(black_box(&SeriesParams::symbolic()), 8, Viscous::TwoZZ))
    });
    g.bench_function("galerkin (3,5)", |b| {
        b.iter(|| galerkin::derive(black_box(3), 5))
    });
    // (21)'s right side as printed (verify/000_cone_plate.toml), read and expanded per k
    let rhs = impactcheck::algebra::expr::parse(
        "sum(factorial(k)/factorial(k - i)*(-1)^i/alpha^(i + 1)*t^(k - i), i, 0, k) - factorial(k)*(-1)^k/alpha^(k + 1)*exp(-alpha*t)",
    )
    .expect("parses");
    g.bench_function("identity (21) k=0..12", |b| {
        b.iter(|| {
            (0..=12).all(|k| {
                identity21::printed_at(&rhs, k).is_ok_and(|p| identity21::check(k, &p).holds)
            })
        })
    });
    g.finish();
}

/// Every verdict of the main job (`verify`'s claims, read and validated each time), without the
/// misprints' power, the reports or the audits: the part of `cargo run --release --bin verify`
/// that the exact algebra and the integrators decide.
fn main_job(c: &mut Criterion) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut g = c.benchmark_group("main job");
    g.sample_size(10);
    g.bench_function("every verdict of verify/", |b| {
        b.iter(|| {
            let papers = impactcheck::verify::load_claims(&root.join("verify")).expect("claims");
            impactcheck::verify::run_all(&papers, &root).map(|o| o.len())
        })
    });
    g.finish();
}

criterion_group!(benches, bench, main_job);
criterion_main!(benches);
