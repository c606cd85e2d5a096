//! Every figure `verify` writes reads alone (issue 54), checked on the figure as a renderer
//! lays it out: each SVG is parsed and its text shaped by usvg (resvg's front half) with the
//! machine's own fonts (DejaVu Sans for `sans-serif`), and every text box is the one the glyphs
//! fill. A figure fails where any text leaves the canvas, two texts overlap, a text covers a
//! data point (a vertex of a curve, a marker), a title names a claim by its id, an error axis
//! does not say relative or absolute, an axis' tick labels mix plain and exponent forms, or two
//! curves lie on each other with neither drawn dashed. The figures of an older writer whose
//! title and legend ran off the canvas are kept as planted SVGs (tests/data/figures/) and must
//! fail.

use std::path::Path;
use std::process::Command;

#[derive(Debug, Clone)]
struct TextBox {
    text: String,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// Turned a quarter (an axis title along y).
    turned: bool,
}

fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    let j = tag[i..].find('"')? + i;
    Some(tag[i..j].to_string())
}

fn num(tag: &str, name: &str) -> Option<f64> {
    attr(tag, name)?.parse().ok()
}

/// The renderer's options: the system's fonts, DejaVu Sans as `sans-serif`.
fn options() -> usvg::Options<'static> {
    let mut opt = usvg::Options::default();
    let db = opt.fontdb_mut();
    db.load_system_fonts();
    db.set_sans_serif_family("DejaVu Sans");
    assert!(
        db.faces()
            .any(|f| f.families.iter().any(|(n, _)| n == "DejaVu Sans")),
        "the figure test needs DejaVu Sans (fonts-dejavu-core) among the system's fonts"
    );
    opt
}

fn texts_of(g: &usvg::Group, out: &mut Vec<TextBox>) {
    for node in g.children() {
        match node {
            usvg::Node::Group(g) => texts_of(g, out),
            usvg::Node::Text(t) => {
                let r = t.abs_bounding_box();
                let text: String = t.chunks().iter().map(|c| c.text()).collect();
                let turned = t.abs_transform().kx.abs() > 0.5 || t.abs_transform().ky.abs() > 0.5;
                out.push(TextBox {
                    text,
                    x0: r.left() as f64,
                    x1: r.right() as f64,
                    y0: r.top() as f64,
                    y1: r.bottom() as f64,
                    turned,
                });
            }
            _ => {}
        }
    }
}

/// A figure as laid out: its canvas, its text boxes (from the renderer), its data points and its
/// curves (vertices of polylines, with whether each is dashed; from the source).
struct Laid {
    size: (f64, f64),
    boxes: Vec<TextBox>,
    points: Vec<(f64, f64)>,
    curves: Vec<(Vec<(f64, f64)>, bool)>,
}

fn lay_out(svg: &str, opt: &usvg::Options) -> Laid {
    let tree = usvg::Tree::from_str(svg, opt).expect("the SVG parses");
    let mut boxes = Vec::new();
    texts_of(tree.root(), &mut boxes);
    let mut points = Vec::new();
    let mut curves = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        rest = &rest[i..];
        let end = rest.find('>').unwrap_or(rest.len() - 1);
        let tag = &rest[..=end];
        if tag.starts_with("<polyline") {
            let mut curve = Vec::new();
            for p in attr(tag, "points").unwrap_or_default().split_whitespace() {
                if let Some((a, b)) = p.split_once(',')
                    && let (Ok(a), Ok(b)) = (a.parse(), b.parse())
                {
                    curve.push((a, b));
                }
            }
            points.extend(curve.iter().copied());
            curves.push((curve, attr(tag, "stroke-dasharray").is_some()));
        } else if tag.starts_with("<circle")
            && let (Some(a), Some(b)) = (num(tag, "cx"), num(tag, "cy"))
        {
            points.push((a, b));
        }
        rest = &rest[end + 1..];
    }
    let size = tree.size();
    Laid {
        size: (size.width() as f64, size.height() as f64),
        boxes,
        points,
        curves,
    }
}

