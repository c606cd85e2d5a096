//! A small SVG line-plot writer for reports and `--plot` (no physics here).
//!
//! Written by hand: plotters would add a dependency tree and compile time for what is a few
//! polylines with axes and a legend.

use super::plot::escape;
pub use super::plot::{Scale, Series, short_number};

/// Renders a plot with one or more series sharing axes, laid out by [`super::plot::figure`]:
/// 1-2-5 ticks (decades on a log axis) in one format per axis, axis titles clear of the tick
/// labels, the legend in a column to the right of the plot area, outside the data.
pub fn plot(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    xs: Scale,
    ys: Scale,
    series: &[Series],
) -> String {
    super::plot::figure(&super::plot::Figure {
        title,
        xlabel,
        xs,
        panels: vec![super::plot::Panel {
            ylabel,
            ys,
            series: series.to_vec(),
        }],
        caption: Vec::new(),
    })
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
    use super::plot::{uniform_labels, wrap};
    let (w, left, right, bottom) = (760.0, 80.0, 190.0, 70.0);
    let title_lines = wrap(title, 14.0, w - 20.0);
    let top = 22.0 + 18.0 * title_lines.len() as f64;
    let h = top + 350.0 + bottom;
    let (pw, ph) = (w - left - right, h - top - bottom);
    let (nx, ny) = (xs.len().max(1), ys.len().max(1));
    let (cw, ch) = (pw / nx as f64, ph / ny as f64);
    let mut out = super::plot::opening(w, h, &title_lines);
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
    let xi = picks(xs.len());
    let xl = uniform_labels(&xi.iter().map(|&i| xs[i]).collect::<Vec<_>>());
    for (i, label) in xi.iter().zip(&xl) {
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n",
            left + (*i as f64 + 0.5) * cw,
            top + ph + 16.0,
            label
        ));
    }
    let yi = picks(ys.len());
    let yl = uniform_labels(&yi.iter().map(|&j| ys[j]).collect::<Vec<_>>());
    for (j, label) in yi.iter().zip(&yl) {
        out.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>\n",
            left - 6.0,
            top + (ny - 1 - j) as f64 * ch + ch / 2.0 + 4.0,
            label
        ));
    }
    let scale = |log: bool| if log { " (log scale)" } else { "" };
    out.push_str(&format!(
        "<text class=\"xlabel\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}{}</text>\n<text x=\"18\" y=\"{:.1}\" transform=\"rotate(-90 18 {:.1})\" text-anchor=\"middle\">{}{}</text>\n",
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
