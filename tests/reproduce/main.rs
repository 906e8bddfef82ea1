//! Library-level tests in one binary (one link step): the published numbers of the thesis and
//! the physical and algebraic invariants of the bodies and reduction methods.

mod body_file;
mod body_file_errors;
mod body_file_export;
mod body_methods;
mod common;
mod companion;
mod companion_witteveen;
mod dense_eigen;
mod errors;
mod external_bodies;
mod exudyn_export;
mod failures;
mod floating_frame;
mod frame;
mod inertia_loads;
mod invariants;
mod linalg;
mod matrix_formats;
mod published;
mod scenes;
#[path = "../common/scratch.rs"]
mod scratch;
mod sparse;
mod stiffening;
