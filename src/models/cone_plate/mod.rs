//! The cone-plate impact of 000_92d54b11128ea1ec.txt: the cone (1), (9)-(11), the plate modes (15)
//! with the coefficients (16) and the coupled system (17), integrated in full.
//!
//! Only the effects a scene names are simulated, each adding only its own states and terms:
//!
//! - cone: $m_s\ddot z = -P$ (states $z, \dot z$);
//! - `viscoelastic`: the contact operator $\tilde E/(1-\tilde\nu^2)$ of section 2. With the
//!   constant-bulk law (the paper's) it is $c\,(1+D/\lambda)[\tilde L(\alpha)-\tilde L(\gamma)]$; each
//!   $\tilde L(\delta)$ becomes an auxiliary state $u_\delta' = -\delta u_\delta + g$, $u(0)=0$
//!   (no convolution is integrated by quadrature). With the constant-Poisson law it is the local
//!   Kelvin-Voigt $E(1+\tau D)/(1-\nu^2)$. Without the effect the material is elastic,
//!   $P = A_7 E z^2/(1-\nu^2)$;
//! - `plate`: one pair $f, \dot f$ per mode, $A_4\ddot f = sP - \text{bending} - A_3 f - \dots$
//!   (with several modes each keeps its own cubic membrane term; the cross-mode membrane coupling
//!   that a multi-mode (12) would bring is not in the paper and not modelled);
//!   `winkler`, `pasternak`, `damper`, `inplane` switch $K_w$, $K_G$, $C_T$, $p_{1,2}$ on,
//!   `membrane` the cubic terms $A_5 f^3 + A_6 f^2\dot f$; `relative-indentation` uses
//!   $z - w(a/2, b/2)$ instead of the paper's $z$.
//!
//! `variant = "corrected"` uses the coefficients derived in [`crate::algebra`] (operator constant
//! $c = -E\lambda/(1-2\nu)$, viscous term $2 z\dot z$, load sign $\sin(m\pi/2)\sin(n\pi/2)$,
//! $A_7$ in the contact law); `"as-printed"` uses the paper's $E\zeta$, $\eta\zeta$, $z\dot z$ of
//! (18), (16) as printed (with $C_T$ inside the operator bracket of $A_2$) and, with the plate,
//! the $A_4$ of (17)'s second line.
//!
//! Energy is booked as integrated states: dissipated work, the work of the memory operators (not
//! a stored energy: with $\alpha < 0$ it can turn negative, which is the operator doing net work on
//! the cone), and, with the paper's absolute indentation, the work the load injects into the plate.
//! Their balance with kinetic and stored energy closes to the solver tolerance.

use crate::algebra::eval::ratfunc_f64;
use crate::algebra::galerkin;
use crate::integrate::{
    Direction, Event, IntegrateError, Method, OdeSystem, Options, Stats, Stop, solve,
};
use std::collections::BTreeMap;

mod scene;

pub use scene::{ConePlateOutcome, ConePlateScene, EFFECTS, EnergyOutcome};

/// Which formulas.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// The paper's formulas exactly as printed.
    AsPrinted,
    /// The formulas derived by the algebra.
    Corrected,
}

/// Which viscoelastic law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// Kelvin-Voigt Young's modulus with constant bulk modulus (the paper's).
    ConstantBulk,
    /// Kelvin-Voigt with the same retardation time in shear and bulk (nu constant).
    ConstantPoisson,
}

/// The effects a scene names.
#[derive(Clone, Debug, Default)]
pub struct Effects {
    /// Viscoelastic material.
    pub viscoelastic: bool,
    /// The plate moves.
    pub plate: bool,
    /// Winkler foundation $K_w$.
    pub winkler: bool,
    /// Pasternak foundation $K_G$.
    pub pasternak: bool,
    /// Damper $C_T$.
    pub damper: bool,
    /// Cubic membrane terms $A_5$, $A_6$.
    pub membrane: bool,
    /// In-plane loads $p_1$, $p_2$.
    pub inplane: bool,
    /// Indentation $z - w(a/2, b/2)$.
    pub relative_indentation: bool,
    /// Plate modes (odd m, n).
    pub modes: Vec<(u32, u32)>,
}

