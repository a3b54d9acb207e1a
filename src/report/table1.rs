//! `table1.md`: the paper's Table 1 (Sußner & Greiner, IMR 2009, Sec. 8) — triangle counts at
//! the largest reachable minimum angle — with this project's figures beside the paper's.
//!
//! Protocol of Sec. 8: "For Triangle we increase the angle by 0.25 degrees step by step until
//! the program fails." The references here go through the same protocol (`maxangle`); our own
//! meshers have fixed bounds and run once with default parameters, so their cells give the
//! triangle count at the minimum angle they reached.

use std::fmt::Write as _;

use serde::Serialize;

use super::row::{one_line, Row, NOT_RUN};

/// One figure of the paper's Table 1, as printed there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperCell {
    pub triangles: u64,
    /// The minimum angle in degrees; the paper gives none for hex on the IMR letters (a PSLG:
    /// bounds are lost at the segments, 13.7° there).
    pub angle: Option<f64>,
    /// Seconds; the paper times only its own mesher ("Triangle below 0.03 s for all").
    pub time_s: Option<f64>,
    /// The cell verbatim from the paper's text.
    pub text: &'static str,
}

/// One row of the paper's Table 1 and the dataset of `datasets` that reproduces it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperRow {
    pub dataset: &'static str,
    /// The row label in the paper.
    pub label: &'static str,
    pub triangle_single: PaperCell,
    pub triangle_double: PaperCell,
    pub hex: PaperCell,
}

const fn cell(triangles: u64, angle: f64, text: &'static str) -> PaperCell {
    PaperCell {
        triangles,
        angle: Some(angle),
        time_s: None,
        text,
    }
}

const fn hex_cell(triangles: u64, angle: Option<f64>, time: f64, text: &'static str) -> PaperCell {
    PaperCell {
        triangles,
        angle,
        time_s: Some(time),
        text,
    }
}

/// Table 1 of paper 000, Sec. 8, in the paper's row order.
pub const PAPER_TABLE1: [PaperRow; 6] = [
    PaperRow {
        dataset: "close-pair",
        label: "2 close pts",
        triangle_single: cell(122, 36.75, "122 at 36.75°"),
        triangle_double: cell(131, 37.00, "131 at 37.00°"),
        hex: hex_cell(684, Some(43.9), 0.005, "684 at 43.9° (0.005 s)"),
    },
    PaperRow {
        dataset: "line-100",
        label: "100 pts on line",
        triangle_single: cell(4890, 35.00, "4890 at 35.00°"),
        triangle_double: cell(5289, 35.00, "5289 at 35.00°"),
        hex: hex_cell(18667, Some(43.9), 0.13, "18667 at 43.9° (0.13 s)"),
    },
    PaperRow {
        dataset: "plane-100",
        label: "100 pts on plane",
        triangle_single: cell(1149, 34.50, "1149 at 34.50°"),
        triangle_double: cell(1133, 34.50, "1133 at 34.50°"),
        hex: hex_cell(12748, Some(43.9), 0.21, "12748 at 43.9° (0.21 s)"),
    },
    PaperRow {
        dataset: "imr",
        label: "IMR-letters",
        triangle_single: cell(2569, 34.50, "2569 at 34.50°"),
        triangle_double: cell(1770, 34.50, "1770 at 34.50°"),
        hex: hex_cell(30551, None, 1.03, "30551 (1.03 s)"),
    },
    PaperRow {
        dataset: "plane-1k",
        label: "1k pts on plane",
        triangle_single: cell(10423, 34.5, "10423 at 34.5°"),
        triangle_double: cell(14414, 34.75, "14414 at 34.75°"),
        hex: hex_cell(127729, Some(43.9), 30.4, "127729 at 43.9° (30.4 s)"),
    },
    PaperRow {
        dataset: "plane-2k",
        label: "2k pts on plane",
        triangle_single: cell(19377, 34.25, "19377 at 34.25"),
        triangle_double: cell(19244, 34.25, "19244 at 34.25"),
        hex: hex_cell(268138, Some(43.9), 123.0, "268138 at 43.9° (123 s)"),
    },
];

