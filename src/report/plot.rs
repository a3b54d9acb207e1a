//! Plots of the report, each written as SVG and PNG with plotters: the angle distribution of
//! every mesher on a dataset with the bounds it promises (paper 000 Sec. 6: 43.9°–90° for the
//! extended refinement, Sec. 5.1: 30°–120° for the simple one), and time and triangle count
//! against input size on log-log axes (the paper's Sec. 8 reads O(n²) off its timings).
//!
//! PNG text is rasterised by plotters' `ab_glyph` backend, which needs a font file at run time:
//! DejaVu Sans from Debian's fonts-dejavu-core (`make fonts`).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle, RGBColor};

use super::stats::power_law_exponent;
use crate::error::{Error, Result};

/// Where the PNG font is loaded from.
pub const FONT_PATH: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

const FONT: &str = "sans-serif";

/// Loads DejaVu Sans once and registers it as plotters' sans-serif font. Both backends need
/// it: the SVG one measures text with it to lay out legends.
pub fn ensure_font() -> Result<()> {
    static LOADED: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    let outcome = LOADED.get_or_init(|| {
        let bytes = read_font(Path::new(FONT_PATH)).map_err(|e| e.to_string())?;
        // plotters keeps a 'static reference; the font lives as long as the process anyway.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        register_font(FONT, FontStyle::Normal, bytes)
            .map_err(|_| format!("{FONT_PATH}: not a font plotters can read"))
    });
    outcome
        .clone()
        .map_err(|message| Error::parse(PathBuf::from(FONT_PATH), 0, message))
}

/// The font file's bytes, or an error that says which package provides it.
fn read_font(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| {
        Error::parse(
            path,
            0,
            format!(
                "{e}; the plots need the DejaVu Sans font: install Debian's fonts-dejavu-core \
                 (`make fonts`)"
            ),
        )
    })
}

/// Colours by mesher name, the same in every plot of a report.
pub fn mesher_color(name: &str) -> RGBColor {
    const KNOWN: [&str; 10] = [
        "hex",
        "hex-simple",
        "cgal",
        "cgal-conforming",
        "triangle",
        "spade",
        "rhomb",
        "saalfeld",
        "lsb",
        "gmsh",
    ];
    const COLORS: [RGBColor; 11] = [
        RGBColor(214, 39, 40),
        RGBColor(255, 127, 14),
        RGBColor(31, 119, 180),
        RGBColor(23, 190, 207),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(0, 0, 0),
    ];
    let i = KNOWN.iter().position(|k| *k == name).unwrap_or(KNOWN.len());
    COLORS[i]
}

/// One mesher's curve in an angle plot.
#[derive(Debug, Clone, PartialEq)]
pub struct AngleSeries {
    pub mesher: String,
    /// Angles per 1° bin (bin i holds [i°, i+1°)), as counted by `quality::metrics`.
    pub histogram: Vec<u64>,
    /// The angles the mesher promises to stay within, drawn as vertical lines.
    pub bounds: Vec<f64>,
    /// The smallest and largest angle measured: the curve is drawn between them, so that a
    /// bin that straddles a bound (43°–44° holding angles from 43.9°) is not drawn at its
    /// centre, across the bound it keeps.
    pub range: Option<(f64, f64)>,
}

impl AngleSeries {
    /// The fraction of all angles in each bin.
    pub fn fractions(&self) -> Vec<f64> {
        let total: u64 = self.histogram.iter().sum();
        if total == 0 {
            return vec![0.0; self.histogram.len()];
        }
        self.histogram
            .iter()
            .map(|&c| c as f64 / total as f64)
            .collect()
    }
}

/// What a reader should find in one angle plot, in words, from the same histograms: for each
/// mesher the range of its occupied bins and its three fullest bins with their shares, and the
/// curves hidden under an identical one. Bin i is [i°, i+1°).
pub fn angle_notes(series: &[AngleSeries]) -> Vec<String> {
    let mut notes = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let total: u64 = s.histogram.iter().sum();
        if total == 0 {
            continue;
        }
        if let Some(first) = series[..k].iter().find(|o| o.histogram == s.histogram) {
            notes.push(format!(
                "`{}`: identical to `{}`'s histogram; its curve lies under that one",
                s.mesher, first.mesher
            ));
            continue;
        }
        let occupied = |i: &usize| s.histogram[*i] > 0;
        let (Some(lo), Some(hi)) = (
            (0..s.histogram.len()).find(occupied),
            (0..s.histogram.len()).rev().find(occupied),
        ) else {
            continue;
        };
        let mut order: Vec<usize> = (0..s.histogram.len()).filter(occupied).collect();
        order.sort_by(|&a, &b| s.histogram[b].cmp(&s.histogram[a]).then(a.cmp(&b)));
        let top: Vec<String> = order
            .iter()
            .take(3)
            .map(|&i| {
                format!(
                    "{i}–{}° ({:.1} %)",
                    i + 1,
                    100.0 * s.histogram[i] as f64 / total as f64
                )
            })
            .collect();
        notes.push(format!(
            "`{}`: angles from the {lo}–{}° bin to the {hi}–{}° bin; fullest bins {}",
            s.mesher,
            lo + 1,
            hi + 1,
            top.join(", ")
        ));
    }
    notes
}

