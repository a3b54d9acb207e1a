//! `pslg.csv` and its README section: every PSLG example meshed by every registered mesher that
//! keeps segments, one row each, isolated and checked like the `results.csv` cases; the
//! examples stay out of `results.csv`.

use std::collections::HashMap;
use std::time::Duration;

use hexmesh::datasets::{self, PSLG_EXAMPLES, WEDGE_DEG};
use hexmesh::quality::ANGLE_SLACK_DEG;
use hexmesh::report::pslg::PSLG_COLUMNS;
use hexmesh::report::{run_report, ReportOptions};

#[test]
fn every_segment_mesher_gets_a_checked_row_for_every_example_and_the_readme_a_section() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let out = std::env::temp_dir().join(format!("hexmesh-report-pslg-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let opts = ReportOptions {
        datasets: PSLG_EXAMPLES.iter().map(|s| s.to_string()).collect(),
        runs: 1,
        out: out.clone(),
        timeout: Duration::from_secs(60),
        max_angle: false,
        ..ReportOptions::default()
    };
    run_report(&opts).unwrap();

    let mut rd = csv::Reader::from_path(out.join("pslg.csv")).unwrap();
    let header: Vec<String> = rd.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, PSLG_COLUMNS);
    let rows: Vec<HashMap<String, String>> = rd
        .records()
        .map(|r| {
            header
                .iter()
                .cloned()
                .zip(r.unwrap().iter().map(String::from))
                .collect()
        })
        .collect();
    let segment_meshers: Vec<&str> = hexmesh::meshers()
        .iter()
        .filter(|m| m.supports_segments())
        .map(|m| m.name())
        .collect();
    assert!(segment_meshers.contains(&"hex"), "{segment_meshers:?}");
    let got: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r["shape"].as_str(), r["mesher"].as_str()))
        .collect();
    let want: Vec<(&str, &str)> = PSLG_EXAMPLES
        .iter()
        .flat_map(|s| segment_meshers.iter().map(move |m| (*s, *m)))
        .collect();
    assert_eq!(
        got, want,
        "one row per example × segment-keeping mesher, in order"
    );

    let num = |r: &HashMap<String, String>, c: &str| -> f64 {
        r[c].parse()
            .unwrap_or_else(|_| panic!("{} × {}: {c} = {:?}", r["shape"], r["mesher"], r[c]))
    };
    for r in &rows {
        let e = datasets::pslg_example(&r["shape"]).unwrap();
        let what = format!("{} × {}", r["shape"], r["mesher"]);
        assert_eq!(num(r, "domain_area"), e.area, "{what}");
        assert_eq!(num(r, "segments") as usize, e.pslg.segments.len(), "{what}");
        if r["triangles"].is_empty() {
            assert!(!r["err"].is_empty(), "{what}: no mesh and no err");
            continue;
        }
        // The near/interior split partitions the mesh.
        assert_eq!(
            num(r, "near_triangles") + num(r, "interior_triangles"),
            num(r, "triangles"),
            "{what}"
        );
        assert!(num(r, "min_angle") <= num(r, "near_min_angle"), "{what}");
        for c in [
            "validity_violations",
            "conformity_violations",
            "near_obtuse_angles",
            "covered_area",
        ] {
            assert!(!r[c].is_empty(), "{what}: {c} is empty");
        }
        if num(r, "validity_violations") == 0.0 && num(r, "conformity_violations") == 0.0 {
            let area = num(r, "covered_area");
            assert!(
                (area - e.area).abs() < 1e-9 * e.area,
                "{what}: covers {area}"
            );
        }
        // The count of near angles above 90° agrees with the largest near angle.
        if num(r, "near_max_angle") <= 90.0 {
            assert_eq!(num(r, "near_obtuse_angles"), 0.0, "{what}");
        }
        if num(r, "near_max_angle") > 90.0 + 1e-6 {
            assert!(num(r, "near_obtuse_angles") >= 1.0, "{what}");
        }
        if r["shape"] == "pslg-wedge-5" {
            // Every triangulation of the wedge has a triangle in its 5° corner.
            assert!(num(r, "min_angle") <= WEDGE_DEG + 1e-9, "{what}");
        }
    }
    for r in rows.iter().filter(|r| r["mesher"] == "hex") {
        assert_eq!(
            r["bounds_ok"], "true",
            "hex on {}: {}",
            r["shape"], r["problem"]
        );
        assert!(
            num(r, "interior_min_angle") >= hexmesh::quality::HEX.min_angle - ANGLE_SLACK_DEG,
            "{}",
            r["shape"]
        );
    }

    // The examples are not datasets of results.csv: its header and nothing else.
    let results = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert_eq!(results.lines().count(), 1, "{results}");

    let readme = std::fs::read_to_string(out.join("README.md")).unwrap();
    assert!(readme.contains("[`pslg.csv`](pslg.csv)"));
    assert!(readme.contains("## PSLG examples"));
    for e in datasets::pslg_examples() {
        assert!(
            readme.contains(&format!("### `{}`\n\nTests {}.", e.name, e.tests)),
            "{}",
            e.name
        );
    }
    for m in &segment_meshers {
        let lines = readme
            .lines()
            .filter(|l| l.starts_with(&format!("| {m} |")) || l.starts_with(&format!("| {m} ⚠ |")))
            .filter(|l| !l.contains("!["))
            .count();
        assert_eq!(
            lines,
            PSLG_EXAMPLES.len(),
            "{m}: one table line per example"
        );
        // Every segment mesher's mesh of pslg-holes is pictured.
        let file = format!("mesh-pslg-holes-{m}.svg");
        assert!(
            readme.contains(&format!("| {m} | ![{m} on pslg-holes]({file}) |")),
            "{m}: picture of pslg-holes"
        );
        assert!(out.join(&file).is_file(), "{file}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}
