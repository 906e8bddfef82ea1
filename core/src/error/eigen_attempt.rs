//! One failed route of the free-body eigensolver, as its error reports it.

/// A route the free-free eigensolver tried and how far it got.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct EigenAttempt {
    /// The route.
    pub route: EigenRoute,
    /// Pairs that passed their residual check.
    pub converged: usize,
    /// Pairs wanted.
    pub wanted: usize,
    /// Worst relative residual of the pairs as they stood (NaN where the Sturm count, not a
    /// residual, refused them).
    pub residual: f64,
    /// Eigenvalues the Sturm count found below the set that the solver did not return, when
    /// that is why the route failed.
    pub missed: Option<usize>,
}

/// The routes of the free-free eigensolver, in the order it tries them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum EigenRoute {
    /// Lanczos at a small negative shift, (rad/s)², with the body's refined null space
    /// (`null_vectors` of them) deflated.
    SmallShift { shift: f64, null_vectors: usize },
    /// Lanczos at a shift set from the lowest elastic eigenvalue's estimate, (rad/s)², with a
    /// larger block and more restarts.
    SpectrumShift {
        shift: f64,
        block: usize,
        restarts: usize,
    },
    /// The complete dense eigenproblem (small bodies only).
    CompleteDense,
}

impl std::fmt::Display for EigenRoute {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::SmallShift {
                shift,
                null_vectors,
            } => write!(
                f,
                "shift {shift} (rad/s)², {null_vectors} null vectors deflated",
                shift = crate::report::readable(shift, 3)
            ),
            Self::SpectrumShift {
                shift,
                block,
                restarts,
            } => write!(
                f,
                "shift {shift} (rad/s)² from the lowest elastic estimate, block {block}, \
                 {restarts} restarts",
                shift = crate::report::readable(shift, 3)
            ),
            Self::CompleteDense => f.write_str("complete dense solve"),
        }
    }
}

impl std::fmt::Display for EigenAttempt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.route)?;
        if let Some(missed) = self.missed {
            write!(f, " (Sturm count: {missed} missed)")?;
        }
        write!(
            f,
            ": {} of {} pairs, worst residual {}",
            self.converged,
            self.wanted,
            crate::report::readable(self.residual, 2)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_attempt_reads_its_route_and_how_far_it_got() {
        let missed = EigenAttempt {
            route: EigenRoute::SmallShift {
                shift: -7.5e3,
                null_vectors: 6,
            },
            converged: 8,
            wanted: 10,
            residual: f64::NAN,
            missed: Some(2),
        };
        assert_eq!(
            missed.to_string(),
            "shift -7500 (rad/s)², 6 null vectors deflated (Sturm count: 2 missed): 8 of 10 \
             pairs, worst residual NaN"
        );
        let stalled = EigenAttempt {
            route: EigenRoute::SpectrumShift {
                shift: -2.0e5,
                block: 8,
                restarts: 150,
            },
            converged: 3,
            wanted: 10,
            residual: 2.5e-6,
            missed: None,
        };
        assert_eq!(
            stalled.to_string(),
            "shift -200000 (rad/s)² from the lowest elastic estimate, block 8, 150 restarts: 3 \
             of 10 pairs, worst residual 2.5e-6"
        );
    }
}
