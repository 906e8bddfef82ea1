//! Typed errors. Every error names its cause (which node, which matrix, which value), so the
//! CLI can print a one-line cause chain and the GUI can show it without losing state.

use thiserror::Error;

/// Everything that can go wrong in flexmodes, from bad user input to a failed decomposition.
#[derive(Debug, Error)]
pub enum Error {
    /// A scene id that is not in the registry.
    #[error("unknown scene `{id}` (known scenes: {known})")]
    UnknownScene { id: String, known: String },

    /// A reduction-method id that is not known, or not available in this scene.
    #[error("unknown or unsupported method `{id}` for scene `{scene}` (available: {available})")]
    UnknownMethod {
        id: String,
        scene: String,
        available: String,
    },

    /// An axis-type id that is not known, or not available in this scene.
    #[error("unknown or unsupported axis type `{id}` for scene `{scene}` (available: {available})")]
    UnknownAxes {
        id: String,
        scene: String,
        available: String,
    },

    /// A 1-based node number outside `1..=count`.
    #[error("node {node} is out of range: the {body} has nodes 1 to {count}")]
    NodeOutOfRange {
        node: usize,
        count: usize,
        body: String,
    },

    /// The same node was given twice in a boundary or master set.
    #[error("node {node} is listed twice in the boundary set")]
    DuplicateNode { node: usize },

    /// A boundary set that is empty or leaves no interior DOF.
    #[error("invalid boundary set {nodes:?}: {reason}")]
    InvalidBoundary { nodes: Vec<usize>, reason: String },

    /// A DOF set (boundary, held, interface, r-set, inputs, outputs) naming a DOF that does
    /// not exist or naming one twice.
    #[error("invalid {set} DOF set: {reason}")]
    InvalidDofSet { set: String, reason: String },

    /// A method asked of the generic [`reduce`](crate::reduction::reduce) entry point that
    /// needs more than a boundary set and a mode count.
    #[error("{method} needs {needs}")]
    MethodNeedsContext { method: String, needs: String },

    /// A node that does not carry the named DOF (a rotation of a solid's node, z of a planar
    /// body).
    #[error("node {node} of the {body} has no {dof} DOF (its nodes carry {carried})")]
    NoSuchDof {
        node: usize,
        dof: String,
        body: String,
        carried: String,
    },

    /// MacNeal–Rubin's r-set (Spanos–Tsuha Eq. 11) must restrain every rigid motion with
    /// exactly as many DOF as there are rigid motions (statically determinate).
    #[error("invalid MacNeal-Rubin r-set {dofs}: {reason}")]
    InvalidRSet { dofs: String, reason: String },

