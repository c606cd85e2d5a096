//! The support at A (002_b53e4779673eb6ed.txt sections 3-4): its modes (contact, roll, slide,
//! detached), the reaction (3.7) and (4.2)-(4.4), the slide direction from rest (4.5), and the
//! joint decision of the support's motion and C's stick.

use super::*;
use nalgebra::{Matrix3, Vector3};

/// The motion at A: rolling (4.2), sliding (4.3)-(4.4), or free of the support.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SupportMode {
    /// $\mathbf V_A = 0$, $\mathbf F^* = \mathbf B_A^{-1}\tilde{\mathbf B}\mathbf F$ (4.2).
    Roll,
    /// $\mathbf F^* = F_N^*(\mathbf N - \mu^*\mathbf e_T)$ (4.3), $F_N^* = -\alpha/\beta$ with (4.4).
    Slide,
    /// No reaction: the support would have to pull (the body detaches, case 1).
    Free,
}

impl SupportMode {
    pub(super) fn name(self) -> &'static str {
        match self {
            SupportMode::Roll => "roll",
            SupportMode::Slide => "slide",
            SupportMode::Free => "detached",
        }
    }
}

/// The support at A during the impact, smooth (3.7)-(3.8) or rough (section 4), with the
/// velocity of A in the state: the support pushes only while A touches it ($V_{A,N} = 0$, the
/// complementarity (3.3) on velocities, not only on their rates), and a body that has left it
/// is pushed again only when A comes back down.
#[derive(Clone, Debug)]
pub(super) struct AtA {
    pub(super) b_tilde: Matrix3<f64>,
    /// $\mathbf B_A$ (rough only: a smooth support needs only $\beta$).
    pub(super) b_a: Matrix3<f64>,
    pub(super) b_a_inv: Matrix3<f64>,
    pub(super) normal: Vector3<f64>,
    /// $\beta = (\mathbf B_A\mathbf N, \mathbf N)$ of (3.7).
    pub(super) beta_n: f64,
    /// $\mu^*$; 0 for a smooth support.
    pub(super) mu: f64,
    pub(super) mode: SupportMode,
    /// slide direction used while the slip at A is below the floor (set when sliding starts)
    pub(super) hint: Vector3<f64>,
    /// The slide started from rest (out of rolling, or from a stop): its rate starts at zero,
    /// so the direction is held at `hint` until the slip exceeds the velocity tolerance.
    pub(super) held: bool,
    /// The band of a regularised friction law at A (0: Coulomb's with roll/slide switches): the
    /// friction is $\mu^* F_N^*\mathbf V_{A,T}/\sqrt{|\mathbf V_{A,T}|^2 + \text{band}^2}$,
    /// viscous below the band, Coulomb's above, and rolling is a slip that stays in the band (see
    /// [`REGULARISE_AFTER`]).
    pub(super) regular: f64,
    pub(super) floor: f64,
}

impl AtA {
    pub(super) fn rough(&self) -> bool {
        self.mu > 0.0
    }

    /// Switches to the regularised law with viscous friction below `band` (see
    /// [`REGULARISE_AFTER`]); a roll becomes a slide that stays in the band.
    pub(super) fn regularise(&mut self, band: f64) {
        self.regular = band;
        self.held = false;
        if self.mode == SupportMode::Roll {
            self.mode = SupportMode::Slide;
        }
    }

