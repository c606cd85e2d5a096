//! Events $g(t, y) = 0$, located by root finding on the dense output, not by overshoot.
//!
//! Each accepted step $[t_a, t_b]$ is sampled at 8 equal sub-intervals of the dense output (no
//! extra right-hand-side evaluations), so two sign changes inside one step are both seen unless
//! they are closer than $h/8$. A crossing is refined by the Illinois variant of regula falsi to
//! the floating-point resolution of $t$. The sign of the last non-zero value is tracked per event:
//! a root at $t_0$ (or at a previous event) does not fire again; an exact zero at a sample point
//! fires once. A non-finite $g$ is an error, never an endless loop.
//!
//! One pair of crossings closer than $h/8$ is still seen: the one that starts at the step's
//! start, where $g$ is at (or near: [`near_start`]) a zero and heads back to it, as after an impact
//! map (a ball leaves the floor at $z = -10^{-19}$ and lands again before the first sample: a step
//! after a jump is long when the flight is a polynomial the method integrates exactly). The
//! slope of $g$ at the start, $g$ there and at the first sample fix a parabola ([`may_dip`]);
//! where it dips to the other side, the least $|g|$ of the first sub-interval is searched on the
//! dense output and both crossings are located.

use super::{IntegrateError, Stepper};

/// Which crossings count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// From negative to positive.
    Rising,
    /// From positive to negative.
    Falling,
    /// Either.
    Both,
}

/// An event function with its direction and whether it stops the solve.
pub struct Event<'a> {
    /// Name for reports (borrowed where the caller keeps it: a sweep makes a few events per
    /// point).
    pub name: std::borrow::Cow<'a, str>,
    /// $g(t, y)$.
    pub g: &'a (dyn Fn(f64, &[f64]) -> f64 + 'a),
    /// Which crossings count.
    pub direction: Direction,
    /// Stop the solve when it fires.
    pub terminal: bool,
    /// `Some(i)` when $g(t, y) = y_i$, a component of the state (set by [`Event::reading`]):
    /// the tracker then reads the component and the interpolant's parts directly, without a
    /// call through `g` (two in three of the Hertz impact's event evaluations).
    pub component: Option<usize>,
    /// $g$ at several points in one call (set by [`Event::batched`]): the times, the states one
    /// after another (the state's length each) and the values to write; what `g` gives at each
    /// point, to the bit. [`Tracker::may_cross`] asks it for all its samples at once.
    pub batch: Option<BatchFn<'a>>,
}

/// $g$ at several points: `(ts, ys, out)` as [`Event::batch`] says.
pub type BatchFn<'a> = &'a (dyn Fn(&[f64], &[f64], &mut [f64]) + 'a);

impl<'a> Event<'a> {
    /// A new event.
    pub fn new(
        name: impl Into<std::borrow::Cow<'a, str>>,
        g: &'a (dyn Fn(f64, &[f64]) -> f64 + 'a),
        direction: Direction,
        terminal: bool,
    ) -> Self {
        Event {
            name: name.into(),
            g,
            direction,
            terminal,
            component: None,
            batch: None,
        }
    }

    /// Declares `batch`, which gives $g$ at several points in one call (an interpreted formula
    /// pays its dispatch once for all of them). [`Tracker`] checks at the start of every solve
    /// that it agrees with `g` there, to the bit, and refuses a solve where it does not.
    pub fn batched(mut self, batch: BatchFn<'a>) -> Self {
        self.batch = Some(batch);
        self
    }

    /// Declares that `g` is the state's component `index`, $g(t, y) = y_{index}$, so that the
    /// tracker reads it without calling `g`. [`Tracker`] checks the declaration at the start of
    /// every solve (`g` and the component must agree there, to the bit) and refuses a solve
    /// where they do not.
    pub fn reading(mut self, index: usize) -> Self {
        self.component = Some(index);
        self
    }

    /// $g(t, y)$: the component when the event reads one, else a call of `g`.
    #[inline(always)]
    pub fn eval(&self, t: f64, y: &[f64]) -> f64 {
        match self.component {
            Some(i) => y[i],
            None => (self.g)(t, y),
        }
    }

    pub(crate) fn reborrow(&self) -> Event<'a> {
        Event {
            name: self.name.clone(),
            g: self.g,
            direction: self.direction,
            terminal: self.terminal,
            component: self.component,
            batch: self.batch,
        }
    }
}

