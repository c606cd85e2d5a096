//! Impact of two rigid bodies with one contact point and Coulomb friction, integrated in the
//! normal impulse (Darboux-Keller), 002_b53e4779673eb6ed.txt section 1.
//!
//! $$\Delta\mathbf V_C = \mathbf B\mathbf I,\quad \mathbf B = (m_1^{-1} + m_2^{-1})\mathbf E_3 + \|b_{ij}\|,\quad
//!   b_{ij} = \sum_k (\mathbf J_k^{-1}(\mathbf G_k\mathbf C\times\mathbf e_i), \mathbf G_k\mathbf C\times\mathbf e_j) \quad (1.7)$$
//! With $\chi = I_n$ the independent variable, $d\mathbf V/d\chi = \mathbf B\,d\mathbf I/d\chi$ and
//! $d\mathbf I/d\chi = \mathbf n - \mu\,\mathbf V_t/|\mathbf V_t|$ while sliding (1.5); when the
//! slip speed reaches zero the body sticks if the tangential impulse rate $\boldsymbol\tau$ that
//! keeps $\mathbf V_t = 0$ satisfies $|\boldsymbol\tau| \le \mu$, and otherwise slides again in the
//! direction $\mathbf u$ the dynamics give ($\mathbf P_t\mathbf B(\mathbf n - \mu\mathbf u) =
//! \kappa\mathbf u$, $\kappa > 0$): no chattering and no division by zero at zero slip.
//! Compression ends at $V_n = 0$; restitution follows Newton ($V_n^+ = -eV_n^-$), Poisson
//! ($I_n = (1+e)I_{n,c}$) or Stronge (normal work in restitution $= -e^2\times$ that in
//! compression). The normal $\mathbf n$ points into the first body, and $\mathbf I$ is the impulse
//! on the first body (1.2)-(1.4).
//!
//! Every solve also returns the checks of Proposition 1: Kelvin's formula (1.10)/(1.11) against
//! the kinetic energy change computed directly from body velocities, (1.12), and the bounds (1.9)
//! and (1.13) with the eigenvalues of $\mathbf B$.

use crate::integrate::{Direction, Event, IntegrateError, Method, OdeSystem, Options, Stop, solve};
use nalgebra::{Matrix2, Matrix3, SymmetricEigen, Vector2, Vector3};

/// A rigid body at the contact.
#[derive(Clone, Debug)]
pub struct Body {
    /// Mass (kg); `None` for a fixed massive obstacle.
    pub mass: Option<f64>,
    /// Central inertia tensor (kg m^2), symmetric positive-definite.
    pub inertia: Matrix3<f64>,
    /// Vector from the centre of mass G to the contact point C (m).
    pub offset: Vector3<f64>,
}

/// Restitution law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// Newton: $V_n^+ = -e V_n^-$.
    Newton,
    /// Poisson: $I_n = (1 + e) I_{n,c}$.
    Poisson,
    /// Stronge: restitution work $= -e^2 \times$ compression work.
    Energetic,
}

impl Law {
    /// Scene name.
    pub fn name(self) -> &'static str {
        match self {
            Law::Newton => "newton",
            Law::Poisson => "poisson",
            Law::Energetic => "energetic",
        }
    }
}

/// The matrix B of (1.7) for two bodies (a body with no mass contributes nothing).
pub fn b_matrix(b1: &Body, b2: &Body) -> Option<Matrix3<f64>> {
    let mut b = Matrix3::zeros();
    for body in [b1, b2] {
        let Some(m) = body.mass else { continue };
        let jinv = body.inertia.try_inverse()?;
        b += Matrix3::identity() / m;
        let r = body.offset;
        for i in 0..3 {
            for j in 0..3 {
                let ei = Vector3::ith(i, 1.0);
                let ej = Vector3::ith(j, 1.0);
                b[(i, j)] += (jinv * r.cross(&ei)).dot(&r.cross(&ej));
            }
        }
    }
    Some(b)
}

/// A phase of the impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Phase {
    /// "slip", "stick" or "reversal" (slip resumed in a new direction).
    pub kind: String,
    /// Normal impulse at which the phase starts (N s).
    pub normal_impulse: f64,
}

