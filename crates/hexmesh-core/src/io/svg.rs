//! Mesh pictures in the style of the paper's Fig. 15 (Sußner & Greiner 2009, Sec. 8): every
//! triangle filled by its smallest angle, red at 0° through yellow to green at 60°, with thin
//! edges and a legend. y points up. Coordinates are pixel units rounded to 0.01 px (about six
//! significant digits): a picture, not data, so 100k triangles stay a few megabytes.

use std::fmt::Write as _;
use std::path::Path;

use super::triangle::{invalid, write_file};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::TriMesh;

/// What to draw and how large.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgOptions {
    /// Picture width in pixels (the height follows the drawn window's aspect ratio).
    pub width: f64,
    /// A caption above the picture.
    pub title: Option<String>,
    /// Points to mark with a circle, e.g. the input points.
    pub highlight: Vec<Point>,
    /// Draw only this window, [xmin, ymin, xmax, ymax] in mesh coordinates, clipping to it
    /// (for zoomed insets); `None` fits the whole mesh.
    pub zoom: Option<[f64; 4]>,
    /// Windows [xmin, ymin, xmax, ymax] in mesh coordinates to outline with a dashed frame,
    /// e.g. where a zoomed inset of the same mesh looks.
    pub frames: Vec<[f64; 4]>,
}

impl Default for SvgOptions {
    fn default() -> SvgOptions {
        SvgOptions {
            width: 800.0,
            title: None,
            highlight: Vec::new(),
            zoom: None,
            frames: Vec::new(),
        }
    }
}

/// Angle buckets: one colour per degree keeps one `<path>` per colour.
const BUCKETS: usize = 61;
const MARGIN: f64 = 10.0;
const TITLE_HEIGHT: f64 = 24.0;
const LEGEND_HEIGHT: f64 = 60.0;

