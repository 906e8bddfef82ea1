//! Errors of the mesh layer (`fem`): bodies the generators cannot build as asked.

use thiserror::Error;

/// Errors of the mesh layer: a body the generators cannot build as asked.
#[derive(Debug, Error, serde::Serialize)]
pub enum MeshError {
    /// A refined slab with no brick along an axis.
    #[error(
        "a refined slab needs at least one brick along each axis (--refine NX,NY,NZ), got 0 along {axis}"
    )]
    NoBricks { axis: &'static str },

    /// A frame element of zero length, or whose `up` vector lies along it.
    #[error("frame element from {from:?} to {to:?}: {why}")]
    DegenerateElement {
        from: [f64; 3],
        to: [f64; 3],
        why: &'static str,
    },

    /// A frame element naming a section the frame does not define.
    #[error("an element of `{body}` uses section {section} of {sections} sections")]
    SectionOutOfRange {
        body: super::Name,
        section: usize,
        sections: usize,
    },

    /// A dual-spin assembly too small to be one.
    #[error(
        "a dual-spin assembly needs at least two booms, one element per boom and arm, two on the column"
    )]
    DualSpinTooSmall,

    /// A rigid mass added where it cannot be lumped: a node that is not a 6-DOF node of a
    /// lumped-mass body.
    #[error(
        "a rigid body's mass can be lumped only on a 6-DOF node of a lumped-mass body (node {node} of {nodes} in `{body}`)"
    )]
    NotALumpedFrameNode {
        body: super::Name,
        node: usize,
        nodes: usize,
    },

    /// Elements that do not fit the mesh they are applied to.
    #[error("{what} {value}, but the mesh has {available}")]
    ElementsMismatch {
        what: &'static str,
        value: usize,
        available: usize,
    },
}
