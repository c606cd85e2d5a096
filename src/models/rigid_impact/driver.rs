//! The impact driven stage by stage: the events of each stage (compression's end, restitution's
//! condition, the slip's stops, the support's switches), the decisions between stages, and the
//! solver-consistency checks (friction never does positive work, energy never grows under the
//! energetic law, A never goes through its support).

use super::events::{StageView, slip_events, stage_end, support_events};
use super::*;
use crate::integrate::{Event, Method, Options, Stop, solve};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// The mode of a slip that starts from rest along the ray `sys.u_hint` ([`stick_or_slide`]'s
/// slide direction: $P_t\mathbf B(\mathbf n - \mu\mathbf u) = \kappa\mathbf u$, $\kappa > 0$).
/// Without a support the matrix is constant and the slip grows along that ray exactly, so its
/// friction direction is held there: left free, a slip that grows slowly (mu just below the
/// critical value, kappa near 0) stays near zero for long, where its direction's turning rate
/// grows like $1/|\mathbf V_t|$, and the steps collapse (`models::samples::rigid_sample`'s degenerate cases,
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
/// whether its start mode is forced. Runs stage by stage: the decisions between stages
/// ([`Run::between_stages`]), one stage's integration to its first event ([`Run::stage`]) and
/// what that event means ([`Run::after_stage`]).
pub(super) fn impact_core(
    b: &Matrix3<f64>,
    at_a: Option<(AtA, Vector3<f64>, bool)>,
    contact: Contact,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let inputs = Inputs::checked(b, at_a.as_ref(), contact, rtol)?;
    let mut run = Run::new(inputs, at_a)?;
    let mut first = true;
    loop {
        if !first {
            run.between_stages()?;
        }
        first = false;
        run.last_fired.clear();
        if run.before_stage()? == Flow::Done {
            break;
        }
        let Some(end) = run.stage()? else {
            continue;
        };
        if run.after_stage(end)? == Flow::Done {
            break;
        }
    }
    run.finish()
}

/// The impact's data, checked, and the scales derived from them.
struct Inputs {
    b: Matrix3<f64>,
    n: Vector3<f64>,
    v_minus: Vector3<f64>,
    /// $V_n^-$ (< 0).
    vn0: f64,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
    /// $|\mathbf V^-|$.
    scale: f64,
    /// The least eigenvalue of B (and of B* with a support: Proposition 3), and the largest.
    lmin: f64,
    lmax: f64,
    lam_floor: f64,
    /// The largest normal impulse integrated to.
    chi_max: f64,
    /// The slip at A taken to have stopped, as at C, far below the tolerance.
    stop_a: f64,
}

impl Inputs {
    fn checked(
        b: &Matrix3<f64>,
        at_a: Option<&(AtA, Vector3<f64>, bool)>,
        contact: Contact,
        rtol: f64,
    ) -> Result<Self, ImpactError> {
        let Contact {
            normal,
            v_minus,
            mu,
            law,
            e,
        } = contact;
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
        // Proposition 3 of 002: with a support the bound takes the smaller of the least
        // eigenvalues of B and B* (the support's reaction can make the impulse larger than B
        // alone allows)
        let lmin = match at_a {
            Some((a, _, _)) => {
                let w = a.b_tilde.transpose() * a.normal;
                let b_star = b - w * w.transpose() / a.beta_n;
                lmin.min(SymmetricEigen::new(b_star).eigenvalues.min())
            }
            None => lmin,
        };
        let lam_floor = lmax * 1e-12;
        let scale = v_minus.norm();
        Ok(Inputs {
            b,
            n,
            v_minus,
            vn0,
            mu,
            law,
            e,
            rtol,
            scale,
            lmin,
            lmax,
            lam_floor,
            chi_max: 20.0 * 2.0 * scale / lmin.max(lam_floor).max(lmax * 1e-6),
            stop_a: (10.0 * 1e-13 * scale).max(1e-2 * rtol * scale),
        })
    }
}

/// Whether the impact goes on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flow {
    Next,
    Done,
}