/// One mesher's line in the scaling plot: (input points, seconds, triangles) per dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalingSeries {
    pub mesher: String,
    pub samples: Vec<(f64, f64, f64)>,
}

/// Panels per row of an angle plot, and each panel's size in pixels.
const ANGLE_COLUMNS: usize = 4;
const ANGLE_PANEL: (u32, u32) = (420, 260);
/// Height of the angle plot's title band.
const ANGLE_TITLE: u32 = 44;
const SIZE_SCALING: (u32, u32) = (1200, 520);

/// Writes `<stem>.svg` and `<stem>.png` in `dir`: angle distributions of one dataset.
pub fn angle_plot(
    dir: &Path,
    stem: &str,
    title: &str,
    series: &[AngleSeries],
) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    let size = angle_plot_size(series.len());
    draw_angles(
        SVGBackend::new(&svg, size).into_drawing_area(),
        title,
        series,
    )
    .map_err(|e| plot_error(&svg, e))?;
    draw_angles(
        BitMapBackend::new(&png, size).into_drawing_area(),
        title,
        series,
    )
    .map_err(|e| plot_error(&png, e))?;
    Ok(vec![svg, png])
}

/// Writes `<stem>.svg` and `<stem>.png` in `dir`: time and triangles against input points.
pub fn scaling_plot(dir: &Path, stem: &str, series: &[ScalingSeries]) -> Result<Vec<PathBuf>> {
    ensure_font()?;
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    draw_scaling(
        SVGBackend::new(&svg, SIZE_SCALING).into_drawing_area(),
        series,
    )
    .map_err(|e| plot_error(&svg, e))?;
    draw_scaling(
        BitMapBackend::new(&png, SIZE_SCALING).into_drawing_area(),
        series,
    )
    .map_err(|e| plot_error(&png, e))?;
    Ok(vec![svg, png])
}

fn plot_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(format!("drawing the plot: {e}")),
    }
}

type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The size of an angle plot of `n` meshers: a grid of [`ANGLE_COLUMNS`] panels per row.
fn angle_plot_size(n: usize) -> (u32, u32) {
    let columns = n.clamp(1, ANGLE_COLUMNS);
    let rows = n.div_ceil(ANGLE_COLUMNS).max(1);
    (
        ANGLE_PANEL.0 * columns as u32,
        ANGLE_TITLE + ANGLE_PANEL.1 * rows as u32,
    )
}

