//! Multi-level substructuring (AMLS): nested dissection into a tree of parts and
//! separators, the leaves' modes, the reductions level by level, and the refined pairs.

mod amls_eigen;
mod amls_parameters;
mod leaf_modes;
mod multilevel_solve;
mod multilevel_substructures;
mod nested_dissection;
mod substructure_front;
mod substructure_tree;

pub use amls_eigen::{AmlsEigenParameters, AmlsStatistics, amls_lowest_modes};
pub use amls_parameters::AmlsParameters;
pub use leaf_modes::{LeafModes, LeafModesParameters, leaf_modes};
pub use multilevel_substructures::MultilevelSubstructures;
pub use nested_dissection::nested_dissection;
pub use substructure_tree::{SubstructureNode, SubstructureTree};
