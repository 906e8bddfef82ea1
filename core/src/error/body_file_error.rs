//! Errors of reading a body: the file, the line and what is wrong there.

use std::path::PathBuf;

use thiserror::Error;

/// Errors of reading a body: the file, the line and what is wrong there.
#[derive(Debug, Error, serde::Serialize)]
pub enum BodyFileError {
    /// A format flexmodes reads but does not write.
    #[error("{format} is read, not written: write matrix-market, abaqus or nastran-dmig")]
    NotWritable { format: &'static str },

    /// A Matrix Market file whose first line is not a real `coordinate` or `array` header.
    #[error("{}:{line}: not a real Matrix Market matrix: {problem}", path.display())]
    MatrixMarketHeader {
        path: PathBuf,
        line: usize,
        problem: super::MatrixLineProblem,
    },

    /// A line of a body's CSV table (node coordinates, edges) that does not fit.
    #[error("{}:{line}: {problem}", path.display())]
    TableLine {
        path: PathBuf,
        line: usize,
        problem: super::TableProblem,
    },

    /// A line of a matrix file (line 0: the file as a whole, printed without a line) that
    /// does not parse.
    #[error("{}{}: {problem}", path.display(), at_line(*line))]
    MatrixLine {
        path: PathBuf,
        line: usize,
        problem: super::MatrixLineProblem,
    },

    /// A byte of a binary matrix file (OP4) where its records do not parse.
    #[error("{}: byte {byte}: {problem}", path.display())]
    MatrixByte {
        path: PathBuf,
        byte: usize,
        problem: super::MatrixLineProblem,
    },

    /// A gzip-compressed matrix file whose stream is damaged.
    #[error("{}: the gzip stream is damaged: {source}", path.display())]
    GzipDamaged {
        path: PathBuf,
        #[serde(serialize_with = "super::as_text::as_text")]
        source: std::io::Error,
    },

    /// A Matrix Market entry whose 1-based index lies outside the size line's dimensions.
    #[error(
        "{}:{line}: entry ({row}, {col}) lies outside the {rows} × {cols} matrix",
        path.display()
    )]
    MatrixIndexOutOfRange {
        path: PathBuf,
        line: usize,
        row: usize,
        col: usize,
        rows: usize,
        cols: usize,
    },

    /// A NaN or infinite value in a matrix file.
    #[error("{}:{line}: the value `{value}` is not finite", path.display())]
    NonFiniteEntry {
        path: PathBuf,
        line: usize,
        value: super::Excerpt,
    },

    /// A body file (TOML) that does not parse or names something inconsistent.
    #[error(
        "{}{}: {problem}",
        path.display(),
        line.map(|l| format!(":{l}")).unwrap_or_default()
    )]
    BodyFile {
        path: PathBuf,
        line: Option<usize>,
        problem: super::BodySpecProblem,
    },

    /// A matrix whose size does not match the body's DOF map or the other matrix.
    #[error("{}: the {what} is {rows} × {cols}, but {expected}", path.display())]
    MatrixSizeMismatch {
        path: PathBuf,
        what: &'static str,
        rows: usize,
        cols: usize,
        expected: super::SizeExpectation,
    },

    /// A stiffness or consistent mass that is not symmetric.
    #[error(
        "{}: the {what} is not symmetric: entry ({row}, {col}) differs from ({col}, {row}) \
         by {asymmetry} relative to the largest entry (tolerance {tolerance})",
        path.display(), asymmetry = crate::report::readable(.asymmetry, 4), tolerance = crate::report::readable(.tolerance, 1))]
    NotSymmetric {
        path: PathBuf,
        what: &'static str,
        row: usize,
        col: usize,
        asymmetry: f64,
        tolerance: f64,
    },

    /// A mass matrix that is not positive definite, located at a DOF.
    #[error(
        "{}: the mass matrix is not positive definite at DOF {dof} (node {node} {component}): \
         {defect}",
        path.display()
    )]
    MassNotPositive {
        path: PathBuf,
        dof: usize,
        /// The node the DOF belongs to, 1-based.
        node: usize,
        component: &'static str,
        defect: super::MassDefect,
    },

    /// A node set that names a node the body does not have.
    #[error(
        "{}: node set `{set}` names node {node}, but the body has nodes 1 to {count}",
        path.display()
    )]
    NodeSetOutOfRange {
        path: PathBuf,
        set: super::Name,
        node: usize,
        count: usize,
    },

    /// A boundary given by a set name that the body file does not define.
    #[error(
        "unknown node set `{name}` (the body defines: {})",
        if known.is_empty() { "no node sets".to_string() } else { super::name::joined(known) }
    )]
    UnknownNodeSet {
        name: super::Excerpt,
        known: Vec<super::Name>,
    },

    /// Drawing asked of a body that has no node coordinates.
    #[error(
        "the body `{body}` has no node coordinates, so it cannot be drawn (add `nodes` under \
         [geometry] in its body file; `report` and `export` work without them)"
    )]
    NoCoordinates { body: super::Name },

    /// A length unit flexmodes cannot convert to metres (gravity, shaking amplitudes).
    #[error(
        "the body's length unit `{unit}` is not one SI quantities can be converted to (m, cm, \
         mm, in, ft)"
    )]
    UnknownLengthUnit { unit: super::Excerpt },

    /// An interface was left to the body file, which names none.
    #[error(
        "the body `{body}` defines no node sets: name its interface (`--boundary` on the \
         command line, `boundary=` in Python)"
    )]
    NoNodeSets { body: super::Name },
}

/// `:LINE` after a path, or nothing for line 0 (a problem of the file as a whole).
fn at_line(line: usize) -> String {
    if line == 0 {
        String::new()
    } else {
        format!(":{line}")
    }
}
