//! Process isolation for one meshing call (a mesher that does not terminate, or C code that
//! calls `exit()`/`abort()`, must not take the harness down).
//!
//! The parent spawns `hexmesh __run-mesher`, writes the request to the child's stdin and
//! reads the answer from its stdout, both in a compact little-endian binary format (raw f64
//! and u32, so a million points cost 16 MB and come back bit-exact; written and read in
//! `wire`):
//!
//! request  = "HXMI" u32:version str:mesher params pslg
//! params   = opt<f64>:min_angle opt<f64>:max_area opt<u64>:max_steps opt<u64>:max_vertices
//!            opt<(u64 secs, u32 nanos)>:max_time opt<f64>:max_rounding opt<str>:switches
//!            opt<u64>:threads u8:forward_progress
//! pslg     = u64:n (f64 x, f64 y)×n u64:m (u32, u32)×m u64:h (f64, f64)×h opt<(f64,f64,f64,f64,f64)>:hexagon (centre, circumradius, turn)
//!            u64:r (f64 x, f64 y, f64 attribute, opt<f64>:max_area)×r  (the regions)
//! answer   = payload u64:payload_len "HXMRESLT"
//! payload  = 0u8 u8:complete opt<str>:stop_reason u64:steps u64:secs u32:nanos u64:peak_rss
//!            u64:nv (f64, f64)×nv u64:nt (u32, u32, u32)×nt
//!          | 1u8 str:mesher str:message
//!          | 2u8 u64:first u64:second f64:distance f64:needed f64:allowed  (InputError::Rounding)
//!          | 3u8 u64:index f64:distance                                    (InputError::NearBoundary)
//!          | 4u8 u8:kind u64:a u64:b u64:c      (a refused domain: `encode_domain_refusal`)
//! opt<T>   = 0u8 | 1u8 T;  str = u32:len utf-8 bytes
//!
//! The answer is a trailer at the very end of stdout, and the child flushes C's stdio
//! buffers before writing it: Triangle prints its errors with `printf`, and such text must
//! neither corrupt the answer nor get lost (it is quoted when the child dies).
//!
//! When the request asks for it (`forward_progress` = 1, which `run_isolated_watched` sets),
//! the child passes the mesher's progress (`hexmesh_core::progress`) to the parent as lines
//! on its stderr, one an event, at most one every `FORWARD_EVERY` within a phase (a new phase
//! and a count's last item always):
//!
//! progress = "hexmesh-progress: " (u64 done | "-") " " (u64 total | "-") " " phase "\n"
//!
//! The parent takes such lines out of the stderr it keeps, so that the error messages that
//! quote the child's stderr (a panic, C's complaints) read as they did before.

use std::io::{BufRead, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitCode, ExitStatus, Stdio};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::Mutex;
use std::thread;
use std::time::{Duration, Instant};

use crate::error::{Error, InputError, Result, Unenclosed};
use crate::geom::{Hexagon, Turn};
use crate::mesh::{Labels, Pslg, Region, TriMesh};
use crate::mesher::{Budget, MeshRun, Params, StopReason};
use crate::progress::{Count, Event, Progress};
use crate::registry;

mod wire;
use wire::*;

/// The hidden subcommand the child runs.
pub const CHILD_COMMAND: &str = "__run-mesher";

const REQUEST_MAGIC: &[u8; 4] = b"HXMI";
const ANSWER_MAGIC: &[u8; 8] = b"HXMRESLT";
const VERSION: u32 = 7;
/// How much of the child's stderr and stdout an error quotes.
const TAIL_BYTES: usize = 2000;
/// The start of a line of the child's stderr that carries the mesher's progress.
const PROGRESS_PREFIX: &str = "hexmesh-progress: ";
/// The child forwards at most one event of a phase this often (a new phase, and the last item
/// of a count, at once): a mesher may report thousands, the parent redraws a few times a
/// second.
const FORWARD_EVERY: Duration = Duration::from_millis(100);

/// One isolated meshing call: the run as the child saw it, and the child's peak resident
/// memory (VmHWM; for a timed-out child, its value just before the kill).
#[derive(Debug, Clone, PartialEq)]
pub struct Isolated {
    pub run: MeshRun,
    pub peak_rss_bytes: u64,
}

