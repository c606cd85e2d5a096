//! The events of one stage of the impact, as owned specifications (a name, a boxed event
//! function, a direction, and the ray it belongs to): the stage's end (compression's end or the
//! restitution condition of 002_b53e4779673eb6ed.txt section 1), the slip at C stopping, dying on
//! a ray or settling on one, and the switches of the support at A (sections 3-4). Every one stops
//! the solve.

use super::*;
use crate::integrate::Direction;
use nalgebra::Vector3;

/// An event function of the normal impulse and the state.
pub(super) type EventFn<'a> = Box<dyn Fn(f64, &[f64]) -> f64 + 'a>;

/// One event of a stage.
pub(super) struct Spec<'a> {
    /// What fired (the driver decides on it).
    pub(super) name: &'static str,
    /// $g(\chi, y)$.
    pub(super) g: EventFn<'a>,
    /// Which crossings count.
    pub(super) direction: Direction,
    /// The slip ray the event belongs to, if any.
    pub(super) ray: Option<Vector3<f64>>,
}

fn spec<'a>(name: &'static str, g: EventFn<'a>, direction: Direction) -> Spec<'a> {
    Spec {
        name,
        g,
        direction,
        ray: None,
    }
}

/// What the stage's events need of the impact, besides the system itself.
pub(super) struct StageView<'a> {
    pub(super) sys: &'a Keller,
    pub(super) y: &'a [f64],
    pub(super) law: Law,
    pub(super) e: f64,
    /// $V_n^-$.
    pub(super) vn0: f64,
    /// The normal impulse and the normal work at the end of compression, once it has ended.
    pub(super) compression: Option<(f64, f64)>,
    pub(super) scale: f64,
    pub(super) rtol: f64,
    pub(super) stop_a: f64,
    /// The slip's stop at C (see [`super::driver`]).
    pub(super) slip_stop: f64,
    /// The stable rays a slip at C may die on.
    pub(super) rays: &'a [Vector3<f64>],
    /// Whether the ray events are armed.
    pub(super) ray_armed: bool,
}

/// The stage's end: compression's end ($V_n = 0$), then the restitution condition of the law.
pub(super) fn stage_end<'a>(v: &StageView<'a>) -> Spec<'a> {
    let (n, law, e, vn0, compression) = (v.sys.n, v.law, v.e, v.vn0, v.compression);
    let g = move |chi: f64, y: &[f64]| {
        let vn = Vector3::new(y[0], y[1], y[2]).dot(&n);
        match (compression, law) {
            (None, _) => vn,
            (Some(_), Law::Newton) => vn + e * vn0,
            (Some((chi_c, _)), Law::Poisson) => chi - (1.0 + e) * chi_c,
            (Some((_, w_c)), Law::Energetic) => y[6] - w_c * (1.0 - e * e),
        }
    };
    spec("stage end", Box::new(g), Direction::Rising)
}