    /// The phase's name: "roll", "slide" or "detached"; "contact" for a smooth support;
    /// "regularised" for a support in contact under the regularised law.
    pub(super) fn phase_name(&self) -> &'static str {
        if self.regular > 0.0 && self.mode != SupportMode::Free {
            return "regularised";
        }
        match (self.rough(), self.mode) {
            (false, SupportMode::Slide | SupportMode::Roll) => "contact",
            (_, m) => m.name(),
        }
    }

    pub(super) fn tangential(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.normal * v.dot(&self.normal)
    }

    pub(super) fn slide_dir(&self, va: &Vector3<f64>) -> Vector3<f64> {
        let vt = self.tangential(va);
        let s = vt.norm();
        if self.regular > 0.0 {
            // smooth (a kink at the band's edge is where a grazing slip sits)
            return vt / s.hypot(self.regular);
        }
        if s > self.floor && !self.held {
            vt / s
        } else {
            self.hint
        }
    }

    /// The reaction of rolling, $\mathbf B_A^{-1}\tilde{\mathbf B}\mathbf F$ (4.2).
    pub(super) fn roll_reaction(&self, f: &Vector3<f64>) -> Vector3<f64> {
        self.b_a_inv * (self.b_tilde * f)
    }

    /// $\mathbf I = \mathbf N - \mu^*\mathbf e_T$ and $\beta = (\mathbf B_A\mathbf I, \mathbf N)$ (4.3)-(4.4).
    pub(super) fn slide_i(&self, va: &Vector3<f64>) -> (Vector3<f64>, f64) {
        if !self.rough() {
            return (self.normal, self.beta_n);
        }
        let i = self.normal - self.slide_dir(va) * self.mu;
        (i, (self.b_a * i).dot(&self.normal))
    }

    /// The reaction $\mathbf F^*$ per unit normal impulse at C.
    pub(super) fn reaction(&self, f: &Vector3<f64>, va: &Vector3<f64>) -> Vector3<f64> {
        match self.mode {
            SupportMode::Free => Vector3::zeros(),
            SupportMode::Roll => {
                let fs = self.roll_reaction(f);
                if fs.dot(&self.normal) > 0.0 {
                    fs
                } else {
                    Vector3::zeros()
                }
            }
            SupportMode::Slide => {
                // F_N* = -alpha/beta (3.7) with (4.4); with beta < 0 this is the sliding one of
                // the two solutions of a Painleve case (alpha > 0), reached only as a branch
                let (i, beta) = self.slide_i(va);
                if beta != 0.0 {
                    i * ((self.b_tilde * f).dot(&self.normal) / beta).max(0.0)
                } else {
                    Vector3::zeros()
                }
            }
        }
    }

    /// $d\mathbf V_A/d\chi = \mathbf B_A\mathbf F^* - \tilde{\mathbf B}\mathbf F$ (3.4); for a smooth
    /// support its normal part only ($\beta F_N^* - (\tilde{\mathbf B}\mathbf F, \mathbf N)$).
    pub(super) fn va_rate(&self, f: &Vector3<f64>, fs: &Vector3<f64>) -> Vector3<f64> {
        let g = self.b_tilde * f;
        if self.rough() {
            self.b_a * fs - g
        } else {
            self.normal * (self.beta_n * fs.dot(&self.normal) - g.dot(&self.normal))
        }
    }

    /// The matrix that maps F to the rate of $\mathbf V_C$ in the current mode (it governs
    /// sticking at C): $\mathbf B^*$ of (3.8) for a smooth support or a slide, $\mathbf B -
    /// \tilde{\mathbf B}'\mathbf B_A^{-1}\tilde{\mathbf B}$ rolling, $\mathbf B$ free (a contact mode is
    /// left, by its event, where the support would pull).
    pub(super) fn b_eff(&self, b: &Matrix3<f64>, va: &Vector3<f64>) -> Matrix3<f64> {
        let bt = &self.b_tilde;
        let nn = self.normal;
        match self.mode {
            SupportMode::Free => *b,
            SupportMode::Roll => b - bt.transpose() * self.b_a_inv * bt,
            SupportMode::Slide => {
                let (i, beta) = self.slide_i(va);
                if beta > 0.0 {
                    b - (bt.transpose() * i) * (bt.transpose() * nn).transpose() / beta
                } else {
                    *b
                }
            }
        }
    }
}

/// beta of (4.4) below this fraction of $(\mathbf B_A\mathbf N, \mathbf N)$ ends the classical
/// solution as a Painleve-type case: the reaction $F_N^* = -\alpha/\beta$ is then over 1000 times
/// its scale and grows without bound as the slide turns further. It does in the seeded cases
/// that reach it: of the 226 of `constrained_fail`'s first 2e5 that stop here, 221 reach 1e-5 of
/// $(\mathbf B_A\mathbf N, \mathbf N)$ too when the floor is set there, and 4 of the rest stall
/// on the blow-up (step size too small).
pub(super) const BETA_FLOOR: f64 = 1e-3;

/// A slip at A below this many times its stop (5e-10 of the velocity scale at rtol 1e-10) slides
/// with its friction direction frozen, until it exceeds [`RELEASE_ABOVE`] times the stop: near
/// zero the direction's turning rate grows like $1/|\mathbf V_{A,T}|$, and a slip that dies there,
/// or hovers at the edge of the friction cone (a reaction that grazes the cone), makes the system
/// stiff without bound. The friction direction differs from the slip's only while the slip is
/// under 1e3 stop (1e-9 of the velocity scale at rtol 1e-10), which bounds the change in the
/// velocities by the order of that slip. A slide from rest is held the same way: its rate starts
/// at zero.
pub(super) const HOLD_BELOW: f64 = 500.0;

