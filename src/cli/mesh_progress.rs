//! The progress of `hexmesh mesh` on a terminal: once a run has taken a second, a line on
//! stderr says what it is doing (meshing in the isolated child, with the mesher's phase and
//! count when it reports them, e.g. "tiles 45/187" with a bar, and the child's resident
//! memory as it grows; writing the files; checking the mesh) and for how long. The parent
//! draws it from what it sees of the child (`isolate::run_isolated_watched`): the memory from
//! `/proc`, the phase from the progress lines the child forwards on its stderr (which meshers
//! report, and what, is in `hexmesh_core::progress`). Nothing is drawn when stderr is not a
//! terminal or the run ends within the second.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::isolate::{ChildProgress, Watch};
use crate::progress::Count;

/// Runs shorter than this show nothing.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// How often the child's memory is read from `/proc` while it meshes.
const READ_MEMORY_EVERY: Duration = Duration::from_millis(250);

/// The width of the bar of a counted phase, in characters.
const BAR_WIDTH: usize = 20;

/// The progress line of one `hexmesh mesh` run.
pub struct MeshProgress {
    /// Where a bar would draw: `None` when stderr is not a terminal (nothing is ever shown).
    target: Option<fn() -> ProgressDrawTarget>,
    bar: Option<ProgressBar>,
    start: Instant,
    mesher: String,
    /// When the child's memory was last read, and what was read.
    last_read: Option<Duration>,
    resident: Option<u64>,
    /// The mesher's report the line shows.
    shown_progress: Option<ChildProgress>,
    /// A line was drawn and cleared (`clear`): the next phase is drawn at once.
    cleared: bool,
}

impl MeshProgress {
    /// The progress of a run of `mesher`, drawn on stderr when it is a terminal.
    pub fn new(mesher: &str) -> MeshProgress {
        let target = std::io::stderr()
            .is_terminal()
            .then_some(ProgressDrawTarget::stderr as fn() -> ProgressDrawTarget);
        MeshProgress::with_target(mesher, target)
    }

    /// The progress drawn on the target `target` makes (`None`: never drawn).
    fn with_target(mesher: &str, target: Option<fn() -> ProgressDrawTarget>) -> MeshProgress {
        MeshProgress {
            target,
            bar: None,
            start: Instant::now(),
            mesher: mesher.to_string(),
            last_read: None,
            resident: None,
            shown_progress: None,
            cleared: false,
        }
    }

    /// The child meshing, as `watch` sees it (`isolate::run_isolated_watched` calls it): the
    /// line is drawn again when the mesher reports something new, and with the memory read
    /// again every `READ_MEMORY_EVERY`.
    pub fn meshing(&mut self, watch: &Watch<'_>) {
        if self.target.is_none() || watch.spent < SHOW_AFTER {
            return;
        }
        let memory_due = self
            .last_read
            .is_none_or(|t| watch.spent.saturating_sub(t) >= READ_MEMORY_EVERY);
        if memory_due {
            self.last_read = Some(watch.spent);
            self.resident = resident_bytes(watch.pid);
        } else if watch.progress == self.shown_progress.as_ref() {
            return;
        }
        self.shown_progress = watch.progress.cloned();
        self.show(meshing_line(&self.mesher, watch.progress, self.resident));
    }

    /// A step after the meshing (writing the files, checking the mesh), shown when the run
    /// has already taken a second.
    pub fn phase(&mut self, what: &str) {
        if self.bar.is_some() || self.cleared || self.start.elapsed() >= SHOW_AFTER {
            self.show(what.to_string());
        }
    }

    /// Whether a line can be drawn at all (stderr is a terminal): only then is the child
    /// asked to forward the mesher's progress.
    pub fn draws(&self) -> bool {
        self.target.is_some()
    }

    /// Whether a line is drawn now.
    #[cfg(test)]
    fn is_shown(&self) -> bool {
        self.bar.is_some()
    }

    /// What the line drawn now says (`None` when none is).
    #[cfg(test)]
    fn shown(&self) -> Option<String> {
        self.bar.as_ref().map(ProgressBar::message)
    }

    /// Clears the line for the command's own output; a later `phase` draws it again (the
    /// elapsed time still counting from the start of the run).
    pub fn clear(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
            self.cleared = true;
        }
    }

    /// Clears the line (the command's own output follows); dropping the progress does too,
    /// so that an error is not printed after a stale line.
    pub fn finish(self) {
        drop(self);
    }

    fn show(&mut self, msg: String) {
        let Some(target) = self.target else {
            return;
        };
        let start = self.start;
        let bar = self.bar.get_or_insert_with(|| {
            let bar = ProgressBar::with_draw_target(None, target());
            if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed:>4} {msg}") {
                bar.set_style(style);
            }
            // The elapsed time counts from the start of the run, not from the first line.
            bar.set_elapsed(start.elapsed());
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        });
        bar.set_message(msg);
    }
}

