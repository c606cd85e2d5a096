//! Where a run of `verify` spends its time (issue 68): the wall clock of each part of the run,
//! in order, and the slowest verdicts. `verify --timing` prints both and writes the parts to
//! `timing/main_job.md`, the folder of measured times.

use std::time::Instant;

/// The wall-clock time of each part of a run, in order.
pub struct Phases {
    last: Instant,
    parts: Vec<(String, f64)>,
}

impl Default for Phases {
    fn default() -> Self {
        Self::new()
    }
}

impl Phases {
    /// Starts the clock.
    pub fn new() -> Self {
        Phases {
            last: Instant::now(),
            parts: Vec::new(),
        }
    }

    /// Closes the part `name`: the time since the last part closed (or the clock started).
    pub fn mark(&mut self, name: &str) {
        let now = Instant::now();
        self.record(name, (now - self.last).as_secs_f64());
        self.last = now;
    }

    /// Adds a part of `seconds` measured elsewhere.
    pub fn record(&mut self, name: &str, seconds: f64) {
        self.parts.push((name.to_string(), seconds));
    }

    /// The parts as a Markdown table: each with its share of the total, then the total.
    pub fn table(&self) -> String {
        let total: f64 = self.parts.iter().map(|p| p.1).sum();
        let mut md =
            String::from("| part of the run | wall clock (s) | share |\n|---|---:|---:|\n");
        for (name, t) in &self.parts {
            md.push_str(&format!(
                "| {name} | {t:.3} | {:.0} % |\n",
                100.0 * t / total.max(1e-12)
            ));
        }
        md.push_str(&format!("| total | {total:.3} | |\n"));
        md
    }
}

/// The `n` slowest of `times` (claim id, seconds), slowest first, as lines, after a line with
/// the total of all.
pub fn slowest(times: &[(String, f64)], n: usize) -> String {
    let mut sorted: Vec<&(String, f64)> = times.iter().collect();
    sorted.sort_by(|a, b| b.1.total_cmp(&a.1));
    let total: f64 = times.iter().map(|t| t.1).sum();
    let mut out = format!(
        "the {} slowest verdicts (of {total:.2} s for all {}):\n",
        n.min(times.len()),
        times.len()
    );
    for (id, t) in sorted.into_iter().take(n) {
        out.push_str(&format!("  {t:8.3} s  {id}\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_add_up_and_the_slowest_come_first() {
        assert!(Phases::default().parts.is_empty());
        let mut p = Phases::new();
        p.record("read", 1.0);
        p.record("verdicts", 3.0);
        // by hand: 1 s and 3 s of 4 s are 25 % and 75 %
        let t = p.table();
        assert!(t.contains("| read | 1.000 | 25 % |"), "{t}");
        assert!(t.contains("| verdicts | 3.000 | 75 % |"), "{t}");
        assert!(t.contains("| total | 4.000 | |"), "{t}");
        p.mark("now");
        assert_eq!(p.parts.len(), 3);
        assert!(p.parts[2].1 >= 0.0 && p.parts[2].1 < 60.0);
        let times = [("a".to_string(), 0.5), ("b".into(), 2.0), ("c".into(), 1.0)];
        assert_eq!(
            slowest(&times, 2),
            "the 2 slowest verdicts (of 3.50 s for all 3):\n     2.000 s  b\n     1.000 s  c\n"
        );
    }
}
