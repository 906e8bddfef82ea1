//! A transformation matrix of reduction with labelled columns.

use faer::Mat;

use super::{Method, ReductionStatistics, reduced_matrices::symmetric_product};
use crate::fem::FeModel;

/// What a column of Ψ is.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnKind {
    /// A unit nodal coordinate (no reduction).
    Nodal,
    /// Modal truncation's boundary movement: a unit boundary DOF with the interior at rest
    /// (Fig. 6-6).
    BoundaryMovement,
    /// A static constraint mode $[I; \Psi_s]$ (Guyan, Craig–Bampton; Fig. 6-5).
    Constraint,
    /// Mode condensation's boundary mode $[I; \Psi_m]$ (Eq. 6.29, Fig. 6-9).
    CondensedBoundary,
    /// Eitelberg's reconstruction of the full state from the kept boundary states.
    EitelbergBoundary,
    /// A fixed-interface normal mode with its frequency in Hz.
    Normal {
        /// Fixed-interface natural frequency, Hz.
        hz: f64,
    },
    /// A free-interface normal mode (a rigid-body mode at 0 Hz), MacNeal–Rubin (Spanos–Tsuha
    /// Eq. 8).
    FreeInterface {
        /// Free-free natural frequency, Hz (0 for a rigid-body mode).
        hz: f64,
    },
    /// A residual-flexibility mode for a unit force on one interface DOF (Spanos–Tsuha Eq. 12).
    Residual,
    /// A loaded-interface normal mode, Benfield–Hruda (Spanos–Tsuha Eq. 18).
    Loaded {
        /// Natural frequency of the loaded component, Hz.
        hz: f64,
    },
    /// A vector of a block Krylov space (Witteveen Eq. 21); block 0 is the static response.
    Krylov {
        /// Block index j of $P^j R$.
        block: usize,
    },
    /// The static response to one rigid motion of a rigid (RBE2) interface: its master's DOF
    /// `dof` (0–2 translations x, y, z; 3–5 rotations about x, y, z).
    RigidInterface {
        /// The interface's name.
        interface: String,
        /// The master DOF, 0..6.
        dof: usize,
    },
    /// A characteristic constraint mode (Castanier–Tan–Pierre): a combination of the
    /// constraint modes, an eigenvector of the boundary's Guyan-reduced pencil.
    CharacteristicConstraint {
        /// Its frequency in the Guyan-reduced boundary pencil, Hz.
        hz: f64,
    },
    /// The static response to one of the frame's unit inertia loads with the boundary held,
    /// made mass-orthogonal to the interior columns before it (a residual vector).
    InertiaResidual {
        /// The load.
        load: crate::fem::InertiaLoadCase,
    },
    /// A balanced-truncation vector with its (position) gramian value.
    Balanced {
        /// The eigenvalue of the gramian block the vector belongs to.
        value: f64,
    },
}

/// One column of Ψ.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The kind of mode.
    pub kind: ColumnKind,
    /// For columns tied to one nodal DOF (unit at that DOF, zero at the other boundary DOF).
    pub dof: Option<usize>,
    /// Human-readable label, e.g. `constraint node 5 x` or `normal 2 (12.33 Hz)`.
    pub label: String,
}

/// $\delta = \Psi z$: rows are the body's DOF in node-major order, columns are labelled.
#[derive(Debug, Clone)]
pub struct Basis {
    /// The method that built it.
    pub method: Method,
    /// The transformation matrix, `dof_count × columns.len()`.
    pub psi: Mat<f64>,
    /// Column descriptions.
    pub columns: Vec<Column>,
    /// Wall time and sizes of the phases that built it.
    pub statistics: ReductionStatistics,
}

impl Basis {
    /// Number of generalised coordinates.
    pub fn size(&self) -> usize {
        self.columns.len()
    }

    /// $\Psi^T K \Psi$ (one sparse product $K\Psi$, then a small dense one).
    pub fn reduced_stiffness(&self, model: &FeModel) -> Mat<f64> {
        symmetric_product(self.psi.as_ref(), model.k.mul(self.psi.as_ref()).as_ref())
    }

    /// $\Psi^T M \Psi$.
    pub fn reduced_mass(&self, model: &FeModel) -> Mat<f64> {
        symmetric_product(self.psi.as_ref(), model.m.mul(self.psi.as_ref()).as_ref())
    }

    /// $\Psi^T A \Psi$ of any symmetric matrix on the body's DOF (a geometric stiffness).
    pub fn project(&self, a: &crate::linalg::SparseSymmetric) -> Mat<f64> {
        symmetric_product(self.psi.as_ref(), a.mul(self.psi.as_ref()).as_ref())
    }

    /// Indices of the columns of a kind (by discriminant).
    pub fn columns_of(&self, pred: impl Fn(&ColumnKind) -> bool) -> Vec<usize> {
        (0..self.columns.len())
            .filter(|&j| pred(&self.columns[j].kind))
            .collect()
    }

    /// Frequencies (Hz) of the kept normal-mode columns, in column order.
    pub fn normal_hz(&self) -> Vec<f64> {
        self.columns
            .iter()
            .filter_map(|c| match c.kind {
                ColumnKind::Normal { hz } => Some(hz),
                _ => None,
            })
            .collect()
    }

    /// Column `j` as a DOF vector.
    pub fn column(&self, j: usize) -> Vec<f64> {
        (0..self.psi.nrows()).map(|i| self.psi[(i, j)]).collect()
    }
}