/// The events of a slip at C: it stops; it stops along its own line; it dies on one of the
/// stable rays (`slip dies on its ray`), or settles on one (its friction direction is then held
/// there). The line is the slip's direction at the stage's start.
pub(super) fn slip_events<'a>(v: &StageView<'a>, line0: Vector3<f64>) -> Vec<Spec<'a>> {
    let (n, scale, slip_stop) = (v.sys.n, v.scale, v.slip_stop);
    let mut out = vec![
        spec(
            "slip stops",
            Box::new(move |_chi: f64, y: &[f64]| {
                let vv = Vector3::new(y[0], y[1], y[2]);
                (vv - n * vv.dot(&n)).norm() - slip_stop
            }),
            Direction::Falling,
        ),
        // a slip that dies along a straight line (a planar impact, a symmetric body, a slip on
        // a ray the scan does not count as stable) reaches |V_t| = 0 with a corner the steps may
        // pass over, whether or not its line is a stable ray; its component along its direction
        // at the stage's start falls through zero at a simple root (where the slip turned
        // instead, it slips on: a new stage takes its new line); a slip held on a ray has the
        // ray's own event
        spec(
            "slip stops along its line",
            Box::new(move |_chi: f64, y: &[f64]| {
                if line0 == Vector3::zeros() {
                    scale
                } else {
                    Vector3::new(y[0], y[1], y[2]).dot(&line0) - slip_stop
                }
            }),
            Direction::Falling,
        ),
    ];
    // when the slip dies out along a stable ray, |V_t| reaches zero with a corner and the
    // integrator overshoots it by more than slip_stop within a step, so |V_t| - slip_stop may
    // never be seen negative; the speed along the ray falls through zero at a simple root
    // (disarmed, constant, after it fired off the ray, until the slip settles or stops); one
    // event per stable ray the slip can die on: with a large mu there may be two, and a slip
    // settles on the one its start leads to
    let live: Vec<Vector3<f64>> = match v.sys.mode {
        Mode::Ray(u) => vec![u],
        _ => v.rays.to_vec(),
    };
    let armed = v.ray_armed;
    for &ray in &live {
        out.push(Spec {
            name: "slip dies on its ray",
            g: Box::new(move |_chi: f64, y: &[f64]| {
                if armed {
                    Vector3::new(y[0], y[1], y[2]).dot(&ray) - slip_stop
                } else {
                    scale
                }
            }),
            direction: Direction::Falling,
            ray: Some(ray),
        });
    }
    // once the slip lies on that ray to within 1e-2 rtol of the velocity scale and 1e-6 rad
    // (its component across the ray), the friction direction is frozen along it: the true
    // direction only converges further, while keeping it free makes the system ever stiffer as
    // |V_t| goes to zero (the turning rate grows like 1/|V_t|)
    if v.sys.mode == Mode::Slip {
        let across = 1e-2 * v.rtol * scale;
        for &ray in &live {
            out.push(Spec {
                name: "slip settles on its ray",
                g: Box::new(move |_chi: f64, y: &[f64]| {
                    let vv = Vector3::new(y[0], y[1], y[2]);
                    let vt = vv - n * vv.dot(&n);
                    if vt.dot(&ray) <= 0.0 {
                        return scale;
                    }
                    // across the ray: below 1e-2 rtol scale, and a small angle (not merely a
                    // small slip)
                    (vt - ray * vt.dot(&ray)).norm() - across.min(1e-6 * vt.norm())
                }),
                direction: Direction::Falling,
                ray: Some(ray),
            });
        }
    }
    out
}

