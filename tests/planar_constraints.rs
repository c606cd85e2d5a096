//! Planar impacts of held bodies (002_b53e4779673eb6ed.txt section 2): a pendulum turning about a
//! fixed axis strikes a rough wall in its plane. B* of (2.4)-(2.5) is then of rank one,
//! $\mathbf B^* = \mathbf w\mathbf w^T/J$ with $\mathbf w = \mathbf e\times\mathbf{OC}$, and the
//! impact has a closed form derived here by hand (independent of both solvers):
//! $\mathbf V = \lambda\mathbf w$ throughout, $\lambda$ from 1 (the scene starts with
//! $\mathbf V^- = \mathbf w$) with $d\lambda/dp = (w_n - s\mu w_t)/J = k$ while C slips with the
//! sign $s = \operatorname{sgn}(\lambda w_t)$. $\lambda$ reaches 0 at $p^* = -1/k$, where
//! compression ends and the slip stops together; there C sticks if $|w_n/w_t| \le \mu$, and
//! the stick moves nothing (a cut-off impact: the pendulum wedges, $\mathbf I = p^*(\mathbf n -
//! s\mu\mathbf t)$); otherwise it slides back with $s' = \operatorname{sgn}(w_t w_n)$, at rate
//! $k' = (w_n - s'\mu w_t)/J$, and restitution lasts $q = e/|k'|$ (Newton: $\lambda = -e$),
//! $q = e\,p^*$ (Poisson) or $q = e/\sqrt{|k k'|}$ (the energetic law: the normal work
//! $\tfrac12 k' q^2 w_n$ equal to $-e^2$ times compression's $\tfrac12 p^* w_n$).
//!
//! Each case runs through the scene (the exact planar solution, "method": "planar-exact") and
//! through the integrator (`[solve] method = "integrate"`); both must agree with the closed form
//! to 1e-8 of the impulse.
use impactcheck::models::Model;
use impactcheck::models::constrained::{ImpactMethod, RigidImpactScene};
use nalgebra::Vector3;

/// The pendulum of scenes/pendulum_wall.toml with its point O moved to `(ox, 0, oz)` from G.
fn scene(ox: f64, oz: f64, mu: f64, law: &str, e: f64) -> (RigidImpactScene, Vector3<f64>, f64) {
    let oc = Vector3::new(0.0, 0.0, -0.3) - Vector3::new(ox, 0.0, oz);
    let w = Vector3::y().cross(&oc);
    let text = format!(
        "model = \"rigid-impact\"\n[[body]]\nmass = 2.0\ninertia = [[0.05, 0.0, 0.0], [0.0, 0.05, 0.0], [0.0, 0.0, 0.05]]\ncontact_offset = [0.0, 0.0, -0.3]\n[[body]]\nmass = \"inf\"\n[fixed]\nbody = 1\noffset = [{ox}, 0.0, {oz}]\naxis = [0.0, 1.0, 0.0]\n[contact]\nnormal = [0.0, 0.0, 1.0]\nmu = {mu}\nlaw = \"{law}\"\ne = {e}\n[initial]\nv_rel = [{}, 0.0, {}]\n",
        w.x, w.z
    );
    let table: toml::Table = text.parse().expect("toml");
    let s = RigidImpactScene::from_table(&table, "pendulum.toml").expect("valid");
    // J about the axis: 0.05 + m |GO projected on the plane|^2
    let j = 0.05 + 2.0 * (ox * ox + oz * oz);
    (s, w, j)
}

/// The closed form of the module doc for the impulse on the pendulum (the first body; the
/// contact normal +z into it, the tangent t = +x).
fn closed_form(w: Vector3<f64>, j: f64, mu: f64, law: &str, e: f64) -> Vector3<f64> {
    let (wt, wn) = (w.x, w.z);
    let s = wt.signum();
    let k = (wn - s * mu * wt) / j;
    let p_star = -1.0 / k;
    let i_t = -s * mu * p_star;
    if (wn / wt).abs() <= mu {
        return Vector3::new(i_t, 0.0, p_star);
    }
    let s2 = (wt * wn).signum();
    let k2 = (wn - s2 * mu * wt) / j;
    let q = match law {
        "newton" => e / k2.abs(),
        "poisson" => e * p_star,
        _ => e / (k * k2).abs().sqrt(),
    };
    Vector3::new(i_t - s2 * mu * q, 0.0, p_star + q)
}

