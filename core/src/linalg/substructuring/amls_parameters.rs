//! How AMLS reduces a body: its cut-off, its shift and its leaves' settings.

use super::LeafModesParameters;

/// How [`MultilevelSubstructures::new`](super::MultilevelSubstructures::new) reduces a body.
#[derive(Debug, Clone, PartialEq)]
pub struct AmlsParameters {
    /// Each node keeps its fixed-interface modes up to this frequency, Hz (infinite: all).
    pub cutoff_hz: f64,
    /// $\sigma$ of $K - \sigma M$, (rad/s)²: below the body's lowest eigenvalue (negative for a
    /// free body, see [`crate::linalg::sparse::negative_shift`]).
    pub shift: f64,
    /// How the leaves' modes are solved.
    pub leaves: LeafModesParameters,
}

impl Default for AmlsParameters {
    fn default() -> Self {
        Self {
            cutoff_hz: f64::INFINITY,
            shift: 0.0,
            leaves: LeafModesParameters::default(),
        }
    }
}
