//! The one work pool of flexmodes: independent computations (a scene's integrations, the
//! scenes `record` writes, a bench's runs) on a few threads at once, used by the CLI, the
//! benches and the GUI alike.

use std::sync::{
    atomic::{AtomicBool, AtomicUsize, Ordering},
    mpsc,
};

use crate::{Progress, Result};

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

/// `run(k, item)` for every item on up to `threads` threads, handing each result to `done`
/// on the calling thread **in the order of the items** as soon as it and those before it are
/// finished. The first error stops new items from starting; it is returned once the running
/// ones have finished (the error of the earliest item when several fail).
pub fn run_in_order<T: Sync, R: Send, E: Send>(
    items: &[T],
    threads: usize,
    run: impl Fn(usize, &T) -> Result<R, E> + Sync,
    done: impl FnMut(usize, R),
) -> Result<(), E> {
    let order: Vec<usize> = (0..items.len()).collect();
    run_in_order_by(items, &order, threads, run, done)
}

/// [`run_in_order`] with the items started in `order` (a permutation of their indices: the
/// longest first, say, so that no thread is left with a long item at the end while the others
/// idle); results are still handed to `done` in the order of the items. After an error, items
/// not yet started stay so, and results are handed on up to the first item without one.
pub fn run_in_order_by<T: Sync, R: Send, E: Send>(
    items: &[T],
    order: &[usize],
    threads: usize,
    run: impl Fn(usize, &T) -> Result<R, E> + Sync,
    mut done: impl FnMut(usize, R),
) -> Result<(), E> {
    let count = items.len();
    let mut sorted = order.to_vec();
    sorted.sort_unstable();
    assert!(
        sorted.iter().copied().eq(0..count),
        "run_in_order_by: the order {order:?} is not a permutation of 0..{count}"
    );
    let threads = threads.clamp(1, count.max(1));
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let (sender, receiver) = mpsc::channel::<(usize, Result<R, E>)>();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let sender = sender.clone();
            let (next, failed, run) = (&next, &failed, &run);
            scope.spawn(move || {
                loop {
                    let started = next.fetch_add(1, Ordering::SeqCst);
                    if started >= count || failed.load(Ordering::SeqCst) {
                        break;
                    }
                    let k = order[started];
                    let result = run(k, &items[k]);
                    if result.is_err() {
                        failed.store(true, Ordering::SeqCst);
                    }
                    if sender.send((k, result)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(sender);
        // Hold what finishes early until those before it are handed on.
        let mut pending: Vec<Option<R>> = (0..count).map(|_| None).collect();
        let mut handed = 0;
        let mut first_error: Option<(usize, E)> = None;
        for (k, result) in receiver {
            match result {
                Ok(r) => pending[k] = Some(r),
                Err(e) => {
                    if first_error.as_ref().is_none_or(|(j, _)| k < *j) {
                        first_error = Some((k, e));
                    }
                }
            }
            while handed < count {
                let Some(r) = pending[handed].take() else {
                    break;
                };
                done(handed, r);
                handed += 1;
            }
        }
        match first_error {
            Some((_, e)) => Err(e),
            None => Ok(()),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Error;

    #[test]
    fn results_are_handed_on_in_order_and_the_first_error_stops_the_rest() {
        for threads in 1..4 {
            let input: Vec<usize> = (0..9).collect();
            let mut seen = Vec::new();
            run_in_order(
                &input,
                threads,
                |_, &i| Ok::<_, Error>(i * 10),
                |k, r| seen.push((k, r)),
            )
            .unwrap();
            assert_eq!(seen, input.iter().map(|&i| (i, i * 10)).collect::<Vec<_>>());

            let mut handed = Vec::new();
            let result = run_in_order(
                &input,
                threads,
                |k, _| if k == 2 { Err(Error::Cancelled) } else { Ok(k) },
                |k, _| handed.push(k),
            );
            assert!(matches!(result, Err(Error::Cancelled)), "{threads} threads");
            // Nothing after the failed item is handed on; items before it all are.
            assert_eq!(handed, vec![0, 1], "{threads} threads");
        }
    }

    #[test]
    fn items_started_in_another_order_are_handed_on_in_theirs() {
        let input: Vec<usize> = (0..7).collect();
        let order = [6, 2, 4, 0, 1, 3, 5];
        for threads in 1..4 {
            let started = std::sync::Mutex::new(Vec::new());
            let mut seen = Vec::new();
            run_in_order_by(
                &input,
                &order,
                threads,
                |k, &i| {
                    started.lock().unwrap().push(k);
                    Ok::<_, Error>(i + 100)
                },
                |k, r| seen.push((k, r)),
            )
            .unwrap();
            assert_eq!(
                seen,
                input.iter().map(|&i| (i, i + 100)).collect::<Vec<_>>()
            );
            if threads == 1 {
                assert_eq!(
                    started.into_inner().unwrap(),
                    order,
                    "one thread starts in order"
                );
            }
        }
    }

    #[test]
    #[should_panic(expected = "not a permutation")]
    fn an_order_that_is_not_a_permutation_is_refused() {
        let _ = run_in_order_by(
            &[1, 2, 3],
            &[0, 0, 2],
            2,
            |_, &i| Ok::<_, Error>(i),
            |_, _| {},
        );
    }

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
