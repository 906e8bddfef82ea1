//! What is wrong with a DOF set a reduction was given (boundary, held, interface, r-set,
//! inputs, outputs), with its data.

/// What is wrong with a DOF set ([`ReductionError::InvalidDofSet`](super::ReductionError)).
/// Nodes are 1-based, as users number them; DOF are 0-based rows of the body's matrices, or
/// a node's DOF by name (`x`, `θz`).
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum DofSetProblem {
    /// No DOF in it.
    #[error("it is empty")]
    Empty,
    /// A DOF the body does not have.
    #[error("DOF {dof} is out of range: the body has {count} DOF")]
    OutOfRange { dof: usize, count: usize },
    /// A DOF given twice.
    #[error("node {node} {dof} is listed twice")]
    Twice { node: usize, dof: &'static str },
    /// A DOF another set of the same reduction already holds.
    #[error("node {node} {dof} already belongs to another set")]
    InAnotherSet { node: usize, dof: &'static str },
    /// Boundary and held DOF that leave no interior DOF.
    #[error("every DOF is a boundary or held DOF, nothing is left to reduce")]
    NothingLeft,
    /// A node set without nodes.
    #[error("the node set is empty")]
    NoNodes,
    /// A rigid interface's DOF that the basis does not keep as a unit boundary column.
    #[error(
        "node {node} {dof} has no unit boundary column in the {method} basis (a rigid interface \
         needs its nodes in the boundary of CB, GR, MT or MC)"
    )]
    NotInBoundary {
        node: usize,
        dof: &'static str,
        method: &'static str,
    },
    /// A node tied to two rigid interfaces.
    #[error("node {node} is tied to two interfaces")]
    TiedTwice { node: usize },
    /// A rigid interface's DOF that is not among the boundary DOF.
    #[error(
        "node {node} {dof} is not a boundary DOF (a rigid interface's nodes must be boundary nodes)"
    )]
    NotBoundary { node: usize, dof: &'static str },
    /// An averaging interface's weights, one per node, that do not match its nodes.
    #[error("{weights} weights for {nodes} nodes")]
    WeightCount { weights: usize, nodes: usize },
    /// An averaging interface's weight that is not positive.
    #[error("the weight of node {node} is {weight}: weights must be positive")]
    NonPositiveWeight { node: usize, weight: f64 },
    /// An averaging interface whose nodes do not fix a rigid motion (all on one line).
    #[error(
        "its {nodes} nodes do not fix a rigid motion (R^T D R has condition {condition}: nodes \
         on one line leave the rotation about it free)", condition = crate::report::readable(.condition, 2))]
    NoRigidMotion { nodes: usize, condition: f64 },
    /// A frequency response without an input or an output.
    #[error("a frequency response needs at least one input and one output")]
    NoInputOrOutput,
    /// A driven interface that is not one rigid (RBE2) interface.
    #[error(
        "the drive must be one rigid interface: rbe2:SET or an rbe2 interface of the body file"
    )]
    DriveNotRigid,
    /// A pinned interface that is not a rigid (RBE2) node set.
    #[error("a pinned interface must be a rigid (rbe2) node set")]
    PinNotRigid,
    /// Vectors, loads or a component's maps of other lengths than the body's (`what`: which).
    #[error("{what}: {found} where the body needs {expected}")]
    Shape {
        what: &'static str,
        found: usize,
        expected: usize,
    },
}
