//! How fast this machine hands out fresh memory: `cargo run --release --example first_touch
//! [MB] [pause seconds] [rounds]`. Each round takes `MB` megabytes of zeroed memory from the
//! system allocator (fresh pages the kernel maps on first write), writes one byte per 4 KiB
//! page, times that, gives the memory back and waits `pause` seconds.
//!
//! A measuring aid for the mesher's times, not a test. On the virtual machines of this project
//! (virtio-balloon with free page reporting) the guest gives freed pages back to the host after
//! a few seconds, and the next first write to one waits for the host. Measured on the AMD
//! machine (1024 MB, three rounds): 0.24–0.26 GB/s for the first round, 0.6 GB/s after a pause
//! of 5 s and 1.4 GB/s with none; a C program writing huge pages (`MADV_HUGEPAGE`) reached
//! 0.27 GB/s the first time and 9–11 GB/s taken again at once. The large datasets pay this on
//! every page they take (plane-100k about 1.3 GB at its peak, plane-1m about 12.7 GB, and more
//! as phases give memory back and take it again), so their system time says as much about the
//! machine as about the mesher; see METHODOLOGY.md.

use std::process::ExitCode;
use std::str::FromStr;
use std::time::{Duration, Instant};

/// Argument `n` (from 1) parsed as a `T` that `ok` accepts, or `default` when it is missing.
fn arg<T: FromStr + Copy>(
    args: &[String],
    n: usize,
    name: &str,
    default: T,
    ok: impl Fn(T) -> bool,
) -> Result<T, String> {
    match args.get(n) {
        None => Ok(default),
        Some(s) => match s.parse::<T>() {
            Ok(v) if ok(v) => Ok(v),
            _ => Err(format!("argument {n} ({name}): '{s}' is not accepted")),
        },
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let parsed = (|| {
        let mb = arg(&args, 1, "megabytes, 1 to 65536", 1024usize, |m| {
            (1..=1 << 16).contains(&m)
        })?;
        let pause = arg(&args, 2, "pause in seconds, 0 to 3600", 5.0f64, |p| {
            (0.0..=3600.0).contains(&p)
        })?;
        let rounds = arg(&args, 3, "rounds, 1 to 1000", 3usize, |r| {
            (1..=1000).contains(&r)
        })?;
        Ok::<_, String>((mb, pause, rounds))
    })();
    let (mb, pause, rounds) = match parsed {
        Ok(p) => p,
        Err(e) => {
            eprintln!("first_touch: {e}\nusage: first_touch [MB] [pause seconds] [rounds]");
            return ExitCode::from(2);
        }
    };
    let bytes = mb << 20;
    for round in 1..=rounds {
        let mut v = vec![0u8; bytes];
        let t = Instant::now();
        for i in (0..bytes).step_by(4096) {
            v[i] = 1;
        }
        let s = t.elapsed().as_secs_f64();
        // Read back so that the writes cannot be left out.
        let sum: usize = v.iter().step_by(4096).map(|&b| b as usize).sum();
        assert_eq!(sum, bytes.div_ceil(4096));
        drop(v);
        println!(
            "round {round}: {mb} MB first touched in {s:.3} s ({:.2} GB/s)",
            bytes as f64 / 1e9 / s
        );
        if round < rounds {
            std::thread::sleep(Duration::from_secs_f64(pause));
        }
    }
    ExitCode::SUCCESS
}
