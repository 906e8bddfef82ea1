//! Which r-set an error of MacNeal–Rubin's reduction names.

use std::fmt;

use super::Name;

/// Which r-set (Spanos–Tsuha Eq. 11) a [`super::ReductionError::InvalidRSet`] names.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub enum RSetName {
    /// The r-set of a statically determinate 3-2-1 support.
    Support321,
    /// The r-set a body (by its name) needs, whatever DOF it holds.
    OfBody(Name),
    /// An r-set of this many DOF.
    Count(usize),
    /// These DOF, by node (1-based) and component (`x`, `θz`).
    Dofs(Vec<(usize, &'static str)>),
}

impl fmt::Display for RSetName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Support321 => f.write_str("of a 3-2-1 support"),
            Self::OfBody(body) => write!(f, "of the {body}"),
            Self::Count(n) => write!(f, "of {n} DOF"),
            Self::Dofs(dofs) => {
                f.write_str("[")?;
                for (i, (node, component)) in dofs.iter().enumerate() {
                    let sep = if i == 0 { "" } else { ", " };
                    write!(f, "{sep}node {node} {component}")?;
                }
                f.write_str("]")
            }
        }
    }
}
