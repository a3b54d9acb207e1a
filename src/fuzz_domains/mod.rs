//! A seeded fuzz campaign on polygonal domains (`hexmesh fuzz --domains --mesher NAME`), for
//! every mesher that keeps segments. Each case is a valid domain in the sense of paper 001:
//! one outer simple polygon of at least four corners, polygonal holes strictly inside it and
//! disjoint from each other (each with a seed inside it, as Triangle's .poly gives holes), and
//! isolated points inside the domain and outside the holes. The families stress what a mesher
//! of domains must get right: random simple polygons, stars, a corner down to 1°, holes,
//! interior points, thin slits and slots down to 1e-3 of the size, a segment 1e-3 of its
//! neighbour's length, and projected map coordinates.
//!
//! Every domain is checked with exact orientation signs before it is used (`is_valid_domain`):
//! no two segments meet except consecutive ones at their shared corner, every corner makes an
//! angle of at least 1°, the holes and points lie where they must, and `Pslg::check` passes.
//! A draw that fails is thrown away and drawn again from the same stream, at most
//! `MAX_REDRAWS` times.
//!
//! Each case is meshed under a per-case `Budget` (`case_budget`), in this process (a panic is
//! caught) or, for Triangle, CGAL and `hex` (`runs_isolated`), in a child process
//! (`isolate::run_isolated`) that is killed when it overruns. A case passes, is refused (an
//! `Error::Input`, counted by its reason), or fails: the verdict fails against what the mesher
//! promises (`promised`), a budget stopped it, or the mesher returned another error or
//! panicked. Failing inputs are written as Triangle .poly files when there is a directory.

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::error::{Error, InputError, Result};
use crate::fuzz::{record_failure, FamilyCounts, FuzzFailure};
use crate::isolate;
use crate::mesh::Pslg;
use crate::mesher::{Budget, MeshRun, Mesher, Params, StopReason};
use crate::quality::{self, Bounds};
use crate::report::case_params;

mod shapes;

pub use shapes::{
    generate_case, generate_family_case, DomainCase, FAMILIES, MAX_POINTS, MAX_REDRAWS,
    SHARP_MAX_DEG, SHARP_MIN_DEG, SHORT_LONG_RATIO, THINNEST,
};

/// The wall-clock time one case may take.
pub const CASE_TIME: Duration = Duration::from_secs(20);

/// The most vertices one mesh may have: a mesh of at most `MAX_POINTS` points that needs
/// more has run away.
pub const CASE_MAX_VERTICES: usize = 500_000;

/// How long an isolated child may run: the case's time and a margin for the child to start
/// and to report a budget it stopped at itself.
pub const ISOLATION_TIMEOUT: Duration = Duration::from_secs(30);

/// Where a campaign runs each meshing call.
#[derive(Debug, Clone, PartialEq)]
pub enum Runner {
    /// In this process, under the case's budget, with panics caught.
    InProcess,
    /// In a child process of the hexmesh binary `exe` (`isolate::run_isolated`), killed
    /// after `ISOLATION_TIMEOUT`.
    Isolated { exe: PathBuf },
}

/// True for the meshers that run in a child process: C and C++ code (Triangle, CGAL) can
/// exit or abort the process and Triangle does not keep a budget; `gmsh` runs a program that
/// must not outlive a timeout (it dies with the child); `hex` is slow on many
/// domains (up to its 20 s budget), and a domain on which it missed its budget would stall
/// the campaign, so it is bounded by the child's timeout too.
pub fn runs_isolated(mesher: &str) -> bool {
    matches!(
        mesher,
        "triangle" | "cgal" | "cgal-conforming" | "gmsh" | "hex"
    )
}

/// The runner a campaign of `mesher` uses (`runs_isolated`); an isolated one needs the
/// hexmesh binary (`isolate::find_exe`).
pub fn runner_for(mesher: &str) -> Result<Runner> {
    if runs_isolated(mesher) {
        Ok(Runner::Isolated {
            exe: isolate::find_exe()?,
        })
    } else {
        Ok(Runner::InProcess)
    }
}

