//! Measurements behind `reports/performance.md` (driven by `benches/peers/peers.py` through
//! `impact bench`): the peer problems for the integrators, the algebra timings, parallel sweeps,
//! the cost of an effect that is off, and scaling with modes and sweep points. Timings are medians
//! of repeated runs on whatever machine runs them; nothing here decides a verdict.

use crate::integrate::workprecision::{WorkPoint, work_precision};
use crate::integrate::{IntegrateError, Method, OdeSystem};
use crate::models::rigid_impact::Contact;
use serde_json::{Value, json};
use std::time::Instant;

/// The cone on a Kelvin-Voigt half-space in units where $k/m = 1$, $V_0 = 1$:
/// $z'' = -z(z + 2\tau z')$ while in contact (the peer scripts use the same right-hand side).
pub struct ConeKv {
    /// Relaxation time $\eta/E$ in these units.
    pub tau: f64,
}

impl OdeSystem for ConeKv {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let z = y[0].max(0.0);
        dy[0] = y[1];
        dy[1] = -z * (z + 2.0 * self.tau * y[1]);
    }
}

/// The unit Hertz impact $z'' = -\max(z, 0)^{3/2}$, written as the peers write it (the model's
/// `Hertz` adds damping and a division by the mass, which would time the right-hand side rather
/// than the integrator).
pub struct HertzUnit;

impl OdeSystem for HertzUnit {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let z = y[0].max(0.0);
        dy[0] = y[1];
        dy[1] = -z * z.sqrt();
    }
}

/// `tau` of the cone peer problem, its end time (inside the contact) and initial state.
pub const CONE_TAU: f64 = 0.3;
/// End time of the cone peer problem (the contact force is still positive there).
pub const CONE_T_END: f64 = 2.0;
/// rho and sigma of the stiff pendulum peer problem (time scales 1e3 apart).
pub const PENDULUM: (f64, f64) = (0.5, 1e-6);

fn points_json(points: &[WorkPoint]) -> Vec<Value> {
    points
        .iter()
        .map(|p| {
            json!({"method": p.method.name(), "tol": p.tol, "rhs_evals": p.stats.rhs_evals,
                   "steps": p.stats.steps, "rejected": p.stats.rejected,
                   "jacobians": p.stats.jac_evals, "lu": p.stats.lu_decomps,
                   "lu_pairs": p.stats.lu_decomps / 2, "seconds": p.seconds,
                   "error": p.error})
        })
        .collect()
}

/// Work-precision of DOP853, DOPRI5 and Radau5 on one peer problem: `hertz` (to the end of
/// contact, exact end state), `cone` (to t = 2, reference: DOP853 at rtol 1e-14), `pendulum`
/// ((2.15) with sigma = 1e-6 to 90 % of the release, reference: the closed form).
pub fn bench_problem(problem: &str, tols: &[f64], repeats: usize) -> Result<Value, String> {
    let methods = [Method::Dop853, Method::Dopri5, Method::Radau5];
    let e = |e: IntegrateError| e.to_string();
    let (t_end, y0, reference, points): (f64, Vec<f64>, Vec<f64>, Vec<WorkPoint>) = match problem {
        "hertz" => {
            let model = HertzUnit;
            let t = crate::models::hertz::TAU_UNDAMPED;
            let y0 = vec![0.0, 1.0];
            let r = vec![0.0, -1.0];
            let p =
                work_precision(&model, (0.0, &y0, t), &r, &methods, tols, repeats).map_err(e)?;
            (t, y0, r, p)
        }
        "cone" => {
            let sys = ConeKv { tau: CONE_TAU };
            let y0 = vec![0.0, 1.0];
            let o = crate::integrate::Options {
                rtol: 1e-14,
                atol: 1e-16,
                method: Method::Dop853,
                ..Default::default()
            };
            let r = crate::integrate::solve(&sys, 0.0, &y0, CONE_T_END, &o)
                .map_err(e)?
                .y;
            let p = work_precision(&sys, (0.0, &y0, CONE_T_END), &r, &methods, tols, repeats)
                .map_err(e)?;
            (CONE_T_END, y0, r, p)
        }
        "pendulum" => {
            let (rho, sigma) = PENDULUM;
            let sys = crate::models::pendulum_wall::PendulumWall { rho, sigma };
            let cf = crate::models::pendulum_wall::ClosedForm::new(rho, sigma);
            let t = 0.9 * cf.release();
            let y0 = vec![0.0, 0.0, 0.0, 1.0];
            let r = cf.state(t).to_vec();
            let p = work_precision(&sys, (0.0, &y0, t), &r, &methods, tols, repeats).map_err(e)?;
            (t, y0, r, p)
        }
        other => {
            return Err(format!(
                "unknown bench problem `{other}`; allowed: hertz, cone, pendulum, algebra, sweeps, effects, scaling"
            ));
        }
    };
    Ok(
        json!({"problem": problem, "t_end": t_end, "y0": y0, "reference": reference,
              "points": points_json(&points)}),
    )
}