/// A located event.
#[derive(Clone, Debug, PartialEq)]
pub struct EventHit {
    /// Time (s).
    pub t: f64,
    /// Which event.
    pub index: usize,
    /// State at `t` (dense output).
    pub y: Vec<f64>,
    /// Whether it stops the solve.
    pub terminal: bool,
}

const SAMPLES: usize = 8;

pub(crate) struct Tracker<'e, 'a> {
    events: &'e [Event<'a>],
    last_sign: Vec<i8>,
    g_prev: Vec<f64>,
    hits: Vec<EventHit>,
    g_now: Vec<f64>,
    /// Scratch for [`Tracker::may_cross`]: the Hermite interpolant's four parts, then the
    /// interpolant and its quadratic part at each of the `SAMPLES - 1` inner samples, then the
    /// state a nudge along the tangent at the start (a slope of g by difference).
    quad: Vec<f64>,
    g_end: Vec<f64>,
    /// The sign each event's g keeps over a step judged free of crossings.
    ref_sign: Vec<i8>,
    /// The times of the interpolant and its quadratic part at the inner samples (each twice),
    /// and g there, for an event's [`Event::batch`].
    batch_ts: [f64; 2 * (SAMPLES - 1)],
    batch_g: [f64; 2 * (SAMPLES - 1)],
}

fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