/// The outcome of one impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ImpactResult {
    /// Impulse on the first body (N s).
    pub impulse: [f64; 3],
    /// Relative velocity at C after impact (m/s).
    pub v_rel_after: [f64; 3],
    /// Normal impulse at the end of compression (N s).
    pub compression_impulse: f64,
    /// Kinetic energy change computed from the bodies' velocities (J).
    pub energy_change: f64,
    /// Kelvin's formula (1.10), $\tfrac12(\mathbf V^- + \mathbf V^+, \mathbf I)$ (J).
    pub kelvin_energy_change: f64,
    /// Smallest eigenvalue of B (1/kg).
    pub lambda_min: f64,
    /// Largest eigenvalue of B (1/kg).
    pub lambda_max: f64,
    /// (1.9): $2|\mathbf V^-|/\lambda$ (N s).
    pub bound_upper: f64,
    /// (1.13): $|(\mathbf V^-, \mathbf n)|/\Lambda$ (N s).
    pub bound_lower: f64,
    /// Phases with the normal impulse at each switch.
    pub phases: Vec<Phase>,
    /// The bodies wedged: relative velocity zero, contact stresses persist (only with a singular
    /// $\mathbf B^*$); the impulse is the one at the moment of wedging.
    pub cut_off: bool,
    /// Work done.
    pub stats: crate::integrate::Stats,
    /// How the impact was solved: "integrate" (the Darboux-Keller equations (1.5) integrated in
    /// the normal impulse) or "planar-exact" ([`super::planar_impact`]).
    pub method: &'static str,
    /// Impulse of the support on the second body (N s), zero without a support.
    pub support_impulse: [f64; 3],
    /// A rough support's motion: "roll", "slide" or "detached" with the normal impulse at C at
    /// which each phase starts (empty without a rough support).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub support_phases: Vec<Phase>,
    /// Tangential velocity of A after the impact (m/s), with a rough support.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_support_after: Option<[f64; 3]>,
    /// The relative velocity along the impact: `(normal impulse, V)` at every accepted step.
    #[serde(skip)]
    pub path: Vec<(f64, [f64; 3])>,
}

/// Why an impact could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum ImpactError {
    /// Bad input.
    #[error("{field} = {value} is not allowed; allowed: {allowed}")]
    OutOfRange {
        /// Field.
        field: String,
        /// Value.
        value: String,
        /// Allowed range.
        allowed: String,
    },
    /// The solver failed.
    #[error("solver: {0}")]
    Integrate(#[from] IntegrateError),
    /// A Painleve-type case at the support: (3.6) with (3.2)/(3.3) admits no motion.
    #[error(
        "Painleve-type case at the support at normal impulse {chi:e} N s: {what}; classical impact theory has no solution here (deformations at A must be modelled)"
    )]
    Painleve {
        /// Normal impulse at C where it happens.
        chi: f64,
        /// What fails.
        what: String,
    },
    /// The integration broke a law it must keep: friction did positive work over a stage (a
    /// slip speeding up under its own friction), or the energy grew under the energetic law.
    /// Never a property of the restitution law: an error of the solver, said with where.
    #[error("solver inconsistency at normal impulse {chi:e} N s: {what}")]
    Inconsistent {
        /// Normal impulse at C where the stage ended (N s).
        chi: f64,
        /// What was broken, with its size.
        what: String,
    },
    /// The restitution condition was not reached.
    #[error("the {law} restitution condition was not reached by normal impulse {chi_max:e} N s")]
    NoEnd {
        /// Law.
        law: String,
        /// Largest normal impulse tried.
        chi_max: f64,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Slip,
    /// Slip held along a ray it has settled on (the friction direction frozen).
    Ray(Vector3<f64>),
    /// A slip starting from a stick that the support's motion broke: its rate starts at zero,
    /// so its direction is held at the one the dynamics give at the break until the slip exceeds
    /// the velocity tolerance (its turning rate grows like 1/|V_t| below that).
    Held(Vector3<f64>),
    Stick(Vector3<f64>),
}

/// A smooth support under the second body: $\tilde{\mathbf B}$, N and $\beta$ of (3.6).
#[derive(Clone, Debug)]
pub struct SmoothSupport {
    /// $\tilde{\mathbf B}$ of (3.4).
    pub b_tilde: Matrix3<f64>,
    /// Unit normal N at A.
    pub normal: Vector3<f64>,
    /// $\beta = (\mathbf B_A\mathbf N, \mathbf N)$.
    pub beta: f64,
}

