//! The Darboux-Keller system (1.5) in the normal impulse: the contact's mode at C (slip, a slip
//! held on a ray, stick) and the right-hand side, with the support's reaction where there is one.

use super::*;
use crate::integrate::OdeSystem;
use nalgebra::{Matrix3, Vector3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Mode {
    Slip,
    /// Slip held along a ray it has settled on (the friction direction frozen).
    Ray(Vector3<f64>),
    /// A slip starting from a stick that the support's motion broke: its rate starts at zero,
    /// so its direction is held at the one the dynamics give at the break until the slip exceeds
    /// the velocity tolerance (its turning rate grows like 1/|V_t| below that).
    Held(Vector3<f64>),
    Stick(Vector3<f64>),
}

pub(super) struct Keller {
    pub(super) at_a: Option<AtA>,
    pub(super) b: Matrix3<f64>,
    pub(super) n: Vector3<f64>,
    pub(super) mu: f64,
    pub(super) mode: Mode,
    /// slip direction used when |V_t| is below the floor (set at a re-slide)
    pub(super) u_hint: Vector3<f64>,
    pub(super) floor: f64,
}

/// $\mathbf V_A$ from the state (zero without a support).
pub(super) fn va_of(y: &[f64]) -> Vector3<f64> {
    if y.len() >= 13 {
        Vector3::new(y[10], y[11], y[12])
    } else {
        Vector3::zeros()
    }
}

impl Keller {
    pub(super) fn tangential(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.n * v.dot(&self.n)
    }

    /// The contact force direction at C per unit normal impulse.
    pub(super) fn rate(&self, v: &Vector3<f64>, va: &Vector3<f64>) -> Vector3<f64> {
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
    pub(super) fn rates(
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
    pub(super) fn b_stick(&self, va: &Vector3<f64>) -> Matrix3<f64> {
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
