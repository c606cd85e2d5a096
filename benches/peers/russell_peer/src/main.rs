//! russell_ode's Radau5 on the stiff peer problems of reports/performance.md (cone, pendulum),
//! printed as JSON: per tolerance the counts (RHS evaluations, steps, Jacobians, LU
//! factorisations), the median time per solve (solver built and run, as `impact bench` times
//! its own) and the error against the reference `impact bench` reports.
//!
//! Tolerances: impactcheck's Radau5 uses rtol = atol = tol as its internal tolerance; russell
//! maps its input as Hairer's RADAU5 does (`0.1 rtol^(2/3)`), so it is given `(10 tol)^(3/2)`,
//! which makes the two internal tolerances equal. Where that input is below the smallest russell
//! accepts (10 machine epsilons; tol = 1e-12 needs 3.2e-17), it gets the smallest it accepts and
//! the output says so (`internal_tol`): it then solves to a looser tolerance than impactcheck.
use russell_lab::{StrError, Vector};
use russell_ode::prelude::*;
use russell_sparse::{CooMatrix, Sym};
use serde_json::json;
use std::time::Instant;

const CONE_TAU: f64 = 0.3;
const RHO: f64 = 0.5;
const SIGMA: f64 = 1e-6;

fn system(problem: &str) -> System<'static, NoArgs> {
    match problem {
        "cone" => System::new(2, |f: &mut Vector, _x, y: &Vector, _a: &mut NoArgs| {
            let z = y[0].max(0.0);
            f[0] = y[1];
            f[1] = -z * (z + 2.0 * CONE_TAU * y[1]);
            Ok(())
        }),
        _ => {
            let r2 = 1.0 / (RHO * RHO);
            let mut s = System::new(4, move |f: &mut Vector, _x, y: &Vector, _a: &mut NoArgs| {
                let (eo, ec) = (y[0], y[1]);
                f[0] = y[2];
                f[1] = y[3];
                f[2] = -eo * (1.0 + r2) - SIGMA * ec * (1.0 - r2);
                f[3] = -eo * (1.0 - r2) - SIGMA * ec * (1.0 + r2);
                Ok(())
            });
            // the analytic (constant) Jacobian, as impactcheck's pendulum model provides
            s.set_jacobian(
                Some(6),
                Sym::No,
                move |jj: &mut CooMatrix, m: f64, _x, _y: &Vector, _a: &mut NoArgs| {
                    jj.reset();
                    jj.put(0, 2, m)?;
                    jj.put(1, 3, m)?;
                    jj.put(2, 0, -m * (1.0 + r2))?;
                    jj.put(2, 1, -m * SIGMA * (1.0 - r2))?;
                    jj.put(3, 0, -m * (1.0 - r2))?;
                    jj.put(3, 1, -m * SIGMA * (1.0 + r2))?;
                    Ok(())
                },
            )
            .expect("jacobian");
            s
        }
    }
}

fn main() -> Result<(), StrError> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 7 {
        return Err("usage: russell_peer cone|pendulum T_END Y0 REF REPEATS TOLS (comma lists)");
    }
    let problem = args[1].as_str();
    let t_end: f64 = args[2].parse().map_err(|_| "T_END")?;
    let list = |s: &str| -> Vec<f64> { s.split(',').map(|v| v.parse().expect("number")).collect() };
    let (y0, reference) = (list(&args[3]), list(&args[4]));
    let repeats: usize = args[5].parse().map_err(|_| "REPEATS")?;
    let tols = list(&args[6]);
    let mut points = Vec::new();
    for &tol in &tols {
        let wanted = (10.0 * tol).powf(1.5);
        let given = wanted.max(10.0 * f64::EPSILON * 1.0001);
        let internal = 0.1 * given.powf(2.0 / 3.0);
        let mut times = Vec::with_capacity(repeats);
        let mut last = None;
        for _ in 0..repeats {
            let start = Instant::now();
            let mut params = Params::new(Method::Radau5);
            params.set_tolerances(given, given, None)?;
            params.newton.use_numerical_jacobian = problem == "cone";
            // one thread: the two factorisations of a 2x2 or 4x4 system in parallel threads
            // would measure thread start-up, not the method
            params.radau5.concurrent = false;
            params.step.n_step_max = 1_000_000;
            let mut solver = OdeSolver::new(params, system(problem))?;
            let mut y = Vector::from(&y0);
            solver.solve(&mut y, 0.0, t_end, None, &mut 0, None)?;
            times.push(start.elapsed().as_secs_f64());
            last = Some((y, solver.stats().clone()));
        }
        times.sort_by(f64::total_cmp);
        let (y, st) = last.ok_or("no repeats")?;
        let error = (0..reference.len())
            .map(|i| (y[i] - reference[i]).abs() / reference[i].abs().max(1.0))
            .fold(0.0, f64::max);
        points.push(json!({
            "method": "radau5", "tol": tol, "input_tol": given, "internal_tol": internal,
            "rhs_evals": st.n_function, "steps": st.n_steps, "accepted": st.n_accepted,
            "rejected": st.n_rejected, "jacobians": st.n_jacobian, "lu": st.n_factor,
            "seconds": times[times.len() / 2], "error": error,
        }));
    }
    println!("{}", json!({ "problem": problem, "peer": "russell_ode Radau5", "points": points }));
    Ok(())
}
