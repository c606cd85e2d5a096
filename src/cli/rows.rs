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
    r: Result<&Cells, String>,
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
        Ok(cells) => cells.warnings.clone(),
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
    pub fn csv(&mut self, v: f64, index: usize, r: Result<&Cells, String>, columns: usize) {
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

    /// Empties the rows, keeping the buffers' room for the next run of points.
    pub fn clear(&mut self) {
        self.text.clear();
        self.marks.clear();
        self.failed = 0;
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

/// The lock's state, even when a thread panicked holding it (nothing here panics while it is
/// held; the state stays whole).
fn lock<T>(m: &std::sync::Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// What the makers of [`ordered`] share: how many runs are written, whether to stop, and the
/// written runs' buffers, cleared, for later runs.
struct Gate {
    written: usize,
    stop: bool,
    spare: Vec<Rows>,
}

/// Stops the makers of [`ordered`]: when the writer fails, or, dropped while its maker
/// unwinds, when a maker panics (the writer then sees the channel close).
struct Stop<'g>(&'g (std::sync::Mutex<Gate>, std::sync::Condvar));

impl Stop<'_> {
    fn now(&self) {
        lock(&self.0.0).stop = true;
        self.0.1.notify_all();
    }
}

impl Drop for Stop<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.now();
        }
    }
}

