//! Errors of serving the classroom: which address, port, file or asset.

use std::{net::IpAddr, path::PathBuf};

use thiserror::Error;

/// Errors of `flexmodes serve`: which address, port, file or asset.
#[derive(Debug, Error)]
pub enum ServeError {
    /// The binary was built without the `serve` feature.
    #[error(
        "this flexmodes was built without the `serve` feature: build it with \
         `cargo build --release --features serve` (see docs/classroom.md)"
    )]
    NotBuilt,

    /// A port another program (or another server) already holds.
    #[error("{address}:{port} is in use (the {what}); choose another with --{option}")]
    PortInUse {
        address: IpAddr,
        port: u16,
        what: &'static str,
        option: &'static str,
    },

    /// An address that is not an IP address of this machine; `source` is the system's (or
    /// the server library's) refusal.
    #[error("cannot bind {address}{}", port.map(|p| format!(":{p}")).unwrap_or_default())]
    Bind {
        address: IpAddr,
        port: Option<u16>,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },

    /// A recording file that does not decode whole (or holds no recording).
    #[error("{}: not a Rerun recording flexmodes can serve: {problem}", .path.display())]
    Recording {
        path: PathBuf,
        problem: RecordingProblem,
    },

    /// A `--control-token` too short or with characters a URL would change (not echoed: it is
    /// the teacher's secret).
    #[error(
        "--control-token: the token given ({length} characters) needs at least 16 characters, \
         each of A-Z, a-z, 0-9, -, _, ., ~"
    )]
    ControlToken { length: usize },

    /// No random control token from the operating system (`source`: its refusal).
    #[error("the classroom server cannot start: no random control token from the operating system")]
    NoRandomToken {
        #[source]
        source: std::io::Error,
    },

    /// No Ctrl-C handler (`source`: why).
    #[error("the classroom server cannot start: it cannot catch Ctrl-C")]
    NoInterruptHandler {
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },

    /// The embedded web viewer's files: `what` no longer holds as flexmodes serves it
    /// (`source`: the library's error, when one was given).
    #[error("the embedded web viewer: {what}")]
    Viewer {
        what: &'static str,
        #[source]
        source: Option<Box<dyn std::error::Error + Send + Sync>>,
    },
}

/// What is wrong with a recording file `flexmodes serve` was given.
#[derive(Debug, Error)]
pub enum RecordingProblem {
    /// The file cannot be read.
    #[error("{0}")]
    Unreadable(std::io::Error),
    /// Message `message` (0-based) does not decode.
    #[error("message {message}: {source}")]
    Damaged {
        message: usize,
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// No message starts a recording.
    #[error("{messages} message(s), none of them starts a recording")]
    NoRecording { messages: usize },
    /// A recording without data.
    #[error("no data in it")]
    NoData,
}