fn median_seconds(repeats: usize, mut f: impl FnMut()) -> f64 {
    let mut ts: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    ts.sort_by(f64::total_cmp);
    ts[ts.len() / 2]
}

/// How many times [`bench_algebra`] derives a0..a`order` for its median: the count asked for up
/// to order 6 (the target is timed as a median), once above (orders 7 and 8 take
/// seconds each).
fn series_repeats(order: usize, repeats: usize) -> usize {
    if order > 6 { 1 } else { repeats }
}

/// The algebra SymPy is compared with: a0..aN (N = 1..8) of 000's series with every symbol free,
/// and the Galerkin coefficients of (16) for (m, n) = (3, 5). Median seconds (of one run for
/// N = 7, 8, which take seconds each).
pub fn bench_algebra(repeats: usize) -> Value {
    use crate::algebra::galerkin;
    use crate::algebra::series::{SeriesParams, Viscous, adomian_terms};
    let series: Vec<Value> = (1..=8)
        .map(|order| {
            let repeats = series_repeats(order, repeats);
            let sec = median_seconds(repeats, || {
                std::hint::black_box(adomian_terms(
                    &SeriesParams::symbolic(),
                    order,
                    Viscous::TwoZZ,
                ));
            });
            json!({"order": order, "seconds": sec, "repeats": repeats})
        })
        .collect();
    let gal = median_seconds(repeats, || {
        std::hint::black_box(galerkin::derive(3, 5).ok());
    });
    let scaling: Vec<Value> = [1u32, 3, 5, 7, 9]
        .iter()
        .map(|&m| {
            let s = median_seconds(repeats.min(5), || {
                std::hint::black_box(galerkin::derive(m, m).ok());
            });
            json!({"m": m, "n": m, "seconds": s})
        })
        .collect();
    json!({"series_symbolic": series, "galerkin_3_5": gal, "galerkin_scaling": scaling,
           "repeats": repeats})
}

fn rigid_one(i: u64) -> bool {
    rigid_case(i).is_ok()
}

/// The `i`-th generic seeded random rigid impact: `(B, V-, mu, e)` with B a random symmetric
/// positive-definite matrix, no structure. Frozen: the regression tests name cases by `i`.
pub fn rigid_inputs_generic(i: u64) -> (nalgebra::Matrix3<f64>, nalgebra::Vector3<f64>, f64, f64) {
    let mut r = crate::rng::Rng(i.wrapping_mul(0x1234_5678_9ABC_DEF1) ^ 0xA5A5);
    let a = nalgebra::Matrix3::from_fn(|_, _| r.range(-1.0, 1.0));
    let b = a * a.transpose() + nalgebra::Matrix3::identity() * 0.05;
    let v = nalgebra::Vector3::new(r.range(-2.0, 2.0), r.range(-2.0, 2.0), -r.range(0.1, 3.0));
    (b, v, r.range(0.0, 1.5), r.range(0.0, 1.0))
}

/// A seeded random rigid impact of `examples/rigid_fail` and the sweep benchmark, contact normal
/// z, the first body's impulse.
#[derive(Clone, Debug)]
pub struct RigidSample {
    /// B of (1.7) (1/kg).
    pub b: nalgebra::Matrix3<f64>,
    /// Relative velocity at C before the impact (m/s).
    pub v: nalgebra::Vector3<f64>,
    /// Friction coefficient.
    pub mu: f64,
    /// Coefficient of restitution.
    pub e: f64,
    /// Restitution law.
    pub law: crate::models::rigid_impact::Law,
    /// The textbook degeneracies it has (empty for a generic sample).
    pub degenerate: Vec<&'static str>,
}

