//! The layout of a line figure that reads alone (issue 54): the title wrapped to the canvas, the
//! legend's column as wide as its longest entry (the canvas grows to hold it), tick labels in one
//! format per axis, curves that coincide at the figure's scale drawn dashed with markers (the
//! largest difference between them in the caption), a linear axis that would flatten a curve
//! turned logarithmic where every value is positive, panels that share the x axis for curves of
//! different sizes, and a caption under the plot. `tests/figures.rs` renders every figure with a
//! real renderer and real fonts and holds these rules.
//!
//! Text widths are estimated here from DejaVu Sans' advances (the sans-serif face the tests
//! render with), rounded up by character class, so that the layout errs on the roomy side.
//!
//! The primitives a figure is drawn from (a curve [`Series`], an axis [`Scale`], a tick label
//! [`short_number`]) live here, below the entry points of `svg.rs` that re-export them.

/// One curve.
#[derive(Clone)]
pub struct Series<'a> {
    /// Legend text.
    pub name: &'a str,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
}

/// Axis scale.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear.
    Linear,
    /// Base-10 logarithmic (non-positive values are dropped).
    Log,
}

/// A short tick label: `0.5`, `20`, `1e-3` (no more digits than the value needs, to 3 figures).
pub fn short_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i32;
    if (-3..=4).contains(&e) {
        let digits = (2 - e).max(0) as usize;
        let s = format!("{v:.digits$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        return s;
    }
    let m = v / 10f64.powi(e);
    let ms = format!("{m:.2}");
    let ms = ms.trim_end_matches('0').trim_end_matches('.');
    if ms == "1" {
        format!("1e{e}")
    } else {
        format!("{ms}e{e}")
    }
}

/// The Okabe-Ito palette (safe for the common colour-vision deficiencies), yellow last.
pub(crate) const COLORS: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];

/// The advance of `s` at `size` px in DejaVu Sans, rounded up per character class.
pub fn text_width(s: &str, size: f64) -> f64 {
    let em: f64 = s
        .chars()
        .map(|c| match c {
            'i' | 'j' | 'l' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' | 'I' => 0.32,
            ' ' | 'f' | 't' | 'r' | '(' | ')' | '[' | ']' | '/' | '-' => 0.42,
            'm' | 'w' | 'M' | 'W' => 0.98,
            c if c.is_ascii_digit() => 0.64,
            c if c.is_ascii_uppercase() => 0.76,
            c if c.is_ascii_lowercase() => 0.63,
            _ => 0.84,
        })
        .sum();
    em * size
}

/// `text` broken at spaces into lines no wider than `width` at `size` px.
pub fn wrap(text: &str, size: f64, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for word in text.split_whitespace() {
        let next = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if !cur.is_empty() && text_width(&next, size) > width {
            lines.push(std::mem::replace(&mut cur, word.to_string()));
        } else {
            cur = next;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// Labels for values in one format: as [`short_number`] when every one is plain there (0.01 to
/// 10^4 or 0), else every one as mantissa and exponent (`2.5e-3`, `1e0`).
pub fn uniform_labels(values: &[f64]) -> Vec<String> {
    let plain = values
        .iter()
        .all(|v| *v == 0.0 || (1e-2..1e4).contains(&v.abs()));
    values
        .iter()
        .map(|&v| {
            if plain || v == 0.0 || !v.is_finite() {
                short_number(v)
            } else {
                let e = v.abs().log10().floor() as i32;
                let m = format!("{:.2}", v / 10f64.powi(e));
                let m = m.trim_end_matches('0').trim_end_matches('.');
                format!("{m}e{e}")
            }
        })
        .collect()
}

/// The SVG's opening: the canvas `w` x `h` on white, and the title's lines centred on it.
pub(crate) fn opening(w: f64, h: f64, title_lines: &[String]) -> String {
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{w:.0}\" height=\"{h:.0}\" fill=\"white\"/>\n"
    );
    for (k, line) in title_lines.iter().enumerate() {
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
            w / 2.0,
            22.0 + 18.0 * k as f64,
            escape(line)
        ));
    }
    out
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// One plot area of a figure: its y axis and its curves.
pub struct Panel<'a> {
    /// The y axis' title: the quantity and its unit.
    pub ylabel: &'a str,
    /// The y scale asked for (a linear one may turn logarithmic, see the module doc).
    pub ys: Scale,
    /// The curves.
    pub series: Vec<Series<'a>>,
}

