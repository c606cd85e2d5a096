//! A run's path (issue 55): the independent variable at every accepted step of the integrator,
//! the states there, and the events located on the way, each column named with its SI unit.
//! `impact run SCENE --trace FILE` writes it (JSON or CSV); Python's `impactcheck.run` hands it
//! back as NumPy arrays whose names carry the units. A model records it only when asked
//! ([`super::Model::run_traced`]): a sweep or a claim never pays for it.

use serde::Serialize;

/// Accepted steps `(t, state)`, as the integrator records them.
pub type Steps = Vec<(f64, Vec<f64>)>;

/// A traced run's path, or why it has none (said by `impact run --trace` and kept by Python's
/// `Run.no_path`).
pub type Traced = Result<Trace, String>;

/// The path recorded, or `why` there is none.
pub fn or_why(trace: Option<Trace>, why: &str) -> Traced {
    trace.ok_or_else(|| why.to_string())
}

/// What a model that integrates no path says.
pub const NO_PATH_IN_TIME: &str =
    "the model integrates no path in time (its outcome is all a run gives)";

/// One named column: its name, its unit and its values, one per accepted step.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Column {
    /// The quantity (`z`, `dz/dt`, a text model's state name).
    pub name: String,
    /// Its SI unit (`m`, `m/s`; `1` for a pure number).
    pub unit: String,
    /// Its values.
    pub values: Vec<f64>,
}

impl Column {
    /// The name with the unit, as a table heads it: `z (m)`, `phase` for a pure number.
    pub fn heading(&self) -> String {
        heading(&self.name, &self.unit)
    }
}

/// `name (unit)`, or the bare name for a pure number (unit `1` or empty).
pub fn heading(name: &str, unit: &str) -> String {
    if unit.is_empty() || unit == "1" {
        name.to_string()
    } else {
        format!("{name} ({unit})")
    }
}

/// An event located on the path: its name, where it fired and the states there.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct TraceEvent {
    /// The event's name, as the model or the scene names it.
    pub name: String,
    /// The independent variable where it fired.
    pub at: f64,
    /// The states there, in the order of [`Trace::states`].
    pub state: Vec<f64>,
}

/// The path of one run.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Trace {
    /// The independent variable (time `t` in s; the normal impulse for the rigid-impact models).
    pub variable: Column,
    /// The states, each as long as `variable`.
    pub states: Vec<Column>,
    /// The events, in the order they fired.
    pub events: Vec<TraceEvent>,
}

impl Trace {
    /// An empty path in `variable` (`(name, unit)`) with the named states.
    pub fn new(variable: (&str, &str), states: &[(&str, &str)]) -> Self {
        let col = |(name, unit): (&str, &str)| Column {
            name: name.to_string(),
            unit: unit.to_string(),
            values: Vec::new(),
        };
        Trace {
            variable: col(variable),
            states: states.iter().map(|s| col(*s)).collect(),
            events: Vec::new(),
        }
    }

    /// Appends a step: the variable and the states (the first `states.len()` of `y`).
    pub fn push(&mut self, at: f64, y: &[f64]) {
        self.variable.values.push(at);
        for (c, v) in self.states.iter_mut().zip(y) {
            c.values.push(*v);
        }
    }

    /// Appends every step of an integrator's trajectory, skipping a step that repeats the last
    /// one recorded (a solve restarted where the previous one stopped, or where `Auto` switched
    /// methods); a jump (the same time, another state) is kept.
    pub fn extend(&mut self, steps: &[(f64, Vec<f64>)]) {
        for (t, y) in steps {
            let repeat = self.variable.values.last().map(|l| l.to_bits()) == Some(t.to_bits())
                && self
                    .states
                    .iter()
                    .zip(y)
                    .all(|(c, v)| c.values.last().map(|l| l.to_bits()) == Some(v.to_bits()));
            if !repeat {
                self.push(*t, y);
            }
        }
    }

    /// Records an event.
    pub fn event(&mut self, name: &str, at: f64, y: &[f64]) {
        let state = y.iter().take(self.states.len()).copied().collect();
        self.events.push(TraceEvent {
            name: name.to_string(),
            at,
            state,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_restarted_solve_is_kept_once_and_events_keep_the_columns() {
        let mut t = Trace::new(("t", "s"), &[("z", "m"), ("phase", "1")]);
        t.extend(&[(0.0, vec![0.0, 1.0]), (0.5, vec![0.25, 2.0])]);
        // a restarted solve repeats its first step: kept once; a jump (same t, new state) kept
        t.extend(&[(0.5, vec![0.25, 2.0]), (1.0, vec![0.1, 3.0])]);
        t.extend(&[(1.0, vec![0.1, -3.0])]);
        t.event("max z", 0.25, &[0.3, 1.5, 99.0]);
        assert_eq!(t.variable.values, [0.0, 0.5, 1.0, 1.0]);
        assert_eq!(t.states[1].values, [1.0, 2.0, 3.0, -3.0]);
        assert_eq!(
            t.events[0].state,
            [0.3, 1.5],
            "states beyond the columns dropped"
        );
        assert_eq!(t.states[0].heading(), "z (m)");
        assert_eq!(t.states[1].heading(), "phase");
    }
}
