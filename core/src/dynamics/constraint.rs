//! Constraints between bodies: spherical joints (Eq. 2.22–2.24, 5.1–5.7) and prescribed nodal
//! motion (Eq. 7.7–7.9). The axis conditions of mean and principal axes (Table 4-2, §4.3) are
//! not listed here: [`super::System`] derives them from each body's [`super::AxisType`].

use nalgebra::Vector3;

use super::Motion;
use crate::fem::NodeIndex;

/// A point a joint holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Attachment {
    /// A fixed point in space, m.
    Ground(Vector3<f64>),
    /// A point of a rigid body, in its body frame (m).
    Point {
        /// Body index.
        body: usize,
        /// Position in the body frame, m.
        local: Vector3<f64>,
    },
    /// A node of a deformable body.
    Node {
        /// Body index.
        body: usize,
        /// The node.
        node: NodeIndex,
    },
}

/// One constraint of the system.
#[derive(Debug, Clone, PartialEq)]
pub enum Constraint {
    /// Two points coincide (3 rows).
    Spherical(Attachment, Attachment),
    /// One global coordinate of a node follows a motion from its initial position `x0` and
    /// velocity `v0` (1 row).
    PrescribedNode {
        /// Deformable body index.
        body: usize,
        /// The node.
        node: NodeIndex,
        /// Global axis 0, 1, 2 (x, y, z).
        axis: usize,
        /// The time function of the absolute coordinate.
        motion: Motion,
        /// Initial coordinate, m.
        x0: f64,
        /// Initial velocity, m/s.
        v0: f64,
    },
}

impl Constraint {
    /// Number of scalar rows.
    pub fn rows(&self) -> usize {
        match self {
            Constraint::Spherical(..) => 3,
            Constraint::PrescribedNode { .. } => 1,
        }
    }

    /// The points it holds (a prescribed node is its node).
    pub fn attachments(&self) -> impl Iterator<Item = Attachment> {
        let (a, b) = match *self {
            Constraint::Spherical(a, b) => (a, Some(b)),
            Constraint::PrescribedNode { body, node, .. } => {
                (Attachment::Node { body, node }, None)
            }
        };
        std::iter::once(a).chain(b)
    }
}
