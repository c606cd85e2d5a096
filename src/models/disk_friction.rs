//! A flat disk of radius a under uniform pressure, sliding with speed V and spinning with angular
//! velocity omega on a plane with Coulomb friction f: the friction force and moment by direct
//! two-dimensional quadrature, against Sinitsyn's closed forms with complete elliptic integrals,
//! 001_989b2e860c39ca83.txt (2.3):
//! $$\frac{dV}{d\Omega} = \mu\frac{k f_1(k)}{f_3(k)}\ (k = V/\Omega \le 1),\qquad
//!   \frac{dV}{d\Omega} = \mu\frac{f_1(k_1)}{f_2(k_1)}\ (k_1 = \Omega/V \le 1),\qquad \Omega = \omega a,\ \mu = 3\rho^2/a^2,$$
//! i.e. the force-to-moment ratio $F/M = (3/a)\,k f_1(k)/f_3(k)$. $K$ and $E$ come from the `ellip`
//! crate (Carlson's symmetric forms); near $k = 1$ they are evaluated from the complementary
//! parameter $m_c = (1-k)(1+k)$, since forming $m = k^2$ loses the digits that matter.

/// $K(k)$ and $E(k)$ for modulus `k` in [0, 1].
pub fn k_e(k: f64) -> (f64, f64) {
    let mc = (1.0 - k) * (1.0 + k);
    // K = R_F(0, mc, 1), E = R_F(0, mc, 1) - k^2 R_D(0, mc, 1)/3
    let rf = ellip::elliprf(0.0, mc, 1.0).unwrap_or(f64::INFINITY);
    let rd = ellip::elliprd(0.0, mc, 1.0).unwrap_or(f64::INFINITY);
    (rf, rf - k * k * rd / 3.0)
}

/// $f_1$, $f_2$, $f_3$ of (2.3).
pub fn f123(k: f64) -> (f64, f64, f64) {
    let (kk, ee) = k_e(k);
    let k2 = k * k;
    let f1 = (1.0 / k2 + 1.0) * ee - (1.0 / k2 - 1.0) * kk;
    let f2 = ((4.0 - 2.0 / k2) * ee - (1.0 / k2 - 1.0) * (3.0 * k2 - 2.0) * kk) / k;
    let f3 = (4.0 - 2.0 * k2) * ee - (1.0 - k2) * kk;
    (f1, f2, f3)
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
            if dx.abs() < 1e-16 {
                let (mut q0, mut q1) = (1.0, x);
                for k in 2..=n {
                    let q2 = ((2 * k - 1) as f64 * x * q1 - (k - 1) as f64 * q0) / k as f64;
                    q0 = q1;
                    q1 = q2;
                }
                let d = n as f64 * (x * q1 - q0) / (x * x - 1.0);
                ws[i] = 2.0 / ((1.0 - x * x) * d * d);
                break;
            }
        }
        xs[i] = x;
    }
    (xs, ws)
}

/// The impulsive motion (2.2) with c = 0 integrated in the normal impulse S: $m\,dV/dS = -F$,
/// $J\,d\omega/dS = -M$, with F and M (per unit normal load, friction f, radius a) from the
/// quadrature; until $u$ has gone from $-u_0$ to $\varepsilon u_0$. Returns $(V^+, \omega^+)$.
#[allow(clippy::too_many_arguments)]
pub fn impulsive_motion(
    m: f64,
    rho: f64,
    a: f64,
    f: f64,
    v0: f64,
    w0: f64,
    u0: f64,
    restitution: f64,
) -> Result<(f64, f64), crate::integrate::IntegrateError> {
    use crate::integrate::{Method, OdeSystem, Options, solve};
    struct Disk {
        m: f64,
        j: f64,
        a: f64,
        f: f64,
    }
    impl OdeSystem for Disk {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _s: f64, y: &[f64], dy: &mut [f64]) {
            let (v, w) = (y[0].max(0.0), y[1].max(0.0));
            if v + w * self.a <= 0.0 {
                dy[0] = 0.0;
                dy[1] = 0.0;
                return;
            }
            // dimensionless: velocities in units of the larger of V and a omega
            let scale = v.max(w * self.a);
            let (fq, mq) = quadrature(v / scale, w * self.a / scale, 48, 480);
            dy[0] = self.f * fq / self.m;
            dy[1] = self.f * self.a * mq / self.j;
        }
    }
    let sys = Disk {
        m,
        j: m * rho * rho,
        a,
        f,
    };
    let s_end = m * u0 * (1.0 + restitution);
    let o = Options {
        rtol: 1e-8,
        atol: 1e-12,
        method: Method::Dop853,
        ..Options::default()
    };
    let sol = solve(&sys, 0.0, &[v0, w0], s_end, &o)?;
    Ok((sol.y[0], sol.y[1]))
}
