//! The one way the core uses several threads: a list of independent items,
//! worked through by up to [`max_threads`] scoped threads (the calling thread
//! among them), each taking the next item not yet taken, so a faster core does
//! more of them (uneven cores: performance and efficiency cores, a busy host).
//! Results come back in item order. On the web everything runs on the calling
//! thread.

/// Most threads worth using here: the machine's (at most eight); one on the web.
pub(crate) fn max_threads() -> usize {
    if cfg!(target_family = "wasm") {
        return 1;
    }
    std::thread::available_parallelism().map_or(1, |n| n.get()).min(8)
}

/// Inputs smaller than this are read on one thread.
const PARALLEL_MIN_BYTES: usize = 1 << 20;
/// Smallest piece worth cutting off for a thread to take.
const PIECE_MIN_BYTES: usize = 1 << 18;

/// Pieces to cut `len` bytes of text into for reading them on several threads:
/// one below [`PARALLEL_MIN_BYTES`] or with one thread; else `per_thread` per
/// thread (at least [`PIECE_MIN_BYTES`] each), so that threads on faster cores
/// take more of them.
pub(crate) fn piece_count(len: usize, per_thread: usize) -> usize {
    let threads = max_threads();
    if len < PARALLEL_MIN_BYTES || threads <= 1 {
        return 1;
    }
    (threads * per_thread).min(len / PIECE_MIN_BYTES).max(threads)
}

/// `f` over `items`, in order; `None` for an item whose `f` panicked. Up to
/// [`max_threads`] threads take items one at a time in order; with one item,
/// or one thread, all on the calling thread.
#[cfg(not(target_family = "wasm"))]
pub(crate) fn map<I: Send, T: Send>(items: Vec<I>, f: impl Fn(I) -> T + Sync) -> Vec<Option<T>> {
    use std::panic::{AssertUnwindSafe, catch_unwind};
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let threads = max_threads().min(items.len());
    if threads <= 1 {
        return items.into_iter().map(|i| catch_unwind(AssertUnwindSafe(|| f(i))).ok()).collect();
    }
    // Each slot holds an item until a thread takes it, then its result.
    let slots: Vec<Mutex<Slot<I, T>>> = items.into_iter().map(|i| Mutex::new(Slot::Item(i))).collect();
    let next = AtomicUsize::new(0);
    let work = || {
        while let Some(slot) = slots.get(next.fetch_add(1, Ordering::Relaxed)) {
            run_slot(slot, &f);
        }
    };
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
    slots
        .into_iter()
        .map(|s| match s.into_inner() {
            Ok(Slot::Done(t)) => Some(t),
            _ => None,
        })
        .collect()
}

/// Takes the item out of `slot`, if still there, and puts back `f`'s result
/// (or [`Slot::Failed`] when `f` panics).
#[cfg(not(target_family = "wasm"))]
fn run_slot<I, T>(slot: &std::sync::Mutex<Slot<I, T>>, f: impl Fn(I) -> T) {
    use std::panic::{AssertUnwindSafe, catch_unwind};
    let item = match slot.lock().map(|mut s| std::mem::replace(&mut *s, Slot::Failed)) {
        Ok(Slot::Item(item)) => item,
        _ => return,
    };
    let result = catch_unwind(AssertUnwindSafe(|| f(item))).map_or(Slot::Failed, Slot::Done);
    if let Ok(mut s) = slot.lock() {
        *s = result;
    }
}

/// One item's place in [`map`].
#[cfg(not(target_family = "wasm"))]
enum Slot<I, T> {
    /// Not taken yet.
    Item(I),
    /// Its result.
    Done(T),
    /// Taken and not finished (its `f` panicked).
    Failed,
}

/// See the native version: here all on the calling thread.
#[cfg(target_family = "wasm")]
pub(crate) fn map<I, T>(items: Vec<I>, f: impl Fn(I) -> T) -> Vec<Option<T>> {
    items.into_iter().map(|i| Some(f(i))).collect()
}

#[cfg(all(test, not(target_family = "wasm")))]
mod tests {
    use super::map;

    #[test]
    fn results_come_back_in_item_order_with_a_failed_item_as_none() {
        let items: Vec<usize> = (0..100).collect();
        let out = map(items, |i| {
            if i == 37 {
                panic!("item 37 fails");
            }
            i * 2
        });
        assert_eq!(out.len(), 100);
        for (i, r) in out.iter().enumerate() {
            assert_eq!(*r, if i == 37 { None } else { Some(i * 2) }, "item {i}");
        }
    }

    #[test]
    fn items_hold_mutable_borrows() {
        let mut data = vec![0u32; 64];
        let parts: Vec<&mut [u32]> = data.chunks_mut(8).collect();
        let done = map(parts, |part| part.iter_mut().for_each(|v| *v += 1));
        assert!(done.iter().all(Option::is_some));
        assert!(data.iter().all(|&v| v == 1));
    }
}