/// Makes `count` runs of rows on rayon's pool and on this thread, `make(k, rows)` filling run
/// `k`'s, and hands them to `write` on this thread in order 0, 1, 2, ... as they are made.
/// This thread is one of the makers and writes what is ready between its runs, so there is
/// one busy thread per core, none waits for another while there is a run to make, and none
/// is woken per run; no run is made `window` or more runs ahead of the next to write, so
/// memory stays bounded at any sweep size; a written run's buffers go to a later
/// run (cleared, their room kept: no growth, no fresh pages). A `write` error stops the
/// makers and is returned; a panic in `make` stops them and is raised here.
///
/// Written here because rayon orders a parallel map's results only by collecting them (a
/// barrier per batch), and no well-kept crate streams one in order with a bounded lookahead.
pub(super) fn ordered<E>(
    count: usize,
    window: usize,
    make: impl Fn(usize, &mut Rows) + Sync,
    mut write: impl FnMut(&Rows) -> Result<(), E>,
) -> Result<(), E> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let gate = (
        std::sync::Mutex::new(Gate {
            written: 0,
            stop: false,
            spare: Vec::new(),
        }),
        std::sync::Condvar::new(),
    );
    let window = window.max(1);
    let next = AtomicUsize::new(0);
    let (tx, rx) = std::sync::mpsc::channel::<(usize, Rows)>();
    let helpers = rayon::current_num_threads()
        .saturating_sub(1)
        .min(count.saturating_sub(1));
    rayon::in_place_scope(|scope| {
        for _ in 0..helpers {
            let (tx, gate, next, make) = (tx.clone(), &gate, &next, &make);
            scope.spawn(move |_| {
                let _stop = Stop(gate);
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= count {
                        return;
                    }
                    let mut rows = {
                        let mut g = lock(&gate.0);
                        while !g.stop && k >= g.written + window {
                            g = gate
                                .1
                                .wait(g)
                                .unwrap_or_else(std::sync::PoisonError::into_inner);
                        }
                        if g.stop {
                            return;
                        }
                        g.spare.pop().unwrap_or_default()
                    };
                    make(k, &mut rows);
                    if tx.send((k, rows)).is_err() {
                        return;
                    }
                }
            });
        }
        drop(tx);
        let stop = Stop(&gate);
        // runs made before their turn, kept until it comes
        let mut early = std::collections::BTreeMap::new();
        let mut written = 0;
        while written < count {
            early.extend(rx.try_iter());
            if let Some(mut rows) = early.remove(&written) {
                if let Err(e) = write(&rows) {
                    stop.now();
                    return Err(e);
                }
                rows.clear();
                written += 1;
                let mut g = lock(&gate.0);
                g.written = written;
                g.spare.push(rows);
                drop(g);
                gate.1.notify_all();
                continue;
            }
            // nothing to write: make the next run if it is within the window, or wait for the
            // helpers' runs
            let k = next.load(Ordering::Relaxed);
            if k < count.min(written + window) {
                if next
                    .compare_exchange(k, k + 1, Ordering::Relaxed, Ordering::Relaxed)
                    .is_ok()
                {
                    let mut rows = lock(&gate.0).spare.pop().unwrap_or_default();
                    make(k, &mut rows);
                    early.insert(k, rows);
                }
                continue;
            }
            match rx.recv() {
                Ok((k, rows)) => {
                    early.insert(k, rows);
                }
                // the helpers stopped: one panicked, and the scope raises it
                Err(_) => break,
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::cells::Leaf;

    fn cells(leaves: &[Option<Leaf>], warnings: &[&str]) -> Cells {
        Cells {
            leaves: leaves.to_vec(),
            warnings: warnings.iter().map(|w| w.to_string()).collect(),
            trail: Default::default(),
        }
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
            Ok(&cells(
                &[Some(Leaf::F64(1.5)), None],
                &["atol tightened to 1e-12"],
            )),
            2,
        );
        a.csv(
            1.0,
            1,
            Ok(&cells(&[Some(Leaf::Bool(true)), Some(Leaf::U64(3))], &[])),
            2,
        );
        let mut b = Rows::default();
        b.csv(2.0, 2, Err("bad, \"one\"".into()), 2);
        b.csv(
            2.5,
            3,
            Ok(&cells(
                &[None, Some(Leaf::I64(-4))],
                &["atol tightened to 1e-13", "w,2"],
            )),
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

    /// Runs made with uneven costs come to the writer in order, each once, never more than
    /// the window ahead of it, in buffers handed back cleared (at most `window` fresh ones:
    /// every other run reuses a written one); no runs at all write nothing.
    #[test]
    fn runs_are_written_in_order_within_the_window_in_reused_buffers() {
        use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
        for (count, window) in [(0, 4), (1, 1), (7, 1), (500, 3), (300, 64)] {
            let written = AtomicUsize::new(0);
            let (ahead, dirty, fresh) = (
                AtomicBool::new(false),
                AtomicBool::new(false),
                AtomicUsize::new(0),
            );
            let make = |k: usize, rows: &mut Rows| {
                ahead.fetch_or(
                    k >= written.load(Ordering::SeqCst) + window,
                    Ordering::SeqCst,
                );
                dirty.fetch_or(!rows.text.is_empty() || rows.failed > 0, Ordering::SeqCst);
                fresh.fetch_add(usize::from(rows.text.capacity() == 0), Ordering::SeqCst);
                // uneven work: some runs take far longer than others
                std::thread::sleep(std::time::Duration::from_micros(
                    (k as u64 * 7919) % 13 * 20,
                ));
                rows.line("", &format!("{k};"), k.is_multiple_of(5));
            };
            let mut seen = String::new();
            let mut failed = 0;
            let write = |rows: &Rows| -> Result<(), ()> {
                seen.push_str(std::str::from_utf8(&rows.text).expect("utf-8"));
                failed += rows.failed;
                written.fetch_add(1, Ordering::SeqCst);
                Ok(())
            };
            ordered(count, window, make, write).expect("writes");
            let want: String = (0..count).map(|k| format!("{k};")).collect();
            assert_eq!(seen, want, "{count} runs, window {window}");
            assert_eq!(failed, count.div_ceil(5));
            assert!(
                !ahead.load(Ordering::SeqCst),
                "a run made beyond the window"
            );
            assert!(
                !dirty.load(Ordering::SeqCst),
                "a buffer handed back not cleared"
            );
            assert!(
                fresh.load(Ordering::SeqCst) <= window.max(1),
                "buffers not reused"
            );
        }
    }

    /// A writer that fails stops the makers and its error is the result; a maker that panics
    /// stops the others and the panic comes out here: neither hangs.
    #[test]
    fn a_failed_write_or_a_panicking_run_stops_the_stream() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let made = AtomicUsize::new(0);
        let mut writes = 0;
        let r = ordered(
            10_000,
            8,
            |k, rows| {
                made.fetch_add(1, Ordering::SeqCst);
                rows.line("", &k.to_string(), false);
            },
            |_| {
                writes += 1;
                if writes == 10 {
                    Err("the pipe closed")
                } else {
                    Ok(())
                }
            },
        );
        assert_eq!(r, Err("the pipe closed"));
        // the runs made: the ten written, the window ahead, one per maker at most past it
        assert!(made.load(Ordering::SeqCst) <= 10 + 8 + rayon::current_num_threads());
        let panicked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            ordered(
                10_000,
                8,
                |k, rows| {
                    assert!(k != 7, "run 7 fails");
                    rows.line("", "x", false);
                },
                |_| Ok::<(), ()>(()),
            )
        }));
        assert!(panicked.is_err(), "the maker's panic is raised");
    }
}