/// A figure: a title in words, panels sharing one x axis, and a caption.
pub struct Figure<'a> {
    /// What the figure shows, in words.
    pub title: &'a str,
    /// The x axis' title: the quantity and its unit.
    pub xlabel: &'a str,
    /// The x scale.
    pub xs: Scale,
    /// The plot areas, top to bottom.
    pub panels: Vec<Panel<'a>>,
    /// Lines of caption under the plot (the claim it belongs to, what to read in it).
    pub caption: Vec<String>,
}

fn tf(v: f64, s: Scale) -> Option<f64> {
    match s {
        Scale::Linear => v.is_finite().then_some(v),
        Scale::Log => (v > 0.0 && v.is_finite()).then(|| v.log10()),
    }
}

/// Tick labels in one format: decades all as `1e-3` when any is outside 0.01..1000, else plain;
/// linear ticks all plain with the step's decimals, or all as mantissa and exponent when the
/// axis reaches 1e5 or its step is below 1e-3.
fn ticks(lo: f64, hi: f64, scale: Scale) -> (f64, f64, Vec<(f64, String)>) {
    match scale {
        Scale::Log => {
            let (a, b) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
            let n = (b - a) as i64;
            let every = (n / 6 + 1).max(1);
            let exps: Vec<i64> = (0..=n)
                .filter(|k| k % every == 0)
                .map(|k| a as i64 + k)
                .collect();
            let plain = exps.iter().all(|e| (-2..=3).contains(e));
            let list = exps
                .iter()
                .map(|&e| {
                    let label = if plain {
                        short_number(10f64.powi(e as i32))
                    } else {
                        format!("1e{e}")
                    };
                    (e as f64, label)
                })
                .collect();
            (a, b, list)
        }
        Scale::Linear => {
            let span = (hi - lo).max(f64::MIN_POSITIVE);
            let raw = span / 5.0;
            let mag = 10f64.powf(raw.log10().floor());
            let step = [1.0, 2.0, 5.0, 10.0]
                .iter()
                .map(|m| m * mag)
                .find(|s| *s >= raw)
                .unwrap_or(10.0 * mag);
            let (a, b) = ((lo / step).floor() * step, (hi / step).ceil() * step);
            let n = ((b - a) / step).round() as i64;
            let values: Vec<f64> = (0..=n)
                .map(|k| {
                    let v = a + k as f64 * step;
                    if v.abs() < step * 1e-9 { 0.0 } else { v }
                })
                .collect();
            let top = a.abs().max(b.abs());
            let scientific = top >= 1e5 || step < 1e-3;
            let list = if scientific {
                // one exponent for the axis: the largest value's
                let e = top.log10().floor() as i32;
                let digits = ((e as f64 - step.log10().floor()).max(0.0) as usize).min(8);
                values
                    .iter()
                    .map(|&v| {
                        let label = if v == 0.0 {
                            "0".to_string()
                        } else {
                            format!("{:.digits$}e{e}", v / 10f64.powi(e))
                        };
                        (v, label)
                    })
                    .collect()
            } else {
                let decimals = (-step.log10().floor()).max(0.0) as usize;
                values
                    .iter()
                    .map(|&v| (v, format!("{v:.decimals$}")))
                    .collect()
            };
            (a, b, list)
        }
    }
}

/// The range of `points` on the axis' own coordinate (`None` when no point is finite there).
fn range(points: &[(f64, f64)], xs: Scale, ys: Scale) -> Option<(f64, f64, f64, f64)> {
    let mut r: Option<(f64, f64, f64, f64)> = None;
    for (x, y) in points {
        let (Some(x), Some(y)) = (tf(*x, xs), tf(*y, ys)) else {
            continue;
        };
        r = Some(match r {
            None => (x, x, y, y),
            Some((a, b, c, d)) => (a.min(x), b.max(x), c.min(y), d.max(y)),
        });
    }
    r
}

