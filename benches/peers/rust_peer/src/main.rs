//! ode_solvers on the peer problems of reports/performance.md (hertz, cone), printed as JSON:
//! per method and tolerance the RHS evaluations, the median time per solve and the error
//! against the reference `impact bench` reports (passed on the command line).
use ode_solvers::{Dop853, Dopri5, OutputType, System, Vector2};
use std::time::Instant;

type State = Vector2<f64>;

struct Problem {
    cone_tau: Option<f64>,
    /// The state after the last accepted step, as solout reports it (with sparse output, the
    /// step's end; the crate's dense output at x_end is what solout reports otherwise).
    last: std::rc::Rc<std::cell::Cell<[f64; 3]>>,
}

impl System<f64, State> for Problem {
    fn system(&self, _t: f64, y: &State, dy: &mut State) {
        let z = y[0].max(0.0);
        dy[0] = y[1];
        dy[1] = match self.cone_tau {
            // the cone on a Kelvin-Voigt half-space: z'' = -z (z + 2 tau z')
            Some(tau) => -z * (z + 2.0 * tau * y[1]),
            // Hertz: z'' = -z^1.5
            None => -z * z.sqrt(),
        };
    }
    fn solout(&mut self, t: f64, y: &State, _dy: &State) -> bool {
        self.last.set([t, y[0], y[1]]);
        false
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let problem = args.get(1).map(String::as_str).unwrap_or("hertz");
    let t_end: f64 = args[2].parse().expect("t_end");
    let reference: Vec<f64> = args[3].split(',').map(|s| s.parse().expect("ref")).collect();
    let repeats: usize = args[4].parse().expect("repeats");
    let tols: Vec<f64> = args[5].split(',').map(|s| s.parse().expect("tol")).collect();
    let cone_tau = (problem == "cone").then_some(0.3);
    let mut points = Vec::new();
    for method in ["dop853", "dopri5"] {
        for &tol in &tols {
            let mut times = Vec::new();
            let (mut evals, mut last) = (0, [0.0; 3]);
            for _ in 0..repeats {
                let y0 = State::new(0.0, 1.0);
                let cell = std::rc::Rc::new(std::cell::Cell::new([0.0; 3]));
                let sys = || Problem {
                    cone_tau,
                    last: cell.clone(),
                };
                let s = Instant::now();
                let (stats, y) = if method == "dop853" {
                    let mut st = Dop853::from_param(
                        sys(), 0.0, t_end, t_end, y0, tol, tol, 0.9, 0.0, 0.333, 6.0, t_end, 0.0,
                        100_000, 1000, OutputType::Sparse,
                    );
                    let stats = st.integrate().expect("integrates");
                    (stats, cell.get())
                } else {
                    let mut st = Dopri5::from_param(
                        sys(), 0.0, t_end, t_end, y0, tol, tol, 0.9, 0.04, 0.2, 10.0, t_end, 0.0,
                        100_000, 1000, OutputType::Sparse,
                    );
                    let stats = st.integrate().expect("integrates");
                    (stats, cell.get())
                };
                times.push(s.elapsed().as_secs_f64());
                evals = stats.num_eval;
                last = y;
            }
            times.sort_by(f64::total_cmp);
            let err = (0..2)
                .map(|i| (last[i + 1] - reference[i]).abs() / reference[i].abs().max(1.0))
                .fold(0.0, f64::max);
            assert!((last[0] - t_end).abs() <= 1e-12 * t_end, "ended at {}", last[0]);
            points.push(serde_json::json!({"method": method, "tol": tol, "rhs_evals": evals,
                "seconds": times[times.len() / 2], "error": err}));
        }
    }
    println!("{}", serde_json::json!({"crate": "ode_solvers 0.6", "problem": problem, "points": points}));
}
