//! Errors of a time integration: where and when it stopped.

use thiserror::Error;

/// Errors of a time integration: where and when it stopped.
#[derive(Debug, Error, serde::Serialize)]
pub enum DynamicsError {
    /// A time integration that could not continue.
    #[error("the integration diverged at t = {time:.4} s: {reason}")]
    Diverged { time: f64, reason: String },

    /// The Newton iterations of an implicit step did not converge, even with a fresh
    /// iteration matrix.
    #[error(
        "Newton's method did not converge at t = {time:.4} s: residual {residual:e} after \
         {iterations} iterations (a smaller --dt may help)"
    )]
    NewtonFailed {
        time: f64,
        iterations: usize,
        residual: f64,
    },
}
