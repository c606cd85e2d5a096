//! The values a sweep runs over: `KEY=START:STOP:COUNT` ranges (linear or geometric), explicit
//! value lists, and shards of them. Below both front ends (`impact sweep`, the verifier's grids).

use crate::models::RunError;

/// The values a sweep runs over.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepValues {
    /// Dotted scene field.
    pub param: String,
    /// Values, in order.
    pub values: Vec<f64>,
    /// Index of each value in the whole sweep (a shard runs a block of them).
    pub indices: Vec<usize>,
    /// Points in the whole sweep.
    pub total: usize,
}

impl SweepValues {
    fn new(param: &str, values: Vec<f64>) -> Self {
        SweepValues {
            param: param.to_string(),
            indices: (0..values.len()).collect(),
            total: values.len(),
            values,
        }
    }

    /// Keeps shard `k` of `n` (0-based): the contiguous block of points
    /// `[k total/n, (k+1) total/n)`, so that n machines together run every point once.
    pub fn shard(mut self, spec: &str) -> Result<Self, RunError> {
        let bad = || RunError::BadArgument {
            arg: "--shard".into(),
            message: format!("`{spec}`: expected K/N with 0 <= K < N, e.g. 0/4"),
        };
        let (k, n) = spec.split_once('/').ok_or_else(bad)?;
        let (k, n): (usize, usize) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if n == 0 || k >= n {
            return Err(bad());
        }
        let (lo, hi) = (k * self.total / n, (k + 1) * self.total / n);
        self.values = self.values[lo..hi].to_vec();
        self.indices = self.indices[lo..hi].to_vec();
        Ok(self)
    }
}

/// Parses `KEY=START:STOP:COUNT` (`log`: geometric spacing, START and STOP > 0).
pub fn parse_vary(spec: &str, log: bool) -> Result<SweepValues, RunError> {
    let bad = |m: &str| RunError::BadArgument {
        arg: "--vary".into(),
        message: format!("`{spec}`: {m}; expected KEY=START:STOP:COUNT, e.g. sigma=0.1:5:50"),
    };
    let (key, range) = spec.split_once('=').ok_or_else(|| bad("no `=`"))?;
    let key = key.trim();
    if key.is_empty() || key.split('.').any(|p| p.is_empty()) {
        return Err(bad(
            "the key must be a dotted scene path such as sigma or impactor.v0",
        ));
    }
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(bad("give START:STOP:COUNT"));
    }
    let num = |s: &str, what: &str| {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(&format!("{what} `{s}` is not a finite number")))
    };
    let (a, b) = (num(parts[0], "START")?, num(parts[1], "STOP")?);
    let n: usize = parts[2]
        .trim()
        .parse()
        .ok()
        .filter(|n| (1..=10_000_000).contains(n))
        .ok_or_else(|| bad("COUNT must be an integer in 1..=10000000"))?;
    if log && (a <= 0.0 || b <= 0.0) {
        return Err(bad("--log needs START > 0 and STOP > 0"));
    }
    let values = (0..n)
        .map(|i| {
            if n == 1 {
                return a;
            }
            let f = i as f64 / (n - 1) as f64;
            if i == n - 1 {
                b
            } else if log {
                tidy((a.ln() + f * (b.ln() - a.ln())).exp())
            } else {
                tidy(a + f * (b - a))
            }
        })
        .collect();
    Ok(SweepValues::new(key, values))
}

/// A grid value to 12 significant digits, rounded as a number (an integer over a power of ten),
/// so that `0:1:11` gives 0.3 and not the 0.30000000000000004 of `0 + 0.3 * 1`: the sweep's
/// inputs and its CSV show the value the user asked for. Values whose power of ten does not fit
/// an `f64` scale are kept as they are.
fn tidy(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let digits = 11 - v.abs().log10().floor() as i32;
    if !(-290..=290).contains(&digits) {
        return v;
    }
    let r = if digits >= 0 {
        let p = 10f64.powi(digits);
        (v * p).round() / p
    } else {
        let p = 10f64.powi(-digits);
        (v / p).round() * p
    };
    if r.is_finite() { r } else { v }
}

/// Parses `--param FIELD --values V1,V2,...`.
pub fn parse_values(param: &str, values: &str) -> Result<SweepValues, RunError> {
    let vals: Vec<f64> = values
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| RunError::BadArgument {
                    arg: "--values".into(),
                    message: format!("`{s}` is not a finite number"),
                })
        })
        .collect::<Result<_, _>>()?;
    if vals.is_empty() {
        return Err(RunError::BadArgument {
            arg: "--values".into(),
            message: "give at least one value, e.g. --values 0.1,1,10".into(),
        });
    }
    Ok(SweepValues::new(param, vals))
}
