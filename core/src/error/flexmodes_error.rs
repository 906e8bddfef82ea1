//! Typed errors. Every error names its cause (which node, which matrix, which value), so the
//! CLI can print a one-line cause chain and the GUI can show it without losing state.

use thiserror::Error;

use super::as_text::{as_optional_text, as_text};

/// Everything that can go wrong in flexmodes, from bad user input to a failed decomposition.
#[derive(Debug, Error, serde::Serialize)]
pub enum Error {
    /// A scene id that is not in the registry.
    #[error("unknown scene `{id}` (known scenes: {})", known.join(", "))]
    UnknownScene {
        id: super::Excerpt,
        known: Vec<&'static str>,
    },

    /// A reduction method the scene does not offer.
    #[error(
        "unknown or unsupported method `{id}` for scene `{scene}` (available: {})",
        listed(.available, "none")
    )]
    UnknownMethod {
        id: &'static str,
        scene: &'static str,
        available: Vec<&'static str>,
    },

    /// An axis type the scene does not offer.
    #[error(
        "unknown or unsupported axis type `{id}` for scene `{scene}` (available: {})",
        listed(.available, "none: this scene has no floating frame")
    )]
    UnknownAxes {
        id: &'static str,
        scene: &'static str,
        available: Vec<&'static str>,
    },

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

    /// An option the user gave that does not hold, or does not apply where it was given:
    /// `option` names it as typed (`--end-time`, `SCENES`), `scene` the scene it was given
    /// for (`None`: a command's option).
    #[error("invalid {option}{}: {reason}", in_scene(*.scene))]
    InvalidOption {
        option: &'static str,
        scene: Option<&'static str>,
        reason: String,
    },

    /// `bench` asked of a scene it does not measure.
    #[error(
        "bench measures slab-modes and the simulation scenes slab-sim1 and slab-sim2, not `{scene}`"
    )]
    NotBenchable { scene: &'static str },

    /// A mesh size `bench --sizes` cannot read.
    #[error(
        "--sizes: `{token}` is neither one of {} nor NXxNYxNZ with positive counts",
        named.join(", ")
    )]
    InvalidSize {
        token: super::Excerpt,
        named: Vec<&'static str>,
    },

    /// A peer a bench runs (a process) failed: the last line it wrote to stderr.
    #[error("{peer} failed: {stderr}")]
    PeerFailed {
        peer: &'static str,
        stderr: super::Excerpt,
    },

    /// A file a peer wrote (`file`) that does not parse.
    #[error("{peer} wrote a {file} that does not parse")]
    PeerOutput {
        peer: &'static str,
        file: &'static str,
        #[source]
        #[serde(serialize_with = "as_text")]
        source: serde_json::Error,
    },

    /// A visual's per-time sequences differ in length (a scene's bug, caught before logging
    /// a frame whose parts do not belong together).
    #[error("the visual `{path}` has {found} {what}; {expected} expected")]
    MismatchedSeries {
        path: super::Name,
        what: &'static str,
        expected: usize,
        found: usize,
    },

    /// Rerun reported an error: `step` what flexmodes asked of it (encode, flush, the
    /// blueprint, the desktop app), `source` Rerun's (or the viewer's) error when it gave one.
    #[error(
        "rerun: {step}{}",
        source.as_ref().map(|s| format!(": {s}")).unwrap_or_default()
    )]
    Rerun {
        step: &'static str,
        #[source]
        #[serde(serialize_with = "as_optional_text")]
        source: Option<Box<dyn std::error::Error + Send + Sync>>,
    },

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

    /// Errors of serving the classroom (`flexmodes serve`).
    #[error(transparent)]
    Serve(#[from] super::ServeError),
}

impl Error {
    /// [`Error::Rerun`] at `step`, caused by `source`.
    pub fn rerun(
        step: &'static str,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        Error::Rerun {
            step,
            source: Some(Box::new(source)),
        }
    }

    /// The message and its causes on one line, `cause: cause: …`, as the command line, the
    /// explorer and Python show it; a cause the message already quotes (an I/O error behind
    /// its path) is not repeated.
    pub fn cause_chain(&self) -> String {
        let mut message = self.to_string();
        let mut source = std::error::Error::source(self);
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
}

/// Result alias used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// ` in scene `ID`` for an error's message, or nothing.
fn in_scene(scene: Option<&str>) -> String {
    scene
        .map(|s| format!(" in scene `{s}`"))
        .unwrap_or_default()
}

/// `ids` comma separated, or `none` when there are none.
fn listed(ids: &[&str], none: &str) -> String {
    if ids.is_empty() {
        none.into()
    } else {
        ids.join(", ")
    }
}
