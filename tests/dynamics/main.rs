//! Time integrations of the floating-frame equations (§7.2, §5.3.3), in their own binary
//! because they are the slow tests: accuracy ordering of the methods, invariants of the
//! integration, the symmetry study, fixed-step stability and errors.

mod generalized_alpha;
mod integration_limits;
mod integrations;
mod simulation_runs;
