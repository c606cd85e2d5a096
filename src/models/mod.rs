//! Physical models, one per file, named by the physics. Models know nothing of reports or of the
//! scene registry.
//!
//! A model that a scene can name implements [`Model`]: it owns its scene parameters (read from
//! the scene table by serde into raw structs and validated with [`params::Fields`]), its run, its
//! typed outcome (what `impact run`, sweeps and `model` claims read) and its plot curves. The
//! registry of names is `crate::scene`; adding a model is one file here plus one line there.

pub mod balls_wall;
pub mod cone_plate;
pub mod constrained;
pub mod deformable;
pub mod disk_friction;
pub mod doc;
pub mod fixed_points;
pub mod hertz;
pub mod ode;
pub mod params;
pub mod pendulum_wall;
pub mod planar_impact;
pub mod relaxation;
pub mod rigid_impact;
pub mod samples;
pub mod support;
pub mod trace;

pub use params::{SceneError, SolveSpec};

/// Curves for `--plot`: `(name, points)`.
pub type Curves = Vec<(String, Vec<(f64, f64)>)>;

/// Why a run failed.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The scene is bad.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The solver could not meet its tolerance (with time and step size).
    #[error("solver: {0}")]
    Integrate(#[from] crate::integrate::IntegrateError),
    /// The solver stopped because a non-passive model's solution grows without bound.
    #[error(
        "solver: {source}; the model is not passive: its operator has the growing mode exp({rate:.4e} t), so the solution grows without bound (use viscoelastic_law = \"constant-poisson\" or a shorter t_end)"
    )]
    NotPassive {
        /// What the solver said.
        source: crate::integrate::IntegrateError,
        /// Growth rate (1/s).
        rate: f64,
    },
    /// A bad argument.
    #[error("{arg}: {message}")]
    BadArgument {
        /// Argument.
        arg: String,
        /// What is wrong.
        message: String,
    },
}

/// The contact of one impact, as every contact model reports it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ContactOutcome {
    /// Whether contact ended inside the window.
    pub ended: bool,
    /// Contact duration (s), or the window if it did not end.
    pub duration: f64,
    /// Largest contact force (N).
    pub peak_force: f64,
    /// Largest indentation (m).
    pub max_indentation: f64,
}

/// A model a scene can name.
pub trait Model: Sized + Clone + Send + Sync + 'static {
    /// The name scenes give it (`model = "hertz"`).
    const NAME: &'static str;
    /// Its reference: every scene key and every outcome ([`doc`], `impact describe`).
    const DOC: &'static doc::ModelDoc;
    /// What one run gives; serialized once, by `impact run`, sweeps and claims.
    type Outcome: serde::Serialize;
    /// Reads and validates a scene table; `path` names the file in errors.
    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError>;
    /// Runs the scene: the outcome and the curves of `impact run --plot`.
    fn run(&self) -> Result<(Self::Outcome, Curves), RunError>;
    /// Runs the scene and records its path ([`trace::Trace`]: every accepted step, the events),
    /// or says why it has none (a model that integrates no path: its outcome is all there is).
    /// The outcome is the one [`Model::run`] gives, to the bit.
    fn run_traced(&self) -> Result<(Self::Outcome, trace::Traced), RunError> {
        Ok((self.run()?.0, Err(trace::NO_PATH_IN_TIME.to_string())))
    }
    /// Sets a numeric scene field on the validated parameters, with the same check and message
    /// as reading it from a table; `None` when this model does not set that field this way (a
    /// sweep then re-reads the scene table with the field changed). It sets that field alone,
    /// and a bad value changes nothing: a sweep sets one copy of the scene point after point.
    fn set_number(&mut self, _field: &str, _v: f64, _path: &str) -> Option<Result<(), SceneError>> {
        None
    }
}
