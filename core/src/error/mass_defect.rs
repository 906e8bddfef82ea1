//! Why a mass matrix is not positive definite at a DOF
//! ([`super::BodyFileError::MassNotPositive`]).

/// Why a mass matrix is not positive definite at a DOF, with the value found.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum MassDefect {
    /// A lumped mass that is not positive.
    #[error("its lumped mass is {value:e}")]
    Lumped { value: f64 },
    /// A consistent mass whose diagonal entry is not positive.
    #[error("its diagonal entry is {value:e}")]
    Diagonal { value: f64 },
    /// A consistent mass whose Cholesky pivot is not positive, even after `regularisation`
    /// of its diagonal was added (a mass semi-definite beyond round-off).
    #[error(
        "the Cholesky pivot of this DOF is not positive, even with {regularisation} of the \
         diagonal added", regularisation = crate::report::readable(.regularisation, 1))]
    Pivot { regularisation: f64 },
}