/// A linear y axis on which some curve would vary over less than 2 % of the axis while it does
/// vary (flattened), or over more than a decade against a log x (a power law drawn as a
/// curve), turns logarithmic when every value is positive.
fn chosen_y_scale(p: &Panel, xs: Scale) -> Scale {
    if p.ys == Scale::Log {
        return Scale::Log;
    }
    let all: Vec<f64> = p
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|q| q.1))
        .filter(|y| y.is_finite())
        .collect();
    if all.is_empty() || all.iter().any(|y| *y <= 0.0) {
        return Scale::Linear;
    }
    let (lo, hi) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(*y), b.max(*y))
        });
    let flattened = p.series.iter().any(|s| {
        let (a, b) = s
            .points
            .iter()
            .map(|q| q.1)
            .filter(|y| y.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(y), b.max(y))
            });
        b > a && (b - a) < 0.02 * (hi - lo) && b < 0.1 * hi
    });
    if flattened || (xs == Scale::Log && hi > 10.0 * lo) {
        Scale::Log
    } else {
        Scale::Linear
    }
}

/// Pairs of curves that coincide at the figure's scale (every shared x within 2 px), with the
/// largest difference between them (absolute, and relative to the larger magnitude).
fn coinciding(p: &Panel, px_per_unit: f64, ys: Scale) -> Vec<(usize, usize, f64, f64)> {
    let mut out = Vec::new();
    for i in 0..p.series.len() {
        for j in i + 1..p.series.len() {
            let (a, b) = (&p.series[i].points, &p.series[j].points);
            if a.len() != b.len() || a.is_empty() {
                continue;
            }
            let mut close = true;
            let (mut abs, mut rel) = (0.0f64, 0.0f64);
            for ((xa, ya), (xb, yb)) in a.iter().zip(b) {
                if (xa - xb).abs() > 1e-12 * xa.abs().max(xb.abs()) {
                    close = false;
                    break;
                }
                let (Some(ta), Some(tb)) = (tf(*ya, ys), tf(*yb, ys)) else {
                    continue;
                };
                close &= (ta - tb).abs() * px_per_unit <= 2.0;
                abs = abs.max((ya - yb).abs());
                let m = ya.abs().max(yb.abs());
                if m > 0.0 {
                    rel = rel.max((ya - yb).abs() / m);
                }
            }
            if close {
                out.push((i, j, abs, rel));
            }
        }
    }
    out
}

/// Where a panel sits and its scales.
struct Frame {
    left: f64,
    top: f64,
    legend_top: f64,
    x: (f64, f64),
    xs: Scale,
    ys: Scale,
}

type Ticks = (f64, f64, Vec<(f64, String)>);

