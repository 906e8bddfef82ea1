//! Finite-element bodies: the App. A beam, the App. B slab and the same mesh standing as the
//! plank of §5.3.3.

mod beam2d;
mod brick_elements;
mod brick_mesh;
mod dof_map;
mod dual_spin;
mod fe_model;
mod frame3d;
mod hex8;
mod hex8_geometric;
mod inertia_loads;
mod l_bracket;
mod mass_properties;
mod node_index;
mod overhang_frame;
mod spinning_beam;
mod triplets;

pub use beam2d::{BeamParameters, beam};
pub use brick_elements::BrickElements;
pub use brick_mesh::{SlabParameters, plank, slab, slab_bricks};
pub use dof_map::{DofMap, NodeDof};
pub use dual_spin::{DualSpin, DualSpinParameters, add_lumped, dual_spin};
pub use fe_model::{Direction, FeModel, RigidMotions};
pub use frame3d::{FrameSection, frame, frame_of_sections, frame_stiffness};
pub use hex8::{
    EDGES as HEX8_EDGES, LOCAL_NODES as HEX8_LOCAL_NODES, hex8_consistent_mass, hex8_stiffness,
};
pub use hex8_geometric::{GaussStresses, hex8_geometric_stiffness, hex8_stresses};
pub use inertia_loads::{InertiaLoadCase, InertiaLoads, acceleration_field};
pub use l_bracket::{LBracketParameters, l_bracket};
pub use mass_properties::MassProperties;
pub use node_index::NodeIndex;
pub use overhang_frame::{
    OverhangDirection, OverhangFrame, OverhangFrameParameters, overhang_frame,
};
pub use spinning_beam::{BEAM_NODE_DOF, BendingPlane, SpinningBeam, SpinningBeamParameters};
pub use triplets::Triplets;
