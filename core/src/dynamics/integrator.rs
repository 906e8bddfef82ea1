//! Two integrators behind one interface, [`simulate`]: the explicit Dormand–Prince 5(4) with
//! adaptive steps (or fixed ones, to verify a critical step) and the implicit generalized-α
//! scheme with fixed steps. Both normalise Euler parameters and project the coordinates onto
//! the position and velocity constraints after every step.

use super::{
    DEFAULT_IMPLICIT_STEP, IntegrationScheme, IntegratorParameters, Simulation, State, System,
    dormand_prince, generalized_alpha,
};
use crate::{Progress, Result};

/// Integrates `sys` from `initial` over `[0, end_time]`.
///
/// The initial state is first projected onto the constraints. A non-finite state, one with a
/// component beyond `divergence_bound`, a step below `min_step` or more than `max_steps`
/// steps is `DynamicsError::Diverged` with the time it happened, never NaN output. With
/// `fixed_step` every step has that length (shortened only to land on output times) and is
/// accepted without error control. `progress` receives the time after each output and stops the
/// integration with [`Error::Cancelled`](crate::Error::Cancelled) once cancelled.
pub fn simulate(
    sys: &System,
    initial: &State,
    p: &IntegratorParameters,
    progress: &Progress,
) -> Result<Simulation> {
    sys.validate()?;
    progress.start_simulation(p.end_time)?;
    if let IntegrationScheme::GeneralizedAlpha { spectral_radius } = p.scheme {
        let step = p.fixed_step.unwrap_or(DEFAULT_IMPLICIT_STEP);
        return generalized_alpha::integrate(sys, initial, p, step, spectral_radius, progress);
    }
    dormand_prince::integrate(sys, initial, p, progress)
}
