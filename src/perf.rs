//! Measurements behind `reports/performance.md` (driven by `benches/peers/peers.py` through
//! `impact bench`): the peer problems for the integrators, the algebra timings, parallel sweeps,
//! the cost of an effect that is off, and scaling with modes and sweep points. Timings are medians
//! of repeated runs on whatever machine runs them; nothing here decides a verdict.

use crate::integrate::workprecision::{WorkPoint, work_precision};
use crate::integrate::{IntegrateError, Method, OdeSystem};
use crate::models::samples::rigid_case;
use serde_json::{Value, json};
use std::time::Instant;

/// The cone on a Kelvin-Voigt half-space in units where $k/m = 1$, $V_0 = 1$:
/// $z'' = -z(z + 2\tau z')$ while in contact (the peer scripts use the same right-hand side).
pub struct ConeKv {
    /// Relaxation time $\eta/E$ in these units.
    pub tau: f64,
}

impl OdeSystem for ConeKv {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let z = y[0].max(0.0);
        dy[0] = y[1];
        dy[1] = -z * (z + 2.0 * self.tau * y[1]);
    }
}

/// The unit Hertz impact $z'' = -\max(z, 0)^{3/2}$, written as the peers write it (the model's
/// `Hertz` adds damping and a division by the mass, which would time the right-hand side rather
/// than the integrator).
pub struct HertzUnit;

impl OdeSystem for HertzUnit {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let z = y[0].max(0.0);
        dy[0] = y[1];
        dy[1] = -z * z.sqrt();
    }
}

/// `tau` of the cone peer problem, its end time (inside the contact) and initial state.
pub const CONE_TAU: f64 = 0.3;
/// End time of the cone peer problem (the contact force is still positive there).
pub const CONE_T_END: f64 = 2.0;
/// rho and sigma of the stiff pendulum peer problem (time scales 1e3 apart).
pub const PENDULUM: (f64, f64) = (0.5, 1e-6);

fn points_json(points: &[WorkPoint]) -> Vec<Value> {
    points
        .iter()
        .map(|p| {
            json!({"method": p.method.name(), "tol": p.tol, "rhs_evals": p.stats.rhs_evals,
                   "steps": p.stats.steps, "rejected": p.stats.rejected,
                   "jacobians": p.stats.jac_evals, "lu": p.stats.lu_decomps,
                   "lu_pairs": p.stats.lu_decomps / 2, "seconds": p.seconds,
                   "error": p.error})
        })
        .collect()
}

/// Work-precision of DOP853, DOPRI5 and Radau5 on one peer problem: `hertz` (to the end of
/// contact, exact end state), `cone` (to t = 2, reference: DOP853 at rtol 1e-14), `pendulum`
/// ((2.15) with sigma = 1e-6 to 90 % of the release, reference: the closed form).
pub fn bench_problem(problem: &str, tols: &[f64], repeats: usize) -> Result<Value, String> {
    let methods = [Method::Dop853, Method::Dopri5, Method::Radau5];
    let e = |e: IntegrateError| e.to_string();
    let (t_end, y0, reference, points): (f64, Vec<f64>, Vec<f64>, Vec<WorkPoint>) = match problem {
        "hertz" => {
            let model = HertzUnit;
            let t = crate::models::hertz::TAU_UNDAMPED;
            let y0 = vec![0.0, 1.0];
            let r = vec![0.0, -1.0];
            let p =
                work_precision(&model, (0.0, &y0, t), &r, &methods, tols, repeats).map_err(e)?;
            (t, y0, r, p)
        }
        "cone" => {
            let sys = ConeKv { tau: CONE_TAU };
            let y0 = vec![0.0, 1.0];
            let o = crate::integrate::Options {
                rtol: 1e-14,
                atol: 1e-16,
                method: Method::Dop853,
                ..Default::default()
            };
            let r = crate::integrate::solve(&sys, 0.0, &y0, CONE_T_END, &o)
                .map_err(e)?
                .y;
            let p = work_precision(&sys, (0.0, &y0, CONE_T_END), &r, &methods, tols, repeats)
                .map_err(e)?;
            (CONE_T_END, y0, r, p)
        }
        "pendulum" => {
            let (rho, sigma) = PENDULUM;
            let sys = crate::models::pendulum_wall::PendulumWall { rho, sigma };
            let cf = crate::models::pendulum_wall::ClosedForm::new(rho, sigma);
            let t = 0.9 * cf.release();
            let y0 = vec![0.0, 0.0, 0.0, 1.0];
            let r = cf.state(t).to_vec();
            let p = work_precision(&sys, (0.0, &y0, t), &r, &methods, tols, repeats).map_err(e)?;
            (t, y0, r, p)
        }
        other => {
            return Err(format!(
                "unknown bench problem `{other}`; allowed: hertz, cone, pendulum, algebra, sweeps, effects, scaling"
            ));
        }
    };
    Ok(
        json!({"problem": problem, "t_end": t_end, "y0": y0, "reference": reference,
              "points": points_json(&points)}),
    )
}

