//! Several independent computations of a scene (time integrations of its methods) on a few
//! threads at once.

use crate::Progress;

/// `run(item, progress)` for every item, in order of the output, on up to `threads` threads
/// at once (0 and 1: one after the other on the calling thread). The first thread reports to
/// `progress`, the others to [`Progress::muted`] handles, so a bar follows one integration
/// at a time; cancelling `progress` stops them all.
pub fn run_concurrently<T: Copy + Sync, R: Send>(
    items: &[T],
    threads: usize,
    progress: &Progress,
    run: impl Fn(T, &Progress) -> R + Sync,
) -> Vec<R> {
    let threads = threads.min(items.len());
    if threads <= 1 {
        return items.iter().map(|&item| run(item, progress)).collect();
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut results: Vec<Option<R>> = (0..items.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|thread| {
                let (next, run) = (&next, &run);
                let progress = if thread == 0 {
                    progress.clone()
                } else {
                    progress.muted()
                };
                scope.spawn(move || {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                        let Some(&item) = items.get(i) else {
                            return done;
                        };
                        done.push((i, run(item, &progress)));
                    }
                })
            })
            .collect();
        for handle in handles {
            // A panic in `run` is a bug: passed on as it is.
            let done = handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            for (i, r) in done {
                results[i] = Some(r);
            }
        }
    });
    results
        .into_iter()
        .map(|r| r.expect("every item was taken by one thread"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Error, Result};

    #[test]
    fn every_item_runs_once_and_results_keep_their_order() {
        for items in [0usize, 1, 2, 5, 11] {
            let input: Vec<usize> = (0..items).collect();
            for threads in 0..4 {
                let calls = std::sync::atomic::AtomicUsize::new(0);
                let out = run_concurrently(&input, threads, &Progress::new(), |i, _| {
                    calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                    i * i
                });
                assert_eq!(calls.into_inner(), items, "{threads} threads");
                assert_eq!(out, input.iter().map(|i| i * i).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn every_thread_sees_a_cancellation() {
        let progress = Progress::new();
        let input: Vec<usize> = (0..6).collect();
        let out: Vec<Result<usize>> = run_concurrently(&input, 2, &progress, |i, p| {
            p.start_simulation(1.0)?;
            if i == 3 {
                progress.cancel();
            }
            // After item 3 every handle, muted or not, reports the cancellation.
            while i > 3 && !p.is_cancelled() {
                std::thread::yield_now();
            }
            p.advance(0.5)?;
            Ok(i)
        });
        assert_eq!(out.len(), 6);
        for (i, r) in out.iter().enumerate().skip(4) {
            assert!(matches!(r, Err(Error::Cancelled)), "item {i}: {r:?}");
        }
    }

    #[test]
    fn a_muted_handle_shares_only_the_cancellation() {
        let progress = Progress::new();
        let muted = progress.muted();
        muted.start_simulation(2.0).unwrap();
        muted.advance(1.0).unwrap();
        assert!(progress.reading().is_none(), "the muted handle reported");
        assert_eq!(muted.reading().map(|r| r.time), Some(1.0));
        progress.cancel();
        assert!(muted.is_cancelled());
        assert!(matches!(muted.advance(1.5), Err(Error::Cancelled)));
        // And the other way round.
        let other = Progress::new();
        other.muted().cancel();
        assert!(other.is_cancelled());
        // Detached stays detached.
        let detached = Progress::default().muted();
        detached.cancel();
        assert!(!detached.is_cancelled() && detached.reading().is_none());
    }
}
