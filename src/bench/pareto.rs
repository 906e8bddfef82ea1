//! Pareto fronts of (cost, error) points: which points no other point dominates.

use super::BenchPoint;

/// For each (cost, error) pair: whether no other pair dominates it (lower or equal in both
/// and lower in one).
pub fn pareto_flags(cost_error: &[(f64, f64)]) -> Vec<bool> {
    cost_error
        .iter()
        .map(|&(c, e)| {
            !cost_error
                .iter()
                .any(|&(c2, e2)| c2 <= c && e2 <= e && (c2 < c || e2 < e))
        })
        .collect()
}

/// `x` rounded to three significant digits: errors equal to three digits count as equal on
/// a Pareto front (CB and MC span one space and differ by round-off only, which must not
/// decide which of the two is on the front).
pub fn three_digits(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let f = 10f64.powi(2 - x.abs().log10().floor() as i32);
    (x * f).round() / f
}

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
