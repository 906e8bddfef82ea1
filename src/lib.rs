//! # flexmodes
//!
//! An explorer of model order reduction for restrained deformable bodies in flexible multibody
//! dynamics, after Y. Lin, *Model Reduction for a Restrained Deformable Body* (2005).
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
//! - [`record`] and [`export`]: the one Rerun recorder, reduced models written out;
//! - [`scenes`]: the registry behind `flexmodes list/record/report`, wiring models to visuals;
//! - [`bench`](mod@bench), [`cli`] and (feature `gui`) the desktop explorer: the doors.

pub mod analysis;
pub mod assets;
pub mod atomic_file;
#[cfg(feature = "cli")]
pub mod bench;
pub mod body_file;
#[cfg(feature = "cli")]
pub mod cli;
pub mod dynamics;
pub mod error;
pub mod export;
pub mod fem;
#[cfg(feature = "gui")]
pub mod gui;
pub mod inline_markdown;
pub mod linalg;
pub mod markdown_tables;
pub mod models;
mod progress;
#[cfg(feature = "cli")]
pub mod record;
pub mod reduction;
pub mod report;
#[cfg(feature = "cli")]
pub mod scenes;
#[cfg(feature = "serve")]
pub mod serve;
#[cfg(feature = "cli")]
mod terminal_progress;
pub mod work_pool;

pub use error::{Error, Result};
pub use progress::{PhaseReading, Progress, ProgressReading};
#[cfg(feature = "cli")]
pub use terminal_progress::TerminalProgress;
