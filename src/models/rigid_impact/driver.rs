//! The impact driven stage by stage: the events of each stage (compression's end, restitution's
//! condition, the slip's stops, the support's switches), the decisions between stages, and the
//! solver-consistency checks (friction never does positive work, energy never grows under the
//! energetic law, A never goes through its support).

use super::*;
use crate::integrate::{Direction, Event, Method, Options, Stop, solve};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// The mode of a slip that starts from rest along the ray `sys.u_hint` ([`stick_or_slide`]'s
/// slide direction: $P_t\mathbf B(\mathbf n - \mu\mathbf u) = \kappa\mathbf u$, $\kappa > 0$).
/// Without a support the matrix is constant and the slip grows along that ray exactly, so its
/// friction direction is held there: left free, a slip that grows slowly (mu just below the
/// critical value, kappa near 0) stays near zero for long, where its direction's turning rate
/// grows like $1/|\mathbf V_t|$, and the steps collapse (`perf::rigid_sample`'s degenerate cases,
/// tests/regression_slip_from_rest_near_critical.rs). With a support the matrix turns with the
/// support's motion and the slip is left free.
pub(super) fn from_rest(sys: &Keller) -> Mode {
    if sys.at_a.is_none() {
        Mode::Ray(sys.u_hint)
    } else {
        Mode::Slip
    }
}