/// A rough support under the second body (002 section 4): Coulomb friction $\mu^*$ at A.
#[derive(Clone, Debug)]
pub struct RoughSupport {
    /// $\tilde{\mathbf B}$ of (3.4).
    pub b_tilde: Matrix3<f64>,
    /// $\mathbf B_A$ of (3.4).
    pub b_a: Matrix3<f64>,
    /// Unit normal N at A, from the support into the body.
    pub normal: Vector3<f64>,
    /// Friction coefficient $\mu^*$ at A (> 0).
    pub mu: f64,
    /// Velocity of A before the impact (m/s; its tangential part is the slip at A).
    pub v_a: Vector3<f64>,
}

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
    fn name(self) -> &'static str {
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
struct AtA {
    b_tilde: Matrix3<f64>,
    /// $\mathbf B_A$ (rough only: a smooth support needs only $\beta$).
    b_a: Matrix3<f64>,
    b_a_inv: Matrix3<f64>,
    normal: Vector3<f64>,
    /// $\beta = (\mathbf B_A\mathbf N, \mathbf N)$ of (3.7).
    beta_n: f64,
    /// $\mu^*$; 0 for a smooth support.
    mu: f64,
    mode: SupportMode,
    /// slide direction used while the slip at A is below the floor (set when sliding starts)
    hint: Vector3<f64>,
    /// The slide started from rest (out of rolling, or from a stop): its rate starts at zero,
    /// so the direction is held at `hint` until the slip exceeds the velocity tolerance.
    held: bool,
    /// The band of a regularised friction law at A (0: Coulomb's with roll/slide switches): the
    /// friction is $\mu^* F_N^*\mathbf V_{A,T}/\sqrt{|\mathbf V_{A,T}|^2 + \text{band}^2}$,
    /// viscous below the band, Coulomb's above, and rolling is a slip that stays in the band (see
    /// [`REGULARISE_AFTER`]).
    regular: f64,
    floor: f64,
}

impl AtA {
    fn rough(&self) -> bool {
        self.mu > 0.0
    }

    /// Switches to the regularised law with viscous friction below `band` (see
    /// [`REGULARISE_AFTER`]); a roll becomes a slide that stays in the band.
    fn regularise(&mut self, band: f64) {
        self.regular = band;
        self.held = false;
        if self.mode == SupportMode::Roll {
            self.mode = SupportMode::Slide;
        }
    }

