//! Errors of a reduction: which boundary, DOF set, mode selection or system does not fit the method.

use thiserror::Error;

/// Errors of a reduction: which boundary, DOF set, mode selection or system does not fit the method.
#[derive(Debug, Error, serde::Serialize)]
pub enum ReductionError {
    /// An empty boundary set.
    #[error("invalid boundary set []: at least one boundary node is needed")]
    NoBoundary,

    /// A boundary set of every node: no interior DOF is left to reduce.
    #[error(
        "invalid boundary set {nodes:?}: every node is a boundary node, nothing is left to reduce"
    )]
    NoInterior { nodes: Vec<usize> },

    /// A DOF set (boundary, held, interface, r-set, inputs, outputs) naming a DOF that does
    /// not exist or naming one twice.
    #[error("invalid {set} DOF set: {problem}")]
    InvalidDofSet {
        set: super::DofSetName,
        problem: super::DofSetProblem,
    },

    /// A Craig–Bampton basis whose constraint modes couple to its normal modes through the
    /// reduced stiffness (they are K-orthogonal in exact arithmetic): `coupling` is the
    /// largest coupling entry over the largest entry of $K_r$.
    #[error(
        "the Craig-Bampton structure check failed: the constraint modes couple to the normal \
         modes through K_r at {coupling} of its largest entry (tolerance {tolerance})", coupling = crate::report::readable(.coupling, 2), tolerance = crate::report::readable(.tolerance, 1))]
    ConstraintModesCouple { coupling: f64, tolerance: f64 },

    /// An export another code cannot take as it is (`to`: the code).
    #[error("cannot export for {to}: {problem}")]
    NotExportable {
        to: &'static str,
        problem: super::ExportProblem,
    },

    /// An interface built from node coordinates (rbe2, rbe3) on a body whose coordinates'
    /// rigid motions are not K's null space though K is free (`defect`: max|KR| over
    /// |K||R|; `nodes`: where |KR| is largest, 1-based): its rigid ring would carry energy in
    /// rigid motion.
    #[error(
        "the interfaces {interfaces} are built from node coordinates that disagree with the \
         stiffness: their rigid motions leave K R = {defect} of |K||R| (round-off leaves \
         below 1e-9), largest at node(s) {nodes}; a ring tied to them would strain in rigid \
         motion. Usually the FE code moved those nodes (CalculiX repositions mid-side nodes of \
         distorted quadratic elements: write the coordinates of its .frd as the body's nodes)",
        defect = crate::report::readable(*defect, 2),
        nodes = nodes.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(", ")
    )]
    GeometryDisagrees {
        interfaces: String,
        defect: f64,
        nodes: Vec<usize>,
    },

    /// A method asked of the generic [`reduce`](crate::reduction::reduce) entry point that
    /// needs more than a boundary set and a mode count.
    #[error("{method} needs {needs}")]
    MethodNeedsContext {
        method: &'static str,
        needs: &'static str,
    },

    /// MacNeal–Rubin's r-set (Spanos–Tsuha Eq. 11) must restrain every rigid motion with
    /// exactly as many DOF as there are rigid motions (statically determinate). `set` says
    /// which: its DOF by node and name, how many, or whose (`of the steel_rod`).
    #[error("invalid MacNeal-Rubin r-set {set}: {problem}")]
    InvalidRSet {
        set: super::RSetName,
        problem: super::RSetProblem,
    },

    /// A modal damping ratio that is not positive, for what needs every pole strictly
    /// stable (`needs`: the gramians of Eq. (39), the modal influence coefficients).
    #[error(
        "{needs} exist only for an asymptotically stable (damped) system, but the modal damping \
         ratio is ζ = {zeta}; add modal damping"
    )]
    NoModalDamping { zeta: f64, needs: &'static str },

    /// Balanced truncation of a body without viscous damping $D = \alpha K$.
    #[error(
        "balanced truncation needs viscous damping (Witteveen uses D = 1e-4·K); α = {alpha} was \
         given"
    )]
    NoViscousDamping { alpha: f64 },

    /// An elastic mode handed to balanced truncation whose eigenvalue is not positive: its
    /// gramian is not finite.
    #[error(
        "balanced truncation needs an asymptotically stable system: an elastic mode of \
         eigenvalue {eigenvalue:e} (rad/s)² has no finite gramian"
    )]
    NonPositiveElasticMode { eigenvalue: f64 },

    /// Elastic modes handed to balanced truncation that are linearly dependent.
    #[error("the elastic modes handed to balanced truncation are linearly dependent")]
    DependentElasticModes,

    /// A frequency band that contains none of the model's modes.
    #[error("the band {low_hz} to {high_hz} Hz contains no mode of the {what}")]
    EmptyBand {
        low_hz: f64,
        high_hz: f64,
        what: &'static str,
    },

    /// $K_{ii}$ is singular: the boundary DOF do not restrain every rigid-body motion.
    #[error(
        "K_ii is singular for boundary nodes {boundary_nodes:?}: {rank_deficiency} rigid-body \
         motion(s) of the interior stay unrestrained ({}); Craig-Bampton, Guyan and \
         mode condensation need at least {needed} properly chosen boundary DOF",
        super::free_motion::FreeMotions(free_motions)
    )]
    SingularInterior {
        boundary_nodes: Vec<usize>,
        rank_deficiency: usize,
        /// The unrestrained motions.
        free_motions: Vec<super::FreeMotion>,
        needed: usize,
    },

    /// More normal modes were requested than the interior eigenproblem has.
    #[error("{requested} normal modes requested but only {available} exist for this interior set")]
    TooManyModes { requested: usize, available: usize },

    /// A comparison was asked for no kept modes (an empty list, or a count of 0).
    #[error("kept-mode counts {counts:?}: give at least one count, each at least 1")]
    NoKeptModes { counts: Vec<usize> },

    /// A frequency cut-off that is not a non-negative number.
    #[error("invalid mode selection: frequency cut-off {hz} Hz must be a non-negative number")]
    InvalidCutoff { hz: f64 },

    /// A reduction's column is not the DOF it stands for (a Guyan column per master DOF, in
    /// order).
    #[error("column {column} of the reduction is not DOF {dof}")]
    ColumnNotAtDof { column: usize, dof: usize },

    /// Eitelberg's method needs every pole of A in the open left half-plane.
    #[error(
        "Eitelberg's method needs a stable A, but its largest real eigenvalue part is \
         {max_real_part} >= 0 (use the output-feedback trick A - B L C)", max_real_part = crate::report::readable(.max_real_part, 4))]
    UnstableSystem { max_real_part: f64 },

    /// Nodal-fixed axes whose plane is given by one axis twice.
    #[error("invalid nodal-fixed axes: a plane needs two different axes, got {axis}{axis}")]
    AxesPlaneRepeated { axis: &'static str },

    /// Nodal-fixed axes anchored twice at one node.
    #[error("invalid nodal-fixed axes: nodes i, j, k must differ, node {node} repeats")]
    AxesNodeRepeated { node: usize },

    /// Nodal-fixed axes along z of a planar body.
    #[error("invalid nodal-fixed axes: the {body} is planar: use the x or y axis")]
    AxesOutOfPlane { body: super::Name },

    /// A nodal-fixed anchor coordinate that is not a boundary (identity) column of Ψ.
    #[error(
        "nodal-fixed axes anchor node {node} {direction}, but that coordinate is not a boundary \
         column of the {method} basis (add node {node} to the boundary set)"
    )]
    AnchorNotInBasis {
        node: usize,
        direction: &'static str,
        method: &'static str,
    },
}