fn median_seconds(repeats: usize, mut f: impl FnMut()) -> f64 {
    let mut ts: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    ts.sort_by(f64::total_cmp);
    ts[ts.len() / 2]
}

/// How many times [`bench_algebra`] derives a0..a`order` for its median: the count asked for up
/// to order 6 (the target is timed as a median), once above (orders 7 and 8 take
/// seconds each).
fn series_repeats(order: usize, repeats: usize) -> usize {
    if order > 6 { 1 } else { repeats }
}

/// The algebra SymPy is compared with: a0..aN (N = 1..8) of 000's series with every symbol free,
/// and the Galerkin coefficients of (16) for (m, n) = (3, 5). Median seconds (of one run for
/// N = 7, 8, which take seconds each).
pub fn bench_algebra(repeats: usize) -> Value {
    use crate::algebra::galerkin;
    use crate::algebra::series::{SeriesParams, Viscous, adomian_terms};
    let series: Vec<Value> = (1..=8)
        .map(|order| {
            let repeats = series_repeats(order, repeats);
            let sec = median_seconds(repeats, || {
                std::hint::black_box(adomian_terms(
                    &SeriesParams::symbolic(),
                    order,
                    Viscous::TwoZZ,
                ));
            });
            json!({"order": order, "seconds": sec, "repeats": repeats})
        })
        .collect();
    let gal = median_seconds(repeats, || {
        std::hint::black_box(galerkin::derive(3, 5).ok());
    });
    let scaling: Vec<Value> = [1u32, 3, 5, 7, 9]
        .iter()
        .map(|&m| {
            let s = median_seconds(repeats.min(5), || {
                std::hint::black_box(galerkin::derive(m, m).ok());
            });
            json!({"m": m, "n": m, "seconds": s})
        })
        .collect();
    json!({"series_symbolic": series, "galerkin_3_5": gal, "galerkin_scaling": scaling,
           "repeats": repeats})
}

fn rigid_one(i: u64) -> bool {
    rigid_case(i).is_ok()
}

fn cone_scene(v0: f64, effects: &str, extra: &str) -> String {
    format!(
        "model = \"cone-plate\"\nviscoelastic_law = \"constant-poisson\"\neffects = [{effects}]\n[impactor]\nmass = 0.05\ntheta_deg = 60.0\nv0 = {v0}\n[material]\nE = 2.0e9\nnu = 0.3\neta = 1.0e6\n{extra}[solve]\nrtol = 1e-8\natol = 1e-14\n"
    )
}

fn cone_model(text: &str) -> Result<crate::models::cone_plate::ConePlate, String> {
    let scene = crate::scene::parse(text, "bench.toml").map_err(|e| e.to_string())?;
    let Some(s) = scene
        .get::<crate::models::cone_plate::ConePlateScene>()
        .cloned()
    else {
        return Err("bench scene is not a cone-plate scene".into());
    };
    crate::models::cone_plate::ConePlate::new(s.params, s.effects, s.variant, s.law)
        .map_err(|e| e.to_string())
}

fn cone_one(sys: &crate::models::cone_plate::ConePlate) -> bool {
    crate::models::cone_plate::run(sys, None, &[], 1e-8, 1e-14, Method::Auto).is_ok()
}

