//! Long lists of independent work split over threads, with results in the order of the list
//! (so they do not depend on the split): engineering, not in paper 000. Used by the extended
//! rules, relocations, coarsening and self-check (`extended`, `blossom`), the dual (`dual`)
//! and the hierarchy's lists of leaves (`subdivision`), with the thread count of the
//! hierarchy (`Hierarchy::threads`, from `Params::threads`). `each_in_order` also overlaps an
//! ordered serial step (a merge) with the making of the next items.

/// Lists of at least this many items are split over threads by `in_parallel`.
pub(crate) const PARALLEL_MIN: usize = 8192;

/// `f` on consecutive chunks of `items`, one per thread of `threads` when the list is long,
/// in order.
pub(crate) fn in_parallel<T: Sync, R: Send>(
    threads: usize,
    items: &[T],
    f: impl Fn(&[T]) -> R + Sync,
) -> Vec<R> {
    in_parallel_from(threads, items, PARALLEL_MIN, f)
}

/// `in_parallel` for lists of at least `min` items (fewer items of more work each).
pub(crate) fn in_parallel_from<T: Sync, R: Send>(
    threads: usize,
    items: &[T],
    min: usize,
    f: impl Fn(&[T]) -> R + Sync,
) -> Vec<R> {
    if threads < 2 || items.len() < min.max(2) {
        return vec![f(items)];
    }
    let size = items.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let f = &f;
        let handles: Vec<_> = items
            .chunks(size)
            .skip(1)
            .map(|chunk| scope.spawn(move || f(chunk)))
            .collect();
        let mut out = vec![f(&items[..size.min(items.len())])];
        for handle in handles {
            match handle.join() {
                Ok(r) => out.push(r),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        out
    })
}

/// `f` on consecutive ranges of `0..n`, one per thread of `threads` when `n` is at least
/// `min`, in order.
pub(crate) fn ranges_in_parallel<R: Send>(
    threads: usize,
    n: usize,
    min: usize,
    f: impl Fn(std::ops::Range<usize>) -> R + Sync,
) -> Vec<R> {
    let ranges: Vec<std::ops::Range<usize>> = if threads < 2 || n < min.max(2) {
        // One range, the whole of `0..n`.
        std::iter::once(0..n).collect()
    } else {
        let size = n.div_ceil(threads);
        (0..n).step_by(size).map(|s| s..(s + size).min(n)).collect()
    };
    // One range a chunk: `in_parallel_from` gives each thread one.
    in_parallel_from(threads, &ranges, 2, |chunk| {
        debug_assert_eq!(chunk.len(), 1);
        f(chunk[0].clone())
    })
}

/// One list sorted by `key` from `runs`, each sorted by it: merged pairwise, a round per
/// doubling, so O(n log runs). Ties keep the earlier run's items first, so runs made by
/// `ranges_in_parallel` and sorted each merge as a stable sort of their concatenation would
/// order them.
pub(crate) fn merge_sorted_runs<T, K: Ord>(mut runs: Vec<Vec<T>>, key: impl Fn(&T) -> K) -> Vec<T> {
    while runs.len() > 1 {
        let mut next = Vec::with_capacity(runs.len().div_ceil(2));
        let mut it = runs.into_iter();
        while let Some(a) = it.next() {
            let Some(b) = it.next() else {
                next.push(a);
                break;
            };
            let mut out = Vec::with_capacity(a.len() + b.len());
            let (mut a, mut b) = (a.into_iter().peekable(), b.into_iter().peekable());
            loop {
                let take_b = match (a.peek(), b.peek()) {
                    (Some(x), Some(y)) => key(y) < key(x),
                    (Some(_), None) => false,
                    (None, Some(_)) => true,
                    (None, None) => break,
                };
                out.extend(if take_b { b.next() } else { a.next() });
            }
            next.push(out);
        }
        runs = next;
    }
    runs.pop().unwrap_or_default()
}

/// Sets `out[i] = f(i)` for every index, over `threads` threads in consecutive ranges when
/// `out` has at least `min` entries: `ranges_in_parallel` without a list of parts to join
/// (for a result of one entry a triangle, a second copy of it).
pub(crate) fn fill_in_parallel<R: Send>(
    threads: usize,
    out: &mut [R],
    min: usize,
    f: impl Fn(usize) -> R + Sync,
) {
    if threads < 2 || out.len() < min.max(2) {
        out.iter_mut().enumerate().for_each(|(i, r)| *r = f(i));
        return;
    }
    let size = out.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let f = &f;
        let mut chunks = out.chunks_mut(size).enumerate();
        let first = chunks.next();
        for (c, chunk) in chunks {
            scope.spawn(move || {
                for (i, r) in chunk.iter_mut().enumerate() {
                    *r = f(c * size + i);
                }
            });
        }
        if let Some((_, chunk)) = first {
            for (i, r) in chunk.iter_mut().enumerate() {
                *r = f(i);
            }
        }
    });
}

