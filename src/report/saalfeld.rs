//! Paper 002's comparison (Saalfeld, "Delaunay Edge Refinements"): how many points a conforming
//! Delaunay triangulation adds. `saalfeld` (Sec. 6, the iteration) and `cgal-conforming` come
//! from their `results.csv` rows; the constructive refinement of Sec. 5 (`saalfeld-sec5`) is run
//! here, isolated like every other case, and checked against the same bounds.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use serde::Serialize;

use super::row::{one_line, Row, NOT_RUN};
use crate::mesh::Pslg;
use crate::quality;
use crate::{isolate, Params};

/// The variant name of the Sec. 5 construction (`registry::variants`).
pub const SEC5: &str = "saalfeld-sec5";

/// The columns of `saalfeld.csv`.
pub const SAALFELD_COLUMNS: &[&str] = &[
    "dataset",
    "points",
    "sec6_added",
    "sec5_added",
    "cgal_conforming_added",
    "sec5_bounds_ok",
    "err",
];

/// One dataset: the vertices each conforming Delaunay mesher adds beyond the input points
/// (for a point set the bounding hexagon's six corners are among them, for all three alike).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SaalfeldRow {
    pub dataset: String,
    pub points: u64,
    pub sec6_added: Option<u64>,
    pub sec5_added: Option<u64>,
    pub cgal_conforming_added: Option<u64>,
    /// The Sec. 5 mesh passed `verify --bounds saalfeld-sec5` (valid, conforming, Delaunay).
    pub sec5_bounds_ok: Option<bool>,
    /// Why a figure is missing (a failed or stopped case), `; `-joined.
    pub err: String,
}

fn added(rows: &[Row], dataset: &str, mesher: &str, errs: &mut Vec<String>) -> Option<u64> {
    let r = rows
        .iter()
        .find(|r| r.dataset == dataset && r.mesher == mesher)?;
    if !r.complete && !r.err.is_empty() && r.err != NOT_RUN {
        errs.push(format!("{mesher}: {}", one_line(&r.err)));
    }
    r.complete.then_some(r.steiner_points).flatten()
}

/// One row per dataset: the Sec. 6 and `cgal-conforming` figures from `rows`, the Sec. 5
/// construction meshed in a child of `exe` (at most `timeout`) and checked.
pub fn saalfeld_rows(
    exe: &Path,
    inputs: &[(String, Pslg)],
    rows: &[Row],
    timeout: Duration,
    mut progress: impl FnMut(&str),
) -> Vec<SaalfeldRow> {
    let bounds = crate::registry::bounds(SEC5).ok();
    inputs
        .iter()
        .map(|(name, input)| {
            progress(&format!("{name} × {SEC5}"));
            let mut errs = Vec::new();
            let sec6_added = added(rows, name, "saalfeld", &mut errs);
            let cgal_conforming_added = added(rows, name, "cgal-conforming", &mut errs);
            let (mut sec5_added, mut sec5_bounds_ok) = (None, None);
            match isolate::run_isolated(exe, SEC5, input, &Params::default(), timeout) {
                Ok(iso) if iso.run.complete => {
                    let mesh = &iso.run.mesh;
                    sec5_added =
                        Some(mesh.vertices.len().saturating_sub(input.points.len()) as u64);
                    sec5_bounds_ok =
                        Some(quality::verdict(mesh, Some(input), bounds.as_ref()).passed());
                }
                Ok(iso) => errs.push(format!(
                    "{SEC5} stopped early: {}",
                    iso.run
                        .stop_reason
                        .as_ref()
                        .map_or("no reason given".into(), ToString::to_string)
                )),
                Err(e) => errs.push(format!("{SEC5}: {e}")),
            }
            SaalfeldRow {
                dataset: name.clone(),
                points: input.points.len() as u64,
                sec6_added,
                sec5_added,
                cgal_conforming_added,
                sec5_bounds_ok,
                err: one_line(&errs.join("; ")),
            }
        })
        .collect()
}

/// The README section.
pub fn render(rows: &[SaalfeldRow]) -> String {
    let mut md = String::from(
        "\n## Conforming Delaunay: points added (paper 002)\n\n\
         Vertices each conforming Delaunay triangulation adds beyond the input points (for a \
         point set the bounding hexagon's six corners are among them): `saalfeld` iterates \
         Delaunay triangulation and segment crossings (Sec. 6), `saalfeld-sec5` is the \
         constructive refinement of Sec. 5 (circles of radius ε/3 around the vertices, then \
         pieces shorter than δ), `cgal-conforming` is CGAL's `make_conforming_Delaunay_2`. \
         The Sec. 5 mesh is checked like the others (valid, conforming, zero exact Delaunay \
         violations). Data: `saalfeld.csv`.\n\n\
         | dataset | points | saalfeld (Sec. 6) | saalfeld-sec5 (Sec. 5) | cgal-conforming | Sec. 5 bounds |\n\
         | --- | ---: | ---: | ---: | ---: | --- |\n",
    );
    let count = |v: Option<u64>| v.map_or_else(|| "—".to_string(), |v| v.to_string());
    for r in rows {
        let ok = match r.sec5_bounds_ok {
            Some(true) => "ok",
            Some(false) => "FAIL",
            None => "—",
        };
        let _ = writeln!(
            md,
            "| `{}` | {} | {} | {} | {} | {ok} |",
            r.dataset,
            r.points,
            count(r.sec6_added),
            count(r.sec5_added),
            count(r.cgal_conforming_added),
        );
    }
    for r in rows.iter().filter(|r| !r.err.is_empty()) {
        let _ = writeln!(md, "\n- `{}`: {}", r.dataset, r.err);
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_section_sets_the_three_counts_side_by_side_and_names_failures() {
        let rows = vec![
            SaalfeldRow {
                dataset: "imr".into(),
                points: 119,
                sec6_added: Some(32),
                sec5_added: Some(900),
                cgal_conforming_added: Some(13),
                sec5_bounds_ok: Some(true),
                err: String::new(),
            },
            SaalfeldRow {
                dataset: "line-100".into(),
                points: 100,
                sec6_added: Some(6),
                sec5_added: None,
                cgal_conforming_added: Some(6),
                sec5_bounds_ok: None,
                err: "saalfeld-sec5: timeout after 60s".into(),
            },
        ];
        let md = render(&rows);
        assert!(md.contains("| `imr` | 119 | 32 | 900 | 13 | ok |"), "{md}");
        assert!(md.contains("| `line-100` | 100 | 6 | — | 6 | — |"), "{md}");
        assert!(
            md.contains("- `line-100`: saalfeld-sec5: timeout after 60s"),
            "{md}"
        );
    }

    #[test]
    fn added_counts_come_from_complete_rows_only() {
        let mut good = Row::empty("imr", 119, "saalfeld", "1");
        good.complete = true;
        good.steiner_points = Some(32);
        let mut bad = Row::empty("imr", 119, "cgal-conforming", "1");
        bad.err = "timeout after 60s".into();
        bad.steiner_points = Some(5);
        let rows = [good, bad];
        let mut errs = Vec::new();
        assert_eq!(added(&rows, "imr", "saalfeld", &mut errs), Some(32));
        assert_eq!(added(&rows, "imr", "cgal-conforming", &mut errs), None);
        assert_eq!(errs, ["cgal-conforming: timeout after 60s"]);
        assert_eq!(added(&rows, "imr", "lsb", &mut errs), None);
    }
}
