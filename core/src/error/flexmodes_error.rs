//! Typed errors. Every error names its cause (which node, which matrix, which value), so the
//! CLI can print a one-line cause chain and the GUI can show it without losing state.

use thiserror::Error;

use super::as_text::as_text;

/// What can go wrong in the numerics, the bodies and the models, from a node out of range to a
/// failed decomposition: one variant per layer's enum, and the few that belong to no layer.
#[derive(Debug, Error, serde::Serialize)]
pub enum Error {
    /// A 1-based node number outside `1..=count`.
    #[error("node {node} is out of range: the {body} has nodes 1 to {count}")]
    NodeOutOfRange {
        node: usize,
        count: usize,
        body: super::Name,
    },

    /// The same node was given twice in a boundary or master set.
    #[error("node {node} is listed twice in the boundary set")]
    DuplicateNode { node: usize },

    /// A node that does not carry the named DOF (a rotation of a solid's node, z of a planar
    /// body).
    #[error(
        "node {node} of the {body} has no {dof} DOF (its nodes carry {})",
        carried.join(", ")
    )]
    NoSuchDof {
        node: usize,
        dof: &'static str,
        body: super::Name,
        carried: Vec<&'static str>,
    },

    /// A model larger than a method (or the machine) can take; `step` names the part of
    /// the method that is limited, when it is one.
    #[error(
        "{method}{} is limited to {limit} DOF, but this model has {dofs}",
        step.map(|s| format!(" ({s})")).unwrap_or_default()
    )]
    TooLarge {
        method: &'static str,
        step: Option<&'static str>,
        dofs: usize,
        limit: usize,
    },

    /// A static load case whose load vector is not the body's length.
    #[error("static load case: {entries} load entries for a body of {dofs} DOF")]
    LoadCaseLength { entries: usize, dofs: usize },

    /// A static load case holding a DOF (1-based) the body does not have.
    #[error("static load case: held DOF {dof} does not exist (the body has {dofs})")]
    LoadCaseHeldDof { dof: usize, dofs: usize },

    /// The computation was asked to stop (a newer request superseded it).
    #[error("cancelled: a newer request superseded this computation")]
    Cancelled,

    /// A stiffness with more zero-energy modes than a free body has rigid motions.
    #[error(
        "the body `{body}` is a mechanism: its stiffness has {zero_modes} zero-energy modes \
         (below {threshold_hz} Hz), more than the {rigid} rigid-body motions of a free \
         body; some DOF are unconnected or a joint is missing", threshold_hz = crate::report::readable(.threshold_hz, 2))]
    Mechanism {
        body: super::Name,
        zero_modes: usize,
        rigid: usize,
        threshold_hz: f64,
    },

    /// I/O error with the path involved.
    #[error("{}: {source}", path.display())]
    Io {
        path: std::path::PathBuf,
        #[source]
        #[serde(serialize_with = "as_text")]
        source: std::io::Error,
    },

    /// Errors of the linear algebra: factorisations, eigensolvers and their checks, memory.
    #[error(transparent)]
    Linalg(#[from] super::LinalgError),

    /// Errors of the mesh generators.
    #[error(transparent)]
    Mesh(#[from] super::MeshError),

    /// Errors of reading a body: the file, the line and what is wrong there.
    #[error(transparent)]
    BodyFile(#[from] super::BodyFileError),

    /// Errors of a time integration: where and when it stopped.
    #[error(transparent)]
    Dynamics(#[from] super::DynamicsError),

    /// Errors of a reduction: which boundary, DOF set, mode selection or system does not fit
    /// the method.
    #[error(transparent)]
    Reduction(#[from] super::ReductionError),

    /// Errors of comparing reports (`flexmodes diff`).
    #[error(transparent)]
    ReportDiff(#[from] super::ReportDiffError),
}

impl Error {
    /// The message and its causes on one line, as the command line, the explorer and Python
    /// show it ([`cause_chain`]).
    pub fn cause_chain(&self) -> String {
        cause_chain(self)
    }
}

/// `error`'s message and its causes on one line, `cause: cause: …`; a cause the message
/// already quotes (an I/O error behind its path) is not repeated. Core's errors and the
/// application's show their chains by this one function.
pub fn cause_chain(error: &dyn std::error::Error) -> String {
    let mut message = error.to_string();
    let mut source = error.source();
    while let Some(s) = source {
        let text = s.to_string();
        if !message.contains(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
        source = s.source();
    }
    message
}

/// Result alias used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
