//! `run_report` keeps going when a case fails (a failure is a row with its `err`, rebar's
//! rule) and refuses bad options before it deletes or runs anything.

use std::time::Duration;

use hexmesh::report::{run_report, ReportOptions};
use hexmesh::Error;

#[test]
fn a_timeout_is_a_row_with_its_err_not_a_crash() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let out = std::env::temp_dir().join(format!("hexmesh-report-to-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let opts = ReportOptions {
        datasets: vec!["plane-1k".into()],
        runs: 3,
        out: out.clone(),
        // Too short for any mesher to answer: every case must become a timeout row.
        timeout: Duration::from_micros(1),
        max_angle: false,
        ..ReportOptions::default()
    };
    run_report(&opts).unwrap();
    let mut rd = csv::Reader::from_path(out.join("results.csv")).unwrap();
    let headers = rd.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let rows: Vec<csv::StringRecord> = rd.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), hexmesh::registry::mesher_names().len());
    assert!(!rows.is_empty(), "no mesher is registered");
    for r in &rows {
        assert_eq!(&r[col("complete")], "false", "{r:?}");
        assert!(r[col("err")].contains("timeout"), "{r:?}");
        assert_eq!(&r[col("runs")], "0", "a failed run ends the case: {r:?}");
    }
    assert!(out.join("README.md").exists());
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn an_unknown_dataset_is_refused_before_the_out_dir_is_touched() {
    let out = std::env::temp_dir().join(format!("hexmesh-report-unk-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("results.csv"), "old").unwrap();
    let opts = ReportOptions {
        datasets: vec!["no-such-set".into()],
        out: out.clone(),
        ..ReportOptions::default()
    };
    let err = run_report(&opts).unwrap_err();
    assert!(matches!(err, Error::Usage(_)), "{err}");
    assert!(err.to_string().contains("no-such-set"));
    assert_eq!(
        std::fs::read_to_string(out.join("results.csv")).unwrap(),
        "old"
    );
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn zero_runs_is_a_usage_error() {
    let opts = ReportOptions {
        runs: 0,
        ..ReportOptions::default()
    };
    assert!(matches!(run_report(&opts), Err(Error::Usage(_))));
}

#[test]
fn hex_simple_is_counted_over_ten_seeds_of_a_random_dataset_beside_the_paper() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let out = std::env::temp_dir().join(format!("hexmesh-report-seeds-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let opts = ReportOptions {
        datasets: vec!["plane-100".into()],
        meshers: vec!["hex-simple".into()],
        runs: 1,
        out: out.clone(),
        ..ReportOptions::default()
    };
    run_report(&opts).unwrap();
    let mut rd = csv::Reader::from_path(out.join("seeds.csv")).unwrap();
    let rows: Vec<hexmesh::report::seeds::SeedRow> = rd.deserialize().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), hexmesh::report::seeds::SEEDS as usize);
    let first = hexmesh::datasets::default_seed("plane-100").unwrap();
    for (s, r) in rows.iter().enumerate() {
        assert_eq!(r.seed, first + s as u64);
        assert!(
            r.err.is_empty() && r.bounds_passed && r.triangles > 0,
            "{r:?}"
        );
    }
    let distinct: std::collections::BTreeSet<usize> = rows.iter().map(|r| r.triangles).collect();
    assert!(distinct.len() > 1, "ten seeds gave one count: {distinct:?}");
    let table = std::fs::read_to_string(out.join("table1.md")).unwrap();
    assert!(
        table.contains("| `plane-100` | hex-simple | 12748 at 43.9° (0.21 s) |"),
        "{table}"
    );
    std::fs::remove_dir_all(&out).unwrap();
}