/// Writes `mesh` as an SVG picture (see the module comment).
pub fn write_svg(path: &Path, mesh: &TriMesh, opts: &SvgOptions) -> Result<()> {
    super::check_mesh(path, mesh)?;
    if !(opts.width.is_finite() && opts.width >= 100.0 && opts.width <= 100_000.0) {
        return Err(invalid(
            path,
            format!(
                "picture width {} must be between 100 and 100000 pixels",
                opts.width
            ),
        ));
    }
    let window = match opts.zoom {
        Some(z) => {
            if !(z.iter().all(|v| v.is_finite()) && z[0] < z[2] && z[1] < z[3]) {
                return Err(invalid(
                    path,
                    format!("zoom window {z:?} must be finite with xmin < xmax and ymin < ymax"),
                ));
            }
            z
        }
        None => fitted_window(mesh, &opts.highlight),
    };

    // Plot area: full width, height from the window's aspect ratio (kept sane for a mesh
    // that is nearly a line).
    let plot_w = opts.width - 2.0 * MARGIN;
    let (dx, dy) = (window[2] - window[0], window[3] - window[1]);
    let plot_h = (plot_w * dy / dx).clamp(plot_w * 0.05, plot_w * 2.0);
    let scale = (plot_w / dx).min(plot_h / dy);
    let top = MARGIN
        + if opts.title.is_some() {
            TITLE_HEIGHT
        } else {
            0.0
        };
    // Centre the window in the plot area; y flips so that it points up.
    let x0 = MARGIN + 0.5 * (plot_w - scale * dx);
    let y0 = top + 0.5 * (plot_h - scale * dy);
    let to_px = |p: Point| -> (f64, f64) {
        (
            x0 + (p[0] - window[0]) * scale,
            y0 + (window[3] - p[1]) * scale,
        )
    };
    let height = top + plot_h + LEGEND_HEIGHT + MARGIN;

    let mut buckets: Vec<String> = vec![String::new(); BUCKETS];
    let mut drawn = 0usize;
    let mut smallest = f64::INFINITY;
    for t in 0..mesh.triangles.len() {
        let corners = mesh.corners(t);
        if !overlaps(&corners, window) {
            continue;
        }
        // In a zoom window, cut each triangle to the window (in mesh coordinates), so that no
        // pixel coordinate grows beyond the picture: renderers work in float32.
        let outline: Vec<Point> =
            if opts.zoom.is_some() && !corners.iter().all(|&c| inside(c, window)) {
                clip(&corners, window)
            } else {
                corners.to_vec()
            };
        if outline.len() < 3 {
            continue;
        }
        let angle = smallest_angle(corners);
        smallest = smallest.min(angle);
        let bucket = (angle.round() as usize).min(BUCKETS - 1);
        // Absolute first corner, then relative moves between the corners rounded to
        // hundredths of a pixel: short numbers, and no rounding error adds up.
        let d = &mut buckets[bucket];
        let q: Vec<(i64, i64)> = outline
            .iter()
            .map(|&c| {
                let (x, y) = to_px(c);
                (hundredths(x), hundredths(y))
            })
            .collect();
        d.push('M');
        push_hundredths(d, q[0].0, false);
        push_hundredths(d, q[0].1, true);
        d.push('l');
        for k in 1..q.len() {
            push_hundredths(d, q[k].0 - q[k - 1].0, k > 1);
            push_hundredths(d, q[k].1 - q[k - 1].1, true);
        }
        d.push('z');
        drawn += 1;
    }

    // Edges thin against the triangles' size, so that dense meshes do not turn grey.
    let plot_area = (scale * dx) * (scale * dy);
    let typical = (plot_area / drawn.max(1) as f64).sqrt();
    let stroke = (typical * 0.04).clamp(0.05, 0.8);

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#,
        w = fmt_px(opts.width),
        h = fmt_px(height)
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    if let Some(title) = &opts.title {
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{}" font-size="15">{}</text>"#,
            fmt_px(MARGIN),
            fmt_px(MARGIN + 15.0),
            escape(title)
        );
    }
    let _ = writeln!(
        svg,
        r#"<clipPath id="plot"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>"#,
        fmt_px(x0),
        fmt_px(y0),
        fmt_px(scale * dx),
        fmt_px(scale * dy)
    );
    let _ = writeln!(
        svg,
        r##"<g clip-path="url(#plot)" stroke="#222" stroke-width="{}" stroke-linejoin="round">"##,
        fmt_px(stroke)
    );
    for (bucket, d) in buckets.iter().enumerate() {
        if !d.is_empty() {
            let _ = writeln!(svg, r#"<path fill="{}" d="{d}"/>"#, colour(bucket as f64));
        }
    }
    let radius = (typical * 0.15).clamp(1.5, 4.0);
    let marks: Vec<(f64, f64)> = opts
        .highlight
        .iter()
        .filter(|p| p[0].is_finite() && p[1].is_finite() && inside(**p, window))
        .map(|&p| to_px(p))
        .collect();
    if !marks.is_empty() {
        let _ = writeln!(
            svg,
            r##"<g fill="none" stroke="#1f3fbf" stroke-width="{}">"##,
            fmt_px((radius * 0.4).min(1.0))
        );
        for (x, y) in marks {
            let _ = writeln!(
                svg,
                r#"<circle cx="{}" cy="{}" r="{}"/>"#,
                fmt_px(x),
                fmt_px(y),
                fmt_px(radius)
            );
        }
        svg.push_str("</g>\n");
    }
    for f in opts
        .frames
        .iter()
        .filter(|f| f.iter().all(|v| v.is_finite()))
    {
        let (xa, ya) = to_px([f[0].max(window[0]), f[3].min(window[3])]);
        let (xb, yb) = to_px([f[2].min(window[2]), f[1].max(window[1])]);
        if xb > xa && yb > ya {
            let _ = writeln!(
                svg,
                r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#1f3fbf" stroke-width="1.5" stroke-dasharray="5 3"/>"##,
                fmt_px(xa),
                fmt_px(ya),
                fmt_px((xb - xa).max(3.0)),
                fmt_px((yb - ya).max(3.0))
            );
        }
    }
    svg.push_str("</g>\n");
    if opts.zoom.is_some() {
        // A frame shows where the inset cuts the mesh.
        let _ = writeln!(
            svg,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555" stroke-width="1"/>"##,
            fmt_px(x0),
            fmt_px(y0),
            fmt_px(scale * dx),
            fmt_px(scale * dy)
        );
    }
    legend(&mut svg, top + plot_h + 8.0, opts.width, drawn, smallest);
    svg.push_str("</svg>\n");
    write_file(path, &svg)
}

