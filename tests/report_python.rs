//! `results.csv` loads with Python's csv module and with pandas, the tools our users read
//! reports with.

use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

use hexmesh::report::{run_report, ReportOptions, COLUMNS};

/// $HEXMESH_PYTHON, else the project's `.venv` (`make venv`).
fn python() -> PathBuf {
    if let Some(p) = std::env::var_os("HEXMESH_PYTHON") {
        return PathBuf::from(p);
    }
    let venv = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python");
    assert!(
        venv.exists(),
        "no Python with pandas: set HEXMESH_PYTHON or run `make venv`"
    );
    venv
}

#[test]
fn results_csv_loads_in_python_csv_and_pandas() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let out = std::env::temp_dir().join(format!("hexmesh-report-py-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let opts = ReportOptions {
        datasets: vec!["close-pair".into()],
        runs: 1,
        out: out.clone(),
        timeout: Duration::from_secs(60),
        max_angle: false,
        ..ReportOptions::default()
    };
    run_report(&opts).unwrap();
    let csv_path = out.join("results.csv");
    let script = r#"
import csv, sys, pandas
path = sys.argv[1]
with open(path, newline="") as f:
    rows = list(csv.DictReader(f))
df = pandas.read_csv(path)
assert len(df) == len(rows), (len(df), len(rows))
assert df["dataset"].eq("close-pair").all()
assert df["triangles"].dropna().ge(1).all()
print(len(df))
print(",".join(df.columns))
"#;
    let output = Command::new(python())
        .arg("-c")
        .arg(script)
        .arg(&csv_path)
        .output()
        .expect("running Python");
    assert!(
        output.status.success(),
        "python failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8(output.stdout).unwrap();
    let mut lines = stdout.lines();
    let n: usize = lines.next().unwrap().parse().unwrap();
    assert_eq!(n, hexmesh::registry::mesher_names().len());
    assert!(n > 0, "no mesher is registered: nothing was loaded");
    assert_eq!(lines.next().unwrap(), COLUMNS.join(","));
    std::fs::remove_dir_all(&out).unwrap();
}
