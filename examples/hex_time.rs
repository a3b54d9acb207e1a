//! Times the extended hexagonal mesher (`hex`) on one dataset: `cargo run --release --example
//! hex_time [dataset] [runs] [stats]`. A profiling aid; the measured figures live in
//! benches/hex.rs. With a third argument (`stats`) it also prints the mesher's counters
//! (`ExtendedStats`: rounds, triangles checked, repairs) from one more, untimed run.
//!
//! An unknown dataset, a count of runs that does not parse or lies outside 1 to 1000, or a
//! third argument other than `stats` is named in an error with the usage, exit code 2; a
//! mesher error is printed, exit code 1.

use std::process::ExitCode;

use hexmesh::hex::extended::{mesh_extended, Hex};
use hexmesh::{Mesher, Params};

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

const USAGE: &str = "usage: hex_time [dataset] [runs, 1 to 1000] [stats]";

/// The dataset, the number of timed runs and whether to print the counters.
fn parse(args: &[String]) -> Result<(String, hexmesh::Pslg, usize, bool), String> {
    if args.len() > 3 {
        return Err(format!(
            "{} arguments given, at most 3 are taken",
            args.len()
        ));
    }
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
    let stats = match args.get(2).map(String::as_str) {
        None => false,
        Some("stats") => true,
        Some(s) => return Err(format!("argument 3: '{s}' is not accepted (only 'stats')")),
    };
    Ok((name, input, runs, stats))
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
    let (name, input, runs, stats) = match parse(&args) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("hex_time: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    for _ in 0..runs {
        let t = std::time::Instant::now();
        let run = match Hex.mesh(&input, &Params::default()) {
            Ok(run) => run,
            Err(e) => {
                eprintln!("hex_time: {name}: {e}");
                return ExitCode::FAILURE;
            }
        };
        println!(
            "{name}: {} triangles in {:.3} s",
            run.mesh.triangles.len(),
            t.elapsed().as_secs_f64()
        );
    }
    if stats {
        match mesh_extended(&input, &Params::default()) {
            Ok(run) => println!("{:#?}", run.stats),
            Err(e) => {
                eprintln!("hex_time: {name}: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}