/// The colour bar from 0° to 60°, its ticks, and the figures of what was drawn.
fn legend(svg: &mut String, y: f64, width: f64, drawn: usize, smallest: f64) {
    let bar_w = (width - 2.0 * MARGIN).min(360.0);
    svg.push_str(r#"<defs><linearGradient id="angle">"#);
    for degrees in (0..=60).step_by(10) {
        let _ = write!(
            svg,
            r#"<stop offset="{}" stop-color="{}"/>"#,
            fmt_px(degrees as f64 / 60.0),
            colour(degrees as f64)
        );
    }
    svg.push_str("</linearGradient></defs>\n");
    let _ = writeln!(
        svg,
        r##"<rect x="{}" y="{}" width="{}" height="10" fill="url(#angle)" stroke="#222" stroke-width="0.5"/>"##,
        fmt_px(MARGIN),
        fmt_px(y),
        fmt_px(bar_w)
    );
    for degrees in (0..=60).step_by(10) {
        let x = MARGIN + bar_w * degrees as f64 / 60.0;
        let anchor = match degrees {
            0 => "start",
            60 => "end",
            _ => "middle",
        };
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{}" text-anchor="{anchor}">{degrees}°</text>"#,
            fmt_px(x),
            fmt_px(y + 24.0)
        );
    }
    // Two short lines, so that the caption fits a narrow (zoomed) picture too.
    let figures = if drawn == 0 {
        "no triangles drawn".to_string()
    } else {
        format!("{drawn} triangles drawn, smallest angle {smallest:.2}°")
    };
    for (k, line) in ["colour: smallest angle of each triangle", figures.as_str()]
        .iter()
        .enumerate()
    {
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{}">{}</text>"#,
            fmt_px(MARGIN),
            fmt_px(y + 38.0 + 14.0 * k as f64),
            escape(line)
        );
    }
}

/// The mesh's bounding box (or the highlighted points' when the mesh is empty), padded by 2%.
fn fitted_window(mesh: &TriMesh, highlight: &[Point]) -> [f64; 4] {
    let points = mesh
        .vertices
        .iter()
        .chain(highlight)
        .filter(|p| p[0].is_finite() && p[1].is_finite());
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in points {
        b = [
            b[0].min(p[0]),
            b[1].min(p[1]),
            b[2].max(p[0]),
            b[3].max(p[1]),
        ];
    }
    if b[0] > b[2] {
        return [0.0, 0.0, 1.0, 1.0];
    }
    let size = (b[2] - b[0]).max(b[3] - b[1]);
    let pad = if size > 0.0 {
        0.02 * size
    } else {
        b[0].abs().max(b[1].abs()).max(1.0) * 1e-3
    };
    [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad]
}

fn inside(p: Point, w: [f64; 4]) -> bool {
    p[0] >= w[0] && p[0] <= w[2] && p[1] >= w[1] && p[1] <= w[3]
}

