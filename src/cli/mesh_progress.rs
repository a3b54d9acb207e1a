//! The progress of `hexmesh mesh` on a terminal: once a run has taken a second, a line on
//! stderr says what it is doing (meshing in the isolated child, with the child's resident
//! memory as it grows; writing the files; checking the mesh) and for how long. The parent
//! draws it from what it sees of the child (`isolate::run_isolated_watched`), so the child's
//! answer protocol is unchanged; nothing is drawn when stderr is not a terminal or the run
//! ends within the second.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Runs shorter than this show nothing.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// How often the child's memory is read from `/proc` while it meshes.
const READ_MEMORY_EVERY: Duration = Duration::from_millis(250);

/// The progress line of one `hexmesh mesh` run.
pub struct MeshProgress {
    /// Where a bar would draw: `None` when stderr is not a terminal (nothing is ever shown).
    target: Option<fn() -> ProgressDrawTarget>,
    bar: Option<ProgressBar>,
    start: Instant,
    mesher: String,
    last_read: Option<Duration>,
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
            cleared: false,
        }
    }

    /// The child meshing, `spent` into its run, with process id `pid`
    /// (`isolate::run_isolated_watched` calls it).
    pub fn meshing(&mut self, spent: Duration, pid: u32) {
        if self.target.is_none() || spent < SHOW_AFTER {
            return;
        }
        if self
            .last_read
            .is_some_and(|t| spent.saturating_sub(t) < READ_MEMORY_EVERY)
        {
            return;
        }
        self.last_read = Some(spent);
        let rss = resident_bytes(pid);
        self.show(meshing_line(&self.mesher, rss));
    }

    /// A step after the meshing (writing the files, checking the mesh), shown when the run
    /// has already taken a second.
    pub fn phase(&mut self, what: &str) {
        if self.bar.is_some() || self.cleared || self.start.elapsed() >= SHOW_AFTER {
            self.show(what.to_string());
        }
    }

    /// Whether a line is drawn now.
    #[cfg(test)]
    fn is_shown(&self) -> bool {
        self.bar.is_some()
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

/// What the line says while the child meshes.
fn meshing_line(mesher: &str, resident: Option<u64>) -> String {
    match resident {
        Some(bytes) => format!(
            "meshing with {mesher} (isolated child, {:.2} GB resident)",
            bytes as f64 / 1e9
        ),
        None => format!("meshing with {mesher} (isolated child)"),
    }
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

    #[test]
    fn nothing_is_drawn_off_a_terminal_however_long_the_run() {
        let mut p = MeshProgress::with_target("hex", None);
        p.meshing(Duration::from_secs(30), std::process::id());
        p.phase("writing the files");
        assert!(!p.is_shown());
        p.finish();
    }

    #[test]
    fn a_line_appears_only_once_the_run_has_taken_a_second() {
        let mut p = MeshProgress::with_target("hex", Some(ProgressDrawTarget::hidden));
        p.meshing(Duration::from_millis(400), std::process::id());
        p.meshing(Duration::from_millis(999), std::process::id());
        assert!(!p.is_shown(), "a run within its first second shows nothing");
        p.meshing(Duration::from_millis(1000), std::process::id());
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
    fn the_meshing_line_names_the_mesher_and_the_memory_when_known() {
        assert_eq!(
            meshing_line("hex", Some(1_234_000_000)),
            "meshing with hex (isolated child, 1.23 GB resident)"
        );
        assert_eq!(
            meshing_line("triangle", None),
            "meshing with triangle (isolated child)"
        );
        // This process's own memory is readable where /proc is.
        if std::path::Path::new("/proc/self/status").exists() {
            assert!(resident_bytes(std::process::id()).is_some_and(|b| b > 0));
        }
    }
}
