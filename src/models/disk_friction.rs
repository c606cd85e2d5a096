//! A flat disk of radius a under uniform pressure, sliding with speed V and spinning with angular
//! velocity omega on a plane with Coulomb friction f: the friction force and moment by direct
//! two-dimensional quadrature, against Sinitsyn's closed forms with complete elliptic integrals,
//! 001_989b2e860c39ca83.txt (2.3):
//! $$\frac{dV}{d\Omega} = \mu\frac{k f_1(k)}{f_3(k)}\ (k = V/\Omega \le 1),\qquad
//!   \frac{dV}{d\Omega} = \mu\frac{f_1(k_1)}{f_2(k_1)}\ (k_1 = \Omega/V \le 1),\qquad \Omega = \omega a,\ \mu = 3\rho^2/a^2,$$
//! i.e. the force-to-moment ratio $F/M = (3/a)\,k f_1(k)/f_3(k)$. $K$ and $E$ come from the `ellip`
//! crate (Carlson's symmetric forms); near $k = 1$ they are evaluated from the complementary
//! parameter $m_c = (1-k)(1+k)$, since forming $m = k^2$ loses the digits that matter.
use crate::models::doc as d;

/// $K(k)$ and $E(k)$ for modulus `k` in [0, 1].
pub fn k_e(k: f64) -> (f64, f64) {
    crate::algebra::expr::complete_elliptic(k)
}

/// $f_1$, $f_2$, $f_3$ of (2.3).
pub fn f123(k: f64) -> (f64, f64, f64) {
    if k < SERIES_BELOW {
        return f123_series(k);
    }
    if k >= 1.0 {
        // K(1) is infinite but enters only as (1 - k^2) K -> 0; E(1) = 1
        return (2.0, 2.0, 2.0);
    }
    let (kk, ee) = k_e(k);
    let k2 = k * k;
    let f1 = (1.0 / k2 + 1.0) * ee - (1.0 / k2 - 1.0) * kk;
    let f2 = ((4.0 - 2.0 / k2) * ee - (1.0 / k2 - 1.0) * (3.0 * k2 - 2.0) * kk) / k;
    let f3 = (4.0 - 2.0 * k2) * ee - (1.0 - k2) * kk;
    (f1, f2, f3)
}

/// Series coefficients $c_n$ with $K = \frac{\pi}{2}\sum c_n k^{2n}$ and
/// $E = \frac{\pi}{2}\sum c_n k^{2n}/(1-2n)$, $c_n = \left(\binom{2n}{n}/4^n\right)^2$.
fn ke_series(n: usize) -> Vec<f64> {
    let mut c = vec![1.0; n];
    for i in 1..n {
        let r = (2 * i - 1) as f64 / (2 * i) as f64;
        c[i] = c[i - 1] * r * r;
    }
    c
}

/// Below this modulus $f_1$, $f_2$, $f_3$ come from the power series: the closed forms subtract
/// terms of size $k^{-2}$ to leave O(1) (and $f_2 = O(k)$), losing $2\log_{10}(1/k)$ digits.
const SERIES_BELOW: f64 = 0.25;

/// $f_1$, $f_2$, $f_3$ of (2.3) from the series of $K$ and $E$ in $k^2$ (for small k).
fn f123_series(k: f64) -> (f64, f64, f64) {
    let c = ke_series(40);
    let e: Vec<f64> = c
        .iter()
        .enumerate()
        .map(|(n, cn)| cn / (1.0 - 2.0 * n as f64))
        .collect();
    let k2 = k * k;
    let half_pi = std::f64::consts::FRAC_PI_2;
    // coefficient of k^(2n) in each function; k^-2 (E -+ K) shifts the index down by one
    let (mut s1, mut s2, mut s3) = (0.0, 0.0, 0.0);
    let mut p = 1.0;
    for n in 0..c.len() - 1 {
        let (en, cn) = (e[n], c[n]);
        let (en1, cn1) = (e[n + 1], c[n + 1]);
        let ep = if n > 0 { e[n - 1] } else { 0.0 };
        let cp = if n > 0 { c[n - 1] } else { 0.0 };
        // f1 = k^-2 (E - K) + E + K
        let a1 = (en1 - cn1) + en + cn;
        // k f2 = 2 k^-2 (K - E) + 4E - 5K + 3 k^2 K
        let a2 = 2.0 * (cn1 - en1) + 4.0 * en - 5.0 * cn + 3.0 * cp;
        // f3 = 4E - 2 k^2 E - K + k^2 K
        let a3 = 4.0 * en - 2.0 * ep - cn + cp;
        s1 += a1 * p;
        s2 += a2 * p;
        s3 += a3 * p;
        p *= k2;
    }
    (half_pi * s1, half_pi * s2 / k, half_pi * s3)
}