/// What the parent sees of the isolated child while it runs (`run_isolated_watched`).
#[derive(Debug, Clone, Copy)]
pub struct Watch<'a> {
    /// The time since the child was started.
    pub spent: Duration,
    /// The child's process id.
    pub pid: u32,
    /// The mesher's last progress report: `None` before the first, and from a mesher that
    /// reports none (`hexmesh_core::progress`).
    pub progress: Option<&'a ChildProgress>,
}

/// A progress event of the mesher in the child (`hexmesh_core::progress::Event`), as the
/// parent reads it from the child's stderr.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChildProgress {
    /// What the mesher is doing.
    pub phase: String,
    /// How far into the phase, when it counts items.
    pub count: Option<Count>,
}

/// Runs `mesher` on `input` in a child process of `exe` and waits at most `timeout`.
///
/// A timeout is not an error: the run comes back empty with `complete == false` and
/// `stop_reason` "timeout after …s". A child that dies (a signal, `exit()` from C) is an
/// `Error::Mesher` naming the signal or status and quoting its output; an error the mesher
/// returned in the child comes back as that error's message.
pub fn run_isolated(
    exe: &Path,
    mesher: &str,
    input: &Pslg,
    params: &Params,
    timeout: Duration,
) -> Result<Isolated> {
    run(exe, mesher, input, params, timeout, None)
}

