//! Errors of the dynamics layer: a body that cannot sit on a floating or driven frame, settings
//! an integrator cannot run with, and where and when an integration stopped.

use thiserror::Error;

use super::DivergenceCause;

/// Errors of the dynamics layer: a body that cannot sit on a floating or driven frame,
/// settings an integrator cannot run with, and where and when an integration stopped.
#[derive(Debug, Error, serde::Serialize)]
pub enum DynamicsError {
    /// A time integration that could not continue.
    #[error("the integration diverged at t = {time:.4} s: {cause}")]
    Diverged { time: f64, cause: DivergenceCause },

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

    /// A time step that is not a positive number of seconds.
    #[error("the time step must be a positive number of seconds, not {step}")]
    InvalidStep { step: f64 },

    /// A spectral radius at infinite frequency outside [0, 1] (generalized-α).
    #[error("the spectral radius ρ∞ must lie in [0, 1], not {rho}")]
    InvalidSpectralRadius { rho: f64 },

    /// A setting of a driven run that must be positive (the ramp time, s).
    #[error("the {setting} must be positive, not {value}")]
    NotPositive { setting: &'static str, value: f64 },

    /// A direction given as the zero vector (the spin axis, the shaking direction).
    #[error("the {setting} is the zero vector")]
    ZeroDirection { setting: &'static str },

    /// A body on a floating or driven frame needs x, y, z translations per node.
    #[error(
        "the body `{body}` on a {frame} frame needs x, y, z translations per node and no rotations"
    )]
    NotSolid {
        body: super::Name,
        frame: &'static str,
    },