/// Sinitsyn's friction force and moment for uniform pressure in closed form, per unit normal
/// load and friction coefficient: $(F/(fN),\ M/(fNa))$ as magnitudes, for $k = V/\Omega$ (any
/// $k \ge 0$; $k > 1$ uses $k_1 = 1/k$). From (2.3)'s $f_1$, $f_2$, $f_3$ with the normalisation
/// fixed by the two limits (pure spin: $M = 2fNa/3$; pure sliding: $F = fN$):
/// $F = \frac{4}{3\pi}k f_1(k)$, $M = \frac{4}{9\pi}f_3(k)$ for $k \le 1$;
/// $F = \frac{4}{3\pi}f_1(k_1)$, $M = \frac{4}{9\pi}f_2(k_1)$ for $k \ge 1$.
/// Their ratio is (2.3)'s $(3/a)\,k f_1/f_3$ and $(3/a)\,f_1(k_1)/f_2(k_1)$.
pub fn force_moment_elliptic(k: f64) -> (f64, f64) {
    let cf = 4.0 / (3.0 * std::f64::consts::PI);
    let cm = 4.0 / (9.0 * std::f64::consts::PI);
    if k <= 1.0 {
        let (f1, _, f3) = f123(k);
        (cf * k * f1, cm * f3)
    } else if k.is_infinite() {
        (1.0, 0.0)
    } else {
        let (f1, f2, _) = f123(1.0 / k);
        (cf * f1, cm * f2)
    }
}

