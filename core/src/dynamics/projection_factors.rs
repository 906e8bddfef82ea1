//! Which factors the velocity correction of a projection solves with.

/// Which factors [`System::project`](super::System::project)'s velocity correction solves
/// with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ProjectionFactors {
    /// Its own: the system's $M$ and $C$ formed and factored at the projected positions.
    Fresh,
    /// Those the last evaluation with the workspace left: an explicit step's last stage,
    /// evaluated at the unprojected end of the step. Its $M$ and $C$ differ from the
    /// projected positions' by the position correction (the drift, $\lesssim 10^{-12}$);
    /// the residual is the projected positions' own, so the corrected velocities meet
    /// their constraints but for that difference times the correction, and the correction
    /// is still the least kinetic energy one, the same for every basis of one space.
    LastEvaluation,
    /// [`Self::LastEvaluation`], its velocity correction checked: where the corrected
    /// velocities miss their constraints by more than $10^{-12}$ of the velocities' size (a
    /// longer step's drift moved $M$ and $C$ further), a correction with
    /// [`Self::Fresh`] factors follows. Generalized-α's fixed steps take it.
    LastEvaluationChecked,
}
