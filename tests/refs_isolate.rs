//! Process isolation and the max-angle protocol, through the real `hexmesh` binary: a normal
//! run comes back bit-exactly, a run that does not terminate is cut off at its timeout, a
//! dying child is an error naming how it died, and the paper's max-angle protocol gives a
//! plausible angle for Triangle and spade.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use hexmesh::isolate::{find_exe, run_isolated, run_isolated_watched, ChildProgress};
use hexmesh::maxangle::{max_angle, DEFAULT_START, DEFAULT_STEP};
use hexmesh::{mesher, Error, Params, Pslg};

fn exe() -> &'static Path {
    Path::new(env!("CARGO_BIN_EXE_hexmesh"))
}

fn point_set(n: u32) -> Pslg {
    let pts = (1..=n)
        .map(|i| {
            let i = f64::from(i);
            [
                (i * 0.618_033_988_749_895).fract(),
                (i * 0.414_213_562_373_095).fract(),
            ]
        })
        .collect();
    Pslg::from_points(pts)
}

fn bits(v: &[[f64; 2]]) -> Vec<u64> {
    v.iter().flat_map(|p| p.map(f64::to_bits)).collect()
}

#[test]
fn an_isolated_run_returns_the_in_process_mesh_bit_exactly() {
    let input = point_set(40);
    let params = Params::default().with_min_angle(30.0);
    for name in ["spade", "triangle"] {
        let local = mesher(name).unwrap().mesh(&input, &params).unwrap();
        let iso = run_isolated(exe(), name, &input, &params, Duration::from_secs(30)).unwrap();
        assert_eq!(
            bits(&iso.run.mesh.vertices),
            bits(&local.mesh.vertices),
            "{name}"
        );
        assert_eq!(iso.run.mesh.triangles, local.mesh.triangles, "{name}");
        assert_eq!(iso.run.complete, local.complete);
        assert_eq!(iso.run.steps, local.steps);
        assert!(iso.peak_rss_bytes > 0, "{name}: no VmHWM");
    }
}

#[test]
fn triangle_at_44_degrees_is_cut_off_at_the_timeout() {
    let input = point_set(40);
    let params = Params::default().with_min_angle(44.0);
    let started = Instant::now();
    let iso = run_isolated(
        exe(),
        "triangle",
        &input,
        &params,
        Duration::from_millis(500),
    )
    .unwrap();
    let waited = started.elapsed();
    assert!(!iso.run.complete);
    assert_eq!(
        iso.run.stop_reason,
        Some(hexmesh::StopReason::Timeout(
            std::time::Duration::from_millis(500)
        ))
    );
    assert!(iso.run.mesh.triangles.is_empty());
    assert!(waited < Duration::from_secs(3), "took {waited:?}");
}

#[test]
fn an_error_in_the_child_is_forwarded_with_its_message() {
    // A hole seed on the diagonal of a square inside a square, a segment: spade refuses the
    // ambiguous seed in the child (the fixture's header says why the input passes the check).
    let input = hexmesh::io::read_input(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/refs/hole_seed_on_inner_diagonal.poly"),
    )
    .expect("fixture");
    let err = run_isolated(
        exe(),
        "spade",
        &input,
        &Params::default(),
        Duration::from_secs(30),
    )
    .unwrap_err();
    match err {
        Error::Mesher { mesher, message } => {
            assert_eq!(mesher, "spade");
            assert!(message.contains("hole 0"), "{message}");
        }
        other => panic!("unexpected error {other}"),
    }
}

#[test]
fn bad_input_and_unknown_meshers_are_refused_before_spawning() {
    let dup = Pslg::from_points(vec![[0.0, 0.0], [0.0, 0.0]]);
    let t = Duration::from_secs(5);
    assert!(matches!(
        run_isolated(exe(), "spade", &dup, &Params::default(), t),
        Err(Error::Input { .. })
    ));
    assert!(matches!(
        run_isolated(exe(), "nope", &point_set(5), &Params::default(), t),
        Err(Error::UnknownMesher { .. })
    ));
}

/// A stand-in child written as a shell script, to die in ways hexmesh itself does not.
///
/// The file is written by a separate `sh`, never through a descriptor of this process: a test
/// thread that forks while this process holds the file open for writing would carry that
/// descriptor into its child, and executing the script would then fail with "Text file busy"
/// (ETXTBSY) — which is how CI once failed here.
fn script(name: &str, body: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(name);
    let status = std::process::Command::new("sh")
        .arg("-c")
        .arg(
            r#"printf '#!/bin/sh\n%s\n' "$1" > "$2.tmp" && chmod 755 "$2.tmp" && mv "$2.tmp" "$2""#,
        )
        .arg("sh")
        .arg(body)
        .arg(&path)
        .status()
        .unwrap();
    assert!(status.success(), "writing {}", path.display());
    path
}

#[test]
fn a_child_killed_by_a_signal_is_an_error_naming_the_signal() {
    let exe = script(
        "refs_abort.sh",
        "cat >/dev/null; echo dying >&2; kill -ABRT $$",
    );
    let err = run_isolated(
        &exe,
        "spade",
        &point_set(5),
        &Params::default(),
        Duration::from_secs(10),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("SIGABRT") && err.contains("dying"), "{err}");
}

