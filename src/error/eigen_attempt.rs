//! One failed route of the free-body eigensolver, as its error reports it.

/// A route the free-free eigensolver tried and how far it got.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct EigenAttempt {
    /// What the route was ("shift -7.5e3, null space refined", ...).
    pub route: String,
    /// Pairs that passed their residual check.
    pub converged: usize,
    /// Pairs wanted.
    pub wanted: usize,
    /// Worst relative residual of the pairs as they stood (NaN where the Sturm count, not a
    /// residual, refused them).
    pub residual: f64,
}

impl std::fmt::Display for EigenAttempt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} of {} pairs, worst residual {:.1e}",
            self.route, self.converged, self.wanted, self.residual
        )
    }
}
