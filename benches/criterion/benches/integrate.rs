//! Time per solve of each method on the Hertz impact z'' = -max(z,0)^1.5 from first touch to the
//! end of contact, at rtol = atol = 1e-6, 1e-9, 1e-12; one solve with and without events; the
//! sweep path in process (scene to CSV or JSON rows); Radau5 on the stiff peer problems (the cone
//! on a Kelvin-Voigt half-space and the pendulum on the wall with stiffness ratio 1e-6) at the
//! same three tolerances (its workspace is allocated once per solve, nothing per step:
//! tests/events_bare.rs asserts it). The side-by-side comparison with SciPy is
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
    // one solve with and without events: DOP853 at 1e-9 to the contact time, bare, and with the
    // Hertz model's three events (contact end, largest indentation, peak force)
    let mut g = c.benchmark_group("events");
    let o = Options {
        rtol: 1e-9,
        atol: 1e-9,
        method: Method::Dop853,
        ..Options::default()
    };
    g.bench_function("dop853 1e-9 without events", |b| {
        b.iter(|| solve(black_box(&model), 0.0, &[0.0, 1.0], TAU_UNDAMPED, &o))
    });
    g.bench_function("dop853 1e-9 with three events", |b| {
        b.iter(|| {
            impactcheck::models::hertz::run(
                black_box(&model),
                1.0,
                1e-9,
                1e-9,
                Method::Dop853,
                Some(TAU_UNDAMPED),
            )
        })
    });
    g.finish();
}

/// The sweep path in process: 2000 Hertz impacts (m = 0.05 kg, k = 3e8, rtol 1e-9, atol 1e-16,
/// v0 from 0.5 to 2 m/s) from the scene file to CSV rows, written to a sink.
fn sweep(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("impactcheck-bench-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let scene = dir.join("hertz.toml");
    let _ = std::fs::write(
        &scene,
        "model = \"hertz\"\n[impactor]\nmass = 0.05\nv0 = 1.0\n[contact]\nk = 3e8\n[solve]\nrtol = 1e-9\natol = 1e-16\n",
    );
    // the same impacts with the model written as text (benches/peers/peers.py's HERTZ_ODE)
    let text = dir.join("hertz_ode.toml");
    let _ = std::fs::write(
        &text,
        "model = \"ode\"\n[parameters]\nm = 0.05\nk = 3e8\nv0 = 1.0\n[units]\nt = \"s\"\nm = \"kg\"\nk = \"N/m^1.5\"\nv0 = \"m/s\"\nz = \"m\"\nv = \"m/s\"\n[state]\nz = 0.0\nv = \"v0\"\n[equations]\nz = \"v\"\nv = \"-k*max(z, 0)^(3/2)/m\"\n[[event]]\nname = \"contact-end\"\nwhen = \"z\"\ndirection = \"down\"\naction = \"stop\"\n[[event]]\nname = \"max-indentation\"\nwhen = \"v\"\ndirection = \"down\"\n[[event]]\nname = \"peak-force\"\nwhen = \"k*max(z, 0)^(1/2)*v\"\ndirection = \"down\"\n[solve]\nrtol = 1e-9\natol = 1e-16\nt_end = 1.0\n",
    );
    let sv = impactcheck::cli::parse_vary("impactor.v0=0.5:2:2000", false).expect("vary");
    let sv_text = impactcheck::cli::parse_vary("parameters.v0=0.5:2:2000", false).expect("vary");
    let mut g = c.benchmark_group("sweep");
    g.sample_size(20);
    // the floor: the same impacts integrated, nothing read or written
    g.bench_function("2000 hertz integration alone", |b| {
        b.iter(|| impactcheck::perf::bench_hertz_sweep(black_box(2000)))
    });
    for (name, format) in [
        ("2000 hertz csv", impactcheck::cli::Format::Csv),
        ("2000 hertz json", impactcheck::cli::Format::Json),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| impactcheck::cli::sweep(&scene, &sv, format, false, &mut std::io::sink()))
        });
    }
    g.bench_function("2000 hertz csv, the model as text", |b| {
        b.iter(|| {
            impactcheck::cli::sweep(
                &text,
                &sv_text,
                impactcheck::cli::Format::Csv,
                false,
                &mut std::io::sink(),
            )
        })
    });
    g.finish();
}

fn stiff(c: &mut Criterion) {
    use impactcheck::models::pendulum_wall::{ClosedForm, PendulumWall};
    use impactcheck::perf::{CONE_T_END, CONE_TAU, ConeKv, PENDULUM};
    let (rho, sigma) = PENDULUM;
    let pendulum = PendulumWall { rho, sigma };
    let release = 0.9 * ClosedForm::new(rho, sigma).release();
    let cone = ConeKv { tau: CONE_TAU };
    let mut g = c.benchmark_group("radau5");
    g.sample_size(20);
    for tol in [1e-6, 1e-9, 1e-12] {
        let o = Options {
            rtol: tol,
            atol: tol,
            method: Method::Radau5,
            ..Options::default()
        };
        g.bench_function(format!("cone {tol:e}"), |b| {
            b.iter(|| solve(black_box(&cone), 0.0, &[0.0, 1.0], CONE_T_END, &o))
        });
        g.bench_function(format!("pendulum {tol:e}"), |b| {
            b.iter(|| {
                solve(
                    black_box(&pendulum),
                    0.0,
                    &[0.0, 0.0, 0.0, 1.0],
                    release,
                    &o,
                )
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench, sweep, stiff);
criterion_main!(benches);