/// The impact with an optional support: its state, the velocity of A before the impact and
/// whether its start mode is forced.
#[allow(clippy::too_many_arguments)]
pub(super) fn impact_core(
    b: &Matrix3<f64>,
    at_a: Option<(AtA, Vector3<f64>, bool)>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let bad = out_of_range;
    if normal.norm() <= 0.0 || normal.norm().is_nan() {
        return Err(bad(
            "contact.normal",
            format!("{normal:?}"),
            "a non-zero vector",
        ));
    }
    if !(0.0..=1.0).contains(&e) {
        return Err(bad("contact.e", e.to_string(), "0 <= e <= 1"));
    }
    if !(mu >= 0.0 && mu.is_finite()) {
        return Err(bad("contact.mu", mu.to_string(), "mu >= 0"));
    }
    let b = *b;
    let n = normal.normalize();
    let vn0 = v_minus.dot(&n);
    if vn0 >= 0.0 || vn0.is_nan() {
        return Err(bad(
            "initial.v_rel",
            format!("{v_minus:?} (normal component {vn0})"),
            "a relative velocity with (v_rel, normal) < 0: the bodies must approach",
        ));
    }
    let eig = SymmetricEigen::new(b).eigenvalues;
    let (lmin, lmax) = (eig.min(), eig.max());
    if lmax <= 0.0 || lmax.is_nan() {
        return Err(bad(
            "body",
            format!("B eigenvalues {eig:?}"),
            "at least one body that can move",
        ));
    }
    // Proposition 3 of 002: with a support the bound takes the smaller of the least eigenvalues
    // of B and B* (the support's reaction can make the impulse larger than B alone allows)
    let lmin = match &at_a {
        Some((a, _, _)) => {
            let w = a.b_tilde.transpose() * a.normal;
            let b_star = b - w * w.transpose() / a.beta_n;
            lmin.min(SymmetricEigen::new(b_star).eigenvalues.min())
        }
        None => lmin,
    };
    let lam_floor = lmax * 1e-12;
    let chi_max = 20.0 * 2.0 * v_minus.norm() / lmin.max(lam_floor).max(lmax * 1e-6);
    let scale = v_minus.norm();
    let forced_start = at_a.as_ref().is_some_and(|r| r.2);
    let v_a0 = at_a.as_ref().map(|r| r.1);
    let mut sys = Keller {
        at_a: at_a.map(|(mut r, _, _)| {
            r.floor = 1e-13 * scale;
            r
        }),
        b,
        n,
        mu,
        mode: Mode::Slip,
        u_hint: Vector3::zeros(),
        floor: 1e-13 * scale,
    };
    let mut y = vec![
        v_minus.x, v_minus.y, v_minus.z, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ];
    let mut chi = 0.0;
    // the slip at A is taken to have stopped, as at C, far below the tolerance
    let stop_a = (10.0 * 1e-13 * scale).max(1e-2 * rtol * scale);
    let mut support_phases = Vec::new();
    if let (Some(r), Some(va)) = (&sys.at_a, v_a0) {
        y.extend_from_slice(va.as_slice());
        // with no slip at C, C's stick (or slide from rest) and the support's motion are one
        // problem ([`c_direction_with`] decides C's for each of the support's modes): the
        // support was decided on C's frictionless direction n before, and a stick at C then
        // taken with the contact matrix B* while the support, pulled by it, gave nothing (the
        // stick slid, and the energy grew under the energetic law: tests/regression_constrained_seeds.rs)
        if mu > 0.0 && sys.tangential(&v_minus).norm() <= sys.floor {
            sys.mode = Mode::Stick(Vector3::zeros());
        }
        if !forced_start {
            decide_support(&mut sys, &mut y, stop_a, 0.0, false, stop_a)?;
        } else if r.rough() && r.mode == SupportMode::Slide && r.tangential(&va).norm() <= stop_a {
            // a forced slide from rest: in the direction (4.5) gives
            let f = sys.rate(&v_minus, &va);
            let r = sys.at_a.as_mut().expect("support");
            let dirs = start_slide_dirs(r, &f);
            let (e, _, _) = dirs
                .into_iter()
                .max_by(|a, b| {
                    (a.2, a.1)
                        .partial_cmp(&(b.2, b.1))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .ok_or_else(|| no_support_motion(0.0, "(4.5) has no slide direction"))?;
            r.hint = e;
            r.held = true;
            y[10..13].copy_from_slice((e * (20.0 * stop_a)).as_slice());
        }
        if let Some(r) = &sys.at_a {
            support_phases.push(Phase {
                kind: r.phase_name().into(),
                normal_impulse: 0.0,
            });
        }
    }
    let mut phases = Vec::new();
    let mut path: Vec<(f64, [f64; 3])> = Vec::new();
    let mut stats = crate::integrate::Stats::default();
    // initial mode
    let vt0 = sys.tangential(&v_minus);
    if vt0.norm() <= sys.floor || mu == 0.0 {
        let va = va_of(&y);
        let b_stick = sys.b_stick(&va);
        let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
        match (mu > 0.0).then(|| stick_or_slide(&b_stick, &rate_of, &n, mu)) {
            Some(Ok(tau)) => {
                sys.mode = Mode::Stick(tau);
                phases.push(Phase {
                    kind: "stick".into(),
                    normal_impulse: 0.0,
                });
            }
            Some(Err(u)) => {
                sys.u_hint = slide_at_c(u, sys.at_a.is_some(), &n, 0.0)?;
                sys.mode = from_rest(&sys);
                phases.push(Phase {
                    kind: "slip".into(),
                    normal_impulse: 0.0,
                });
            }
            None => phases.push(Phase {
                kind: "slip".into(),
                normal_impulse: 0.0,
            }),
        }
    } else {
        phases.push(Phase {
            kind: "slip".into(),
            normal_impulse: 0.0,
        });
    }
    // B* (or B) and mu are fixed while the support keeps its mode: the ray a dying slip
    // settles on is found once per mode of the support
    let find_rays = |sys: &Keller, y: &[f64]| {
        let va = va_of(y);
        let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
        if mu > 0.0 {
            decay_rays(&rate_of, &n, mu)
        } else {
            Vec::new()
        }
    };
    let mut rays = find_rays(&sys, &y);
    let mut b_stick = sys.b_stick(&va_of(&y));
    let mut ray_armed = true;
    let mut chi_c: Option<f64> = None;
    let mut w_c = 0.0;
    let mut cut_off = false;
    let mut switches = 0usize;
    let mut band_switches = 0usize;
    let mut last_fired = String::new();
    let mut first = true;
    loop {
        // the support's motion after every stop (a switch at C changes alpha at once, which
        // no event can see as a crossing), and C's stick after every change of the support
        if !first && sys.at_a.is_some() {
            let before = sys.at_a.as_ref().map(|r| r.mode);
            let leaving_roll = last_fired == "support starts to slide";
            // after the slip at A was seen to stop (or to turn off its frozen direction), what
            // is left of it in the band where its direction is held (HOLD_BELOW stop) is no
            // slip: deciding on it would chatter about zero, a slip held there turning away
            // from its frozen direction again and again
            let rest_below = if last_fired.starts_with("support slip stops") {
                HOLD_BELOW * stop_a
            } else {
                stop_a
            };
            decide_support(&mut sys, &mut y, stop_a, chi, leaving_roll, rest_below)?;
            if last_fired == "support slip nearly stops"
                && let Some(r) = sys.at_a.as_mut()
                && r.mode == SupportMode::Slide
            {
                // frozen at the slip's own direction (decide_support set it as the hint)
                r.held = true;
            }
            let after = sys.at_a.as_ref().map(|r| r.mode);
            let restarted = last_fired.starts_with("support slip stops")
                || last_fired == "support starts to slide";
            if let (Some(m), Some(r)) = (after, &sys.at_a)
                && (after != before || (restarted && m == SupportMode::Slide))
            {
                support_phases.push(Phase {
                    kind: r.phase_name().into(),
                    normal_impulse: chi,
                });
            }
            if after != before
                || last_fired.starts_with("support")
                || last_fired == "stick at C breaks"
            {
                // the matrices of C's stick/slip switch change with the support's mode
                b_stick = sys.b_stick(&va_of(&y));
                rays = find_rays(&sys, &y);
                ray_armed = true;
                if let Mode::Stick(_) = sys.mode {
                    let va = va_of(&y);
                    let decided = {
                        let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
                        stick_or_slide(&b_stick, &rate_of, &n, mu)
                    };
                    match decided {
                        Ok(tau) => sys.mode = Mode::Stick(tau),
                        Err(u) => {
                            let u = slide_at_c(u, true, &n, chi)?;
                            sys.u_hint = u;
                            sys.mode = Mode::Held(u);
                            let slip_stop = (10.0 * sys.floor).max(1e-2 * rtol * scale);
                            let v = Vector3::new(y[0], y[1], y[2]);
                            let vnew = v - sys.tangential(&v) + u * (20.0 * slip_stop);
                            y[..3].copy_from_slice(vnew.as_slice());
                            phases.push(Phase {
                                kind: "slip".into(),
                                normal_impulse: chi,
                            });
                        }
                    }
                }
            }
        }
        // a rough support that slides turns the matrix of C's slip with its slide direction:
        // the ray a dying slip settles on moves with it
        if !first
            && let Some(a) = &sys.at_a
            && a.rough()
            && a.mode == SupportMode::Slide
        {
            rays = find_rays(&sys, &y);
            b_stick = sys.b_stick(&va_of(&y));
        }
        first = false;
        last_fired.clear();
        switches += 1;
        if switches > 10_000 {
            return Err(ImpactError::NoEnd {
                law: format!(
                    "{} (more than 10000 stick/slip switches at normal impulse {chi:e})",
                    law.name()
                ),
                chi_max,
            });
        }
        if let Mode::Stick(tau) = sys.mode
            && (b_stick * (n + tau)).norm() <= 1e-10 * lmax
        {
            // the velocity no longer changes while the reaction grows: a cut-off impact
            cut_off = true;
            break;
        }
        // the end condition of the current stage
        let target = |y: &[f64]| -> f64 {
            let vn = Vector3::new(y[0], y[1], y[2]).dot(&n);
            match chi_c {
                None => vn,
                Some(_) => match law {
                    Law::Newton => vn + e * vn0,
                    Law::Poisson => 0.0,
                    Law::Energetic => y[6] - w_c * (1.0 - e * e),
                },
            }
        };
        let poisson_end = chi_c.map(|c| (1.0 + e) * c);
        let end_g = |chi: f64, y: &[f64]| match (chi_c, law) {
            (Some(_), Law::Poisson) => chi - poisson_end.unwrap_or(chi),
            _ => target(y),
        };
        // the slip is taken to have stopped at a speed far below the tolerance: when the slip
        // velocity spirals into zero (anisotropic B) its direction turns ever faster and the
        // steps shrink with |V_t|, so chasing it down to the round-off floor costs unbounded
        // steps; stopping at 1e-2 rtol x the velocity scale changes the impulse by less than that
        let slip_stop = (10.0 * sys.floor).max(1e-2 * rtol * scale);
        let slip_g = |_chi: f64, y: &[f64]| {
            let v = Vector3::new(y[0], y[1], y[2]);
            (v - n * v.dot(&n)).norm() - slip_stop
        };
        let stage_done_already = chi_c.is_some() && end_g(chi, &y) >= 0.0;
        if stage_done_already {
            break;
        }
        // when the slip dies out along a stable ray, |V_t| reaches zero with a corner and the
        // integrator overshoots it by more than slip_stop within a step, so |V_t| - slip_stop
        // may never be seen negative; the speed along the ray falls through zero at a simple root
        // (disarmed, constant, after it fired off the ray, until the slip settles or stops)
        // (one event per stable ray the slip can die on: with a large mu there may be two, and a
        // slip settles on the one its start leads to)
        let armed = ray_armed;
        let live_rays: Vec<Vector3<f64>> = match sys.mode {
            Mode::Ray(u) => vec![u],
            _ => rays.clone(),
        };
        let ray_gs: Vec<_> = live_rays
            .iter()
            .map(|&ray| {
                move |_chi: f64, y: &[f64]| {
                    if armed {
                        Vector3::new(y[0], y[1], y[2]).dot(&ray) - slip_stop
                    } else {
                        scale
                    }
                }
            })
            .collect();
        // once the slip lies on that ray to within 1e-2 rtol of the velocity scale and 1e-6 rad
        // (its component across the ray), the friction direction is frozen along it: the true
        // direction only converges further, while keeping it free makes the system ever stiffer
        // as |V_t| goes to zero (the turning rate grows like 1/|V_t|)
        let across = 1e-2 * rtol * scale;
        let aligned_gs: Vec<_> = live_rays
            .iter()
            .map(|&ray| {
                move |_chi: f64, y: &[f64]| {
                    let v = Vector3::new(y[0], y[1], y[2]);
                    let vt = v - n * v.dot(&n);
                    if vt.dot(&ray) <= 0.0 {
                        return scale;
                    }
                    // across the ray: below 1e-2 rtol scale, and a small angle (not merely a
                    // small slip)
                    (vt - ray * vt.dot(&ray)).norm() - across.min(1e-6 * vt.norm())
                }
            })
            .collect();
        // a slip that dies along a straight line (a planar impact, a symmetric body, a slip on
        // a ray the scan does not count as stable) reaches |V_t| = 0 with a corner the steps may
        // pass over, whether or not its line is a stable ray; its component along its direction
        // at the stage's start falls through zero at a simple root (where the slip turned
        // instead, by more than 1e3 stops across, it slips on: a new stage takes its new line);
        // a slip held on a ray has the ray's own event
        let v_start = Vector3::new(y[0], y[1], y[2]);
        let vt_start = v_start - n * v_start.dot(&n);
        let line0 = if vt_start.norm() > 10.0 * slip_stop && sys.mode == Mode::Slip {
            vt_start.normalize()
        } else {
            Vector3::zeros()
        };
        let line_g = move |_chi: f64, y: &[f64]| {
            if line0 == Vector3::zeros() {
                scale
            } else {
                Vector3::new(y[0], y[1], y[2]).dot(&line0) - slip_stop
            }
        };
        let mut events = vec![Event::new("stage end", &end_g, Direction::Rising, true)];
        // the ray each event belongs to, by event index
        let mut ray_of_event: Vec<Option<Vector3<f64>>> = vec![None];
        let slipping = matches!(sys.mode, Mode::Slip | Mode::Ray(_)) && mu > 0.0;
        if slipping {
            events.push(Event::new("slip stops", &slip_g, Direction::Falling, true));
            ray_of_event.push(None);
            events.push(Event::new(
                "slip stops along its line",
                &line_g,
                Direction::Falling,
                true,
            ));
            ray_of_event.push(None);
            for (g, ray) in ray_gs.iter().zip(&live_rays) {
                events.push(Event::new(
                    "slip dies on its ray",
                    g,
                    Direction::Falling,
                    true,
                ));
                ray_of_event.push(Some(*ray));
            }
            if sys.mode == Mode::Slip {
                for (g, ray) in aligned_gs.iter().zip(&live_rays) {
                    events.push(Event::new(
                        "slip settles on its ray",
                        g,
                        Direction::Falling,
                        true,
                    ));
                    ray_of_event.push(Some(*ray));
                }
            }
        }
        // the rough support's switches (002 section 4): its slip stops, its rolling reaction
        // leaves the friction cone or would pull, it would push again after letting go; and a
        // stick at C that the support's motion breaks
        let sys_ref = &sys;
        let state = |y: &[f64]| {
            let (v, va) = (Vector3::new(y[0], y[1], y[2]), va_of(y));
            (sys_ref.rate(&v, &va), va)
        };
        let a_slip_g = |_chi: f64, y: &[f64]| {
            sys_ref
                .at_a
                .as_ref()
                .map_or(scale, |r| r.tangential(&va_of(y)).norm() - stop_a)
        };
        // a slip at A that dies out along a line reaches |V_A,T| = 0 with a corner the steps
        // may pass over; its component along the direction it had when this stage began falls
        // through zero at a simple root (where the slip turned instead, it slides on)
        let a_dir0 = sys
            .at_a
            .as_ref()
            .map_or(Vector3::zeros(), |r| r.slide_dir(&va_of(&y)));
        let a_reverse_g = move |_chi: f64, y: &[f64]| va_of(y).dot(&a_dir0) - stop_a;
        // beta of (4.4) falling to zero as the slide turns: the reaction grows without bound
        let a_beta_g = |_chi: f64, y: &[f64]| {
            sys_ref
                .at_a
                .as_ref()
                .map_or(scale, |r| r.slide_i(&va_of(y)).1 - BETA_FLOOR * r.beta_n)
        };
        let a_beta_neg_g = |_chi: f64, y: &[f64]| {
            sys_ref
                .at_a
                .as_ref()
                .map_or(-scale, |r| r.slide_i(&va_of(y)).1 + BETA_FLOOR * r.beta_n)
        };
        let a_cone_g = |_chi: f64, y: &[f64]| {
            let (f, _) = state(y);
            sys_ref.at_a.as_ref().map_or(-scale, |r| {
                let fs = r.roll_reaction(&f);
                let fs_n = fs.dot(&r.normal);
                (fs - r.normal * fs_n).norm() - r.mu * fs_n
            })
        };
        // -alpha of (3.6): the support lets go where alpha turns positive (a rolling reaction
        // that would pull leaves the cone first)
        let a_minus_alpha_g = |_chi: f64, y: &[f64]| {
            let (f, _) = state(y);
            sys_ref
                .at_a
                .as_ref()
                .map_or(scale, |r| (r.b_tilde * f).dot(&r.normal))
        };
        // a free body comes back down onto the support (an approach slower than stop_a is
        // taken as arriving)
        let a_lands_g = |_chi: f64, y: &[f64]| {
            sys_ref
                .at_a
                .as_ref()
                .map_or(scale, |r| va_of(y).dot(&r.normal) + stop_a)
        };
        // a held slip (at A or C) is freed once it exceeds the velocity tolerance
        let established = RELEASE_ABOVE * stop_a;
        let a_established_g = |_chi: f64, y: &[f64]| {
            sys_ref
                .at_a
                .as_ref()
                .map_or(-scale, |r| r.tangential(&va_of(y)).norm() - established)
        };
        // a slip at A that falls below HOLD_BELOW stop has its direction frozen (see there)
        let a_dying_g = |_chi: f64, y: &[f64]| {
            sys_ref.at_a.as_ref().map_or(scale, |r| {
                r.tangential(&va_of(y)).norm() - HOLD_BELOW * stop_a
            })
        };
        let c_established_g = |_chi: f64, y: &[f64]| {
            let v = Vector3::new(y[0], y[1], y[2]);
            (v - n * v.dot(&n)).norm() - established
        };
        let c_stick_g = |_chi: f64, y: &[f64]| {
            let va = va_of(y);
            let b_now = sys_ref.b_stick(&va);
            stick_tau(&b_now, &n).map_or(mu, |t| t.norm()) - mu * (1.0 + 1e-9)
        };
        if let Some(r) = &sys.at_a {
            match r.mode {
                SupportMode::Slide if r.regular > 0.0 => {
                    events.push(stop_at(
                        "support beta vanishes",
                        &a_beta_g,
                        Direction::Falling,
                    ));
                    events.push(stop_at(
                        "support lets go",
                        &a_minus_alpha_g,
                        Direction::Falling,
                    ));
                }
                SupportMode::Slide => {
                    if r.rough() {
                        events.push(stop_at("support slip stops", &a_slip_g, Direction::Falling));
                        events.push(stop_at(
                            "support slip stops along its line",
                            &a_reverse_g,
                            Direction::Falling,
                        ));
                        events.push(stop_at(
                            "support beta vanishes",
                            &a_beta_g,
                            Direction::Falling,
                        ));
                        if r.slide_i(&va_of(&y)).1 < 0.0 {
                            // the sliding branch of a two-solution case (beta of (4.4) < 0): its
                            // reaction -alpha/beta stays positive only while alpha > 0, and grows
                            // without bound as beta rises to 0; either ends it (without these the
                            // reaction was clipped to zero and A went through the support:
                            // tests/regression_constrained_seeds.rs)
                            events.push(stop_at(
                                "support's sliding branch ends",
                                &a_minus_alpha_g,
                                Direction::Rising,
                            ));
                            events.push(stop_at(
                                "support beta vanishes",
                                &a_beta_neg_g,
                                Direction::Rising,
                            ));
                        }
                        if r.held {
                            events.push(stop_at(
                                "support slip established",
                                &a_established_g,
                                Direction::Rising,
                            ));
                        } else {
                            events.push(stop_at(
                                "support slip nearly stops",
                                &a_dying_g,
                                Direction::Falling,
                            ));
                        }
                    }
                    events.push(stop_at(
                        "support lets go",
                        &a_minus_alpha_g,
                        Direction::Falling,
                    ));
                }
                SupportMode::Roll => {
                    events.push(stop_at(
                        "support starts to slide",
                        &a_cone_g,
                        Direction::Rising,
                    ));
                    events.push(stop_at(
                        "support lets go",
                        &a_minus_alpha_g,
                        Direction::Falling,
                    ));
                }
                SupportMode::Free => events.push(stop_at(
                    "support reached again",
                    &a_lands_g,
                    Direction::Falling,
                )),
            }
            if let Mode::Held(_) = sys.mode {
                events.push(Event::new("slip stops", &slip_g, Direction::Falling, true));
                events.push(stop_at(
                    "slip at C established",
                    &c_established_g,
                    Direction::Rising,
                ));
            }
            if r.rough() && matches!(sys.mode, Mode::Stick(_)) && mu > 0.0 {
                events.push(stop_at("stick at C breaks", &c_stick_g, Direction::Rising));
            }
        }
        let names: Vec<String> = events.iter().map(|e| e.name.clone()).collect();
        let opts = Options {
            rtol,
            atol: rtol * scale * 1e-3,
            // the regularised band is stiff (its rate is the friction's over the band) in a way
            // the explicit method's stiffness test does not always see: Radau5 from the start
            method: if sys.at_a.as_ref().is_some_and(|r| r.regular > 0.0) {
                Method::Radau5
            } else {
                Method::Auto
            },
            events,
            trajectory: true,
            ..Options::default()
        };
        let y_before = y.clone();
        let sol = match solve(&sys, chi, &y, chi_max, &opts) {
            Ok(sol) => sol,
            Err(e) => {
                // a rough support in contact whose exact law the solver could not follow (a slip
                // at A hovering at the edge of its band, its direction stiff without bound):
                // the stage again with the support's friction regularised, else the failure
                if let Some(r) = sys.at_a.as_mut()
                    && r.rough()
                    && r.regular == 0.0
                    && r.mode != SupportMode::Free
                {
                    r.regularise(RELEASE_ABOVE * stop_a);
                    support_phases.push(Phase {
                        kind: r.phase_name().into(),
                        normal_impulse: chi,
                    });
                    last_fired = "support regularised".into();
                    continue;
                }
                return Err(e.into());
            }
        };

        stats = stats + sol.stats;
        if sys.at_a.is_none() {
            friction_work_check(&b, &y_before, &sol.y, rtol, scale, sol.t)?;
        }
        // a support in contact holds A on it: a reaction the law clipped to zero (the sliding
        // branch of a Painleve case whose alpha changed sign, unseen) let A through it
        if let Some(r) = &sys.at_a
            && r.mode != SupportMode::Free
            && va_of(&sol.y).dot(&r.normal) < -1e4 * stop_a
        {
            return Err(ImpactError::Inconsistent {
                chi: sol.t,
                what: format!(
                    "A went into the support at {:.3e} m/s while in contact ({}); its reaction could not hold it",
                    -va_of(&sol.y).dot(&r.normal),
                    r.phase_name()
                ),
            });
        }
        path.extend(sol.trajectory.iter().map(|(c, y)| (*c, [y[0], y[1], y[2]])));
        chi = sol.t;
        y = sol.y.clone();
        let fired = match sol.stop {
            Stop::Event { index, .. } => names[index].as_str(),
            Stop::End => "",
        };
        last_fired = fired.to_string();
        if fired.starts_with("support slip") {
            band_switches += 1;
            if band_switches > REGULARISE_AFTER
                && let Some(r) = sys.at_a.as_mut()
                && r.regular == 0.0
            {
                r.regularise(RELEASE_ABOVE * stop_a);
                support_phases.push(Phase {
                    kind: r.phase_name().into(),
                    normal_impulse: chi,
                });
            }
        }
        if fired.starts_with("support") || fired == "stick at C breaks" {
            continue;
        }
        if fired == "slip at C established" {
            sys.mode = Mode::Slip;
            continue;
        }
        match sol.stop {
            Stop::End => {
                return Err(ImpactError::NoEnd {
                    law: law.name().into(),
                    chi_max,
                });
            }
            Stop::Event { index: 0, .. } => {
                if chi_c.is_none() {
                    chi_c = Some(chi);
                    w_c = y[6];
                    // a zero-e law ends with compression
                    let done = match law {
                        Law::Newton | Law::Poisson | Law::Energetic => e == 0.0,
                    };
                    if done {
                        break;
                    }
                    continue;
                }
                break;
            }
            Stop::Event { .. }
                if fired == "slip stops along its line" && {
                    let left = sys.tangential(&Vector3::new(y[0], y[1], y[2])).norm();
                    left > 10.0 * slip_stop
                        && (left > TURNED_ABOVE * slip_stop || left >= 0.1 * vt_start.norm())
                } =>
            {
                // the slip turned off its line without stopping: on, along its new line. What
                // is left across the line is a slip through zero (a stop) where it is below
                // TURNED_ABOVE stops and a tenth of the slip at the stage's start; a slip that
                // starts from a nudge and turns keeps its size
                continue;
            }
            Stop::Event { index, .. }
                if fired == "slip settles on its ray"
                    && ray_of_event[index].is_some_and(|ray| {
                        sys.tangential(&Vector3::new(y[0], y[1], y[2])).dot(&ray) > 10.0 * slip_stop
                    }) =>
            {
                sys.mode = Mode::Ray(ray_of_event[index].unwrap_or_default());
                ray_armed = true;
                continue;
            }
            Stop::Event { .. }
                if fired == "slip dies on its ray" && {
                    let left = sys.tangential(&Vector3::new(y[0], y[1], y[2])).norm();
                    left > 10.0 * slip_stop
                        && (left > TURNED_ABOVE * slip_stop || left >= 0.1 * vt_start.norm())
                } =>
            {
                // the slip crossed the ray's normal line off the ray, away from zero (by more
                // than a stop, as for its own line: TURNED_ABOVE; a slip left below that bends
                // onto a nearly neutral ray and creeps, seed 899244 of constrained_fail): slip on,
                // with its own direction, without the ray event (it would fire again at once)
                // until the slip settles
                ray_armed = false;
                sys.mode = Mode::Slip;
                continue;
            }
            Stop::Event { .. } => {
                ray_armed = true;
                // slip stopped: stick or slide again
                let va = va_of(&y);
                let mut decided = {
                    let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
                    stick_or_slide(&b_stick, &rate_of, &n, mu)
                };
                // neither with the support pushing: C's stick and the support's contact are one
                // complementarity problem; the support letting go (where C's motion under the
                // free matrix then has alpha of (3.6) >= 0) is its other branch
                if let (Err(None), Some(a)) = (decided, sys.at_a.as_mut())
                    && a.mode != SupportMode::Free
                {
                    let before = std::mem::replace(&mut a.mode, SupportMode::Free);
                    let freed = {
                        let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
                        stick_or_slide(&b, &rate_of, &n, mu)
                    };
                    let f = match freed {
                        Ok(tau) => Some(n + tau),
                        Err(Some(u)) => Some(n - u * mu),
                        Err(None) => None,
                    };
                    let lets_go = sys
                        .at_a
                        .as_ref()
                        .zip(f)
                        .is_some_and(|(a, f)| -(a.b_tilde * f).dot(&a.normal) >= 0.0);
                    if lets_go {
                        decided = freed;
                        b_stick = b;
                        rays = find_rays(&sys, &y);
                        if let Some(a) = &sys.at_a {
                            support_phases.push(Phase {
                                kind: a.phase_name().into(),
                                normal_impulse: chi,
                            });
                        }
                    } else if let Some(a) = sys.at_a.as_mut() {
                        a.mode = before;
                    }
                }
                match decided {
                    Ok(tau) => {
                        sys.mode = Mode::Stick(tau);
                        phases.push(Phase {
                            kind: "stick".into(),
                            normal_impulse: chi,
                        });
                    }
                    Err(u) => {
                        let u = slide_at_c(u, sys.at_a.is_some(), &n, chi)?;
                        sys.u_hint = u;
                        sys.mode = from_rest(&sys);
                        // nudge past the floor in the new direction so the slip event re-arms:
                        // 20 slip_stop, far above the absolute tolerance (1e-3 rtol scale), so
                        // that integration noise cannot take the slip back under the stop (the
                        // switches then chatter), and at most 0.2 rtol scale, under the tolerance
                        let v = Vector3::new(y[0], y[1], y[2]);
                        let vt = sys.tangential(&v);
                        let vnew = v - vt + u * (20.0 * slip_stop);
                        y[0] = vnew.x;
                        y[1] = vnew.y;
                        y[2] = vnew.z;
                        phases.push(Phase {
                            kind: "reversal".into(),
                            normal_impulse: chi,
                        });
                    }
                }
            }
        }
    }
    let vp = Vector3::new(y[0], y[1], y[2]);
    // the impulse: integral of dI/dchi over chi (its normal component equals chi)
    let imp = Vector3::new(y[3], y[4], y[5]);
    let kelvin = 0.5 * (v_minus + vp).dot(&imp);
    let direct = v_minus.dot(&imp) + 0.5 * imp.dot(&(b * imp));
    // Stronge's law dissipates: its normal work is (1 - e^2) that of compression and friction's
    // is never positive
    if law == Law::Energetic
        && sys.at_a.is_none()
        && direct > ENERGY_SLACK * rtol * scale * imp.norm()
    {
        return Err(ImpactError::Inconsistent {
            chi,
            what: format!(
                "the kinetic energy grew by {direct:.6e} J under the energetic law, which dissipates"
            ),
        });
    }
    Ok(ImpactResult {
        cut_off,
        impulse: [imp.x, imp.y, imp.z],
        v_rel_after: [vp.x, vp.y, vp.z],
        compression_impulse: chi_c.unwrap_or(chi),
        energy_change: direct,
        kelvin_energy_change: kelvin,
        lambda_min: lmin,
        lambda_max: lmax,
        bound_upper: if lmin > lam_floor {
            2.0 * v_minus.norm() / lmin
        } else {
            f64::INFINITY
        },
        bound_lower: vn0.abs() / lmax,
        phases,
        stats,
        method: "integrate",
        support_impulse: [y[7], y[8], y[9]],
        support_phases,
        v_support_after: sys.at_a.as_ref().filter(|r| r.rough()).map(|_| {
            let va = va_of(&y);
            [va.x, va.y, va.z]
        }),
        path,
    })
}

/// A slip that crosses the normal line of its stage's direction with less than this many stops
/// left across it (1e-8 of the velocity scale at rtol 1e-10), and under a tenth of the slip the
/// stage began with, has stopped: it passed through zero along a curve (the integration's error
/// about a straight one, or a slip bending onto a nearly neutral ray when mu is just below the
/// critical value, where it would otherwise creep about zero with stiff turning for the rest of
/// the impact: `perf::rigid_sample` seed 865738). The velocities change by at most that slip.
pub(super) const TURNED_ABOVE: f64 = 1e4;

/// How many times `rtol x |V-| x |I|` an energy balance may miss by before it is a solver
/// inconsistency (the integrated impulse carries an error of order `rtol |I|`).
pub(super) const ENERGY_SLACK: f64 = 1e3;

/// The work of friction over one stage of a free impact, from its start `y0` and end `y1`: the
/// kinetic energy change $(\mathbf V_0, \Delta\mathbf I) + \tfrac12(\mathbf B\Delta\mathbf I,
/// \Delta\mathbf I)$ less the normal work $\int V_n\,d\chi$ (state 6). It is never positive
/// (the friction opposes the slip, or a stick does no work); a positive one is a slip pushed
/// along by its own friction, reported as an inconsistency at the stage's end.
pub(super) fn friction_work_check(
    b: &Matrix3<f64>,
    y0: &[f64],
    y1: &[f64],
    rtol: f64,
    scale: f64,
    chi: f64,
) -> Result<(), ImpactError> {
    let v0 = Vector3::new(y0[0], y0[1], y0[2]);
    let di = Vector3::new(y1[3] - y0[3], y1[4] - y0[4], y1[5] - y0[5]);
    let work = v0.dot(&di) + 0.5 * di.dot(&(b * di)) - (y1[6] - y0[6]);
    // (and the rounding of the differences of the running totals it is taken from)
    let i1 = Vector3::new(y1[3], y1[4], y1[5]);
    let rounding = 64.0 * f64::EPSILON * (y1[6].abs() + scale * i1.norm());
    if work > ENERGY_SLACK * rtol * scale * di.norm() + rounding {
        return Err(ImpactError::Inconsistent {
            chi,
            what: format!(
                "friction did positive work {work:.6e} J over the stage from normal impulse {:e} N s (a slip driven by its own friction)",
                y0[5]
            ),
        });
    }
    Ok(())
}
