//! Progress of a long report, which can run for an hour and should show how far it got: an
//! indicatif bar when stderr is a terminal, plain numbered lines
//! otherwise (CI logs, `make report > log`), so a slow case can be found in either.

use std::io::{IsTerminal, Write};

use indicatif::{ProgressBar, ProgressStyle};

/// Reports steps of a known total to stderr.
pub struct Progress {
    bar: Option<ProgressBar>,
    total: u64,
    done: u64,
}

impl Progress {
    /// A bar on a terminal, plain lines otherwise.
    pub fn new(total: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total);
            if let Ok(style) =
                ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {msg}")
            {
                bar.set_style(style.progress_chars("=> "));
            }
            bar
        });
        Progress {
            bar,
            total,
            done: 0,
        }
    }

    /// Says what is running now.
    pub fn start(&self, what: &str) {
        match &self.bar {
            Some(bar) => bar.set_message(what.to_string()),
            None => {
                let _ = writeln!(
                    std::io::stderr(),
                    "[{}/{}] {what} ...",
                    self.done + 1,
                    self.total
                );
            }
        }
    }

    /// Marks one step done, with a one-line outcome.
    pub fn finish_step(&mut self, outcome: &str) {
        self.done += 1;
        match &self.bar {
            Some(bar) => {
                bar.inc(1);
                bar.println(outcome);
            }
            None => {
                let _ = writeln!(std::io::stderr(), "    {outcome}");
            }
        }
    }

    /// Runs `run`, which announces each of its steps by label as it starts it: a label
    /// finishes the step before it (with that step's label as outcome), and the last step
    /// is finished when `run` returns.
    pub fn labelled<R>(&mut self, run: impl FnOnce(&mut dyn FnMut(&str)) -> R) -> R {
        let mut last = String::new();
        let out = run(&mut |label: &str| {
            if !last.is_empty() {
                self.finish_step(&last);
            }
            self.start(label);
            last = label.to_string();
        });
        if !last.is_empty() {
            self.finish_step(&last);
        }
        out
    }

    /// A line that is not a step (a file written, a phase begun).
    pub fn note(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => {
                let _ = writeln!(std::io::stderr(), "{line}");
            }
        }
    }

    pub fn done(&self) -> u64 {
        self.done
    }

    /// Clears the bar.
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_counted() {
        let mut p = Progress::new(2);
        p.start("a");
        p.finish_step("a ok");
        p.start("b");
        p.finish_step("b ok");
        assert_eq!(p.done(), 2);
        p.finish();
    }

    #[test]
    fn labelled_steps_each_count_once_the_last_when_the_run_ends() {
        let mut p = Progress::new(3);
        let out = p.labelled(|step| {
            for label in ["a", "b", "c"] {
                step(label);
            }
            7
        });
        assert_eq!((out, p.done()), (7, 3));
        assert_eq!(p.labelled(|_| ()), ());
        assert_eq!(p.done(), 3, "a run that starts nothing finishes nothing");
        p.finish();
    }
}