fn overlap(a: &TextBox, b: &TextBox) -> bool {
    let eps = 0.5;
    a.x0 + eps < b.x1 && b.x0 + eps < a.x1 && a.y0 + eps < b.y1 && b.y0 + eps < a.y1
}

fn is_number(t: &str) -> bool {
    t.trim().parse::<f64>().is_ok()
}

/// What is wrong with one laid-out figure; `ids` are the claim ids no title may show.
/// Whether an axis title gives a unit: `dimensionless`, or a parenthesised unit the library's
/// unit parser reads (a bare number is no unit), or degrees.
fn has_unit(title: &str) -> bool {
    if title.contains("dimensionless") {
        return true;
    }
    let mut rest = title;
    while let Some(i) = rest.find('(') {
        let Some(j) = rest[i..].find(')') else { break };
        // `(s, log)`: the unit, then what else the parentheses say of the axis
        let inside = rest[i + 1..i + j]
            .split(',')
            .next()
            .unwrap_or_default()
            .trim();
        let number = inside.parse::<f64>().is_ok();
        if inside == "degrees"
            || (!number
                && !inside.is_empty()
                && impactcheck::algebra::units::Unit::parse(inside).is_ok())
        {
            return true;
        }
        rest = &rest[i + j + 1..];
    }
    false
}

/// The x axis titles of a figure as written (the writers mark them `class="xlabel"`).
fn x_titles(svg: &str) -> Vec<String> {
    svg.split("<text class=\"xlabel\"")
        .skip(1)
        .filter_map(|rest| {
            let (_, after) = rest.split_once('>')?;
            let (text, _) = after.split_once("</text>")?;
            Some(
                text.replace("&lt;", "<")
                    .replace("&gt;", ">")
                    .replace("&amp;", "&"),
            )
        })
        .collect()
}

/// What is wrong with the x axes of one figure: none marked, or one without a unit.
fn x_problems(name: &str, svg: &str) -> Vec<String> {
    let titles = x_titles(svg);
    if titles.is_empty() {
        return vec![format!("{name}: no x axis title (class=\"xlabel\")")];
    }
    titles
        .iter()
        .filter(|t| !has_unit(t))
        .map(|t| format!("{name}: the x axis `{t}` has no unit"))
        .collect()
}