impl<'e, 'a> Tracker<'e, 'a> {
    pub(crate) fn new(
        events: &'e [Event<'a>],
        t0: f64,
        y0: &[f64],
        n: usize,
    ) -> Result<Self, IntegrateError> {
        let mut g_prev = Vec::with_capacity(events.len());
        for (index, e) in events.iter().enumerate() {
            let v = (e.g)(t0, y0);
            if !v.is_finite() {
                return Err(IntegrateError::EventNonFinite { t: t0, index });
            }
            if let Some(i) = e.component
                && y0.get(i).is_none_or(|c| c.to_bits() != v.to_bits())
            {
                return Err(IntegrateError::BadOption {
                    field: "events[].component",
                    value: format!("{i} for event {index} ({}), whose g(t0, y0) = {v}", e.name),
                    allowed: "a state component i with g(t, y) = y[i]",
                });
            }
            if let Some(b) = e.batch {
                let mut w = [f64::NAN];
                b(&[t0], y0, &mut w);
                if w[0].to_bits() != v.to_bits() {
                    return Err(IntegrateError::BadOption {
                        field: "events[].batch",
                        value: format!(
                            "{} for event {index} ({}), whose g(t0, y0) = {v}",
                            w[0], e.name
                        ),
                        allowed: "g at each point, to the bit",
                    });
                }
            }
            g_prev.push(v);
        }
        Ok(Tracker {
            events,
            last_sign: g_prev.iter().map(|v| sign(*v)).collect(),
            ref_sign: g_prev.iter().map(|v| sign(*v)).collect(),
            g_now: g_prev.clone(),
            g_end: g_prev.clone(),
            g_prev,
            hits: Vec::new(),
            // no scratch (no allocation) for a solve without events
            quad: vec![
                0.0;
                if events.is_empty() {
                    0
                } else {
                    (4 + 2 * SAMPLES - 1) * n
                }
            ],
            batch_ts: [0.0; 2 * (SAMPLES - 1)],
            batch_g: [0.0; 2 * (SAMPLES - 1)],
        })
    }

    pub(crate) fn take_hits(&mut self) -> Vec<EventHit> {
        std::mem::take(&mut self.hits)
    }

    /// Whether the last accepted step may hold a crossing, judged from what the step already has:
    /// the cubic Hermite interpolant of its end values and derivatives (free: no evaluation of
    /// the system), sampled where [`Tracker::scan`] samples, with the exact end value. A step
    /// may hold one when a sampled sign differs from the last sign, or when some sample of g is
    /// within twice the part of g that the interpolant's cubic term makes (g at the cubic less g
    /// at the quadratic interpolant): the terms the cubic leaves out are smaller still, so only
    /// a near-zero or grazing g needs the 7th-order dense output. When it
    /// cannot, the tracker moves to the end of the step as a scan would, and the 7th-order dense
    /// output is never formed. `None` when the stepper has no such interpolant.
    pub(crate) fn may_cross<St: Stepper>(
        &mut self,
        st: &St,
        ta: f64,
        tb: f64,
        buf: &mut [f64],
    ) -> Result<Option<bool>, IntegrateError> {
        if !st.has_hermite() {
            return Ok(None);
        }
        for (index, e) in self.events.iter().enumerate() {
            let v = e.eval(tb, st.y());
            if !v.is_finite() {
                return Err(IntegrateError::EventNonFinite { t: tb, index });
            }
            self.g_end[index] = v;
            // g leaving an exact zero (a root at t0 or at the last event) is no crossing, as
            // in the scan: the end's sign is then the one a sample must keep
            let s0 = self.last_sign[index];
            self.ref_sign[index] = if s0 == 0 { sign(v) } else { s0 };
            if sign(v) != self.ref_sign[index] {
                return Ok(Some(true));
            }
        }
        // g zero at both ends: any sample would differ in sign or lie within its share
        if self.ref_sign.contains(&0) {
            return Ok(Some(true));
        }
        let n = buf.len();
        let (parts, samples) = self.quad.split_at_mut(4 * n);
        let (samples, nudged) = samples.split_at_mut(2 * (SAMPLES - 1) * n);
        let h = st.hermite_parts(parts);
        // the interpolant and its quadratic part at every inner sample, once for all events
        let mut times = [0.0; SAMPLES - 1];
        for (j, (t, pair)) in times
            .iter_mut()
            .zip(samples.chunks_exact_mut(2 * n))
            .enumerate()
        {
            let frac = (j + 1) as f64 / SAMPLES as f64;
            *t = ta + (tb - ta) * frac;
            let (out, quad) = pair.split_at_mut(n);
            super::hermite_at(parts, (*t - ta) / h, out, quad);
        }
        // |g| when g keeps the sign s_ref; not above zero when it does not (or is NaN); the
        // cubic term's share of g bounds the higher terms the interpolant leaves out (each
        // smaller by about h |lambda| on a resolved step); an infinite g is within any share.
        // The answer is the same in any order of samples and events: nothing is kept until
        // every pair has passed.
        // (g at the quadratic part is asked for only when the sign is kept)
        #[inline(always)]
        fn within(v: f64, s_ref: i8, at_quad: impl FnOnce() -> f64) -> bool {
            let kept = v * f64::from(s_ref);
            kept.is_nan() || kept <= 0.0 || kept <= 2.0 * (v - at_quad()).abs()
        }
        for (index, (e, &s_ref)) in self.events.iter().zip(&self.ref_sign).enumerate() {
            let mut pairs = samples.chunks_exact(2 * n).zip(times);
            // g at the first sample, for the pair of crossings below
            let mut g1 = f64::NAN;
            let may = match (e.component, e.batch) {
                // a component: the samples' own entries, no call
                (Some(i), _) => {
                    g1 = samples[i];
                    pairs.any(|(pair, _)| within(pair[i], s_ref, || pair[n + i]))
                }
                // every sample in one call: the interpolant at the even points, its quadratic
                // part at the odd ones
                (None, Some(gb)) => {
                    for (pair, t) in self.batch_ts.chunks_exact_mut(2).zip(times) {
                        pair.fill(t);
                    }
                    gb(&self.batch_ts, samples, &mut self.batch_g);
                    g1 = self.batch_g[0];
                    self.batch_g
                        .chunks_exact(2)
                        .any(|v| within(v[0], s_ref, || v[1]))
                }
                (None, None) => pairs.any(|(pair, t)| {
                    let (out, quad) = pair.split_at(n);
                    let v = (e.g)(t, out);
                    if g1.is_nan() {
                        g1 = v;
                    }
                    within(v, s_ref, || (e.g)(t, quad))
                }),
            };
            if may {
                return Ok(Some(true));
            }
            // a pair of crossings inside the first sub-interval, from the start's slope
            let (g0, s0) = (self.g_prev[index], self.last_sign[index]);
            if !near_start(s0, g0, g1) {
                continue;
            }
            let slope = tangent_slope(e, parts, ta, tb - ta, g0, nudged);
            if turns_back(s0, s_ref, g0, slope / SAMPLES as f64, g1) {
                return Ok(Some(true));
            }
        }
        self.g_now.copy_from_slice(&self.g_end);
        self.g_prev.copy_from_slice(&self.g_end);
        self.last_sign.copy_from_slice(&self.ref_sign);
        Ok(Some(false))
    }

    /// Scans one accepted step; returns the first terminal hit, if any (all hits, terminal or
    /// not, up to it are kept for `take_hits`).
    pub(crate) fn scan<St: Stepper>(
        &mut self,
        st: &St,
        ta: f64,
        tb: f64,
        buf: &mut [f64],
    ) -> Result<Option<EventHit>, IntegrateError> {
        let mut t_left = ta;
        for j in 1..=SAMPLES {
            let t_right = if j == SAMPLES {
                tb
            } else {
                ta + (tb - ta) * (j as f64) / (SAMPLES as f64)
            };
            if j == SAMPLES {
                buf.copy_from_slice(st.y());
            } else {
                st.dense(t_right, buf);
            }
            let mut found: Vec<EventHit> = Vec::new();
            for (index, e) in self.events.iter().enumerate() {
                let v = e.eval(t_right, buf);
                if !v.is_finite() {
                    return Err(IntegrateError::EventNonFinite { t: t_right, index });
                }
                self.g_now[index] = v;
                let s0 = self.last_sign[index];
                let s1 = sign(v);
                if j == 1 {
                    self.dip(st, index, (t_left, t_right), v, &mut found)?;
                }
                let crossed = s0 != 0 && s1 != s0;
                if crossed {
                    let rising = s0 < 0;
                    let wanted = match e.direction {
                        super::Direction::Both => true,
                        super::Direction::Rising => rising,
                        super::Direction::Falling => !rising,
                    };
                    if wanted {
                        let t = if s1 == 0 {
                            t_right
                        } else {
                            locate(st, e, t_left, self.g_prev[index], t_right, v)?
                        };
                        let mut y = vec![0.0; buf.len()];
                        st.dense(t, &mut y);
                        found.push(EventHit {
                            t,
                            index,
                            y,
                            terminal: e.terminal,
                        });
                    }
                }
                if s1 != 0 || crossed {
                    self.last_sign[index] = s1;
                }
                self.g_prev[index] = v;
            }
            found.sort_by(|a, b| a.t.total_cmp(&b.t));
            if let Some(k) = found.iter().position(|h| h.terminal) {
                // the hits at the same time as the first terminal one stay (two events on one
                // `when`): the caller acts on each
                let tk = found[k].t;
                let last = found
                    .iter()
                    .rposition(|h| h.t.to_bits() == tk.to_bits())
                    .unwrap_or(k);
                found.truncate(last + 1);
                let term = found[k].clone();
                self.hits.extend(found);
                return Ok(Some(term));
            }
            self.hits.extend(found);
            t_left = t_right;
        }
        Ok(None)
    }
}

