//! Axis conditions of a floating frame (chapter 4).

use crate::reduction::NodalFixedAxes;

/// How a deformable body's floating frame is tied to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AxisType {
    /// Six nodal deflections held at zero by removing their columns from Ψ (§4.1, §5.4.1).
    NodalFixed(NodalFixedAxes),
    /// Mean axes by Lagrange multipliers (§4.2, Eq. 5.19, Table 4-2): origin at the mass
    /// centre, no deformation momentum or angular momentum relative to the frame.
    Mean,
    /// Principal axes (§4.3): products of inertia zero plus the translational mean-axis
    /// conditions.
    Principal,
}

impl AxisType {
    /// The stable id (`nodal_fixed`, `mean`, `principal`).
    pub fn id(&self) -> &'static str {
        match self {
            AxisType::NodalFixed(_) => "nodal_fixed",
            AxisType::Mean => "mean",
            AxisType::Principal => "principal",
        }
    }
}
