//! What an integration returns: the samples at every output time and its cost.

use super::{State, System};

/// One output sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// The state.
    pub state: State,
    /// Total energy, J.
    pub energy: f64,
    /// Largest position-level constraint violation.
    pub position_violation: f64,
    /// Largest velocity-level constraint violation.
    pub velocity_violation: f64,
}

/// The result of a time integration.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// Samples at every output time, starting at t = 0.
    pub samples: Vec<Sample>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (explicit scheme); rebuilt Newton iteration matrices (implicit one).
    pub rejected: usize,
    /// Newton iterations (implicit scheme; 0 for the explicit one).
    pub newton_iterations: usize,
    /// Evaluations of the equations of motion ([`System::accelerations`](super::System::accelerations)):
    /// every stage, Newton iteration and finite difference of the integration.
    pub evaluations: usize,
    /// Wall-clock time of the integration, s.
    pub wall_time_s: f64,
}

impl Simulation {
    /// Bytes the samples hold on the heap: each sample's positions and velocities and its
    /// own size.
    pub fn heap_bytes(&self) -> usize {
        self.samples
            .iter()
            .map(|s| {
                std::mem::size_of::<Sample>()
                    + std::mem::size_of::<f64>() * (s.state.q.len() + s.state.v.len())
            })
            .sum()
    }
}

/// The sample of `state` at time `t`: energy and constraint violations evaluated.
pub(super) fn sample(sys: &System, t: f64, state: &State) -> Sample {
    let (p, v) = sys.violation(t, state);
    Sample {
        t,
        state: state.clone(),
        energy: sys.energy(state),
        position_violation: p,
        velocity_violation: v,
    }
}
