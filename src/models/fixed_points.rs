//! Bodies with fixed points or axes, 002_b53e4779673eb6ed.txt section 2: the matrix $\mathbf B^*$
//! of (2.1) and the geometric test of Proposition 2.
//!
//! For a body turning about a fixed point O, $\Delta\mathbf V_C = (\mathbf J_O^{-1}(\mathbf{OC}\times\mathbf I))\times\mathbf{OC}$;
//! about a fixed axis (O, e), $\Delta\mathbf V_C = (\mathbf e^*, \mathbf I)\,\mathbf e^*/J_e$ with
//! $\mathbf e^* = \mathbf e\times\mathbf{OC}$ (2.4); a free body contributes the terms of (1.7); an
//! immovable one nothing. Proposition 2: $\mathbf B^*$ is singular iff a straight line through C
//! meets both fixed sets.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// How a body is held.
#[derive(Clone, Debug)]
pub enum Hold {
    /// Free: mass (kg), central inertia (kg m^2), G->C (m).
    Free {
        /// Mass.
        mass: f64,
        /// Central inertia.
        inertia: Matrix3<f64>,
        /// G -> C.
        gc: Vector3<f64>,
    },
    /// About a fixed point O: inertia about O, O->C.
    Point {
        /// Inertia tensor about O.
        inertia_o: Matrix3<f64>,
        /// O -> C.
        oc: Vector3<f64>,
    },
    /// About a fixed axis through O with unit direction e: moment of inertia about the axis, O->C.
    Axis {
        /// Moment of inertia about the axis.
        j_axis: f64,
        /// Axis direction.
        e: Vector3<f64>,
        /// O -> C.
        oc: Vector3<f64>,
    },
    /// Immovable (its fixed set is all of space).
    Fixed,
}

/// One body's part of $\mathbf B^*$.
pub fn contribution(h: &Hold) -> Matrix3<f64> {
    let cols = |f: &dyn Fn(Vector3<f64>) -> Vector3<f64>| {
        Matrix3::from_columns(&[f(Vector3::x()), f(Vector3::y()), f(Vector3::z())])
    };
    match h {
        Hold::Free { mass, inertia, gc } => {
            let jinv = inertia.try_inverse().unwrap_or_else(Matrix3::zeros);
            cols(&|i| i / *mass + (jinv * gc.cross(&i)).cross(gc))
        }
        Hold::Point { inertia_o, oc } => {
            let jinv = inertia_o.try_inverse().unwrap_or_else(Matrix3::zeros);
            cols(&|i| (jinv * oc.cross(&i)).cross(oc))
        }
        Hold::Axis { j_axis, e, oc } => {
            let es = e.normalize().cross(oc);
            es * es.transpose() / *j_axis
        }
        Hold::Fixed => Matrix3::zeros(),
    }
}

/// $\mathbf B^*$ of (2.1) for two bodies.
pub fn b_star(h1: &Hold, h2: &Hold) -> Matrix3<f64> {
    contribution(h1) + contribution(h2)
}

/// True if $\mathbf B^*$ is singular (smallest eigenvalue below `1e-10` of the largest).
pub fn singular(b: &Matrix3<f64>) -> bool {
    let ev = SymmetricEigen::new(*b).eigenvalues;
    ev.min() <= 1e-10 * ev.max().abs().max(f64::MIN_POSITIVE)
}

/// The directions of lines through C that meet a body's fixed set: `None` for none (free body),
/// otherwise a basis of the admissible directions' span (empty = all directions).
enum Directions {
    None,
    Line(Vector3<f64>),
    Plane(Vector3<f64>),
    All,
}

fn directions(h: &Hold) -> Directions {
    match h {
        Hold::Free { .. } => Directions::None,
        Hold::Point { oc, .. } => {
            if oc.norm() == 0.0 {
                Directions::All
            } else {
                Directions::Line(oc.normalize())
            }
        }
        Hold::Axis { e, oc, .. } => {
            let es = e.normalize().cross(oc);
            if es.norm() <= 1e-14 * oc.norm().max(1.0) {
                Directions::All
            } else {
                Directions::Plane(es.normalize())
            }
        }
        Hold::Fixed => Directions::All,
    }
}

/// Proposition 2's geometric condition: a line through C meets both fixed sets.
pub fn line_meets_both(h1: &Hold, h2: &Hold) -> bool {
    let tol = 1e-9;
    match (directions(h1), directions(h2)) {
        (Directions::None, _) | (_, Directions::None) => false,
        (Directions::All, _) | (_, Directions::All) => true,
        (Directions::Line(a), Directions::Line(b)) => a.cross(&b).norm() <= tol,
        (Directions::Line(a), Directions::Plane(p))
        | (Directions::Plane(p), Directions::Line(a)) => a.dot(&p).abs() <= tol,
        (Directions::Plane(_), Directions::Plane(_)) => true,
    }
}
