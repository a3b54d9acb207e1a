//! One row of `results.csv` per dataset × mesher, the schema the rest of the report is
//! generated from (rebar's habit: a failure is a row with its `err`, never a missing row).
//!
//! Column names follow Verdict, not the paper, where the two differ: `radius_ratio_max` is
//! R/(2r) (1 for equilateral; the paper's "aspect ratio" bound 1.20787 of Sec. 6 is this
//! quantity), `edge_ratio_max` is longest/shortest edge of a triangle.

use std::path::Path;

use serde::Serialize;

use crate::error::{Error, Result};

/// The columns whose values depend on the machine and the moment: everything else in
/// `results.csv` is byte-identical from run to run.
pub const VOLATILE_COLUMNS: &[&str] = &["time_median_s", "time_min_s", "time_max_s", "peak_rss_mb"];

/// The `err` of a case that was not attempted (a mesher that cannot take the input).
pub const NOT_RUN: &str = "not run: the mesher does not keep input segments";

/// One dataset × mesher case. `None` fields are written as empty cells (pandas reads NaN).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    pub dataset: String,
    /// Input points of the dataset (the x axis of the scaling plot).
    pub points: u64,
    pub mesher: String,
    pub version: String,
    /// What the harness asked for, in `Params` terms: `default` or `min_angle=30`.
    pub params: String,
    /// What the mesher says it did with that, in its own terms (`Mesher::settings`).
    pub settings: String,
    /// The mesher finished (no budget stop, no timeout, no error).
    pub complete: bool,
    /// Why the case failed or stopped early; empty when it did not.
    pub err: String,
    pub vertices: Option<u64>,
    /// Vertices that are not input points: what the mesher added (for a point set this counts
    /// the bounding hexagon's corners too). Saalfeld's and CGAL's conforming Delaunay
    /// triangulations compare on this column (paper 002).
    pub steiner_points: Option<u64>,
    pub triangles: Option<u64>,
    pub covered_area: Option<f64>,
    /// Degrees.
    pub min_angle: Option<f64>,
    /// Degrees.
    pub max_angle: Option<f64>,
    /// Verdict's radius ratio R/(2r), the worst triangle.
    pub radius_ratio_max: Option<f64>,
    /// Longest over shortest edge of a triangle, the worst triangle.
    pub edge_ratio_max: Option<f64>,
    pub shortest_edge: Option<f64>,
    /// Closest distance between two input points.
    pub d_min: Option<f64>,
    pub shortest_over_dmin: Option<f64>,
    /// Interior edges whose opposite vertex lies strictly inside the circumcircle (exact).
    pub delaunay_exact_violations: Option<u64>,
    /// Interior edges whose opposite angles sum to more than 180° + 1e-7°.
    pub delaunay_tol_violations: Option<u64>,
    /// On a PSLG, the angles of the triangles that touch no segment, where the hexagon
    /// bounds hold (paper Sec. 7); empty for point sets.
    pub interior_min_angle: Option<f64>,
    pub interior_max_angle: Option<f64>,
    /// Number of validity violations (0 = a valid mesh).
    pub valid: Option<u64>,
    /// The verdict passed: the mesh is valid and every bound its mesher promises holds
    /// for the run's parameters (`Mesher::promise`; on a PSLG the shape bounds are checked away from
    /// the segments).
    pub bounds_ok: Option<bool>,
    /// The first thing the verdict found wrong: a validity violation, else a failed bound
    /// with its value and limit; empty when it passed.
    pub problem: String,
    pub time_median_s: Option<f64>,
    pub time_min_s: Option<f64>,
    pub time_max_s: Option<f64>,
    /// Peak resident memory of the child process that meshed (the largest over the runs).
    pub peak_rss_mb: Option<f64>,
    /// Runs that completed and were timed.
    pub runs: u64,
}

impl Row {
    /// A row with only its identity filled in: what a case that failed before measuring
    /// anything reports, next to its `err`.
    pub fn empty(dataset: &str, points: usize, mesher: &str, version: &str) -> Row {
        Row {
            dataset: dataset.to_string(),
            points: points as u64,
            mesher: mesher.to_string(),
            version: version.to_string(),
            params: String::new(),
            settings: String::new(),
            complete: false,
            err: String::new(),
            vertices: None,
            steiner_points: None,
            triangles: None,
            covered_area: None,
            min_angle: None,
            max_angle: None,
            radius_ratio_max: None,
            edge_ratio_max: None,
            shortest_edge: None,
            d_min: None,
            shortest_over_dmin: None,
            delaunay_exact_violations: None,
            delaunay_tol_violations: None,
            interior_min_angle: None,
            interior_max_angle: None,
            valid: None,
            bounds_ok: None,
            problem: String::new(),
            time_median_s: None,
            time_min_s: None,
            time_max_s: None,
            peak_rss_mb: None,
            runs: 0,
        }
    }
}

