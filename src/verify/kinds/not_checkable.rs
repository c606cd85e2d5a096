//! Kind `not-checkable`: a claim the text gives too little to check; `reason` says exactly what
//! is missing, and the verdict says so.

use super::{Checked, Kind, Session};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;

/// The keys of a `not-checkable` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NotCheckableSpec {
    /// Exactly what is missing from the text.
    reason: String,
}

/// A checked `not-checkable` claim.
pub struct NotCheckable {
    reason: String,
}

impl Kind for NotCheckable {
    const NAME: &'static str = "not-checkable";
    type Spec = NotCheckableSpec;

    fn validate(_: &Checked, _: &Head, s: NotCheckableSpec) -> Result<Self, VerifyError> {
        Ok(NotCheckable { reason: s.reason })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        Ok(outcome(
            cx.file,
            c,
            Verdict::NotCheckable,
            self.reason.clone(),
        ))
    }

    fn report(&self, _: &Head) -> String {
        "Kind `not-checkable`: the reason is what the text lacks.".into()
    }
}