/// Friction on a disk of radius `a` pressed with unit normal load, pressure linear over the disk,
/// $p = (1 + \mathbf g\cdot\mathbf x)/(\pi a^2)$ with $\mathbf g = 4\mathbf c/a^2$ so that the centre
/// of pressure is at $\mathbf c$ from the centre O (uniform pressure: $\mathbf c = 0$; the
/// pressure stays non-negative for $|\mathbf c| \le a/4$, 001 (1.8)). The base moves with velocity
/// `v_o` of O and spin `omega` about the normal. Returns the force $\mathbf F/f$ and the moment
/// about O, $M_O/f$, and an estimate of the quadrature error.
///
/// The velocity at $\mathbf x$ is $\omega\,\hat z\times(\mathbf x - \mathbf P)$, P the
/// instantaneous centre. In polar coordinates $(r, \psi)$ about P the friction direction depends
/// on $\psi$ only and the pressure is linear in r, so the radial integrals are exact; the angular
/// integral is adaptive Gauss-Legendre to `tol`. With P outside the disk the angle is mapped by
/// $\sin\psi = (a/d)\sin\phi$, which removes the square-root ends at the tangent lines.
/// Written by hand: the radial integrals are exact and only a one-dimensional adaptive rule is
/// needed, which is a few lines on top of [`gauss_legendre`].
pub fn friction(v_o: [f64; 2], omega: f64, c: [f64; 2], a: f64, tol: f64) -> FrictionResult {
    let p0 = 1.0 / (std::f64::consts::PI * a * a);
    let g = [4.0 * c[0] / (a * a), 4.0 * c[1] / (a * a)];
    let speed = v_o[0].hypot(v_o[1]);
    if omega == 0.0 {
        if speed == 0.0 {
            return FrictionResult::default();
        }
        // pure translation: F = -v/|v|, M_O = -(c x v)/|v|
        let (ux, uy) = (v_o[0] / speed, v_o[1] / speed);
        return FrictionResult {
            force: [-ux, -uy],
            moment: -(c[0] * uy - c[1] * ux),
            error: 0.0,
        };
    }
    let sgn = omega.signum();
    let pp = [-v_o[1] / omega, v_o[0] / omega];
    let d = pp[0].hypot(pp[1]);
    // u: from P towards O (any direction when P = O)
    let u = if d > 0.0 {
        [-pp[0] / d, -pp[1] / d]
    } else {
        [1.0, 0.0]
    };
    let gp = 1.0 + g[0] * pp[0] + g[1] * pp[1];
    // integrand per unit psi: (Fx, Fy, M_O) before the factor -f sgn p0
    let at = |psi: f64, h: f64, s: f64, dsin: f64, inside: bool| -> [f64; 3] {
        let (sn, cs) = psi.sin_cos();
        let e = [u[0] * cs - u[1] * sn, u[0] * sn + u[1] * cs];
        let ge = g[0] * e[0] + g[1] * e[1];
        let (rad, mom) = if inside {
            // r from 0 to r2 = h + s (h = d cos psi may be negative)
            let r2 = h + s;
            (
                gp * r2 * r2 / 2.0 + ge * r2 * r2 * r2 / 3.0,
                gp * r2 * r2 * (2.0 * s - h) / 6.0 + ge * r2 * r2 * r2 * (3.0 * s - h) / 12.0,
            )
        } else {
            // r from h - s to h + s; the pressure at the chord's midpoint, the foot of the
            // perpendicular from O, at (d sin psi) (z x e) from O: formed from bounded terms
            // (gp + ge h is the same number as a difference of two of size |g| d)
            let pmid = 1.0 + dsin * (g[1] * e[0] - g[0] * e[1]);
            (
                pmid * 2.0 * h * s + ge * 2.0 * s * s * s / 3.0,
                2.0 * s * s * s / 3.0 * (gp + 2.0 * ge * h),
            )
        };
        [-e[1] * rad, e[0] * rad, mom]
    };
    let mut acc = Acc::default();
    if d <= a {
        let f = |psi: f64| {
            let sn = psi.sin();
            let h = d * psi.cos();
            let s = ((a - d * sn) * (a + d * sn)).max(0.0).sqrt();
            at(psi, h, s, d * sn, true)
        };
        let pi = std::f64::consts::PI;
        for (lo, hi) in [
            (-pi, -pi / 2.0),
            (-pi / 2.0, 0.0),
            (0.0, pi / 2.0),
            (pi / 2.0, pi),
        ] {
            adaptive(&f, lo, hi, tol / 4.0, 0, &mut acc);
        }
    } else {
        let ratio = a / d;
        let f = |phi: f64| {
            let (sp, cp) = phi.sin_cos();
            let sn = ratio * sp;
            let psi = sn.asin();
            let cpsi = ((1.0 - sn) * (1.0 + sn)).sqrt();
            let h = d * cpsi;
            let s = a * cp.max(0.0);
            let jac = ratio * cp.max(0.0) / cpsi;
            let v = at(psi, h, s, a * sp, false);
            [v[0] * jac, v[1] * jac, v[2] * jac]
        };
        let hp = std::f64::consts::FRAC_PI_2;
        adaptive(&f, -hp, 0.0, tol / 2.0, 0, &mut acc);
        adaptive(&f, 0.0, hp, tol / 2.0, 0, &mut acc);
    }
    let k = -sgn * p0;
    FrictionResult {
        force: [k * acc.sum[0], k * acc.sum[1]],
        moment: k * acc.sum[2],
        error: p0 * acc.err,
    }
}

/// Force (over f), moment about O (over f) and the quadrature's error estimate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrictionResult {
    /// $\mathbf F/f$ per unit normal load.
    pub force: [f64; 2],
    /// $M_O/f$ per unit normal load.
    pub moment: f64,
    /// Estimated absolute error of the three components.
    pub error: f64,
}

#[derive(Default)]
struct Acc {
    sum: [f64; 3],
    err: f64,
}

/// Nodes and weights of the 12-point Gauss-Legendre rule on [-1, 1], computed once.
fn gl12() -> &'static (Vec<f64>, Vec<f64>) {
    static NODES: std::sync::OnceLock<(Vec<f64>, Vec<f64>)> = std::sync::OnceLock::new();
    NODES.get_or_init(|| gauss_legendre(12))
}

fn rule(f: &dyn Fn(f64) -> [f64; 3], lo: f64, hi: f64) -> [f64; 3] {
    let (xs, ws) = gl12();
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    let mut s = [0.0; 3];
    for (x, w) in xs.iter().zip(ws) {
        let v = f(mid + half * x);
        for i in 0..3 {
            s[i] += w * half * v[i];
        }
    }
    s
}

