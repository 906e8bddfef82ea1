//! The residual check every sparse eigensolver's pairs pass before they are returned: the
//! relative residual $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$ of an elastic pair, and
//! $\|K\varphi - \lambda M\varphi\| / (\max|K|\,\|\varphi\|)$ of a zero-energy one (whose
//! $K\varphi$ is round-off). A pair passes below the tolerance, or below the floor the data
//! allows: computing $K\varphi$ alone costs $\varepsilon\,\||K||\varphi|\|$ of round-off (64 ε,
//! or four times the data's own precision when the matrices were written with fewer digits).

use faer::{Mat, MatRef};

use super::SparseSymmetric;

/// Multiple of $\varepsilon\,\||K||\varphi|\| / \|K\varphi\|$ (the round-off of the residual
/// itself) below which a pair passes whatever the tolerance.
const ROUND_OFF_FLOOR: f64 = 64.0;

/// The residuals of a set of pairs and how many pass.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PairResiduals {
    /// Each pair's residual (infinite where it is not a number).
    pub residuals: Vec<f64>,
    /// Whether each pair passes (its residual at most the tolerance or its round-off floor).
    pub passed: Vec<bool>,
    /// The worst residual (NaN when one is NaN).
    pub max: f64,
}

impl PairResiduals {
    /// How many pairs pass.
    pub fn converged(&self) -> usize {
        self.passed.iter().filter(|&&p| p).count()
    }
}

/// What a pair's residual is checked to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ResidualCheck {
    /// The largest residual that passes (above the round-off floor).
    pub tolerance: f64,
    /// The relative precision $K$ and $M$ are known to (the digits they were written with).
    pub data_precision: f64,
}

/// The residuals of the pairs (`values`, the columns of `vectors`) of $(K, M)$ from their
/// images `kv` $= KV$ and `mv` $= MV$; the first `zero_energy` pairs are measured against
/// $\max|K|\,\|\varphi\|$.
pub(crate) fn pair_residuals(
    k: &SparseSymmetric,
    values: &[f64],
    vectors: MatRef<'_, f64>,
    (kv, mv): (MatRef<'_, f64>, MatRef<'_, f64>),
    zero_energy: usize,
    check: ResidualCheck,
) -> PairResiduals {
    let ResidualCheck {
        tolerance,
        data_precision,
    } = check;
    let n = vectors.nrows();
    let count = values.len();
    assert_eq!(
        (vectors.ncols(), kv.ncols(), mv.ncols()),
        (count, count, count),
        "one vector and its images per value"
    );
    let k_scale = k.max_abs();
    let mut residuals = Vec::with_capacity(count);
    let mut denominators = Vec::with_capacity(count);
    for (c, &lambda) in values.iter().enumerate() {
        let r = Mat::from_fn(n, 1, |i, _| kv[(i, c)] - lambda * mv[(i, c)]);
        let denom = if c < zero_energy {
            k_scale * vectors.col(c).norm_l2()
        } else {
            kv.col(c).norm_l2()
        };
        residuals.push(r.norm_l2() / denom.max(f64::MIN_POSITIVE));
        denominators.push(denom);
    }
    // The round-off floor, needed only where the tolerance is not met, and only where it could
    // be met: ‖|K||φ|‖ ≤ ‖K‖₁‖φ‖ (K symmetric), so a residual above the floor that bound gives
    // fails without the sparse product |K||φ|.
    let coefficient = (ROUND_OFF_FLOOR * f64::EPSILON).max(4.0 * data_precision);
    let norm1 = column_sum_norm(k);
    let mut passed: Vec<bool> = residuals.iter().map(|&r| r <= tolerance).collect();
    let near: Vec<usize> = (0..count)
        .filter(|&c| {
            // (1 % above it: the bound's own round-off never decides a pair.)
            let bound = 1.01 * coefficient * norm1 * vectors.col(c).norm_l2()
                / denominators[c].max(f64::MIN_POSITIVE);
            !passed[c] && residuals[c] <= bound
        })
        .collect();
    if !near.is_empty() {
        let picked = Mat::from_fn(n, near.len(), |i, j| vectors[(i, near[j])]);
        let kv_abs = k.abs_mul(picked.as_ref());
        for (j, &c) in near.iter().enumerate() {
            let floor =
                coefficient * kv_abs.col(j).norm_l2() / denominators[c].max(f64::MIN_POSITIVE);
            passed[c] = residuals[c] <= tolerance.max(floor);
        }
    }
    let max = residuals.iter().fold(0.0f64, |a, &r| a.max(r));
    for r in &mut residuals {
        if r.is_nan() {
            *r = f64::INFINITY;
        }
    }
    PairResiduals {
        residuals,
        passed,
        max,
    }
}

/// $\|A\|_1$, the largest absolute column sum.
fn column_sum_norm(a: &SparseSymmetric) -> f64 {
    let f = a.as_faer();
    (0..f.ncols())
        .map(|j| f.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}