fn problems_of(name: &str, f: &Laid, ids: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    let (w, h) = f.size;
    for (i, a) in f.boxes.iter().enumerate() {
        if a.x0 < -0.5 || a.y0 < -0.5 || a.x1 > w + 0.5 || a.y1 > h + 0.5 {
            out.push(format!(
                "{name}: `{}` leaves the canvas ({:.0}..{:.0} x {:.0}..{:.0} on {w:.0} x {h:.0})",
                a.text, a.x0, a.x1, a.y0, a.y1
            ));
        }
        for b in &f.boxes[i + 1..] {
            if overlap(a, b) {
                out.push(format!("{name}: `{}` overlaps `{}`", a.text, b.text));
            }
        }
        if let Some(p) = f
            .points
            .iter()
            .find(|(x, y)| *x > a.x0 && *x < a.x1 && *y > a.y0 && *y < a.y1)
        {
            out.push(format!("{name}: `{}` covers the data point {p:?}", a.text));
        }
        let lower = a.text.to_lowercase();
        if lower.contains("error") && !a.turned && !is_number(&a.text) {
            // an axis title is a text of its own; captions say it in their sentence
        }
        if a.turned
            && lower.contains("error")
            && !lower.contains("relative")
            && !lower.contains("absolute")
        {
            out.push(format!(
                "{name}: the error axis `{}` says neither relative nor absolute",
                a.text
            ));
        }
    }
    // the y axis says its quantity's unit (issue 67): its title, wrapped over lines, holds
    // `dimensionless` or a unit in parentheses that the unit parser reads (`(m s^-1)`), or
    // degrees
    let turned: Vec<&str> = f
        .boxes
        .iter()
        .filter(|b| b.turned)
        .map(|b| b.text.as_str())
        .collect();
    if !turned.is_empty() && !has_unit(&turned.join(" ")) {
        out.push(format!(
            "{name}: the y axis `{}` has no unit",
            turned.join(" ")
        ));
    }
    // the title: the topmost texts, above the first plot frame's top
    if let Some(first) = f.boxes.first() {
        for id in ids {
            if first.text.contains(id.as_str()) {
                out.push(format!(
                    "{name}: the title names the claim by its id `{id}`: `{}`",
                    first.text
                ));
            }
        }
    }
    // tick labels of one axis: numbers on one line (x) or ending at one x (y), all in one form
    let numbers: Vec<&TextBox> = f.boxes.iter().filter(|b| is_number(&b.text)).collect();
    let mut groups: Vec<Vec<&TextBox>> = Vec::new();
    for b in &numbers {
        match groups.iter_mut().find(|g| {
            (g[0].y1 - b.y1).abs() < 1.0 || (g[0].x1 - b.x1).abs() < 1.0 && g[0].y1 != b.y1
        }) {
            Some(g) => g.push(b),
            None => groups.push(vec![b]),
        }
    }
    for g in groups.iter().filter(|g| g.len() >= 3) {
        // a zero is written `0` in either form
        let g: Vec<&&TextBox> = g.iter().filter(|b| b.text.trim() != "0").collect();
        let exp = g.iter().filter(|b| b.text.contains('e')).count();
        if exp != 0 && exp != g.len() {
            let labels: Vec<&str> = g.iter().map(|b| b.text.as_str()).collect();
            out.push(format!(
                "{name}: one axis mixes plain and exponent labels: {labels:?}"
            ));
        }
    }
    // curves on each other: both must show (one dashed)
    for (i, (a, da)) in f.curves.iter().enumerate() {
        for (b, db) in &f.curves[i + 1..] {
            let on = a.len() == b.len()
                && a.len() > 1
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| (p.0 - q.0).abs() < 0.2 && (p.1 - q.1).abs() <= 2.0);
            if on && !da && !db {
                out.push(format!(
                    "{name}: two curves of {} points lie on each other, neither dashed",
                    a.len()
                ));
            }
        }
    }
    out
}

