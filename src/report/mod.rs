//! `hexmesh report`: every registered mesher on every dataset, each case in a child process,
//! checked against what its mesher promises, written as CSV, the paper's Table 1 (Sec. 8),
//! plots, mesh pictures in the manner of Fig. 15 and a README generated from the data.
//!
//! - `row`: the `results.csv` schema.
//! - `stats`: median/min/max of runs, power-law exponents.
//! - `table1`: the paper's Table 1 and `table1.md`.
//! - `plot`: angle distributions and scaling plots (SVG + PNG).
//! - `readme`: the generated `README.md`.
//! - `progress`: a progress bar on a terminal, plain lines otherwise.
//! - `lsb`, `saalfeld`: the comparisons papers 003 and 002 make (angle descent, points added).
//! - `pslg`: the PSLG examples meshed by every mesher that keeps segments (`pslg.csv`).
//! - `run`: the cases, isolated and checked; `run_report` ties everything together.

mod case;
pub mod lsb;
pub mod plot;
pub mod progress;
pub mod pslg;
pub mod readme;
pub mod row;
mod run;
pub mod saalfeld;
pub mod seeds;
pub mod stats;
pub mod table1;

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::error::{Error, Result};
use crate::mesher::Params;

pub(crate) use case::first_problem;
pub use row::{Row, COLUMNS, VOLATILE_COLUMNS};
pub use run::run_report;
pub use table1::MaxAngleRow;

/// The reference quality meshers: asked for [`REFERENCE_MIN_ANGLE`] in `results.csv` and put
/// through the paper's max-angle protocol for `table1.md`. Every other mesher runs with
/// default parameters: ours because their bounds are fixed by their algorithm,
/// `cgal-conforming` because it makes a conforming Delaunay triangulation and refines for no
/// angle at all.
pub const REFERENCES: &[&str] = &["cgal", "triangle", "spade"];

/// The minimum angle the references are asked for in `results.csv` (degrees).
pub const REFERENCE_MIN_ANGLE: f64 = 30.0;

/// What a mesher is asked for in `results.csv` and the benches, and how a row spells it:
/// a reference the [`REFERENCE_MIN_ANGLE`], any other mesher nothing (its bounds are fixed).
pub fn case_params(mesher: &str) -> (Params, String) {
    if REFERENCES.contains(&mesher) {
        (
            Params::default().with_min_angle(REFERENCE_MIN_ANGLE),
            format!("min_angle={REFERENCE_MIN_ANGLE}"),
        )
    } else {
        (Params::default(), "default".to_string())
    }
}

/// What `hexmesh report` runs and where it writes.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportOptions {
    /// Dataset names (`datasets::by_name`): the paper's datasets go to `results.csv`, the PSLG
    /// examples (`datasets::PSLG_EXAMPLES`) to `pslg.csv`. Empty means `datasets::SMALL` and
    /// every PSLG example.
    pub datasets: Vec<String>,
    /// Mesher names (`registry::mesher`); empty means every registered mesher.
    pub meshers: Vec<String>,
    /// Times each case is meshed; the report gives median, min and max.
    pub runs: usize,
    /// Adds `datasets::SCALING` (plane-10k/100k/1m) and draws the scaling plot.
    pub scaling: bool,
    /// The reports directory; its generated files are replaced whole.
    pub out: PathBuf,
    /// Time one meshing call may take before its child is killed and the row says so.
    pub timeout: Duration,
    /// Step of the max-angle protocol in degrees (the paper's 0.25°).
    pub max_angle_step: f64,
    /// First angle the max-angle protocol requests, degrees.
    pub max_angle_start: f64,
    /// Time one request of the max-angle protocol may take before it counts as a failure.
    pub max_angle_timeout: Duration,
    /// Runs the max-angle protocol for `table1.md`; without it the references' Table 1 cells
    /// say "not run".
    pub max_angle: bool,
    /// Triangle's switches for the `triangle` rows of `results.csv` and `pslg.csv`
    /// (`Params::switches`); without a `q`, since the report asks for its own angle.
    pub triangle_switches: Option<String>,
}

impl Default for ReportOptions {
    fn default() -> ReportOptions {
        ReportOptions {
            datasets: Vec::new(),
            meshers: Vec::new(),
            runs: 3,
            scaling: false,
            out: PathBuf::from("reports"),
            timeout: Duration::from_secs(180),
            max_angle_step: 0.25,
            max_angle_start: 20.0,
            max_angle_timeout: Duration::from_secs(10),
            max_angle: true,
            triangle_switches: None,
        }
    }
}

/// True for the names of files `run_report` generates: only these are deleted before a
/// new report is written, so a user's own files in the directory survive.
pub fn is_generated_file(name: &str) -> bool {
    let fixed = [
        "results.csv",
        "maxangle.csv",
        "lsb.csv",
        "saalfeld.csv",
        "seeds.csv",
        "pslg.csv",
        "table1.md",
        "README.md",
    ];
    fixed.contains(&name)
        || (name.starts_with("angles-") && (name.ends_with(".svg") || name.ends_with(".png")))
        || name == "scaling.svg"
        || name == "scaling.png"
        || (name.starts_with("mesh-") && name.ends_with(".svg"))
}

/// Creates `dir` and deletes the files an earlier report generated there, so that no stale
/// picture of a mesher or dataset no longer run survives.
pub fn clear_generated(dir: &Path) -> Result<()> {
    let io = |e: std::io::Error| Error::Io {
        path: dir.to_path_buf(),
        source: e,
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    for entry in std::fs::read_dir(dir).map_err(io)? {
        let entry = entry.map_err(io)?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if is_generated_file(name) && entry.file_type().map_err(io)?.is_file() {
            let path = entry.path();
            std::fs::remove_file(&path).map_err(|e| Error::Io { path, source: e })?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_are_asked_for_30_degrees_and_ours_for_nothing() {
        let (p, s) = case_params("triangle");
        assert_eq!((p.min_angle, s.as_str()), (Some(30.0), "min_angle=30"));
        let (p, s) = case_params("hex");
        assert_eq!((p, s.as_str()), (Params::default(), "default"));
    }

    #[test]
    fn only_generated_files_are_cleared() {
        let dir = std::env::temp_dir().join(format!("hexmesh-clear-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for f in [
            "results.csv",
            "pslg.csv",
            "angles-imr.png",
            "mesh-imr-hex-zoom.svg",
            "scaling.svg",
            "notes.txt",
            "angles.txt",
        ] {
            std::fs::write(dir.join(f), "x").unwrap();
        }
        clear_generated(&dir).unwrap();
        let mut left: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(left, ["angles.txt", "notes.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
