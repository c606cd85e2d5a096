//! Seeded random impacts: the generators of `examples/rigid_fail` and
//! `examples/constrained_fail`, the sweep benchmarks of `perf`, the hard cases of `verify` and the
//! regression tests, which name cases by their index (the generators are frozen), and the
//! independent check that calls an integrated impact a wrong answer ([`wrong_answer`], against
//! the exact planar solution). Below the front ends so that `verify` may use them.

use crate::models::rigid_impact::Contact;
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