/// The fraction of a step at which a slope of $g$ is taken by difference, along the tangent of
/// the motion (so that the motion's own curvature, however short its time scale against the
/// step's, does not enter: only $g$'s).
const NUDGE: f64 = 1e-8;

/// The slope of $g$ at the start of the step, per unit of the step, from the Hermite `parts`
/// ([`super::Stepper::hermite_parts`]) of a step of length `h` from `ta`, where `g` is `g0`: a
/// component's is the interpolant's own; another $g$'s is taken by difference along the tangent
/// $y_0 + \epsilon h y'_0$ (`scratch` holds that state).
fn tangent_slope(e: &Event, parts: &[f64], ta: f64, h: f64, g0: f64, scratch: &mut [f64]) -> f64 {
    let n = scratch.len();
    let (y0, rest) = parts.split_at(n);
    let (dy, c1) = rest.split_at(n);
    match e.component {
        Some(i) => dy[i] + c1[i],
        None => {
            for (m, x) in scratch.iter_mut().enumerate() {
                *x = y0[m] + NUDGE * (dy[m] + c1[m]);
            }
            (e.eval(ta + NUDGE * h, scratch) - g0) / NUDGE
        }
    }
}

/// Whether the start of a step is near enough to a zero of $g$ for the pair check of
/// [`turns_back`]: at a zero (`s0 = 0`), or closer to it than $g$ moves by the first sample
/// ($|g_0| \le |g_1 - g_0|$), as right after an event or a jump. A pair of crossings inside the
/// first sub-interval from a start farther from zero is, like a pair closer than $h/8$ anywhere
/// else in the step, not looked for (the slope would cost one more evaluation of $g$ on every
/// step).
fn near_start(s0: i8, g0: f64, g1: f64) -> bool {
    s0 == 0 || g0.abs() <= (g1 - g0).abs()
}