/// The support's switches (002 section 4) for its current mode: its slip stops, its rolling
/// reaction leaves the friction cone or would pull, it would push again after letting go; and
/// at C a held slip that is established, or a stick the support's motion breaks.
pub(super) fn support_events<'a>(v: &StageView<'a>) -> Vec<Spec<'a>> {
    let Some(r) = v.sys.at_a.as_ref() else {
        return Vec::new();
    };
    let (sys, stop_a, n, mu) = (v.sys, v.stop_a, v.sys.n, v.sys.mu);
    let force = move |y: &[f64]| sys.rate(&Vector3::new(y[0], y[1], y[2]), &va_of(y));
    // -alpha of (3.6): the support lets go where alpha turns positive (a rolling reaction that
    // would pull leaves the cone first)
    let minus_alpha = move || -> EventFn<'a> {
        Box::new(move |_chi: f64, y: &[f64]| (r.b_tilde * force(y)).dot(&r.normal))
    };
    // beta of (4.4) falling to zero as the slide turns: the reaction grows without bound
    let beta = move |sign: f64| -> EventFn<'a> {
        Box::new(move |_chi: f64, y: &[f64]| r.slide_i(&va_of(y)).1 - sign * BETA_FLOOR * r.beta_n)
    };
    let mut out = Vec::new();
    match r.mode {
        SupportMode::Slide if r.regular > 0.0 => {
            out.push(spec("support beta vanishes", beta(1.0), Direction::Falling));
            out.push(spec("support lets go", minus_alpha(), Direction::Falling));
        }
        SupportMode::Slide => {
            if r.rough() {
                out.extend(rough_slide_events(v, r));
                if r.slide_i(&va_of(v.y)).1 < 0.0 {
                    // the sliding branch of a two-solution case (beta of (4.4) < 0): its reaction
                    // -alpha/beta stays positive only while alpha > 0, and grows without bound as
                    // beta rises to 0; either ends it (without these the reaction was clipped to
                    // zero and A went through the support: tests/regression_constrained_seeds.rs)
                    out.push(spec(
                        "support's sliding branch ends",
                        minus_alpha(),
                        Direction::Rising,
                    ));
                    out.push(spec("support beta vanishes", beta(-1.0), Direction::Rising));
                }
                out.push(held_or_dying(v, r));
            }
            out.push(spec("support lets go", minus_alpha(), Direction::Falling));
        }
        SupportMode::Roll => {
            let cone = move |_chi: f64, y: &[f64]| {
                let fs = r.roll_reaction(&force(y));
                let fs_n = fs.dot(&r.normal);
                (fs - r.normal * fs_n).norm() - r.mu * fs_n
            };
            out.push(spec(
                "support starts to slide",
                Box::new(cone),
                Direction::Rising,
            ));
            out.push(spec("support lets go", minus_alpha(), Direction::Falling));
        }
        // a free body comes back down onto the support (an approach slower than stop_a is
        // taken as arriving)
        SupportMode::Free => out.push(spec(
            "support reached again",
            Box::new(move |_chi: f64, y: &[f64]| va_of(y).dot(&r.normal) + stop_a),
            Direction::Falling,
        )),
    }
    // a held slip at C is freed once it exceeds the velocity tolerance
    let established = RELEASE_ABOVE * stop_a;
    if let Mode::Held(_) = sys.mode {
        let slip_stop = v.slip_stop;
        let slip = move |y: &[f64]| {
            let vv = Vector3::new(y[0], y[1], y[2]);
            (vv - n * vv.dot(&n)).norm()
        };
        out.push(spec(
            "slip stops",
            Box::new(move |_chi: f64, y: &[f64]| slip(y) - slip_stop),
            Direction::Falling,
        ));
        out.push(spec(
            "slip at C established",
            Box::new(move |_chi: f64, y: &[f64]| slip(y) - established),
            Direction::Rising,
        ));
    }
    if r.rough() && matches!(sys.mode, Mode::Stick(_)) && mu > 0.0 {
        let stick = move |_chi: f64, y: &[f64]| {
            let b_now = sys.b_stick(&va_of(y));
            stick_tau(&b_now, &n).map_or(mu, |t| t.norm()) - mu * (1.0 + 1e-9)
        };
        out.push(spec(
            "stick at C breaks",
            Box::new(stick),
            Direction::Rising,
        ));
    }
    out
}

/// The events of a rough support's slide at A: the slip stops (or stops along the line it had
/// at the stage's start: a slip dying along a line reaches |V_A,T| = 0 with a corner the steps
/// may pass over), and beta of (4.4) falls to its floor.
fn rough_slide_events<'a>(v: &StageView<'a>, r: &'a AtA) -> Vec<Spec<'a>> {
    let stop_a = v.stop_a;
    let dir0 = r.slide_dir(&va_of(v.y));
    vec![
        spec(
            "support slip stops",
            Box::new(move |_chi: f64, y: &[f64]| r.tangential(&va_of(y)).norm() - stop_a),
            Direction::Falling,
        ),
        spec(
            "support slip stops along its line",
            Box::new(move |_chi: f64, y: &[f64]| va_of(y).dot(&dir0) - stop_a),
            Direction::Falling,
        ),
        spec(
            "support beta vanishes",
            Box::new(move |_chi: f64, y: &[f64]| r.slide_i(&va_of(y)).1 - BETA_FLOOR * r.beta_n),
            Direction::Falling,
        ),
    ]
}

/// A held slide at A is established (its direction freed) above [`RELEASE_ABOVE`] stops; a free
/// one that falls below [`HOLD_BELOW`] stops has its direction held.
fn held_or_dying<'a>(v: &StageView<'a>, r: &'a AtA) -> Spec<'a> {
    let stop_a = v.stop_a;
    let slip = move |y: &[f64]| r.tangential(&va_of(y)).norm();
    if r.held {
        let established = RELEASE_ABOVE * stop_a;
        spec(
            "support slip established",
            Box::new(move |_chi: f64, y: &[f64]| slip(y) - established),
            Direction::Rising,
        )
    } else {
        spec(
            "support slip nearly stops",
            Box::new(move |_chi: f64, y: &[f64]| slip(y) - HOLD_BELOW * stop_a),
            Direction::Falling,
        )
    }
}