/// The limits each case is meshed under.
pub fn case_budget() -> Budget {
    Budget {
        max_steps: None,
        max_vertices: Some(CASE_MAX_VERTICES),
        max_time: Some(CASE_TIME),
    }
}

/// The refusals or failures of one reason: how many, and the first (its message on one line).
#[derive(Debug, Clone, PartialEq)]
pub struct Tally {
    pub count: u64,
    pub first_case: u64,
    pub first_family: &'static str,
    pub first_message: String,
}

/// What a campaign on domains found.
#[derive(Debug, Clone, PartialEq)]
pub struct DomainSummary {
    pub mesher: String,
    pub seed: u64,
    /// The first case's number (0 unless the campaign was asked to start later).
    pub first: u64,
    pub cases: u64,
    pub passed: u64,
    pub refused: u64,
    pub failures: u64,
    /// Refusals by reason (the `InputError` variant's name), in name order.
    pub refusals: BTreeMap<String, Tally>,
    /// Failures by reason (`Failure::reason`), in name order.
    pub failure_reasons: BTreeMap<String, Tally>,
    /// Cases where the generator gave up and meshed `fallback_domain` (none expected).
    pub fallbacks: u64,
    /// Over the meshes that passed: the smallest and largest angle, in degrees; of the
    /// triangles near a segment and of the others (the verdict's split), when there were any.
    pub min_angle: Option<f64>,
    pub max_angle: Option<f64>,
    pub near_min_angle: Option<f64>,
    pub near_max_angle: Option<f64>,
    /// The smallest near-segment angle but at input corners sharper than the bound taken
    /// whole, for a mesher that promises one there (the verdict's near-segment row).
    pub near_min_angle_kept: Option<f64>,
    pub interior_min_angle: Option<f64>,
    pub interior_max_angle: Option<f64>,
    /// The most triangles in one mesh that passed.
    pub max_triangles: usize,
    /// Cases, refusals and failures per family, in the order of `FAMILIES`.
    pub families: Vec<FamilyCounts>,
    /// Seconds per family, in the order of `FAMILIES`: where a campaign's time goes.
    pub family_times: Vec<FamilyTime>,
    pub first_failure: Option<FuzzFailure>,
    /// Every failing case: case number, family, where its input was written.
    pub failed: Vec<(u64, &'static str, Option<PathBuf>)>,
}

/// The seconds a family's cases took, every outcome counted.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FamilyTime {
    /// All its cases together.
    pub seconds: f64,
    /// Its slowest case (seconds, case number).
    pub slowest: Option<(f64, u64)>,
}

impl DomainSummary {
    /// The slowest case (seconds, case number), every outcome counted: the slowest of the
    /// families' (the earlier case on a tie).
    pub fn slowest(&self) -> Option<(f64, u64)> {
        self.family_times
            .iter()
            .filter_map(|t| t.slowest)
            .reduce(|a, b| {
                if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
                    b
                } else {
                    a
                }
            })
    }

    /// The summary with its times cleared: what is the same for any number of jobs.
    pub fn without_times(mut self) -> Self {
        for t in &mut self.family_times {
            *t = FamilyTime::default();
        }
        self
    }
}

/// How one case ended.
enum Outcome {
    Passed(Box<quality::Verdict>),
    Refused(InputError, String),
    Failed(Failure),
}

/// Why a case failed: a short key the summary counts failures by, and the whole message.
struct Failure {
    /// "verdict: " and the checks that failed, "stopped early: budget" or "stopped early:
    /// child timed out", "mesher error: " and its kind (`error_kind`), "panic" or "verdict
    /// panic".
    reason: String,
    /// The first line tells what failed; a verdict's table follows.
    message: String,
}

/// The outcome of a case that failed for `reason`.
fn failed(reason: &str, message: String) -> Outcome {
    Outcome::Failed(Failure {
        reason: reason.to_string(),
        message,
    })
}