/// What a stage ended with.
struct StageEnd {
    stop: Stop,
    /// The event's name ("" at the end of the window).
    fired: &'static str,
    /// The ray the event belongs to, if any.
    ray: Option<Vector3<f64>>,
    /// The slip at C when the stage began.
    vt_start: Vector3<f64>,
}

/// The impact between its stages.
struct Run {
    k: Inputs,
    sys: Keller,
    /// $(\mathbf V_C, \mathbf I, \int V_n\,d\chi, \mathbf I^*[, \mathbf V_A])$.
    y: Vec<f64>,
    chi: f64,
    phases: Vec<Phase>,
    support_phases: Vec<Phase>,
    path: Vec<(f64, [f64; 3])>,
    stats: crate::integrate::Stats,
    /// The stable rays a slip at C may die on, for the support's current mode.
    rays: Vec<Vector3<f64>>,
    /// The matrix that governs C's stick/slip switch.
    b_stick: Matrix3<f64>,
    ray_armed: bool,
    /// The normal impulse and normal work at the end of compression.
    compression: Option<(f64, f64)>,
    cut_off: bool,
    switches: usize,
    band_switches: usize,
    last_fired: String,
}

impl Run {
    /// The state at the start: the support's mode decided (with C's stick where C does not
    /// slip), then C's mode.
    fn new(k: Inputs, at_a: Option<(AtA, Vector3<f64>, bool)>) -> Result<Self, ImpactError> {
        let forced_start = at_a.as_ref().is_some_and(|r| r.2);
        let v_a0 = at_a.as_ref().map(|r| r.1);
        let sys = Keller {
            at_a: at_a.map(|(mut r, _, _)| {
                r.floor = 1e-13 * k.scale;
                r
            }),
            b: k.b,
            n: k.n,
            mu: k.mu,
            mode: Mode::Slip,
            u_hint: Vector3::zeros(),
            floor: 1e-13 * k.scale,
        };
        let v = k.v_minus;
        let mut run = Run {
            y: vec![v.x, v.y, v.z, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            sys,
            k,
            chi: 0.0,
            phases: Vec::new(),
            support_phases: Vec::new(),
            path: Vec::new(),
            stats: crate::integrate::Stats::default(),
            rays: Vec::new(),
            b_stick: Matrix3::zeros(),
            ray_armed: true,
            compression: None,
            cut_off: false,
            switches: 0,
            band_switches: 0,
            last_fired: String::new(),
        };
        if let Some(va) = v_a0 {
            run.start_support(va, forced_start)?;
        }
        run.start_at_c()?;
        run.rays = run.find_rays();
        run.b_stick = run.sys.b_stick(&va_of(&run.y));
        Ok(run)
    }

    /// The support's mode at the start.
    fn start_support(&mut self, va: Vector3<f64>, forced_start: bool) -> Result<(), ImpactError> {
        let (sys, stop_a) = (&mut self.sys, self.k.stop_a);
        self.y.extend_from_slice(va.as_slice());
        // with no slip at C, C's stick (or slide from rest) and the support's motion are one
        // problem ([`c_direction_with`] decides C's for each of the support's modes): the
        // support was decided on C's frictionless direction n before, and a stick at C then
        // taken with the contact matrix B* while the support, pulled by it, gave nothing (the
        // stick slid, and the energy grew under the energetic law: tests/regression_constrained_seeds.rs)
        if self.k.mu > 0.0 && sys.tangential(&self.k.v_minus).norm() <= sys.floor {
            sys.mode = Mode::Stick(Vector3::zeros());
        }
        let slide_from_rest = sys.at_a.as_ref().is_some_and(|r| {
            r.rough() && r.mode == SupportMode::Slide && r.tangential(&va).norm() <= stop_a
        });
        if !forced_start {
            decide_support(sys, &mut self.y, stop_a, 0.0, false, stop_a)?;
        } else if slide_from_rest {
            // a forced slide from rest: in the direction (4.5) gives
            let f = sys.rate(&self.k.v_minus, &va);
            let r = sys.at_a.as_mut().expect("support");
            let (e, _, _) = start_slide_dirs(r, &f)
                .into_iter()
                .max_by(|a, b| {
                    (a.2, a.1)
                        .partial_cmp(&(b.2, b.1))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .ok_or_else(|| no_support_motion(0.0, "(4.5) has no slide direction"))?;
            r.hint = e;
            r.held = true;
            self.y[10..13].copy_from_slice((e * (20.0 * stop_a)).as_slice());
        }
        if let Some(r) = &self.sys.at_a {
            self.support_phases.push(Phase {
                kind: r.phase_name().into(),
                normal_impulse: 0.0,
            });
        }
        Ok(())
    }

    /// C's mode at the start: a slip, or at zero slip a stick or a slide from rest.
    fn start_at_c(&mut self) -> Result<(), ImpactError> {
        let (mu, n) = (self.k.mu, self.k.n);
        let sys = &mut self.sys;
        let vt0 = sys.tangential(&self.k.v_minus);
        let kind = if vt0.norm() <= sys.floor && mu > 0.0 {
            let va = va_of(&self.y);
            let b_stick = sys.b_stick(&va);
            let decided = {
                let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
                stick_or_slide(&b_stick, &rate_of, &n, mu)
            };
            match decided {
                Ok(tau) => {
                    sys.mode = Mode::Stick(tau);
                    "stick"
                }
                Err(u) => {
                    sys.u_hint = slide_at_c(u, sys.at_a.is_some(), &n, 0.0)?;
                    sys.mode = from_rest(sys);
                    "slip"
                }
            }
        } else {
            if vt0.norm() <= sys.floor {
                // frictionless at zero slip: the mode the decision above would have left
                sys.mode = Mode::Slip;
            }
            "slip"
        };
        self.phases.push(Phase {
            kind: kind.into(),
            normal_impulse: 0.0,
        });
        Ok(())
    }

    /// The stable rays a dying slip at C may settle on: B* (or B) and mu are fixed while the
    /// support keeps its mode, so they are found once per mode of the support.
    fn find_rays(&self) -> Vec<Vector3<f64>> {
        let va = va_of(&self.y);
        let rate_of = |f: &Vector3<f64>| self.sys.rates(f, &va).0;
        if self.k.mu > 0.0 {
            decay_rays(&rate_of, &self.k.n, self.k.mu)
        } else {
            Vec::new()
        }
    }

    /// The slip at C taken to have stopped, far below the tolerance: when the slip spirals into
    /// zero (anisotropic B) its direction turns ever faster and the steps shrink with |V_t|, so
    /// chasing it down to the round-off floor costs unbounded steps; stopping at 1e-2 rtol x the
    /// velocity scale changes the impulse by less than that.
    fn slip_stop(&self) -> f64 {
        (10.0 * self.sys.floor).max(1e-2 * self.k.rtol * self.k.scale)
    }

    fn v(&self) -> Vector3<f64> {
        Vector3::new(self.y[0], self.y[1], self.y[2])
    }

    /// The decisions after every stop: the support's motion (a switch at C changes alpha at
    /// once, which no event can see as a crossing), and C's stick after every change of the
    /// support; the rays and C's matrix follow a rough support's slide.
    fn between_stages(&mut self) -> Result<(), ImpactError> {
        if self.sys.at_a.is_some() {
            self.decide_support_between()?;
        }
        // a rough support that slides turns the matrix of C's slip with its slide direction:
        // the ray a dying slip settles on moves with it
        if let Some(a) = &self.sys.at_a
            && a.rough()
            && a.mode == SupportMode::Slide
        {
            self.rays = self.find_rays();
            self.b_stick = self.sys.b_stick(&va_of(&self.y));
        }
        Ok(())
    }

    fn decide_support_between(&mut self) -> Result<(), ImpactError> {
        let (stop_a, chi) = (self.k.stop_a, self.chi);
        let last = self.last_fired.as_str();
        let before = self.sys.at_a.as_ref().map(|r| r.mode);
        let leaving_roll = last == "support starts to slide";
        // after the slip at A was seen to stop (or to turn off its frozen direction), what is
        // left of it in the band where its direction is held (HOLD_BELOW stop) is no slip:
        // deciding on it would chatter about zero, a slip held there turning away from its
        // frozen direction again and again
        let rest_below = if last.starts_with("support slip stops") {
            HOLD_BELOW * stop_a
        } else {
            stop_a
        };
        decide_support(
            &mut self.sys,
            &mut self.y,
            stop_a,
            chi,
            leaving_roll,
            rest_below,
        )?;
        if last == "support slip nearly stops"
            && let Some(r) = self.sys.at_a.as_mut()
            && r.mode == SupportMode::Slide
        {
            // frozen at the slip's own direction (decide_support set it as the hint)
            r.held = true;
        }
        let after = self.sys.at_a.as_ref().map(|r| r.mode);
        let restarted = last.starts_with("support slip stops") || last == "support starts to slide";
        if let (Some(m), Some(r)) = (after, &self.sys.at_a)
            && (after != before || (restarted && m == SupportMode::Slide))
        {
            self.support_phases.push(Phase {
                kind: r.phase_name().into(),
                normal_impulse: chi,
            });
        }
        if after != before || last.starts_with("support") || last == "stick at C breaks" {
            // the matrices of C's stick/slip switch change with the support's mode
            self.b_stick = self.sys.b_stick(&va_of(&self.y));
            self.rays = self.find_rays();
            self.ray_armed = true;
            if let Mode::Stick(_) = self.sys.mode {
                self.restick_at_c()?;
            }
        }
        Ok(())
    }

    /// C's stick decided again under the support's new mode: it sticks on, or slides from rest
    /// in the direction the dynamics give, held there until the slip is established.
    fn restick_at_c(&mut self) -> Result<(), ImpactError> {
        let (mu, n) = (self.k.mu, self.k.n);
        let va = va_of(&self.y);
        let decided = {
            let sys = &self.sys;
            let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
            stick_or_slide(&self.b_stick, &rate_of, &n, mu)
        };
        match decided {
            Ok(tau) => self.sys.mode = Mode::Stick(tau),
            Err(u) => {
                let u = slide_at_c(u, true, &n, self.chi)?;
                self.sys.u_hint = u;
                self.sys.mode = Mode::Held(u);
                let v = self.v();
                let vnew = v - self.sys.tangential(&v) + u * (20.0 * self.slip_stop());
                self.y[..3].copy_from_slice(vnew.as_slice());
                self.phases.push(Phase {
                    kind: "slip".into(),
                    normal_impulse: self.chi,
                });
            }
        }
        Ok(())
    }

    /// Counts the stage, and ends the impact where it is cut off or its end condition already
    /// holds.
    fn before_stage(&mut self) -> Result<Flow, ImpactError> {
        self.switches += 1;
        if self.switches > 10_000 {
            return Err(ImpactError::NoEnd {
                law: format!(
                    "{} (more than 10000 stick/slip switches at normal impulse {:e})",
                    self.k.law.name(),
                    self.chi
                ),
                chi_max: self.k.chi_max,
            });
        }
        if let Mode::Stick(tau) = self.sys.mode
            && (self.b_stick * (self.k.n + tau)).norm() <= 1e-10 * self.k.lmax
        {
            // the velocity no longer changes while the reaction grows: a cut-off impact
            self.cut_off = true;
            return Ok(Flow::Done);
        }
        if self.compression.is_some() {
            let end = stage_end(&self.view());
            if (end.g)(self.chi, &self.y) >= 0.0 {
                return Ok(Flow::Done);
            }
        }
        Ok(Flow::Next)
    }

    fn view(&self) -> StageView<'_> {
        StageView {
            sys: &self.sys,
            y: &self.y,
            law: self.k.law,
            e: self.k.e,
            vn0: self.k.vn0,
            compression: self.compression,
            scale: self.k.scale,
            rtol: self.k.rtol,
            stop_a: self.k.stop_a,
            slip_stop: self.slip_stop(),
            rays: &self.rays,
            ray_armed: self.ray_armed,
        }
    }

    /// Integrates one stage to its first event; `None` where the solver could not follow a
    /// rough support's exact law and the stage is to be run again with it regularised.
    fn stage(&mut self) -> Result<Option<StageEnd>, ImpactError> {
        let (k, slip_stop) = (&self.k, self.slip_stop());
        let v = self.v();
        let vt_start = v - k.n * v.dot(&k.n);
        let solved = {
            let view = self.view();
            let line0 = if vt_start.norm() > 10.0 * slip_stop && self.sys.mode == Mode::Slip {
                vt_start.normalize()
            } else {
                Vector3::zeros()
            };
            let mut specs = vec![stage_end(&view)];
            if matches!(self.sys.mode, Mode::Slip | Mode::Ray(_)) && k.mu > 0.0 {
                specs.extend(slip_events(&view, line0));
            }
            specs.extend(support_events(&view));
            let events: Vec<Event> = specs
                .iter()
                .map(|s| Event::new(s.name, &*s.g, s.direction, true))
                .collect();
            let opts = Options {
                rtol: k.rtol,
                atol: k.rtol * k.scale * 1e-3,
                // the regularised band is stiff (its rate is the friction's over the band) in a
                // way the explicit method's stiffness test does not always see: Radau5 from the
                // start
                method: if self.sys.at_a.as_ref().is_some_and(|r| r.regular > 0.0) {
                    Method::Radau5
                } else {
                    Method::Auto
                },
                events,
                trajectory: true,
                ..Options::default()
            };
            solve(&self.sys, self.chi, &self.y, k.chi_max, &opts).map(|sol| {
                let (fired, ray) = match sol.stop {
                    Stop::Event { index, .. } => (specs[index].name, specs[index].ray),
                    Stop::End => ("", None),
                };
                (sol, fired, ray)
            })
        };
        let (sol, fired, ray) = match solved {
            Ok(x) => x,
            Err(e) => {
                // a rough support in contact whose exact law the solver could not follow (a slip
                // at A hovering at the edge of its band, its direction stiff without bound):
                // the stage again with the support's friction regularised, else the failure
                if let Some(r) = self.sys.at_a.as_mut()
                    && r.rough()
                    && r.regular == 0.0
                    && r.mode != SupportMode::Free
                {
                    r.regularise(RELEASE_ABOVE * self.k.stop_a);
                    self.support_phases.push(Phase {
                        kind: r.phase_name().into(),
                        normal_impulse: self.chi,
                    });
                    self.last_fired = "support regularised".into();
                    return Ok(None);
                }
                return Err(e.into());
            }
        };
        self.stats = self.stats + sol.stats;
        self.consistent(&sol.y, sol.t)?;
        self.path
            .extend(sol.trajectory.iter().map(|(c, y)| (*c, [y[0], y[1], y[2]])));
        self.chi = sol.t;
        self.y = sol.y;
        self.last_fired = fired.to_string();
        Ok(Some(StageEnd {
            stop: sol.stop,
            fired,
            ray,
            vt_start,
        }))
    }

    /// The laws a stage must keep: friction never does positive work (free impacts), and a
    /// support in contact holds A on it (a reaction the law clipped to zero, the sliding branch
    /// of a Painleve case whose alpha changed sign unseen, let A through it).
    fn consistent(&self, y1: &[f64], chi: f64) -> Result<(), ImpactError> {
        let k = &self.k;
        if self.sys.at_a.is_none() {
            friction_work_check(&k.b, &self.y, y1, k.rtol, k.scale, chi)?;
        }
        if let Some(r) = &self.sys.at_a
            && r.mode != SupportMode::Free
            && va_of(y1).dot(&r.normal) < -1e4 * k.stop_a
        {
            return Err(ImpactError::Inconsistent {
                chi,
                what: format!(
                    "A went into the support at {:.3e} m/s while in contact ({}); its reaction could not hold it",
                    -va_of(y1).dot(&r.normal),
                    r.phase_name()
                ),
            });
        }
        Ok(())
    }

    /// Whether a slip that fired a stop event with `vt_start` at the stage's start has turned
    /// off its line (or ray) rather than stopped: more than 10 stops left, and either more than
    /// [`TURNED_ABOVE`] stops or a tenth of its start (a slip that starts from a nudge and turns
    /// keeps its size).
    fn turned(&self, vt_start: &Vector3<f64>) -> bool {
        let slip_stop = self.slip_stop();
        let left = self.sys.tangential(&self.v()).norm();
        left > 10.0 * slip_stop
            && (left > TURNED_ABOVE * slip_stop || left >= 0.1 * vt_start.norm())
    }

    /// What the stage's event means: the support switches (decided between stages), compression
    /// ends, the impact ends, the slip settles on a ray, turns, or stops.
    fn after_stage(&mut self, end: StageEnd) -> Result<Flow, ImpactError> {
        let fired = end.fired;
        if fired.starts_with("support slip") {
            self.band_switches += 1;
            if self.band_switches > REGULARISE_AFTER
                && let Some(r) = self.sys.at_a.as_mut()
                && r.regular == 0.0
            {
                r.regularise(RELEASE_ABOVE * self.k.stop_a);
                self.support_phases.push(Phase {
                    kind: r.phase_name().into(),
                    normal_impulse: self.chi,
                });
            }
        }
        if fired.starts_with("support") || fired == "stick at C breaks" {
            return Ok(Flow::Next);
        }
        if fired == "slip at C established" {
            self.sys.mode = Mode::Slip;
            return Ok(Flow::Next);
        }
        let slip_stop = self.slip_stop();
        match end.stop {
            Stop::End => Err(ImpactError::NoEnd {
                law: self.k.law.name().into(),
                chi_max: self.k.chi_max,
            }),
            Stop::Event { index: 0, .. } => {
                if self.compression.is_some() {
                    return Ok(Flow::Done);
                }
                self.compression = Some((self.chi, self.y[6]));
                // a zero-e law ends with compression
                Ok(if self.k.e == 0.0 {
                    Flow::Done
                } else {
                    Flow::Next
                })
            }
            // the slip turned off its line without stopping: on, along its new line. What is
            // left across the line is a slip through zero (a stop) where it is below
            // TURNED_ABOVE stops and a tenth of the slip at the stage's start
            Stop::Event { .. }
                if fired == "slip stops along its line" && self.turned(&end.vt_start) =>
            {
                Ok(Flow::Next)
            }
            Stop::Event { .. }
                if fired == "slip settles on its ray"
                    && end.ray.is_some_and(|ray| {
                        self.sys.tangential(&self.v()).dot(&ray) > 10.0 * slip_stop
                    }) =>
            {
                self.sys.mode = Mode::Ray(end.ray.unwrap_or_default());
                self.ray_armed = true;
                Ok(Flow::Next)
            }
            // the slip crossed the ray's normal line off the ray, away from zero (by more than a
            // stop, as for its own line: TURNED_ABOVE; a slip left below that bends onto a
            // nearly neutral ray and creeps, seed 899244 of constrained_fail): slip on, with its
            // own direction, without the ray event (it would fire again at once) until the slip
            // settles
            Stop::Event { .. } if fired == "slip dies on its ray" && self.turned(&end.vt_start) => {
                self.ray_armed = false;
                self.sys.mode = Mode::Slip;
                Ok(Flow::Next)
            }
            Stop::Event { .. } => {
                self.at_slip_stop()?;
                Ok(Flow::Next)
            }
        }
    }

    /// The slip at C stopped: stick, or slide again in the direction the dynamics give (a
    /// reversal), with the support letting go where C can do neither under its push.
    fn at_slip_stop(&mut self) -> Result<(), ImpactError> {
        let (mu, n, chi) = (self.k.mu, self.k.n, self.chi);
        self.ray_armed = true;
        let va = va_of(&self.y);
        let mut decided = {
            let sys = &self.sys;
            let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
            stick_or_slide(&self.b_stick, &rate_of, &n, mu)
        };
        // neither with the support pushing: C's stick and the support's contact are one
        // complementarity problem; the support letting go (where C's motion under the free
        // matrix then has alpha of (3.6) >= 0) is its other branch
        if let (Err(None), Some(a)) = (decided, self.sys.at_a.as_mut())
            && a.mode != SupportMode::Free
        {
            let before = std::mem::replace(&mut a.mode, SupportMode::Free);
            let freed = {
                let sys = &self.sys;
                let rate_of = |f: &Vector3<f64>| sys.rates(f, &va).0;
                stick_or_slide(&self.k.b, &rate_of, &n, mu)
            };
            let f = match freed {
                Ok(tau) => Some(n + tau),
                Err(Some(u)) => Some(n - u * mu),
                Err(None) => None,
            };
            let lets_go = self
                .sys
                .at_a
                .as_ref()
                .zip(f)
                .is_some_and(|(a, f)| -(a.b_tilde * f).dot(&a.normal) >= 0.0);
            if lets_go {
                decided = freed;
                self.b_stick = self.k.b;
                self.rays = self.find_rays();
                if let Some(a) = &self.sys.at_a {
                    self.support_phases.push(Phase {
                        kind: a.phase_name().into(),
                        normal_impulse: chi,
                    });
                }
            } else if let Some(a) = self.sys.at_a.as_mut() {
                a.mode = before;
            }
        }
        let kind = match decided {
            Ok(tau) => {
                self.sys.mode = Mode::Stick(tau);
                "stick"
            }
            Err(u) => {
                let u = slide_at_c(u, self.sys.at_a.is_some(), &n, chi)?;
                self.sys.u_hint = u;
                self.sys.mode = from_rest(&self.sys);
                // nudge past the floor in the new direction so the slip event re-arms: 20
                // slip_stop, far above the absolute tolerance (1e-3 rtol scale), so that
                // integration noise cannot take the slip back under the stop (the switches then
                // chatter), and at most 0.2 rtol scale, under the tolerance
                let v = self.v();
                let vnew = v - self.sys.tangential(&v) + u * (20.0 * self.slip_stop());
                self.y[..3].copy_from_slice(vnew.as_slice());
                "reversal"
            }
        };
        self.phases.push(Phase {
            kind: kind.into(),
            normal_impulse: chi,
        });
        Ok(())
    }

    /// The result, with Stronge's law held to its dissipation: its normal work is (1 - e^2)
    /// that of compression and friction's is never positive.
    fn finish(self) -> Result<ImpactResult, ImpactError> {
        let (k, y) = (&self.k, &self.y);
        let vp = Vector3::new(y[0], y[1], y[2]);
        // the impulse: integral of dI/dchi over chi (its normal component equals chi)
        let imp = Vector3::new(y[3], y[4], y[5]);
        let kelvin = 0.5 * (k.v_minus + vp).dot(&imp);
        let direct = k.v_minus.dot(&imp) + 0.5 * imp.dot(&(k.b * imp));
        if k.law == Law::Energetic
            && self.sys.at_a.is_none()
            && direct > ENERGY_SLACK * k.rtol * k.scale * imp.norm()
        {
            return Err(ImpactError::Inconsistent {
                chi: self.chi,
                what: format!(
                    "the kinetic energy grew by {direct:.6e} J under the energetic law, which dissipates"
                ),
            });
        }
        Ok(ImpactResult {
            cut_off: self.cut_off,
            impulse: [imp.x, imp.y, imp.z],
            v_rel_after: [vp.x, vp.y, vp.z],
            compression_impulse: self.compression.map_or(self.chi, |c| c.0),
            energy_change: direct,
            kelvin_energy_change: kelvin,
            lambda_min: k.lmin,
            lambda_max: k.lmax,
            bound_upper: if k.lmin > k.lam_floor {
                2.0 * k.scale / k.lmin
            } else {
                f64::INFINITY
            },
            bound_lower: k.vn0.abs() / k.lmax,
            phases: self.phases,
            stats: self.stats,
            method: "integrate",
            support_impulse: [y[7], y[8], y[9]],
            support_phases: self.support_phases,
            v_support_after: self.sys.at_a.as_ref().filter(|r| r.rough()).map(|_| {
                let va = va_of(y);
                [va.x, va.y, va.z]
            }),
            path: self.path,
        })
    }
}

/// A slip that crosses the normal line of its stage's direction with less than this many stops
/// left across it (1e-8 of the velocity scale at rtol 1e-10), and under a tenth of the slip the
/// stage began with, has stopped: it passed through zero along a curve (the integration's error
/// about a straight one, or a slip bending onto a nearly neutral ray when mu is just below the
/// critical value, where it would otherwise creep about zero with stiff turning for the rest of
/// the impact: `models::samples::rigid_sample` seed 865738). The velocities change by at most that slip.
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
