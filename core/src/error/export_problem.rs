//! Why a reduced body cannot be carried into another code as it is
//! ([`super::ReductionError::NotExportable`]).

/// What stops an export, with its data; `ring`: the frame's rigid interface, by name.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum ExportProblem {
    /// The body's nodes carry other DOF than the three translations.
    #[error(
        "Exudyn's reduced-order FFRF object takes three translations per node; the body's \
         nodes carry {}",
        carried.join(" ")
    )]
    NotTranslations { carried: Vec<&'static str> },

    /// The body file gives no coordinates, which the frame and the mode shapes need.
    #[error("the body file gives no node coordinates")]
    NoCoordinates,

    /// No rigid interface to attach the floating frame to.
    #[error(
        "the floating frame is attached to a rigid interface: give one as `rbe2:SET` (the first \
         is the frame)"
    )]
    NoFrameInterface,

    /// The basis moves a node of the frame's ring (m, per unit modal coordinate).
    #[error(
        "the kept basis moves node {node} of the frame's ring `{ring}` by {moved} (largest \
         entry {largest}): the frame would not be attached to it", moved = crate::report::readable(.moved, 3), largest = crate::report::readable(.largest, 3))]
    FrameRingMoves {
        node: usize,
        ring: super::Name,
        moved: f64,
        largest: f64,
    },

    /// The basis lacks the ring's six constraint modes.
    #[error(
        "the basis has no six constraint modes of `{ring}`: {other} of its {columns} columns \
         are other"
    )]
    NoConstraintModes {
        ring: super::Name,
        other: usize,
        columns: usize,
    },

    /// Without the ring's constraint modes no column is left.
    #[error(
        "with `{ring}` as the frame nothing elastic is left: keep modes (--modes) or another \
         interface"
    )]
    NothingElastic { ring: super::Name },

    /// The basis without the ring's constraint modes still has zero-energy modes.
    #[error(
        "the basis without `{ring}`'s constraint modes keeps {zero} zero-energy mode(s) (lowest \
         {lowest_hz} Hz): the frame's interface alone does not hold the body", lowest_hz = crate::report::readable(.lowest_hz, 4))]
    ZeroEnergyLeft {
        ring: super::Name,
        zero: usize,
        lowest_hz: f64,
    },
}
