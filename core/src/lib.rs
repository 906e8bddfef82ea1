//! # flexmodes-core
//!
//! flexmodes' numerics and bodies, without Rerun or a command line: what the command line, the
//! desktop explorer and the Python package share. Model order reduction for restrained deformable
//! bodies in flexible multibody dynamics, after Y. Lin, *Model Reduction for a Restrained
//! Deformable Body* (2005).
//!
//! Data flows one way, layer by layer (see `ARCHITECTURE.md`):
//!
//! - [`error`]: one error enum per layer, wrapped by [`Error`];
//! - [`linalg`]: checked dense kernels, sparse Cholesky, the partial eigensolver, saddle-point
//!   solvers;
//! - [`fem`] and [`body_file`]: the thesis' bodies and bodies from other FE codes;
//! - [`reduction`]: one file per method (Guyan, modal truncation, Craig–Bampton, mode
//!   condensation, Eitelberg, MacNeal–Rubin, Benfield–Hruda, moment matching, balanced
//!   truncation), each returning a labelled Ψ;
//! - [`dynamics`]: floating-frame bodies, constraints and the two integrators;
//! - [`analysis`]: frequencies, deformed profiles, mean-axis evaluation, FRF and MAC;
//! - [`models`]: the scenes' physical set-ups and their measures, as typed results;
//! - [`export`]: reduced models written out (Exudyn, JSON);
//! - [`report`], [`markdown_tables`], [`inline_markdown`]: tables of typed results.
//!
//! The crate `flexmodes` adds the Rerun recorder, the scenes, the benches, the command line, the
//! desktop explorer and the classroom server; it re-exports these modules under its own name.

pub mod analysis;
pub mod assets;
pub mod atomic_file;
pub mod body_file;
pub mod dynamics;
pub mod error;
pub mod export;
pub mod fem;
pub mod inline_markdown;
pub mod linalg;
pub mod markdown_tables;
pub mod models;
mod progress;
pub mod reduction;
pub mod report;
pub mod report_diff;
pub mod work_pool;

pub use error::{Error, Result};
pub use progress::{PhaseReading, Progress, ProgressReading, same_shared};