/// Adaptive bisection: accept an interval when its 12-point value and the sum over its halves
/// agree to `tol` (absolute, max over components); the halves' sum is kept.
fn adaptive(f: &dyn Fn(f64) -> [f64; 3], lo: f64, hi: f64, tol: f64, depth: u32, acc: &mut Acc) {
    let whole = rule(f, lo, hi);
    let mid = 0.5 * (lo + hi);
    let (l, r) = (rule(f, lo, mid), rule(f, mid, hi));
    let diff = (0..3)
        .map(|i| (l[i] + r[i] - whole[i]).abs())
        .fold(0.0, f64::max);
    // below a few ulps of the interval's own contribution no bisection can help
    let floor = 16.0 * f64::EPSILON * (0..3).map(|i| l[i].abs() + r[i].abs()).fold(0.0, f64::max);
    // (a NaN is accepted and propagates instead of bisecting forever)
    if diff.is_nan() || diff <= tol.max(floor) || depth >= 30 {
        for i in 0..3 {
            acc.sum[i] += l[i] + r[i];
        }
        acc.err += diff;
    } else {
        adaptive(f, lo, mid, tol / 2.0, depth + 1, acc);
        adaptive(f, mid, hi, tol / 2.0, depth + 1, acc);
    }
}

/// Friction force along the sliding direction and moment about the centre (both per unit normal
/// load, f = 1, a = 1) for sliding speed `v` and spin `w`, by Gauss-Legendre in r (with the
/// instantaneous centre's radius as a node boundary) and the midpoint rule in theta.
pub fn quadrature(v: f64, w: f64, nr: usize, nt: usize) -> (f64, f64) {
    // the instantaneous centre sits at r = v/w on theta = pi/2: split the radial integral there
    let rc = if w > 0.0 { (v / w).min(1.0) } else { 1.0 };
    let (xs, ws) = gauss_legendre(nr);
    let mut f = 0.0;
    let mut m = 0.0;
    let segments: Vec<(f64, f64)> = if rc > 0.0 && rc < 1.0 {
        vec![(0.0, rc), (rc, 1.0)]
    } else {
        vec![(0.0, 1.0)]
    };
    for (lo, hi) in segments {
        for (x, wr) in xs.iter().zip(&ws) {
            let r = lo + (hi - lo) * 0.5 * (x + 1.0);
            let jr = (hi - lo) * 0.5 * wr * r;
            for j in 0..nt {
                let th = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / nt as f64;
                let (px, py) = (r * th.cos(), r * th.sin());
                let (vx, vy) = (v - w * py, w * px);
                let s = (vx * vx + vy * vy).sqrt();
                if s == 0.0 {
                    continue;
                }
                let da = jr * 2.0 * std::f64::consts::PI / nt as f64 / std::f64::consts::PI;
                f -= vx / s * da;
                m -= (px * vy - py * vx) / s * da;
            }
        }
    }
    (f, m)
}

fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    // Newton iteration on the Legendre polynomial from Chebyshev-like starting points
    let mut xs = vec![0.0; n];
    let mut ws = vec![0.0; n];
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            // P_n' at the previous iterate: it differs from P_n' at x by O(dx), below 1e-16 once
            // converged
            ws[i] = 2.0 / ((1.0 - x * x) * dp * dp);
            if dx.abs() < 1e-16 {
                break;
            }
        }
        xs[i] = x;
    }
    (xs, ws)
}

/// The impulsive motion (2.2) with c = 0 integrated in the normal impulse S ([`Plate`] with the
/// centre of mass at the base centre), from sliding speed `v0` and spin `w0` until $u$ has gone
/// from $-u_0$ to $\varepsilon u_0$. Returns $(V^+, \omega^+)$.
pub fn impulsive_motion(
    plate: &Plate,
    v0: f64,
    w0: f64,
    u0: f64,
    restitution: f64,
) -> Result<(f64, f64), crate::integrate::IntegrateError> {
    let (m, rho, a, f) = (plate.m, plate.rho, plate.a, plate.f);
    let plate = Plate {
        m,
        rho,
        a,
        f,
        c: [0.0, 0.0],
    };
    let s_end = m * u0 * (1.0 + restitution);
    let out = plate.run([v0, 0.0], w0, s_end, 2)?;
    let y = out.last().map(|x| x.1).unwrap_or([f64::NAN; 3]);
    Ok((y[0].hypot(y[1]), y[2]))
}

