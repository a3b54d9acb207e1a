//! Long lists of independent work split over the machine's threads, with results in the
//! order of the list (so they do not depend on the split): engineering, not in paper 000.
//! Used by the extended rules and relocations (`extended`) and by the dual (`dual`).

/// Lists of at least this many items are split over threads by `in_parallel`.
pub(crate) const PARALLEL_MIN: usize = 8192;

/// `f` on consecutive chunks of `items`, one per available thread (at most four) when the
/// list is long, in order.
pub(crate) fn in_parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&[T]) -> R + Sync) -> Vec<R> {
    in_parallel_from(items, PARALLEL_MIN, f)
}

/// `in_parallel` for lists of at least `min` items (fewer items of more work each).
pub(crate) fn in_parallel_from<T: Sync, R: Send>(
    items: &[T],
    min: usize,
    f: impl Fn(&[T]) -> R + Sync,
) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get().min(4));
    if threads < 2 || items.len() < min {
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
