//! A small SVG line-plot writer for reports and `--plot` (no physics here).
//!
//! Written by hand: plotters would add a dependency tree and compile time for what is a few
//! polylines with axes and a legend.

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

/// The Okabe-Ito palette (safe for the common colour-vision deficiencies), yellow last.
const COLORS: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];

fn tf(v: f64, s: Scale) -> Option<f64> {
    match s {
        Scale::Linear => v.is_finite().then_some(v),
        Scale::Log => (v > 0.0 && v.is_finite()).then(|| v.log10()),
    }
}

/// Ticks over `[lo, hi]` (in the axis' own coordinate: log10 for a log axis) and the range they
/// span: 1-2-5 steps on a linear axis, whole decades on a log axis; each with its label.
fn ticks(lo: f64, hi: f64, scale: Scale) -> (f64, f64, Vec<(f64, String)>) {
    match scale {
        Scale::Log => {
            let (a, b) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
            let n = (b - a) as i64;
            let every = (n / 6 + 1).max(1);
            let list = (0..=n)
                .filter(|k| k % every == 0)
                .map(|k| {
                    let e = a as i64 + k;
                    (e as f64, short_number(10f64.powi(e as i32)))
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
            let decimals = (-step.log10().floor()).max(0.0) as usize;
            let n = ((b - a) / step).round() as i64;
            let list = (0..=n)
                .map(|k| {
                    let v = a + k as f64 * step;
                    let v = if v.abs() < step * 1e-9 { 0.0 } else { v };
                    let label = if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
                        short_number(v)
                    } else {
                        format!("{v:.decimals$}")
                    };
                    (v, label)
                })
                .collect();
            (a, b, list)
        }
    }
}

/// Renders a plot with one or more series sharing axes: 1-2-5 ticks (decades on a log axis)
/// with the shortest labels, axis titles clear of the tick labels, and the legend in a column to
/// the right of the plot area, outside the data.
pub fn plot(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xs: Scale,
    ys: Scale,
    series: &[Series],
) -> String {
    let (w, h) = (800.0, 460.0);
    let (left, right, top, bottom) = (84.0, 230.0, 44.0, 64.0);
    let (pw, ph) = (w - left - right, h - top - bottom);
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| {
            s.points
                .iter()
                .filter_map(|(x, y)| Some((tf(*x, xs)?, tf(*y, ys)?)))
        })
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in &pts {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    if pts.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 <= 1e-12 * x0.abs().max(1e-300) {
        let d = if x0 == 0.0 { 1.0 } else { 0.1 * x0.abs() };
        (x0, x1) = (x0 - d, x1 + d);
    }
    if y1 - y0 <= 1e-12 * y0.abs().max(1e-300) {
        let d = if y0 == 0.0 { 1.0 } else { 0.1 * y0.abs() };
        (y0, y1) = (y0 - d, y1 + d);
    }
    let (x0, x1, xt) = ticks(x0, x1, xs);
    let (y0, y1, yt) = ticks(y0, y1, ys);
    let sx = |x: f64| left + (x - x0) / (x1 - x0) * pw;
    let sy = |y: f64| top + ph - (y - y0) / (y1 - y0) * ph;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n<text x=\"{:.1}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
        left + pw / 2.0,
        escape(title)
    );
    out.push_str(&format!(
        "<rect x=\"{left}\" y=\"{top}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"black\"/>\n"
    ));
    for (v, label) in &xt {
        let x = sx(*v);
        out.push_str(&format!(
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"black\"/>\n<text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n",
            top + ph,
            top + ph + 5.0,
            top + ph + 18.0,
            escape(label)
        ));
    }
    for (v, label) in &yt {
        let y = sy(*v);
        out.push_str(&format!(
            "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{left}\" y2=\"{y:.1}\" stroke=\"black\"/>\n<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            left - 5.0,
            left - 8.0,
            y + 4.0,
            escape(label)
        ));
    }
    out.push_str(&format!(
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n<text x=\"16\" y=\"{:.1}\" transform=\"rotate(-90 16 {:.1})\" text-anchor=\"middle\">{}</text>\n",
        left + pw / 2.0,
        h - 18.0,
        escape(xlabel),
        top + ph / 2.0,
        top + ph / 2.0,
        escape(ylabel)
    ));
    for (i, s) in series.iter().enumerate() {
        let c = COLORS[i % COLORS.len()];
        let d: Vec<String> = s
            .points
            .iter()
            .filter_map(|(x, y)| Some(format!("{:.1},{:.1}", sx(tf(*x, xs)?), sy(tf(*y, ys)?))))
            .collect();
        let ly = top + 8.0 + 20.0 * i as f64;
        out.push_str(&format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"2\"/>\n<line x1=\"{:.1}\" y1=\"{ly:.1}\" x2=\"{:.1}\" y2=\"{ly:.1}\" stroke=\"{c}\" stroke-width=\"3\"/>\n<text x=\"{:.1}\" y=\"{:.1}\">{}</text>\n",
            d.join(" "),
            left + pw + 14.0,
            left + pw + 34.0,
            left + pw + 40.0,
            ly + 4.0,
            escape(s.name)
        ));
    }
    out.push_str("</svg>\n");
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A scatter plot: one marker per point, one colour per series (for classification maps).
pub fn scatter(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    scatter_with_lines(title, xlabel, ylabel, &[], series)
}

