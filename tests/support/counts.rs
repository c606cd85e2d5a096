//! The relations of an audit's JSON per status.

use serde_json::Value;

/// Consistent, inconsistent, undetermined, unreadable.
pub fn status_counts(audit: &Value) -> [usize; 4] {
    let n = |s: &str| {
        audit["relations"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["status"] == s)
            .count()
    };
    [
        n("consistent"),
        n("inconsistent"),
        n("undetermined"),
        n("unreadable"),
    ]
}
