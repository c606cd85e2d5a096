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

const COLORS: [&str; 8] = [
    "#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666",
];

fn tf(v: f64, s: Scale) -> Option<f64> {
    match s {
        Scale::Linear => v.is_finite().then_some(v),
        Scale::Log => (v > 0.0 && v.is_finite()).then(|| v.log10()),
    }
}

fn tick_label(v: f64, s: Scale) -> String {
    match s {
        Scale::Log => format!("1e{}", v.round() as i64),
        Scale::Linear => format!("{v:.3e}"),
    }
}

/// Renders a plot with one or more series sharing axes.
pub fn plot(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xs: Scale,
    ys: Scale,
    series: &[Series],
) -> String {
    let (w, h, pad) = (720.0, 440.0, 70.0);
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
    if x1 - x0 <= f64::EPSILON * x0.abs().max(1.0) {
        x1 = x0 + 1.0;
    }
    if y1 - y0 <= f64::EPSILON * y0.abs().max(1.0) {
        y1 = y0 + 1.0;
    }
    let sx = |x: f64| pad + (x - x0) / (x1 - x0) * (w - 2.0 * pad);
    let sy = |y: f64| h - pad - (y - y0) / (y1 - y0) * (h - 2.0 * pad);
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n<text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
        w / 2.0,
        escape(title)
    );
    out.push_str(&format!(
        "<line x1=\"{pad}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>\n<line x1=\"{pad}\" y1=\"{pad}\" x2=\"{pad}\" y2=\"{}\" stroke=\"black\"/>\n",
        h - pad,
        w - pad,
        h - pad,
        h - pad
    ));
    for i in 0..=4 {
        let fx = x0 + (x1 - x0) * i as f64 / 4.0;
        let fy = y0 + (y1 - y0) * i as f64 / 4.0;
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            sx(fx),
            h - pad + 16.0,
            tick_label(fx, xs),
            pad - 6.0,
            sy(fy) + 4.0,
            tick_label(fy, ys)
        ));
    }
    out.push_str(&format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{}</text>\n",
        w / 2.0,
        h - 20.0,
        escape(xlabel),
        h / 2.0,
        h / 2.0,
        escape(ylabel)
    ));
    for (i, s) in series.iter().enumerate() {
        let c = COLORS[i % COLORS.len()];
        let d: Vec<String> = s
            .points
            .iter()
            .filter_map(|(x, y)| Some(format!("{:.1},{:.1}", sx(tf(*x, xs)?), sy(tf(*y, ys)?))))
            .collect();
        out.push_str(&format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"2\"/>\n<text x=\"{}\" y=\"{}\" fill=\"{c}\">{}</text>\n",
            d.join(" "),
            w - pad - 200.0,
            pad + 16.0 * i as f64,
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

/// [`plot`] for curves held as `(name, points)` pairs.
pub fn plot_curves(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xs: Scale,
    ys: Scale,
    curves: &[(String, Vec<(f64, f64)>)],
) -> String {
    let series: Vec<Series> = curves
        .iter()
        .map(|(n, p)| Series {
            name: n,
            points: p.clone(),
        })
        .collect();
    plot(title, xlabel, ylabel, xs, ys, &series)
}
