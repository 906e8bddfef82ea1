//! What size a body's matrix should have had
//! ([`super::BodyFileError::MatrixSizeMismatch`]).

/// What size a body's matrix should have had, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum SizeExpectation {
    /// A stiffness must be square, with at least one DOF.
    #[error("a stiffness must be square, with at least one DOF")]
    Square,
    /// A mass the size of the stiffness (`n` × `n`), or a lumped vector of `n`.
    #[error("the stiffness is {n} × {n} (or give an {n} × 1 lumped vector)")]
    LikeStiffness { n: usize },
    /// Without coordinates, the DOF must divide into nodes of `per` DOF.
    #[error("its DOF do not divide into nodes of {per} DOF (`dofs` in {body_file})")]
    WholeNodes { per: usize, body_file: super::Name },
    /// No more DOF than the mass file's entries: every DOF needs a positive mass.
    #[error("every DOF needs a positive mass, and the mass {mass} holds only {entries} entries")]
    MassEntries { mass: super::Name, entries: usize },
    /// As many rows as the DOF map has equations.
    #[error("the DOF map {map} has {equations} equations")]
    DofMapEquations { map: super::Name, equations: usize },
    /// The nodes times their DOF.
    #[error("{nodes} nodes with {} DOF each ({}) make {} DOF", dofs.len(), super::name::joined(dofs), nodes * dofs.len())]
    NodesTimesDof {
        nodes: usize,
        dofs: Vec<super::Name>,
    },
}
