//! Long lists of independent work split over threads, with results in the order of the list
//! (so they do not depend on the split): engineering, not in paper 000. Used by the extended
//! rules and relocations (`extended`) and by the dual (`dual`), with the thread count of the
//! hierarchy (`Hierarchy::threads`, from `Params::threads`).

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
}