/// Whether $g$, with the sign `s0` (0: leaving an exact zero toward `s_end`, the sign it has at
/// the first sample), the value `g0` and the slope `d0` (per unit of the first sub-interval) at
/// the start and `g1` at the first sample, may reach the other side and come back inside the
/// first sub-interval, which no sample would see. The parabola
/// $u(x) = u_0 + d_0 x + a x^2$ through them (in $u = s_0 g$, positive on the kept side):
/// heading to zero at the start ($d_0 < 0$), back on the kept side at the sample ($u_1 > 0$), and
/// turning before it ($0 < x^* < 1$) to a least value below half the start's ($u^* \le u_0/2$). Leaving an exact zero: it heads to the
/// side other than the one it is on at the sample.
fn turns_back(s0: i8, s_end: i8, g0: f64, d0: f64, g1: f64) -> bool {
    if s0 == 0 {
        return s_end != 0 && sign(d0) == -s_end;
    }
    let s = f64::from(s0);
    let (u0, d0, u1) = (s * g0, s * d0, s * g1);
    let a = u1 - u0 - d0;
    // (on the other side at the sample, the samples see the crossing)
    if !(d0 < 0.0 && a > 0.0 && u1 > 0.0) {
        return false;
    }
    let x = -d0 / (2.0 * a);
    x < 1.0 && u0 - d0 * d0 / (4.0 * a) <= 0.5 * u0
}

