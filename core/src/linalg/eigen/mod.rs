//! The partial generalised eigensolver of large bodies (shift-invert block Lanczos) and the
//! Sturm count that proves no pair below the top one was missed.

mod checked_pairs;
mod partial_eigen;
mod sturm_count;

pub(crate) use partial_eigen::next_uniform;
pub use partial_eigen::{PartialEigenParameters, PartialEigenStatistics, lowest_modes};
pub use sturm_count::{SturmCount, inertia_at, sturm_count};