/// The paper's row for a dataset, if Table 1 has one.
pub fn paper_row(dataset: &str) -> Option<&'static PaperRow> {
    PAPER_TABLE1.iter().find(|r| r.dataset == dataset)
}

/// The outcome of the max-angle protocol for one reference mesher on one dataset; also a row
/// of `maxangle.csv`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MaxAngleRow {
    pub dataset: String,
    pub mesher: String,
    /// The step in degrees between requested angles.
    pub step: f64,
    /// The first requested angle.
    pub start: f64,
    /// The largest requested minimum angle that still gave a good mesh; empty when even the
    /// first request failed.
    pub angle: Option<f64>,
    pub triangles: Option<u64>,
    /// The meshing call's time at that angle, seconds.
    pub time_s: Option<f64>,
    /// Why the next step counted as a failure (error, timeout, angle not reached, ...).
    pub next_failure: String,
    /// The mesher's effective settings at `angle` (at the failed request when there is none).
    pub settings: String,
    /// Set when the protocol itself could not run.
    pub err: String,
}

/// The columns of `maxangle.csv`, in order (the field names of [`MaxAngleRow`]).
pub const MAX_ANGLE_COLUMNS: &[&str] = &[
    "dataset",
    "mesher",
    "step",
    "start",
    "angle",
    "triangles",
    "time_s",
    "next_failure",
    "settings",
    "err",
];

/// Renders `table1.md`. `meshers` gives the column order; a mesher in `references` gets its
/// cell from `max_angles`, any other from its `results.csv` row.
pub fn render(
    rows: &[Row],
    max_angles: &[MaxAngleRow],
    meshers: &[String],
    references: &[&str],
    reference_request: f64,
) -> String {
    let mut md = String::new();
    md.push_str("# Table 1 of Sußner & Greiner (IMR 2009), the paper's figures beside ours\n\n");
    md.push_str(
        "Generated by `hexmesh report` from `results.csv` and `maxangle.csv`; do not edit.\n\n",
    );
    md.push_str(
        "Each cell is *triangles at minimum angle (meshing time)*. The three `paper:` columns are \
         copied from the paper's Table 1 (Triangle v1.6 in single and double precision, and the \
         paper's own hexagon mesher on a 2.6 GHz Core2 Duo; the paper does not time Triangle, \
         \"below 0.03 seconds for all data sets\").\n\n",
    );
    let _ = writeln!(
        md,
        "Reference meshers ({}) follow the paper's protocol: the requested minimum angle rises \
         by the step until the mesher fails (error, timeout, or an output below the request); \
         the cell is the last request that worked and its mesh. Our meshers have fixed bounds \
         and run with default parameters; their cell gives the minimum angle measured on the \
         output. `results.csv` has the references at {} ° instead.\n",
        references.join(", "),
        reference_request
    );

    md.push_str(
        "| data set | paper: Triangle single | paper: Triangle double | paper: Hexagon Delaunay |",
    );
    for m in meshers {
        if references.contains(&m.as_str()) {
            let _ = write!(md, " {m} (max angle) |");
        } else {
            let _ = write!(md, " {m} |");
        }
    }
    md.push('\n');
    md.push_str("| --- | --- | --- | --- |");
    for _ in meshers {
        md.push_str(" --- |");
    }
    md.push('\n');
    for paper in &PAPER_TABLE1 {
        let _ = write!(
            md,
            "| {} (`{}`) | {} | {} | {} |",
            paper.label,
            paper.dataset,
            paper.triangle_single.text,
            paper.triangle_double.text,
            paper.hex.text
        );
        for m in meshers {
            let text = if references.contains(&m.as_str()) {
                max_angle_cell(max_angles, paper.dataset, m)
            } else {
                row_cell(rows, paper.dataset, m)
            };
            let _ = write!(md, " {} |", escape_cell(&text));
        }
        md.push('\n');
    }

    md.push_str(
        "\n## Covered area\n\nThe hexagon mesher's dual mesh does not reach the bounding \
         hexagon's corners, so it covers less area than meshers that mesh the whole hexagon \
         (the references mesh the bounding hexagon with the points inside it); triangle \
         counts are only comparable next to this.\n\n",
    );
    md.push_str("| data set |");
    for m in meshers {
        let _ = write!(md, " {m} |");
    }
    md.push_str("\n| --- |");
    for _ in meshers {
        md.push_str(" --- |");
    }
    md.push('\n');
    for paper in &PAPER_TABLE1 {
        let _ = write!(md, "| `{}` |", paper.dataset);
        for m in meshers {
            let text = find_row(rows, paper.dataset, m)
                .and_then(|r| r.covered_area)
                .map_or_else(|| "—".to_string(), |a| format!("{a:.6}"));
            let _ = write!(md, " {text} |");
        }
        md.push('\n');
    }
    md
}