/// The friction coefficient that separates stick from slip at zero slip, $\mu^* =
/// |\mathbf B_{tt}^{-1}\mathbf B_{tn}|$ (contact normal z); infinite where $\mathbf B_{tt}$
/// is singular.
pub fn critical_mu(b: &nalgebra::Matrix3<f64>) -> f64 {
    let btt = nalgebra::Matrix2::new(b[(0, 0)], b[(0, 1)], b[(1, 0)], b[(1, 1)]);
    let btn = nalgebra::Vector2::new(b[(0, 2)], b[(1, 2)]);
    btt.try_inverse()
        .map_or(f64::INFINITY, |inv| (inv * btn).norm())
}

/// A random rotation (a uniformly drawn unit quaternion).
fn random_rotation(r: &mut crate::rng::Rng) -> nalgebra::Matrix3<f64> {
    let q = nalgebra::Quaternion::new(
        r.range(-1.0, 1.0),
        r.range(-1.0, 1.0),
        r.range(-1.0, 1.0),
        r.range(-1.0, 1.0),
    );
    nalgebra::UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .into_inner()
}

/// The friction coefficient of a degenerate sample: the critical value exactly, or next to it
/// (1e-9 and 1e-3 either side).
fn near_critical(r: &mut crate::rng::Rng, critical: f64) -> f64 {
    let factor = [1.0, 1.0 - 1e-9, 1.0 + 1e-9, 1.0 - 1e-3, 1.0 + 1e-3][(r.next() * 5.0) as usize];
    critical * factor
}

/// The `i`-th seeded random rigid impact: one in three (`(i / 3) % 3 == 0`, every law alike) has
/// the degeneracies of the textbook cases (one or more of: exactly planar motion, B diagonal
/// (principal axes along the contact frame), a symmetric body (isotropic tangential block), the
/// contact point on a principal axis of a rotated body, zero initial slip, mu at or next to the
/// critical value, e = 0 or 1); the rest are [`rigid_inputs_generic`]. The law is `i % 3`
/// (Poisson, Newton, energetic).
pub fn rigid_sample(i: u64) -> RigidSample {
    use crate::models::rigid_impact::{Body, Law, b_matrix};
    use nalgebra::{Matrix3, Vector3};
    let law = [Law::Poisson, Law::Newton, Law::Energetic][(i % 3) as usize];
    if !(i / 3).is_multiple_of(3) {
        let (b, v, mu, e) = rigid_inputs_generic(i);
        return RigidSample {
            b,
            v,
            mu,
            e,
            law,
            degenerate: Vec::new(),
        };
    }
    let mut r = crate::rng::Rng(i.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD6E8_FEB8_6659_FD93);
    let mut tags = Vec::new();
    let shape = (r.next() * 5.0) as usize;
    let b = match shape {
        1 => {
            // planar: y decoupled from the plane (x, z)
            tags.push("planar");
            let (l11, l21, l22) = (r.range(0.2, 1.2), r.range(-1.0, 1.0), r.range(0.2, 1.2));
            let (bxx, bxz, bzz) = (l11 * l11, l11 * l21, l21 * l21 + l22 * l22);
            Matrix3::new(bxx, 0.0, bxz, 0.0, r.range(0.05, 2.0), 0.0, bxz, 0.0, bzz)
        }
        2 => {
            tags.push("principal axes along the contact frame");
            Matrix3::from_diagonal(&Vector3::new(
                r.range(0.05, 2.0),
                r.range(0.05, 2.0),
                r.range(0.05, 2.0),
            ))
        }
        3 => {
            tags.push("symmetric body");
            let a = r.range(0.1, 2.0);
            let (c1, c2) = (r.range(-1.0, 1.0), r.range(-1.0, 1.0));
            let bnn = (c1 * c1 + c2 * c2) / a + r.range(0.05, 2.0);
            Matrix3::new(a, 0.0, c1, 0.0, a, c2, c1, c2, bnn)
        }
        4 => {
            tags.push("contact point on a principal axis");
            let rot = random_rotation(&mut r);
            let k = (r.next() * 3.0) as usize;
            let arm = r.range(0.05, 0.5) * if r.next() < 0.5 { -1.0 } else { 1.0 };
            let inertia = Matrix3::from_diagonal(&Vector3::new(
                r.range(0.01, 0.2),
                r.range(0.01, 0.2),
                r.range(0.01, 0.2),
            ));
            let body = Body {
                mass: Some(r.range(0.1, 10.0)),
                inertia: rot * inertia * rot.transpose(),
                offset: rot * Vector3::ith(k, arm),
            };
            let ground = Body {
                mass: None,
                inertia: Matrix3::identity(),
                offset: Vector3::zeros(),
            };
            b_matrix(&body, &ground).unwrap_or_else(Matrix3::identity)
        }
        _ => rigid_inputs_generic(i).0,
    };
    let mut v = Vector3::new(r.range(-2.0, 2.0), r.range(-2.0, 2.0), -r.range(0.1, 3.0));
    if shape == 1 {
        v.y = 0.0;
    }
    if r.next() < 0.3 || (shape == 0 && r.next() < 0.5) {
        tags.push("zero slip");
        v.x = 0.0;
        v.y = 0.0;
    }
    let critical = critical_mu(&b);
    let mu = if r.next() < 0.35 && critical.is_finite() && critical < 10.0 {
        tags.push("critical mu");
        near_critical(&mut r, critical)
    } else {
        r.range(0.0, 1.5)
    };
    let e = if r.next() < 0.3 || tags.is_empty() {
        tags.push("e = 0 or 1");
        if r.next() < 0.5 { 0.0 } else { 1.0 }
    } else {
        r.range(0.0, 1.0)
    };
    RigidSample {
        b,
        v,
        mu,
        e,
        law,
        degenerate: tags,
    }
}

