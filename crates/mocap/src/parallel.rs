//! The one way the core uses several threads: a list of independent items, each
//! handed to its own scoped thread (the first on the calling thread), results in
//! order. On the web everything runs on the calling thread.

/// Most threads worth using here: the machine's (at most eight); one on the web.
pub(crate) fn max_threads() -> usize {
    if cfg!(target_family = "wasm") {
        return 1;
    }
    std::thread::available_parallelism().map_or(1, |n| n.get()).min(8)
}

/// `f` over `items`, one thread per item after the first; in order; `None` for
/// an item whose thread failed (a panic in `f`). With one item, or on the web,
/// all on the calling thread.
#[cfg(not(target_family = "wasm"))]
pub(crate) fn map<I: Send, T: Send>(items: Vec<I>, f: impl Fn(I) -> T + Sync) -> Vec<Option<T>> {
    if items.len() <= 1 {
        return items.into_iter().map(|i| Some(f(i))).collect();
    }
    std::thread::scope(|scope| {
        let f = &f;
        let mut items = items.into_iter();
        let first = items.next();
        let handles: Vec<_> = items.map(|item| scope.spawn(move || f(item))).collect();
        let mut out: Vec<Option<T>> = first.map(|i| Some(f(i))).into_iter().collect();
        out.extend(handles.into_iter().map(|h| h.join().ok()));
        out
    })
}

/// See the native version: here all on the calling thread.
#[cfg(target_family = "wasm")]
pub(crate) fn map<I, T>(items: Vec<I>, f: impl Fn(I) -> T) -> Vec<Option<T>> {
    items.into_iter().map(|i| Some(f(i))).collect()
}