/// One panel of [`figure`]: its frame, ticks (the x ticks only under the last panel), y title,
/// curves and legend rows; the pairs of curves drawn dashed are said in `said`.
fn draw_panel(
    out: &mut String,
    p: &Panel,
    frame: &Frame,
    ticks: (&[(f64, String)], &Ticks),
    legend_row: &mut usize,
    said: &mut Vec<String>,
) {
    const PW: f64 = 486.0;
    const PH: f64 = 300.0;
    let xt = ticks.0;
    let ticks = ticks.1;
    let (left, ptop, ys) = (frame.left, frame.top, frame.ys);
    let ((x0, x1), (y0, y1, yt)) = (frame.x, ticks);
    let sx = |x: f64| left + (x - x0) / (x1 - x0) * PW;
    let sy = |y: f64| ptop + PH - (y - y0) / (y1 - y0) * PH;
    out.push_str(&format!(
        "<rect x=\"{left:.1}\" y=\"{ptop:.1}\" width=\"{PW}\" height=\"{PH}\" fill=\"none\" stroke=\"black\"/>\n"
    ));
    {
        for (v, label) in xt {
            let x = sx(*v);
            out.push_str(&format!(
                "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"black\"/>\n<text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n",
                ptop + PH,
                ptop + PH + 5.0,
                ptop + PH + 18.0,
                escape(label)
            ));
        }
    }
    for (v, label) in yt {
        let y = sy(*v);
        out.push_str(&format!(
            "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{left:.1}\" y2=\"{y:.1}\" stroke=\"black\"/>\n<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            left - 5.0,
            left - 8.0,
            y + 4.0,
            escape(label)
        ));
    }
    let ylabel = if ys == Scale::Log && p.ys == Scale::Linear {
        format!("{} (log scale)", p.ylabel)
    } else {
        p.ylabel.to_string()
    };
    let ylines = wrap(&ylabel, 12.0, PH - 10.0);
    for (i, line) in ylines.iter().enumerate() {
        // a baseline per line, 16 px apart: glyphs reach 12 px left of it and 4 px right
        let x = 16.0 + 16.0 * i as f64;
        out.push_str(&format!(
            "<text x=\"{x:.1}\" y=\"{:.1}\" transform=\"rotate(-90 {x:.1} {:.1})\" text-anchor=\"middle\">{}</text>\n",
            ptop + PH / 2.0,
            ptop + PH / 2.0,
            escape(line)
        ));
    }
    let pairs = coinciding(p, PH / (y1 - y0), ys);
    for (i, s) in p.series.iter().enumerate() {
        let c = COLORS[*legend_row % COLORS.len()];
        let drawn: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter_map(|(x, y)| Some((sx(tf(*x, frame.xs)?), sy(tf(*y, ys)?))))
            .collect();
        let d: Vec<String> = drawn
            .iter()
            .map(|(x, y)| format!("{x:.1},{y:.1}"))
            .collect();
        let over = pairs.iter().any(|q| q.1 == i);
        let dash = if over {
            " stroke-dasharray=\"7 5\""
        } else {
            ""
        };
        out.push_str(&format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"2\"{dash}/>\n",
            d.join(" ")
        ));
        if over {
            let every = (drawn.len() / 16).max(1);
            for (x, y) in drawn.iter().step_by(every) {
                out.push_str(&format!(
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.5\"/>\n"
                ));
            }
        }
        let ly = frame.legend_top + 8.0 + 20.0 * *legend_row as f64;
        out.push_str(&format!(
            "<line x1=\"{:.1}\" y1=\"{ly:.1}\" x2=\"{:.1}\" y2=\"{ly:.1}\" stroke=\"{c}\" stroke-width=\"3\"{dash}/>\n<text x=\"{:.1}\" y=\"{:.1}\">{}</text>\n",
            left + PW + 12.0,
            left + PW + 36.0,
            left + PW + 42.0,
            ly + 4.0,
            escape(s.name)
        ));
        *legend_row += 1;
    }
    for (i, j, abs, rel) in pairs {
        said.push(format!(
            "`{}` (dashed, circles) lies on `{}` at this scale: they differ by at most {} ({} relative).",
            p.series[j].name,
            p.series[i].name,
            short_number(abs),
            short_number(rel)
        ));
    }
}