/// Adds one case of `reason` to `tally`.
fn count(
    tally: &mut BTreeMap<String, Tally>,
    reason: String,
    case: u64,
    family: &'static str,
    message: &str,
) {
    let first_message = message.lines().next().unwrap_or_default().to_string();
    tally
        .entry(reason)
        .and_modify(|r| r.count += 1)
        .or_insert(Tally {
            count: 1,
            first_case: case,
            first_family: family,
            first_message,
        });
}

fn min_opt(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        (x, y) => x.or(y),
    }
}

fn max_opt(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.max(y)),
        (x, y) => x.or(y),
    }
}

/// The name of an input error's variant: the key refusals are counted by.
pub fn refusal_reason(problem: &InputError) -> String {
    let debug = format!("{problem:?}");
    debug
        .split(|c: char| !c.is_alphanumeric())
        .next()
        .unwrap_or_default()
        .to_string()
}

/// Runs the generated domains numbered `cases` (`0..10_000` is a whole campaign, `n..n + 1`
/// case `n` of it alone) through the mesher `mesher`, seeded by `seed`, each where `runner`
/// says; `progress` is called after each case with the number done. The input of
/// each failing case is written into `out` (`write_failure`, up to a hundred) when it is
/// given. Errors when the mesher is unknown or does not keep segments (a usage error that
/// names the meshers that do).
pub fn domain_campaign(
    mesher: &str,
    cases: Range<u64>,
    seed: u64,
    out: Option<&Path>,
    runner: &Runner,
    jobs: usize,
    progress: impl FnMut(u64),
) -> Result<DomainSummary> {
    let m = crate::registry::mesher(mesher)?;
    domain_campaign_with(m.as_ref(), cases, seed, out, runner, jobs, progress)
}

/// `domain_campaign` with a mesher given as such (an isolated runner runs the registered
/// mesher of its name).
///
/// `jobs` cases are meshed side by side (at least one), each on one thread of the mesher's
/// when there are several: the summary is folded in case order, so it is the same for any
/// number of jobs but for the times (`family_times`).
pub fn domain_campaign_with(
    m: &dyn Mesher,
    cases: Range<u64>,
    seed: u64,
    out: Option<&Path>,
    runner: &Runner,
    jobs: usize,
    mut progress: impl FnMut(u64),
) -> Result<DomainSummary> {
    let mesher = m.name();
    if !m.supports_segments() {
        return Err(Error::Usage(format!(
            "{mesher} does not keep segments, so it cannot mesh a domain; fuzz --domains runs \
             the meshers that do: {}",
            segment_meshers().join(", ")
        )));
    }
    let jobs = jobs.max(1);
    let (first, end) = (cases.start, cases.end);
    let mut params = case_params(mesher).0.with_budget(case_budget());
    if jobs > 1 {
        params = params.with_threads(std::num::NonZeroUsize::MIN);
    }
    // What the mesher promises for these parameters (a reference: the angle it is asked for).
    let bounds = m.promise(&params);
    let mut summary = DomainSummary {
        mesher: mesher.to_string(),
        seed,
        first: cases.start,
        cases: 0,
        passed: 0,
        refused: 0,
        failures: 0,
        refusals: BTreeMap::new(),
        failure_reasons: BTreeMap::new(),
        fallbacks: 0,
        min_angle: None,
        max_angle: None,
        near_min_angle: None,
        near_max_angle: None,
        near_min_angle_kept: None,
        interior_min_angle: None,
        interior_max_angle: None,
        max_triangles: 0,
        families: FAMILIES
            .iter()
            .map(|&family| FamilyCounts {
                family,
                cases: 0,
                refused: 0,
                failures: 0,
            })
            .collect(),
        family_times: vec![FamilyTime::default(); FAMILIES.len()],
        first_failure: None,
        failed: Vec::new(),
    };
    let work = |case: u64| {
        let generated = generate_case(seed, case);
        let start = std::time::Instant::now();
        let outcome = run_case(m, &generated.input, &params, &bounds, runner);
        let secs = start.elapsed().as_secs_f64();
        Meshed {
            case,
            generated,
            outcome,
            secs,
        }
    };
    // Each case meshed is added to the summary in case order.
    let mut fold = |meshed: Meshed| {
        let case = meshed.case;
        fold_case(&mut summary, meshed, out, mesher, seed);
        progress(case + 1 - first);
    };
    if jobs == 1 {
        // On the calling thread (its stack), as before there were jobs.
        cases.for_each(|case| fold(work(case)));
    } else {
        // Each job takes the next case, meshes it and sends it back; the cases are folded
        // in order as they complete.
        let next = std::sync::atomic::AtomicU64::new(first);
        let (send, done) = std::sync::mpsc::channel();
        std::thread::scope(|scope| {
            for _ in 0..jobs {
                let send = send.clone();
                let (next, work) = (&next, &work);
                scope.spawn(move || loop {
                    let case = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    if case >= end || send.send(work(case)).is_err() {
                        break;
                    }
                });
            }
            drop(send);
            let mut waiting = BTreeMap::new();
            let mut folded = first;
            for item in done {
                waiting.insert(item.case, item);
                while let Some(item) = waiting.remove(&folded) {
                    fold(item);
                    folded += 1;
                }
            }
        });
    }
    Ok(summary)
}

