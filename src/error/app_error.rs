//! The application's errors: what a user asked of the command line, the explorer or the
//! classroom that does not hold (an unknown scene, method or option), and what Rerun, a bench's
//! peer or the server reported. Every error of the numerics comes wrapped, as
//! [`Error::Core`].

use thiserror::Error;

use flexmodes_core::error::{
    BodyFileError, DynamicsError, LinalgError, MeshError, ReductionError, ReportDiffError,
};

/// Everything that can go wrong in flexmodes: the application's own errors and, wrapped,
/// core's.
#[derive(Debug, Error)]
pub enum Error {
    /// A scene id that is not in the registry.
    #[error("unknown scene `{id}` (known scenes: {})", known.join(", "))]
    UnknownScene {
        id: flexmodes_core::error::Excerpt,
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
        token: flexmodes_core::error::Excerpt,
        named: Vec<&'static str>,
    },

    /// A peer a bench runs (a process) failed: the last line it wrote to stderr.
    #[error("{peer} failed: {stderr}")]
    PeerFailed {
        peer: &'static str,
        stderr: flexmodes_core::error::Excerpt,
    },

    /// A file a peer wrote (`file`) that does not parse.
    #[error("{peer} wrote a {file} that does not parse")]
    PeerOutput {
        peer: &'static str,
        file: &'static str,
        #[source]
        source: serde_json::Error,
    },

    /// A visual's per-time sequences differ in length (a scene's bug, caught before logging
    /// a frame whose parts do not belong together).
    #[error("the visual `{path}` has {found} {what}; {expected} expected")]
    MismatchedSeries {
        path: flexmodes_core::error::Name,
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
        source: Option<Box<dyn std::error::Error + Send + Sync>>,
    },

    /// Errors of serving the classroom (`flexmodes serve`).
    #[error(transparent)]
    Serve(#[from] super::ServeError),

    /// Errors of the numerics, the bodies, the reductions, the dynamics and the models
    /// (flexmodes-core's).
    #[error(transparent)]
    Core(#[from] flexmodes_core::Error),
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

    /// Core's [`Io`](flexmodes_core::Error::Io) error of `path`.
    pub fn io(path: impl Into<std::path::PathBuf>, source: std::io::Error) -> Self {
        Error::Core(flexmodes_core::Error::Io {
            path: path.into(),
            source,
        })
    }

    /// Whether the work was asked to stop (a newer request superseded it), not failed.
    pub fn is_cancelled(&self) -> bool {
        matches!(self, Error::Core(flexmodes_core::Error::Cancelled))
    }

    /// The message and its causes on one line, as the command line and the explorer show it
    /// (core's [`cause_chain`](flexmodes_core::error::cause_chain)).
    pub fn cause_chain(&self) -> String {
        flexmodes_core::error::cause_chain(self)
    }
}

/// A layer's error enters the application's through core's, so `?` reads one step.
macro_rules! through_core {
    ($($layer:ty),* $(,)?) => {
        $(impl From<$layer> for Error {
            fn from(e: $layer) -> Self {
                Error::Core(e.into())
            }
        })*
    };
}

through_core!(
    LinalgError,
    MeshError,
    BodyFileError,
    DynamicsError,
    ReductionError,
    ReportDiffError
);

/// Result alias of the application.
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