impl Tracker<'_, '_> {
    /// The pair of crossings of event `index` inside the first sub-interval `(ta, t1)` of a
    /// step, where `g` is `g1` at `t1` (see [`turns_back`]): the least $s_0 g$ is searched by golden
    /// section on the dense output, and where it lies on the other side the two crossings on
    /// either side of it are located; the wanted ones go to `found`. Leaving an exact zero, the
    /// one crossing back (from just after the start) is located.
    fn dip<St: Stepper>(
        &self,
        st: &St,
        index: usize,
        (ta, t1): (f64, f64),
        g1: f64,
        found: &mut Vec<EventHit>,
    ) -> Result<(), IntegrateError> {
        let e = &self.events[index];
        let (s0, g0) = (self.last_sign[index], self.g_prev[index]);
        // (before any allocation: most steps of a scan end here)
        if (s0 != 0 && sign(g1) != s0) || !near_start(s0, g0, g1) {
            return Ok(());
        }
        let n = st.y().len();
        let mut y = vec![0.0; n];
        let mut g_at = |t: f64| -> Result<f64, IntegrateError> {
            st.dense(t, &mut y);
            let v = e.eval(t, &y);
            if v.is_finite() {
                Ok(v)
            } else {
                Err(IntegrateError::EventNonFinite { t, index })
            }
        };
        // the slope at the start, per unit of (ta, t1): the stepper's tangent, or a difference
        // of the dense output
        let slope = if st.has_hermite() {
            let mut parts = vec![0.0; 5 * n];
            let (parts, scratch) = parts.split_at_mut(4 * n);
            let h = st.hermite_parts(parts);
            tangent_slope(e, parts, ta, h, g0, scratch) * (t1 - ta) / h
        } else {
            (g_at(ta + NUDGE * (t1 - ta))? - g0) / NUDGE
        };
        if !turns_back(s0, sign(g1), g0, slope, g1) {
            return Ok(());
        }
        let wanted = |rising: bool| match e.direction {
            super::Direction::Both => true,
            super::Direction::Rising => rising,
            super::Direction::Falling => !rising,
        };
        let push = |t: f64, found: &mut Vec<EventHit>| {
            let mut y = vec![0.0; n];
            st.dense(t, &mut y);
            found.push(EventHit {
                t,
                index,
                y,
                terminal: e.terminal,
            });
        };
        if s0 == 0 {
            // left the zero toward the slope's sign, back across it before t1: the crossing
            // lies after the first time g is seen on that side, halving toward the start
            let mut tn = ta + 0.5 * (t1 - ta);
            for _ in 0..1100 {
                let gn = g_at(tn)?;
                if sign(gn) == sign(slope) {
                    if wanted(sign(gn) < 0) {
                        push(locate(st, e, tn, gn, t1, g1)?, found);
                    }
                    break;
                }
                if tn <= ta {
                    break;
                }
                tn = ta + 0.5 * (tn - ta);
            }
            return Ok(());
        }
        // the least u = s0 g on [ta, t1], by golden section
        let s = f64::from(s0);
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (ta, t1);
        let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
        let (mut uc, mut ud) = (s * g_at(c)?, s * g_at(d)?);
        for _ in 0..200 {
            if (b - a).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs()) + f64::MIN_POSITIVE
                || uc <= 0.0
                || ud <= 0.0
            {
                break;
            }
            if uc < ud {
                (b, d, ud) = (d, c, uc);
                c = b - r * (b - a);
                uc = s * g_at(c)?;
            } else {
                (a, c, uc) = (c, d, ud);
                d = a + r * (b - a);
                ud = s * g_at(d)?;
            }
        }
        let (tm, um) = if uc <= ud { (c, uc) } else { (d, ud) };
        if um > 0.0 {
            return Ok(());
        }
        // from s0 to the other side, and back
        let gm = s * um;
        if wanted(s0 < 0) {
            let t = if gm == 0.0 {
                tm
            } else {
                locate(st, e, ta, g0, tm, gm)?
            };
            push(t, found);
        }
        if gm != 0.0 && wanted(s0 > 0) {
            push(locate(st, e, tm, gm, t1, g1)?, found);
        }
        Ok(())
    }
}

