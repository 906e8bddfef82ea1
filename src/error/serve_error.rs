//! Errors of serving the classroom: which address, port, file or asset.

use std::{net::IpAddr, path::PathBuf};

use thiserror::Error;

/// Errors of `flexmodes serve`: which address, port, file or asset.
#[derive(Debug, Error, serde::Serialize)]
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

    /// An address that is not an IP address of this machine.
    #[error("cannot bind {address}{}: {reason}", port.map(|p| format!(":{p}")).unwrap_or_default())]
    Bind {
        address: IpAddr,
        port: Option<u16>,
        reason: String,
    },

    /// A recording file that does not decode whole (or holds no recording).
    #[error("{}: not a Rerun recording flexmodes can serve: {reason}", .path.display())]
    Recording { path: PathBuf, reason: String },

    /// A `--control-token` too short or with characters a URL would change (not echoed: it is
    /// the teacher's secret).
    #[error(
        "--control-token: the token given ({length} characters) needs at least 16 characters, \
         each of A-Z, a-z, 0-9, -, _, ., ~"
    )]
    ControlToken { length: usize },

    /// No random control token from the operating system, or no Ctrl-C handler.
    #[error("the classroom server cannot start: {reason}")]
    System { reason: String },

    /// The embedded web viewer's files.
    #[error("the embedded web viewer: {reason}")]
    Viewer { reason: String },
}
