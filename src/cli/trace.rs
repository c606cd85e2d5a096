//! The path of a run for `impact run --trace FILE` and Python's `run` (issue 55): which models
//! record one, the traced run, and the path written as CSV (JSON is the [`Trace`]'s serde form).

use super::{Format, RunError, Value, csv_quote, render_run};

/// What `--trace FILE` writes, by the file's extension: `.json` or `.csv`.
pub(super) fn trace_kind(file: &std::path::Path) -> Result<Format, RunError> {
    match file.extension().and_then(|e| e.to_str()) {
        Some("json") => Ok(Format::Json),
        Some("csv") => Ok(Format::Csv),
        _ => Err(RunError::BadArgument {
            arg: "--trace".into(),
            message: format!(
                "{}: the trace is written as JSON (a file ending .json) or CSV (.csv)",
                file.display()
            ),
        }),
    }
}

pub use crate::models::trace::Trace;

/// Runs a validated scene with its path recorded ([`Trace`]): the outcome (the same as
/// [`run_validated`]'s, to the bit) and the path; an error for a model that integrates none.
pub fn run_traced(scene: &crate::scene::Scene) -> Result<(Value, Trace), RunError> {
    let (v, tr) = scene.run_traced()?;
    let tr = tr.map_err(|why| RunError::BadArgument {
        arg: "--trace".into(),
        message: format!(
            "{} records no path for this scene: {why}; the models that record one: {}",
            scene.model(),
            TRACED.join(", ")
        ),
    })?;
    Ok((v, tr))
}

/// `impact run SCENE` with its path recorded: the outcome as [`run_scene`] prints it (the same
/// to the bit) and the path, or why it has none.
pub fn run_scene_traced(
    path: &std::path::Path,
    format: Format,
) -> Result<(String, crate::models::trace::Traced), RunError> {
    let (v, tr) = crate::scene::load(path)?.run_traced()?;
    Ok((render_run(&v, format), tr))
}

/// The models whose runs record a path.
pub const TRACED: &[&str] = &[
    "hertz",
    "cone-plate",
    "ode",
    "pendulum-wall",
    "rigid-impact",
    "balls-wall",
];