/// Impacts per second on 1 and on all threads (rayon): `n_rigid` seeded random rigid impacts
/// (Poisson, friction) and `n_cone` cone impacts on a Kelvin-Voigt half-space at rtol 1e-8 with
/// impact speeds spread over 0.5..5 m/s.
pub fn bench_sweeps(n_rigid: usize, n_cone: usize) -> Result<Value, String> {
    use rayon::prelude::*;
    let threads = rayon::current_num_threads();
    let cones: Vec<_> = (0..n_cone)
        .map(|i| {
            cone_model(&cone_scene(
                0.5 + 4.5 * i as f64 / n_cone.max(1) as f64,
                "\"viscoelastic\"",
                "",
            ))
        })
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for t in [1, threads] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| e.to_string())?;
        let s = Instant::now();
        let ok = pool.install(|| {
            (0..n_rigid as u64)
                .into_par_iter()
                .filter(|&i| rigid_one(i))
                .count()
        });
        let rigid_s = s.elapsed().as_secs_f64();
        let s = Instant::now();
        let ok_c = pool.install(|| cones.par_iter().filter(|c| cone_one(c)).count());
        let cone_s = s.elapsed().as_secs_f64();
        rows.push(json!({"threads": t,
            "rigid": {"impacts": n_rigid, "solved": ok, "seconds": rigid_s, "per_second": n_rigid as f64 / rigid_s},
            "cone": {"impacts": n_cone, "solved": ok_c, "seconds": cone_s, "per_second": n_cone as f64 / cone_s}}));
    }
    Ok(json!({"threads_available": threads, "runs": rows}))
}

/// The in-process rate of the sweep path's integration: `n` Hertz impacts (m = 0.05 kg,
/// k = 3e8 N/m^1.5, rtol 1e-9, atol 1e-16, v0 from 0.5 to 2 m/s, to the end of contact with the
/// model's three events) on all threads, nothing parsed or written; the floor under
/// `impact sweep` of the same points.
pub fn bench_hertz_sweep(n: usize) -> Result<Value, String> {
    use crate::models::hertz::{ContactLaw, Hertz, run};
    use rayon::prelude::*;
    let model = Hertz {
        mass: 0.05,
        k: 3e8,
        damping: 0.0,
        law: ContactLaw::Hertz,
    };
    let s = Instant::now();
    let ok = (0..n)
        .into_par_iter()
        .filter(|&i| {
            let v0 = 0.5 + 1.5 * i as f64 / (n.max(2) - 1) as f64;
            run(&model, v0, 1e-9, 1e-16, Method::Dop853, None).is_ok_and(|r| r.ended)
        })
        .count();
    let secs = s.elapsed().as_secs_f64();
    Ok(
        json!({"impacts": n, "solved": ok, "seconds": secs, "per_second": n as f64 / secs,
        "threads": rayon::current_num_threads()}),
    )
}

/// The cost of effects that are off: state size and time per solve of the cone alone, of the
/// cone with each further effect named, and of a hand-written two-state cone ODE with the same
/// contact law (the floor: what a model with nothing else would cost).
pub fn bench_effects(repeats: usize) -> Result<Value, String> {
    let plate = "[plate]\na = 0.2\nb = 0.2\nh = 0.002\nrho = 1200.0\nmodes = [[1, 1]]\n[foundation]\nkw = 1.0e6\nkg = 1.0e3\nct = 10.0\n";
    let configs = [
        ("cone alone (viscoelastic)", "\"viscoelastic\"", ""),
        ("+ plate (1 mode)", "\"viscoelastic\", \"plate\"", plate),
        (
            "+ plate + Winkler + Pasternak + damper",
            "\"viscoelastic\", \"plate\", \"winkler\", \"pasternak\", \"damper\"",
            plate,
        ),
    ];
    let mut rows = Vec::new();
    for (name, eff, extra) in configs {
        let sys = cone_model(&cone_scene(2.0, eff, extra))?;
        let dim = sys.state_dim();
        let mut evals = 0;
        let secs = median_seconds(repeats, || {
            if let Ok(r) =
                crate::models::cone_plate::run(&sys, None, &[], 1e-8, 1e-14, Method::Dop853)
            {
                evals = r.stats.rhs_evals;
            }
        });
        rows.push(json!({"config": name, "state_dim": dim, "rhs_evals": evals, "seconds": secs}));
    }
    // the floor: the same cone law as a bare two-state ODE (z, z'), stopped at z = 0
    let alone = cone_model(&cone_scene(2.0, "\"viscoelastic\"", ""))?;
    let (k, tau) = alone
        .kelvin_voigt()
        .ok_or("the cone alone is not Kelvin-Voigt")?;
    struct Bare {
        k_over_m: f64,
        tau: f64,
    }
    impl OdeSystem for Bare {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            let z = y[0].max(0.0);
            dy[0] = y[1];
            dy[1] = -self.k_over_m * z * (z + 2.0 * self.tau * y[1]);
        }
    }
    let bare = Bare {
        k_over_m: k / 0.05,
        tau,
    };
    let unload =
        |_t: f64, y: &[f64]| y[0].max(0.0) * (y[0].max(0.0) + 2.0 * tau * y[1]) + y[0].min(0.0);
    let mut evals = 0;
    let secs = median_seconds(repeats, || {
        let o = crate::integrate::Options {
            rtol: 1e-8,
            atol: 1e-14,
            method: Method::Dop853,
            events: vec![crate::integrate::Event::new(
                "force returns to zero",
                &unload,
                crate::integrate::Direction::Falling,
                true,
            )],
            ..Default::default()
        };
        if let Ok(s) = crate::integrate::solve(&bare, 0.0, &[0.0, 2.0], 1.0, &o) {
            evals = s.stats.rhs_evals;
        }
    });
    rows.push(
        json!({"config": "hand-written 2-state cone ODE (floor)", "state_dim": 2,
                     "rhs_evals": evals, "seconds": secs}),
    );
    Ok(json!({"rows": rows, "repeats": repeats}))
}

