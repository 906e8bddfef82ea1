//! Reduction methods: each builds a transformation $\delta = \Psi z$ with labelled columns.

mod basis;
mod craig_bampton;
mod eitelberg;
mod full;
mod guyan;
mod method;
mod modal_truncation;
mod mode_condensation;
mod nodal_fixed;
mod partition;

pub use basis::{Basis, Column, ColumnKind};
pub use craig_bampton::craig_bampton;
pub use eitelberg::{
    EitelbergParameters, EitelbergReduction, StateSpaceReduction, eitelberg, eitelberg_state_space,
};
pub use full::no_reduction;
pub use guyan::guyan;
pub use method::{Method, ModeSelection, ReductionParameters, reduce};
pub use modal_truncation::modal_truncation;
pub use mode_condensation::mode_condensation;
pub use nodal_fixed::{NodalFixedAxes, TableConfiguration};
pub use partition::{Partition, constraint_modes, fixed_interface_modes};
