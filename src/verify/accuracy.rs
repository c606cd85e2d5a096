//! "What accuracy costs in time": work-precision diagrams for each model, every method, tolerances
//! 1e-3..1e-13, against a reference (a closed form where there is one, else a run at 1e-14).
//!
//! Timings vary from run to run, so none of this enters `summary.json`; the page and its plots
//! are rewritten by every `verify` run.

use crate::integrate::workprecision::{WorkPoint, work_precision};
use crate::integrate::{Method, OdeSystem, Options, solve};
use crate::models::cone_plate::{ConePlate, Effects, Law, Params, Variant};
use crate::models::hertz::{Hertz, TAU_UNDAMPED};
use crate::report::svg::{Scale, Series, plot};

const METHODS: [Method; 3] = [Method::Dop853, Method::Dopri5, Method::Radau5];

fn tolerances() -> Vec<f64> {
    (3..=13).map(|k| 10f64.powi(-k)).collect()
}

struct Problem {
    name: &'static str,
    file: &'static str,
    description: String,
    points: Vec<WorkPoint>,
}

fn run_problem<S: OdeSystem>(
    sys: &S,
    y0: &[f64],
    t_end: f64,
    reference: Option<Vec<f64>>,
    repeats: usize,
) -> Result<Vec<WorkPoint>, crate::integrate::IntegrateError> {
    let reference = match reference {
        Some(r) => r,
        None => {
            let o = Options {
                rtol: 1e-14,
                atol: 1e-20,
                method: Method::Dop853,
                ..Options::default()
            };
            solve(sys, 0.0, y0, t_end, &o)?.y
        }
    };
    work_precision(
        sys,
        (0.0, y0, t_end),
        &reference,
        &METHODS,
        &tolerances(),
        repeats,
    )
}

fn diagram(p: &Problem, x_is_time: bool) -> String {
    let series: Vec<Series> = METHODS
        .iter()
        .map(|m| Series {
            name: m.name(),
            points: p
                .points
                .iter()
                .filter(|w| w.method == *m)
                .map(|w| {
                    let x = if x_is_time {
                        w.seconds
                    } else {
                        w.stats.rhs_evals as f64
                    };
                    (x, w.error.max(1e-17))
                })
                .collect(),
        })
        .collect();
    plot(
        &format!(
            "What accuracy costs: {}, each method at rtol = atol = 1e-3 to 1e-13",
            p.name
        ),
        if x_is_time {
            "time per solve (s)"
        } else {
            "right-hand-side evaluations (a count, dimensionless)"
        },
        "achieved error, relative to max(1, |y|), max norm at the end (dimensionless)",
        Scale::Log,
        Scale::Log,
        &series,
    )
}

/// Renders `accuracy_cost.md` and its plots.
pub fn render(repeats: usize) -> Result<Vec<(String, String)>, crate::integrate::IntegrateError> {
    let hertz = Hertz {
        mass: 1.0,
        k: 1.0,
        damping: 0.0,
        law: crate::models::hertz::ContactLaw::Hertz,
    };
    let mut problems = vec![Problem {
        name: "Hertz impact",
        file: "wp_hertz",
        description: "z'' = -max(z,0)^1.5, z(0) = 0, z'(0) = 1, to the end of contact t = 3.218065459719043; reference: the exact end state (0, -1)".into(),
        points: run_problem(&hertz, &[0.0, 1.0], TAU_UNDAMPED, Some(vec![0.0, -1.0]), repeats)?,
    }];
    let params = Params {
        mass: 0.05,
        theta_deg: 60.0,
        v0: 2.0,
        e: 2.0e9,
        nu: 0.3,
        eta: 1.0e6,
        a: 0.2,
        b: 0.2,
        h: 0.002,
        rho: 1200.0,
        kw: Some(1.0e6),
        kg: Some(1.0e3),
        ct: Some(10.0),
        inplane: Some((0.0, 0.0)),
    };
    let effects = Effects {
        viscoelastic: true,
        plate: true,
        winkler: true,
        pasternak: true,
        damper: true,
        membrane: true,
        relative_indentation: true,
        modes: vec![(1, 1)],
        ..Effects::default()
    };
    if let Ok(cp) = ConePlate::new(params, effects, Variant::Corrected, Law::ConstantPoisson) {
        let y0 = cp.initial_state();
        problems.push(Problem {
            name: "cone-plate (000), Kelvin-Voigt, plate and foundation",
            file: "wp_cone_plate",
            description: format!(
                "scene of issue 4 with viscoelastic_law = \"constant-poisson\", state size {}, to t = 5e-4 s (inside the contact); reference: DOP853 at rtol 1e-14",
                cp.state_dim()
            ),
            points: run_problem(&cp, &y0, 5e-4, None, repeats)?,
        });
    }
    let mut files = Vec::new();
    let mut md = String::from(
        "# What accuracy costs in time\n\nWritten by `verify --timing`. For each model: the achieved error (max-norm at the end \
         point, relative for components above 1) against the time per solve and against the right-hand-side \
         evaluations, for each method at rtol = atol = 1e-3 ... 1e-13 (median of repeated solves on this machine; \
         timings are not part of `summary.json`). Lower-left is better: at a given accuracy, pick the method whose \
         curve is furthest left. Side-by-side ratios against SciPy are in [performance.md](../performance.md).\n\n",
    );
    for p in &problems {
        md.push_str(&format!("## {}\n\n{}.\n\n", p.name, p.description));
        md.push_str("| method | tol | error | RHS evals | steps | rejected | time (us) |\n|---|---|---|---|---|---|---|\n");
        for w in &p.points {
            md.push_str(&format!(
                "| {} | {:.0e} | {:.2e} | {} | {} | {} | {:.1} |\n",
                w.method.name(),
                w.tol,
                w.error,
                w.stats.rhs_evals,
                w.stats.steps,
                w.stats.rejected,
                w.seconds * 1e6
            ));
        }
        // the cheapest method meeting each accuracy
        md.push_str("\nCheapest method by time for each achieved accuracy:\n\n");
        for target in [1e-4, 1e-8, 1e-12] {
            let best = p
                .points
                .iter()
                .filter(|w| w.error <= target)
                .min_by(|a, b| a.seconds.total_cmp(&b.seconds));
            md.push_str(&match best {
                Some(w) => format!(
                    "- error <= {target:.0e}: {} at tol {:.0e} ({:.1} us)\n",
                    w.method.name(),
                    w.tol,
                    w.seconds * 1e6
                ),
                None => format!("- error <= {target:.0e}: no method reached it in this ladder\n"),
            });
        }
        let (ft, fe) = (
            format!("{}_time.svg", p.file),
            format!("{}_evals.svg", p.file),
        );
        md.push_str(&format!(
            "\n![error against time]({ft})\n![error against evaluations]({fe})\n\n"
        ));
        files.push((format!("timing/{ft}"), diagram(p, true)));
        files.push((format!("timing/{fe}"), diagram(p, false)));
    }
    files.push(("timing/accuracy_cost.md".to_string(), md));
    Ok(files)
}
