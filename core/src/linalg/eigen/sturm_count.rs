//! The Sturm sequence check of a partial eigensolution, as Nastran's and ANSYS' Lanczos
//! solvers make it: by Sylvester's law of inertia the number of negative pivots of an
//! $LDL^T$ factor of $K - \sigma' M$ is the number of eigenvalues of the pencil below
//! $\sigma'$. With $\sigma'$ just above the highest eigenvalue accepted, a count larger than the
//! number of pairs found says that the solver skipped some.
//!
//! The Ritz values $\tilde\lambda_i$ of any subspace lie above the true eigenvalues
//! ($\tilde\lambda_i \ge \lambda_i$, Cauchy's interlacing), so the count of true eigenvalues
//! below $\sigma'$ is at least that of Ritz values below it, and equal when nothing was missed.
//! $\sigma'$ is placed in the gap above the highest accepted eigenvalue (half way to the next
//! Ritz value, at most 1 % and at least $10^{-5}$ of the eigenvalue above it) so a pair whose
//! value is known to its residual cannot straddle it.
//!
//! The count is made without storing the factor ([`crate::linalg::sparse::multifrontal_inertia`]: a front
//! at a time, as many values as a few of the largest fronts) when the elimination's growth
//! keeps its estimated backward error within `STURM_BACKWARD_ERROR`; otherwise by the stored
//! supernodal $LDL^T$ factor, whose backward error is measured by a solve.

use crate::error::LinalgError;
use crate::linalg::Result;
use crate::linalg::sparse::{
    IndefiniteFactor, MassMatrix, SparseSymmetric, SymbolicFactor, multifrontal_inertia,
};

/// Shifts tried before the check gives up (a zero pivot or an inaccurate factor moves
/// $\sigma'$ further into the gap).
const SHIFT_TRIES: usize = 3;

/// Largest backward error $\|b - A\hat x\| / \|\,|A||\hat x|\,\|$ of a solve with the
/// $LDL^T$ factor whose inertia is counted ($10^6\varepsilon$).
const STURM_BACKWARD_ERROR: f64 = crate::linalg::sparse::TRUSTED_BACKWARD_ERROR;

/// The outcome of a Sturm sequence check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SturmCount {
    /// The shift $\sigma'$, (rad/s)².
    pub shift: f64,
    /// Eigenvalues of the pencil below $\sigma'$ (negative pivots of $K - \sigma' M$).
    pub below: usize,
    /// Pairs the solver computed below $\sigma'$ (accepted pairs and Ritz values).
    pub found: usize,
}

impl SturmCount {
    /// Eigenvalues below the shift that the solver did not find.
    pub fn missed(&self) -> usize {
        self.below.saturating_sub(self.found)
    }
}

/// Counts the eigenvalues of $K\varphi = \lambda M\varphi$ below a shift just above
/// `accepted.last()` and compares with the pairs found: `accepted` are the accepted eigenvalues
/// (ascending), `ritz_above` the Ritz values the solver holds above them (ascending, upper
/// bounds of the next eigenvalues). `symbolic` analyses the pattern of $K - \sigma M$.
pub fn sturm_count(
    k: &SparseSymmetric,
    m: &MassMatrix,
    symbolic: &SymbolicFactor,
    accepted: &[f64],
    ritz_above: &[f64],
) -> Result<SturmCount> {
    let Some(&top) = accepted.last() else {
        return Ok(SturmCount {
            shift: 0.0,
            below: 0,
            found: 0,
        });
    };
    let scale = top.abs().max(f64::MIN_POSITIVE);
    let next = ritz_above.first().copied().unwrap_or(f64::INFINITY);
    let mut offset = (0.5 * (next - top)).clamp(1e-5 * scale, 1e-2 * scale);
    let mut last_error = None;
    let mut shift = top + offset;
    for _ in 0..SHIFT_TRIES {
        shift = top + offset;
        let found = accepted.len() + ritz_above.iter().filter(|&&r| r < shift).count();
        match inertia_at(k, m, symbolic, shift) {
            Ok(below) => {
                return Ok(SturmCount {
                    shift,
                    below,
                    found,
                });
            }
            Err(e) => last_error = Some(e),
        }
        offset *= 3.0;
    }
    Err(LinalgError::SturmCheckFailed {
        shift,
        tries: SHIFT_TRIES,
        last: last_error.map(Box::new),
    })
}