impl Drop for MeshProgress {
    fn drop(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

/// What the line says while the child meshes: the mesher's last report first when there is
/// one (so that a narrow terminal, which cuts the line's end, keeps it), then the memory.
fn meshing_line(mesher: &str, progress: Option<&ChildProgress>, resident: Option<u64>) -> String {
    let gb = |bytes: u64| format!("{:.2} GB resident", bytes as f64 / 1e9);
    let Some(progress) = progress else {
        return match resident {
            Some(bytes) => format!("meshing with {mesher} (isolated child, {})", gb(bytes)),
            None => format!("meshing with {mesher} (isolated child)"),
        };
    };
    let mut line = format!("meshing with {mesher}: {}", progress.phase);
    match progress.count {
        Some(Count {
            done,
            total: Some(total),
        }) => line.push_str(&format!(" {done}/{total} {}", bar(done, total))),
        Some(Count { done, total: None }) => line.push_str(&format!(" {done}")),
        None => {}
    }
    if let Some(bytes) = resident {
        line.push_str(&format!(" ({})", gb(bytes)));
    }
    line
}

/// A bar of `BAR_WIDTH` characters, filled in the share `done` of `total`.
fn bar(done: u64, total: u64) -> String {
    let filled = if total == 0 {
        BAR_WIDTH
    } else {
        (done.min(total) as u128 * BAR_WIDTH as u128 / total as u128) as usize
    };
    format!("[{}{}]", "=".repeat(filled), " ".repeat(BAR_WIDTH - filled))
}

/// The resident memory of process `pid` (`VmRSS` of its `/proc` status), if it can be read.
fn resident_bytes(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let kb = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse::<u64>()
        .ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the parent sees of a child `millis` into its run (this process stands in for the
    /// child, so that its memory can be read).
    fn watch(millis: u64, progress: Option<&ChildProgress>) -> Watch<'_> {
        Watch {
            spent: Duration::from_millis(millis),
            pid: std::process::id(),
            progress,
        }
    }

    fn report(phase: &str, done: Option<u64>, total: Option<u64>) -> ChildProgress {
        ChildProgress {
            phase: phase.to_string(),
            count: done.map(|done| Count { done, total }),
        }
    }

    #[test]
    fn nothing_is_drawn_off_a_terminal_however_long_the_run() {
        let mut p = MeshProgress::with_target("hex", None);
        p.meshing(&watch(30_000, Some(&report("tiles", Some(3), Some(9)))));
        p.phase("writing the files");
        assert!(!p.is_shown());
        p.finish();
    }

    #[test]
    fn a_line_appears_only_once_the_run_has_taken_a_second() {
        let mut p = MeshProgress::with_target("hex", Some(ProgressDrawTarget::hidden));
        let tiles = report("tiles", Some(1), Some(187));
        p.meshing(&watch(400, Some(&tiles)));
        p.meshing(&watch(999, Some(&tiles)));
        assert!(!p.is_shown(), "a run within its first second shows nothing");
        p.meshing(&watch(1000, Some(&tiles)));
        assert!(p.is_shown());
        p.phase("writing the files");
        assert!(p.is_shown());
        // Cleared for the command's output, drawn again for the check.
        p.clear();
        assert!(!p.is_shown());
        p.phase("checking the mesh against its promise");
        assert!(p.is_shown());
        p.finish();
    }

    #[test]
    fn the_line_follows_the_meshers_reports_between_reads_of_the_memory() {
        let mut p = MeshProgress::with_target("hex", Some(ProgressDrawTarget::hidden));
        let starts_with = |p: &MeshProgress, text: &str| {
            let shown = p.shown().unwrap_or_default();
            assert!(shown.starts_with(text), "{shown:?} is not {text:?}...");
        };
        p.meshing(&watch(1000, Some(&report("tiles", Some(45), Some(187)))));
        starts_with(&p, "meshing with hex: tiles 45/187 [====                ]");
        // 10 ms later the memory is not read again, but a new report is drawn at once.
        p.meshing(&watch(1010, Some(&report("tiles", Some(187), Some(187)))));
        starts_with(&p, "meshing with hex: tiles 187/187 [====================]");
        p.meshing(&watch(
            1020,
            Some(&report("self-check of the dual", None, None)),
        ));
        starts_with(&p, "meshing with hex: self-check of the dual");
        p.meshing(&watch(1030, Some(&report("repair round", Some(2), None))));
        starts_with(&p, "meshing with hex: repair round 2");
        p.finish();
        // A mesher that reports nothing: the line names the mesher and the memory alone.
        let mut p = MeshProgress::with_target("triangle", Some(ProgressDrawTarget::hidden));
        p.meshing(&watch(1500, None));
        starts_with(&p, "meshing with triangle (isolated child");
        p.finish();
    }

    #[test]
    fn the_meshing_line_names_the_mesher_the_phase_and_the_memory_when_known() {
        assert_eq!(
            meshing_line("hex", None, Some(1_234_000_000)),
            "meshing with hex (isolated child, 1.23 GB resident)"
        );
        assert_eq!(
            meshing_line("triangle", None, None),
            "meshing with triangle (isolated child)"
        );
        assert_eq!(
            meshing_line(
                "hex",
                Some(&report("tiles", Some(45), Some(187))),
                Some(1_234_000_000)
            ),
            "meshing with hex: tiles 45/187 [====                ] (1.23 GB resident)"
        );
        assert_eq!(
            meshing_line("hex", Some(&report("extended rules", None, None)), None),
            "meshing with hex: extended rules"
        );
        assert_eq!(
            meshing_line("hex", Some(&report("repair round", Some(3), None)), None),
            "meshing with hex: repair round 3"
        );
        // This process's own memory is readable where /proc is.
        if std::path::Path::new("/proc/self/status").exists() {
            assert!(resident_bytes(std::process::id()).is_some_and(|b| b > 0));
        }
    }

    #[test]
    fn the_bar_fills_with_the_share_done() {
        assert_eq!(bar(0, 187), format!("[{}]", " ".repeat(20)));
        assert_eq!(
            bar(94, 187),
            format!("[{}{}]", "=".repeat(10), " ".repeat(10))
        );
        assert_eq!(bar(187, 187), format!("[{}]", "=".repeat(20)));
        // A count past its total, or of nothing, is a full bar.
        assert_eq!(bar(200, 187), bar(187, 187));
        assert_eq!(bar(0, 0), bar(1, 1));
    }
}
