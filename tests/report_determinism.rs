//! `results.csv` and `pslg.csv` are byte-identical from run to run except for the time and
//! memory columns, and `lsb.csv` and `saalfeld.csv` (which have none) are byte-identical
//! (METHODOLOGY.md "Reproducibility"): the report's deterministic-output promise.

use std::path::{Path, PathBuf};
use std::time::Duration;

use hexmesh::report::pslg::PSLG_COLUMNS;
use hexmesh::report::{run_report, ReportOptions, COLUMNS, VOLATILE_COLUMNS};

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("hexmesh-report-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn tiny(out: &Path) -> ReportOptions {
    let mut datasets = vec!["close-pair".to_string(), "plane-100".to_string()];
    datasets.extend(
        hexmesh::datasets::PSLG_EXAMPLES
            .iter()
            .map(|s| s.to_string()),
    );
    ReportOptions {
        datasets,
        runs: 1,
        out: out.to_path_buf(),
        timeout: Duration::from_secs(60),
        max_angle: false,
        ..ReportOptions::default()
    }
}

/// The CSV with the volatile columns left out, one string per line; `columns` is its header.
fn stable_part(path: &Path, columns: &[&str]) -> Vec<String> {
    let mut rd = csv::Reader::from_path(path).unwrap();
    let header: Vec<String> = rd.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, columns);
    let keep: Vec<usize> = (0..header.len())
        .filter(|&i| !VOLATILE_COLUMNS.contains(&header[i].as_str()))
        .collect();
    rd.records()
        .map(|r| {
            let r = r.unwrap();
            keep.iter().map(|&i| &r[i]).collect::<Vec<_>>().join(",")
        })
        .collect()
}

#[test]
fn results_and_pslg_csv_are_identical_between_runs_except_time_and_memory() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let (a, b) = (temp_dir("det-a"), temp_dir("det-b"));
    run_report(&tiny(&a)).unwrap();
    run_report(&tiny(&b)).unwrap();
    let (ra, rb) = (
        stable_part(&a.join("results.csv"), COLUMNS),
        stable_part(&b.join("results.csv"), COLUMNS),
    );
    let meshers = hexmesh::registry::mesher_names().len();
    assert!(meshers > 0, "no mesher is registered: nothing was compared");
    assert_eq!(ra.len(), 2 * meshers, "one row per dataset × mesher");
    assert_eq!(ra, rb);
    let (pa, pb) = (
        stable_part(&a.join("pslg.csv"), PSLG_COLUMNS),
        stable_part(&b.join("pslg.csv"), PSLG_COLUMNS),
    );
    let segment_meshers = hexmesh::meshers()
        .iter()
        .filter(|m| m.supports_segments())
        .count();
    assert_eq!(
        pa.len(),
        hexmesh::datasets::PSLG_EXAMPLES.len() * segment_meshers,
        "one row per example × segment-keeping mesher"
    );
    assert_eq!(pa, pb);
    // The papers' own comparisons have no time column: byte-identical.
    // lsb.csv: header + 2 datasets × 2 variants; saalfeld.csv: header + 2 datasets.
    for (file, lines) in [("lsb.csv", 5), ("saalfeld.csv", 3)] {
        let read = |d: &Path| std::fs::read_to_string(d.join(file)).unwrap();
        let (x, y) = (read(&a), read(&b));
        assert_eq!(x.lines().count(), lines, "{file}: {x}");
        assert_eq!(x, y, "{file}");
    }
    let readme = |d: &Path| std::fs::read_to_string(d.join("table1.md")).unwrap();
    assert!(readme(&a).contains("| 2 close pts (`close-pair`) |"));
    std::fs::remove_dir_all(&a).unwrap();
    std::fs::remove_dir_all(&b).unwrap();
}
