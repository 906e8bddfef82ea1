//! One measured point of a simulation bench, and the settings its runs share.

use crate::{
    dynamics::{IntegrationScheme, IntegratorParameters},
    reduction::Method,
};

/// Simulated interval of the fixed-step run below the critical step, s (the run above it
/// takes the scene's whole interval: a weakly excited highest mode needs its steps to grow).
pub(crate) const STABILITY_RUN_S: f64 = 1.0;
/// Fixed steps of the stability runs as multiples of the predicted critical step: 10 % below,
/// and three times above, where Dormand–Prince grows 1.44× per step on the highest mode
/// (just above the limit the growth is too slow to see: 1.003 per step at 1.5×).
pub(crate) const BELOW_CRITICAL: f64 = 0.9;
pub(crate) const ABOVE_CRITICAL: f64 = 3.0;

/// Relative and absolute tolerances (m, m/s, rad) of the loose Dormand–Prince runs: the
/// error control then lets the step grow until stability bounds it, so a reduced model's
/// larger critical step pays (the full model's stiff modes hold its step near 2 ms).
pub const LOOSE_RTOL: f64 = 1e-3;
pub const LOOSE_ATOL: f64 = 1e-6;

/// One measured point.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchPoint {
    /// Method.
    pub method: Method,
    /// Kept normal modes (0 for NR and GR).
    pub modes: usize,
    /// Generalised coordinates of the deformable body.
    pub dofs: usize,
    /// Building the basis, s.
    pub offline_s: f64,
    /// Integration wall time per simulated second.
    pub online_s_per_sim_s: f64,
    /// Mean over ξ, η, ζ of node 8's relative RMS error against NR.
    pub rel_rms_error: f64,
    /// Accepted integration steps.
    pub steps: usize,
    /// Evaluations of the equations of motion in the integration.
    pub evaluations: usize,
    /// The online cost per evaluation (the median wall time over the evaluations, the
    /// steps' and projections' own work included), µs.
    pub us_per_evaluation: f64,
    /// The integrator.
    pub integrator: IntegrationScheme,
    /// Relative tolerance of an adaptive Dormand–Prince run (None: generalized-α).
    pub rtol: Option<f64>,
    /// Not dominated: no other point is at once faster online and more accurate.
    pub pareto: bool,
}

impl BenchPoint {
    /// The integrator and its setting: `dp5` (the scenes' tolerances), `dp5 rtol 1e-3` (the
    /// loose run) or `gen-alpha`.
    pub fn integrator_label(&self) -> String {
        match (self.integrator, self.rtol) {
            (IntegrationScheme::DormandPrince, Some(r))
                if r != IntegratorParameters::default().rtol =>
            {
                format!("dp5 rtol {r}", r = flexmodes_core::report::readable(r, 1))
            }
            (scheme, _) => scheme.id().into(),
        }
    }
}
