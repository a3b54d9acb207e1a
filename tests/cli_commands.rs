//! The commands end to end, as a user runs them: mesh with every registered mesher then verify
//! against its promise, max-angle, fuzz, and the hexagon picture.

use std::path::PathBuf;
use std::process::{Command, Output};

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

/// A path in this test binary's own scratch directory under target/ (one fixed place, so
/// that runs do not leave a copy in /tmp each time), with the files an earlier run wrote
/// under it (`NAME.*`) removed, so that a test sees only what its own commands write.
fn temp(name: &str) -> PathBuf {
    let dir = scratch();
    std::fs::create_dir_all(&dir).expect("temp dir");
    let stem = format!("{name}.");
    for entry in std::fs::read_dir(&dir).expect("read temp dir").flatten() {
        if entry.file_name().to_string_lossy().starts_with(&stem) {
            std::fs::remove_file(entry.path()).expect("remove an earlier run's file");
        }
    }
    let path = dir.join(name);
    if path.is_dir() {
        std::fs::remove_dir_all(&path).expect("remove an earlier run's directory");
    }
    path
}

/// This test binary's scratch directory under target/.
fn scratch() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_commands")
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr)
}

#[test]
fn the_variants_mesh_by_name_and_lsbs_descent_bound_needs_the_input() {
    for name in ["saalfeld-sec5", "lsb-plain", "lsb"] {
        let prefix = temp(&format!("imr-{name}"));
        let p = prefix.to_str().expect("utf-8");
        let out = hexmesh(&["mesh", "datasets/imr.poly", "--mesher", name, "-o", p]);
        assert!(out.status.success(), "{name}: {}", text(&out));
        let out = hexmesh(&[
            "verify",
            p,
            "--input",
            "datasets/imr.poly",
            "--bounds",
            name,
        ]);
        assert!(out.status.success(), "{name}:\n{}", text(&out));
        let shown = text(&out);
        if name.starts_with("lsb") {
            let line = shown
                .lines()
                .find(|l| l.contains("lsb descent"))
                .unwrap_or_else(|| panic!("{name}: no descent check in\n{shown}"));
            assert!(
                line.ends_with("ok") && line.contains("≥ 0.5000000"),
                "{line}"
            );
            let out = hexmesh(&["verify", p, "--bounds", name]);
            let line = text(&out)
                .lines()
                .find(|l| l.contains("lsb descent"))
                .map(String::from)
                .unwrap_or_default();
            assert!(line.contains("skipped: needs the input"), "{line}");
        } else {
            assert!(shown.contains("non-Delaunay edges (exact)"), "{shown}");
        }
    }
    let out = hexmesh(&["meshers"]);
    assert!(
        text(&out).contains("saalfeld-sec5    hexmesh"),
        "{}",
        text(&out)
    );
}

#[test]
fn every_registered_mesher_meshes_and_verifies_against_its_own_bounds() {
    for name in hexmesh::mesher_names() {
        let prefix = temp(&format!("plane-100-{name}"));
        let p = prefix.to_str().expect("utf-8");
        let mut args = vec!["mesh", "datasets/plane-100.node", "--mesher", name, "-o", p];
        args.extend(["--format", "node,vtk,msh,svg", "--timeout", "120"]);
        let reference = matches!(name, "cgal" | "triangle" | "spade");
        if reference {
            args.extend(["--min-angle", "30"]);
        }
        let out = hexmesh(&args);
        assert!(out.status.success(), "{name}: {}", text(&out));
        for ext in ["node", "ele", "vtk", "msh", "svg"] {
            assert!(prefix.with_extension(ext).exists(), "{name}: no .{ext}");
        }
        let bounds = if reference {
            "min-angle=30".to_string()
        } else {
            name.to_string()
        };
        let out = hexmesh(&[
            "verify",
            p,
            "--input",
            "datasets/plane-100.node",
            "--bounds",
            &bounds,
        ]);
        assert!(
            out.status.success(),
            "{name} fails its bounds:\n{}",
            text(&out)
        );
    }
}