#[test]
fn a_pendulum_striking_a_rough_wall_in_its_plane_matches_the_closed_form() {
    let mut cases = 0;
    let mut cut_off = 0;
    for (ox, oz) in [
        (-0.5f64, 0.1f64),
        (-0.3, 0.4),
        (0.2, 0.6),
        (-0.8, -0.2),
        (0.6, 0.3),
    ] {
        for mu in [0.0f64, 0.2, 0.5, 1.0, 2.0, 5.0] {
            for law in ["newton", "poisson", "energetic"] {
                for e in [0.0, 0.5, 1.0] {
                    let w: Vector3<f64> = Vector3::y().cross(&Vector3::new(-ox, 0.0, -0.3 - oz));
                    // the pendulum approaches the wall (V_n = w_n < 0), and friction does not
                    // jam it (k < 0: no classical end otherwise)
                    if w.z >= 0.0 || (w.z - w.x.signum() * mu * w.x) >= 0.0 {
                        continue;
                    }
                    let (mut s, w, j) = scene(ox, oz, mu, law, e);
                    cases += 1;
                    let want = closed_form(w, j, mu, law, e);
                    cut_off += usize::from((w.z / w.x).abs() <= mu);
                    for method in [ImpactMethod::Auto, ImpactMethod::Integrate] {
                        s.method = method;
                        let (out, _) = s.run().expect("runs");
                        assert_eq!(
                            out.method,
                            Some(if method == ImpactMethod::Auto {
                                "planar-exact"
                            } else {
                                "integrate"
                            })
                        );
                        let got = Vector3::from(out.impulse.expect("impulse"));
                        assert!(
                            (got - want).norm() <= 1e-8 * want.norm(),
                            "O = ({ox}, {oz}), mu {mu}, {law}, e {e}, {method:?}: {got:?} against {want:?}"
                        );
                    }
                }
            }
        }
    }
    assert!(
        cases >= 60 && cut_off >= 20 && cases - cut_off >= 20,
        "{cases} {cut_off}"
    );
}

/// A scene the model must refuse, with the field and the reason named: a held body whose
/// contact velocity it cannot have, an inertia 1e-11 off symmetric (above the 1e-12 relative
/// rounding allowed), a zero contact normal.
#[test]
fn impossible_held_motions_and_bad_matrices_are_refused_by_name() {
    let base = |inertia: &str, fixed: &str, normal: &str, v: &str| {
        format!(
            "model = \"rigid-impact\"\n[[body]]\nmass = 2.0\ninertia = {inertia}\ncontact_offset = [0.0, 0.0, -0.3]\n[[body]]\nmass = \"inf\"\n{fixed}[contact]\nnormal = {normal}\nmu = 0.3\nlaw = \"newton\"\ne = 0.5\n[initial]\nv_rel = {v}\n"
        )
    };
    let iso = "[[0.05, 0.0, 0.0], [0.0, 0.05, 0.0], [0.0, 0.0, 0.05]]";
    let point = "[fixed]\nbody = 1\noffset = [0.0, 0.0, 0.0]\n";
    let cases = [
        (
            // held at G: C can only turn about it, orthogonally to OC = (0, 0, -0.3); this
            // velocity is along OC, its component 1 m/s an exact multiple of |OC|
            base(iso, point, "[0.0, 0.0, 1.0]", "[0.0, 0.0, -1.0]"),
            "orthogonal to OC",
        ),
        (
            base(
                "[[0.05, 1e-4, 0.0], [1.00000001e-4, 0.05, 0.0], [0.0, 0.0, 0.05]]",
                "",
                "[0.0, 0.0, 1.0]",
                "[0.1, 0.0, -1.0]",
            ),
            "not symmetric positive-definite",
        ),
        (
            base(iso, "", "[0.0, 0.0, 0.0]", "[0.1, 0.0, -1.0]"),
            "contact.normal",
        ),
    ];
    for (text, want) in cases {
        let table: toml::Table = text.parse().expect("toml");
        let err = match RigidImpactScene::from_table(&table, "bad.toml") {
            Err(e) => e.to_string(),
            Ok(s) => match s.run() {
                Err(e) => e.to_string(),
                Ok(_) => panic!("accepted: {text}"),
            },
        };
        assert!(err.contains(want), "`{want}` not in: {err}");
    }
}
