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
