//! Linear algebra for small and large bodies behind one interface: dense kernels over faer for
//! the thesis' models (at most a few hundred DOF), sparse symmetric matrices, sparse Cholesky
//! and a partial generalised eigensolver for refined meshes of up to ~150 000 DOF.

mod dense;
mod generalized_eigen;
mod lyapunov;
mod mass_matrix;
mod memory;
mod nested_dissection;
mod partial_eigen;
mod sparse_symmetric;
mod symmetric_factor;

pub use dense::{
    frobenius, identity, max_abs, max_abs_diff, principal_angles, select, select_cols, select_rows,
    symmetry_defect,
};
pub use generalized_eigen::{GeneralizedEigen, fix_sign, generalized_eigen, hz_from_eigenvalue};
pub use lyapunov::solve_lyapunov;
pub use mass_matrix::MassMatrix;
pub use memory::{
    available_bytes, check_reduction_memory, estimated_reduction_bytes, peak_resident_bytes,
};
pub use nested_dissection::nested_dissection;
pub use partial_eigen::{
    PartialEigenParameters, PartialEigenStatistics, lowest_modes, negative_shift,
};
pub use sparse_symmetric::{SparseAssembly, SparseSymmetric, SparsityPattern};
pub use symmetric_factor::{SymbolicFactor, SymmetricFactor};