/// A flat plate on a rough plane whose base is a disk of radius `a`, its centre of mass (= centre
/// of pressure, 001 section 1) at `c` from the base centre O, impulsive motion (2.2) in the
/// normal impulse S: $m\,d\mathbf v_G/dS = f\mathbf F$, $J_c\,d\omega/dS = f M_G$,
/// $M_G = M_O - (\mathbf c\times\mathbf F)_z$, with F and $M_O$ from [`friction`] (pressure
/// linear, centre of pressure at c). States: $v_{Ox}$, $v_{Oy}$, $\omega$.
pub struct Plate {
    /// Mass (kg).
    pub m: f64,
    /// Central radius of gyration about the normal (m).
    pub rho: f64,
    /// Base radius (m).
    pub a: f64,
    /// Friction coefficient.
    pub f: f64,
    /// O -> centre of mass (m), |c| <= a/4.
    pub c: [f64; 2],
}

impl crate::integrate::OdeSystem for Plate {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _s: f64, y: &[f64], dy: &mut [f64]) {
        let (v, w) = ([y[0], y[1]], y[2]);
        let r = friction(v, w, self.c, self.a, 1e-14);
        let j = self.m * self.rho * self.rho;
        let m_g = r.moment - (self.c[0] * r.force[1] - self.c[1] * r.force[0]);
        let dw = self.f * m_g / j;
        // v_O = v_G + omega z x (O - G) = v_G - omega z x c
        dy[0] = self.f * r.force[0] / self.m + dw * self.c[1];
        dy[1] = self.f * r.force[1] / self.m - dw * self.c[0];
        dy[2] = dw;
    }
}

impl Plate {
    /// $dV/d\Omega$ ($\Omega = a\omega$, $V = v_{Ox}$) in the motion with the instantaneous
    /// centre on the line through O perpendicular to the lines of equal pressure (c along y,
    /// $v_O$ along x: $\theta = \pi/2$ of (2.7)), at $V/\Omega = q$.
    pub fn slope(&self, q: f64) -> f64 {
        let mut dy = [0.0; 3];
        crate::integrate::OdeSystem::rhs(self, 0.0, &[q * self.a, 0.0, 1.0], &mut dy);
        dy[0] / (self.a * dy[2])
    }

    /// Integrates from `(v_o, omega)` over the normal impulse `s_end`, returning the state at
    /// `samples` equally spaced impulses (the first at 0).
    pub fn run(
        &self,
        v_o: [f64; 2],
        omega: f64,
        s_end: f64,
        samples: usize,
    ) -> Result<Vec<(f64, [f64; 3])>, crate::integrate::IntegrateError> {
        use crate::integrate::{Method, Options, solve};
        let times: Vec<f64> = (0..samples)
            .map(|i| (s_end * i as f64 / (samples - 1).max(1) as f64).min(s_end))
            .collect();
        let scale = v_o[0].hypot(v_o[1]).max(omega.abs() * self.a);
        let o = Options {
            rtol: 1e-11,
            atol: 1e-14 * scale,
            method: Method::Dop853,
            dense_times: times.clone(),
            ..Options::default()
        };
        let sol = solve(self, 0.0, &[v_o[0], v_o[1], omega], s_end, &o)?;
        Ok(sol
            .dense
            .iter()
            .map(|(t, y)| (*t, [y[0], y[1], y[2]]))
            .collect())
    }
}

/// The `disk-friction` scene: 001_989b2e860c39ca83.txt (2.3), a disk of radius `a` sliding with
/// speed `v` (along x) and spinning with `omega`; the centre of pressure at `c` along y.
#[derive(Clone, Debug)]
pub struct DiskFrictionScene {
    /// Disk radius (m).
    pub a: f64,
    /// Sliding speed of the centre (m/s).
    pub v: f64,
    /// Spin (rad/s).
    pub omega: f64,
    /// Offset of the centre of pressure (m), 0 <= c <= a/4.
    pub c: f64,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct RawScene {
    model: Option<toml::Value>,
    k: Option<toml::Value>,
    v: Option<toml::Value>,
    omega: Option<toml::Value>,
    a: Option<toml::Value>,
    c: Option<toml::Value>,
}

/// What `impact run` prints for a `disk-friction` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct DiskFrictionOutcome {
    /// `"disk-friction"`.
    pub model: &'static str,
    /// V/(a omega); `None` when omega = 0.
    pub k: Option<f64>,
    /// |F|/(f N).
    pub force: f64,
    /// |M|/(f N a).
    pub moment: f64,
    /// (2.3) with elliptic integrals, for c = 0.
    pub force_elliptic: Option<f64>,
    /// (2.3) with elliptic integrals, for c = 0.
    pub moment_elliptic: Option<f64>,
    /// F/(f N).
    pub force_vector: [f64; 2],
    /// M/(f N a), signed.
    pub moment_signed: f64,
    /// Estimated quadrature error.
    pub quadrature_error: f64,
    /// The units.
    pub units: &'static str,
}

