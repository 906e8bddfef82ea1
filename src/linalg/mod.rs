//! Thin wrappers over faer for the dense problems of these models (at most a few hundred DOF):
//! generalised symmetric eigenproblems, checked solves, the Lyapunov equation.

mod dense;
mod generalized_eigen;
mod lyapunov;
mod stiffness_solve;

pub use dense::{
    frobenius, identity, max_abs, max_abs_diff, principal_angles, select, select_cols, select_rows,
    symmetry_defect,
};
pub use generalized_eigen::{GeneralizedEigen, fix_sign, generalized_eigen, hz_from_eigenvalue};
pub use lyapunov::solve_lyapunov;
pub use stiffness_solve::InteriorStiffness;