#[test]
fn no_figure_has_overlapping_text_or_text_over_data() {
    let out = std::env::temp_dir().join(format!("impactcheck-figures-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["--timing", "--repeats", "1", "--out"])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("verify runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary"))
            .expect("json");
    let ids: Vec<String> = summary["claims"]
        .as_array()
        .expect("claims")
        .iter()
        .filter_map(|c| c["id"].as_str().map(str::to_string))
        .collect();
    let opt = options();
    let mut problems = Vec::new();
    let mut figures = 0;
    let mut svgs: Vec<std::path::PathBuf> = Vec::new();
    for dir in [out.clone(), out.join("timing")] {
        for entry in std::fs::read_dir(&dir).expect("out dir") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "svg") {
                svgs.push(path);
            }
        }
    }
    for path in &svgs {
        figures += 1;
        let svg = std::fs::read_to_string(path).expect("svg");
        let name = Path::new(path)
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        problems.extend(problems_of(&name, &lay_out(&svg, &opt), &ids));
    }
    let _ = std::fs::remove_dir_all(&out);
    assert!(figures >= 10, "only {figures} figures");
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn the_check_sees_overlaps_covered_points_and_a_canvas_left() {
    // a legend entry drawn inside the data, a tick label on top of another, a title off the
    // canvas, an id in the title and two curves on each other: each must be seen
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" font-family="sans-serif" font-size="12">
<text x="-20" y="12">000.eq1 a title too long for its canvas</text>
<polyline points="10,50 60,48 110,52" fill="none" stroke="black"/>
<polyline points="10,51 60,49 110,53" fill="none" stroke="red"/>
<text x="40" y="52">legend</text>
<text x="150" y="90" text-anchor="middle">0.25</text>
<text x="160" y="90" text-anchor="middle">0.5</text>
<text x="16" y="50" transform="rotate(-90 16 50)" text-anchor="middle">error</text>
</svg>"#;
    let f = lay_out(svg, &options());
    assert_eq!(f.boxes.len(), 5);
    assert!(f.boxes[4].turned && !f.boxes[0].turned);
    let p = problems_of("t", &f, &["000.eq1".to_string()]);
    let has = |what: &str| p.iter().any(|x| x.contains(what));
    assert!(
        has("`000.eq1 a title too long for its canvas` leaves the canvas"),
        "{p:?}"
    );
    assert!(
        has("the title names the claim by its id `000.eq1`"),
        "{p:?}"
    );
    assert!(has("`0.25` overlaps `0.5`"), "{p:?}");
    assert!(has("`legend` covers the data point"), "{p:?}");
    assert!(has("says neither relative nor absolute"), "{p:?}");
    assert!(has("lie on each other, neither dashed"), "{p:?}");
}

#[test]
fn every_committed_figure_has_axes_with_units_and_a_bare_quantity_fails() {
    // every SVG of reports/ (the benchmarks' figures too), laid out as a renderer does
    let opt = options();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("reports");
    let mut problems = Vec::new();
    let mut figures = 0;
    for dir in [root.clone(), root.join("timing")] {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "svg") {
                figures += 1;
                let svg = std::fs::read_to_string(&path).expect("svg");
                let name = path.file_name().unwrap().to_string_lossy().to_string();
                problems.extend(
                    problems_of(&name, &lay_out(&svg, &opt), &[])
                        .into_iter()
                        .filter(|p| p.contains("has no unit")),
                );
                problems.extend(x_problems(&name, &svg));
            }
        }
    }
    assert!(figures >= 30, "only {figures} figures");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // planted: a force without its unit, a log scale that is no unit, a bare number; each fails,
    // and the same axes with a unit pass
    for (title, ok) in [
        ("force", false),
        ("force (log scale)", false),
        ("x (2)", false),
        ("force (kg m s^-2)", true),
        ("phi (degrees)", true),
        ("energy / E0 (dimensionless)", true),
    ] {
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="300" font-family="sans-serif" font-size="12"><text x="16" y="150" transform="rotate(-90 16 150)" text-anchor="middle">{title}</text></svg>"#
        );
        let p = problems_of("t", &lay_out(&svg, &opt), &[]);
        assert_eq!(
            p.iter().any(|x| x.contains("has no unit")),
            !ok,
            "{title}: {p:?}"
        );
        // the same title on the x axis
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="300"><text class="xlabel" x="150" y="290" text-anchor="middle">{title}</text></svg>"#
        );
        assert_eq!(x_problems("t", &svg).is_empty(), ok, "x axis {title}");
    }
    // a figure with no marked x axis fails, and a time axis with its unit and scale passes
    assert!(!x_problems("t", "<svg><text x=\"1\" y=\"1\">t (s)</text></svg>").is_empty());
    let timed = r#"<svg><text class="xlabel" x="1" y="1">time per solve (s, log)</text></svg>"#;
    assert!(x_problems("t", timed).is_empty());
}

#[test]
fn the_figures_of_the_old_writer_fail() {
    // written by the writer before issue 54 (reports/ at bcb1245): the title ran off the left
    // edge, the legend off the right one
    let opt = options();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/figures");
    for (file, text) in [
        (
            "planted_title_cut_on_the_left.svg",
            "classics.hertz.max-indentation.model:",
        ),
        (
            "planted_legend_cut_on_the_right.svg",
            "constant-bulk: work on material / E0",
        ),
    ] {
        let svg = std::fs::read_to_string(dir.join(file)).expect("planted figure");
        let p = problems_of(file, &lay_out(&svg, &opt), &[]);
        assert!(
            p.iter()
                .any(|x| x.contains(text) && x.contains("leaves the canvas")),
            "{file}: {p:?}"
        );
    }
}
