//! Axis conditions of a floating frame (chapter 4).

use crate::{error::UnknownId, reduction::NodalFixedAxes};

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
        self.kind().id()
    }

    /// Which kind of axes, without the nodal-fixed nodes.
    pub fn kind(&self) -> AxisKind {
        match self {
            AxisType::NodalFixed(_) => AxisKind::NodalFixed,
            AxisType::Mean => AxisKind::Mean,
            AxisType::Principal => AxisKind::Principal,
        }
    }
}

/// The kinds of floating frame a scene offers and `--axes` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisKind {
    /// Nodal-fixed axes (§4.1).
    NodalFixed,
    /// Mean axes (§4.2).
    Mean,
    /// Principal axes (§4.3).
    Principal,
}

impl AxisKind {
    /// Every kind, in the thesis' order.
    pub const ALL: [AxisKind; 3] = [AxisKind::NodalFixed, AxisKind::Mean, AxisKind::Principal];

    /// The stable id (`nodal_fixed`, `mean`, `principal`).
    pub fn id(self) -> &'static str {
        match self {
            AxisKind::NodalFixed => "nodal_fixed",
            AxisKind::Mean => "mean",
            AxisKind::Principal => "principal",
        }
    }
}

impl std::fmt::Display for AxisKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl std::str::FromStr for AxisKind {
    type Err = UnknownId;

    fn from_str(s: &str) -> Result<Self, UnknownId> {
        let s = s.trim();
        AxisKind::ALL
            .into_iter()
            .find(|k| k.id() == s)
            .ok_or_else(|| UnknownId::new("axis type", s, &AxisKind::ALL.map(AxisKind::id)))
    }
}