impl Effects {
    /// Turns on the effect a scene names (`"plate"`, `"winkler"`, ...; `"modes"` is accepted and
    /// does nothing: the modes come from `[plate]`); false for a name that is not an effect.
    pub fn switch_on(&mut self, name: &str) -> bool {
        match name {
            "viscoelastic" => self.viscoelastic = true,
            "plate" => self.plate = true,
            "winkler" => self.winkler = true,
            "pasternak" => self.pasternak = true,
            "damper" => self.damper = true,
            "membrane" => self.membrane = true,
            "inplane" => self.inplane = true,
            "modes" => {}
            "relative-indentation" => self.relative_indentation = true,
            _ => return false,
        }
        true
    }

    /// Names of the active effects, for reports.
    pub fn names(&self) -> Vec<String> {
        let mut v = Vec::new();
        for (on, name) in [
            (self.viscoelastic, "viscoelastic"),
            (self.plate, "plate"),
            (self.winkler, "winkler"),
            (self.pasternak, "pasternak"),
            (self.damper, "damper"),
            (self.membrane, "membrane"),
            (self.inplane, "inplane"),
            (self.relative_indentation, "relative-indentation"),
        ] {
            if on {
                v.push(name.to_string());
            }
        }
        v
    }
}

/// Physical parameters (SI).
#[derive(Clone, Debug)]
pub struct Params {
    /// Cone mass $m_s$ (kg).
    pub mass: f64,
    /// Angle between the plane and the cone surface (degrees).
    pub theta_deg: f64,
    /// Impact speed (m/s).
    pub v0: f64,
    /// Relaxed Young's modulus (Pa).
    pub e: f64,
    /// Poisson's ratio.
    pub nu: f64,
    /// Viscosity (Pa s).
    pub eta: f64,
    /// Plate sides (m).
    pub a: f64,
    /// Plate sides (m).
    pub b: f64,
    /// Thickness (m).
    pub h: f64,
    /// Density (kg/m^3).
    pub rho: f64,
    /// Winkler modulus (N/m^3), with the effect "winkler".
    pub kw: Option<f64>,
    /// Pasternak modulus (N/m), with "pasternak".
    pub kg: Option<f64>,
    /// Damper (N s/m^3), with "damper".
    pub ct: Option<f64>,
    /// In-plane loads $(p_1, p_2)$ (N/m), with "inplane".
    pub inplane: Option<(f64, f64)>,
}

impl Params {
    /// The value of an optional effect's parameter when the effect is named: an error naming it
    /// when the effect is on and the value is missing; `None` when the effect is off.
    fn when<T: Copy>(on: bool, v: Option<T>, what: &str) -> Result<Option<T>, BuildError> {
        match (on, v) {
            (false, _) => Ok(None),
            (true, Some(v)) => Ok(Some(v)),
            (true, None) => Err(BuildError::Unsupported(format!(
                "the effect needs {what}: give it, or leave the effect out"
            ))),
        }
    }
}

/// How the contact force depends on the indentation history.
#[derive(Clone, Debug)]
enum ContactLaw {
    /// $P = k d^2$.
    Elastic { k: f64 },
    /// $P = k(d^2 + 2\tau d\dot d)$.
    KelvinVoigt { k: f64, tau: f64 },
    /// $P = K (u_\alpha - u_\gamma)$, $u' = -\delta u + w_0 d^2 + w_1 d\dot d$.
    Memory {
        k: f64,
        alpha: f64,
        gamma: f64,
        w0: f64,
        w1: f64,
    },
}

#[derive(Clone, Debug)]
enum Bending {
    /// $b f$ (+ $b\tau\dot f$ when viscoelastic).
    Local { stiff: f64, visc: Option<f64> },
    /// $(v_\alpha - v_\gamma)$ with $v' = -\delta v + w_0 f + w_1 \dot f$, times `k`.
    Memory { k: f64, w0: f64, w1: f64 },
}