    /// A floating-frame body needs a lumped mass, the same in x, y and z at each node.
    #[error(
        "the floating-frame body `{body}` needs a lumped (diagonal, isotropic per node) mass matrix"
    )]
    MassNotLumped { body: super::Name },

    /// A driven body's mass is not $M_s \otimes I_3$: node `node` (1-based) differs by
    /// direction, or couples to `other` unequally across directions.
    #[error(
        "the body `{body}`: the mass at node {node}{} is not the same in x, y and z; the driven \
         frame's equations need M = Mₛ ⊗ I₃",
        other.map(|o| format!(" coupled to node {o}")).unwrap_or_default()
    )]
    MassNotIsotropic {
        body: super::Name,
        node: usize,
        other: Option<usize>,
    },

    /// A DOF held twice: in two pinned rings, or in a pinned ring and the drive's.
    #[error(
        "DOF {dof} (1-based) of the pinned ring `{ring}` is also in the drive's ring or in another pinned ring"
    )]
    RingsOverlap { ring: super::Name, dof: usize },

    /// A basis column that moves a DOF the driven frame holds.
    #[error(
        "column {column} of the basis moves DOF {dof} (1-based) by {motion}, which the frame \
         holds (the drive's ring does not move; a pinned ring only turns about its master)", motion = crate::report::readable(.motion, 4))]
    BasisMovesHeldDof {
        column: usize,
        dof: usize,
        motion: f64,
    },

    /// The explicit scheme was asked to run the full (sparse) body.
    #[error(
        "the explicit scheme runs reduced bodies only: the full body's consistent mass would \
         need a sparse solve per stage at a step below the mesh's highest frequency"
    )]
    ExplicitFullBody,

    /// An operation a driven body of another kind does (a projection of a reduced body; an
    /// effective matrix without stiffness): a misuse inside flexmodes, said rather than
    /// panicking.
    #[error("driven body: {what}")]
    Misuse { what: &'static str },

    /// A constraint or load of a system names a node its body does not have, or a point of a
    /// body that is not rigid.
    #[error("the system's {what} names {place}")]
    BadAttachment {
        what: &'static str,
        place: super::AttachmentProblem,
    },

    /// The histories of a driven body are seen from the drive's frame or mean axes.
    #[error(
        "a driven body's histories are seen from the drive's frame (nodal_fixed) or from mean axes; {axes} axes are not offered"
    )]
    AxesNotOffered { axes: &'static str },

    /// An output that names no node set (or `node:N` without a number).
    #[error(
        "no node set `{name}` to output (the body has: {}; or node:N with a 1-based node number)",
        super::name::joined(known)
    )]
    UnknownOutput {
        name: super::Excerpt,
        known: Vec<super::Name>,
    },

    /// Driven studies to be joined that are not runs of one body under one drive: they differ
    /// in `what` (their sample times, outputs, drive or its motion).
    #[error("the driven studies to join differ in their {what}: they are not runs of one drive")]
    StudiesDiffer { what: &'static str },

    /// A body's preloaded stiffness was written for another spin than the driven frame's:
    /// another axis (the angle between them), an axis through other points (the frame's
    /// origin's distance from the preload's axis, the body's length unit), or other held DOF
    /// (how many the preload held, how many the drive's ring clamps, how many of the ring's
    /// it held).
    #[error(
        "the body's [preload] was written for another spin: {}",
        match (angle_rad, offset, held) {
            (Some(a), _, _) => format!("its axis is {a} rad from the spin axis", a = crate::report::readable(a, 3)),
            (_, Some(d), _) => format!(
                "its axis passes {d} from the frame's origin (the --axis-point given, or the \
                 drive's master): give a point of the preload's axis with --axis-point X,Y,Z",
                d = crate::report::readable(d, 4)
            ),
            (_, _, Some((h, r, both))) => format!(
                "its static step held {h} DOF, the drive's ring clamps {r} ({both} of them in                  both): hold the drive's ring alone in CalculiX's *BOUNDARY"
            ),
            _ => "it does not match".to_string(),
        }
    )]
    PreloadMismatch {
        angle_rad: Option<f64>,
        offset: Option<f64>,
        held: Option<(usize, usize, usize)>,
    },

    /// The drive's ring is not coaxial with the axis the body's preloaded stiffness was spun
    /// about (the deck's CENTRIF line): the centre of the circle fitted to the ring lies
    /// `distance` from that axis (through `point`), beyond the ring's own geometric
    /// tolerance (the body's length unit).
    #[error(
        "the drive `{drive}`'s ring is centred {distance} from the axis its [preload] was spun \
         about (through {x}, {y}, {z}; the ring's own tolerance is {tolerance}): the frame \
         would not turn about the preload's axis. Give the spin's axis point with \
         --axis-point X,Y,Z, or turn the stiffening off (--stiffening off)",
        distance = crate::report::readable(*distance, 4),
        tolerance = crate::report::readable(*tolerance, 3),
        x = crate::report::readable(point[0], 6),
        y = crate::report::readable(point[1], 6),
        z = crate::report::readable(point[2], 6)
    )]
    DriveOffPreloadAxis {
        drive: String,
        distance: f64,
        tolerance: f64,
        point: [f64; 3],
    },

    /// A geometric stiffness of a unit frame load (`case`: rate², angular acceleration,
    /// g_x, …) that is not square of the body's size or not symmetric (`defect`: largest
    /// |K − Kᵀ| over largest |K|); `case` none: no case given at all.
    #[error(
        "{}",
        match case {
            Some(c) => format!(
                "the geometric stiffness of the {c} case is {rows} × {cols} with a symmetry \
                 defect {defect}: it must be {dim} × {dim} and symmetric"
            , defect = crate::report::readable(defect, 2)),
            None => "a body's stiffening needs at least one geometric stiffness".to_string(),
        }
    )]
    GeometricStiffnessInvalid {
        case: Option<&'static str>,
        rows: usize,
        cols: usize,
        dim: usize,
        defect: f64,
    },

    /// A model too large for a dense route that forms its operators column by column.
    #[error("{what} takes models of at most {limit} coordinates; this one has {coordinates}")]
    DenseRouteTooLarge {
        what: &'static str,
        coordinates: usize,
        limit: usize,
    },

    /// The geometric stiffness of a free frame's loads cannot be formed for this body: its
    /// rigid motions are not known (mean or principal axes need them for inertia relief),
    /// or the three nodes that would hold it statically determinately lie on a line.
    #[error("the dynamic stiffening of `{body}` cannot be formed: {why}")]
    StiffeningSupport {
        body: super::Name,
        why: &'static str,
    },
}
