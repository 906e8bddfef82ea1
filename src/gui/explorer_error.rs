//! What the explorer's last request or command ran into: the panel shows it under its
//! controls while the last good recording stays on screen.

use std::{fmt, path::PathBuf, sync::Arc};

use crate::{Error, scenes::SceneId};

/// The explorer's last failure, with the error that caused it.
#[derive(Debug, Clone)]
pub enum ExplorerError {
    /// The panel's settings do not make a request: a field that does not parse, a body file
    /// that does not load.
    Settings(Arc<Error>),
    /// The scene refused its options or failed while computing them.
    Scene {
        /// The scene asked for.
        scene: SceneId,
        /// Why.
        error: Arc<Error>,
    },
    /// The scene's output did not make a recording.
    Recording {
        /// The scene whose output it was.
        scene: SceneId,
        /// Why.
        error: Arc<Error>,
    },
    /// The recording could not be saved.
    Save {
        /// Where it was to be written.
        path: PathBuf,
        /// Why.
        error: Arc<Error>,
    },
}

impl ExplorerError {
    /// The error that caused the failure (match on it for its data).
    pub fn cause(&self) -> &Error {
        match self {
            ExplorerError::Settings(error)
            | ExplorerError::Scene { error, .. }
            | ExplorerError::Recording { error, .. }
            | ExplorerError::Save { error, .. } => error,
        }
    }
}

/// The cause's chain, as the command line prints it; a failed save names its file first.
impl fmt::Display for ExplorerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let ExplorerError::Save { path, .. } = self {
            write!(f, "saving {}: ", path.display())?;
        }
        f.write_str(&self.cause().cause_chain())
    }
}

impl std::error::Error for ExplorerError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(self.cause())
    }
}
