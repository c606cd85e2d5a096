//! Every figure `verify` writes is readable: no two text boxes overlap, and no text (tick label,
//! title, legend entry) covers a data point (a vertex of a curve or a marker). Text widths are
//! estimated from the font size (0.6 em per character, the mean advance of a sans-serif face),
//! heights as one em; a rotated axis title is turned with its box.

use std::path::Path;
use std::process::Command;

#[derive(Debug, Clone)]
struct TextBox {
    text: String,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
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

/// Text boxes and data points of one SVG.
fn parse(svg: &str) -> (Vec<TextBox>, Vec<(f64, f64)>) {
    let base_size = svg
        .find("<svg")
        .and_then(|i| {
            num(
                &svg[i..svg[i..].find('>').map_or(svg.len(), |j| i + j)],
                "font-size",
            )
        })
        .unwrap_or(12.0);
    let mut boxes = Vec::new();
    let mut points = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        rest = &rest[i..];
        let end = rest.find('>').unwrap_or(rest.len() - 1);
        let tag = &rest[..=end];
        if tag.starts_with("<text") {
            let close = rest.find("</text>").unwrap_or(end);
            let content = rest[end + 1..close]
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            let size = num(tag, "font-size").unwrap_or(base_size);
            let (x, y) = (num(tag, "x").unwrap_or(0.0), num(tag, "y").unwrap_or(0.0));
            let width = 0.6 * size * content.chars().count() as f64;
            let anchor = attr(tag, "text-anchor").unwrap_or_else(|| "start".into());
            let (a0, a1) = match anchor.as_str() {
                "middle" => (-width / 2.0, width / 2.0),
                "end" => (-width, 0.0),
                _ => (0.0, width),
            };
            let b = if attr(tag, "transform").is_some_and(|t| t.starts_with("rotate(-90")) {
                // turned a quarter: the text runs upward from (x, y)
                TextBox {
                    text: content,
                    x0: x - size,
                    x1: x,
                    y0: y - a1,
                    y1: y - a0,
                }
            } else {
                TextBox {
                    text: content,
                    x0: x + a0,
                    x1: x + a1,
                    y0: y - 0.8 * size,
                    y1: y + 0.2 * size,
                }
            };
            boxes.push(b);
        } else if tag.starts_with("<polyline") {
            for p in attr(tag, "points").unwrap_or_default().split_whitespace() {
                if let Some((a, b)) = p.split_once(',')
                    && let (Ok(a), Ok(b)) = (a.parse(), b.parse())
                {
                    points.push((a, b));
                }
            }
        } else if tag.starts_with("<circle")
            && let (Some(a), Some(b)) = (num(tag, "cx"), num(tag, "cy"))
        {
            points.push((a, b));
        }
        rest = &rest[end + 1..];
    }
    (boxes, points)
}

fn overlap(a: &TextBox, b: &TextBox) -> bool {
    let eps = 0.5;
    a.x0 + eps < b.x1 && b.x0 + eps < a.x1 && a.y0 + eps < b.y1 && b.y0 + eps < a.y1
}

#[test]
fn no_figure_has_overlapping_text_or_text_over_data() {
    let out = std::env::temp_dir().join(format!("impactcheck-figures-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["--repeats", "1", "--out"])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("verify runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut problems = Vec::new();
    let mut figures = 0;
    for entry in std::fs::read_dir(&out).expect("out dir") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "svg") {
            continue;
        }
        figures += 1;
        let svg = std::fs::read_to_string(&path).expect("svg");
        let (boxes, points) = parse(&svg);
        let name = Path::new(&path)
            .file_name()
            .map(|n| n.to_string_lossy().to_string());
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                if overlap(a, b) {
                    problems.push(format!("{name:?}: `{}` overlaps `{}`", a.text, b.text));
                }
            }
            if let Some(p) = points
                .iter()
                .find(|(x, y)| *x > a.x0 && *x < a.x1 && *y > a.y0 && *y < a.y1)
            {
                problems.push(format!(
                    "{name:?}: `{}` covers the data point {p:?}",
                    a.text
                ));
            }
        }
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
fn the_check_sees_overlaps_and_covered_points() {
    // a legend entry drawn inside the data and a tick label on top of another: both must be seen
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" font-size="12">
<polyline points="10,50 60,48 110,52" fill="none"/>
<text x="40" y="52">legend</text>
<text x="150" y="90" text-anchor="middle">0.25</text>
<text x="160" y="90" text-anchor="middle">0.5</text>
<text x="16" y="50" transform="rotate(-90 16 50)" text-anchor="middle">y (m)</text>
</svg>"#;
    let (boxes, points) = parse(svg);
    assert_eq!(boxes.len(), 4);
    assert_eq!(points.len(), 3);
    assert!(overlap(&boxes[1], &boxes[2]), "{boxes:?}");
    assert!(!overlap(&boxes[0], &boxes[3]));
    let covered = points
        .iter()
        .any(|(x, y)| *x > boxes[0].x0 && *x < boxes[0].x1 && *y > boxes[0].y0 && *y < boxes[0].y1);
    assert!(covered);
}
