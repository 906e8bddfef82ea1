//! The simulation bench's Pareto front ([`crate::analysis::pareto_flags`] on its points).

use super::BenchPoint;
use crate::analysis::{pareto_flags, three_digits};

/// Marks the points no other point dominates in (online cost, error to three digits).
pub fn mark_pareto(points: &mut [BenchPoint]) {
    let cost_error: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.online_s_per_sim_s, three_digits(p.rel_rms_error)))
        .collect();
    for (p, flag) in points.iter_mut().zip(pareto_flags(&cost_error)) {
        p.pareto = flag;
    }
}
