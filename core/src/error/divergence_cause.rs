//! Why a time integration could not go on: the state's bound, the step count, the step size,
//! or a fixed step that blew up.

use thiserror::Error;

/// Why a time integration diverged ([`super::DynamicsError::Diverged`]), with its data.
#[derive(Debug, Clone, PartialEq, Error, serde::Serialize)]
pub enum DivergenceCause {
    /// A state component passed the divergence bound between steps.
    #[error("the state grew beyond {bound}", bound = crate::report::readable(.bound, 2))]
    StateBeyondBound {
        /// The bound (m, m/s, rad/s, modal units).
        bound: f64,
    },
    /// Adaptive steps shrank below the smallest step while the state kept leaving the bound
    /// or turning non-finite.
    #[error(
        "the state grew beyond {bound} or became non-finite",
        bound = crate::report::readable(.bound, 2)
    )]
    StepsCannotHold {
        /// The bound.
        bound: f64,
    },
    /// A fixed step (no error control) took the state past the bound or to non-finite
    /// values.
    #[error(
        "with the fixed step {step} s the state grew beyond {bound} or became non-finite",
        step = crate::report::readable(.step, 5),
        bound = crate::report::readable(.bound, 2)
    )]
    FixedStepBeyondBound {
        /// The step, s.
        step: f64,
        /// The bound.
        bound: f64,
    },
    /// A fixed step reached a state whose system matrix lost definiteness in floating point.
    #[error("with the fixed step {step} s the {matrix} became singular", step = crate::report::readable(.step, 5))]
    FixedStepSingular {
        /// The step, s.
        step: f64,
        /// The matrix that became singular.
        matrix: super::MatrixLabel,
    },
    /// A coordinate of a fixed-step integration passed the bound.
    #[error(
        "a coordinate reached {largest}, beyond {bound}, with fixed steps of {step} s", largest = crate::report::readable(.largest, 4), bound = crate::report::readable(.bound, 4), step = crate::report::readable(.step, 4))]
    CoordinateBeyondBound {
        /// The largest coordinate's magnitude.
        largest: f64,
        /// The bound.
        bound: f64,
        /// The step, s.
        step: f64,
    },
    /// More steps than allowed.
    #[error("more than {max_steps} steps")]
    TooManySteps {
        /// The allowed count.
        max_steps: usize,
    },
    /// The error control asked for a step below the smallest allowed.
    #[error("step size fell below {min_step:e} s")]
    StepTooSmall {
        /// The smallest step, s.
        min_step: f64,
    },
}
