//! Time per solve of each method on the Hertz impact z'' = -max(z,0)^1.5 from first touch to the
//! end of contact, at rtol = atol = 1e-6, 1e-9, 1e-12. The side-by-side comparison with SciPy is
//! benches/peers/run.sh (one script run, ratios in reports/performance.md).

use criterion::{Criterion, criterion_group, criterion_main};
use impactcheck::integrate::{Method, Options, solve};
use impactcheck::models::hertz::{Hertz, TAU_UNDAMPED};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let model = Hertz {
        mass: 1.0,
        k: 1.0,
        damping: 0.0,
        law: impactcheck::models::hertz::ContactLaw::Hertz,
    };
    let mut g = c.benchmark_group("hertz");
    for method in [Method::Dop853, Method::Dopri5, Method::Radau5] {
        for tol in [1e-6, 1e-9, 1e-12] {
            let o = Options {
                rtol: tol,
                atol: tol,
                method,
                ..Options::default()
            };
            g.bench_function(format!("{} {tol:e}", method.name()), |b| {
                b.iter(|| solve(black_box(&model), 0.0, &[0.0, 1.0], TAU_UNDAMPED, &o))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