#[test]
fn a_child_that_exits_like_triangle_is_an_error_quoting_its_stdout() {
    let exe = script(
        "refs_exit.sh",
        "cat >/dev/null; echo 'Error:  Ran out of precision at (1, 2).'; exit 1",
    );
    let err = run_isolated(
        &exe,
        "triangle",
        &point_set(5),
        &Params::default(),
        Duration::from_secs(10),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("status 1") && err.contains("Ran out of precision"),
        "{err}"
    );
}

#[test]
fn a_watched_hex_run_forwards_its_progress_and_returns_the_same_mesh() {
    // More points than a tile of `hex` holds, so that it reports tiles.
    let input = point_set(2100);
    let params = Params::default();
    let t = Duration::from_secs(60);
    let plain = run_isolated(exe(), "hex", &input, &params, t).unwrap();
    let mut seen: Vec<ChildProgress> = Vec::new();
    let watched = run_isolated_watched(exe(), "hex", &input, &params, t, &mut |w| {
        if let Some(p) = w.progress {
            if seen.last() != Some(p) {
                seen.push(p.clone());
            }
        }
    })
    .unwrap();
    assert_eq!(
        bits(&watched.run.mesh.vertices),
        bits(&plain.run.mesh.vertices)
    );
    assert_eq!(watched.run.mesh.triangles, plain.run.mesh.triangles);
    // How many reports the watch sees depends on the machine's speed; those it sees are
    // hex's, in the order of its run: the tiles counted up to their number, then the rest.
    let tiles: Vec<_> = seen.iter().filter(|p| p.phase == "tiles").collect();
    for pair in tiles.windows(2) {
        let (a, b) = (pair[0].count.unwrap(), pair[1].count.unwrap());
        assert!(a.done < b.done && a.total == b.total, "{seen:?}");
    }
    let first_other = seen.iter().position(|p| p.phase != "tiles");
    assert!(
        seen[first_other.unwrap_or(seen.len())..]
            .iter()
            .all(|p| p.phase != "tiles"),
        "{seen:?}"
    );
}

#[test]
fn the_childs_progress_lines_are_left_out_of_the_stderr_an_error_quotes() {
    let exe = script(
        "refs_progress.sh",
        "cat >/dev/null; echo 'hexmesh-progress: 3 9 tiles' >&2; echo dying >&2; \
         echo 'hexmesh-progress: - - joining the tiles' >&2; kill -ABRT $$",
    );
    let err = run_isolated_watched(
        &exe,
        "spade",
        &point_set(5),
        &Params::default(),
        Duration::from_secs(10),
        &mut |_| {},
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("SIGABRT") && err.contains("dying"), "{err}");
    assert!(!err.contains("hexmesh-progress"), "{err}");
}

#[test]
fn find_exe_honours_hexmesh_exe() {
    // Only this test touches the variable, so setting it cannot race another test's reading.
    std::env::set_var("HEXMESH_EXE", exe());
    assert_eq!(find_exe().unwrap(), exe());
    std::env::set_var("HEXMESH_EXE", "/nonexistent/hexmesh");
    assert!(find_exe().is_err());
    std::env::remove_var("HEXMESH_EXE");
    assert!(find_exe().unwrap().ends_with("hexmesh"));
}

#[test]
fn max_angle_of_a_small_point_set_is_plausible_for_triangle_and_spade() {
    let input = point_set(12);
    for name in ["triangle", "spade"] {
        let r = max_angle(
            exe(),
            name,
            &input,
            DEFAULT_STEP,
            Duration::from_secs(2),
            DEFAULT_START,
        )
        .unwrap();
        let angle = r.angle.unwrap_or(0.0);
        assert!((30.0..45.0).contains(&angle), "{r}");
        assert!(r.measured_min_angle.unwrap() >= angle - 1e-6, "{r}");
        assert!(r.triangles > 0);
        assert_eq!(r.failed_at, angle + DEFAULT_STEP, "{r}");
        eprintln!("{r}");
    }
}

#[test]
fn max_angle_refuses_a_bad_step_an_unknown_mesher_and_a_missing_binary() {
    let input = point_set(5);
    let t = Duration::from_secs(2);
    assert!(max_angle(exe(), "spade", &input, 0.0, t, 20.0).is_err());
    assert!(max_angle(exe(), "spade", &input, f64::NAN, t, 20.0).is_err());
    assert!(matches!(
        max_angle(exe(), "nope", &input, 0.25, t, 20.0),
        Err(Error::UnknownMesher { .. })
    ));
    assert!(matches!(
        max_angle(
            Path::new("/nonexistent/hexmesh"),
            "spade",
            &input,
            0.25,
            t,
            20.0
        ),
        Err(Error::Io { .. })
    ));
}

#[test]
fn max_angle_on_a_pslg_with_sloped_segments_is_plausible() {
    // The IMR letters: Steiner points on sloped segments are rounded off the segment's line,
    // which conformity must tolerate, or every step would fail.
    let input = hexmesh::datasets::by_name("imr").unwrap();
    let r = max_angle(exe(), "triangle", &input, 1.0, Duration::from_secs(2), 30.0).unwrap();
    let angle = r.angle.unwrap_or(0.0);
    assert!((30.0..45.0).contains(&angle), "{r}");
}
