//! The adversarial search of a `bound` claim for its extreme: from the samples closest to the
//! bound, Nelder-Mead (the `argmin` crate) minimises the inequality's relative margin over the
//! sample box, so a constant printed tighter than the truth is refuted even where random samples
//! reach only part of the bound, and `sharp = true` can ask whether the bound is attained.
//!
//! The search runs in the unit cube of the sampled fields (each coordinate the probability of its
//! distribution below the value), where the box is the same for every distribution; a vertex
//! outside the cube is evaluated at its clamped point plus a penalty growing with the distance.

use super::scene::{Samples, Scene};
use crate::algebra::expr::Inequality;
use argmin::core::{CostFunction, Error, Executor, State};
use argmin::solver::neldermead::NelderMead;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How many of the closest samples the search starts from.
pub const STARTS: usize = 3;
/// Nelder-Mead iterations per start.
const ITERATIONS: u64 = 300;
/// The first simplex: each vertex one step of this size from the start, toward the middle.
const STEP: f64 = 0.1;

/// The most adverse point the search found.
#[derive(Clone, Debug)]
pub struct Extreme {
    /// The relative margin there ([`Inequality::margin`]; negative: violated).
    pub margin: f64,
    /// Both sides there.
    pub sides: (f64, f64),
    /// The fields' values there.
    pub point: Vec<(String, f64)>,
    /// Evaluations of the inequality (scene runs, with a scene) over all starts.
    pub evaluations: usize,
}

/// The margin of `ineq` at a point of the unit cube.
struct Margin<'a> {
    samples: &'a Samples,
    scene: Option<&'a Scene>,
    ineq: &'a Inequality,
    evaluations: &'a AtomicUsize,
}

impl Margin<'_> {
    fn at(&self, u: &[f64]) -> Option<(f64, (f64, f64))> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let pt = self.samples.point_at(u);
        let (l, r) = Samples::sides(self.scene, self.ineq, &pt).ok()?;
        let m = self.ineq.margin(l, r);
        m.is_finite().then_some((m, (l, r)))
    }
}

impl CostFunction for Margin<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, u: &Self::Param) -> Result<f64, Error> {
        let outside: f64 = u.iter().map(|x| (x - x.clamp(0.0, 1.0)).abs()).sum();
        // a point that does not run is no extreme: a cost above every margin (|margin| <= 2)
        let m = self.at(u).map_or(10.0, |(m, _)| m);
        Ok(m + 4.0 * outside)
    }
}

/// Searches from each start (points of the unit cube) for the least margin of `ineq`; `None`
/// when no start gives a point that runs.
pub fn search(
    samples: &Samples,
    scene: Option<&Scene>,
    ineq: &Inequality,
    starts: &[Vec<f64>],
) -> Option<Extreme> {
    use rayon::prelude::*;
    let evaluations = AtomicUsize::new(0);
    let found: Vec<(f64, Vec<f64>)> = starts
        .par_iter()
        .filter_map(|u0| {
            let cost = Margin {
                samples,
                scene,
                ineq,
                evaluations: &evaluations,
            };
            let mut simplex = vec![u0.clone()];
            for i in 0..u0.len() {
                let mut v = u0.clone();
                v[i] += if v[i] > 0.5 { -STEP } else { STEP };
                simplex.push(v);
            }
            let solver = NelderMead::new(simplex).with_sd_tolerance(1e-14).ok()?;
            let res = Executor::new(cost, solver)
                .configure(|s| s.max_iters(ITERATIONS))
                .run()
                .ok()?;
            let best = res.state().get_best_param()?.clone();
            Some((res.state().get_best_cost(), best))
        })
        .collect();
    let (_, u) = found.into_iter().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let u: Vec<f64> = u.iter().map(|x| x.clamp(0.0, 1.0)).collect();
    let probe = Margin {
        samples,
        scene,
        ineq,
        evaluations: &evaluations,
    };
    let (margin, sides) = probe.at(&u)?;
    Some(Extreme {
        margin,
        sides,
        point: samples.point_at(&u),
        evaluations: evaluations.load(Ordering::Relaxed),
    })
}

/// How close `l rel r` comes to its bound as a ratio (`l/r` for `<`, `r/l` for `>`), when both
/// sides are positive (1: attained).
pub fn ratio(ineq: &Inequality, (l, r): (f64, f64)) -> Option<f64> {
    use crate::algebra::expr::Rel;
    let (num, den) = match ineq.rel {
        Rel::Lt | Rel::Le => (l, r),
        Rel::Gt | Rel::Ge => (r, l),
    };
    (num >= 0.0 && den > 0.0).then(|| num / den)
}

#[cfg(test)]
mod tests {
    use super::ratio;
    use crate::algebra::expr::parse_inequality;

    #[test]
    fn the_ratio_to_a_bound_is_side_over_bound_for_positive_sides() {
        // by hand: l <= r at (1, 4) reaches 1/4 of its bound; l >= r at (4, 1) too; a side
        // that is not positive gives no ratio
        let le = parse_inequality("a <= b").expect("parses");
        let ge = parse_inequality("a >= b").expect("parses");
        assert_eq!(ratio(&le, (1.0, 4.0)), Some(0.25));
        assert_eq!(ratio(&ge, (4.0, 1.0)), Some(0.25));
        assert_eq!(ratio(&le, (1.0, -4.0)), None);
        assert_eq!(ratio(&le, (-1.0, 4.0)), None);
        assert_eq!(ratio(&le, (0.0, 4.0)), Some(0.0));
        assert_eq!(ratio(&le, (1.0, 0.0)), None);
    }
}
