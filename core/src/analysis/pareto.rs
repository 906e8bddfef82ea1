//! Pareto fronts of (cost, error) points: which points no other point dominates.

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_of_hand_made_points() {
        // (cost, error): a staircase of three, one point dominated in both, one tied.
        let points = [
            (1.0, 0.5),
            (2.0, 0.2),
            (3.0, 0.1),
            (2.5, 0.3),
            (2.0, 0.2),
            (4.0, 0.1),
        ];
        assert_eq!(
            pareto_flags(&points),
            vec![true, true, true, false, true, false]
        );
        // One point, and none.
        assert_eq!(pareto_flags(&[(1.0, 1.0)]), vec![true]);
        assert!(pareto_flags(&[]).is_empty());
        // Equal error, lower cost wins; equal cost, lower error wins.
        assert_eq!(pareto_flags(&[(1.0, 0.1), (2.0, 0.1)]), vec![true, false]);
        assert_eq!(pareto_flags(&[(1.0, 0.1), (1.0, 0.2)]), vec![true, false]);
    }

    #[test]
    fn three_digits_rounds_to_three_significant_digits() {
        for (x, rounded) in [
            (0.123456, 0.123),
            (123456.0, 123000.0),
            (-0.0098765, -0.00988),
            (1.0, 1.0),
            (0.0, 0.0),
        ] {
            let r = three_digits(x);
            assert!(
                (r - rounded).abs() <= 1e-12 * rounded.abs().max(1e-300),
                "{x}: {r}"
            );
        }
        assert!(three_digits(f64::NAN).is_nan());
    }
}