/// `run_isolated`, calling `watch` with the time spent, the child's process id and the
/// mesher's last progress report each time it looks whether the child has finished (every
/// 20 ms at most), so that the caller can show the run's progress (`hexmesh mesh` draws
/// it). The child is asked to forward the mesher's progress (module docs).
pub fn run_isolated_watched(
    exe: &Path,
    mesher: &str,
    input: &Pslg,
    params: &Params,
    timeout: Duration,
    watch: &mut dyn FnMut(&Watch<'_>),
) -> Result<Isolated> {
    run(exe, mesher, input, params, timeout, Some(watch))
}

/// `run_isolated`, and `run_isolated_watched` when there is a `watch`.
fn run(
    exe: &Path,
    mesher: &str,
    input: &Pslg,
    params: &Params,
    timeout: Duration,
    watch: Option<&mut dyn FnMut(&Watch<'_>)>,
) -> Result<Isolated> {
    input.validate_input()?;
    registry::mesher(mesher)?;
    let request = encode_request(mesher, input, params, watch.is_some());
    let spawn_err = |e: std::io::Error| Error::Io {
        path: exe.to_path_buf(),
        source: e,
    };
    let mut child = Command::new(exe)
        .arg(CHILD_COMMAND)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(spawn_err)?;
    let start = Instant::now();
    let (stdin, stdout, stderr) = (child.stdin.take(), child.stdout.take(), child.stderr.take());
    // A child that dies early closes its stdin: the broken pipe is expected, the exit status
    // tells what happened.
    let writer = thread::spawn(move || {
        if let Some(mut s) = stdin {
            let _ = s.write_all(&request);
        }
    });
    let out_reader = thread::spawn(move || read_all(stdout));
    let (events, reports) = mpsc::channel();
    let err_reader = thread::spawn(move || read_stderr(stderr, &events));

    let waited = wait_with_timeout(&mut child, timeout, start, watch, &reports);
    let elapsed = start.elapsed();
    let _ = writer.join();
    let out = out_reader.join().unwrap_or_default();
    let err = err_reader.join().unwrap_or_default();
    let status = match waited {
        Ok(Waited::Exited(status)) => status,
        Ok(Waited::TimedOut { peak_rss_bytes }) => {
            return Ok(Isolated {
                run: MeshRun {
                    mesh: TriMesh::default(),
                    complete: false,
                    stop_reason: Some(StopReason::Timeout(timeout)),
                    steps: 0,
                    elapsed,
                },
                peak_rss_bytes,
            })
        }
        Err(e) => return Err(spawn_err(e)),
    };
    if !status.success() {
        return Err(Error::mesher(
            mesher,
            format!(
                "isolated child {}{}{}",
                describe_status(status),
                quote("stderr", &err),
                quote("stdout", &out)
            ),
        ));
    }
    let payload = trailer(&out).ok_or_else(|| {
        Error::mesher(
            mesher,
            format!(
                "isolated child exited without an answer{}",
                quote("stderr", &err)
            ),
        )
    })?;
    decode_answer(payload, mesher)
}

enum Waited {
    Exited(ExitStatus),
    TimedOut { peak_rss_bytes: u64 },
}

fn wait_with_timeout(
    child: &mut Child,
    timeout: Duration,
    start: Instant,
    mut watch: Option<&mut dyn FnMut(&Watch<'_>)>,
    reports: &Receiver<ChildProgress>,
) -> std::io::Result<Waited> {
    let mut pause = Duration::from_millis(1);
    let mut last = None;
    loop {
        if let Some(status) = child.try_wait()? {
            return Ok(Waited::Exited(status));
        }
        let spent = start.elapsed();
        if let Some(watch) = watch.as_mut() {
            // Only the latest report is shown; the ones before it are passed by.
            if let Some(report) = reports.try_iter().last() {
                last = Some(report);
            }
            watch(&Watch {
                spent,
                pid: child.id(),
                progress: last.as_ref(),
            });
        }
        if spent >= timeout {
            let peak_rss_bytes = peak_rss(&format!("/proc/{}/status", child.id()));
            // The child may have exited between try_wait and kill: then kill fails harmlessly.
            let _ = child.kill();
            let status = child.wait()?;
            if status.success() {
                return Ok(Waited::Exited(status));
            }
            return Ok(Waited::TimedOut { peak_rss_bytes });
        }
        thread::sleep(pause.min(timeout - spent));
        pause = (pause * 2).min(Duration::from_millis(20));
    }
}

fn read_all<R: Read>(source: Option<R>) -> Vec<u8> {
    let mut buf = Vec::new();
    if let Some(mut s) = source {
        let _ = s.read_to_end(&mut buf);
    }
    buf
}

/// The child's stderr: its progress lines (module docs) sent to `events` as they come, every
/// other byte kept, in order, for the error messages that quote it.
fn read_stderr<R: Read>(source: Option<R>, events: &Sender<ChildProgress>) -> Vec<u8> {
    let mut kept = Vec::new();
    let Some(source) = source else {
        return kept;
    };
    let mut lines = std::io::BufReader::new(source);
    let mut line = Vec::new();
    loop {
        line.clear();
        match lines.read_until(b'\n', &mut line) {
            Ok(0) | Err(_) => return kept,
            Ok(_) => {}
        }
        match parse_progress_line(&line) {
            // The parent may have stopped listening; the rest is still read and kept.
            Some(report) => drop(events.send(report)),
            None => kept.extend_from_slice(&line),
        }
    }
}

/// The progress line (module docs) that forwards `event`.
fn progress_line(event: &Event) -> String {
    let figure = |v: Option<u64>| v.map_or("-".to_string(), |v| v.to_string());
    let done = event.count.map(|c| c.done);
    let total = event.count.and_then(|c| c.total);
    format!(
        "{PROGRESS_PREFIX}{} {} {}\n",
        figure(done),
        figure(total),
        event.phase
    )
}

/// The report a whole progress line (`progress_line`) carries; `None` for any other line.
fn parse_progress_line(line: &[u8]) -> Option<ChildProgress> {
    let line = std::str::from_utf8(line).ok()?;
    let rest = line.strip_prefix(PROGRESS_PREFIX)?.strip_suffix('\n')?;
    let (done, rest) = rest.split_once(' ')?;
    let (total, phase) = rest.split_once(' ')?;
    let figure = |s: &str| match s {
        "-" => Ok(None),
        s => s.parse::<u64>().map(Some),
    };
    let (done, total) = (figure(done).ok()?, figure(total).ok()?);
    let count = match (done, total) {
        (Some(done), total) => Some(Count { done, total }),
        (None, None) => None,
        (None, Some(_)) => return None,
    };
    Some(ChildProgress {
        phase: phase.to_string(),
        count,
    })
}

/// The observer the child gives the mesher when the parent asks for its progress: each
/// event it passes on (`worth_forwarding`) becomes a progress line on stderr, written whole
/// in one call so that other writers to stderr do not split it.
fn forward_progress() -> Progress {
    let last: Mutex<Option<(&'static str, Instant)>> = Mutex::new(None);
    Progress::new(move |event| {
        let mut last = last
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let now = Instant::now();
        if !worth_forwarding(*last, &event, now) {
            return;
        }
        *last = Some((event.phase, now));
        let _ = std::io::stderr()
            .lock()
            .write_all(progress_line(&event).as_bytes());
    })
}

/// Whether the child passes `event` on at `now`, `last` being the phase of the last event it
/// passed on and when: a new phase and the last item of a count at once, other events of a
/// phase at most once every `FORWARD_EVERY`.
fn worth_forwarding(last: Option<(&str, Instant)>, event: &Event, now: Instant) -> bool {
    let finished = event.count.is_some_and(|c| Some(c.done) == c.total);
    let recent = last.is_some_and(|(phase, at)| {
        phase == event.phase && now.saturating_duration_since(at) < FORWARD_EVERY
    });
    finished || !recent
}

fn describe_status(status: ExitStatus) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = status.signal() {
            let name = match sig {
                4 => "SIGILL",
                6 => "SIGABRT",
                7 => "SIGBUS",
                8 => "SIGFPE",
                9 => "SIGKILL",
                11 => "SIGSEGV",
                15 => "SIGTERM",
                _ => "signal",
            };
            return format!("was killed by signal {sig} ({name})");
        }
    }
    match status.code() {
        Some(code) => format!("exited with status {code}"),
        None => "ended abnormally".to_string(),
    }
}

fn quote(what: &str, bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let text = text.trim();
    if text.is_empty() {
        return String::new();
    }
    let mut cut = text.len().saturating_sub(TAIL_BYTES);
    while !text.is_char_boundary(cut) {
        cut += 1;
    }
    format!("; {what}: {}", &text[cut..])
}

/// The peak resident set size recorded in a /proc status file, in bytes (0 if unknown).
fn peak_rss(status_file: &str) -> u64 {
    std::fs::read_to_string(status_file)
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

/// The payload of the answer trailer at the end of `out`, if there is a whole one.
fn trailer(out: &[u8]) -> Option<&[u8]> {
    let body = out.strip_suffix(ANSWER_MAGIC.as_slice())?;
    let len_at = body.len().checked_sub(8)?;
    let len = u64::from_le_bytes(body[len_at..].try_into().ok()?);
    let start = len_at.checked_sub(usize::try_from(len).ok()?)?;
    Some(&body[start..len_at])
}

/// The child side: reads a request from stdin, runs the mesher, writes the answer to stdout.
/// The CLI calls this for the hidden `__run-mesher` subcommand.
pub fn child_main() -> ExitCode {
    let mut request = Vec::new();
    if let Err(e) = std::io::stdin().lock().read_to_end(&mut request) {
        eprintln!("hexmesh {CHILD_COMMAND}: cannot read the request: {e}");
        return ExitCode::from(2);
    }
    let (name, input, mut params, forward) = match decode_request(&request) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("hexmesh {CHILD_COMMAND}: {e}");
            return ExitCode::from(2);
        }
    };
    drop(request);
    if forward {
        params.progress = Some(forward_progress());
    }
    let mut payload = Vec::new();
    match run_in_child(&name, &input, &params) {
        Ok((run, rss)) => encode_run(&mut payload, &run, rss),
        // A refusal that names input points goes back as such, so that the parent can put
        // the lines of its file on them.
        Err(Error::Input {
            problem:
                InputError::Rounding {
                    first,
                    second,
                    distance,
                    needed,
                    allowed,
                },
            ..
        }) => {
            payload.push(2);
            put_u64(&mut payload, first as u64);
            put_u64(&mut payload, second as u64);
            for v in [distance, needed, allowed] {
                put_f64(&mut payload, v);
            }
        }
        Err(Error::Input {
            problem: InputError::NearBoundary { index, distance },
            ..
        }) => {
            payload.push(3);
            put_u64(&mut payload, index as u64);
            put_f64(&mut payload, distance);
        }
        Err(Error::Input { problem, .. }) if domain_refusal(&problem).is_some() => {
            let (kind, [a, b, c]) = domain_refusal(&problem).unwrap_or_default();
            payload.push(4);
            payload.push(kind);
            for v in [a, b, c] {
                put_u64(&mut payload, v as u64);
            }
        }
        Err(e) => {
            let (mesher, message) = match e {
                Error::Mesher { mesher, message } => (mesher, message),
                other => (name.clone(), other.to_string()),
            };
            payload.push(1);
            put_str(&mut payload, &mesher);
            put_str(&mut payload, &message);
        }
    }
    flush_c_stdio();
    let len = payload.len() as u64;
    put_u64(&mut payload, len);
    payload.extend_from_slice(ANSWER_MAGIC);
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(&payload).and_then(|_| out.flush()) {
        eprintln!("hexmesh {CHILD_COMMAND}: cannot write the answer: {e}");
        return ExitCode::from(2);
    }
    ExitCode::SUCCESS
}

fn run_in_child(name: &str, input: &Pslg, params: &Params) -> Result<(MeshRun, u64)> {
    input.validate_input()?;
    let mesher = registry::mesher(name)?;
    let start = Instant::now();
    let mut run = mesher.mesh(input, params)?;
    run.elapsed = start.elapsed();
    Ok((run, peak_rss("/proc/self/status").max(children_peak_rss())))
}

/// The largest peak resident set size of the processes this one has waited for (a mesher
/// that runs a program, as `gmsh` does), in bytes; 0 where unknown.
fn children_peak_rss() -> u64 {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: getrusage writes one `rusage` into the zeroed value it is given.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        if unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) } == 0 {
            // Linux reports ru_maxrss in kilobytes.
            return u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024;
        }
    }
    0
}