/// Agreement required of an integrated impact with the exact planar solution, relative to the
/// impulse's size (impulse) and to it times |V-| (energy).
pub const AGREE: f64 = 1e-8;

/// Why an integrated impact with matrix `b` is a wrong answer, if it is: where the impact is
/// planar, its impulse or energy change differs from the exact planar solution
/// ([`crate::models::planar_impact`]) by more than [`AGREE`]; and under a law the theory says
/// dissipates here (the energetic law always; Poisson's in planar motion, where it is
/// energetically consistent) the kinetic energy grew by more than that.
pub fn wrong_answer(
    b: &nalgebra::Matrix3<f64>,
    contact: Contact,
    r: &crate::models::rigid_impact::ImpactResult,
) -> Option<String> {
    let Contact {
        normal,
        v_minus: v,
        mu,
        law,
        e,
    } = contact;
    use crate::models::planar_impact::{PLANAR_TOL, PlanarProblem, planar_frame};
    use crate::models::rigid_impact::Law;
    let got = nalgebra::Vector3::from(r.impulse);
    let frame = planar_frame(b, &normal, &v, PLANAR_TOL);
    // the impulse's scale: the least normal impulse of a central impact, |V_n-| / lambda_max
    let scale = got
        .norm()
        .max(v.dot(&normal.normalize()).abs() / r.lambda_max.max(1e-300));
    if let Some(frame) = &frame {
        match PlanarProblem::in_plane(b, frame, &v, mu, law, e).solve() {
            Ok(exact) => {
                let imp = frame.t * exact.impulse_t + frame.n * exact.impulse_n;
                let de = v.dot(&imp) + 0.5 * imp.dot(&(b * imp));
                let scale = scale.max(imp.norm());
                if (got - imp).norm() > AGREE * scale
                    || (r.energy_change - de).abs() > AGREE * scale * v.norm()
                {
                    return Some(format!(
                        "planar: impulse {:?} against the exact {:?} (difference {:.3e} of its size), energy change {:.6e} against {de:.6e} J",
                        r.impulse,
                        imp.as_slice(),
                        (got - imp).norm() / scale,
                        r.energy_change
                    ));
                }
            }
            Err(err) => return Some(format!("planar, but the exact solution fails: {err}")),
        }
    }
    let dissipates = law == Law::Energetic || (law == Law::Poisson && frame.is_some());
    if dissipates && r.energy_change > AGREE * scale * v.norm() {
        return Some(format!(
            "the kinetic energy grew by {:.6e} J under {} law, which dissipates here",
            r.energy_change,
            law.name()
        ));
    }
    None
}

/// The `i`-th seeded random rigid impact of the sweeps ([`rigid_sample`]): `(B, V-, mu, e)`.
pub fn rigid_inputs(i: u64) -> (nalgebra::Matrix3<f64>, nalgebra::Vector3<f64>, f64, f64) {
    let s = rigid_sample(i);
    (s.b, s.v, s.mu, s.e)
}