/// The number of eigenvalues of $K\varphi = \lambda M\varphi$ below `shift`: the negative
/// pivots of an $LDL^T$ factor of $K - \sigma M$ (Sylvester's law of inertia), first without
/// keeping the factor ([`multifrontal_inertia`]: fronts forgotten once eliminated), and, when
/// that elimination grew past its bound, by the stored factor, whose backward error is
/// measured instead of estimated ([`LinalgError::SturmFactorInaccurate`] when it is too
/// large). `symbolic` analyses the pattern of $K - \sigma M$.
pub fn inertia_at(
    k: &SparseSymmetric,
    m: &MassMatrix,
    symbolic: &SymbolicFactor,
    shift: f64,
) -> Result<usize> {
    let shifted = k.shifted(m, shift);
    if let Some(inertia) = multifrontal_inertia(&shifted, symbolic)?
        && inertia.trusted()
    {
        return Ok(inertia.negative);
    }
    let factor = IndefiniteFactor::factor(shifted, symbolic, "Sturm shift K - σ'M")?;
    // An unpivoted LDLᵀ that grew (a small pivot) may have the wrong inertia: its backward
    // error must stay near round-off.
    let probe = faer::Mat::from_fn(k.dim(), 1, |i, _| 1.0 + (i % 7) as f64);
    let backward = factor.backward_error(probe.as_ref());
    if backward <= STURM_BACKWARD_ERROR {
        Ok(factor.negative_pivots())
    } else {
        Err(LinalgError::SturmFactorInaccurate {
            shift,
            backward,
            bound: STURM_BACKWARD_ERROR,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of springs (tridiagonal K) with a consistent-like tridiagonal M: eigenvalues
    /// known from the dense solve.
    fn chain(n: usize) -> (SparseSymmetric, MassMatrix, Vec<f64>) {
        let mut k = Vec::new();
        let mut m = Vec::new();
        for i in 0..n {
            k.push((i, i, 2.0 + i as f64 * 0.01));
            m.push((i, i, 4.0));
            if i + 1 < n {
                k.extend([(i, i + 1, -1.0), (i + 1, i, -1.0)]);
                m.extend([(i, i + 1, 1.0), (i + 1, i, 1.0)]);
            }
        }
        let k = SparseSymmetric::from_triplets(n, &k);
        let m = SparseSymmetric::from_triplets(n, &m);
        let all = crate::linalg::dense::generalized_eigen(
            k.to_dense().as_ref(),
            m.to_dense().as_ref(),
            "chain",
        )
        .unwrap();
        (k, MassMatrix::Consistent(m), all.values)
    }

    #[test]
    fn counts_what_a_solver_skipped() {
        for n in [30, 200] {
            let (k, m, values) = chain(n);
            let symbolic = SymbolicFactor::analyse(k.shifted(&m, 0.1).as_faer()).unwrap();
            for wanted in [1, 5, 12] {
                let found = &values[..wanted];
                let count = sturm_count(&k, &m, &symbolic, found, &values[wanted..]).unwrap();
                assert_eq!(
                    (count.below, count.missed()),
                    (wanted, 0),
                    "n {n}, {wanted}"
                );
                // The same set with its second-lowest pair left out: one missed.
                let mut gap: Vec<f64> = found.to_vec();
                if wanted > 1 {
                    gap.remove(1);
                    let count = sturm_count(&k, &m, &symbolic, &gap, &values[wanted..]).unwrap();
                    assert_eq!(count.missed(), 1, "n {n}, {wanted}: {count:?}");
                }
            }
        }
    }
}
