//! A rigid-body motion a boundary set leaves free, as [`super::ReductionError::SingularInterior`]
//! names it.

/// One rigid-body motion the boundary DOF do not restrain: the data, written out in words by
/// its `Display` (directions unit or as found, points in m, 3 decimals).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub enum FreeMotion {
    /// A translation along `along` (a planar body's has z = 0).
    Translation { along: [f64; 3], planar: bool },
    /// A planar body's rotation in its plane about the point `about`, m.
    PlanarRotation { about: [f64; 2] },
    /// A rotation about the unit `axis` through `point`, m; `node` when the axis passes
    /// through a boundary node (1-based, as users number nodes), `point` then being it.
    Rotation {
        axis: [f64; 3],
        point: [f64; 3],
        node: Option<usize>,
    },
}

impl std::fmt::Display for FreeMotion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Translation {
                along: [x, y, _],
                planar: true,
            } => write!(f, "translation along ({x:.3}, {y:.3})"),
            Self::Translation {
                along: [x, y, z], ..
            } => write!(f, "translation along ({x:.3}, {y:.3}, {z:.3})"),
            Self::PlanarRotation { about: [x, y] } => {
                write!(f, "rotation in the plane about ({x:.3}, {y:.3}) m")
            }
            Self::Rotation {
                axis: [a, b, c],
                point: [x, y, z],
                node,
            } => {
                write!(f, "rotation about ({a:.3}, {b:.3}, {c:.3}) through ")?;
                if let Some(node) = node {
                    write!(f, "node {node} at ")?;
                }
                write!(f, "({x:.3}, {y:.3}, {z:.3}) m")
            }
        }
    }
}

/// Motions joined by "; ", as the error's message lists them.
pub(super) struct FreeMotions<'a>(pub(super) &'a [FreeMotion]);

impl std::fmt::Display for FreeMotions<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, motion) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{motion}")?;
        }
        Ok(())
    }
}