/// The columns of `results.csv`, in order (the field names of [`Row`]).
pub const COLUMNS: &[&str] = &[
    "dataset",
    "points",
    "mesher",
    "version",
    "params",
    "settings",
    "complete",
    "err",
    "vertices",
    "steiner_points",
    "triangles",
    "covered_area",
    "min_angle",
    "max_angle",
    "radius_ratio_max",
    "edge_ratio_max",
    "shortest_edge",
    "d_min",
    "shortest_over_dmin",
    "delaunay_exact_violations",
    "delaunay_tol_violations",
    "interior_min_angle",
    "interior_max_angle",
    "valid",
    "bounds_ok",
    "problem",
    "time_median_s",
    "time_min_s",
    "time_max_s",
    "peak_rss_mb",
    "runs",
];

/// Writes `rows` as CSV under the header `columns`, which is written even when there are no
/// rows, so that an empty report still loads in pandas. Errors and settings strings may hold
/// commas, quotes or newlines; the csv crate quotes them, which Python's csv module reads.
pub fn write_csv<T: Serialize>(path: &Path, columns: &[&str], rows: &[T]) -> Result<()> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_path(path)
        .map_err(|e| csv_error(path, e))?;
    w.write_record(columns).map_err(|e| csv_error(path, e))?;
    for row in rows {
        w.serialize(row).map_err(|e| csv_error(path, e))?;
    }
    w.flush().map_err(|e| Error::Io {
        path: path.to_path_buf(),
        source: e,
    })
}

fn csv_error(path: &Path, e: csv::Error) -> Error {
    let message = e.to_string();
    match e.into_kind() {
        csv::ErrorKind::Io(source) => Error::Io {
            path: path.to_path_buf(),
            source,
        },
        _ => Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::other(format!("writing CSV: {message}")),
        },
    }
}

/// Single-line text for a CSV cell and a Markdown table: newlines would break the table and
/// a child's stderr tail can have many.
pub fn one_line(text: &str) -> String {
    let joined = text.split_whitespace().collect::<Vec<_>>().join(" ");
    const LIMIT: usize = 300;
    if joined.chars().count() > LIMIT {
        let cut: String = joined.chars().take(LIMIT).collect();
        format!("{cut}…")
    } else {
        joined
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn made_up_row() -> Row {
        let mut r = Row::empty("plane-100", 100, "hex", "0.1.0");
        r.params = "default".into();
        r.settings = "extended refinement, 43.9°-90°".into();
        r.complete = true;
        r.vertices = Some(6000);
        r.triangles = Some(12000);
        r.min_angle = Some(43.9);
        r.time_median_s = Some(0.01);
        r.runs = 3;
        r
    }

    #[test]
    fn csv_header_names_every_column_in_schema_order() {
        let dir = std::env::temp_dir().join(format!("hexmesh-row-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("r.csv");
        write_csv(&path, COLUMNS, &[made_up_row()]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let header = text.lines().next().unwrap();
        assert!(header.starts_with("dataset,points,mesher,version,params,settings,complete,err,"));
        assert!(header.ends_with("time_median_s,time_min_s,time_max_s,peak_rss_mb,runs"));
        for c in VOLATILE_COLUMNS {
            assert!(header.split(',').any(|h| h == *c), "{c} missing");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn columns_are_the_serialized_field_names() {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(made_up_row()).unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        assert_eq!(header, COLUMNS);
    }

    #[test]
    fn an_empty_report_still_has_its_header() {
        let dir = std::env::temp_dir().join(format!("hexmesh-row-e-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("r.csv");
        write_csv::<Row>(&path, COLUMNS, &[]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.trim_end(), COLUMNS.join(","));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn errors_with_commas_and_newlines_stay_one_quoted_cell() {
        let dir = std::env::temp_dir().join(format!("hexmesh-row-q-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("r.csv");
        let mut r = made_up_row();
        r.err = "child died, signal 6\n\"abort\"".into();
        write_csv(&path, COLUMNS, &[r]).unwrap();
        let mut rd = csv::Reader::from_path(&path).unwrap();
        let rec = rd.records().next().unwrap().unwrap();
        assert_eq!(&rec[7], "child died, signal 6\n\"abort\"");
        assert_eq!(rec.len(), rd.headers().unwrap().len());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn one_line_folds_whitespace_and_caps_length() {
        assert_eq!(one_line("a\n  b\tc"), "a b c");
        assert_eq!(one_line(&"x ".repeat(400)).chars().count(), 301);
    }
}
