//! Errors of the linear algebra: factorisations, eigensolvers and their checks, memory.

use thiserror::Error;

use super::MatrixLabel;

/// Errors of the linear algebra: factorisations, eigensolvers and their checks, memory.
#[derive(Debug, Error, serde::Serialize)]
pub enum LinalgError {
    /// A Cholesky factorisation met a pivot that is not positive.
    #[error(
        "the {matrix} matrix is not positive definite: the pivot of its row {index} (0-based) \
         is not positive"
    )]
    NonPositivePivot { matrix: MatrixLabel, index: usize },

    /// More eigenpairs than the partial eigensolver's basis leaves room for.
    #[error(
        "{wanted} modes of a {dof}-DOF problem: too many for the partial eigensolver, use the \
         dense path"
    )]
    TooManyPairs { wanted: usize, dof: usize },

    /// Multi-level substructuring kept fewer modes below its cut-off than the pairs asked for.
    #[error(
        "multi-level substructuring kept {kept} modes below {hz} Hz, fewer than the {wanted} \
         asked for: raise the cut-off", hz = crate::report::readable(.hz, 4))]
    CutoffTooLow { kept: usize, wanted: usize, hz: f64 },

    /// An allocation the computation needs could not be made.
    #[error(
        "out of memory: {what}{}{}",
        matrix.as_ref().map(|m| format!(" of {m}")).unwrap_or_default(),
        entries.map(|n| format!(" ({n} entries)")).unwrap_or_default()
    )]
    OutOfMemory {
        /// What could not be allocated: "Cholesky factor", "LDLᵀ workspace", …
        what: &'static str,
        matrix: Option<MatrixLabel>,
        entries: Option<usize>,
    },

    /// A sparse factor whose values and workspace exceed the memory the machine has free,
    /// refused after the symbolic analysis and before any of it is allocated (Linux would grant
    /// the allocation and end the process when its pages are touched).
    #[error(
        "the {what} of the {matrix} matrix needs {needed_gb:.2} GB ({entries} entries and its workspace), \
         more than the {available_gb:.2} GB this machine has free"
    )]
    FactorTooLarge {
        what: &'static str,
        matrix: MatrixLabel,
        entries: usize,
        needed_gb: f64,
        available_gb: f64,
    },

    /// A mesh whose estimated memory exceeds what the machine has.
    #[error(
        "a {dofs}-DOF mesh needs about {estimated_gb:.1} GB, more than the {available_gb:.1} GB \
         this machine has free"
    )]
    MeshTooLarge {
        dofs: usize,
        estimated_gb: f64,
        available_gb: f64,
    },

    /// The partial eigensolver stopped before every wanted pair was accurate.
    #[error(
        "the partial eigensolver did not converge: {converged} of {wanted} pairs converged, \
         worst relative residual {residual}", residual = crate::report::readable(.residual, 2))]
    EigenNotConverged {
        converged: usize,
        wanted: usize,
        residual: f64,
    },

    /// A matrix factored with the analysis of another sparsity pattern.
    #[error(
        "the {matrix} matrix has another sparsity pattern ({given} entries) than the one analysed \
         for its factorisation ({analysed} entries)"
    )]
    PatternMismatch {
        matrix: MatrixLabel,
        analysed: usize,
        given: usize,
    },

    /// The Sturm sequence check could not factor $K - \sigma' M$ accurately at any of the
    /// `tries` shifts tried; `last` is why the last one failed.
    #[error(
        "the Sturm sequence check failed: K - σ'M could not be factored accurately at any of \
         {tries} shifts, the last σ' = {shift} (rad/s)²", shift = crate::report::readable(.shift, 7))]
    SturmCheckFailed {
        shift: f64,
        tries: usize,
        #[source]
        last: Option<Box<LinalgError>>,
    },

    /// An unpivoted $LDL^T$ factor of $K - \sigma' M$ that grew: its solves' backward error
    /// is above the bound, so its inertia may be wrong.
    #[error(
        "the LDL^T factor of K - σ'M at σ' = {shift} (rad/s)² solves with a backward error \
         of {backward}, above {bound}", shift = crate::report::readable(.shift, 7), backward = crate::report::readable(.backward, 2), bound = crate::report::readable(.bound, 1))]
    SturmFactorInaccurate {
        shift: f64,
        backward: f64,
        bound: f64,
    },

    /// Every route of the free-body eigensolver failed.
    #[error(
        "the free-free eigensolver found no accurate set of {wanted} pairs; routes tried: {}",
        routes.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
    )]
    EigenRoutesFailed {
        wanted: usize,
        routes: Vec<super::EigenAttempt>,
    },

    /// A partial eigensolution that the Sturm count shows to have skipped eigenvalues, after
    /// every retry.
    #[error(
        "the partial eigensolver missed {missed} mode(s) below {hz} Hz: the Sturm count \
         finds {below} eigenvalues below the shift, the solver {found}", hz = crate::report::readable(.hz, 7))]
    MissedModes {
        missed: usize,
        below: usize,
        found: usize,
        hz: f64,
    },

    /// A dense eigen-decomposition whose pairs failed their residual or orthonormality check
    /// with every kernel tried.
    #[error(
        "the {what} eigenproblem failed its check: worst residual {residual} against a \
         tolerance of {tolerance} (faer and nalgebra both tried)", residual = crate::report::readable(.residual, 2), tolerance = crate::report::readable(.tolerance, 2))]
    EigenCheckFailed {
        what: MatrixLabel,
        residual: f64,
        tolerance: f64,
    },

    /// A NaN or infinite entry in a matrix handed to a decomposition.
    #[error("the {what} matrix has a non-finite entry at row {row}, column {col} (0-based)")]
    NotFinite {
        what: MatrixLabel,
        row: usize,
        col: usize,
    },

    /// A matrix that should be symmetric positive definite is not.
    #[error("the {matrix} matrix is not positive definite")]
    NotPositiveDefinite { matrix: MatrixLabel },

    /// A square matrix that must be inverted is singular: its factorisation failed, or gave
    /// a non-finite solution. `rcond` is the reciprocal condition estimate where one was
    /// computed.
    #[error(
        "the {matrix} matrix is singular{}",
        rcond.map(|r| format!(" (reciprocal condition estimate {r})", r = crate::report::readable(r, 2))).unwrap_or_default()
    )]
    SingularMatrix {
        matrix: MatrixLabel,
        rcond: Option<f64>,
    },

    /// An eigen- or singular-value decomposition did not converge.
    #[error("the {what} decomposition did not converge")]
    DecompositionFailed { what: MatrixLabel },

    /// Two sequences that must match (the same frequencies, the same length) do not.
    #[error("{what} differ: {left} against {right}")]
    LengthMismatch {
        what: &'static str,
        left: usize,
        right: usize,
    },

    /// The Lyapunov equation solve left a residual larger than its tolerance.
    /// A solve with a factor left a residual above its tolerance after refinement.
    #[error(
        "the solve with the {matrix} matrix left a relative residual {residual} after \
         refinement (tolerance {tolerance})", residual = crate::report::readable(.residual, 2), tolerance = crate::report::readable(.tolerance, 1))]
    SolveInaccurate {
        matrix: MatrixLabel,
        residual: f64,
        tolerance: f64,
    },

    #[error("the Lyapunov equation was solved with relative residual {residual}", residual = crate::report::readable(.residual, 2))]
    LyapunovInaccurate { residual: f64 },
}
