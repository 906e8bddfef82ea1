//! Errors of comparing reports (`flexmodes diff`): a file that holds no report, or reports
//! whose numbers moved.

use thiserror::Error;

/// Errors of comparing two reports or two folders of them.
#[derive(Debug, Error, serde::Serialize)]
pub enum ReportDiffError {
    /// A `.json` file that does not parse.
    #[error("{path}: not JSON at line {line}, column {column}: {message}")]
    NotJson {
        path: String,
        line: usize,
        column: usize,
        message: String,
    },

    /// A file (or a recording) that holds no scene report.
    #[error("{path}: {why}")]
    NoReport { path: String, why: String },

    /// Two folders with no scene in common.
    #[error("{old} and {new} have no report in common (a report is SCENE.json or SCENE.rrd)")]
    NothingInCommon { old: String, new: String },

    /// Numbers moved beyond the tolerance, or entries were added or removed.
    #[error(
        "{changes} change(s) beyond a relative tolerance of {rtol:e} in {reports} report(s) compared"
    )]
    Differ {
        changes: usize,
        rtol: f64,
        reports: usize,
    },
}