    /// The phase's name: "roll", "slide" or "detached"; "contact" for a smooth support;
    /// "regularised" for a support in contact under the regularised law.
    fn phase_name(&self) -> &'static str {
        if self.regular > 0.0 && self.mode != SupportMode::Free {
            return "regularised";
        }
        match (self.rough(), self.mode) {
            (false, SupportMode::Slide | SupportMode::Roll) => "contact",
            (_, m) => m.name(),
        }
    }

    fn tangential(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.normal * v.dot(&self.normal)
    }

    fn slide_dir(&self, va: &Vector3<f64>) -> Vector3<f64> {
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
    fn roll_reaction(&self, f: &Vector3<f64>) -> Vector3<f64> {
        self.b_a_inv * (self.b_tilde * f)
    }

    /// $\mathbf I = \mathbf N - \mu^*\mathbf e_T$ and $\beta = (\mathbf B_A\mathbf I, \mathbf N)$ (4.3)-(4.4).
    fn slide_i(&self, va: &Vector3<f64>) -> (Vector3<f64>, f64) {
        if !self.rough() {
            return (self.normal, self.beta_n);
        }
        let i = self.normal - self.slide_dir(va) * self.mu;
        (i, (self.b_a * i).dot(&self.normal))
    }

    /// The reaction $\mathbf F^*$ per unit normal impulse at C.
    fn reaction(&self, f: &Vector3<f64>, va: &Vector3<f64>) -> Vector3<f64> {
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
    fn va_rate(&self, f: &Vector3<f64>, fs: &Vector3<f64>) -> Vector3<f64> {
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
    fn b_eff(&self, b: &Matrix3<f64>, va: &Vector3<f64>) -> Matrix3<f64> {
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

struct Keller {
    at_a: Option<AtA>,
    b: Matrix3<f64>,
    n: Vector3<f64>,
    mu: f64,
    mode: Mode,
    /// slip direction used when |V_t| is below the floor (set at a re-slide)
    u_hint: Vector3<f64>,
    floor: f64,
}

/// $\mathbf V_A$ from the state (zero without a support).
fn va_of(y: &[f64]) -> Vector3<f64> {
    if y.len() >= 13 {
        Vector3::new(y[10], y[11], y[12])
    } else {
        Vector3::zeros()
    }
}

impl Keller {
    fn tangential(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.n * v.dot(&self.n)
    }

    /// The contact force direction at C per unit normal impulse.
    fn rate(&self, v: &Vector3<f64>, va: &Vector3<f64>) -> Vector3<f64> {
        match self.mode {
            Mode::Stick(tau) => match &self.at_a {
                // the matrix that holds V_t = 0 turns with a slide at A
                Some(a) if a.rough() && a.mode == SupportMode::Slide => {
                    self.n + stick_tau(&a.b_eff(&self.b, va), &self.n).unwrap_or(tau)
                }
                _ => self.n + tau,
            },
            Mode::Ray(u) | Mode::Held(u) => self.n - u * self.mu,
            Mode::Slip => {
                let vt = self.tangential(v);
                let s = vt.norm();
                let u = if s > self.floor { vt / s } else { self.u_hint };
                self.n - u * self.mu
            }
        }
    }

    /// $d\mathbf V_C/d\chi$, the support's reaction and $d\mathbf V_A/d\chi$ for the contact force
    /// direction `f`.
    fn rates(
        &self,
        f: &Vector3<f64>,
        va: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        match &self.at_a {
            Some(a) => {
                let fs = a.reaction(f, va);
                let dv = self.b * f - a.b_tilde.transpose() * fs;
                (dv, fs, a.va_rate(f, &fs))
            }
            None => (self.b * f, Vector3::zeros(), Vector3::zeros()),
        }
    }

    /// The matrix that governs V_C near a stick/slip switch at C (see [`AtA::b_eff`]).
    fn b_stick(&self, va: &Vector3<f64>) -> Matrix3<f64> {
        match &self.at_a {
            Some(a) => a.b_eff(&self.b, va),
            None => self.b,
        }
    }
}

impl OdeSystem for Keller {
    fn dim(&self) -> usize {
        if self.at_a.is_some() { 13 } else { 10 }
    }
    fn rhs(&self, _chi: f64, y: &[f64], dy: &mut [f64]) {
        let v = Vector3::new(y[0], y[1], y[2]);
        let va = va_of(y);
        let d = self.rate(&v, &va);
        let (dv, fs, dva) = self.rates(&d, &va);
        dy[..3].copy_from_slice(dv.as_slice());
        dy[3..6].copy_from_slice(d.as_slice());
        dy[6] = v.dot(&self.n);
        dy[7..10].copy_from_slice(fs.as_slice());
        if self.at_a.is_some() {
            dy[10..13].copy_from_slice(dva.as_slice());
        }
    }
}

/// The rate of the relative velocity at C for a contact force direction (see [`velocity_rate`]).
type Rate<'a> = &'a dyn Fn(&Vector3<f64>) -> Vector3<f64>;

/// Orthonormal tangent basis of the plane normal to `n`.
fn tangent_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let a = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = (a - n * a.dot(n)).normalize();
    (t1, n.cross(&t1))
}

/// The tangential rate $\boldsymbol\tau$ of the impulse that keeps $\mathbf V_t = 0$ under the matrix
/// `b`: the least-norm solution of $\mathbf B_{tt}\boldsymbol\tau = -\mathbf B_{tn}$ ($\mathbf B_{tt}$ may be
/// singular with fixed points, (2.5)); `None` when that system has no solution.
fn stick_tau(b: &Matrix3<f64>, n: &Vector3<f64>) -> Option<Vector3<f64>> {
    let (t1, t2) = tangent_basis(n);
    let bt = Matrix2::new(
        t1.dot(&(b * t1)),
        t1.dot(&(b * t2)),
        t2.dot(&(b * t1)),
        t2.dot(&(b * t2)),
    );
    let rhs = -Vector2::new(t1.dot(&(b * n)), t2.dot(&(b * n)));
    let scale = b.norm().max(f64::MIN_POSITIVE);
    let x = bt.svd(true, true).solve(&rhs, 1e-12 * scale).ok()?;
    ((bt * x - rhs).norm() <= 1e-9 * scale).then(|| t1 * x[0] + t2 * x[1])
}

/// At zero slip: stick (with the tangential rate that keeps $V_t = 0$) or the direction to slide;
/// `Err(None)` where neither is consistent: the stick needs a tangential rate outside the
/// friction cone and every slip direction decays (possible only where the matrix is not
/// symmetric: a rough support that slides).
fn stick_or_slide(
    b: &Matrix3<f64>,
    rate: Rate,
    n: &Vector3<f64>,
    mu: f64,
) -> Result<Vector3<f64>, Option<Vector3<f64>>> {
    if let Some(tau) = stick_tau(b, n)
        && tau.norm() <= mu * (1.0 + 1e-12)
    {
        return Ok(tau);
    }
    // slide: the direction u on the unit circle with P_t B (n - mu u) parallel to u, growing
    // (with the support's reaction where it pushes); a stable root first, then the largest rate
    let best = slide_rays(rate, n, mu, 720)
        .into_iter()
        .filter(|r| r.rate > 0.0)
        .max_by(|x, y| {
            (x.stable, x.rate)
                .partial_cmp(&(y.stable, y.rate))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    Err(best.map(|r| r.u))
}

/// The slide direction [`stick_or_slide`] found at C, or, where it found none: with a support,
/// a Painleve-type case at C (its friction makes the matrix of C non-symmetric, and C then has
/// no consistent motion); without one (B symmetric, where this does not occur but for rounding
/// at a degenerate B), the first tangent direction.
fn slide_at_c(
    u: Option<Vector3<f64>>,
    supported: bool,
    n: &Vector3<f64>,
    chi: f64,
) -> Result<Vector3<f64>, ImpactError> {
    match u {
        Some(u) => Ok(u),
        None if supported => Err(no_support_motion(
            chi,
            "C can neither stick (the tangential rate it needs lies outside the friction cone) nor slip (every slip direction decays) while the support moves as it does",
        )),
        None => Ok(tangent_basis(n).0),
    }
}

/// A ray of slip directions: `u` on the unit circle with $P_t\mathbf B(\mathbf n - \mu\mathbf u)$
/// parallel to `u`; `rate` is the slip speed's rate along it (positive: the slip grows), `stable`
/// whether nearby directions turn towards it.
#[derive(Clone, Copy, Debug)]
struct SlipRay {
    u: Vector3<f64>,
    rate: f64,
    stable: bool,
}

/// Every slip ray, found by scanning the circle and bisecting the cross product
/// $\mathbf u \times P_t\mathbf B(\mathbf n - \mu\mathbf u)$. A root where it falls through zero
/// as the angle grows is stable: a slip direction near it turns towards it.
///
/// The samples sit half a step off the tangent basis (the rays of a planar or symmetric impact
/// lie on it, where the cross product is zero but for rounding, of either sign), and the scan
/// closes on the value of its first sample: evaluating the same direction twice (at 0 and at
/// 2 pi, whose sines differ by rounding) could give two signs, and a ray at 0 was then missed
/// (tests/regression_planar_rod.rs).
fn slide_rays(rate: Rate, n: &Vector3<f64>, mu: f64, samples: usize) -> Vec<SlipRay> {
    let (t1, t2) = tangent_basis(n);
    let f = |th: f64| {
        let u = t1 * th.cos() + t2 * th.sin();
        let w = rate(&(n - u * mu));
        let wt = Vector2::new(t1.dot(&w), t2.dot(&w));
        let uu = Vector2::new(th.cos(), th.sin());
        (uu.x * wt.y - uu.y * wt.x, uu.dot(&wt), u)
    };
    let step = 2.0 * std::f64::consts::PI / samples as f64;
    let angle = |k: usize| (k as f64 + 0.5) * step;
    let mut rays = Vec::new();
    let first = f(angle(0));
    let mut prev = first;
    for k in 1..=samples {
        let (th0, th1) = (angle(k - 1), angle(k));
        let cur = if k == samples { first } else { f(th1) };
        // a root in (th0, th1]: a change of sign, or a zero reached from either side (a zero
        // at th0 belongs to the interval before)
        let crossing = (prev.0 != 0.0) && (cur.0 == 0.0 || prev.0.signum() != cur.0.signum());
        if crossing {
            let stable = prev.0 > 0.0;
            let (mut a, mut bb) = (th0, th1);
            let pa = prev.0 > 0.0;
            for _ in 0..60 {
                let mid = 0.5 * (a + bb);
                let fm = f(mid).0;
                if fm != 0.0 && (fm > 0.0) == pa {
                    a = mid;
                } else {
                    bb = mid;
                }
            }
            let (_, rate, u) = f(0.5 * (a + bb));
            rays.push(SlipRay { u, rate, stable });
        }
        prev = cur;
    }
    rays
}

/// The stable rays along which a slip dies out (its speed falls at a constant rate there): a
/// slip that settles on one reaches zero at a simple root of $(\mathbf V_t, \mathbf u) -
/// \text{stop}$, where $|\mathbf V_t|$ only touches zero between two samples of a step. With a
/// large $\mu$ there can be two; which one a slip settles on depends on where it starts.
fn decay_rays(rate: Rate, n: &Vector3<f64>, mu: f64) -> Vec<Vector3<f64>> {
    slide_rays(rate, n, mu, 180)
        .into_iter()
        .filter(|r| r.stable && r.rate < 0.0)
        .map(|r| r.u)
        .collect()
}

fn out_of_range(field: &str, value: String, allowed: &str) -> ImpactError {
    ImpactError::OutOfRange {
        field: field.into(),
        value,
        allowed: allowed.into(),
    }
}

/// Solves one impact. `v_minus` is the relative velocity at C before impact (m/s), with
/// $(\mathbf V^-, \mathbf n) < 0$ (approaching).
#[allow(clippy::too_many_arguments)]
pub fn impact(
    b1: &Body,
    b2: &Body,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let bad = out_of_range;
    let b = b_matrix(b1, b2).ok_or_else(|| {
        bad(
            "body.inertia",
            "singular".into(),
            "symmetric positive-definite",
        )
    })?;
    let mut r = impact_with_matrix(&b, normal, v_minus, mu, law, e, rtol)?;
    r.energy_change = kinetic_change(b1, b2, &v_minus, &Vector3::from(r.impulse));
    Ok(r)
}

/// Solves one impact for a given matrix $\mathbf B$ (or $\mathbf B^*$ of (2.1), possibly
/// singular); `energy_change` is then Kelvin's (1.11) from B. A cut-off impact (the relative
/// velocity vanishes while sticking is possible and $\mathbf B(\mathbf n + \boldsymbol\tau) = 0$:
/// the bodies wedge) is reported with `cut_off = true`.
pub fn impact_with_matrix(
    b: &Matrix3<f64>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    impact_general(b, None, normal, v_minus, mu, law, e, rtol)
}

/// As [`impact_with_matrix`], with an optional smooth support under the second body (section
/// 3): the support reacts only while $\alpha < 0$, so $\mathbf B$ switches to $\mathbf B^*$ (3.8).
#[allow(clippy::too_many_arguments)]
pub fn impact_general(
    b: &Matrix3<f64>,
    support: Option<SmoothSupport>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let at_a = support.map(|s| {
        (
            AtA {
                b_tilde: s.b_tilde,
                b_a: Matrix3::zeros(),
                b_a_inv: Matrix3::zeros(),
                normal: s.normal.normalize(),
                beta_n: s.beta,
                mu: 0.0,
                mode: SupportMode::Slide,
                hint: Vector3::zeros(),
                held: false,
                regular: 0.0,
                floor: 0.0,
            },
            Vector3::zeros(),
            false,
        )
    });
    impact_core(b, at_a, normal, v_minus, mu, law, e, rtol)
}

/// As [`impact_general`], with Coulomb friction $\mu^*$ at the support (002 section 4): the
/// support rolls (4.2), slides (4.3)-(4.4) or lets go, switching as its slip stops, its reaction
/// leaves the friction cone or would have to pull; the slide direction at a start from rest
/// solves (4.5). `start` forces the support's mode at the start (the branches of a Painleve
/// case with two solutions); `None` takes the one (3.6) admits.
#[allow(clippy::too_many_arguments)]
pub fn impact_rough(
    b: &Matrix3<f64>,
    rough: RoughSupport,
    start: Option<SupportMode>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    if !(rough.mu > 0.0 && rough.mu.is_finite()) {
        return Err(out_of_range(
            "support.mu",
            rough.mu.to_string(),
            "mu* > 0 (0 is the smooth support)",
        ));
    }
    let b_a_inv = rough.b_a.try_inverse().ok_or_else(|| {
        out_of_range(
            "support",
            "singular B_A".into(),
            "a second body with mass and an invertible inertia",
        )
    })?;
    let nn = rough.normal.normalize();
    let a = AtA {
        b_tilde: rough.b_tilde,
        b_a: rough.b_a,
        b_a_inv,
        normal: nn,
        beta_n: (rough.b_a * nn).dot(&nn),
        mu: rough.mu,
        mode: start.unwrap_or(SupportMode::Roll),
        hint: Vector3::zeros(),
        held: false,
        regular: 0.0,
        floor: 0.0,
    };
    impact_core(
        b,
        Some((a, rough.v_a, start.is_some())),
        normal,
        v_minus,
        mu,
        law,
        e,
        rtol,
    )
}

/// beta of (4.4) below this fraction of $(\mathbf B_A\mathbf N, \mathbf N)$ ends the classical
/// solution as a Painleve-type case: the reaction $F_N^* = -\alpha/\beta$ is then over 1000 times
/// its scale and grows without bound as the slide turns further. It does in the seeded cases
/// that reach it: of the 226 of `constrained_fail`'s first 2e5 that stop here, 221 reach 1e-5 of
/// $(\mathbf B_A\mathbf N, \mathbf N)$ too when the floor is set there, and 4 of the rest stall
/// on the blow-up (step size too small).
const BETA_FLOOR: f64 = 1e-3;

/// A slip at A below this many times its stop (5e-10 of the velocity scale at rtol 1e-10) slides
/// with its friction direction frozen, until it exceeds [`RELEASE_ABOVE`] times the stop: near
/// zero the direction's turning rate grows like $1/|\mathbf V_{A,T}|$, and a slip that dies there,
/// or hovers at the edge of the friction cone (a reaction that grazes the cone), makes the system
/// stiff without bound. The friction direction differs from the slip's only while the slip is
/// under 1e3 stop (1e-9 of the velocity scale at rtol 1e-10), which bounds the change in the
/// velocities by the order of that slip. A slide from rest is held the same way: its rate starts
/// at zero.
const HOLD_BELOW: f64 = 500.0;

/// The slip (in stops) above which a held direction at A is freed (see [`HOLD_BELOW`]).
const RELEASE_ABOVE: f64 = 1e3;

/// After this many switches of A's slip about its band (its slip nearly stopping, stopping, or
/// re-established), or where the solver cannot follow the exact law in a stage, the support's
/// friction is regularised for the rest of the impact: $\mathbf V_{A,T}/\sqrt{|\mathbf V_{A,T}|^2 +
/// b^2}$ for the slide direction, b = [`RELEASE_ABOVE`] stops (viscous below b, Coulomb's above,
/// smooth across: a grazing slip sits at the edge), with no roll/slide switches (rolling is then
/// a slip that stays in the band). This ends a reaction that grazes the friction cone, where the
/// slide direction of (4.5) moves faster than its slip grows and the exact law switches without
/// end. The band is stiff and is integrated by Radau5; the velocities change by the order of the
/// band (1e-9 of the velocity scale at rtol 1e-10).
const REGULARISE_AFTER: usize = 200;

/// A terminal event (every switch of the impact stops the solve).
fn stop_at<'a>(
    name: &str,
    g: &'a (dyn Fn(f64, &[f64]) -> f64 + 'a),
    direction: Direction,
) -> Event<'a> {
    Event::new(name, g, direction, true)
}

/// Why the support admits no motion at some instant.
fn no_support_motion(chi: f64, what: &str) -> ImpactError {
    ImpactError::Painleve {
        chi,
        what: what.into(),
    }
}

/// A slide at A whose beta of (4.4) fell to [`BETA_FLOOR`] with alpha < 0.
fn beta_vanishes(chi: f64, beta: f64) -> ImpactError {
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
fn start_slide_dirs(r: &AtA, f: &Vector3<f64>) -> Vec<(Vector3<f64>, f64, bool)> {
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
fn c_direction_with(
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
fn decide_support(
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

/// The mode of a slip that starts from rest along the ray `sys.u_hint` ([`stick_or_slide`]'s
/// slide direction: $P_t\mathbf B(\mathbf n - \mu\mathbf u) = \kappa\mathbf u$, $\kappa > 0$).
/// Without a support the matrix is constant and the slip grows along that ray exactly, so its
/// friction direction is held there: left free, a slip that grows slowly (mu just below the
/// critical value, kappa near 0) stays near zero for long, where its direction's turning rate
/// grows like $1/|\mathbf V_t|$, and the steps collapse (`perf::rigid_sample`'s degenerate cases,
/// tests/regression_slip_from_rest_near_critical.rs). With a support the matrix turns with the
/// support's motion and the slip is left free.
fn from_rest(sys: &Keller) -> Mode {
    if sys.at_a.is_none() {
        Mode::Ray(sys.u_hint)
    } else {
        Mode::Slip
    }
}

/// The impact with an optional support: its state, the velocity of A before the impact and
/// whether its start mode is forced.
#[allow(clippy::too_many_arguments)]
fn impact_core(
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
const TURNED_ABOVE: f64 = 1e4;

/// How many times `rtol x |V-| x |I|` an energy balance may miss by before it is a solver
/// inconsistency (the integrated impulse carries an error of order `rtol |I|`).
const ENERGY_SLACK: f64 = 1e3;

/// The work of friction over one stage of a free impact, from its start `y0` and end `y1`: the
/// kinetic energy change $(\mathbf V_0, \Delta\mathbf I) + \tfrac12(\mathbf B\Delta\mathbf I,
/// \Delta\mathbf I)$ less the normal work $\int V_n\,d\chi$ (state 6). It is never positive
/// (the friction opposes the slip, or a stick does no work); a positive one is a slip pushed
/// along by its own friction, reported as an inconsistency at the stage's end.
fn friction_work_check(
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

/// Kinetic energy change of the bodies computed from their velocities (1.2)-(1.3): body 1
/// translating with the relative velocity, body 2 at rest (any split gives the same change).
pub fn kinetic_change(b1: &Body, b2: &Body, v_minus: &Vector3<f64>, imp: &Vector3<f64>) -> f64 {
    kinetic_change_supported(b1, b2, v_minus, imp, None)
}

/// As [`kinetic_change`], with the support impulse `(G2->A, I*)` on the second body (3.1).
pub fn kinetic_change_supported(
    b1: &Body,
    b2: &Body,
    v_minus: &Vector3<f64>,
    imp: &Vector3<f64>,
    support: Option<(Vector3<f64>, Vector3<f64>)>,
) -> f64 {
    kinetic_change_moving(b1, b2, v_minus, &Vector3::zeros(), imp, support)
}

/// As [`kinetic_change_supported`], with the second body translating at `v2` before the impact
/// (a support point that slides at `v2`) and the first at `v2 + v_minus`.
pub fn kinetic_change_moving(
    b1: &Body,
    b2: &Body,
    v_minus: &Vector3<f64>,
    v2: &Vector3<f64>,
    imp: &Vector3<f64>,
    support: Option<(Vector3<f64>, Vector3<f64>)>,
) -> f64 {
    let ke = |body: &Body, v: &Vector3<f64>, w: &Vector3<f64>| -> f64 {
        body.mass.map_or(0.0, |m| {
            0.5 * m * v.norm_squared() + 0.5 * w.dot(&(body.inertia * w))
        })
    };
    let mut before = 0.0;
    let mut after = 0.0;
    for (k, body) in [b1, b2].into_iter().enumerate() {
        let Some(m) = body.mass else { continue };
        let sign = if k == 0 { 1.0 } else { -1.0 };
        // the relative velocity is carried by body 1, or by body 2 when body 1 is fixed
        let v0 = match (k, b1.mass) {
            (0, _) => *v_minus + v2,
            (_, None) => -v_minus,
            _ => *v2,
        };
        let w0 = Vector3::zeros();
        let (extra_f, extra_m) = match (k, support) {
            (1, Some((g2a, istar))) => (istar, g2a.cross(&istar)),
            _ => (Vector3::zeros(), Vector3::zeros()),
        };
        let dv = (imp * sign + extra_f) / m;
        let dw = body.inertia.try_inverse().unwrap_or_else(Matrix3::zeros)
            * (body.offset.cross(&(imp * sign)) + extra_m);
        before += ke(body, &v0, &w0);
        after += ke(body, &(v0 + dv), &(w0 + dw));
    }
    after - before
}