/// The SVG of `f`: see the module doc.
pub fn figure(f: &Figure) -> String {
    const PW: f64 = 486.0;
    const PH: f64 = 300.0;
    let title_lines = wrap(f.title, 14.0, 760.0);
    let legend_w = f
        .panels
        .iter()
        .flat_map(|p| p.series.iter().map(|s| text_width(s.name, 12.0)))
        .fold(0.0, f64::max)
        + 46.0;
    let layouts: Vec<_> = f
        .panels
        .iter()
        .map(|p| {
            let ys = chosen_y_scale(p, f.xs);
            let pts: Vec<(f64, f64)> = p.series.iter().flat_map(|s| s.points.clone()).collect();
            (ys, range(&pts, f.xs, ys))
        })
        .collect();
    // one x range for every panel
    let (mut x0, mut x1) = layouts
        .iter()
        .filter_map(|(_, r)| r.map(|r| (r.0, r.1)))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, d)| {
            (a.min(c), b.max(d))
        });
    if !x0.is_finite() {
        (x0, x1) = (0.0, 1.0);
    }
    if x1 - x0 <= 1e-12 * x0.abs().max(1e-300) {
        let d = if x0 == 0.0 { 1.0 } else { 0.1 * x0.abs() };
        (x0, x1) = (x0 - d, x1 + d);
    }
    let (x0, x1, xt) = ticks(x0, x1, f.xs);
    let yticks: Vec<_> = layouts
        .iter()
        .map(|(ys, r)| {
            let (mut y0, mut y1) = r.map_or((0.0, 1.0), |r| (r.2, r.3));
            if y1 - y0 <= 1e-12 * y0.abs().max(1e-300) {
                let d = if y0 == 0.0 { 1.0 } else { 0.1 * y0.abs() };
                (y0, y1) = (y0 - d, y1 + d);
            }
            ticks(y0, y1, *ys)
        })
        .collect();
    let label_w = yticks
        .iter()
        .flat_map(|t| t.2.iter().map(|(_, l)| text_width(l, 12.0)))
        .fold(0.0, f64::max);
    // room for the tick labels and the y titles' lines (16 px each)
    let title_lines_y = f
        .panels
        .iter()
        .map(|p| wrap(&format!("{} (log scale)", p.ylabel), 12.0, PH - 10.0).len())
        .max()
        .unwrap_or(1) as f64;
    let left = (label_w + 18.0 + 16.0 * title_lines_y).max(60.0);
    let top = 16.0 + 18.0 * title_lines.len() as f64;
    let w = (left + PW + legend_w + 12.0).max(text_width(&title_lines[0], 14.0) + 20.0);
    let panel_gap = 24.0;
    let panels_h = f.panels.len().max(1) as f64 * (PH + panel_gap) - panel_gap;
    let caption: Vec<String> = f
        .caption
        .iter()
        .flat_map(|c| wrap(c, 11.0, w - 20.0))
        .collect();
    let h = top + panels_h + 48.0 + 15.0 * caption.len() as f64 + 8.0;
    let mut out = opening(w, h, &title_lines);
    let mut dashes_said = Vec::new();
    let mut legend_row = 0;
    for (k, (p, yt)) in f.panels.iter().zip(&yticks).enumerate() {
        let frame = Frame {
            left,
            top: top + k as f64 * (PH + panel_gap),
            legend_top: top,
            x: (x0, x1),
            xs: f.xs,
            ys: layouts[k].0,
        };
        let xt = if k + 1 == f.panels.len() {
            &xt[..]
        } else {
            &[]
        };
        draw_panel(
            &mut out,
            p,
            &frame,
            (xt, yt),
            &mut legend_row,
            &mut dashes_said,
        );
    }
    let last_bottom = top + panels_h;
    let xlabel = if f.xs == Scale::Log {
        format!("{} (log scale)", f.xlabel)
    } else {
        f.xlabel.to_string()
    };
    out.push_str(&format!(
        "<text class=\"xlabel\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n",
        left + PW / 2.0,
        last_bottom + 38.0,
        escape(&xlabel)
    ));
    let said: Vec<String> = dashes_said
        .iter()
        .flat_map(|c| wrap(c, 11.0, w - 20.0))
        .collect();
    for (k, line) in caption.iter().chain(&said).enumerate() {
        out.push_str(&format!(
            "<text x=\"10\" y=\"{:.1}\" font-size=\"11\" fill=\"#333333\">{}</text>\n",
            last_bottom + 60.0 + 15.0 * k as f64,
            escape(line)
        ));
    }
    // the canvas holds the caption lines added for coinciding curves
    let h2 = h + 15.0 * said.len() as f64;
    out = out.replacen(
        &format!("height=\"{h:.0}\" font-family"),
        &format!("height=\"{h2:.0}\" font-family"),
        1,
    );
    out = out.replacen(
        &format!("<rect width=\"{w:.0}\" height=\"{h:.0}\""),
        &format!("<rect width=\"{w:.0}\" height=\"{h2:.0}\""),
        1,
    );
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_names_its_axes_with_their_units_and_says_its_caption() {
        let svg = figure(&Figure {
            title: "the indentation against time",
            xlabel: "t (s)",
            xs: Scale::Linear,
            panels: vec![Panel {
                ylabel: "z (m)",
                ys: Scale::Linear,
                series: vec![Series {
                    name: "z",
                    points: vec![(0.0, 0.0), (1.0, 2.0), (2.0, 1.0)],
                }],
            }],
            caption: vec!["Claim t.a: the caption.".into()],
        });
        assert!(svg.starts_with("<svg"), "{svg}");
        // the x axis title is marked for tests/figures.rs, which requires its unit
        assert!(svg.contains("<text class=\"xlabel\""), "{svg}");
        assert!(svg.contains(">t (s)</text>"), "{svg}");
        assert!(svg.contains(">z (m)</text>"), "{svg}");
        assert!(svg.contains("Claim t.a: the caption."), "{svg}");
        let log = figure(&Figure {
            xs: Scale::Log,
            xlabel: "t (s)",
            title: "t",
            panels: vec![],
            caption: vec![],
        });
        assert!(log.contains(">t (s) (log scale)</text>"), "{log}");
    }
}
