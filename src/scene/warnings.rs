//! A sweep's warnings said once: many rows of a sweep carry the same warning with other numbers
//! ("atol tightened from 1e-9 to 2.1e-13 = rtol x the indentation scale 2.1e-4 m, ..." on every
//! row of a Hertz sweep over small speeds: 229k rows, 59 MB of CSV). A warning is written in full
//! on the first row (in index order) that has its wording; a later row with the same wording
//! carries `like row N:` and its own numbers, so that nothing is lost and the CSV stays small.
//! The wording is the text with its numbers taken out ([`shape`]).

use std::collections::HashMap;

/// The warning's wording (each number replaced by `#`) and its numbers, in order. A number starts
/// with a digit that does not follow a letter, `_` or `.` (so `v0`, `a1_22` and `x.0` are words),
/// and may carry a fraction and an exponent; a full stop after it is the sentence's.
pub fn shape(text: &str) -> (String, Vec<&str>) {
    let bytes = text.as_bytes();
    let mut wording = String::with_capacity(text.len());
    let mut numbers = Vec::new();
    let mut i = 0;
    let word_char = |b: u8| b.is_ascii_alphanumeric() || b == b'_' || b == b'.';
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit() && (i == 0 || !word_char(bytes[i - 1]));
        if !starts {
            let c = text[i..].chars().next().unwrap_or(' ');
            wording.push(c);
            i += c.len_utf8();
            continue;
        }
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
            i += 1;
        }
        if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
            let mut j = i + 1;
            if j < bytes.len() && matches!(bytes[j], b'+' | b'-') {
                j += 1;
            }
            if j < bytes.len() && bytes[j].is_ascii_digit() {
                while j < bytes.len() && bytes[j].is_ascii_digit() {
                    j += 1;
                }
                i = j;
            }
        }
        // a word that starts with digits (`3D`, `2nd`) stays a word
        if i < bytes.len() && (bytes[i].is_ascii_alphabetic() || bytes[i] == b'_') {
            while i < bytes.len() && word_char(bytes[i]) {
                i += 1;
            }
            wording.push_str(&text[start..i]);
            continue;
        }
        let mut end = i;
        while end > start + 1 && bytes[end - 1] == b'.' {
            end -= 1;
        }
        numbers.push(&text[start..end]);
        wording.push('#');
        wording.push_str(&text[end..i]);
    }
    (wording, numbers)
}

/// The wordings met so far: the first row of each and how many rows carry it.
#[derive(Default)]
pub struct Said {
    first: HashMap<String, (usize, usize)>,
    order: Vec<String>,
}

impl Said {
    /// The `warnings` cell of row `index` (rows are given in index order): each warning in full
    /// the first time its wording appears, else `like row N:` and its numbers; joined by `; `.
    pub fn cell(&mut self, index: usize, warnings: &[String]) -> String {
        let mut parts = Vec::with_capacity(warnings.len());
        for w in warnings {
            let (wording, numbers) = shape(w);
            match self.first.get_mut(&wording) {
                Some((first, count)) if *first != index => {
                    *count += 1;
                    parts.push(if numbers.is_empty() {
                        format!("like row {first}")
                    } else {
                        format!("like row {first}: {}", numbers.join(" "))
                    });
                }
                Some((_, count)) => {
                    *count += 1;
                    parts.push(w.clone());
                }
                None => {
                    self.first.insert(wording.clone(), (index, 1));
                    self.order.push(wording);
                    parts.push(w.clone());
                }
            }
        }
        parts.join("; ")
    }

    /// One line per wording said on more than one row: how many rows, and the first.
    pub fn summary(&self) -> Vec<String> {
        self.order
            .iter()
            .filter_map(|w| {
                let (first, count) = self.first[w];
                (count > 1).then(|| {
                    format!("{count} rows warn `{w}` (in full at row {first}, `#` its numbers)")
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Wordings and numbers written out by hand from the texts.
    #[test]
    fn numbers_leave_the_wording_and_words_stay() {
        let (w, n) = shape("atol tightened from 1e-9 to 2.15e-13 = rtol x the scale 2.1e-4 m.");
        assert_eq!(w, "atol tightened from # to # = rtol x the scale # m.");
        assert_eq!(n, ["1e-9", "2.15e-13", "2.1e-4"]);
        let (w, n) = shape("v0 of a1_22 in 3D at x.0 gained 12 %, then 0.5");
        assert_eq!(w, "v0 of a1_22 in 3D at x.0 gained # %, then #");
        assert_eq!(n, ["12", "0.5"]);
    }

    #[test]
    fn a_wording_is_in_full_once_then_referred_to() {
        let mut s = Said::default();
        let a = |x: &str| vec![format!("scale {x} m"), "Painleve case".to_string()];
        assert_eq!(s.cell(0, &a("1e-6")), "scale 1e-6 m; Painleve case");
        assert_eq!(s.cell(1, &a("2e-6")), "like row 0: 2e-6; like row 0");
        assert_eq!(s.cell(2, &["other".to_string()]), "other");
        assert_eq!(
            s.summary(),
            [
                "2 rows warn `scale # m` (in full at row 0, `#` its numbers)",
                "2 rows warn `Painleve case` (in full at row 0, `#` its numbers)"
            ]
        );
    }
}