/// The `i`-th seeded random rigid impact of the sweeps, solved by the integrator under
/// Poisson's law.
pub fn rigid_case(
    i: u64,
) -> Result<crate::models::rigid_impact::ImpactResult, crate::models::rigid_impact::ImpactError> {
    let (b, v, mu, e) = rigid_inputs(i);
    crate::models::rigid_impact::impact_with_matrix(
        &b,
        Contact::new(
            nalgebra::Vector3::z(),
            v,
            mu,
            crate::models::rigid_impact::Law::Poisson,
            e,
        ),
        1e-10,
    )
}

/// The `i`-th seeded random constrained impact of `examples/constrained_fail` (002 sections
/// 2-4): two bodies with random masses, inertias and offsets; by `i % 4` both free, the first
/// with a fixed point, the first with a fixed axis, or a support under the second (smooth for
/// half of them, else Coulomb friction mu* in [0, 1.5)); the law by `i % 3` (Poisson, Newton,
/// energetic); mu in [0, 1.5), e in [0, 1), rtol 1e-10. The generator is frozen: the regression
/// tests name cases by `i`.
pub fn constrained_scene_generic(i: u64) -> crate::models::constrained::RigidImpactScene {
    use crate::models::rigid_impact::{Body, Law};
    use nalgebra::{Matrix3, Vector3};
    let mut r = crate::rng::Rng(i.wrapping_mul(0x2545F4914F6CDD1D) ^ 0x5A5A);
    let body = |r: &mut crate::rng::Rng| Body {
        mass: Some(r.range(0.1, 10.0)),
        inertia: Matrix3::from_diagonal(&Vector3::new(
            r.range(0.01, 0.2),
            r.range(0.01, 0.2),
            r.range(0.01, 0.2),
        )),
        offset: Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5)),
    };
    let b1 = body(&mut r);
    let b2 = body(&mut r);
    let law = [Law::Poisson, Law::Newton, Law::Energetic][(i % 3) as usize];
    let kind = i % 4;
    let fixed = if kind == 1 || kind == 2 {
        let axis = (kind == 2).then(|| {
            Vector3::new(r.range(-1., 1.), r.range(-1., 1.), r.range(-1., 1.)).normalize()
        });
        Some((
            0usize,
            Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5)),
            axis,
        ))
    } else {
        None
    };
    let support = (kind == 3).then(|| crate::models::support::Support {
        offset: Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), -r.range(0.1, 0.6)),
        normal: Vector3::new(r.range(-0.2, 0.2), r.range(-0.2, 0.2), 1.0).normalize(),
        mu: if r.next() < 0.5 {
            0.0
        } else {
            r.range(0.0, 1.5)
        },
    });
    let v = Vector3::new(r.range(-2., 2.), r.range(-2., 2.), -r.range(0.05, 3.0));
    crate::models::constrained::RigidImpactScene {
        bodies: [b1, b2],
        normal: Vector3::z(),
        mu: r.range(0.0, 1.5),
        law,
        e: r.range(0.0, 1.0),
        v_rel: v,
        rtol: 1e-10,
        support,
        v_support: Vector3::zeros(),
        fixed,
        method: Default::default(),
    }
}

