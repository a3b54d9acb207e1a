//! Times the extended hexagonal mesher (`hex`) on one dataset: `cargo run --release --example
//! hex_time [dataset] [runs] [options]`. A profiling aid; the measured figures live in
//! benches/hex.rs. The options, in any order:
//! - `stats`: also print the mesher's counters (`ExtendedStats`: rounds, triangles checked,
//!   repairs) from one more, untimed run;
//! - `phases`: also print, from one more run, the seconds spent in each phase the mesher
//!   reports (`hexmesh_core::progress`), in the order first entered;
//! - `threads=N`: let the mesher use N threads (default: all the machine has).
//!
//! An unknown dataset, a count of runs that does not parse or lies outside 1 to 1000, or an
//! option other than these is named in an error with the usage, exit code 2; a mesher error
//! is printed, exit code 1.

use std::num::NonZeroUsize;
use std::process::ExitCode;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use hexmesh::hex::extended::{mesh_extended, Hex};
use hexmesh::progress::Progress;
use hexmesh::{Mesher, Params};

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

const USAGE: &str =
    "usage: hex_time [dataset] [runs, 1 to 1000] [stats] [phases] [threads=N, N at least 1]";

/// What to run: the dataset, the number of timed runs, the extra reports and the threads.
struct Run {
    name: String,
    input: hexmesh::Pslg,
    runs: usize,
    stats: bool,
    phases: bool,
    params: Params,
}

fn parse(args: &[String]) -> Result<Run, String> {
    let name = args.first().map_or("plane-2k", String::as_str).to_string();
    let input = hexmesh::datasets::by_name(&name).map_err(|e| format!("argument 1: {e}"))?;
    let runs = match args.get(1) {
        None => 3,
        Some(s) => match s.parse::<usize>() {
            Ok(n) if (1..=1000).contains(&n) => n,
            _ => {
                return Err(format!(
                    "argument 2 (runs, 1 to 1000): '{s}' is not accepted"
                ))
            }
        },
    };
    let mut run = Run {
        name,
        input,
        runs,
        stats: false,
        phases: false,
        params: Params::default(),
    };
    for (i, option) in args.iter().enumerate().skip(2) {
        match option.as_str() {
            "stats" => run.stats = true,
            "phases" => run.phases = true,
            other => match other
                .strip_prefix("threads=")
                .and_then(|n| n.parse::<NonZeroUsize>().ok())
            {
                Some(n) => run.params = run.params.clone().with_threads(n),
                None => {
                    return Err(format!(
                        "argument {}: '{other}' is not accepted (stats, phases or threads=N)",
                        i + 1
                    ))
                }
            },
        }
    }
    Ok(run)
}

/// Meshes once with an observer and prints the seconds between each phase's first report and
/// the next phase's, summed over the phase's visits, in the order the phases first came.
fn print_phases(run: &Run) -> Result<(), String> {
    let log: Arc<Mutex<Vec<(&'static str, Instant)>>> = Arc::default();
    let sink = Arc::clone(&log);
    let params = run
        .params
        .clone()
        .with_progress(Progress::new(move |event| {
            let mut log = sink.lock().unwrap_or_else(|e| e.into_inner());
            if log.last().map(|&(phase, _)| phase) != Some(event.phase) {
                log.push((event.phase, Instant::now()));
            }
        }));
    let start = Instant::now();
    let mesh = Hex.mesh(&run.input, &params).map_err(|e| e.to_string())?;
    let end = Instant::now();
    let log = log.lock().unwrap_or_else(|e| e.into_inner());
    let mut totals: Vec<(&'static str, f64)> = Vec::new();
    if let Some(&(_, first)) = log.first() {
        totals.push(("(before the first report)", (first - start).as_secs_f64()));
    }
    for (i, &(phase, at)) in log.iter().enumerate() {
        let until = log.get(i + 1).map_or(end, |&(_, next)| next);
        let seconds = (until - at).as_secs_f64();
        match totals.iter_mut().find(|(p, _)| *p == phase) {
            Some((_, total)) => *total += seconds,
            None => totals.push((phase, seconds)),
        }
    }
    println!(
        "{}: {} triangles in {:.3} s, by phase:",
        run.name,
        mesh.mesh.triangles.len(),
        (end - start).as_secs_f64()
    );
    for (phase, seconds) in totals {
        println!("  {seconds:8.3} s  {phase}");
    }
    Ok(())
}

fn main() -> ExitCode {
    hexmesh::configure_allocator();
    // A reader that stops early (`hex_time plane-1k 1 stats | head`) ends the run quietly,
    // as it ends the `hexmesh` command.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of one signal, before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args: Vec<String> = std::env::args().skip(1).collect();
    let run = match parse(&args) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("hex_time: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    for _ in 0..run.runs {
        let t = Instant::now();
        let mesh = match Hex.mesh(&run.input, &run.params) {
            Ok(mesh) => mesh,
            Err(e) => {
                eprintln!("hex_time: {}: {e}", run.name);
                return ExitCode::FAILURE;
            }
        };
        println!(
            "{}: {} triangles in {:.3} s",
            run.name,
            mesh.mesh.triangles.len(),
            t.elapsed().as_secs_f64()
        );
    }
    if run.phases {
        if let Err(e) = print_phases(&run) {
            eprintln!("hex_time: {}: {e}", run.name);
            return ExitCode::FAILURE;
        }
    }
    if run.stats {
        match mesh_extended(&run.input, &run.params) {
            Ok(mesh) => println!("{:#?}", mesh.stats),
            Err(e) => {
                eprintln!("hex_time: {}: {e}", run.name);
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}