/// A path as CSV: a heading row (`t (s),z (m),...,event`), then one row per accepted step and
/// one per event, in the order of the variable (an event after a step at the same time); the
/// `event` column names the event, empty on a step. Numbers are written as JSON writes them
/// (shortest round trip), so they read back to the bit.
pub fn trace_csv(tr: &Trace) -> String {
    let mut out = std::iter::once(tr.variable.heading())
        .chain(tr.states.iter().map(crate::models::trace::Column::heading))
        .chain(std::iter::once("event".to_string()))
        .map(|h| csv_quote(&h))
        .collect::<Vec<_>>()
        .join(",");
    out.push('\n');
    let row = |out: &mut String, at: f64, state: &mut dyn Iterator<Item = f64>, name: &str| {
        out.push_str(&Value::from(at).to_string());
        for v in state {
            out.push(',');
            out.push_str(&Value::from(v).to_string());
        }
        out.push(',');
        out.push_str(&csv_quote(name));
        out.push('\n');
    };
    let mut events = tr.events.iter().peekable();
    for (i, at) in tr.variable.values.iter().enumerate() {
        while let Some(e) = events.next_if(|e| e.at < *at) {
            row(&mut out, e.at, &mut e.state.iter().copied(), &e.name);
        }
        row(
            &mut out,
            *at,
            &mut tr.states.iter().map(|c| c.values[i]),
            "",
        );
    }
    for e in events {
        row(&mut out, e.at, &mut e.state.iter().copied(), &e.name);
    }
    out
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // equal to the bit is what these tests ask
mod tests {
    use super::*;

    /// The expected text is written out by hand from the steps and events put in.
    #[test]
    fn csv_puts_events_among_steps_by_time_and_quotes_headings() {
        let mut t = Trace::new(("t", "s"), &[("w(a/2, b/2)", "m"), ("phase", "1")]);
        t.extend(&[
            (0.0, vec![0.0, 1.0]),
            (0.5, vec![0.25, 2.0]),
            (1.0, vec![0.1, 3.0]),
        ]);
        t.event("max, z", 0.25, &[0.3, 1.5]);
        t.event("end", 1.0, &[0.1, 3.0]);
        t.event("after", 2.0, &[f64::NAN, 4.0]);
        let expected = "t (s),\"w(a/2, b/2) (m)\",phase,event\n\
                        0.0,0.0,1.0,\n\
                        0.25,0.3,1.5,\"max, z\"\n\
                        0.5,0.25,2.0,\n\
                        1.0,0.1,3.0,\n\
                        1.0,0.1,3.0,end\n\
                        2.0,null,4.0,after\n";
        assert_eq!(trace_csv(&t), expected);
    }

    /// Every example scene: a path for exactly the models [`TRACED`] names, and the traced
    /// run's outcome equal to the plain run's (the recording changes nothing).
    #[test]
    fn the_traced_models_record_a_path_and_the_same_outcome() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut traced_seen = std::collections::BTreeSet::new();
        for entry in std::fs::read_dir(&dir).expect("scenes/") {
            let path = entry.expect("entry").path();
            let scene = crate::scene::load(&path).expect("an example scene loads");
            let traced = run_traced(&scene);
            let name = scene.model();
            let plain = match scene.run() {
                Ok((v, _)) => v,
                Err(e) => {
                    // a scene that shows a failure fails the same way traced
                    let t = traced.expect_err("fails traced too").to_string();
                    assert!(TRACED.contains(&name) && t == e.to_string(), "{t} vs {e}");
                    continue;
                }
            };
            match traced {
                Ok((v, tr)) => {
                    assert!(TRACED.contains(&name), "{name} is not listed in TRACED");
                    traced_seen.insert(name);
                    assert_eq!(v, plain, "{}", path.display());
                    assert!(tr.variable.values.len() >= 2, "{}", path.display());
                    let n = tr.variable.values.len();
                    assert!(tr.states.iter().all(|c| c.values.len() == n));
                    assert!(tr.variable.values.windows(2).all(|w| w[0] <= w[1]));
                    assert_eq!(tr.variable.values[0], 0.0);
                    let (text, tr2) = run_scene_traced(&path, Format::Json).expect("runs");
                    assert_eq!(serde_json::from_str::<Value>(&text).expect("json"), plain);
                    assert_eq!(tr2.as_ref(), Ok(&tr));
                }
                Err(e) => {
                    // why: the model records none, or (a rigid impact without an impulse, a
                    // balls-wall scene without its stiffness) this scene gives it none
                    let e = e.to_string();
                    let why = run_scene_traced(&path, Format::Json)
                        .expect("runs")
                        .1
                        .expect_err("no path");
                    assert!(e.contains("records no path") && e.contains(&why), "{e}");
                    let expected = match name {
                        "rigid-impact" if plain["impulse"].is_null() => "took no steps",
                        "balls-wall" if plain["time_unit_s"].is_null() => "stiffness",
                        _ if !TRACED.contains(&name) => crate::models::trace::NO_PATH_IN_TIME,
                        _ => "a path was expected",
                    };
                    assert!(why.contains(expected), "{}: {why}", path.display());
                }
            }
        }
        // balls-wall's example gives no stiffness: its path is the test below's
        traced_seen.insert("balls-wall");
        for m in TRACED {
            assert!(
                traced_seen.contains(m),
                "no example scene of {m} with a path"
            );
        }
    }

    #[test]
    fn the_trace_file_is_json_or_csv_by_its_ending() {
        use std::path::Path;
        assert_eq!(trace_kind(Path::new("a/b.json")).ok(), Some(Format::Json));
        assert_eq!(trace_kind(Path::new("b.csv")).ok(), Some(Format::Csv));
        let e = trace_kind(Path::new("b.txt")).expect_err("refused");
        assert!(e.to_string().contains("b.txt") && e.to_string().contains(".csv"));
    }

    fn traced(scene: &str) -> (Value, Trace) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(scene);
        run_traced(&crate::scene::load(&path).expect("loads")).expect("traces")
    }

    /// Independent of the code: the undamped Hertz impact of scenes/hertz.toml (m = k = v0 = 1)
    /// keeps m v^2/2 + (2/5) k z^(5/2) = 1/2 at every recorded step, and its "max indentation"
    /// sits at Hertz's closed form z_max = (5 m v0^2 / (4 k))^(2/5) = 1.25^0.4 with v = 0.
    #[test]
    fn a_hertz_path_keeps_its_energy_and_peaks_at_the_closed_form() {
        let (v, tr) = traced("hertz.toml");
        let heads: Vec<String> = tr.states.iter().map(|c| c.heading()).collect();
        assert_eq!(heads, ["z (m)", "dz/dt (m/s)"]);
        let (z, u) = (&tr.states[0].values, &tr.states[1].values);
        for (z, u) in z.iter().zip(u) {
            let energy = 0.5 * u * u + 0.4 * z.max(0.0).powf(2.5);
            assert!((energy - 0.5).abs() < 1e-7, "energy {energy}");
        }
        let names: Vec<&str> = tr.events.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["max indentation", "peak force", "contact end"]);
        let peak = &tr.events[0];
        assert!((peak.state[0] - 1.25f64.powf(0.4)).abs() < 1e-8 && peak.state[1].abs() < 1e-8);
        assert_eq!(
            tr.events[2].at,
            v["contact"]["duration"].as_f64().expect("a number")
        );
        assert_eq!(tr.variable.values.last(), Some(&tr.events[2].at));
    }

    /// scenes/oscillator_wall.toml against its closed form: the k-th impact at
    /// t1 + (k-1) pi/wd, wd t1 = pi - atan(wd/sigma), sigma = zeta w, wd = w sqrt(1 - zeta^2);
    /// at each, the path holds the state before and, at the same time, after the jump v -> -e v.
    #[test]
    fn an_oscillator_on_a_wall_records_each_impact_before_and_after_its_jump() {
        let (_, tr) = traced("oscillator_wall.toml");
        let (w, zeta, e) = (20.0f64, 0.05f64, 0.8);
        let (sigma, wd) = (zeta * w, w * (1.0 - zeta * zeta).sqrt());
        let t1 = (std::f64::consts::PI - (wd / sigma).atan()) / wd;
        let heads: Vec<String> = tr.states.iter().map(|c| c.heading()).collect();
        let iv = heads.iter().position(|h| h.starts_with("v ")).expect("v");
        let impacts: Vec<_> = tr.events.iter().filter(|e| e.name == "impact").collect();
        assert!(impacts.len() >= 5, "{} impacts", impacts.len());
        for (k, hit) in impacts.iter().enumerate() {
            let want = t1 + k as f64 * std::f64::consts::PI / wd;
            assert!(
                (hit.at - want).abs() < 1e-9,
                "impact {k}: {} vs {want}",
                hit.at
            );
            let rows: Vec<usize> = (0..tr.variable.values.len())
                .filter(|i| tr.variable.values[*i] == hit.at)
                .collect();
            assert_eq!(rows.len(), 2, "the step before the jump and the one after");
            let (before, after) = (tr.states[iv].values[rows[0]], tr.states[iv].values[rows[1]]);
            assert_eq!(before, hit.state[iv]);
            assert!(before < 0.0 && (after + e * before).abs() <= 1e-15 * before.abs());
        }
    }

    /// A Kelvin-Voigt half-space (scenes/cone_halfspace_kv.toml): no plate column; the force
    /// column is the law's P = k z (z + 2 tau z') (zero at the start), never above the outcome's
    /// peak; the path ends where contact ends, on the event that ended it.
    #[test]
    fn a_cone_path_carries_its_force_and_ends_with_the_contact() {
        let (v, tr) = traced("cone_halfspace_kv.toml");
        let heads: Vec<String> = tr.states.iter().map(|c| c.heading()).collect();
        assert_eq!(heads, ["z (m)", "dz/dt (m/s)", "P (N)"]);
        let p = &tr.states[2].values;
        assert_eq!(p[0], 0.0);
        let peak = v["contact"]["peak_force"].as_f64().expect("a number");
        assert!(p.iter().all(|x| *x <= peak));
        assert!(p.iter().fold(0.0f64, |a, b| a.max(*b)) > 0.9 * peak);
        // the law's ratio P / (z (z + 2 tau z')) is one constant k along the contact
        let ks: Vec<f64> = (1..p.len() - 1)
            .map(|i| {
                let (z, u) = (tr.states[0].values[i], tr.states[1].values[i]);
                p[i] / (z * z + 2.0 * z * u * tau_of_scene())
            })
            .collect();
        assert!(ks.iter().all(|k| (k / ks[0] - 1.0).abs() < 1e-9), "{ks:?}");
        let last = tr.events.last().expect("an event");
        assert!(last.name.contains("returns to zero"));
        assert_eq!(Some(&last.at), tr.variable.values.last());
        assert_eq!(
            last.at,
            v["contact"]["duration"].as_f64().expect("a number")
        );
    }

    /// tau = eta / E of the Kelvin-Voigt material of scenes/cone_halfspace_kv.toml.
    fn tau_of_scene() -> f64 {
        1.0e6 / 2.0e9
    }

    /// scenes/pendulum_on_wall.toml (rho = 0.5, sigma = 1, |GO| = 1, v0 = 1, m = c2 = 1)
    /// against (2.15) solved in closed form by its eigenvectors
    /// ([`crate::models::pendulum_wall::ClosedForm`]): every step's deformations and rates, and
    /// the unloading (eps_Cn = 0) as the last event.
    #[test]
    fn a_pendulum_path_is_the_closed_form_of_its_linear_equations() {
        let (_, tr) = traced("pendulum_on_wall.toml");
        let exact = crate::models::pendulum_wall::ClosedForm::new(0.5, 1.0);
        let heads: Vec<String> = tr.states.iter().map(|c| c.heading()).collect();
        assert_eq!(
            heads,
            [
                "eps_On (m)",
                "eps_Cn (m)",
                "deps_On/dt (m/s)",
                "deps_Cn/dt (m/s)"
            ]
        );
        for (i, t) in tr.variable.values.iter().enumerate() {
            let want = exact.state(*t);
            for (k, w) in want.iter().enumerate() {
                let got = tr.states[k].values[i];
                assert!((got - w).abs() < 1e-6, "t = {t}, state {k}: {got} vs {w}");
            }
        }
        let last = tr.events.last().expect("the unloading");
        assert_eq!(last.name, "contact unloads");
        // this scene unloads tangentially (eps_Cn' = 0 there: its warning), so the instant is
        // ill-conditioned; it is a root of the closed form's eps_Cn all the same
        assert!(last.state[1].abs() < 1e-9 && exact.state(last.at)[1].abs() < 1e-9);
    }

    /// scenes/rigid_impact.toml (Poisson's law, e = 0.6, the normal along z): the path starts at
    /// the approach velocity v_rel, compression ends where V_n = 0, and by Poisson's definition
    /// the normal impulse at the end is (1 + e) times the one at the end of compression; the
    /// last step's velocity is the outcome's v_rel_after.
    #[test]
    fn a_rigid_impact_path_runs_in_the_normal_impulse_to_poissons_end() {
        let (v, tr) = traced("rigid_impact.toml");
        assert_eq!(tr.variable.heading(), "I_n (N s)");
        let first: Vec<f64> = tr.states.iter().map(|c| c.values[0]).collect();
        assert_eq!(first, [0.8, 0.2, -1.0]);
        assert_eq!(tr.variable.values[0], 0.0);
        let comp = tr
            .events
            .iter()
            .find(|e| e.name == "compression ends")
            .expect("compression ends");
        assert!(comp.state[2].abs() < 1e-9, "V_n = {}", comp.state[2]);
        let end = *tr.variable.values.last().expect("steps");
        assert!(
            (end - 1.6 * comp.at).abs() < 1e-9 * end,
            "{end} vs 1.6 x {}",
            comp.at
        );
        let after: Vec<f64> = tr
            .states
            .iter()
            .map(|c| *c.values.last().expect("steps"))
            .collect();
        let want: Vec<f64> = v["v_rel_after"]
            .as_array()
            .expect("v_rel_after")
            .iter()
            .map(|x| x.as_f64().expect("a number"))
            .collect();
        assert_eq!(after, want);
    }

    /// scenes/balls_wall.toml with a ball-ball stiffness k = 1e9 N/m^1.5 (its time unit): the
    /// path in SI keeps the energy of two Hertz contacts, m (v1^2 + v2^2)/2 + k/(p+1)
    /// ((x1 - x2)_+^(p+1) + kappa (x2)_+^(p+1)) = m v0^2/2, at every step (the integrator does not
    /// conserve it by construction), and ends at the outcome's velocities times v0; without the
    /// stiffness the run says it has no path and why.
    #[test]
    fn a_balls_wall_path_keeps_the_energy_of_its_two_contacts() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let text = std::fs::read_to_string(dir.join("balls_wall.toml")).expect("the scene");
        let table: toml::Table = format!("{text}\nstiffness = 1.0e9\n")
            .parse()
            .expect("TOML");
        let scene = crate::scene::parse_table(&table, "balls").expect("loads");
        let (v, tr) = run_traced(&scene).expect("a path with the stiffness");
        let (m, v0, k, p, kappa) = (0.26, 1.0, 1.0e9, 1.5, 2.8284271247461903);
        let col = |i: usize| &tr.states[i].values;
        let e0 = 0.5 * m * v0 * v0;
        for i in 0..tr.variable.values.len() {
            let (x1, v1, x2, v2) = (col(0)[i], col(1)[i], col(2)[i], col(3)[i]);
            let stored = k / (p + 1.0)
                * ((x1 - x2).max(0.0).powf(p + 1.0) + kappa * x2.max(0.0).powf(p + 1.0));
            let energy = 0.5 * m * (v1 * v1 + v2 * v2) + stored;
            assert!(
                (energy / e0 - 1.0).abs() < 1e-6,
                "step {i}: {energy} vs {e0}"
            );
        }
        let n = tr.variable.values.len() - 1;
        assert_eq!(
            col(1)[n],
            v["v_striker_after"].as_f64().expect("a number") * v0
        );
        assert_eq!(
            col(3)[n],
            v["v_wall_ball_after"].as_f64().expect("a number") * v0
        );
        let plain = crate::scene::load(&dir.join("balls_wall.toml")).expect("loads");
        let why = plain
            .run_traced()
            .expect("runs")
            .1
            .expect_err("no stiffness, no path");
        assert!(why.contains("stiffness"), "{why}");
    }
}