/// The `i`-th seeded random constrained impact of `examples/constrained_fail`, with the textbook
/// degeneracies it was given: one in three (`(i / 12) % 3 == 0`, every kind and law alike) is
/// [`constrained_scene_generic`] made degenerate in one or more ways (exactly planar motion:
/// offsets, normals and velocities in the plane (x, z), a fixed axis along y; symmetric bodies;
/// the first body's contact point on its principal axis z; zero initial slip; mu at or next to
/// the critical value of B or B*; e = 0 or 1), the rest the generic case.
pub fn constrained_scene_tagged(
    i: u64,
) -> (
    crate::models::constrained::RigidImpactScene,
    Vec<&'static str>,
) {
    use nalgebra::{Matrix3, Vector3};
    let mut s = constrained_scene_generic(i);
    if !(i / 12).is_multiple_of(3) {
        return (s, Vec::new());
    }
    let mut r = crate::rng::Rng(i.wrapping_mul(0xBF58_476D_1CE4_E5B9) ^ 0x94D0_49BB_1331_11EB);
    let mut tags = Vec::new();
    if r.next() < 0.5 {
        tags.push("planar");
        for b in s.bodies.iter_mut() {
            b.offset.y = 0.0;
        }
        s.v_rel.y = 0.0;
        if let Some((_, go, axis)) = s.fixed.as_mut() {
            go.y = 0.0;
            if axis.is_some() {
                *axis = Some(Vector3::y());
            }
        }
        if let Some(sup) = s.support.as_mut() {
            sup.offset.y = 0.0;
            sup.normal.y = 0.0;
            sup.normal = sup.normal.normalize();
        }
    }
    if r.next() < 0.3 {
        tags.push("symmetric bodies");
        for b in s.bodies.iter_mut() {
            let a = r.range(0.01, 0.2);
            let c = if r.next() < 0.5 {
                a
            } else {
                r.range(0.01, 0.2)
            };
            b.inertia = Matrix3::from_diagonal(&Vector3::new(a, a, c));
        }
    }
    if r.next() < 0.3 {
        tags.push("contact point on a principal axis");
        s.bodies[0].offset = Vector3::new(0.0, 0.0, -r.range(0.05, 0.5));
    }
    if r.next() < 0.3 {
        tags.push("zero slip");
        s.v_rel.x = 0.0;
        s.v_rel.y = 0.0;
    }
    if r.next() < 0.3 {
        tags.push("e = 0 or 1");
        s.e = if r.next() < 0.5 { 0.0 } else { 1.0 };
    }
    let critical =
        crate::models::constrained::scene_matrix(&s).map_or(f64::INFINITY, |b| critical_mu(&b));
    if (r.next() < 0.35 || tags.is_empty()) && critical.is_finite() && critical < 10.0 {
        tags.push("critical mu");
        s.mu = near_critical(&mut r, critical);
    }
    if tags.is_empty() {
        tags.push("zero slip");
        s.v_rel.x = 0.0;
        s.v_rel.y = 0.0;
    }
    (s, tags)
}

/// The `i`-th seeded random constrained impact of `examples/constrained_fail`
/// ([`constrained_scene_tagged`] without its tags).
pub fn constrained_scene(i: u64) -> crate::models::constrained::RigidImpactScene {
    constrained_scene_tagged(i).0
}

fn cone_scene(v0: f64, effects: &str, extra: &str) -> String {
    format!(
        "model = \"cone-plate\"\nviscoelastic_law = \"constant-poisson\"\neffects = [{effects}]\n[impactor]\nmass = 0.05\ntheta_deg = 60.0\nv0 = {v0}\n[material]\nE = 2.0e9\nnu = 0.3\neta = 1.0e6\n{extra}[solve]\nrtol = 1e-8\natol = 1e-14\n"
    )
}

fn cone_model(text: &str) -> Result<crate::models::cone_plate::ConePlate, String> {
    let scene = crate::scene::parse(text, "bench.toml").map_err(|e| e.to_string())?;
    let Some(s) = scene
        .get::<crate::models::cone_plate::ConePlateScene>()
        .cloned()
    else {
        return Err("bench scene is not a cone-plate scene".into());
    };
    crate::models::cone_plate::ConePlate::new(s.params, s.effects, s.variant, s.law)
        .map_err(|e| e.to_string())
}

fn cone_one(sys: &crate::models::cone_plate::ConePlate) -> bool {
    crate::models::cone_plate::run(sys, None, &[], 1e-8, 1e-14, Method::Auto).is_ok()
}

/// Impacts per second on 1 and on all threads (rayon): `n_rigid` seeded random rigid impacts
/// (Poisson, friction) and `n_cone` cone impacts on a Kelvin-Voigt half-space at rtol 1e-8 with
/// impact speeds spread over 0.5..5 m/s.
pub fn bench_sweeps(n_rigid: usize, n_cone: usize) -> Result<Value, String> {
    use rayon::prelude::*;
    let threads = rayon::current_num_threads();
    let cones: Vec<_> = (0..n_cone)
        .map(|i| {
            cone_model(&cone_scene(
                0.5 + 4.5 * i as f64 / n_cone.max(1) as f64,
                "\"viscoelastic\"",
                "",
            ))
        })
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for t in [1, threads] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| e.to_string())?;
        let s = Instant::now();
        let ok = pool.install(|| {
            (0..n_rigid as u64)
                .into_par_iter()
                .filter(|&i| rigid_one(i))
                .count()
        });
        let rigid_s = s.elapsed().as_secs_f64();
        let s = Instant::now();
        let ok_c = pool.install(|| cones.par_iter().filter(|c| cone_one(c)).count());
        let cone_s = s.elapsed().as_secs_f64();
        rows.push(json!({"threads": t,
            "rigid": {"impacts": n_rigid, "solved": ok, "seconds": rigid_s, "per_second": n_rigid as f64 / rigid_s},
            "cone": {"impacts": n_cone, "solved": ok_c, "seconds": cone_s, "per_second": n_cone as f64 / cone_s}}));
    }
    Ok(json!({"threads_available": threads, "runs": rows}))
}

