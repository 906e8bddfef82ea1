//! What is wrong with where a system's constraint or load is attached.

/// What is wrong with where a system's constraint or load is attached. Bodies are counted from
/// 0 (their place in the system), nodes by their 1-based numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum AttachmentProblem {
    /// A node the body does not have.
    NoSuchNode { body: usize, node: usize },
    /// A point of a body that is not rigid (a deformable body is attached at its nodes).
    NotRigid { body: usize },
    /// A node the body does not have, or an axis other than x, y, z (0, 1, 2).
    NoSuchNodeOrAxis {
        body: usize,
        node: usize,
        axis: usize,
    },
}

impl std::fmt::Display for AttachmentProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoSuchNode { body, node } => {
                write!(f, "node {node} of body {body}, which it does not have")
            }
            Self::NotRigid { body } => write!(f, "a point of body {body}, which is not rigid"),
            Self::NoSuchNodeOrAxis { body, node, axis } => write!(
                f,
                "node {node} of body {body}, which it does not have (or axis {axis})"
            ),
        }
    }
}