/// Small multiples: one panel per mesher, all on the same axes (0°–180°, the same log scale),
/// so that a curve is never hidden under another and panels compare at a glance. Each panel
/// names its mesher and the range measured, and labels its promised bounds on their dashed
/// lines.
fn draw_angles<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    series: &[AngleSeries],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (band, body) = root.split_vertically(ANGLE_TITLE);
    band.draw(&Text::new(
        title.to_string(),
        (12, 10),
        (FONT, 22).into_font().color(&BLACK),
    ))?;
    let fractions: Vec<Vec<f64>> = series.iter().map(AngleSeries::fractions).collect();
    // A log axis: the hexagon meshers put most angles in a few bins, and a linear axis would
    // flatten every refinement mesher's curve against zero. Empty bins sit on the floor.
    let (floor, y_top) = log_range(&fractions);
    let columns = series.len().clamp(1, ANGLE_COLUMNS);
    let rows = series.len().div_ceil(ANGLE_COLUMNS).max(1);
    let panels = body.split_evenly((rows, columns));
    for ((s, f), panel) in series.iter().zip(&fractions).zip(&panels) {
        let color = mesher_color(&s.mesher);
        let caption = match s.range {
            Some((lo, hi)) => format!("{}: {}–{}", s.mesher, short_degrees(lo), short_degrees(hi)),
            None => s.mesher.clone(),
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(caption, (FONT, 16).into_font().color(&color))
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(48)
            .build_cartesian_2d(0f64..180f64, (floor..y_top).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("angle (°)")
            .x_labels(7)
            .y_labels(4)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style((FONT, 11))
            .axis_desc_style((FONT, 12))
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        chart.draw_series(LineSeries::new(
            curve_points(f, s.range, floor),
            color.stroke_width(2),
        ))?;
        for (k, &b) in s.bounds.iter().enumerate() {
            chart.draw_series(DashedLineSeries::new(
                vec![(b, floor), (b, y_top)],
                6,
                4,
                BLACK.mix(0.6).stroke_width(1),
            ))?;
            // The label sits beside its line, inside the panel, staggered so that two bounds
            // close together (30° and 43.9°) do not overlap.
            let x = if b > 150.0 { b - 30.0 } else { b + 2.0 };
            let y = y_top / 3f64.powi(k as i32 + 1);
            chart.draw_series(std::iter::once(Text::new(
                format!("bound {}", short_degrees(b)),
                (x, y),
                (FONT, 12).into_font().color(&BLACK),
            )))?;
        }
    }
    root.present()
}

/// The points of one curve: a point per bin at its centre, on the floor when the bin is empty;
/// with the measured `range`, only the bins that meet it, at their centre moved into it.
fn curve_points(fractions: &[f64], range: Option<(f64, f64)>, floor: f64) -> Vec<(f64, f64)> {
    fractions
        .iter()
        .enumerate()
        .filter_map(|(i, &v)| {
            let centre = i as f64 + 0.5;
            match range {
                None => Some((centre, v.max(floor))),
                Some((lo, hi)) if i as f64 <= hi && i as f64 + 1.0 > lo => {
                    Some((centre.clamp(lo, hi), v.max(floor)))
                }
                Some(_) => None,
            }
        })
        .collect()
}

/// The y range of the angle plot: from below the smallest non-empty bin to above the peak.
fn log_range(fractions: &[Vec<f64>]) -> (f64, f64) {
    let values = || fractions.iter().flatten().copied().filter(|&v| v > 0.0);
    let low = values().fold(f64::INFINITY, f64::min);
    let peak = values().fold(0.0_f64, f64::max);
    if !low.is_finite() || peak <= 0.0 {
        return (1e-4, 1.0);
    }
    ((low / 2.0).max(1e-9), (peak * 2.0).min(1.0))
}

/// Degrees to at most four decimals, without trailing zeros: 30°, 43.8979°.
fn short_degrees(b: f64) -> String {
    let text = format!("{b:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    format!("{text}°")
}

fn draw_scaling<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    series: &[ScalingSeries],
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(SIZE_SCALING.0 / 2);
    draw_scaling_panel(&left, series, "meshing time (s)", |s| s.1)?;
    draw_scaling_panel(&right, series, "triangles", |s| s.2)?;
    root.present()
}

fn draw_scaling_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    series: &[ScalingSeries],
    what: &str,
    y_of: impl Fn(&(f64, f64, f64)) -> f64,
) -> DrawResult<DB> {
    let positive = |v: f64| v > 0.0 && v.is_finite();
    let xs: Vec<f64> = series
        .iter()
        .flat_map(|s| s.samples.iter().map(|p| p.0))
        .filter(|&x| positive(x))
        .collect();
    let ys: Vec<f64> = series
        .iter()
        .flat_map(|s| s.samples.iter().map(&y_of))
        .filter(|&y| positive(y))
        .collect();
    let range = |v: &[f64]| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0_f64, f64::max);
        if lo.is_finite() && hi > 0.0 {
            (lo / 2.0, hi * 2.0)
        } else {
            (1.0, 10.0)
        }
    };
    let (x0, x1) = range(&xs);
    let (y0, y1) = range(&ys);
    let mut chart = ChartBuilder::on(area)
        .caption(format!("{what} against input points"), (FONT, 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("input points")
        .y_desc(what)
        .x_label_formatter(&|v| log_label(*v))
        .y_label_formatter(&|v| log_label(*v))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .draw()?;
    for s in series {
        let mut pts: Vec<(f64, f64)> = s
            .samples
            .iter()
            .map(|p| (p.0, y_of(p)))
            .filter(|&(x, y)| positive(x) && positive(y))
            .collect();
        if pts.is_empty() {
            continue;
        }
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let color = mesher_color(&s.mesher);
        let label = match power_law_exponent(&pts) {
            Some(b) => format!("{} (∝ n^{b:.2})", s.mesher),
            None => s.mesher.clone(),
        };
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    Ok(())
}

/// Tick labels of a log axis: whole numbers without a fraction, small ones as short decimals.
fn log_label(v: f64) -> String {
    if v >= 1.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("hexmesh-plot-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_missing_font_names_the_package_to_install() {
        let e = read_font(Path::new("/nonexistent/DejaVuSans.ttf")).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("/nonexistent/DejaVuSans.ttf: "), "{text}");
        assert!(text.contains("fonts-dejavu-core"), "{text}");
    }

    #[test]
    fn fractions_sum_to_one_and_empty_histograms_are_zero() {
        let mut h = vec![0u64; 180];
        h[44] = 3;
        h[90] = 1;
        let s = AngleSeries {
            mesher: "hex".into(),
            histogram: h,
            bounds: vec![],
            range: None,
        };
        let f = s.fractions();
        assert_eq!(f[44], 0.75);
        assert!((f.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let z = AngleSeries {
            mesher: "x".into(),
            histogram: vec![0; 180],
            bounds: vec![],
            range: None,
        };
        assert!(z.fractions().iter().all(|&v| v == 0.0));
    }

    #[test]
    fn angle_notes_give_range_fullest_bins_and_hidden_curves() {
        let mut h = vec![0u64; 180];
        h[43] = 1;
        h[60] = 6;
        h[45] = 2;
        h[90] = 1;
        let series = vec![
            AngleSeries {
                mesher: "saalfeld".into(),
                histogram: h.clone(),
                bounds: vec![],
                range: None,
            },
            AngleSeries {
                mesher: "cgal-conforming".into(),
                histogram: h,
                bounds: vec![],
                range: None,
            },
            AngleSeries {
                mesher: "empty".into(),
                histogram: vec![0; 180],
                bounds: vec![],
                range: None,
            },
        ];
        let notes = angle_notes(&series);
        assert_eq!(
            notes,
            [
                "`saalfeld`: angles from the 43–44° bin to the 90–91° bin; fullest bins \
                 60–61° (60.0 %), 45–46° (20.0 %), 43–44° (10.0 %)",
                "`cgal-conforming`: identical to `saalfeld`'s histogram; its curve lies under that one",
            ]
        );
    }

    #[test]
    fn log_range_spans_the_smallest_bin_and_the_peak() {
        let (lo, hi) = log_range(&[vec![0.0, 0.001, 0.5], vec![0.25, 0.0]]);
        assert_eq!((lo, hi), (0.0005, 1.0));
        let (lo, hi) = log_range(&[vec![0.0, 0.01, 0.1]]);
        assert_eq!((lo, hi), (0.005, 0.2));
        assert_eq!(log_range(&[vec![0.0; 3]]), (1e-4, 1.0));
    }

    #[test]
    fn a_curve_with_its_measured_range_stays_inside_it() {
        let mut f = vec![0.0; 180];
        f[43] = 0.25;
        f[60] = 0.5;
        f[90] = 0.25;
        let pts = curve_points(&f, Some((43.9, 90.0)), 1e-6);
        assert_eq!(pts.first(), Some(&(43.9, 0.25)));
        assert_eq!(pts.last(), Some(&(90.0, 0.25)));
        assert!(pts.iter().all(|p| (43.9..=90.0).contains(&p.0)));
        assert_eq!(pts.len(), 90 - 43 + 1);
        // Without a range every bin is drawn at its centre.
        let all = curve_points(&f, None, 1e-6);
        assert_eq!(all.len(), 180);
        assert_eq!(all[43], (43.5, 0.25));
    }

    #[test]
    fn angle_plot_draws_a_panel_per_mesher_with_labelled_bounds_as_svg_and_png() {
        let dir = temp_dir("angles");
        let mut h = vec![0u64; 180];
        for (i, v) in h.iter_mut().enumerate().take(91).skip(43) {
            *v = (i as u64) % 7 + 1;
        }
        let series = vec![
            AngleSeries {
                mesher: "hex".into(),
                histogram: h.clone(),
                bounds: vec![43.8979, 90.0],
                range: None,
            },
            AngleSeries {
                mesher: "triangle".into(),
                histogram: h,
                bounds: vec![30.0],
                range: None,
            },
        ];
        let files = angle_plot(&dir, "angles-test", "angles of test", &series).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        // One panel per mesher, each bound labelled on its line.
        let text = |t: &str| svg.lines().any(|l| l.trim() == t);
        assert!(text("hex") && text("triangle"), "{svg}");
        assert!(svg.contains("bound 43.8979°"));
        assert!(svg.contains("bound 90°"));
        assert!(svg.contains("bound 30°"));
        let png = std::fs::read(&files[1]).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        if std::env::var_os("HEXMESH_KEEP_PLOTS").is_none() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }

    #[test]
    fn scaling_plot_legend_gives_the_fitted_exponent() {
        let dir = temp_dir("scaling");
        let samples = [100.0, 1000.0, 10000.0]
            .iter()
            .map(|&n| (n, 1e-6 * n * n, 12.0 * n))
            .collect();
        let series = vec![ScalingSeries {
            mesher: "hex".into(),
            samples,
        }];
        let files = scaling_plot(&dir, "scaling", &series).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        assert!(svg.contains("hex (∝ n^2.00)"), "time exponent");
        assert!(svg.contains("hex (∝ n^1.00)"), "triangle exponent");
        assert!(std::fs::metadata(&files[1]).unwrap().len() > 1000);
        if std::env::var_os("HEXMESH_KEEP_PLOTS").is_none() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}
