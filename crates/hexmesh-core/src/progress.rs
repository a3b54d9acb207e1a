//! What a mesher is doing while it runs, for a caller that shows it (`hexmesh mesh` draws a
//! line on a terminal): a callback in [`Params::progress`](crate::Params::progress) that a
//! mesher calls at each phase of its run, and as the items of a counted phase finish.
//!
//! Reporting changes nothing the mesher computes: the mesh is the same bytes with an observer
//! or without one, and with none a report costs one test of an `Option`. `hex` reports its
//! phases and its tiles, `hex-simple` its phases, `rhomb` on a domain its tree, its band, each
//! fill it tries and each finer band; the other meshers report nothing.

use std::fmt;
use std::sync::{Arc, Mutex, PoisonError};

/// One report of a mesher: the phase it is in, and how far into it when it counts items.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Event {
    /// What the mesher is doing, in a few words ("tiles", "self-check of the dual").
    pub phase: &'static str,
    /// How many of the phase's items are done, when it counts them.
    pub count: Option<Count>,
}

/// Items of a phase done, and of how many when that is known beforehand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Count {
    /// Items finished so far.
    pub done: u64,
    /// All the phase's items; `None` when the phase goes on until it is done (repair rounds).
    pub total: Option<u64>,
}

/// The observer of a run's progress: a callback the mesher calls with each [`Event`], from
/// whichever of its threads reached it. A mesher never calls it from two threads at once,
/// and the events of a counted phase come in the order of their counts.
///
/// Two `Progress` values are equal when they are the same callback (clones of one
/// `Progress`), so that `Params` stay comparable.
#[derive(Clone)]
pub struct Progress(Arc<dyn Fn(Event) + Send + Sync>);

impl Progress {
    /// An observer calling `report` with each event.
    pub fn new(report: impl Fn(Event) + Send + Sync + 'static) -> Progress {
        Progress(Arc::new(report))
    }

    /// Calls the observer with `event`.
    pub fn report(&self, event: Event) {
        (self.0)(event)
    }
}

impl fmt::Debug for Progress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Progress(..)")
    }
}

impl PartialEq for Progress {
    fn eq(&self, other: &Progress) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Reports that the run enters `phase`, when someone listens.
pub(crate) fn phase(progress: Option<&Progress>, phase: &'static str) {
    if let Some(p) = progress {
        p.report(Event { phase, count: None });
    }
}

/// Reports the `done`-th round of `phase`, whose rounds are not known beforehand.
pub(crate) fn round(progress: Option<&Progress>, phase: &'static str, done: u64) {
    if let Some(p) = progress {
        p.report(Event {
            phase,
            count: Some(Count { done, total: None }),
        });
    }
}

/// The items of one counted phase, finished on any thread: `tick` reports each with its
/// count. The count and the report are made under one lock, so that the observer sees the
/// counts in order (0 of `total` first, `total` of `total` last) and never two calls at once.
pub(crate) struct Counter<'a> {
    progress: Option<&'a Progress>,
    phase: &'static str,
    total: u64,
    done: Mutex<u64>,
}

impl<'a> Counter<'a> {
    /// A phase of `total` items, reported as begun (0 done).
    pub(crate) fn start(progress: Option<&'a Progress>, phase: &'static str, total: u64) -> Self {
        let counter = Counter {
            progress,
            phase,
            total,
            done: Mutex::new(0),
        };
        counter.report(0);
        counter
    }

    /// One more item finished.
    pub(crate) fn tick(&self) {
        if self.progress.is_none() {
            return;
        }
        let mut done = self.done.lock().unwrap_or_else(PoisonError::into_inner);
        *done += 1;
        self.report(*done);
    }

    fn report(&self, done: u64) {
        if let Some(p) = self.progress {
            p.report(Event {
                phase: self.phase,
                count: Some(Count {
                    done,
                    total: Some(self.total),
                }),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_counter_on_many_threads_reports_every_count_once_and_in_order() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let progress = {
            let seen = Arc::clone(&seen);
            Progress::new(move |e| seen.lock().unwrap().push(e))
        };
        let counter = Counter::start(Some(&progress), "items", 400);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| (0..100).for_each(|_| counter.tick()));
            }
        });
        let seen = seen.lock().unwrap();
        let counts: Vec<u64> = seen.iter().map(|e| e.count.unwrap().done).collect();
        assert_eq!(counts, (0..=400).collect::<Vec<u64>>());
        assert!(seen
            .iter()
            .all(|e| e.phase == "items" && e.count.unwrap().total == Some(400)));
    }

    #[test]
    fn progress_values_are_equal_when_they_are_the_same_callback() {
        let a = Progress::new(|_| {});
        let b = Progress::new(|_| {});
        assert_eq!(a, a.clone());
        assert_ne!(a, b);
        assert_eq!(format!("{a:?}"), "Progress(..)");
    }
}
