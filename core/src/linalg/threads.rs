//! How many threads the numerics use, and the kernels that use them: a kernel runs on every
//! thread only when its work is large enough to pay for waking them (a supernodal factor of
//! tens of millions of entries, a triangular solve with hundreds of right-hand sides, an
//! $n \times k$ product of ~$10^8$ flops); below that it stays on the calling thread. On the
//! 2-core machines flexmodes is measured on, faer's thread pool on every kernel cost more in
//! wake-ups than it gained: the refined slab's Craig–Bampton took 1.42 s instead of 0.68 s at
//! 6 825 DOF (block solves of four right-hand sides, $n \times 64$ products).

use std::sync::atomic::{AtomicUsize, Ordering};

use faer::Par;

/// Threads set by [`set_threads`]; 0 until then (one thread).
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Dense kernels (products, wide solves) of more flops than this run on every thread.
pub const PARALLEL_FLOPS: f64 = 1e8;

/// Sparse factorisations of more flops than this run their supernodes' dense kernels on every
/// thread: below it most supernodes are too small to split (the refined slab at 6 825 DOF,
/// 5e8 flops, factored in 0.094 s on one thread and 0.124 s on two; at 28 413 DOF, 9e9 flops,
/// 0.86 s and 0.61 s).
pub const PARALLEL_FACTOR_FLOPS: f64 = 2e9;

/// Uses `threads` threads (`None`: the machine's cores) for the numerics and for independent
/// work (a scene's integrations, `record`'s scenes), and returns the count in use. The first
/// call builds the thread pool; a later one can lower the count the kernels use but not grow
/// the pool. Kernels not chosen by size run on the calling thread.
pub fn set_threads(threads: Option<usize>) -> usize {
    let wanted = threads.unwrap_or_else(machine_threads).max(1);
    // The pool is built once per process; a second build (tests, the GUI after the CLI) fails
    // and the first pool stays.
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(wanted)
        .build_global();
    let used = wanted.min(rayon::current_num_threads());
    faer::set_global_parallelism(Par::Seq);
    THREADS.store(used, Ordering::Relaxed);
    used
}

/// Lets the kernels use `threads` threads (at most the pool's, see [`set_threads`]) from now
/// on; returns the count in use. For benches that compare thread counts in one run.
pub fn use_threads(threads: usize) -> usize {
    let used = threads.clamp(1, rayon::current_num_threads().max(1));
    THREADS.store(used, Ordering::Relaxed);
    used
}

/// The threads in use (1 before [`set_threads`]).
pub fn threads() -> usize {
    THREADS.load(Ordering::Relaxed).max(1)
}

/// The machine's cores (1 when unknown).
pub fn machine_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Every thread for a dense kernel of `flops` above [`PARALLEL_FLOPS`], else the calling
/// thread.
pub fn par_for_flops(flops: f64) -> Par {
    par_above(flops, PARALLEL_FLOPS)
}

/// Every thread for a sparse factorisation of `flops` above [`PARALLEL_FACTOR_FLOPS`], else
/// the calling thread.
pub fn par_for_factor(flops: f64) -> Par {
    par_above(flops, PARALLEL_FACTOR_FLOPS)
}

fn par_above(flops: f64, threshold: f64) -> Par {
    let t = threads();
    if t > 1 && flops > threshold {
        Par::rayon(t)
    } else {
        Par::Seq
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernels_go_parallel_only_above_their_thresholds_and_with_threads() {
        // One thread: nothing is split, however large.
        use_threads(1);
        assert_eq!(par_for_flops(1e12), Par::Seq);
        assert_eq!(par_for_factor(1e12), Par::Seq);
        // Two threads (where the pool has them): the large kernels only.
        if use_threads(2) == 2 {
            assert_eq!(par_for_flops(2.0 * PARALLEL_FLOPS), Par::rayon(2));
            assert_eq!(par_for_flops(0.5 * PARALLEL_FLOPS), Par::Seq);
            assert_eq!(par_for_factor(2.0 * PARALLEL_FACTOR_FLOPS), Par::rayon(2));
            assert_eq!(par_for_factor(0.5 * PARALLEL_FACTOR_FLOPS), Par::Seq);
        }
        use_threads(1);
    }
}