impl super::Model for DiskFrictionScene {
    const NAME: &'static str = "disk-friction";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = DiskFrictionOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, super::SceneError> {
        let f = super::params::Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let a = f.num(
            raw.a.as_ref(),
            "a",
            Some(1.0),
            |v| v > 0.0,
            "a > 0 (m), the disk radius",
        )?;
        let has_vw = raw.v.is_some() || raw.omega.is_some();
        let (v, omega) = match (raw.k.is_some(), has_vw) {
            (true, true) => {
                return Err(f.out_of_range(
                    "k",
                    "given together with v/omega".into(),
                    "either k, or v and omega (with a)",
                ));
            }
            (true, false) => {
                let k = f.num(
                    raw.k.as_ref(),
                    "k",
                    None,
                    |v| v >= 0.0,
                    "k = V/(a omega) >= 0",
                )?;
                (k * a, 1.0)
            }
            _ => {
                let v = f.num(
                    raw.v.as_ref(),
                    "v",
                    None,
                    |v| v >= 0.0,
                    "v >= 0 (m/s), sliding speed of the centre; or give k = V/(a omega)",
                )?;
                let w = f.num(
                    raw.omega.as_ref(),
                    "omega",
                    None,
                    |v| v >= 0.0,
                    "omega >= 0 (rad/s)",
                )?;
                if v == 0.0 && w == 0.0 {
                    return Err(f.out_of_range(
                        "v",
                        "0 with omega = 0".into(),
                        "v > 0 or omega > 0 (a disk at rest has no kinetic friction)",
                    ));
                }
                (v, w)
            }
        };
        Ok(DiskFrictionScene {
            a,
            v,
            omega,
            c: f.num(
                raw.c.as_ref(),
                "c",
                Some(0.0),
                |v| (0.0..=a / 4.0).contains(&v),
                &format!("0 <= c <= a/4 = {} (m), centre of pressure off the centre; beyond a/4 part of the disk lifts off (001 (1.8))", a / 4.0),
            )?,
        })
    }

    fn run(&self) -> Result<(DiskFrictionOutcome, super::Curves), super::RunError> {
        let s = self;
        let r = friction([s.v, 0.0], s.omega, [0.0, s.c], s.a, 1e-14);
        let k = if s.omega > 0.0 {
            s.v / (s.a * s.omega)
        } else {
            f64::INFINITY
        };
        let elliptic = (s.c == 0.0).then(|| force_moment_elliptic(k));
        let out = DiskFrictionOutcome {
            model: Self::NAME,
            k: k.is_finite().then_some(k),
            force: r.force[0].hypot(r.force[1]),
            moment: r.moment.abs() / s.a,
            force_elliptic: elliptic.map(|e| e.0),
            moment_elliptic: elliptic.map(|e| e.1),
            force_vector: r.force,
            moment_signed: r.moment / s.a,
            quadrature_error: r.error,
            units: "F/(f N) and M/(f N a), N the normal load; the moment about the disk centre; the elliptic forms of (2.3) apply for c = 0",
        };
        Ok((out, vec![]))
    }
}

