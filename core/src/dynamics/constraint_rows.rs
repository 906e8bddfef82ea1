//! The system's constraint rows at one instant, $C\dot v = \gamma$ with their residuals, as
//! buffers an integration reuses; and the view of them a block elimination takes.

use std::ops::Range;

use nalgebra::{DMatrix, DVector, Matrix3};

/// Constraint rows at one instant.
#[derive(Debug, Clone)]
pub(crate) struct Rows {
    /// Jacobian, rows × nv.
    pub c: DMatrix<f64>,
    /// Acceleration right-hand side.
    pub gamma: DVector<f64>,
    /// Velocity right-hand side.
    pub target: DVector<f64>,
    /// Position residual (0 for non-holonomic rows).
    pub phi: DVector<f64>,
    /// Whether each row is holonomic.
    pub holonomic: Vec<bool>,
    /// The bodies' $H_c(z)$ at the state the rows are of ([`super::System::modal_moments`]): the axis
    /// conditions need them, and so do the mass matrix and forces at the same state.
    pub moments: Vec<Vec<Matrix3<f64>>>,
    /// Where the last [`super::System::rows_into`] wrote `c`: the next one clears these
    /// entries alone, not all of `c` (a joint's rows have a few nonzeros among `nv` columns;
    /// clearing the whole Jacobian was a twelfth of a full model's evaluation).
    pub written: WrittenEntries,
}

/// The entries of a Jacobian an evaluation wrote.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct WrittenEntries {
    /// Entries added to (joints and prescribed nodes): (row, columns).
    pub added: Vec<(usize, Range<usize>)>,
    /// Blocks overwritten whole (a body's six axis rows from the row, over its modal
    /// columns): cleared only when the next evaluation's blocks are not the same.
    pub assigned: Vec<(usize, Range<usize>)>,
}

impl Rows {
    /// No rows: buffers for [`super::System::rows_into`].
    pub(crate) fn empty() -> Self {
        Self {
            c: DMatrix::zeros(0, 0),
            gamma: DVector::zeros(0),
            target: DVector::zeros(0),
            phi: DVector::zeros(0),
            holonomic: Vec::new(),
            moments: Vec::new(),
            written: WrittenEntries::default(),
        }
    }
}

/// The constraint rows $C$ a block elimination is of, their right-hand side $g$, and per
/// body the rows that may touch its modal coordinates ([`super::System::modal_rows`]).
#[derive(Clone, Copy)]
pub(super) struct ConstraintRows<'a> {
    pub(super) c: &'a DMatrix<f64>,
    pub(super) g: &'a DVector<f64>,
    pub(super) modal_rows: &'a [Vec<usize>],
}