fn find_row<'a>(rows: &'a [Row], dataset: &str, mesher: &str) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.dataset == dataset && r.mesher == mesher)
}

/// `N at θ° (t s)` in the paper's style, from a results row.
fn row_cell(rows: &[Row], dataset: &str, mesher: &str) -> String {
    let Some(r) = find_row(rows, dataset, mesher) else {
        return "not run".to_string();
    };
    if r.err == NOT_RUN {
        return "not run (no segments)".to_string();
    }
    let mut text = match (r.triangles, r.min_angle) {
        (Some(t), Some(a)) => format!("{t} at {a:.2}°{}", time_text(r.time_median_s)),
        (Some(t), None) => format!("{t}{}", time_text(r.time_median_s)),
        _ => String::new(),
    };
    if !r.err.is_empty() {
        if !text.is_empty() {
            text.push_str("; ");
        }
        let what = if r.complete { "note" } else { "failed" };
        let _ = write!(text, "{what}: {}", short(&r.err));
    }
    if text.is_empty() {
        text = "no mesh".to_string();
    }
    text
}

fn max_angle_cell(max_angles: &[MaxAngleRow], dataset: &str, mesher: &str) -> String {
    let Some(m) = max_angles
        .iter()
        .find(|m| m.dataset == dataset && m.mesher == mesher)
    else {
        return "not run".to_string();
    };
    if m.err == NOT_RUN {
        return "not run (no segments)".to_string();
    }
    if !m.err.is_empty() {
        return format!("failed: {}", short(&m.err));
    }
    match (m.angle, m.triangles) {
        (Some(a), Some(t)) => format!("{t} at {a:.2}°{}", time_text(m.time_s)),
        _ => format!("fails at {:.2}°: {}", m.start, short(&m.next_failure)),
    }
}

fn time_text(t: Option<f64>) -> String {
    t.map_or_else(String::new, |s| format!(" ({})", seconds(s)))
}

/// Seconds with three significant digits, as the paper prints them.
pub fn seconds(s: f64) -> String {
    if s >= 100.0 {
        format!("{s:.0} s")
    } else if s >= 10.0 {
        format!("{s:.1} s")
    } else if s >= 1.0 {
        format!("{s:.2} s")
    } else {
        let digits = (2 - s.log10().floor() as i64).clamp(3, 9) as usize;
        format!("{s:.digits$} s")
    }
}

fn short(text: &str) -> String {
    let line = one_line(text);
    const LIMIT: usize = 80;
    if line.chars().count() > LIMIT {
        format!("{}…", line.chars().take(LIMIT).collect::<String>())
    } else {
        line
    }
}