/// The slip (in stops) above which a held direction at A is freed (see [`HOLD_BELOW`]).
pub(super) const RELEASE_ABOVE: f64 = 1e3;

/// After this many switches of A's slip about its band (its slip nearly stopping, stopping, or
/// re-established), or where the solver cannot follow the exact law in a stage, the support's
/// friction is regularised for the rest of the impact: $\mathbf V_{A,T}/\sqrt{|\mathbf V_{A,T}|^2 +
/// b^2}$ for the slide direction, b = [`RELEASE_ABOVE`] stops (viscous below b, Coulomb's above,
/// smooth across: a grazing slip sits at the edge), with no roll/slide switches (rolling is then
/// a slip that stays in the band). This ends a reaction that grazes the friction cone, where the
/// slide direction of (4.5) moves faster than its slip grows and the exact law switches without
/// end. The band is stiff and is integrated by Radau5; the velocities change by the order of the
/// band (1e-9 of the velocity scale at rtol 1e-10).
pub(super) const REGULARISE_AFTER: usize = 200;

/// Why the support admits no motion at some instant.
pub(super) fn no_support_motion(chi: f64, what: &str) -> ImpactError {
    ImpactError::Painleve {
        chi,
        what: what.into(),
    }
}

/// A slide at A whose beta of (4.4) fell to [`BETA_FLOOR`] with alpha < 0.
pub(super) fn beta_vanishes(chi: f64, beta: f64) -> ImpactError {
    no_support_motion(
        chi,
        &format!(
            "A slides with beta of (4.4) = {beta:.3e} (at most 1e-3 of (B_A N, N)) and alpha < 0: the support's reaction grows without bound"
        ),
    )
}

/// The slide directions at A from rest, (4.5): unit tangential $\mathbf e_T$ with
/// $\varkappa\mathbf e_T = F_N^*\mathbf B_A(\mathbf N - \mu^*\mathbf e_T) - \tilde{\mathbf B}\mathbf F$,
/// $\varkappa > 0$ (down to $-10^{-9}|\tilde{\mathbf B}\mathbf F|$ at the cone's edge),
/// $F_N^* \ge 0$ (the normal component fixes $F_N^*$); `(e_T, kappa, stable)` for each root, stable where nearby directions turn towards it (the cross product falls through zero as the
/// angle grows), as for the slip at C ([`slide_rays`]).
pub(super) fn start_slide_dirs(r: &AtA, f: &Vector3<f64>) -> Vec<(Vector3<f64>, f64, bool)> {
    let nn = r.normal;
    let (t1, t2) = tangent_basis(&nn);
    let g = r.b_tilde * f;
    let resid = |th: f64| -> (f64, f64, f64, Vector3<f64>) {
        let e = t1 * th.cos() + t2 * th.sin();
        let a = r.b_a * (nn - e * r.mu);
        let fn_star = g.dot(&nn) / a.dot(&nn);
        let v = a * fn_star - g;
        let vt = v - nn * v.dot(&nn);
        (e.cross(&vt).dot(&nn), vt.dot(&e), fn_star, e)
    };
    let samples = 720;
    let tau = 2.0 * std::f64::consts::PI;
    let mut out = Vec::new();
    let mut prev = resid(0.0);
    for k in 1..=samples {
        let (a0, a1) = (
            tau * (k - 1) as f64 / samples as f64,
            tau * k as f64 / samples as f64,
        );
        let cur = resid(a1);
        if prev.0.is_finite()
            && cur.0.is_finite()
            && (prev.0 == 0.0 || prev.0.signum() != cur.0.signum())
        {
            let (mut lo, mut hi) = (a0, a1);
            let s_lo = prev.0 > 0.0;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (resid(mid).0 > 0.0) == s_lo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let (_, kappa, fn_star, e) = resid(0.5 * (lo + hi));
            // kappa starts at zero where a rolling reaction reaches the cone, and the event
            // that finds that instant may stop on either side of it: a rate below zero by
            // rounding (1e-9 of (B~F)) is the slide that begins there
            if kappa > -1e-9 * g.norm() && fn_star >= 0.0 {
                out.push((e, kappa, prev.0 > 0.0));
            }
        }
        prev = cur;
    }
    out
}