/// Illinois regula falsi on $g(t, y(t))$ with $y$ from the dense output; returns the end of the
/// final bracket on the far side of the crossing.
fn locate<St: Stepper>(
    st: &St,
    e: &Event,
    mut ta: f64,
    mut ga: f64,
    mut tb: f64,
    mut gb: f64,
) -> Result<f64, IntegrateError> {
    let n = st.y().len();
    let mut y = vec![0.0; n];
    let mut side = 0i8;
    for _ in 0..200 {
        if (tb - ta).abs() <= 2.0 * f64::EPSILON * ta.abs().max(tb.abs()) + f64::MIN_POSITIVE {
            break;
        }
        let mut t = (ta * gb - tb * ga) / (gb - ga);
        if !(t > ta.min(tb) && t < ta.max(tb)) {
            t = 0.5 * (ta + tb);
        }
        st.dense(t, &mut y);
        let g = e.eval(t, &y);
        if !g.is_finite() {
            return Err(IntegrateError::EventNonFinite { t, index: 0 });
        }
        if g == 0.0 {
            return Ok(t);
        }
        if sign(g) == sign(gb) {
            tb = t;
            gb = g;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        } else {
            ta = t;
            ga = g;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        }
    }
    Ok(tb)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{OdeSystem, Options, dop853::Dop853};

    /// $y_1' = 3t^2$, $y_2' = 1 - 2t$: the solution $(t^3, t - t^2)$ is a cubic, which the
    /// cubic Hermite interpolant of an exact step reproduces.
    struct Cubic;
    impl OdeSystem for Cubic {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, t: f64, _y: &[f64], dy: &mut [f64]) {
            dy[0] = 3.0 * t * t;
            dy[1] = 1.0 - 2.0 * t;
        }
    }

    /// One DOP853 step of `Cubic` over [0, 1] (exact to rounding: the right-hand side is a
    /// polynomial of degree 2 in t).
    fn one_step() -> Dop853 {
        let opts = Options {
            h0: Some(1.0),
            ..Options::default()
        };
        let mut st = Dop853::new(&Cubic, 0.0, &[0.0, 0.0], 1.0, &opts);
        st.step(&Cubic, 1.0).expect("one step");
        assert!(st.t_old().abs() < 1e-15 && (st.t() - 1.0).abs() < 1e-15);
        st
    }

    #[test]
    fn hermite_parts_give_the_cubic_and_its_quadratic_part() {
        let st = one_step();
        let mut parts = [0.0; 8];
        let h = st.hermite_parts(&mut parts);
        assert!((h - 1.0).abs() < 1e-15, "{h}");
        let (mut out, mut quad) = ([0.0; 2], [0.0; 2]);
        for s in [0.125, 0.3, 0.5, 0.875] {
            super::super::hermite_at(&parts, s, &mut out, &mut quad);
            // reference: the exact solution, and the quadratic through y(0), y(1) with the slope
            // y'(0), written out independently: q(s) = y0 + y'(0) s + (y1 - y0 - y'(0)) s^2
            let exact = [s * s * s, s - s * s];
            let q = [s * s, s - s * s];
            for m in 0..2 {
                assert!((out[m] - exact[m]).abs() < 1e-14, "s = {s}: {out:?}");
                assert!((quad[m] - q[m]).abs() < 1e-14, "s = {s}: {quad:?}");
            }
        }
    }

    /// An event that reads a state component fires where the same g called through its
    /// closure fires, to the bit (the harmonic oscillator's zeros of x and v, with a
    /// terminal stop); a component that does not match g at the start is refused, naming it.
    #[test]
    fn an_event_reading_a_component_is_the_closure_it_declares() {
        use crate::integrate::{Method, solve};
        struct Harmonic;
        impl OdeSystem for Harmonic {
            fn dim(&self) -> usize {
                2
            }
            fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
                dy[0] = y[1];
                dy[1] = -y[0];
            }
        }
        let x = |_t: f64, y: &[f64]| y[0];
        let v = |_t: f64, y: &[f64]| y[1];
        let run = |read: bool| {
            let mut events = vec![
                Event::new("x", &x, Direction::Both, false),
                Event::new("v", &v, Direction::Falling, false),
                Event::new("x rises", &x, Direction::Rising, true),
            ];
            if read {
                events = events
                    .into_iter()
                    .zip([0, 1, 0])
                    .map(|(e, i)| e.reading(i))
                    .collect();
            }
            let opts = Options {
                rtol: 1e-10,
                atol: 1e-12,
                method: Method::Dop853,
                events,
                ..Options::default()
            };
            solve(&Harmonic, 0.0, &[0.3, 1.0], 20.0, &opts).expect("solves")
        };
        let (called, read) = (run(false), run(true));
        assert_eq!(called.events, read.events);
        assert_eq!(called.t.to_bits(), read.t.to_bits());
        // x = A sin(t + phi): zeros where t + phi = k pi (independent closed form)
        let phi = 0.3f64.atan2(1.0);
        let expect = [std::f64::consts::PI - phi, 2.0 * std::f64::consts::PI - phi];
        let zeros: Vec<f64> = read
            .events
            .iter()
            .filter(|e| e.index != 1)
            .map(|e| e.t)
            .collect();
        assert_eq!(zeros.len(), 3, "{zeros:?}");
        assert!((zeros[0] - expect[0]).abs() < 1e-8 && (zeros[1] - expect[1]).abs() < 1e-8);
        // a wrong component is an error before the first step
        let wrong = [Event::new("x", &x, Direction::Both, false).reading(1)];
        let opts = Options {
            events: wrong.iter().map(Event::reborrow).collect(),
            ..Options::default()
        };
        let err = solve(&Harmonic, 0.0, &[0.3, 1.0], 1.0, &opts).expect_err("refused");
        assert!(err.to_string().contains("component"), "{err}");
        let beyond = [Event::new("x", &x, Direction::Both, false).reading(2)];
        let opts = Options {
            events: beyond.iter().map(Event::reborrow).collect(),
            ..Options::default()
        };
        assert!(solve(&Harmonic, 0.0, &[0.3, 1.0], 1.0, &opts).is_err());
    }

    #[test]
    fn may_cross_tells_a_step_with_a_crossing_from_one_without() {
        let st = one_step();
        let far = |_t: f64, y: &[f64]| y[0] + 1.0;
        // t - t^2 - 0.2: negative at both ends, positive in the middle (two roots inside)
        let hump = |_t: f64, y: &[f64]| y[1] - 0.2;
        // t^3 - 0.5: one root inside, the end's sign differs
        let rises = |_t: f64, y: &[f64]| y[0] - 0.5;
        let mut buf = [0.0; 2];
        type G<'a> = &'a dyn Fn(f64, &[f64]) -> f64;
        // zero throughout: every sample lies within its share
        let zero = |_t: f64, _y: &[f64]| 0.0;
        let cases: [(G, bool); 4] = [(&far, false), (&hump, true), (&rises, true), (&zero, true)];
        for (g, expect) in cases {
            let events = [Event::new("g", g, Direction::Both, false)];
            let mut tr = Tracker::new(&events, 0.0, &[0.0, 0.0], 2).expect("finite");
            let got = tr.may_cross(&st, 0.0, 1.0, &mut buf).expect("finite");
            assert_eq!(got, Some(expect), "g(0) = {}", g(0.0, &[0.0, 0.0]));
            // the same g asked for every sample in one call: the same answer
            let batch = |ts: &[f64], ys: &[f64], out: &mut [f64]| {
                for (p, o) in out.iter_mut().enumerate() {
                    *o = g(ts[p], &ys[2 * p..2 * p + 2]);
                }
            };
            let events = [Event::new("g", g, Direction::Both, false).batched(&batch)];
            let mut tr = Tracker::new(&events, 0.0, &[0.0, 0.0], 2).expect("finite");
            let got = tr.may_cross(&st, 0.0, 1.0, &mut buf).expect("finite");
            assert_eq!(got, Some(expect), "batched, g(0) = {}", g(0.0, &[0.0, 0.0]));
        }
        // a batch that is not g is refused at the start
        let wrong = |_: &[f64], _: &[f64], out: &mut [f64]| out.fill(0.5);
        let events = [Event::new("g", &far, Direction::Both, false).batched(&wrong)];
        assert!(matches!(
            Tracker::new(&events, 0.0, &[0.0, 0.0], 2),
            Err(IntegrateError::BadOption {
                field: "events[].batch",
                ..
            })
        ));
    }
}
