//! What is wrong on a line of a body's CSV table (node coordinates, edges)
//! ([`super::BodyFileError::TableLine`]).

/// What is wrong on one line of a table, with its data.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum TableProblem {
    /// A line that is not a row of numbers (past the first line, which may be a header).
    #[error("`{text}` is not a row of numbers")]
    NotNumbers { text: super::Excerpt },
    /// An edge row with fewer than two nodes.
    #[error("an edge needs two nodes (a face three or more)")]
    EdgeTooShort,
    /// A node number outside the body's nodes (1-based).
    #[error("node {node} is out of range: the body has nodes 1 to {count}")]
    NodeOutOfRange { node: usize, count: usize },
    /// A coordinate row whose leading node number breaks the count 1, 2, 3, …
    #[error(
        "a leading node number must count 1, 2, 3, ... in order: expected {expected}, got {found}"
    )]
    NodeNumberOutOfOrder { expected: usize, found: f64 },
    /// A coordinate row of other than 2 or 3 coordinates (after an optional node number).
    #[error("a node needs 2 or 3 coordinates (optionally after its number), got {values} values")]
    CoordinateCount { values: usize },
}