#[test]
fn every_pslg_example_meshes_and_verifies_by_name() {
    for name in hexmesh::datasets::PSLG_EXAMPLES {
        let prefix = temp(&format!("{name}-hex"));
        let p = prefix.to_str().expect("utf-8");
        let out = hexmesh(&["mesh", name, "--mesher", "hex", "-o", p]);
        assert!(out.status.success(), "{name}: {}", text(&out));
        let out = hexmesh(&["verify", p, "--input", name, "--bounds", "hex"]);
        assert!(out.status.success(), "{name}:\n{}", text(&out));
    }
    // --input resolves the name to that example, not to any PSLG: against another one the
    // holes mesh misses input points and covers a hole seed.
    let p = scratch().join("pslg-holes-hex");
    let p = p.to_str().expect("utf-8");
    let out = hexmesh(&["verify", p, "--input", "pslg-nested", "--bounds", "hex"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(text(&out).contains("FAIL"), "{}", text(&out));
}

#[test]
fn a_timeout_stops_a_mesher_that_does_not_terminate_and_writes_nothing() {
    let prefix = temp("close-pair-triangle-44");
    let p = prefix.to_str().expect("utf-8");
    let out = hexmesh(&[
        "mesh",
        "close-pair",
        "--mesher",
        "triangle",
        "--min-angle",
        "44",
        "--timeout",
        "0.5",
        "-o",
        p,
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(text(&out).contains("timeout"), "{}", text(&out));
    assert!(!prefix.with_extension("ele").exists());
}

#[test]
fn max_angle_prints_a_row_and_json() {
    let out = hexmesh(&[
        "max-angle",
        "close-pair",
        "--mesher",
        "triangle",
        "--start",
        "30",
        "--step",
        "1",
        "--timeout",
        "2",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let json = stdout.lines().last().expect("a JSON line");
    let v: serde_json::Value = serde_json::from_str(json).expect("JSON");
    let angle = v["angle"].as_f64().expect("an angle");
    assert!((30.0..45.0).contains(&angle), "{angle}");
    assert!(v["triangles"].as_u64().is_some_and(|t| t > 0));
    // The effective settings of the last good request: Triangle's switch string at that angle.
    let settings = v["settings"].as_str().expect("settings");
    assert!(
        settings.contains(&format!("triangulate(\"pzAQaq{angle}\")"))
            && settings.contains("2s timeout"),
        "{settings}"
    );
}

#[test]
fn fuzz_runs_a_small_campaign_and_summarises_it() {
    let out = hexmesh(&[
        "fuzz",
        "--mesher",
        "hex-simple",
        "--cases",
        "40",
        "--seed",
        "7",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let t = text(&out);
    assert!(
        t.contains("40 cases (seed 7)") && t.contains("0 failed"),
        "{t}"
    );
    assert!(t.contains("worst angles seen"), "{t}");
}

#[test]
fn fuzz_writes_failing_cases_only_into_out_and_only_when_asked() {
    let help = text(&hexmesh(&["fuzz", "--help"]));
    assert!(
        help.contains("--out <DIR>") && help.contains("no files are written"),
        "{help}"
    );
    // A campaign that passes writes nothing, not even the directory.
    let dir = temp("fuzz-out");
    let out = hexmesh(&[
        "fuzz",
        "--mesher",
        "hex-simple",
        "--cases",
        "20",
        "--out",
        dir.to_str().expect("utf-8"),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    assert!(!dir.exists());
}

#[test]
fn the_hexagon_picture_is_drawn_for_hex_simple_and_refused_for_others() {
    let prefix = temp("close-pair-hex-simple");
    let svg = temp("close-pair-hexagons.svg");
    let (p, s) = (
        prefix.to_str().expect("utf-8"),
        svg.to_str().expect("utf-8"),
    );
    let out = hexmesh(&[
        "mesh",
        "close-pair",
        "--mesher",
        "hex-simple",
        "-o",
        p,
        "--hexagons",
        s,
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let picture = std::fs::read_to_string(&svg).expect("picture written");
    assert!(picture.starts_with("<svg") || picture.starts_with("<?xml"));
    assert!(picture.matches("<polygon").count() > 10, "hexagons drawn");
    let out = hexmesh(&[
        "mesh",
        "close-pair",
        "--mesher",
        "spade",
        "-o",
        p,
        "--hexagons",
        s,
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
}

#[test]
fn mesh_exits_1_when_its_mesh_misses_the_requested_angle_and_says_which() {
    // On the sliver, spade splits the long side once and keeps both 1e-7° input corners
    // whole, which a minimum angle leaves out; Triangle cuts slivers that are no input corner.
    let sliver = "tests/fixtures/refs/sliver_pslg.poly";
    let prefix = temp("whole-corners-spade");
    let p = prefix.to_str().expect("utf-8");
    let out = hexmesh(&[
        "mesh",
        sliver,
        "--mesher",
        "spade",
        "--min-angle",
        "25",
        "-o",
        p,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let out = hexmesh(&["verify", p, "--input", sliver, "--bounds", "min-angle=25"]);
    assert!(
        text(&out).contains("2 angles at input corners"),
        "{}",
        text(&out)
    );
    for (input, mesher) in [
        (sliver, "triangle"),
        ("tests/fixtures/refs/translated_close_points.node", "spade"),
    ] {
        let prefix = temp(&format!("missed-angle-{mesher}"));
        let p = prefix.to_str().expect("utf-8");
        let out = hexmesh(&[
            "mesh",
            input,
            "--mesher",
            mesher,
            "--min-angle",
            "25",
            "-o",
            p,
            "--timeout",
            "60",
        ]);
        let t = text(&out);
        assert_eq!(out.status.code(), Some(1), "{input} {mesher}: {t}");
        assert!(t.contains("fails --bounds min-angle=25: min angle"), "{t}");
        // Written for inspection, and verify agrees.
        let out = hexmesh(&["verify", p, "--input", input, "--bounds", "min-angle=25"]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out));
        // --no-check skips the check, as before.
        let out = hexmesh(&[
            "mesh",
            input,
            "--mesher",
            mesher,
            "--min-angle",
            "25",
            "-o",
            p,
            "--no-check",
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    }
}

#[test]
fn a_cgal_exception_is_an_error_of_mesh_and_an_error_row_of_max_angle() {
    let input = "tests/fixtures/refs/sliver_pslg.poly";
    let prefix = temp("sliver-cgal");
    let out = hexmesh(&[
        "mesh",
        input,
        "--mesher",
        "cgal",
        "-o",
        prefix.to_str().expect("utf-8"),
    ]);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(2), "{t}");
    assert!(
        t.contains("mesher cgal: CGAL: CGAL ERROR: assertion violation"),
        "{t}"
    );
    assert!(
        !t.contains("panicked") && !t.contains("terminate called"),
        "{t}"
    );
    assert!(!prefix.with_extension("ele").exists());

    let out = hexmesh(&["max-angle", input, "--mesher", "cgal", "--timeout", "10"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    let mut lines = stdout.lines();
    let row = lines.next().expect("the row");
    assert!(
        row.starts_with("cgal: no angle met; 20.00° failed: error: CGAL: CGAL ERROR"),
        "{row}"
    );
    let v: serde_json::Value =
        serde_json::from_str(lines.next().expect("the JSON line")).expect("JSON");
    assert!(v["angle"].is_null(), "{v}");
    assert!(
        v["failure"]
            .as_str()
            .is_some_and(|f| f.contains("Refine_edges.h")),
        "{v}"
    );
    assert!(lines.next().is_none(), "{stdout}");
}

#[test]
fn triangle_dying_and_cgal_throwing_on_a_lattice_input_are_errors_not_crashes() {
    let input = "tests/fixtures/refs/lattice_triangle_segfault.node";
    let prefix = temp("lattice");
    let p = prefix.to_str().expect("utf-8");
    let out = hexmesh(&["mesh", input, "--mesher", "triangle", "-o", p]);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(2), "{t}");
    assert!(
        t.contains("mesher triangle: isolated child was killed by signal 11"),
        "{t}"
    );
    let out = hexmesh(&["mesh", input, "--mesher", "cgal", "-o", p]);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(2), "{t}");
    assert!(t.contains("CGAL ERROR: assertion violation"), "{t}");
    assert!(!prefix.with_extension("ele").exists());
    // spade finishes and calls its mesh complete, but it has a sliver along the hexagon's edge
    // (points an ulp inside it), far below its default 30°: mesh says so.
    let out = hexmesh(&["mesh", input, "--mesher", "spade", "-o", p]);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(1), "{t}");
    assert!(t.contains("fails --bounds min-angle=30: min angle"), "{t}");
    // cgal-conforming promises no angle: its mesh is valid and Delaunay.
    let out = hexmesh(&["mesh", input, "--mesher", "cgal-conforming", "-o", p]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
}

/// Found by the issue 3/6 audit: a copy of the binary under another name could not mesh
/// ("cannot find the hexmesh binary"), and with a `hexmesh` beside it would have run that one
/// as its children. The command line now runs its children as itself.
#[test]
fn a_renamed_binary_runs_its_children_as_itself() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp("renamed");
    std::fs::create_dir_all(&dir).expect("dir");
    let copy = dir.join("hexmesh-copy");
    std::fs::copy(env!("CARGO_BIN_EXE_hexmesh"), &copy).expect("copy the binary");
    // A decoy named hexmesh that would fail every child it ran.
    let decoy = dir.join("hexmesh");
    std::fs::write(&decoy, "#!/bin/sh\nexit 3\n").expect("decoy");
    std::fs::set_permissions(&decoy, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    let prefix = dir.join("plane-100");
    let run = || {
        Command::new(&copy)
            .args(["mesh", "datasets/plane-100.node", "--mesher", "spade", "-o"])
            .arg(&prefix)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env_remove("HEXMESH_EXE")
            .output()
    };
    // A child another test thread forks while the copy's write descriptor is open holds it
    // until its exec, and running the copy then fails with "text file busy": try again.
    let mut out = run();
    for _ in 0..50 {
        match &out {
            Err(e) if e.kind() == std::io::ErrorKind::ExecutableFileBusy => {
                std::thread::sleep(std::time::Duration::from_millis(20));
                out = run();
            }
            _ => break,
        }
    }
    let out = out.expect("the copy runs");
    assert!(out.status.success(), "{}", text(&out));
    assert!(prefix.with_extension("ele").exists());
}

/// A reader that closes the pipe early (`hexmesh verify … | head -1`) ends the command
/// quietly: no panic message about printing to stdout, no panic exit code.
#[test]
fn a_closed_output_pipe_ends_the_command_without_a_panic() {
    use std::process::Stdio;
    let prefix = temp("closed-pipe-plane-1k");
    let out = hexmesh(&[
        "mesh",
        "plane-1k",
        "--mesher",
        "hex-simple",
        "-o",
        prefix.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let mut child = Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(["verify", prefix.to_str().unwrap(), "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    // Close the read end at once: every write of the JSON report meets a closed pipe.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("finishes");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(out.status.code(), Some(101), "{stderr}");
}

/// On a domain, hex's summary does not claim its interior angles for the whole mesh: it says
/// where they hold and states the near-segment figures apart, as measured; on a point set
/// there is no such line.
#[test]
fn the_hex_summary_states_near_segment_figures_apart_on_a_domain() {
    let prefix = temp("imr-hex-summary");
    let p = prefix.to_str().expect("utf-8");
    let out = hexmesh(&["mesh", "datasets/imr.poly", "--mesher", "hex", "-o", p]);
    assert!(out.status.success(), "{}", text(&out));
    let shown = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        shown.contains("its bounds hold away from the segments")
            && shown.contains("triangles touching a segment have angles")
            && shown.contains("(promised 30-120 deg but at input corners sharper than 30 deg"),
        "{shown}"
    );
    let prefix = temp("plane-100-hex-summary");
    let p = prefix.to_str().expect("utf-8");
    let out = hexmesh(&["mesh", "plane-100", "--mesher", "hex", "-o", p]);
    assert!(out.status.success(), "{}", text(&out));
    assert!(!String::from_utf8_lossy(&out.stderr).contains("touching a segment"));
}

#[test]
fn the_thread_count_changes_no_byte_and_zero_threads_is_refused() {
    let mut files = Vec::new();
    for threads in ["1", "2"] {
        let prefix = temp(&format!("threads-{threads}"));
        let p = prefix.to_str().expect("utf-8");
        let out = hexmesh(&[
            "mesh",
            "plane-2k",
            "--mesher",
            "hex",
            "--threads",
            threads,
            "-o",
            p,
        ]);
        assert!(out.status.success(), "{threads}: {}", text(&out));
        let read = |ext: &str| std::fs::read(prefix.with_extension(ext)).expect("written");
        files.push((read("node"), read("ele")));
    }
    assert!(
        files[0] == files[1],
        "1 and 2 threads wrote different files"
    );
    let prefix = temp("threads-0");
    let out = hexmesh(&[
        "mesh",
        "plane-100",
        "--mesher",
        "hex",
        "--threads",
        "0",
        "-o",
        prefix.to_str().expect("utf-8"),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(
        text(&out).contains("--threads must be at least 1"),
        "{}",
        text(&out)
    );
    assert!(!prefix.with_extension("node").exists());
}