#[derive(Clone, Debug)]
struct Mode {
    sign: f64,
    a4: f64,
    a3: f64,
    /// The foundation damper's term, with "damper".
    ct: Option<f64>,
    bending: Bending,
    /// The cubic membrane terms, with "membrane".
    membrane: Option<Membrane>,
    idx: usize,
    idx_op: Option<usize>,
}

/// The membrane terms of a mode: $A_5 f^3$ and, viscoelastic, $A_6 f^2 \dot f$.
#[derive(Clone, Copy, Debug)]
struct Membrane {
    el: f64,
    visc: Option<f64>,
}

/// The assembled system.
#[derive(Clone, Debug)]
pub struct ConePlate {
    /// Parameters.
    pub params: Params,
    /// Effects.
    pub effects: Effects,
    /// Variant.
    pub variant: Variant,
    /// Law.
    pub law: Law,
    contact: ContactLaw,
    idx_contact_op: Option<usize>,
    modes: Vec<Mode>,
    rates: (f64, f64),
    idx_diss: Option<usize>,
    idx_opwork: Option<usize>,
    idx_inj: Option<usize>,
    dim: usize,
    /// Notes for the report (e.g. what the printed formulas imply).
    pub warnings: Vec<String>,
}

/// Why a model could not be built.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// A combination the printed formulas cannot express.
    #[error("{0}")]
    Unsupported(String),
    /// The exact algebra failed.
    #[error(transparent)]
    Algebra(#[from] crate::algebra::AlgebraError),
    /// A coefficient could not be evaluated.
    #[error(transparent)]
    Eval(#[from] crate::algebra::eval::EvalError),
}

/// The values of the symbols of the exact Galerkin coefficients (16): the material, the
/// plate, the effects that are on (the others' coefficients 0) and $\tan\theta$.
fn galerkin_values(
    p: &Params,
    effects: &Effects,
    lambda: f64,
    zeta: f64,
) -> Result<BTreeMap<String, f64>, BuildError> {
    // an effect that is off has no term: its coefficient's symbol is 0 in the exact forms
    let kw = Params::when(effects.winkler, p.kw, "foundation.kw")?;
    let kg = Params::when(effects.pasternak, p.kg, "foundation.kg")?;
    let ct = Params::when(effects.damper, p.ct, "foundation.ct")?;
    let (p1, p2) = Params::when(effects.inplane, p.inplane, "inplane.p1 and p2")?.unzip();
    Ok([
        ("E", p.e),
        ("eta", p.eta),
        ("nu", p.nu),
        ("lambda", lambda),
        ("zeta", zeta),
        ("a", p.a),
        ("b", p.b),
        ("h", p.h),
        ("rho", p.rho),
        ("Kw", kw.unwrap_or(0.0)),
        ("KG", kg.unwrap_or(0.0)),
        ("CT", ct.unwrap_or(0.0)),
        ("p1", p1.unwrap_or(0.0)),
        ("p2", p2.unwrap_or(0.0)),
        ("tan_theta", p.theta_deg.to_radians().tan()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect())
}

/// A plate mode with the coefficients of (16) as printed (000): $A_1$, $A_2$ inside the
/// operator bracket, $A_4$, $A_3$, and with the membrane $A_5$, $A_6$; the load sign 1.
fn printed_mode(
    printed: &[crate::algebra::ratfunc::RatFunc],
    vals: &BTreeMap<String, f64>,
    membrane: bool,
    idx: usize,
) -> Result<Mode, BuildError> {
    let ev = |k: usize| ratfunc_f64(&printed[k], vals);
    let (a1, a2) = (ev(0)?, ev(1)?);
    Ok(Mode {
        sign: 1.0,
        a4: ev(3)?,
        a3: ev(2)?,
        bending: Bending::Memory {
            k: 1.0,
            w0: a1,
            w1: a2,
        },
        ct: None,
        membrane: if membrane {
            Some(Membrane {
                el: ev(4)?,
                visc: Some(ev(5)?),
            })
        } else {
            None
        },
        idx,
        idx_op: Some(idx + 2),
    })
}

impl ConePlate {
    /// Builds the system for the named effects.
    pub fn new(
        params: Params,
        effects: Effects,
        variant: Variant,
        law: Law,
    ) -> Result<Self, BuildError> {
        let p = &params;
        let lambda = p.e / p.eta;
        let tau = p.eta / p.e;
        let one_m_2nu = 1.0 - 2.0 * p.nu;
        let alpha = -2.0 * (1.0 + p.nu) * lambda / one_m_2nu;
        let gamma = 2.0 * (1.0 - p.nu) * lambda / one_m_2nu;
        let zeta = one_m_2nu / (4.0 * lambda);
        let c_corr = -p.e * lambda / one_m_2nu;
        let a7 = 2.0 / (std::f64::consts::PI * p.theta_deg.to_radians().tan());
        let e_plane = p.e / (1.0 - p.nu * p.nu);
        let mut warnings = Vec::new();
        if variant == Variant::AsPrinted && !effects.viscoelastic {
            return Err(BuildError::Unsupported(
                "variant \"as-printed\" needs the \"viscoelastic\" effect: the printed operator E zeta [1 + (eta/E) d/dt][L(alpha) - L(gamma)] has alpha, gamma, zeta built from lambda = E/eta and no elastic limit".into(),
            ));
        }
        let mut dim = 2;
        let vals = galerkin_values(p, &effects, lambda, zeta)?;
        // contact law
        let contact_coef = if variant == Variant::AsPrinted && effects.plate {
            warnings.push(
                "as printed, (17) drives the cone with A4 = rho h a b/4 in place of A7 = 2/(pi tan theta) (dimensionally inconsistent)".into(),
            );
            p.rho * p.h * p.a * p.b / 4.0
        } else {
            a7
        };
        let (contact, idx_contact_op) = match (effects.viscoelastic, variant, law) {
            (false, _, _) => (
                ContactLaw::Elastic {
                    k: contact_coef * e_plane,
                },
                None,
            ),
            (true, Variant::Corrected, Law::ConstantPoisson) => (
                ContactLaw::KelvinVoigt {
                    k: contact_coef * e_plane,
                    tau,
                },
                None,
            ),
            (true, Variant::Corrected, Law::ConstantBulk) => {
                dim += 2;
                (
                    ContactLaw::Memory {
                        k: contact_coef * c_corr,
                        alpha,
                        gamma,
                        w0: 1.0,
                        w1: 2.0 * tau,
                    },
                    Some(2),
                )
            }
            (true, Variant::AsPrinted, _) => {
                if law == Law::ConstantPoisson {
                    warnings.push("the printed formulas are those of the constant-bulk law; law \"constant-poisson\" is ignored by variant \"as-printed\"".into());
                }
                dim += 2;
                (
                    ContactLaw::Memory {
                        k: contact_coef * zeta,
                        alpha,
                        gamma,
                        w0: p.e,
                        w1: p.eta,
                    },
                    Some(2),
                )
            }
        };
        let mut has_diss = matches!(contact, ContactLaw::KelvinVoigt { .. });
        let mut has_opwork = matches!(contact, ContactLaw::Memory { .. });
        // plate modes
        let mut modes = Vec::new();
        if effects.plate {
            let list = if effects.modes.is_empty() {
                vec![(1, 1)]
            } else {
                effects.modes.clone()
            };
            for (m, n) in list {
                let g = galerkin::derive(m, n)?;
                let ev = |r: &crate::algebra::ratfunc::RatFunc| ratfunc_f64(r, &vals);
                let idx = dim;
                dim += 2;
                let printed = galerkin::printed_16(m, n);
                let mode = match variant {
                    Variant::Corrected => {
                        let bend = ev(&g.parts.bend)?;
                        let (bending, idx_op) = match (effects.viscoelastic, law) {
                            (false, _) => (
                                Bending::Local {
                                    stiff: bend * e_plane,
                                    visc: None,
                                },
                                None,
                            ),
                            (true, Law::ConstantPoisson) => (
                                Bending::Local {
                                    stiff: bend * e_plane,
                                    visc: Some(bend * e_plane * tau),
                                },
                                None,
                            ),
                            (true, Law::ConstantBulk) => {
                                dim += 2;
                                (
                                    Bending::Memory {
                                        k: bend * c_corr,
                                        w0: 1.0,
                                        w1: tau,
                                    },
                                    Some(idx + 2),
                                )
                            }
                        };
                        let membrane = if effects.membrane {
                            let cubic = ev(&g.parts.cubic)?;
                            Some(Membrane {
                                el: cubic * p.e,
                                visc: effects.viscoelastic.then_some(2.0 * cubic * p.eta),
                            })
                        } else {
                            None
                        };
                        Mode {
                            sign: f64::from(g.load_sign),
                            a4: ev(&g.parts.a4)?,
                            a3: ev(&g.parts.a3)?,
                            ct: if effects.damper {
                                Some(ev(&g.parts.ct)?)
                            } else {
                                None
                            },
                            bending,
                            membrane,
                            idx,
                            idx_op,
                        }
                    }
                    Variant::AsPrinted => {
                        dim += 2;
                        printed_mode(&printed, &vals, effects.membrane, idx)?
                    }
                };
                has_diss |= mode.ct.is_some()
                    || mode.membrane.is_some_and(|m| m.visc.is_some())
                    || matches!(mode.bending, Bending::Local { visc: Some(_), .. });
                has_opwork |= matches!(mode.bending, Bending::Memory { .. });
                modes.push(mode);
            }
        }
        let mut take = |on: bool| {
            on.then(|| {
                dim += 1;
                dim - 1
            })
        };
        let idx_diss = take(has_diss);
        let idx_opwork = take(has_opwork);
        let idx_inj = take(effects.plate && !effects.relative_indentation);
        Ok(ConePlate {
            params,
            effects,
            variant,
            law,
            contact,
            idx_contact_op,
            modes,
            rates: (alpha, gamma),
            idx_diss,
            idx_opwork,
            idx_inj,
            dim,
            warnings,
        })
    }

    /// Number of states.
    pub fn state_dim(&self) -> usize {
        self.dim
    }

    /// The operator rates $(\alpha, \gamma)$ (1/s); $\alpha < 0$ is a growing mode.
    pub fn rates(&self) -> (f64, f64) {
        self.rates
    }

    /// Initial state: $z = 0$, $\dot z = v_0$, everything else at rest.
    pub fn initial_state(&self) -> Vec<f64> {
        let mut y = vec![0.0; self.dim];
        y[1] = self.params.v0;
        y
    }

    /// Indentation and its rate.
    fn indentation(&self, y: &[f64]) -> (f64, f64) {
        let (mut d, mut dd) = (y[0], y[1]);
        if self.effects.relative_indentation {
            for md in &self.modes {
                d -= md.sign * y[md.idx];
                dd -= md.sign * y[md.idx + 1];
            }
        }
        (d, dd)
    }

    /// `(k, tau)` of the Kelvin-Voigt contact law $P = k\delta(|\delta| + 2\tau\dot\delta)$, when
    /// that is the law (the cone alone with the constant-Poisson law).
    pub fn kelvin_voigt(&self) -> Option<(f64, f64)> {
        match self.contact {
            ContactLaw::KelvinVoigt { k, tau } => Some((k, tau)),
            _ => None,
        }
    }

    /// Contact force $P$ (N), unclamped: negative means the law would pull (contact has ended).
    pub fn contact_force(&self, y: &[f64]) -> f64 {
        let (d, dd) = self.indentation(y);
        match self.contact {
            ContactLaw::Elastic { k } => k * d * d.abs(),
            ContactLaw::KelvinVoigt { k, tau } => k * d * (d.abs() + 2.0 * tau * dd),
            ContactLaw::Memory { k, .. } => {
                let i = self.idx_contact_op.unwrap_or(2);
                k * (y[i] - y[i + 1])
            }
        }
    }

    /// Plate deflection under the cone, $w(a/2, b/2)$ (m).
    pub fn centre_deflection(&self, y: &[f64]) -> Option<f64> {
        (!self.modes.is_empty()).then(|| self.modes.iter().map(|m| m.sign * y[m.idx]).sum())
    }

    /// Kinetic energy (J).
    pub fn kinetic(&self, y: &[f64]) -> f64 {
        0.5 * self.params.mass * y[1] * y[1]
            + self
                .modes
                .iter()
                .map(|m| 0.5 * m.a4 * y[m.idx + 1].powi(2))
                .sum::<f64>()
    }

    /// Stored (potential) energy of the local terms (J).
    pub fn stored(&self, y: &[f64]) -> f64 {
        let (d, _) = self.indentation(y);
        let contact = match self.contact {
            ContactLaw::Elastic { k } | ContactLaw::KelvinVoigt { k, .. } => {
                k * d.max(0.0).powi(3) / 3.0
            }
            ContactLaw::Memory { .. } => 0.0,
        };
        contact
            + self
                .modes
                .iter()
                .map(|m| {
                    let f = y[m.idx];
                    let bend = match m.bending {
                        Bending::Local { stiff, .. } => 0.5 * stiff * f * f,
                        Bending::Memory { .. } => 0.0,
                    };
                    let membrane = m.membrane.map_or(0.0, |mb| 0.25 * mb.el * f.powi(4));
                    bend + 0.5 * m.a3 * f * f + membrane
                })
                .sum::<f64>()
    }

    fn get(&self, y: &[f64], i: Option<usize>) -> f64 {
        i.map_or(0.0, |i| y[i])
    }

    /// `(dissipated, operator work, injected)` energies (J).
    pub fn booked(&self, y: &[f64]) -> (f64, f64, f64) {
        (
            self.get(y, self.idx_diss),
            self.get(y, self.idx_opwork),
            self.get(y, self.idx_inj),
        )
    }

    /// Relative error of $KE + \text{stored} + \text{dissipated} + W_{op} - W_{inj} = KE_0$.
    pub fn balance_error(&self, y: &[f64]) -> f64 {
        let e0 = 0.5 * self.params.mass * self.params.v0 * self.params.v0;
        let (diss, op, inj) = self.booked(y);
        (self.kinetic(y) + self.stored(y) + diss + op - inj - e0).abs() / e0
    }
}

impl OdeSystem for ConePlate {
    fn dim(&self) -> usize {
        self.dim
    }

    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let (d, dd) = self.indentation(y);
        let in_contact = d > 0.0;
        let p = if in_contact {
            self.contact_force(y)
        } else {
            0.0
        };
        dy[0] = y[1];
        dy[1] = -p / self.params.mass;
        let (mut diss, mut opwork) = (0.0, 0.0);
        match self.contact {
            ContactLaw::Elastic { .. } => {}
            ContactLaw::KelvinVoigt { k, tau } => {
                if in_contact {
                    diss += 2.0 * k * tau * d * dd * dd;
                }
            }
            ContactLaw::Memory {
                alpha,
                gamma,
                w0,
                w1,
                ..
            } => {
                let i = self.idx_contact_op.unwrap_or(2);
                let g = if in_contact {
                    w0 * d * d + w1 * d * dd
                } else {
                    0.0
                };
                dy[i] = -alpha * y[i] + g;
                dy[i + 1] = -gamma * y[i + 1] + g;
                opwork += p * dd;
            }
        }
        let mut inj = 0.0;
        for m in &self.modes {
            let (f, fd) = (y[m.idx], y[m.idx + 1]);
            let bend = match m.bending {
                Bending::Local { stiff, visc: None } => stiff * f,
                Bending::Local {
                    stiff,
                    visc: Some(visc),
                } => {
                    diss += visc * fd * fd;
                    stiff * f + visc * fd
                }
                Bending::Memory { k, w0, w1 } => {
                    let i = m.idx_op.unwrap_or(m.idx + 2);
                    let (alpha, gamma) = self.rates;
                    let g = w0 * f + w1 * fd;
                    dy[i] = -alpha * y[i] + g;
                    dy[i + 1] = -gamma * y[i + 1] + g;
                    let force = k * (y[i] - y[i + 1]);
                    opwork += force * fd;
                    force
                }
            };
            // absent terms are exact zeros, so the sums are those of the full model
            let ct = m.ct.unwrap_or(0.0);
            let (cubic_el, cubic_visc) = m
                .membrane
                .map_or((0.0, 0.0), |mb| (mb.el, mb.visc.unwrap_or(0.0)));
            let membrane = cubic_el * f * f * f + cubic_visc * f * f * fd;
            diss += ct * fd * fd + cubic_visc * f * f * fd * fd;
            let load = m.sign * p;
            if !self.effects.relative_indentation {
                inj += load * fd;
            }
            dy[m.idx] = fd;
            dy[m.idx + 1] = (load - bend - m.a3 * f - ct * fd - membrane) / m.a4;
        }
        if let Some(i) = self.idx_diss {
            dy[i] = diss;
        }
        if let Some(i) = self.idx_opwork {
            dy[i] = opwork;
        }
        if let Some(i) = self.idx_inj {
            dy[i] = inj;
        }
    }
}

/// A sample of the solution.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Cone displacement (m).
    pub z: f64,
    /// Cone velocity (m/s).
    pub zdot: f64,
    /// Plate deflection under the cone (m), if the plate moves.
    pub f: Option<f64>,
    /// Contact force (N).
    #[serde(rename = "P")]
    pub p: f64,
}

/// The result of one impact.
#[derive(Clone, Debug)]
pub struct Run {
    /// Samples at the requested times.
    pub samples: Vec<Sample>,
    /// Contact ended inside the window.
    pub ended: bool,
    /// Contact duration (s), or the window.
    pub duration: f64,
    /// Largest contact force (N).
    pub peak_force: f64,
    /// Largest indentation (m).
    pub max_indentation: f64,
    /// Kinetic energy at impact (J).
    pub energy_initial: f64,
    /// Kinetic plus stored energy at the end (J).
    pub energy_final: f64,
    /// Dissipated energy (J).
    pub dissipated: f64,
    /// Work of the memory operators (J); negative: the material did net work on the bodies.
    pub operator_work: f64,
    /// Smallest operator work seen (J).
    pub operator_work_min: f64,
    /// Work injected by the load into the plate with the paper's absolute indentation (J).
    pub injected: f64,
    /// Energy balance error (relative).
    pub balance_error: f64,
    /// The trajectory (every accepted step), for plots and the trace.
    pub trajectory: Vec<(f64, Vec<f64>)>,
    /// The events located, in the order they fired: name, time (s), state.
    pub events: Vec<(&'static str, f64, Vec<f64>)>,
    /// Work done.
    pub stats: Stats,
    /// What the report must say.
    pub warnings: Vec<String>,
}

/// The events of [`run`], by index.
const EVENT_NAMES: [&str; 3] = [
    "indentation returns to zero",
    "contact force returns to zero",
    "max indentation",
];

/// Integrates one impact until contact ends or `t_end` (s).
pub fn run(
    sys: &ConePlate,
    t_end: Option<f64>,
    samples: &[f64],
    rtol: f64,
    atol: f64,
    method: Method,
) -> Result<Run, IntegrateError> {
    let window = t_end.unwrap_or(1.0);
    let gap = |_t: f64, y: &[f64]| sys.indentation(y).0;
    let force = |_t: f64, y: &[f64]| {
        if sys.indentation(y).0 > 0.0 {
            sys.contact_force(y)
        } else {
            0.0
        }
    };
    let rate = |_t: f64, y: &[f64]| sys.indentation(y).1;
    let events = vec![
        Event::new(EVENT_NAMES[0], &gap, Direction::Falling, true),
        Event::new(EVENT_NAMES[1], &force, Direction::Falling, true),
        Event::new(EVENT_NAMES[2], &rate, Direction::Falling, false),
    ];
    let mut times: Vec<f64> = samples
        .iter()
        .copied()
        .filter(|t| *t >= 0.0 && *t <= window)
        .collect();
    times.sort_by(f64::total_cmp);
    let opts = Options {
        rtol,
        atol,
        method,
        events,
        dense_times: times,
        trajectory: true,
        ..Options::default()
    };
    let sol = solve(sys, 0.0, &sys.initial_state(), window, &opts)?;
    let ended = matches!(sol.stop, Stop::Event { index: 0 | 1, .. });
    let mut warnings = sys.warnings.clone();
    if !ended {
        warnings.push(format!(
            "contact did not end within the window of {window:e} s"
        ));
    }
    let mut peak: f64 = 0.0;
    let mut max_d: f64 = 0.0;
    let mut op_min: f64 = 0.0;
    let mut tension: Option<(f64, f64)> = None;
    for (t, y) in &sol.trajectory {
        let (d, _) = sys.indentation(y);
        if d > 0.0 {
            let p = sys.contact_force(y);
            peak = peak.max(p);
            // the end point sits on the root of P: only earlier points count as tension
            if p < 0.0 && *t < sol.t && tension.is_none() {
                tension = Some((*t, p));
            }
        }
        max_d = max_d.max(d);
        op_min = op_min.min(sys.booked(y).1);
    }
    for e in &sol.events {
        if e.index == 2 {
            max_d = max_d.max(sys.indentation(&e.y).0);
            peak = peak.max(sys.contact_force(&e.y));
        }
    }
    // a force that returns to zero along a slow manifold (very viscous material: the cone rides
    // the recovering surface with P ~ 0) makes the end of contact, and so the duration,
    // ill-conditioned: say so rather than print a duration with digits it does not have
    if matches!(sol.stop, Stop::Event { index: 1, .. }) && sol.trajectory.len() >= 2 && peak > 0.0 {
        let (tp, yp) = &sol.trajectory[sol.trajectory.len() - 2];
        let p_prev = sys.contact_force(yp);
        let slope = p_prev / (sol.t - tp).max(f64::MIN_POSITIVE);
        let scale = peak / sol.t.max(f64::MIN_POSITIVE);
        if slope < 1e-3 * scale {
            warnings.push(format!(
                "the contact force returns to zero tangentially (|dP/dt| about {slope:.3e} N/s at the end, against peak/duration = {scale:.3e} N/s): the end of contact and the duration are ill-conditioned; the maximum indentation and the final energy are not"
            ));
        }
    }
    if let Some((t, p)) = tension {
        warnings.push(format!(
            "the contact law is tensile while indented (first at t = {t:.6e} s, P = {p:.6e} N): the material pulls the cone in instead of resisting it"
        ));
    }
    let (alpha, _) = sys.rates();
    if sys.effects.viscoelastic
        && (sys.law == Law::ConstantBulk || sys.variant == Variant::AsPrinted)
        && alpha < 0.0
    {
        warnings.push(format!(
            "not passive: the constant-bulk operator has a growing mode exp({:.6e} t) (alpha = {alpha:.6e} 1/s); over {:.3e} s it grows by a factor {:.3e}",
            -alpha,
            sol.t,
            (-alpha * sol.t).exp()
        ));
    }
    if op_min < -1e-9 * 0.5 * sys.params.mass * sys.params.v0.powi(2) {
        warnings.push(format!(
            "the material did net positive work on the bodies: operator work reached {op_min:.6e} J"
        ));
    }
    let y = &sol.y;
    let (diss, op, inj) = sys.booked(y);
    let samples = sol
        .dense
        .iter()
        .map(|(t, y)| Sample {
            t: *t,
            z: y[0],
            zdot: y[1],
            f: sys.centre_deflection(y),
            p: if sys.indentation(y).0 > 0.0 {
                sys.contact_force(y)
            } else {
                0.0
            },
        })
        .collect();
    Ok(Run {
        samples,
        ended,
        duration: sol.t,
        peak_force: peak,
        max_indentation: max_d,
        energy_initial: 0.5 * sys.params.mass * sys.params.v0.powi(2),
        energy_final: sys.kinetic(y) + sys.stored(y),
        dissipated: diss,
        operator_work: op,
        operator_work_min: op_min,
        injected: inj,
        balance_error: sys.balance_error(y),
        trajectory: sol.trajectory,
        events: sol
            .events
            .into_iter()
            .map(|e| (EVENT_NAMES[e.index], e.t, e.y))
            .collect(),
        stats: sol.stats,
        warnings,
    })
}