/// One case of a campaign as meshed: its number, its domain, what came of it and how many
/// seconds it took.
struct Meshed {
    case: u64,
    generated: DomainCase,
    outcome: Outcome,
    secs: f64,
}

/// A case of campaign `seed` added to `summary`; a failure's input written into `out`, if
/// given.
fn fold_case(
    summary: &mut DomainSummary,
    meshed: Meshed,
    out: Option<&Path>,
    mesher: &str,
    seed: u64,
) {
    let Meshed {
        case,
        generated,
        outcome,
        secs,
    } = meshed;
    let (family, input) = (generated.family, &generated.input);
    let fam = FAMILIES.iter().position(|&f| f == family).unwrap_or(0);
    summary.cases += 1;
    summary.families[fam].cases += 1;
    if generated.redraws == MAX_REDRAWS {
        summary.fallbacks += 1;
    }
    let time = &mut summary.family_times[fam];
    time.seconds += secs;
    if time.slowest.is_none_or(|(s, _)| secs > s) {
        time.slowest = Some((secs, case));
    }
    match outcome {
        Outcome::Passed(v) => {
            summary.passed += 1;
            let m = &v.metrics;
            summary.min_angle = min_opt(summary.min_angle, m.min_angle.map(|w| w.value));
            summary.max_angle = max_opt(summary.max_angle, m.max_angle.map(|w| w.value));
            if let Some(split) = &v.split {
                let (near, inner) = (&split.near, &split.interior);
                summary.near_min_angle =
                    min_opt(summary.near_min_angle, near.min_angle.map(|w| w.value));
                summary.near_max_angle =
                    max_opt(summary.near_max_angle, near.max_angle.map(|w| w.value));
                summary.interior_min_angle =
                    min_opt(summary.interior_min_angle, inner.min_angle.map(|w| w.value));
                let kept = v
                    .checks
                    .iter()
                    .find(|c| c.what == "min angle near segments (deg)")
                    .and_then(|c| c.value);
                summary.near_min_angle_kept = min_opt(summary.near_min_angle_kept, kept);
                summary.interior_max_angle =
                    max_opt(summary.interior_max_angle, inner.max_angle.map(|w| w.value));
            }
            summary.max_triangles = summary.max_triangles.max(m.triangles);
        }
        Outcome::Refused(problem, message) => {
            summary.refused += 1;
            summary.families[fam].refused += 1;
            count(
                &mut summary.refusals,
                refusal_reason(&problem),
                case,
                family,
                &message,
            );
        }
        Outcome::Failed(Failure { reason, message }) => {
            count(&mut summary.failure_reasons, reason, case, family, &message);
            summary.failures += 1;
            summary.families[fam].failures += 1;
            record_failure(
                &mut summary.failed,
                &mut summary.first_failure,
                FuzzFailure {
                    case,
                    family,
                    message,
                    path: None,
                },
                out.map(|dir| move || write_failure(dir, mesher, seed, case, family, input)),
            );
        }
    }
}