/// Scaling: the cone on the full plate with modes (m, n) up to (9, 9) (state size and time per
/// solve), and a sweep's wall time against its number of points.
pub fn bench_scaling(repeats: usize) -> Result<Value, String> {
    use rayon::prelude::*;
    let mut modes_rows = Vec::new();
    for mmax in [1u32, 3, 5, 7, 9] {
        let modes: Vec<String> = (1..=mmax)
            .step_by(2)
            .flat_map(|m| (1..=mmax).step_by(2).map(move |n| format!("[{m}, {n}]")))
            .collect();
        let extra = format!(
            "[plate]\na = 0.2\nb = 0.2\nh = 0.002\nrho = 1200.0\nmodes = [{}]\n[foundation]\nkw = 1.0e6\nkg = 1.0e3\nct = 10.0\n",
            modes.join(", ")
        );
        let sys = cone_model(&cone_scene(
            2.0,
            "\"viscoelastic\", \"plate\", \"winkler\", \"pasternak\", \"damper\"",
            &extra,
        ))?;
        let dim = sys.state_dim();
        let mut evals = 0;
        let secs = median_seconds(repeats, || {
            if let Ok(r) =
                crate::models::cone_plate::run(&sys, None, &[], 1e-8, 1e-14, Method::Auto)
            {
                evals = r.stats.rhs_evals;
            }
        });
        modes_rows.push(
            json!({"max_mode": mmax, "modes": modes.len(), "state_dim": dim,
                               "rhs_evals": evals, "seconds": secs}),
        );
    }
    let mut points_rows = Vec::new();
    for n in [100usize, 1000, 10000] {
        let s = Instant::now();
        let ok = (0..n as u64)
            .into_par_iter()
            .filter(|&i| rigid_one(i))
            .count();
        points_rows.push(json!({"points": n, "solved": ok, "seconds": s.elapsed().as_secs_f64()}));
    }
    Ok(json!({"modes": modes_rows, "sweep_points": points_rows}))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_points_carry_the_counts_the_peer_tables_compare() {
        // the pendulum at 1e-6 against its closed form (an independent solution): Radau5's
        // point must name its steps, Jacobians and LU decompositions, consistently
        let v = bench_problem("pendulum", &[1e-6], 1).expect("bench runs");
        let radau = v["points"]
            .as_array()
            .expect("points")
            .iter()
            .find(|p| p["method"] == "radau5")
            .expect("radau5 point")
            .clone();
        let n = |k: &str| {
            radau[k]
                .as_u64()
                .unwrap_or_else(|| panic!("{k} in {radau}"))
        };
        assert!(n("steps") > 0 && n("jacobians") >= 1, "{radau}");
        // `lu` counts each system, `lu_pairs` the pairs of a real and a complex one (Hairer's
        // NDEC): at least one pair per Jacobian, at most one per attempted step
        assert_eq!(n("lu"), 2 * n("lu_pairs"), "{radau}");
        assert!(n("lu_pairs") >= n("jacobians"), "{radau}");
        assert!(n("lu_pairs") <= n("steps") + n("rejected"), "{radau}");
        assert!(radau["error"].as_f64().expect("error") < 1e-5, "{radau}");
        assert!(bench_problem("nope", &[1e-6], 1).is_err());
    }

    /// Order 6, the order of the one-second target, is a median of the repeats asked
    /// for; orders 7 and 8 are timed once.
    #[test]
    fn the_series_bench_takes_a_median_up_to_order_six() {
        for order in 1..=6 {
            assert_eq!(series_repeats(order, 5), 5, "order {order}");
        }
        assert_eq!(series_repeats(7, 5), 1);
        assert_eq!(series_repeats(8, 5), 1);
    }
}
