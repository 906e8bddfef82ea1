//! # flexmodes
//!
//! An explorer of model order reduction for restrained deformable bodies in flexible multibody
//! dynamics, after Y. Lin, *Model Reduction for a Restrained Deformable Body* (2005).
//!
//! Data flows one way, layer by layer (see `ARCHITECTURE.md`):
//!
//! - [`error`]: one error enum per layer, wrapped by core's, wrapped by the application's
//!   [`Error`];
//! - [`linalg`]: checked dense kernels, sparse Cholesky, the partial eigensolver, saddle-point
//!   solvers;
//! - [`fem`] and [`body_file`]: the thesis' bodies and bodies from other FE codes;
//! - [`reduction`]: one file per method (Guyan, modal truncation, Craig–Bampton, mode
//!   condensation, Eitelberg, MacNeal–Rubin, Benfield–Hruda, moment matching, balanced
//!   truncation), each returning a labelled Ψ;
//! - [`dynamics`]: floating-frame bodies, constraints and the two integrators;
//! - [`analysis`]: frequencies, deformed profiles, mean-axis evaluation, FRF and MAC;
//! - [`models`]: the scenes' physical set-ups and their measures, as typed results;
//! - [`record`] and [`export`]: the one Rerun recorder, reduced models written out;
//! - [`scenes`]: the registry behind `flexmodes list/record/report`, wiring models to visuals;
//! - [`bench`](mod@bench), [`cli`] and (feature `gui`) the desktop explorer: the doors.
//!
//! Everything up to [`models`] and [`export`] is the crate `flexmodes-core` (no Rerun, no command
//! line; the Python package builds on it alone), re-exported here under the same names: the
//! compiler keeps the numerics from importing a scene or the recorder.

pub use flexmodes_core::{
    PhaseReading, Progress, ProgressReading, analysis, assets, atomic_file, body_file, dynamics,
    export, fem, inline_markdown, linalg, markdown_tables, models, reduction, report, report_diff,
    work_pool,
};

pub mod error;

pub use error::{Error, Result};

#[cfg(feature = "cli")]
pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
#[cfg(feature = "gui")]
pub mod gui;
#[cfg(feature = "cli")]
pub mod record;
#[cfg(feature = "cli")]
pub mod scenes;
#[cfg(feature = "serve")]
pub mod serve;
#[cfg(feature = "cli")]
mod terminal_progress;

#[cfg(feature = "cli")]
pub use terminal_progress::TerminalProgress;
