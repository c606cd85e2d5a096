//! A sweep's rows as they are made: many rows written where they ran into one buffer
//! ([`Rows`]: one allocation for a run of points, not one per row), the cells of a CSV row
//! written straight from the outcome, a row's warnings left for the writer (said once per
//! wording, in index order: [`crate::scene::warnings::Said`]).

use crate::scene::cells::Cells;
use crate::scene::warnings::Said;

/// A CSV field, quoted when it holds a comma, a quote or a line end.
pub(super) fn csv_quote(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The CSV row of point `index` appended to `out`: the value and the outcome's cells and the
/// comma that opens the warnings cell, then the error, the index and the line's end. Returns
/// where the warnings cell goes and the run's warnings. A failed run has a cell for each of the
/// `columns` too, empty. Numbers are written by serde_json's own formatter (no `fmt`).
pub(super) fn csv_line(
    out: &mut Vec<u8>,
    v: f64,
    index: usize,
    r: Result<Cells, String>,
    columns: usize,
) -> (usize, Vec<String>) {
    let _ = serde_json::to_writer(&mut *out, &v);
    match &r {
        Ok(cells) => {
            for cell in &cells.leaves {
                out.push(b',');
                if let Some(c) = cell {
                    c.write(out);
                }
            }
        }
        Err(_) => out.extend(std::iter::repeat_n(b',', columns)),
    }
    out.push(b',');
    let split = out.len();
    out.push(b',');
    let warnings = match r {
        Ok(cells) => cells.warnings,
        Err(e) => {
            out.extend_from_slice(csv_quote(&e).as_bytes());
            Vec::new()
        }
    };
    out.push(b',');
    let _ = serde_json::to_writer(&mut *out, &index);
    out.push(b'\n');
    (split, warnings)
}

/// The rows of a run of consecutive points, in index order: their text in one buffer, and for
/// each CSV row with warnings the place of its warnings cell, its index and its warnings.
#[derive(Debug, Default)]
pub(super) struct Rows {
    text: Vec<u8>,
    marks: Vec<(usize, usize, Vec<String>)>,
    /// The failed points among them.
    pub failed: usize,
}

impl Rows {
    /// Appends the CSV row of point `index` ([`csv_line`]).
    pub fn csv(&mut self, v: f64, index: usize, r: Result<Cells, String>, columns: usize) {
        self.failed += usize::from(r.is_err());
        let (at, warnings) = csv_line(&mut self.text, v, index, r, columns);
        if !warnings.is_empty() {
            self.marks.push((at, index, warnings));
        }
    }

    /// Opens a row of JSON or text after `sep` (`bad` marks a failed point): the buffer to write
    /// the row's text to (UTF-8), in place.
    pub fn open(&mut self, sep: &str, bad: bool) -> &mut Vec<u8> {
        self.failed += usize::from(bad);
        self.text.extend_from_slice(sep.as_bytes());
        &mut self.text
    }

    /// Appends a row of JSON or text, after `sep`; `bad` marks a failed point.
    pub fn line(&mut self, sep: &str, line: &str, bad: bool) {
        self.open(sep, bad).extend_from_slice(line.as_bytes());
    }

    /// Writes the rows to `out` from byte `skip` on (the separator before the first row of a
    /// sweep left out), each CSV row's warnings as `said` has them.
    pub fn write_to(
        &self,
        out: &mut dyn std::io::Write,
        said: &mut Said,
        skip: usize,
    ) -> std::io::Result<()> {
        let mut from = skip.min(self.text.len());
        for (at, index, warnings) in &self.marks {
            out.write_all(&self.text[from..*at])?;
            out.write_all(csv_quote(&said.cell(*index, warnings)).as_bytes())?;
            from = *at;
        }
        out.write_all(&self.text[from..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::cells::Leaf;

    fn cells(leaves: &[Option<Leaf>], warnings: &[&str]) -> Result<Cells, String> {
        Ok(Cells {
            leaves: leaves.to_vec(),
            warnings: warnings.iter().map(|w| w.to_string()).collect(),
            order: Vec::new(),
        })
    }

    /// Rows written by hand from their cells: a warning in full the first time its wording
    /// appears, `like row N` after, across two runs of rows written one after the other; a
    /// failed point's error quoted; a JSON run's first separator left out.
    #[test]
    fn rows_are_their_cells_with_each_warning_said_once() {
        let mut said = Said::default();
        let mut a = Rows::default();
        a.csv(
            0.5,
            0,
            cells(&[Some(Leaf::F64(1.5)), None], &["atol tightened to 1e-12"]),
            2,
        );
        a.csv(
            1.0,
            1,
            cells(&[Some(Leaf::Bool(true)), Some(Leaf::U64(3))], &[]),
            2,
        );
        let mut b = Rows::default();
        b.csv(2.0, 2, Err("bad, \"one\"".into()), 2);
        b.csv(
            2.5,
            3,
            cells(
                &[None, Some(Leaf::I64(-4))],
                &["atol tightened to 1e-13", "w,2"],
            ),
            2,
        );
        let mut out = Vec::new();
        a.write_to(&mut out, &mut said, 0).expect("writes");
        b.write_to(&mut out, &mut said, 0).expect("writes");
        assert_eq!(
            String::from_utf8(out).expect("utf-8"),
            "0.5,1.5,,atol tightened to 1e-12,,0\n\
             1.0,true,3,,,1\n\
             2.0,,,,\"bad, \"\"one\"\"\",2\n\
             2.5,,-4,\"like row 0: 1e-13; w,2\",,3\n"
        );
        assert_eq!((a.failed, b.failed), (0, 1));
        let mut j = Rows::default();
        j.line(",\n    ", "{\"index\":0}", false);
        j.open(",\n    ", true).extend_from_slice(b"{\"index\":1}");
        let mut out = Vec::new();
        j.write_to(&mut out, &mut said, 1).expect("writes");
        assert_eq!(out, b"\n    {\"index\":0},\n    {\"index\":1}");
        assert_eq!(j.failed, 1);
    }
}
