//! Errors: the application's own ([`Error`], [`ServeError`]) and, re-exported, every layer's
//! of flexmodes-core (core's wrapping one as [`CoreError`]).

mod app_error;
mod serve_error;

pub use app_error::{Error, Result};
pub use flexmodes_core::error::*;
pub use flexmodes_core::error::{Error as CoreError, Result as CoreResult};
pub use serve_error::{RecordingProblem, ServeError};