    /// Balanced truncation of a system whose poles are not all strictly stable.
    #[error(
        "balanced truncation needs an asymptotically stable (damped) system: {reason}; add \
         modal damping or a damping matrix"
    )]
    UndampedSystem { reason: String },

    /// A frequency band that contains none of the model's modes.
    #[error("the band {low_hz} to {high_hz} Hz contains no mode of the {what}")]
    EmptyBand {
        low_hz: f64,
        high_hz: f64,
        what: String,
    },

    /// $K_{ii}$ is singular: the boundary DOF do not restrain every rigid-body motion.
    #[error(
        "K_ii is singular for boundary nodes {boundary_nodes:?}: {rank_deficiency} rigid-body \
         motion(s) of the interior stay unrestrained ({free_motions}); Craig-Bampton, Guyan and \
         mode condensation need at least {needed} properly chosen boundary DOF"
    )]
    SingularInterior {
        boundary_nodes: Vec<usize>,
        rank_deficiency: usize,
        /// The unrestrained motions in words, e.g. `rotation about (1, 0, 0) through (0, 0, 0) m`.
        free_motions: String,
        needed: usize,
    },

    /// A Cholesky factorisation met a pivot that is not positive.
    #[error(
        "the {matrix} matrix is not positive definite: the pivot of its row {index} (0-based) \
         is not positive"
    )]
    NonPositivePivot { matrix: String, index: usize },

    /// An allocation the computation needs could not be made.
    #[error("out of memory: {what}")]
    OutOfMemory { what: String },

    /// A model larger than a method (or the machine) can take.
    #[error("{method} is limited to {limit} DOF, but this model has {dofs}")]
    TooLarge {
        method: String,
        dofs: usize,
        limit: usize,
    },

    /// A mesh whose estimated memory exceeds what the machine has.
    #[error(
        "a {dofs}-DOF mesh needs about {estimated_gb:.1} GB, more than the {available_gb:.1} GB \
         this machine has free"
    )]
    MeshTooLarge {
        dofs: usize,
        estimated_gb: f64,
        available_gb: f64,
    },

    /// The partial eigensolver stopped before every wanted pair was accurate.
    #[error(
        "the partial eigensolver did not converge: {converged} of {wanted} pairs converged, \
         worst relative residual {residual:.1e}"
    )]
    EigenNotConverged {
        converged: usize,
        wanted: usize,
        residual: f64,
    },

    /// A dense eigen-decomposition whose pairs failed their residual or orthonormality check
    /// with every kernel tried.
    #[error(
        "the {what} eigenproblem failed its check: worst residual {residual:.1e} against a \
         tolerance of {tolerance:.1e} (faer and nalgebra both tried)"
    )]
    EigenCheckFailed {
        what: String,
        residual: f64,
        tolerance: f64,
    },

    /// A NaN or infinite entry in a matrix handed to a decomposition.
    #[error("the {what} has a non-finite entry at row {row}, column {col} (0-based)")]
    NotFinite {
        what: String,
        row: usize,
        col: usize,
    },

    /// More normal modes were requested than the interior eigenproblem has.
    #[error("{requested} normal modes requested but only {available} exist for this interior set")]
    TooManyModes { requested: usize, available: usize },

    /// A frequency cut-off that keeps no mode where at least one is required.
    #[error("invalid mode selection: {reason}")]
    InvalidModeSelection { reason: String },

    /// A matrix that should be symmetric positive definite is not.
    #[error("the {matrix} matrix is not positive definite")]
    NotPositiveDefinite { matrix: String },

    /// A square matrix that must be inverted is singular: its factorisation failed, or gave
    /// a non-finite solution. `rcond` is the reciprocal condition estimate where one was
    /// computed.
    #[error(
        "the {matrix} matrix is singular{}",
        rcond.map(|r| format!(" (reciprocal condition estimate {r:.1e})")).unwrap_or_default()
    )]
    SingularMatrix { matrix: String, rcond: Option<f64> },

    /// An eigen- or singular-value decomposition did not converge.
    #[error("the {what} decomposition did not converge")]
    DecompositionFailed { what: String },

    /// Eitelberg's method needs every pole of A in the open left half-plane.
    #[error(
        "Eitelberg's method needs a stable A, but its largest real eigenvalue part is \
         {max_real_part:.3e} >= 0 (use the output-feedback trick A - B L C)"
    )]
    UnstableSystem { max_real_part: f64 },

    /// The Lyapunov equation solve left a residual larger than its tolerance.
    #[error("the Lyapunov equation was solved with relative residual {residual:.1e}")]
    LyapunovInaccurate { residual: f64 },

    /// A nodal-fixed anchor coordinate that is not a boundary (identity) column of Ψ.
    #[error(
        "nodal-fixed axes anchor node {node} {direction}, but that coordinate is not a boundary \
         column of the {method} basis (add node {node} to the boundary set)"
    )]
    AnchorNotInBasis {
        node: usize,
        direction: &'static str,
        method: String,
    },

    /// A nodal-fixed configuration whose three nodes are not distinct or whose axes do not fit.
    #[error("invalid nodal-fixed axes: {reason}")]
    InvalidAxes { reason: String },

    /// A static load case that does not fit the body.
    #[error("static load case: {reason}")]
    InvalidLoadCase { reason: String },

    /// A time integration that could not continue.
    #[error("the integration diverged at t = {time:.4} s: {reason}")]
    Diverged { time: f64, reason: String },

    /// The Newton iterations of an implicit step did not converge, even with a fresh
    /// iteration matrix.
    #[error(
        "Newton's method did not converge at t = {time:.4} s: residual {residual:e} after \
         {iterations} iterations (a smaller --dt may help)"
    )]
    NewtonFailed {
        time: f64,
        iterations: usize,
        residual: f64,
    },

    /// The computation was asked to stop (a newer request superseded it).
    #[error("cancelled: a newer request superseded this computation")]
    Cancelled,

    /// Bad scene option (a combination the scene cannot honour).
    #[error("invalid option for scene `{scene}`: {reason}")]
    InvalidOption { scene: String, reason: String },

    /// Writing a recording failed; the destination was left untouched.
    #[error("could not write recording {path}: {reason}")]
    RecordingWrite { path: String, reason: String },

    /// Rerun reported an error while logging.
    #[error("rerun: {0}")]
    Rerun(String),

    /// A Matrix Market file whose first line is not a real `coordinate` or `array` header.
    #[error("{path}:{line}: not a real Matrix Market matrix: {found}")]
    MatrixMarketHeader {
        path: String,
        line: usize,
        found: String,
    },

    /// A line of a Matrix Market file (or a CSV file of a body) that does not parse.
    #[error("{path}:{line}: {reason}")]
    MatrixMarketLine {
        path: String,
        line: usize,
        reason: String,
    },

    /// A Matrix Market entry whose 1-based index lies outside the size line's dimensions.
    #[error("{path}:{line}: entry ({row}, {col}) lies outside the {rows} × {cols} matrix")]
    MatrixIndexOutOfRange {
        path: String,
        line: usize,
        row: usize,
        col: usize,
        rows: usize,
        cols: usize,
    },

    /// A NaN or infinite value in a matrix file.
    #[error("{path}:{line}: the value `{value}` is not finite")]
    NonFiniteEntry {
        path: String,
        line: usize,
        value: String,
    },

    /// A body file (TOML) that does not parse or names something inconsistent.
    #[error("{path}{}: {reason}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    BodyFile {
        path: String,
        line: Option<usize>,
        reason: String,
    },

    /// A matrix whose size does not match the body's DOF map or the other matrix.
    #[error("{path}: the {what} is {rows} × {cols}, but {expected}")]
    MatrixSizeMismatch {
        path: String,
        what: String,
        rows: usize,
        cols: usize,
        expected: String,
    },

    /// A stiffness or consistent mass that is not symmetric.
    #[error(
        "{path}: the {what} is not symmetric: entry ({row}, {col}) differs from ({col}, {row}) \
         by {asymmetry:.3e} relative to the largest entry (tolerance {tolerance:.0e})"
    )]
    NotSymmetric {
        path: String,
        what: String,
        row: usize,
        col: usize,
        asymmetry: f64,
        tolerance: f64,
    },

    /// A mass matrix that is not positive definite, located at a DOF.
    #[error("{path}: the mass matrix is not positive definite at DOF {dof} ({label}): {reason}")]
    MassNotPositive {
        path: String,
        dof: usize,
        label: String,
        reason: String,
    },

    /// A node set that names a node the body does not have.
    #[error("{path}: node set `{set}` names node {node}, but the body has nodes 1 to {count}")]
    NodeSetOutOfRange {
        path: String,
        set: String,
        node: usize,
        count: usize,
    },

    /// A boundary given by a set name that the body file does not define.
    #[error("unknown node set `{name}` (the body defines: {known})")]
    UnknownNodeSet { name: String, known: String },

    /// Drawing asked of a body that has no node coordinates.
    #[error(
        "the body `{body}` has no node coordinates, so it cannot be drawn (add `nodes` under \
         [geometry] in its body file; `report` and `export` work without them)"
    )]
    NoCoordinates { body: String },

    /// A stiffness with more zero-energy modes than a free body has rigid motions.
    #[error(
        "the body `{body}` is a mechanism: its stiffness has {zero_modes} zero-energy modes \
         (below {threshold_hz:.1e} Hz), more than the {rigid} rigid-body motions of a free \
         body; some DOF are unconnected or a joint is missing"
    )]
    Mechanism {
        body: String,
        zero_modes: usize,
        rigid: usize,
        threshold_hz: f64,
    },

    /// I/O error with the path involved.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
}

/// Result alias used across the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl From<rerun::RecordingStreamError> for Error {
    fn from(e: rerun::RecordingStreamError) -> Self {
        Error::Rerun(e.to_string())
    }
}

impl From<rerun::SerializationError> for Error {
    fn from(e: rerun::SerializationError) -> Self {
        Error::Rerun(e.to_string())
    }
}