/// A pipe would end the Markdown cell early.
fn escape_cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(dataset: &str, mesher: &str, triangles: u64, angle: f64, t: f64) -> Row {
        let mut r = Row::empty(dataset, 2, mesher, "1");
        r.complete = true;
        r.triangles = Some(triangles);
        r.min_angle = Some(angle);
        r.time_median_s = Some(t);
        r.covered_area = Some(2.5);
        r
    }

    #[test]
    fn paper_figures_match_the_papers_table() {
        // Paper 000, Sec. 8, Table 1: spot checks of every column.
        let cp = paper_row("close-pair").unwrap();
        assert_eq!(cp.triangle_single.triangles, 122);
        assert_eq!(cp.triangle_double.angle, Some(37.0));
        assert_eq!(cp.hex.time_s, Some(0.005));
        let imr = paper_row("imr").unwrap();
        assert_eq!(imr.hex.angle, None);
        assert_eq!(imr.triangle_single.triangles, 2569);
        assert_eq!(paper_row("plane-2k").unwrap().hex.triangles, 268138);
        let order: Vec<_> = PAPER_TABLE1.iter().map(|r| r.dataset).collect();
        assert_eq!(
            order,
            [
                "close-pair",
                "line-100",
                "plane-100",
                "imr",
                "plane-1k",
                "plane-2k"
            ]
        );
    }

    #[test]
    fn table_puts_our_cells_beside_the_papers() {
        let rows = vec![row("close-pair", "hex", 700, 43.9, 0.001)];
        let max = vec![MaxAngleRow {
            dataset: "close-pair".into(),
            mesher: "triangle".into(),
            step: 0.25,
            start: 20.0,
            angle: Some(36.5),
            triangles: Some(120),
            time_s: Some(0.0012),
            next_failure: "timeout after 10 s".into(),
            settings: String::new(),
            err: String::new(),
        }];
        let md = render(
            &rows,
            &max,
            &["hex".into(), "triangle".into()],
            &["triangle"],
            30.0,
        );
        let line = md.lines().find(|l| l.starts_with("| 2 close pts")).unwrap();
        assert_eq!(
            line,
            "| 2 close pts (`close-pair`) | 122 at 36.75° | 131 at 37.00° | 684 at 43.9° (0.005 s) \
             | 700 at 43.90° (0.00100 s) | 120 at 36.50° (0.00120 s) |"
        );
        let plane = md
            .lines()
            .find(|l| l.starts_with("| 100 pts on plane"))
            .unwrap();
        assert!(plane.ends_with("| not run | not run |"), "{plane}");
        assert!(md.contains("| `close-pair` | 2.500000 | — |"), "{md}");
    }

    #[test]
    fn a_reference_failing_at_the_first_step_says_so() {
        let max = vec![MaxAngleRow {
            dataset: "imr".into(),
            mesher: "spade".into(),
            step: 0.25,
            start: 20.0,
            angle: None,
            triangles: None,
            time_s: None,
            next_failure: "error | with pipe".into(),
            settings: String::new(),
            err: String::new(),
        }];
        let md = render(&[], &max, &["spade".into()], &["spade"], 30.0);
        assert!(
            md.contains("| fails at 20.00°: error \\| with pipe |"),
            "{md}"
        );
    }

    #[test]
    fn max_angle_columns_are_the_serialized_field_names() {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(MaxAngleRow {
            dataset: "d".into(),
            mesher: "m".into(),
            step: 0.25,
            start: 20.0,
            angle: None,
            triangles: None,
            time_s: None,
            next_failure: String::new(),
            settings: String::new(),
            err: String::new(),
        })
        .unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        assert_eq!(header, MAX_ANGLE_COLUMNS);
    }

    #[test]
    fn a_mesher_without_segments_is_not_run_on_imr() {
        let mut r = Row::empty("imr", 200, "rhomb", "1");
        r.err = NOT_RUN.into();
        let md = render(&[r], &[], &["rhomb".into()], &[], 30.0);
        let line = md.lines().find(|l| l.starts_with("| IMR-letters")).unwrap();
        assert!(line.ends_with("| not run (no segments) |"), "{line}");
    }

    #[test]
    fn seconds_keep_three_significant_digits() {
        assert_eq!(seconds(123.4), "123 s");
        assert_eq!(seconds(30.44), "30.4 s");
        assert_eq!(seconds(1.034), "1.03 s");
        assert_eq!(seconds(0.21), "0.210 s");
        assert_eq!(seconds(0.005), "0.00500 s");
    }
}