/// The part of a triangle inside the window: Sutherland & Hodgman's polygon clipping
/// ("Reentrant polygon clipping", CACM 1974) against the window's four sides in turn.
fn clip(corners: &[Point; 3], w: [f64; 4]) -> Vec<Point> {
    let mut polygon: Vec<Point> = corners.to_vec();
    for (axis, bound, keep_above) in [
        (0, w[0], true),
        (0, w[2], false),
        (1, w[1], true),
        (1, w[3], false),
    ] {
        let keep = |p: Point| {
            if keep_above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let mut out = Vec::with_capacity(polygon.len() + 2);
        for i in 0..polygon.len() {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            if keep(a) {
                out.push(a);
            }
            if keep(a) != keep(b) {
                let t = (bound - a[axis]) / (b[axis] - a[axis]);
                let mut p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                p[axis] = bound;
                out.push(p);
            }
        }
        polygon = out;
        if polygon.is_empty() {
            break;
        }
    }
    polygon
}

/// True when the triangle's bounding box meets the window.
fn overlaps(c: &[Point; 3], w: [f64; 4]) -> bool {
    let xmin = c[0][0].min(c[1][0]).min(c[2][0]);
    let xmax = c[0][0].max(c[1][0]).max(c[2][0]);
    let ymin = c[0][1].min(c[1][1]).min(c[2][1]);
    let ymax = c[0][1].max(c[1][1]).max(c[2][1]);
    xmax >= w[0] && xmin <= w[2] && ymax >= w[1] && ymin <= w[3]
}

/// Smallest interior angle in degrees; a degenerate triangle has 0°.
pub(crate) fn smallest_angle(c: [Point; 3]) -> f64 {
    (0..3)
        .map(|i| {
            let (a, b, d) = (c[i], c[(i + 1) % 3], c[(i + 2) % 3]);
            let u = [b[0] - a[0], b[1] - a[1]];
            let v = [d[0] - a[0], d[1] - a[1]];
            let cross = (u[0] * v[1] - u[1] * v[0]).abs();
            let dot = u[0] * v[0] + u[1] * v[1];
            cross.atan2(dot).to_degrees()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Red at 0°, yellow at 30°, green at 60° (hue 0 → 120, HSV with s = 0.8, v = 0.9).
fn colour(degrees: f64) -> String {
    let hue = (degrees.clamp(0.0, 60.0) / 60.0) * 120.0;
    let (s, v) = (0.8, 0.9);
    let c = v * s;
    let x = c * (1.0 - ((hue / 60.0) % 2.0 - 1.0).abs());
    let (r, g) = if hue < 60.0 { (c, x) } else { (x, c) };
    let m = v - c;
    let byte = |f: f64| ((f + m) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(0.0))
}

/// A pixel coordinate with at most two decimals and no trailing zeros.
fn fmt_px(v: f64) -> String {
    let mut s = format!("{:.2}", v);
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".to_string();
    }
    s
}

/// A pixel coordinate in hundredths; the picture is at most 100000 px wide, so this fits.
fn hundredths(v: f64) -> i64 {
    (v * 100.0).round() as i64
}

/// Appends hundredths `h` as a decimal number, after a space if `separate` and the number
/// does not start with a minus sign (which separates on its own).
fn push_hundredths(out: &mut String, h: i64, separate: bool) {
    if h < 0 {
        out.push('-');
    } else if separate {
        out.push(' ');
    }
    let a = h.unsigned_abs();
    let _ = write!(out, "{}", a / 100);
    match a % 100 {
        0 => {}
        f if f % 10 == 0 => {
            let _ = write!(out, ".{}", f / 10);
        }
        f => {
            let _ = write!(out, ".{f:02}");
        }
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equilateral_smallest_angle_is_sixty_and_degenerate_is_zero() {
        let h = 3f64.sqrt() / 2.0;
        assert!((smallest_angle([[0.0, 0.0], [1.0, 0.0], [0.5, h]]) - 60.0).abs() < 1e-9);
        assert_eq!(smallest_angle([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), 0.0);
        assert_eq!(smallest_angle([[0.0, 0.0], [0.0, 0.0], [2.0, 1.0]]), 0.0);
    }

    #[test]
    fn colour_runs_from_red_through_yellow_to_green() {
        assert_eq!(colour(0.0), "#e62e2e");
        assert_eq!(colour(30.0), "#e6e62e");
        assert_eq!(colour(60.0), "#2ee62e");
    }

    #[test]
    fn hundredths_are_written_short_and_signs_separate() {
        let mut s = String::new();
        for (h, sep) in [
            (25970, false),
            (-3, true),
            (1250, true),
            (-100, true),
            (7, false),
        ] {
            push_hundredths(&mut s, h, sep);
        }
        assert_eq!(s, "259.7-0.03 12.5-10.07");
    }

    #[test]
    fn clipping_keeps_the_part_inside_the_window() {
        let triangle = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        let part = clip(&triangle, [1.0, -1.0, 2.0, 1.0]);
        // The unit-wide strip 1 <= x <= 2 cut from the triangle's bottom: a rectangle.
        let mut sorted = part.clone();
        sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        assert_eq!(sorted, vec![[1.0, 0.0], [1.0, 1.0], [2.0, 0.0], [2.0, 1.0]]);
        assert!(clip(&triangle, [5.0, 5.0, 6.0, 6.0]).is_empty());
    }

    #[test]
    fn pixel_coordinates_are_short() {
        assert_eq!(fmt_px(12.345678), "12.35");
        assert_eq!(fmt_px(3.0), "3");
        assert_eq!(fmt_px(-0.001), "0");
        assert_eq!(fmt_px(0.5), "0.5");
    }
}