/// C's contact force direction if the support were in `mode`: while C sticks, the stick (or
/// the slide it turns into) is decided with that mode's matrix, so the support's choice and
/// C's are made together (a small complementarity problem, solved by trying the modes).
pub(super) fn c_direction_with(
    sys: &mut Keller,
    mode: SupportMode,
    v: &Vector3<f64>,
    va: &Vector3<f64>,
) -> Vector3<f64> {
    let Mode::Stick(_) = sys.mode else {
        return sys.rate(v, va);
    };
    let Some(a) = sys.at_a.as_mut() else {
        return sys.rate(v, va);
    };
    let old = std::mem::replace(&mut a.mode, mode);
    let b_e = sys.b_stick(va);
    let f = {
        let rate_of = |f: &Vector3<f64>| sys.rates(f, va).0;
        match stick_or_slide(&b_e, &rate_of, &sys.n, sys.mu) {
            Ok(tau) => sys.n + tau,
            Err(u) => sys.n - u.unwrap_or_else(|| tangent_basis(&sys.n).0) * sys.mu,
        }
    };
    if let Some(a) = sys.at_a.as_mut() {
        a.mode = old;
    }
    f
}

/// Chooses the support's motion at a switch (or at the start) from the state, together with
/// C's stick where C sticks ([`c_direction_with`]). A that moves away from the support (faster
/// than `stop`) is free. Otherwise A touches it (an approach slower than `stop` is taken as
/// arriving: $V_{A,N}$ is set to 0), and with alpha of (3.6) for C's direction in each mode:
/// letting go where alpha >= 0 with the support free (case 1; taken also where a contact mode is
/// admissible too: section 4 takes the body to leave in the paradoxical cases); else contact
/// where alpha < 0 with C's direction in contact: a smooth support pushes; a rough one slides
/// while A slips (none if (4.4)'s beta <= 0), else rolls if (4.2)'s reaction lies in the
/// friction cone, else slides in the direction (4.5) gives (the fastest, where several do), the
/// slip nudged to `20 stop` along it so that its stop event re-arms. Neither admissible is a
/// Painleve-type case with no solution, reported as such.
pub(super) fn decide_support(
    sys: &mut Keller,
    y: &mut [f64],
    stop: f64,
    chi: f64,
    leaving_roll: bool,
    rest_below: f64,
) -> Result<(), ImpactError> {
    let v = Vector3::new(y[0], y[1], y[2]);
    let mut va = va_of(y);
    let Some(r) = sys.at_a.as_ref() else {
        return Ok(());
    };
    let nn = r.normal;
    if va.dot(&nn) > stop {
        if let Some(r) = sys.at_a.as_mut() {
            r.mode = SupportMode::Free;
        }
        return Ok(());
    }
    va -= nn * va.dot(&nn);
    y[10..13].copy_from_slice(va.as_slice());
    if sys.at_a.as_ref().is_some_and(|r| r.regular > 0.0) {
        // the regularised law: in contact it slides (rolling is a slip inside the band), unless
        // the support would have to pull
        let f = c_direction_with(sys, SupportMode::Slide, &v, &va);
        if let Some(r) = sys.at_a.as_mut() {
            let alpha = -(r.b_tilde * f).dot(&nn);
            let (_, beta) = r.slide_i(&va);
            if alpha >= 0.0 {
                r.mode = SupportMode::Free;
            } else if beta <= BETA_FLOOR * r.beta_n {
                return Err(beta_vanishes(chi, beta));
            } else {
                r.mode = SupportMode::Slide;
            }
        }
        return Ok(());
    }
    let alpha_of = |sys: &Keller, f: &Vector3<f64>| {
        sys.at_a
            .as_ref()
            .map_or(0.0, |r| -(r.b_tilde * f).dot(&r.normal))
    };
    // the sliding branch of a two-solution case (beta of (4.4) < 0, alpha > 0: F_N* = -alpha/beta
    // > 0) slides on while A slips and the reaction stays positive
    if let Some(r) = sys.at_a.as_ref()
        && r.rough()
        && r.mode == SupportMode::Slide
        && r.tangential(&va).norm() > rest_below
    {
        let (_, beta) = r.slide_i(&va);
        let f = sys.rate(&v, &va);
        let alpha = -(r.b_tilde * f).dot(&nn);
        if beta < 0.0 && alpha > 0.0 {
            // its friction follows its slip as any slide's (a direction held from rest was kept
            // frozen here, while A slid elsewhere under it, and friction did positive work:
            // tests/regression_constrained_seeds.rs)
            if let Some(r) = sys.at_a.as_mut() {
                let slip = r.tangential(&va).norm();
                if slip > r.floor {
                    r.hint = r.tangential(&va) / slip;
                }
                r.held = slip <= HOLD_BELOW * stop * (1.0 + 1e-6);
            }
            return Ok(());
        }
    }
    let f_free = c_direction_with(sys, SupportMode::Free, &v, &va);
    if alpha_of(sys, &f_free) >= 0.0 {
        if let Some(r) = sys.at_a.as_mut() {
            r.mode = SupportMode::Free;
        }
        return Ok(());
    }
    let rough = sys.at_a.as_ref().is_some_and(|r| r.rough());
    let slips = sys
        .at_a
        .as_ref()
        .is_some_and(|r| r.tangential(&va).norm() > rest_below);
    let contact = if !rough || slips {
        SupportMode::Slide
    } else {
        SupportMode::Roll
    };
    let f = c_direction_with(sys, contact, &v, &va);
    if alpha_of(sys, &f) >= 0.0 {
        return Err(no_support_motion(
            chi,
            "with the support free it would be pushed into (alpha < 0), in contact it would pull (alpha > 0)",
        ));
    }
    let Some(r) = sys.at_a.as_mut() else {
        return Ok(());
    };
    if !rough {
        r.mode = SupportMode::Slide;
        return Ok(());
    }
    if slips {
        let slip = r.tangential(&va).norm();
        if slip > r.floor {
            r.hint = r.tangential(&va) / slip;
        }
        // a slip below HOLD_BELOW stop slides with its direction frozen until it exceeds
        // RELEASE_ABOVE stop (see the event "support slip nearly stops" in `impact_core`)
        r.held = slip <= HOLD_BELOW * stop * (1.0 + 1e-6);
        let (_, beta) = r.slide_i(&va);
        if beta <= BETA_FLOOR * r.beta_n {
            return Err(beta_vanishes(chi, beta));
        }
        r.mode = SupportMode::Slide;
        return Ok(());
    }
    // at rest: what slip is left (below `rest_below`, under the tolerance) is taken as none
    va = Vector3::zeros();
    y[10..13].copy_from_slice(va.as_slice());
    let fs = r.roll_reaction(&f);
    let fs_n = fs.dot(&nn);
    // (a roll whose reaction just left the cone, located on the cone's far side to rounding,
    // does not roll again)
    if !leaving_roll && fs_n >= 0.0 && (fs - nn * fs_n).norm() <= r.mu * fs_n * (1.0 + 1e-12) {
        r.mode = SupportMode::Roll;
        return Ok(());
    }
    // from rest into a slide: the direction (4.5) gives with C's rate of rolling
    let dirs = start_slide_dirs(r, &f);
    let Some((mut e, _, _)) = dirs.into_iter().max_by(|a, b| {
        (a.2, a.1)
            .partial_cmp(&(b.2, b.1))
            .unwrap_or(std::cmp::Ordering::Equal)
    }) else {
        return Err(no_support_motion(
            chi,
            "rolling needs a reaction outside the friction cone and (4.5) has no slide direction",
        ));
    };
    r.hint = e;
    r.held = true;
    r.mode = SupportMode::Slide;
    let vnew = e * (20.0 * stop);
    y[10..13].copy_from_slice(vnew.as_slice());
    // where C sticks, its stick depends on the slide (the matrix B* of (3.8) turns with e) and
    // the slide on C's force: the two are iterated to a joint fixed point, each time (4.5)'s root
    // nearest the last direction (C's stick is decided once more when the stage starts)
    if matches!(sys.mode, Mode::Stick(_)) {
        // (it contracts linearly, by 0.4 to 0.7 a pass in the seeded cases: 10 passes typical,
        // 93 at most in 105 cases of 2e5)
        for _ in 0..200 {
            let f = c_direction_with(sys, SupportMode::Slide, &v, &vnew);
            let Some(r) = sys.at_a.as_mut() else {
                break;
            };
            let Some((next, _, _)) = start_slide_dirs(r, &f).into_iter().max_by(|a, b| {
                a.0.dot(&e)
                    .partial_cmp(&b.0.dot(&e))
                    .unwrap_or(std::cmp::Ordering::Equal)
            }) else {
                break;
            };
            r.hint = next;
            let moved = (next - e).norm();
            e = next;
            if moved <= 1e-12 {
                break;
            }
        }
        y[10..13].copy_from_slice((e * (20.0 * stop)).as_slice());
    }
    Ok(())
}