/// Linear axes with `lines` drawn as polylines and `markers` as circles at their points.
pub fn scatter_with_lines(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    lines: &[Series],
    markers: &[Series],
) -> String {
    let all: Vec<Series> = lines.iter().chain(markers).cloned().collect();
    let drawn = plot(title, xlabel, ylabel, Scale::Linear, Scale::Linear, &all);
    // re-draw the polylines of the marker series (those after the lines) as circles
    let mut out = String::new();
    let mut polyline = 0;
    for line in drawn.lines() {
        if let Some(rest) = line.strip_prefix("<polyline points=\"") {
            polyline += 1;
            if polyline <= lines.len() {
                out.push_str(line);
                out.push('\n');
                continue;
            }
            let pts = rest.split('"').next().unwrap_or("");
            let color = line
                .split("stroke=\"")
                .nth(1)
                .and_then(|s| s.split('"').next())
                .unwrap_or("black");
            for p in pts.split_whitespace() {
                if let Some((x, y)) = p.split_once(',') {
                    out.push_str(&format!(
                        "<circle cx=\"{x}\" cy=\"{y}\" r=\"3\" fill=\"{color}\"/>\n"
                    ));
                }
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Curves held as `(name, points)` pairs, as [`Series`].
fn as_series(curves: &[(String, Vec<(f64, f64)>)]) -> Vec<Series<'_>> {
    curves
        .iter()
        .map(|(n, p)| Series {
            name: n,
            points: p.clone(),
        })
        .collect()
}

/// [`plot`] for curves held as `(name, points)` pairs.
pub fn plot_curves(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xs: Scale,
    ys: Scale,
    curves: &[(String, Vec<(f64, f64)>)],
) -> String {
    plot(title, xlabel, ylabel, xs, ys, &as_series(curves))
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

/// One axis of a region map: its label, grid values and whether the grid is logarithmic.
pub struct MapAxis<'a> {
    /// The axis title (with units).
    pub label: &'a str,
    /// The grid values.
    pub values: &'a [f64],
    /// Whether the values are spaced logarithmically.
    pub log: bool,
}

/// A region map: the grid `xs` x `ys` (cells in row-major order, `y` slowest), each cell inside
/// the region (`Some(true)`), outside it (`Some(false)`) or not computed (`None`); the legend sits
/// to the right of the plot, outside the data. Colours from the Okabe-Ito palette.
pub fn region_map(title: &str, x: &MapAxis, y: &MapAxis, cells: &[Option<bool>]) -> String {
    let (xlabel, xs, x_log) = (x.label, x.values, x.log);
    let (ylabel, ys, y_log) = (y.label, y.values, y.log);
    let (w, h, left, right, top, bottom) = (760.0, 460.0, 80.0, 190.0, 40.0, 70.0);
    let (pw, ph) = (w - left - right, h - top - bottom);
    let (nx, ny) = (xs.len().max(1), ys.len().max(1));
    let (cw, ch) = (pw / nx as f64, ph / ny as f64);
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
        left + pw / 2.0,
        escape(title)
    );
    for j in 0..ny {
        for i in 0..nx {
            let fill = match cells.get(j * nx + i).copied().flatten() {
                Some(true) => "#0072B2",
                Some(false) => "#E69F00",
                None => "#999999",
            };
            out.push_str(&format!(
                "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"{fill}\" stroke=\"white\" stroke-width=\"0.5\"/>\n",
                left + i as f64 * cw,
                top + (ny - 1 - j) as f64 * ch,
                cw,
                ch
            ));
        }
    }
    // ticks at up to 5 grid values per axis, at cell centres
    let picks = |n: usize| -> Vec<usize> {
        if n <= 5 {
            (0..n).collect()
        } else {
            (0..5).map(|k| k * (n - 1) / 4).collect()
        }
    };
    for i in picks(xs.len()) {
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n",
            left + (i as f64 + 0.5) * cw,
            top + ph + 16.0,
            short_number(xs[i])
        ));
    }
    for j in picks(ys.len()) {
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            left - 6.0,
            top + (ny - 1 - j) as f64 * ch + ch / 2.0 + 4.0,
            short_number(ys[j])
        ));
    }
    let scale = |log: bool| if log { " (log grid)" } else { "" };
    out.push_str(&format!(
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}{}</text>\n<text x=\"18\" y=\"{:.1}\" transform=\"rotate(-90 18 {:.1})\" text-anchor=\"middle\">{}{}</text>\n",
        left + pw / 2.0,
        h - 24.0,
        escape(xlabel),
        scale(x_log),
        top + ph / 2.0,
        top + ph / 2.0,
        escape(ylabel),
        scale(y_log)
    ));
    for (k, (fill, name)) in [
        ("#0072B2", "holds"),
        ("#E69F00", "fails"),
        ("#999999", "did not run"),
    ]
    .iter()
    .enumerate()
    {
        let y = top + 10.0 + 22.0 * k as f64;
        out.push_str(&format!(
            "<rect x=\"{:.1}\" y=\"{y:.1}\" width=\"14\" height=\"14\" fill=\"{fill}\"/>\n<text x=\"{:.1}\" y=\"{:.1}\">{name}</text>\n",
            left + pw + 20.0,
            left + pw + 40.0,
            y + 12.0
        ));
    }
    out.push_str("</svg>\n");
    out
}

/// The data of a figure as CSV in long form: one row per point, `series,x,y`, with the axis
/// titles in the header (so a reader can redraw or check any figure).
pub fn csv(xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    let q = |t: &str| format!("\"{}\"", t.replace('"', "\"\""));
    let mut out = format!("series,{},{}\n", q(xlabel), q(ylabel));
    for s in series {
        for (x, y) in &s.points {
            out.push_str(&format!("{},{x:e},{y:e}\n", q(s.name)));
        }
    }
    out
}

/// [`csv`] for curves held as `(name, points)` pairs.
pub fn csv_curves(xlabel: &str, ylabel: &str, curves: &[(String, Vec<(f64, f64)>)]) -> String {
    csv(xlabel, ylabel, &as_series(curves))
}