/// `f` on each of `items`, handed out one at a time to `threads` threads as each finishes
/// its last, so that items of uneven cost share out evenly; the results in the order of the
/// items.
pub(crate) fn each_in_parallel<T: Sync, R: Send>(
    threads: usize,
    items: &[T],
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    if threads < 2 || items.len() < 2 {
        return items.iter().map(f).collect();
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(item) = items.get(i) else {
                return done;
            };
            done.push((i, f(item)));
        }
    };
    let mut all = std::thread::scope(|scope| {
        let work = &work;
        let handles: Vec<_> = (1..threads.min(items.len()))
            .map(|_| scope.spawn(work))
            .collect();
        let mut all = work();
        for handle in handles {
            match handle.join() {
                Ok(done) => all.extend(done),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        all
    });
    all.sort_unstable_by_key(|d| d.0);
    all.into_iter().map(|d| d.1).collect()
}

/// `make` on each of `items` over `threads` threads, each result handed to `take` on the
/// calling thread in the order of the items, while the other threads make the next ones: the
/// ordered, serial part (`take`) overlaps the parallel one. No result is made more than
/// `window` items ahead of the next one taken, so at most about `window` results wait at once.
/// The calling thread makes items too while the next one to take is not ready.
pub(crate) fn each_in_order<T: Sync, R: Send>(
    threads: usize,
    items: &[T],
    window: usize,
    make: impl Fn(&T) -> R + Sync,
    mut take: impl FnMut(R),
) {
    use std::collections::BTreeMap;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Condvar, Mutex, PoisonError};

    if threads < 2 || items.len() < 2 {
        items.iter().for_each(|item| take(make(item)));
        return;
    }
    let window = window.max(1);
    /// The results made and not yet taken, how many are taken, and whether a thread failed.
    struct Shared<R> {
        ready: BTreeMap<usize, R>,
        taken: usize,
        failed: bool,
    }
    let shared = Mutex::new(Shared {
        ready: BTreeMap::new(),
        taken: 0,
        failed: false,
    });
    let changed = Condvar::new();
    let next = AtomicUsize::new(0);
    // The next item to make, if it lies within the window of the next one to take.
    let claim = |taken: usize| -> Option<usize> {
        let mut i = next.load(Ordering::Relaxed);
        while i < items.len() && i < taken + window {
            match next.compare_exchange(i, i + 1, Ordering::Relaxed, Ordering::Relaxed) {
                Ok(_) => return Some(i),
                Err(now) => i = now,
            }
        }
        None
    };
    let lock = || shared.lock().unwrap_or_else(PoisonError::into_inner);
    // A thread whose `make` panics says so, so that nobody waits for its result; the scope
    // then passes the panic on.
    struct OnPanic<'s, R>(&'s Mutex<Shared<R>>, &'s Condvar, &'s AtomicUsize, usize);
    impl<R> Drop for OnPanic<'_, R> {
        fn drop(&mut self) {
            if std::thread::panicking() {
                self.2.store(self.3, Ordering::Relaxed);
                self.0.lock().unwrap_or_else(PoisonError::into_inner).failed = true;
                self.1.notify_all();
            }
        }
    }
    let worker = || {
        let _guard = OnPanic(&shared, &changed, &next, items.len());
        loop {
            let i = {
                let mut s = lock();
                loop {
                    if s.failed || next.load(Ordering::Relaxed) >= items.len() {
                        return;
                    }
                    if let Some(i) = claim(s.taken) {
                        break i;
                    }
                    s = changed.wait(s).unwrap_or_else(PoisonError::into_inner);
                }
            };
            let r = make(&items[i]);
            lock().ready.insert(i, r);
            changed.notify_all();
        }
    };
    std::thread::scope(|scope| {
        let worker = &worker;
        for _ in 1..threads.min(items.len()) {
            scope.spawn(worker);
        }
        let _guard = OnPanic(&shared, &changed, &next, items.len());
        let mut k = 0;
        while k < items.len() {
            let (ready, mine) = {
                let mut s = lock();
                if s.failed {
                    return;
                }
                match s.ready.remove(&k) {
                    Some(r) => (Some(r), None),
                    None => (None, claim(k)),
                }
            };
            if let Some(r) = ready {
                take(r);
                k += 1;
                lock().taken = k;
                changed.notify_all();
            } else if let Some(i) = mine {
                let r = make(&items[i]);
                lock().ready.insert(i, r);
            } else {
                let mut s = lock();
                while !s.failed && !s.ready.contains_key(&k) {
                    s = changed.wait(s).unwrap_or_else(PoisonError::into_inner);
                }
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parts_concatenated_are_the_serial_result_for_every_thread_count() {
        let items: Vec<u32> = (0..1000).collect();
        let serial: Vec<u32> = items.iter().map(|x| x * 3).collect();
        for threads in 1..=9 {
            let parts = in_parallel_from(threads, &items, 10, |c| {
                c.iter().map(|x| x * 3).collect::<Vec<_>>()
            });
            assert_eq!(parts.len(), threads.min(items.len()), "{threads} threads");
            assert_eq!(parts.concat(), serial, "{threads} threads");
        }
        // A short list is not split.
        assert_eq!(in_parallel_from(4, &items[..5], 10, |c| c.len()), vec![5]);
    }

    #[test]
    fn the_ranges_cover_every_index_once_in_order() {
        for n in [0, 1, 2, 9, 100, 101] {
            for threads in 1..=4 {
                let parts = ranges_in_parallel(threads, n, 2, |r| r.collect::<Vec<_>>());
                assert_eq!(parts.concat(), (0..n).collect::<Vec<_>>(), "{n} {threads}");
                // Split when there is something to split, into at most one range a thread.
                let split = n >= 2 && threads > 1;
                assert_eq!(parts.len() > 1, split, "{n} {threads}");
                assert!(parts.len() <= threads.max(1), "{n} {threads}");
            }
        }
    }

    #[test]
    fn merged_runs_are_the_stable_sort_of_their_concatenation() {
        // Items (key, tag): equal keys in several runs, so that a merge taking a later run's
        // item first on a tie would show in the tags.
        let items: Vec<(u32, usize)> = (0..500).map(|i| ((i * 7919 % 61) as u32, i)).collect();
        let mut stable = items.clone();
        stable.sort_by_key(|e| e.0);
        for runs in [1, 2, 3, 5, 8] {
            let size = items.len().div_ceil(runs);
            let sorted: Vec<Vec<(u32, usize)>> = items
                .chunks(size)
                .map(|c| {
                    let mut c = c.to_vec();
                    c.sort_by_key(|e| e.0);
                    c
                })
                .collect();
            assert_eq!(merge_sorted_runs(sorted, |e| e.0), stable, "{runs} runs");
        }
        assert!(merge_sorted_runs(Vec::<Vec<u8>>::new(), |&e| e).is_empty());
    }

    /// `n` items of uneven costs (`cost`), so that threads finish them out of order.
    fn uneven(n: u64) -> Vec<u64> {
        (0..n).map(|i| (i * 7919) % 50).collect()
    }

    /// Work of about a thousand steps per unit of `n`.
    fn cost(&n: &u64) -> u64 {
        (0..n * 1000).fold(n, |a, x| a.wrapping_mul(31).wrapping_add(x))
    }

    #[test]
    fn every_entry_is_filled_with_its_own_index_s_value() {
        for n in [0, 1, 2, 9, 100, 101] {
            for threads in 1..=4 {
                let mut out = vec![0usize; n];
                fill_in_parallel(threads, &mut out, 2, |i| 3 * i + 1);
                assert_eq!(
                    out,
                    (0..n).map(|i| 3 * i + 1).collect::<Vec<_>>(),
                    "{n} {threads}"
                );
            }
        }
    }

    #[test]
    fn items_handed_out_one_at_a_time_come_back_in_their_order() {
        let items = uneven(200);
        let serial: Vec<u64> = items.iter().map(cost).collect();
        for threads in 1..=5 {
            assert_eq!(
                each_in_parallel(threads, &items, cost),
                serial,
                "{threads} threads"
            );
        }
        assert!(each_in_parallel(3, &items[..0], cost).is_empty());
    }

    #[test]
    fn results_are_taken_in_item_order_never_more_than_a_window_ahead() {
        let items = uneven(300);
        let serial: Vec<u64> = items.iter().map(cost).collect();
        for threads in 1..=5 {
            for window in [1, 3, 40, 1000] {
                let made = std::sync::atomic::AtomicUsize::new(0);
                let mut taken = Vec::new();
                let mut ahead = 0;
                each_in_order(
                    threads,
                    &items,
                    window,
                    |n| {
                        made.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                        cost(n)
                    },
                    |r| {
                        taken.push(r);
                        // Made and not yet taken, this one included.
                        let waiting =
                            made.load(std::sync::atomic::Ordering::SeqCst) - (taken.len() - 1);
                        ahead = ahead.max(waiting);
                    },
                );
                assert_eq!(taken, serial, "{threads} threads, window {window}");
                assert!(
                    ahead <= window,
                    "{threads} threads, window {window}: {ahead}"
                );
            }
        }
    }

    #[test]
    fn a_panic_in_make_reaches_the_caller_instead_of_hanging() {
        let items: Vec<u32> = (0..100).collect();
        let run = std::panic::catch_unwind(|| {
            each_in_order(
                3,
                &items,
                4,
                |&n| {
                    assert_ne!(n, 37, "item 37");
                    n
                },
                |_| {},
            )
        });
        assert!(run.is_err());
    }
}
