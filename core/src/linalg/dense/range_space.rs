//! When the range-space method of [`block_saddle_point_solve`](super::block_saddle_point_solve)
//! trusts a Cholesky factor: the pivot ratios below which a block is not clearly definite.

/// Pivot ratio below which [`block_saddle_point_solve`](super::block_saddle_point_solve) keeps a frame block, or hands $S$ to the
/// indefinite solver:
/// the smallest over the largest squared Cholesky pivot of $\hat M_{ff}$, and of the
/// Jacobi-scaled $S$.
const RANGE_SPACE_PIVOT: f64 = 1e-10;
/// Smallest squared pivot of the eliminated frame block $\hat M_{ff}$ the range-space method
/// accepts, as a fraction of the largest diagonal entry of the frame blocks before
/// elimination (a mass or a moment of inertia of the whole body). Below it Ψ nearly holds a
/// rigid motion and the frame block is round-off.
pub(super) const RANGE_SPACE_FRAME_PIVOT: f64 = 1e-8;

/// Whether the squared Cholesky pivots `l_diagonal` stay above `RANGE_SPACE_PIVOT` of the
/// largest.
pub(super) fn pivots_ok(l_diagonal: impl IntoIterator<Item = f64>) -> bool {
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0f64);
    for x in l_diagonal {
        if !x.is_finite() {
            return false;
        }
        smallest = smallest.min(x * x);
        largest = largest.max(x * x);
    }
    smallest > RANGE_SPACE_PIVOT * largest
}

/// Rows and columns of one body's frame block in [`block_saddle_point_solve`](super::block_saddle_point_solve).
pub(super) const FRAME_BLOCK: usize = 6;
