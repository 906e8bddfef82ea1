//! Reduction methods: each builds a transformation $\delta = \Psi z$ with labelled columns, on
//! dense linear algebra for small bodies and sparse for refined meshes.

mod amls_free_modes;
mod averaging_interface;
mod balanced_truncation;
mod basis;
mod benfield_hruda;
mod block_factor;
mod boundary_coordinates;
mod characteristic_constraint_modes;
mod component_synthesis;
mod craig_bampton;
mod eitelberg;
mod free_body_solver;
mod free_modes;
mod full;
mod guyan;
mod inertia_residual_vectors;
mod interface_loads;
mod interior_problem;
mod macneal_rubin;
mod method;
mod modal_balanced_basis;
mod modal_influence;
mod modal_model;
mod modal_truncation;
mod mode_condensation;
mod moment_matching;
mod nodal_fixed;
mod partition;
mod reduced_matrices;
mod reduction_request;
mod releasable_factor;
mod restrained_ritz;
mod rigid_interface;

pub use crate::error::ReductionError;
pub use amls_free_modes::{
    AMLS_LEAF, Eigensolver, amls_free_pairs, first_cutoff_hz, free_pairs_by,
};
pub use averaging_interface::AveragingInterface;
pub use balanced_truncation::{
    BalancedBasisParameters, BalancedTruncation, balanced_basis, balanced_truncation,
    modal_gramians,
};
pub use basis::{Basis, Column, ColumnKind};
pub use benfield_hruda::{InterfaceLoading, LoadedInterface, benfield_hruda};
pub use boundary_coordinates::BoundaryCoordinates;
pub use characteristic_constraint_modes::{CharacteristicConstraintModes, reduce_interface};
pub use component_synthesis::{Component, Synthesis};
pub use eitelberg::{
    EITELBERG_DOF_LIMIT, EitelbergParameters, EitelbergReduction, StateSpaceReduction, eitelberg,
    eitelberg_state_space,
};
pub use free_body_solver::{FreeBodyParameters, free_body_pairs};
pub(crate) use free_body_solver::{SturmPencil, sturm_checked};
pub use free_modes::{
    lowest_free_body_pairs, lowest_free_modes, mass_normalised_rigid_modes, restrained_modes,
    selected_free_modes,
};
pub use full::no_reduction;
pub use inertia_residual_vectors::{
    RESIDUAL_VECTOR_DEFLATION, ResidualVectorsAdded, static_share_outside,
    with_inertia_residual_vectors,
};
pub use interface_loads::InterfaceLoads;
pub use interior_problem::{
    COMPLETE_EIGEN_LIMIT, DENSE_INTERIOR_LIMIT, InteriorProblem, ReductionStatistics,
    STATIC_RESPONSE_TOLERANCE,
};
pub use interior_problem::{constraint_modes, fixed_interface_modes};
pub use macneal_rubin::{MacNealRubinParameters, macneal_rubin};
pub use method::{Method, ModeSelection, SolverPath};
pub use modal_balanced_basis::{ModalBalancedParameters, modal_balanced_basis};
pub use modal_influence::{ModalInfluence, modal_influence};
pub use modal_model::{IoMap, ModalModel, StateSpace};
pub use mode_condensation::{MC_COMPLETE_ROUTE_LIMIT, ModeCondensationRoute};
pub use moment_matching::{Deflation, MomentMatching, MomentMatchingParameters, moment_matching};
pub use nodal_fixed::{NodalFixedAxes, TableConfiguration};
pub use partition::Partition;
pub use reduced_matrices::{CONSTRAINT_COUPLING_TOLERANCE, ReducedMatrices};
pub use reduction_request::{ReductionRequest, reduce, reduce_interior};
pub use releasable_factor::RELEASED_FACTOR_BYTES;
pub(crate) use releasable_factor::ReleasableFactor;
pub use restrained_ritz::RestrainedRitzModel;
pub use rigid_interface::{MASTER_DOF_NAMES, RigidInterface, tie_rigid_interfaces};
