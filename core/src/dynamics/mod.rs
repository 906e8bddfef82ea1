//! Multibody dynamics with floating frames (chapters 2–5, 7.2, 8): rigid bodies with Euler
//! parameters, deformable bodies in modal coordinates $\delta = \Psi z$ on a floating frame,
//! spherical joints, prescribed nodal motion, axis conditions, and two integrators (explicit
//! Dormand–Prince, implicit generalized-α) behind one interface.

mod axes;
mod body;
mod combination;
mod constraint;
mod constraint_rows;
mod dense_driven;
mod dormand_prince;
mod driven_explicit;
mod driven_frame_body;
mod driven_integration;
mod evaluation_workspace;
mod frame_coordinates;
mod frame_stiffening;
mod free_frame_stiffening;
mod generalized_alpha;
mod inertia_invariants;
mod integrator;
mod integrator_parameters;
mod prescribed;
mod projection_factors;
mod rotation;
mod shake;
mod simulation;
mod sparse_driven;
mod spin_up;
mod system;
mod system_constraints;
mod system_elimination;
mod system_kinematics;
#[cfg(test)]
mod test_systems;

pub use crate::error::{DivergenceCause, DynamicsError};
pub use axes::{AxisKind, AxisType};
pub use body::{Body, FlexibleBody, ModalMassInverse, RigidBody};
pub use combination::Combination;
pub use constraint::{Attachment, Constraint};
pub use dormand_prince::{critical_step, imaginary_stability_limit, stability_polynomial};
pub use driven_explicit::{DrivenExplicit, integrate_driven_explicit};
pub use driven_frame_body::{
    DRIVEN_SOLVE_TOLERANCE, DenseDrivenOperators, DrivenFrameBody, positions,
};
pub use driven_integration::{DrivenCost, DrivenIntegration, Driving, integrate_driven};
pub use frame_coordinates::{FrameCoordinates, PinnedRing};
pub use frame_stiffening::{
    FrameStiffening, STIFFENING_CASE_NAMES, STIFFENING_CASES, stiffening_coefficients,
};
pub use free_frame_stiffening::{
    CaseSupport, FREE_FRAME_CASE_NAMES, FREE_FRAME_CASES, FreeFrameStiffening,
    free_frame_coefficients, unit_case_stiffnesses, unit_field,
};
pub use generalized_alpha::GeneralizedAlphaCoefficients;
pub use inertia_invariants::InertiaInvariants;
pub use integrator::simulate;
pub use integrator_parameters::{
    DEFAULT_IMPLICIT_STEP, DEFAULT_SPECTRAL_RADIUS, IntegrationScheme, IntegratorParameters,
};
pub use prescribed::Motion;
pub use rotation::{euler_parameters_from_matrix, rotation_matrix, skew};
pub use shake::Shake;
pub use simulation::{Sample, Simulation};
pub use sparse_driven::ISOTROPIC_MASS_TOLERANCE;
pub use spin_up::SpinUp;
pub use system::{STANDARD_GRAVITY, State, System};