/// The registered meshers and variants that keep segments.
pub fn segment_meshers() -> Vec<&'static str> {
    crate::registry::meshers()
        .into_iter()
        .chain(crate::registry::variants())
        .filter(|m| m.supports_segments())
        .map(|m| m.name())
        .collect()
}

/// The text of a panic's payload.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

/// The kind of a mesher's error message, which failures are counted by: its words up to
/// the first that holds a figure or a bracket (where the particulars start) or through a
/// colon after the first word, at most seven, without a closing "of", "at", "in", "near",
/// "after" or colon. "stopped: time budget of 20s reached" is "stopped: time budget", "no
/// triangulation in [30°, 90°] joins ..." is "no triangulation".
pub fn error_kind(message: &str) -> String {
    let mut words: Vec<&str> = Vec::new();
    for w in message.split_whitespace().take(7) {
        if w.contains(|c: char| c.is_ascii_digit() || "([{".contains(c)) {
            break;
        }
        words.push(w);
        if words.len() > 1 && w.ends_with(':') {
            break;
        }
    }
    while words
        .last()
        .is_some_and(|w| ["of", "at", "in", "near", "after"].contains(w))
    {
        words.pop();
    }
    let kind = words.join(" ");
    kind.trim_end_matches(':').to_string()
}

fn run_case(
    mesher: &dyn Mesher,
    input: &Pslg,
    params: &Params,
    bounds: &Bounds,
    runner: &Runner,
) -> Outcome {
    let result: Result<MeshRun> = match runner {
        Runner::InProcess => match catch_unwind(AssertUnwindSafe(|| mesher.mesh(input, params))) {
            Ok(r) => r,
            Err(payload) => {
                return failed(
                    "panic",
                    format!("panicked: {}", panic_text(payload.as_ref())),
                )
            }
        },
        Runner::Isolated { exe } => {
            isolate::run_isolated(exe, mesher.name(), input, params, ISOLATION_TIMEOUT)
                .map(|iso| iso.run)
        }
    };
    let run = match result {
        Ok(run) => run,
        Err(Error::Input { problem, .. }) => {
            let message = problem.describe(0);
            return Outcome::Refused(problem, message);
        }
        Err(e) => {
            let key = match &e {
                Error::Mesher { message, .. } => format!("mesher error: {}", error_kind(message)),
                _ => "mesher error".to_string(),
            };
            return failed(&key, e.to_string());
        }
    };
    if !run.complete {
        let why = run
            .stop_reason
            .as_ref()
            .map_or("no reason given".into(), ToString::to_string);
        // `isolate::run_isolated` says so when it killed the child.
        let reason = if matches!(run.stop_reason, Some(StopReason::Timeout(_))) {
            "stopped early: child timed out"
        } else {
            "stopped early: budget"
        };
        return failed(reason, format!("stopped early: {why}"));
    }
    match catch_unwind(AssertUnwindSafe(|| {
        quality::verdict(&run.mesh, Some(input), Some(bounds)).numbered(quality::Numbering::FILES)
    })) {
        Ok(v) if v.passed() => Outcome::Passed(Box::new(v)),
        Ok(v) => {
            let checks: Vec<&quality::Check> = v
                .checks
                .iter()
                .filter(|c| c.status == quality::Status::Fail)
                .collect();
            let names: Vec<&str> = checks.iter().map(|c| c.what.as_str()).collect();
            let figures: Vec<String> = checks
                .iter()
                .map(|c| match c.value {
                    Some(x) => format!("{} = {x} ({} {})", c.what, c.relation, c.limit),
                    None => c.what.clone(),
                })
                .collect();
            failed(
                &format!("verdict: {}", names.join(", ")),
                format!("quality verdict failed: {}\n{v}", figures.join("; ")),
            )
        }
        Err(payload) => failed(
            "verdict panic",
            format!("the verdict panicked: {}", panic_text(payload.as_ref())),
        ),
    }
}

