//! # flexmodes
//!
//! An explorer of model order reduction for restrained deformable bodies in flexible multibody
//! dynamics, after Y. Lin, *Model Reduction for a Restrained Deformable Body* (2005).
//!
//! - [`fem`]: the App. A beam, the App. B slab and the standing plank;
//! - [`reduction`]: Guyan, modal truncation, Craig–Bampton, mode condensation, Eitelberg and
//!   nodal-fixed column removal, each returning a labelled Ψ;
//! - [`analysis`]: frequencies, deformed profiles, principal angles;
//! - [`scenes`]: the scene registry behind `flexmodes list/record/report`;
//! - [`record`]: the one Rerun recorder used by the CLI (and later the GUI).

pub mod analysis;
pub mod assets;
pub mod atomic_file;
pub mod bench;
pub mod body_file;
pub mod cli;
pub mod dynamics;
pub mod error;
pub mod export;
pub mod fem;
#[cfg(feature = "gui")]
pub mod gui;
pub mod linalg;
pub mod models;
mod progress;
pub mod record;
pub mod reduction;
pub mod report;
pub mod scenes;
mod terminal_progress;
pub mod work_pool;

pub use error::{Error, Result};
pub use progress::{PhaseReading, Progress, ProgressReading};
pub use terminal_progress::TerminalProgress;