/// The in-process rate of the sweep path's integration: `n` Hertz impacts (m = 0.05 kg,
/// k = 3e8 N/m^1.5, rtol 1e-9, atol 1e-16, v0 from 0.5 to 2 m/s, to the end of contact with the
/// model's three events) on all threads, nothing parsed or written; the floor under
/// `impact sweep` of the same points.
pub fn bench_hertz_sweep(n: usize) -> Result<Value, String> {
    use crate::models::hertz::{ContactLaw, Hertz, run};
    use rayon::prelude::*;
    let model = Hertz {
        mass: 0.05,
        k: 3e8,
        damping: 0.0,
        law: ContactLaw::Hertz,
    };
    let s = Instant::now();
    let ok = (0..n)
        .into_par_iter()
        .filter(|&i| {
            let v0 = 0.5 + 1.5 * i as f64 / (n.max(2) - 1) as f64;
            run(&model, v0, 1e-9, 1e-16, Method::Dop853, None).is_ok_and(|r| r.ended)
        })
        .count();
    let secs = s.elapsed().as_secs_f64();
    Ok(
        json!({"impacts": n, "solved": ok, "seconds": secs, "per_second": n as f64 / secs,
        "threads": rayon::current_num_threads()}),
    )
}

/// The cost of effects that are off: state size and time per solve of the cone alone, of the
/// cone with each further effect named, and of a hand-written two-state cone ODE with the same
/// contact law (the floor: what a model with nothing else would cost).
pub fn bench_effects(repeats: usize) -> Result<Value, String> {
    let plate = "[plate]\na = 0.2\nb = 0.2\nh = 0.002\nrho = 1200.0\nmodes = [[1, 1]]\n[foundation]\nkw = 1.0e6\nkg = 1.0e3\nct = 10.0\n";
    let configs = [
        ("cone alone (viscoelastic)", "\"viscoelastic\"", ""),
        ("+ plate (1 mode)", "\"viscoelastic\", \"plate\"", plate),
        (
            "+ plate + Winkler + Pasternak + damper",
            "\"viscoelastic\", \"plate\", \"winkler\", \"pasternak\", \"damper\"",
            plate,
        ),
    ];
    let mut rows = Vec::new();
    for (name, eff, extra) in configs {
        let sys = cone_model(&cone_scene(2.0, eff, extra))?;
        let dim = sys.state_dim();
        let mut evals = 0;
        let secs = median_seconds(repeats, || {
            if let Ok(r) =
                crate::models::cone_plate::run(&sys, None, &[], 1e-8, 1e-14, Method::Dop853)
            {
                evals = r.stats.rhs_evals;
            }
        });
        rows.push(json!({"config": name, "state_dim": dim, "rhs_evals": evals, "seconds": secs}));
    }
    // the floor: the same cone law as a bare two-state ODE (z, z'), stopped at z = 0
    let alone = cone_model(&cone_scene(2.0, "\"viscoelastic\"", ""))?;
    let (k, tau) = alone
        .kelvin_voigt()
        .ok_or("the cone alone is not Kelvin-Voigt")?;
    struct Bare {
        k_over_m: f64,
        tau: f64,
    }
    impl OdeSystem for Bare {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            let z = y[0].max(0.0);
            dy[0] = y[1];
            dy[1] = -self.k_over_m * z * (z + 2.0 * self.tau * y[1]);
        }
    }
    let bare = Bare {
        k_over_m: k / 0.05,
        tau,
    };
    let unload =
        |_t: f64, y: &[f64]| y[0].max(0.0) * (y[0].max(0.0) + 2.0 * tau * y[1]) + y[0].min(0.0);
    let mut evals = 0;
    let secs = median_seconds(repeats, || {
        let o = crate::integrate::Options {
            rtol: 1e-8,
            atol: 1e-14,
            method: Method::Dop853,
            events: vec![crate::integrate::Event::new(
                "force returns to zero",
                &unload,
                crate::integrate::Direction::Falling,
                true,
            )],
            ..Default::default()
        };
        if let Ok(s) = crate::integrate::solve(&bare, 0.0, &[0.0, 2.0], 1.0, &o) {
            evals = s.stats.rhs_evals;
        }
    });
    rows.push(
        json!({"config": "hand-written 2-state cone ODE (floor)", "state_dim": 2,
                     "rhs_evals": evals, "seconds": secs}),
    );
    Ok(json!({"rows": rows, "repeats": repeats}))
}