/// The `disk-friction` model's reference (`impact describe disk-friction`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "disk-friction",
    summary: "The friction force and moment on a disk of radius a sliding and spinning on a rough plane under uniform pressure (001, (2.3): the functions f1, f2, f3 in complete elliptic integrals), by quadrature over the base and, for a centred pressure, by the elliptic closed forms; c moves the centre of pressure off the centre (001 (1.8)).",
    conventions: &[
        "force in units of f N (friction coefficient times the normal load), moment in units of f N a",
        "force_vector is opposite to the centre's velocity (along x) when the pressure is centred",
    ],
    example: "scenes/disk_friction.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"disk-friction\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "a",
            unit: "m",
            range: "a > 0",
            default: "required",
            meaning: "disk radius",
        },
        d::Key {
            key: "k",
            unit: "1",
            range: "k = V/(a omega) >= 0",
            default: "either k, or v and omega",
            meaning: "the slip ratio",
        },
        d::Key {
            key: "v",
            unit: "m/s",
            range: "v >= 0",
            default: "with omega",
            meaning: "sliding speed of the centre",
        },
        d::Key {
            key: "omega",
            unit: "rad/s",
            range: "omega >= 0 (v or omega > 0)",
            default: "with v",
            meaning: "spin",
        },
        d::Key {
            key: "c",
            unit: "m",
            range: "0 <= c <= a/4",
            default: "0",
            meaning: "offset of the centre of pressure (beyond a/4 part of the disk lifts off)",
        },
    ]],
    outcomes: &[
        d::COMMON,
        &[
            d::Out {
                path: "k",
                unit: "1",
                meaning: "V/(a omega); null when omega = 0",
            },
            d::Out {
                path: "force",
                unit: "1 (f N)",
                meaning: "|F|/(f N)",
            },
            d::Out {
                path: "moment",
                unit: "1 (f N a)",
                meaning: "|M|/(f N a)",
            },
            d::Out {
                path: "force_elliptic",
                unit: "1 (f N)",
                meaning: "(2.3) with elliptic integrals, for c = 0",
            },
            d::Out {
                path: "moment_elliptic",
                unit: "1 (f N a)",
                meaning: "(2.3) with elliptic integrals, for c = 0",
            },
            d::Out {
                path: "force_vector",
                unit: "1 (f N)",
                meaning: "F/(f N), [x, y]",
            },
            d::Out {
                path: "moment_signed",
                unit: "1 (f N a)",
                meaning: "M/(f N a), signed",
            },
            d::Out {
                path: "quadrature_error",
                unit: "1",
                meaning: "estimated quadrature error",
            },
            d::Out {
                path: "units",
                unit: "-",
                meaning: "what the numbers are in",
            },
        ],
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    /// The series branch of f1, f2, f3 against the closed forms where both are accurate (k = 0.25,
    /// where the closed forms lose about 1.2 digits).
    #[test]
    fn series_meets_closed_forms() {
        let k: f64 = SERIES_BELOW;
        let s = f123_series(k);
        let (kk, ee) = k_e(k);
        let k2 = k * k;
        let f1 = (1.0 / k2 + 1.0) * ee - (1.0 / k2 - 1.0) * kk;
        let f2 = ((4.0 - 2.0 / k2) * ee - (1.0 / k2 - 1.0) * (3.0 * k2 - 2.0) * kk) / k;
        let f3 = (4.0 - 2.0 * k2) * ee - (1.0 - k2) * kk;
        for (a, b) in [(s.0, f1), (s.1, f2), (s.2, f3)] {
            assert!((a - b).abs() < 1e-13 * b.abs(), "{a} vs {b}");
        }
    }

    /// The instantaneous-centre quadrature against the closed forms over k in [0, 1) and beyond,
    /// including k within 1e-12 of 1 on both sides (independent: K, E from Carlson's forms).
    #[test]
    fn friction_matches_elliptic_forms() {
        let mut ks: Vec<f64> = (0..=40).map(|i| i as f64 * 0.025).collect();
        ks.extend([
            1e-6,
            0.999_999,
            1.0 - 1e-12,
            1.0,
            1.0 + 1e-12,
            1.5,
            3.0,
            1e3,
        ]);
        for k in ks {
            // k = V/Omega with a = 2: V along x, omega = 1
            let a = 2.0;
            let r = friction([k * a, 0.0], 1.0, [0.0, 0.0], a, 1e-14);
            let (fe, me) = force_moment_elliptic(k);
            let (fq, mq) = (r.force[0].hypot(r.force[1]), -r.moment / a);
            assert!((fq - fe).abs() < 1e-12, "k = {k}: F {fq} vs {fe}");
            assert!((mq - me).abs() < 1e-12, "k = {k}: M {mq} vs {me}");
        }
    }

    /// Friction is a vector law: rotating the velocity and the centre of pressure rotates the
    /// force and keeps the moment; mirroring them (x -> -x, which turns the spin) mirrors the
    /// force and turns the moment. Both with the instantaneous centre in the disk and outside,
    /// the centre of pressure off both axes (a symmetry, not a value of the code).
    #[test]
    fn friction_is_covariant_under_rotation_and_mirror() {
        let a = 1.5;
        for (v, w, c) in [
            ([0.3, 0.2], 1.0, [0.1, -0.2]),    // P inside (|v|/w < a)
            ([2.0, -1.1], 0.7, [-0.25, 0.15]), // P outside
            ([0.0, 0.4], -2.0, [0.2, 0.2]),    // negative spin
        ] {
            let r0 = friction(v, w, c, a, 1e-14);
            let th: f64 = 0.7;
            let (sn, cs) = th.sin_cos();
            let rot = |x: [f64; 2]| [cs * x[0] - sn * x[1], sn * x[0] + cs * x[1]];
            let r1 = friction(rot(v), w, rot(c), a, 1e-14);
            let f0 = rot(r0.force);
            for i in 0..2 {
                assert!(
                    (r1.force[i] - f0[i]).abs() < 1e-12,
                    "{v:?} {w} {c:?}: {r1:?} vs {f0:?}"
                );
            }
            assert!((r1.moment - r0.moment).abs() < 1e-12, "{r1:?} vs {r0:?}");
            let mir = |x: [f64; 2]| [-x[0], x[1]];
            let r2 = friction(mir(v), -w, mir(c), a, 1e-14);
            let f2 = mir(r0.force);
            for i in 0..2 {
                assert!((r2.force[i] - f2[i]).abs() < 1e-12, "{r2:?} vs {f2:?}");
            }
            assert!((r2.moment + r0.moment).abs() < 1e-12, "{r2:?} vs {r0:?}");
            // and the force is a unit load's: |F| <= 1, equal only in pure translation
            assert!(r0.force[0].hypot(r0.force[1]) < 1.0);
        }
    }

    /// The brute-force quadrature (Gauss-Legendre in r, midpoint in theta) against (2.3)'s
    /// elliptic forms, P inside and outside the disk.
    #[test]
    fn brute_force_quadrature_meets_the_elliptic_forms() {
        for k in [0.3, 0.8, 2.5] {
            let (f, m) = quadrature(k, 1.0, 24, 4000);
            let (fe, me) = force_moment_elliptic(k);
            assert!((f.abs() - fe).abs() < 1e-5, "k = {k}: F {f} vs {fe}");
            assert!((m.abs() - me).abs() < 1e-5, "k = {k}: M {m} vs {me}");
        }
    }

    /// Impulsive motion without spin and with the centre of mass over the base centre: the
    /// friction is f N against the velocity, so dV/dS = -f/m and V+ = v0 - f u0 (1 + e) (by
    /// hand), the spin stays 0.
    #[test]
    fn impulsive_translation_loses_f_times_the_normal_impulse() {
        let plate = Plate {
            m: 2.0,
            rho: 0.3,
            a: 0.5,
            f: 0.2,
            c: [0.0, 0.0],
        };
        let (v0, u0, e) = (3.0, 1.5, 0.6);
        let (v, w) = impulsive_motion(&plate, v0, 0.0, u0, e).expect("integrates");
        let want = v0 - 0.2 * u0 * (1.0 + e);
        assert!((v - want).abs() < 1e-10, "{v} vs {want}");
        assert!(w.abs() < 1e-12, "{w}");
    }

    /// The scene's k is V/(a omega), and its force and moment are (2.3)'s at that k.
    #[test]
    fn the_scene_reports_k_and_the_elliptic_forms() {
        use crate::models::Model;
        let s = DiskFrictionScene {
            a: 2.0,
            v: 1.0,
            omega: 4.0,
            c: 0.0,
        };
        let (out, _) = s.run().expect("runs");
        let k = out.k.expect("spinning");
        assert!((k - 0.125).abs() < 1e-15, "{k}");
        let (fe, me) = force_moment_elliptic(0.125);
        assert!(
            (out.force - fe).abs() < 1e-12 && (out.moment - me).abs() < 1e-12,
            "{out:?}"
        );
    }

    /// A linear pressure: pure translation and pure spin have closed forms.
    #[test]
    fn linear_pressure_limits() {
        let (a, c) = (1.0, [0.0, 0.2]);
        // spin about O: F = (4 c/(3a), 0) for omega > 0, M_O = -2a/3
        let r = friction([0.0, 0.0], 1.0, c, a, 1e-14);
        assert!((r.force[0] - 4.0 * 0.2 / 3.0).abs() < 1e-13 && r.force[1].abs() < 1e-13);
        assert!((r.moment + 2.0 / 3.0).abs() < 1e-13);
        // translation along x with tiny spin: F -> -x, M_O -> -(c x v) = 0.2
        let r = friction([1.0, 0.0], 1e-9, c, a, 1e-14);
        assert!((r.force[0] + 1.0).abs() < 1e-8, "{:?}", r);
        assert!((r.moment - 0.2).abs() < 1e-8, "{:?}", r);
    }
}
