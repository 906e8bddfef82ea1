//! What is wrong with a MacNeal–Rubin r-set (Spanos–Tsuha Eq. 11) or the 3-2-1 support
//! chosen for it.

/// What is wrong with an r-set ([`ReductionError::InvalidRSet`](super::ReductionError)).
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum RSetProblem {
    /// A body whose rigid-body motions are not known from its geometry (no coordinates, or
    /// DOF that are not nodal translations and rotations).
    #[error("the rigid motions of the body are not known from its geometry")]
    UnknownRigidMotions,
    /// An r-set given for a held component, which has no rigid-body motions to restrain.
    #[error(
        "the component is held, so it has no rigid-body motions to restrain; leave the r-set empty"
    )]
    HeldComponent,
    /// An r-set that restrains only `rank` of the `rigid` rigid-body motions.
    #[error(
        "it restrains only {rank} of the {rigid} rigid-body motions, so the restrained stiffness \
         of Eq. (13) is singular"
    )]
    Deficient { rank: usize, rigid: usize },
    /// More DOF than rigid-body motions: statically indeterminate.
    #[error(
        "it is redundant: {dofs} DOF for {rigid} rigid-body motions (statically indeterminate); \
         Eq. (13) needs a statically determinate set"
    )]
    Redundant { dofs: usize, rigid: usize },
    /// Fewer than three nodes outside the interface for a 3-2-1 support.
    #[error("{nodes} nodes outside the interface; three are needed")]
    TooFewNodes { nodes: usize },
    /// The nodes outside the interface lie on a line: no 3-2-1 support fixes the rotation about it.
    #[error("the nodes outside the interface lie on a line")]
    Collinear,
}