/// Scaling: the cone on the full plate with modes (m, n) up to (9, 9) (state size and time per
/// solve), and a sweep's wall time against its number of points.
pub fn bench_scaling(repeats: usize) -> Result<Value, String> {
    use rayon::prelude::*;
    let mut modes_rows = Vec::new();
    for mmax in [1u32, 3, 5, 7, 9] {
        let modes: Vec<String> = (1..=mmax)
            .step_by(2)
            .flat_map(|m| (1..=mmax).step_by(2).map(move |n| format!("[{m}, {n}]")))
            .collect();
        let extra = format!(
            "[plate]\na = 0.2\nb = 0.2\nh = 0.002\nrho = 1200.0\nmodes = [{}]\n[foundation]\nkw = 1.0e6\nkg = 1.0e3\nct = 10.0\n",
            modes.join(", ")
        );
        let sys = cone_model(&cone_scene(
            2.0,
            "\"viscoelastic\", \"plate\", \"winkler\", \"pasternak\", \"damper\"",
            &extra,
        ))?;
        let dim = sys.state_dim();
        let mut evals = 0;
        let secs = median_seconds(repeats, || {
            if let Ok(r) =
                crate::models::cone_plate::run(&sys, None, &[], 1e-8, 1e-14, Method::Auto)
            {
                evals = r.stats.rhs_evals;
            }
        });
        modes_rows.push(
            json!({"max_mode": mmax, "modes": modes.len(), "state_dim": dim,
                               "rhs_evals": evals, "seconds": secs}),
        );
    }
    let mut points_rows = Vec::new();
    for n in [100usize, 1000, 10000] {
        let s = Instant::now();
        let ok = (0..n as u64)
            .into_par_iter()
            .filter(|&i| rigid_one(i))
            .count();
        points_rows.push(json!({"points": n, "solved": ok, "seconds": s.elapsed().as_secs_f64()}));
    }
    Ok(json!({"modes": modes_rows, "sweep_points": points_rows}))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_points_carry_the_counts_the_peer_tables_compare() {
        // the pendulum at 1e-6 against its closed form (an independent solution): Radau5's
        // point must name its steps, Jacobians and LU decompositions, consistently
        let v = bench_problem("pendulum", &[1e-6], 1).expect("bench runs");
        let radau = v["points"]
            .as_array()
            .expect("points")
            .iter()
            .find(|p| p["method"] == "radau5")
            .expect("radau5 point")
            .clone();
        let n = |k: &str| {
            radau[k]
                .as_u64()
                .unwrap_or_else(|| panic!("{k} in {radau}"))
        };
        assert!(n("steps") > 0 && n("jacobians") >= 1, "{radau}");
        // `lu` counts each system, `lu_pairs` the pairs of a real and a complex one (Hairer's
        // NDEC): at least one pair per Jacobian, at most one per attempted step
        assert_eq!(n("lu"), 2 * n("lu_pairs"), "{radau}");
        assert!(n("lu_pairs") >= n("jacobians"), "{radau}");
        assert!(n("lu_pairs") <= n("steps") + n("rejected"), "{radau}");
        assert!(radau["error"].as_f64().expect("error") < 1e-5, "{radau}");
        assert!(bench_problem("nope", &[1e-6], 1).is_err());
    }

    /// Order 6, the order of the one-second target, is a median of the repeats asked
    /// for; orders 7 and 8 are timed once.
    #[test]
    fn the_series_bench_takes_a_median_up_to_order_six() {
        for order in 1..=6 {
            assert_eq!(series_repeats(order, 5), 5, "order {order}");
        }
        assert_eq!(series_repeats(7, 5), 1);
        assert_eq!(series_repeats(8, 5), 1);
    }
}