/// Writes out what C code left in its stdio buffers, so that it lands before the answer.
fn flush_c_stdio() {
    #[cfg(unix)]
    {
        extern "C" {
            fn fflush(stream: *mut std::ffi::c_void) -> std::ffi::c_int;
        }
        // SAFETY: fflush(NULL) flushes every open output stream; it takes no Rust data.
        unsafe {
            fflush(std::ptr::null_mut());
        }
    }
}

/// The running executable, when it is the hexmesh command line: set by `cli::main`, whatever
/// the binary is called, so that its children are the same binary.
static CLI_EXE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Records that the running executable is the hexmesh command line (`cli::main` calls it).
/// A copy renamed `hexmesh-v2` then runs its children as itself, rather than failing, or
/// running another `hexmesh` that happens to sit next to it.
pub fn running_as_cli() {
    if let Ok(current) = std::env::current_exe() {
        let _ = CLI_EXE.set(current);
    }
}

/// The hexmesh binary to run children of: `HEXMESH_EXE` if set; else the running executable
/// if it is the command line (`running_as_cli`) or is called hexmesh; else a `hexmesh` next to
/// it or one directory up (cargo puts test binaries in target/<profile>/deps/, the binary in
/// target/<profile>/).
pub fn find_exe() -> Result<PathBuf> {
    if let Some(p) = std::env::var_os("HEXMESH_EXE").filter(|p| !p.is_empty()) {
        let p = PathBuf::from(p);
        if p.is_file() {
            return Ok(p);
        }
        return Err(Error::Usage(format!(
            "HEXMESH_EXE={} is not a file",
            p.display()
        )));
    }
    if let Some(cli) = CLI_EXE.get() {
        return Ok(cli.clone());
    }
    let current = std::env::current_exe().map_err(|e| Error::Io {
        path: PathBuf::from("/proc/self/exe"),
        source: e,
    })?;
    if current.file_stem().is_some_and(|s| s == "hexmesh") {
        return Ok(current);
    }
    let name = format!("hexmesh{}", std::env::consts::EXE_SUFFIX);
    let dir = current.parent();
    let candidates = [
        dir.map(|d| d.join(&name)),
        dir.and_then(Path::parent).map(|d| d.join(&name)),
    ];
    candidates
        .into_iter()
        .flatten()
        .find(|p| p.is_file())
        .ok_or_else(|| {
            Error::Usage(format!(
                "cannot find the hexmesh binary near {}; set HEXMESH_EXE",
                current.display()
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_round_trips_bit_exactly() {
        let input = Pslg {
            points: vec![[0.1, -0.0], [f64::MIN_POSITIVE, 3.0e300], [1.0 / 3.0, 2.0]],
            segments: vec![[0, 1], [1, 2]],
            holes: vec![[0.25, 0.5]],
            hexagon: Some(Hexagon {
                center: [0.5, 0.5],
                circumradius: 2.0,
                turn: Turn {
                    cos: 0.6,
                    sin: -0.8,
                },
            }),
            labels: Labels {
                regions: vec![
                    Region {
                        point: [0.5, 0.25],
                        attribute: 1.0 / 3.0,
                        max_area: Some(0.01),
                    },
                    Region {
                        point: [0.125, -0.0],
                        attribute: 0.5,
                        max_area: None,
                    },
                ],
                ..Labels::default()
            },
        };
        let mut params = Params::default()
            .with_min_angle(30.25)
            .with_max_edge(0.125)
            .with_switches("q25DS100 ünï")
            .with_threads(std::num::NonZeroUsize::new(3).unwrap());
        params.budget.max_time = Some(Duration::from_millis(1500));
        params.budget.max_vertices = Some(77);
        let buf = encode_request("triangle", &input, &params, true);
        let (name, back, p, forward) = decode_request(&buf).unwrap();
        assert_eq!(name, "triangle");
        assert!(forward);
        assert_eq!(p, params);
        assert_eq!(p.switches.as_deref(), Some("q25DS100 ünï"));
        assert_eq!(back.segments, input.segments);
        assert_eq!(back.labels.regions, input.labels.regions);
        let region_bits = |v: &[Region]| {
            v.iter()
                .flat_map(|r| {
                    [
                        r.point[0],
                        r.point[1],
                        r.attribute,
                        r.max_area.unwrap_or(-1.0),
                    ]
                })
                .map(f64::to_bits)
                .collect::<Vec<_>>()
        };
        assert_eq!(
            region_bits(&back.labels.regions),
            region_bits(&input.labels.regions)
        );
        let bits = |v: &[[f64; 2]]| {
            v.iter()
                .flat_map(|p| p.map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&back.points), bits(&input.points));
        assert_eq!(back.hexagon, input.hexagon);
    }

    #[test]
    fn every_domain_refusal_round_trips() {
        let problems = [
            InputError::DanglingSegment {
                segment: 4,
                vertex: 5,
            },
            InputError::BranchingSegment {
                segment: 7,
                vertex: 2,
                count: 3,
            },
            InputError::SegmentInsideDomain { segment: 9 },
            InputError::SegmentOutsideDomain { segment: 1 },
            InputError::PointOutsideDomain { point: 12 },
            InputError::NoEnclosedRegion {
                segments: 3,
                cause: Unenclosed::Open,
            },
            InputError::NoEnclosedRegion {
                segments: 4,
                cause: Unenclosed::Holes,
            },
            InputError::NoEnclosedRegion {
                segments: 1,
                cause: Unenclosed::Collinear,
            },
        ];
        for problem in problems {
            let (kind, v) = domain_refusal(&problem).unwrap();
            assert_eq!(domain_problem(kind, v), Some(problem));
        }
        assert_eq!(domain_refusal(&InputError::Empty), None);
        assert_eq!(domain_problem(5, [2, 3, 0]), None);
        assert_eq!(domain_problem(6, [0; 3]), None);
    }

    #[test]
    fn truncated_and_oversized_messages_are_errors() {
        let buf = encode_request(
            "spade",
            &Pslg::from_points(vec![[0.0, 0.0]]),
            &Params::default(),
            false,
        );
        for cut in 0..buf.len() {
            assert!(decode_request(&buf[..cut]).is_err(), "cut at {cut}");
        }
        let mut huge = buf.clone();
        // The point count sits right after magic, version, name, nine absent options and the
        // progress flag.
        let at = 4 + 4 + 4 + 5 + 9 + 1;
        huge[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
        let e = decode_request(&huge).unwrap_err().to_string();
        assert!(e.contains("exceeds the message"), "{e}");
    }

    #[test]
    fn the_answer_is_found_after_foreign_output() {
        let run = MeshRun {
            mesh: TriMesh {
                vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                triangles: vec![[0, 1, 2]],
            },
            complete: true,
            stop_reason: None,
            steps: 3,
            elapsed: Duration::from_micros(5),
        };
        let mut out = b"Warning: something printed by C\n".to_vec();
        let mut payload = Vec::new();
        encode_run(&mut payload, &run, 4096);
        let len = payload.len() as u64;
        out.extend_from_slice(&payload);
        put_u64(&mut out, len);
        out.extend_from_slice(ANSWER_MAGIC);
        let back = decode_answer(trailer(&out).unwrap(), "x").unwrap();
        assert_eq!(back.run, run);
        assert_eq!(back.peak_rss_bytes, 4096);
        assert!(trailer(&out[..out.len() - 1]).is_none());
    }

    fn event(phase: &'static str, done: Option<u64>, total: Option<u64>) -> Event {
        Event {
            phase,
            count: done.map(|done| Count { done, total }),
        }
    }

    #[test]
    fn a_progress_line_carries_its_event_and_no_other_line_parses_as_one() {
        for e in [
            event("tiles", Some(45), Some(187)),
            event("self-check: the dual", None, None),
            event("repair round", Some(3), None),
        ] {
            let line = progress_line(&e);
            let back = parse_progress_line(line.as_bytes()).expect(&line);
            assert_eq!(back.phase, e.phase);
            assert_eq!(back.count, e.count);
        }
        assert_eq!(
            progress_line(&event("tiles", Some(45), Some(187))),
            "hexmesh-progress: 45 187 tiles\n"
        );
        for other in [
            "thread 'main' panicked at src/x.rs:1:1:\n",
            "hexmesh-progress: 45 187 tiles",
            "hexmesh-progress: - 187 tiles\n",
            "hexmesh-progress: x - tiles\n",
            "hexmesh-progress: 45 187\n",
            " hexmesh-progress: 45 187 tiles\n",
        ] {
            assert_eq!(parse_progress_line(other.as_bytes()), None, "{other:?}");
        }
    }

    #[test]
    fn the_childs_stderr_loses_its_progress_lines_and_keeps_everything_else_in_order() {
        let stderr = "Warning: from C\nhexmesh-progress: 1 7 tiles\nthread 'main' panicked\n\
                      hexmesh-progress: - - joining the tiles\nno newline at the end";
        let (events, reports) = mpsc::channel();
        let kept = read_stderr(Some(stderr.as_bytes()), &events);
        assert_eq!(
            String::from_utf8(kept).unwrap(),
            "Warning: from C\nthread 'main' panicked\nno newline at the end"
        );
        let reports: Vec<ChildProgress> = reports.try_iter().collect();
        assert_eq!(
            reports,
            [
                ChildProgress {
                    phase: "tiles".into(),
                    count: Some(Count {
                        done: 1,
                        total: Some(7)
                    })
                },
                ChildProgress {
                    phase: "joining the tiles".into(),
                    count: None
                },
            ]
        );
        // A parent that stopped listening still gets the rest of the text.
        let (events, reports) = mpsc::channel();
        drop(reports);
        let kept = read_stderr(Some(stderr.as_bytes()), &events);
        assert_eq!(
            String::from_utf8(kept).unwrap(),
            "Warning: from C\nthread 'main' panicked\nno newline at the end"
        );
    }

    #[test]
    fn within_a_phase_events_are_forwarded_a_tenth_of_a_second_apart() {
        let t0 = Instant::now();
        let at = |ms: u64| t0 + Duration::from_millis(ms);
        let tiles = |done| event("tiles", Some(done), Some(187));
        // The first event, and a new phase, pass at once.
        assert!(worth_forwarding(None, &tiles(0), t0));
        assert!(worth_forwarding(
            Some(("tiles", at(0))),
            &event("joining the tiles", None, None),
            at(1)
        ));
        // Within the phase, not before a tenth of a second has passed.
        assert!(!worth_forwarding(Some(("tiles", at(0))), &tiles(5), at(99)));
        assert!(worth_forwarding(Some(("tiles", at(0))), &tiles(5), at(100)));
        // The last item of a count passes at once.
        assert!(worth_forwarding(Some(("tiles", at(0))), &tiles(187), at(1)));
        // Rounds without a total are throttled like any other event of their phase.
        let round = event("local checks", Some(2), None);
        assert!(!worth_forwarding(
            Some(("local checks", at(0))),
            &round,
            at(50)
        ));
    }

    #[test]
    fn every_stop_reason_round_trips_with_its_figure() {
        let reasons = [
            StopReason::Steps(u64::MAX),
            StopReason::Vertices(7),
            StopReason::Time(Duration::new(3, 999_999_999)),
            StopReason::Rounds(1000),
            StopReason::Stalled("rounded crossings coincide".into()),
            StopReason::Timeout(Duration::from_millis(500)),
            StopReason::Reported("CGAL: ünïcode words".into()),
            StopReason::VertexLimit {
                needed: usize::MAX,
                limit: 2_000_000,
            },
        ];
        for reason in reasons {
            let run = MeshRun {
                mesh: TriMesh::default(),
                complete: false,
                stop_reason: Some(reason.clone()),
                steps: 1,
                elapsed: Duration::ZERO,
            };
            let mut payload = Vec::new();
            encode_run(&mut payload, &run, 0);
            let back = decode_answer(&payload, "x").unwrap();
            assert_eq!(back.run.stop_reason, Some(reason));
        }
    }
}