/// Writes the domain of a failing case as a Triangle .poly file into `dir` (created if
/// missing), named so that the files sort by mesher, seed and case and say the family:
/// `domains-MESHER-seedSEED-caseCCCCCC-FAMILY.poly`; returns its path.
pub fn write_failure(
    dir: &Path,
    mesher: &str,
    seed: u64,
    case: u64,
    family: &str,
    input: &Pslg,
) -> Result<PathBuf> {
    let io_err = |path: &Path, source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(|e| io_err(dir, e))?;
    let path = dir.join(format!(
        "domains-{mesher}-seed{seed}-case{case:06}-{family}.poly"
    ));
    crate::io::write_pslg(&path, input)?;
    let body = std::fs::read_to_string(&path).map_err(|e| io_err(&path, e))?;
    let text = format!(
        "# fuzz --domains case {case} of seed {seed} ({family}) that failed {mesher}\n{body}"
    );
    std::fs::write(&path, text).map_err(|e| io_err(&path, e))?;
    Ok(path)
}

fn degrees(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |a| format!("{a:.6}°"))
}

impl fmt::Display for DomainSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "fuzz --domains {}: {} cases{} (seed {}), {} passed, {} refused, {} failed",
            self.mesher,
            self.cases,
            crate::fuzz::from_case(self.first),
            self.seed,
            self.passed,
            self.refused,
            self.failures
        )?;
        if self.refusals.is_empty() {
            writeln!(f, "refusals by reason: none")?;
        } else {
            writeln!(f, "refusals by reason:")?;
            for (reason, r) in &self.refusals {
                writeln!(
                    f,
                    "  {reason:<16} {:>7} (first: case {} ({}): {})",
                    r.count, r.first_case, r.first_family, r.first_message
                )?;
            }
        }
        if !self.failure_reasons.is_empty() {
            writeln!(f, "failures by reason:")?;
            for (reason, r) in &self.failure_reasons {
                writeln!(
                    f,
                    "  {reason:<16} {:>7} (first: case {} ({}): {})",
                    r.count, r.first_case, r.first_family, r.first_message
                )?;
            }
        }
        writeln!(
            f,
            "worst angles over passing meshes: min {}, max {}; near segments min {}, max {}; \
             away from segments min {}, max {}; largest mesh {} triangles",
            degrees(self.min_angle),
            degrees(self.max_angle),
            degrees(self.near_min_angle),
            degrees(self.near_max_angle),
            degrees(self.interior_min_angle),
            degrees(self.interior_max_angle),
            self.max_triangles
        )?;
        if let Some(kept) = self.near_min_angle_kept {
            writeln!(
                f,
                "near segments min but whole sharp input corners (the promised figure): {}",
                degrees(Some(kept))
            )?;
        }
        if let Some((secs, case)) = self.slowest() {
            writeln!(f, "slowest case: {case} ({secs:.3} s)")?;
        }
        if self.fallbacks > 0 {
            writeln!(
                f,
                "the generator gave up after {MAX_REDRAWS} draws on {} cases and meshed the square instead",
                self.fallbacks
            )?;
        }
        for (c, t) in self.families.iter().zip(&self.family_times) {
            write!(
                f,
                "  {:<18} {:>7} cases, {:>6} refused, {:>5} failed, {:>9.1} s",
                c.family, c.cases, c.refused, c.failures, t.seconds
            )?;
            match t.slowest {
                Some((secs, case)) => writeln!(f, " (slowest: case {case}, {secs:.1} s)")?,
                None => writeln!(f)?,
            }
        }
        if let Some(first) = &self.first_failure {
            writeln!(
                f,
                "first failure: case {} ({}): {}",
                first.case, first.family, first.message
            )?;
            if let Some(path) = &first.path {
                writeln!(f, "input written to {}", path.display())?;
            }
        }
        if self.failed.len() > 1 {
            writeln!(f, "all {} failing cases:", self.failed.len())?;
            for (case, family, path) in &self.failed {
                match path {
                    Some(p) => writeln!(f, "  case {case} ({family}): {}", p.display())?,
                    None => writeln!(f, "  case {case} ({family})")?,
                }
            }
        }
        Ok(())
    }
}
