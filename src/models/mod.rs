//! Physical models, one per file, named by the physics. Models know nothing of reports.

pub mod balls_wall;
pub mod cone_plate;
pub mod constrained;
pub mod disk_friction;
pub mod fixed_points;
pub mod hertz;
pub mod pendulum_wall;
pub mod relaxation;
pub mod rigid_impact;
pub mod support;
