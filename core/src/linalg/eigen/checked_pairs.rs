//! The pairs a Lanczos step's Ritz vectors give, checked on the original pencil $(K, M)$: their
//! residuals, after one step of inverse iteration where they do not converge at once (Ericsson
//! and Ruhe's purification).

use faer::Mat;

use super::PartialEigenParameters;
use crate::error::LinalgError;
use crate::linalg::Result;
use crate::linalg::dense::{
    GeneralizedEigen, ZERO_ENERGY_RATIO, eigenvalue_scale, fix_sign, generalized_eigen,
};
use crate::linalg::sparse::{
    MassMatrix, ResidualCheck, SparseSymmetric, SymmetricFactor, pair_residuals,
};

/// Worst residual of a converged set below which [`refined_pairs`] spares the extra solve.
const REFINEMENT_NOT_NEEDED: f64 = 1e-12;

/// $\lambda = \sigma + 1/\theta$ of the Ritz values after the first `wanted`, ascending.
pub(super) fn ritz_values_above(sigma: f64, theta: &[f64], wanted: usize) -> Vec<f64> {
    let mut above: Vec<f64> = theta
        .iter()
        .skip(wanted)
        .filter(|t| **t > 0.0)
        .map(|t| sigma + 1.0 / t)
        .collect();
    above.sort_by(f64::total_cmp);
    above
}

/// The wanted pairs checked on the original pencil, after one step of inverse iteration on
/// the Ritz vectors that are not known null vectors: $X = A U$, then Rayleigh–Ritz of
/// $(K, M)$ on the span of $X$. A Ritz vector $u$ carries the solves' round-off in every
/// direction, and $K$ multiplies the part along its stiffest modes by $\lambda_{max}$; one
/// application of $A$ damps the part along an eigenvector of eigenvalue $\mu$ by
/// $(\lambda - \sigma)/(\mu - \sigma)$ (Ericsson and Ruhe's purification). The better of
/// the two sets (the one with more converged pairs, then the smaller worst residual) is kept.
pub(super) fn refined_pairs(
    pencil: &ShiftedPencil<'_>,
    factor: &SymmetricFactor,
    pairs: &RitzPairs<'_>,
) -> Result<CheckedPairs> {
    let ShiftedPencil { k, m, sigma, .. } = *pencil;
    let (theta, ritz) = (pairs.theta, pairs.ritz);
    let (wanted, known) = (pairs.wanted, pairs.known);
    let plain = checked_pairs(pencil, pairs)?;
    let free = wanted - known;
    if free == 0 || plain.converged == wanted && plain.max_residual <= REFINEMENT_NOT_NEEDED {
        return Ok(plain);
    }
    let u = ritz.subcols(known, free);
    let mut x = factor.solve(m.mul(u).as_ref());
    if known > 0 {
        // Keep X M-orthogonal to the known null vectors, as the iteration kept U.
        let null = ritz.subcols(0, known);
        for _ in 0..2 {
            let coeffs = m.mul(null).transpose() * &x;
            x -= null * &coeffs;
        }
    }
    let kx = k.mul(x.as_ref());
    let mx = m.mul(x.as_ref());
    let kr = x.transpose() * &kx;
    let mr = x.transpose() * &mx;
    let sym = |a: &Mat<f64>| Mat::from_fn(free, free, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let Ok(small) = generalized_eigen(sym(&kr).as_ref(), sym(&mr).as_ref(), "refined Ritz") else {
        return Ok(plain);
    };
    let y = x * &small.vectors;
    let mut vectors = ritz.subcols(0, wanted).to_owned();
    vectors.subcols_mut(known, free).copy_from(&y);
    let mut refined_theta = theta[..wanted].to_vec();
    for (c, &l) in small.values.iter().enumerate() {
        refined_theta[known + c] = 1.0 / (l - sigma);
    }
    let refined = checked_pairs(
        pencil,
        &RitzPairs {
            theta: &refined_theta,
            ritz: &vectors,
            ..*pairs
        },
    )?;
    let better = refined.converged > plain.converged
        || refined.converged == plain.converged && refined.max_residual < plain.max_residual;
    Ok(if better { refined } else { plain })
}

/// The pencil $(K, M)$, the shift σ of its Lanczos iteration and the tolerances its pairs
/// are checked to.
#[derive(Clone, Copy)]
pub(super) struct ShiftedPencil<'a> {
    pub(super) k: &'a SparseSymmetric,
    pub(super) m: &'a MassMatrix,
    pub(super) sigma: f64,
    pub(super) params: &'a PartialEigenParameters,
}

/// One Rayleigh–Ritz step's pairs of the shifted operator: $\theta = 1/(\lambda - \sigma)$
/// and the Ritz vectors, the first `known` of them known null vectors, `wanted` asked for.
#[derive(Clone, Copy)]
pub(super) struct RitzPairs<'a> {
    pub(super) theta: &'a [f64],
    pub(super) ritz: &'a Mat<f64>,
    pub(super) wanted: usize,
    pub(super) known: usize,
}

pub(super) struct CheckedPairs {
    pub(super) eigen: GeneralizedEigen,
    pub(super) converged: usize,
    pub(super) max_residual: f64,
}

/// λ = σ + 1/θ, ascending, with the residual check on the original pencil.
pub(super) fn checked_pairs(
    pencil: &ShiftedPencil<'_>,
    pairs: &RitzPairs<'_>,
) -> Result<CheckedPairs> {
    let ShiftedPencil {
        k,
        m,
        sigma,
        params,
    } = *pencil;
    let RitzPairs {
        theta,
        ritz,
        wanted,
        known,
    } = *pairs;
    let n = k.dim();
    let mut values = Vec::with_capacity(wanted);
    let mut vectors = Mat::<f64>::zeros(n, wanted);
    for (c, &t) in theta.iter().take(wanted).enumerate() {
        values.push(sigma + 1.0 / t);
        vectors.col_mut(c).copy_from(ritz.col(c));
        fix_sign(vectors.col_mut(c));
    }
    let kv = k.mul(vectors.as_ref());
    let mvv = m.mul(vectors.as_ref());
    // The known null vectors and the zero-energy pairs (the lowest) have Kφ ≈ 0: measured
    // against ‖K‖‖φ‖.
    let scale = eigenvalue_scale((0..n).map(|j| (k.get(j, j), m.get(j, j))));
    let zero_energy = values
        .iter()
        .take_while(|&&l| l.abs() <= ZERO_ENERGY_RATIO * scale)
        .count()
        .max(known);
    let checked = pair_residuals(
        k,
        &values,
        vectors.as_ref(),
        (kv.as_ref(), mvv.as_ref()),
        zero_energy,
        ResidualCheck {
            tolerance: params.residual_tolerance,
            data_precision: params.data_precision,
        },
    );
    let (converged, max_residual, residuals) =
        (checked.converged(), checked.max, checked.residuals);
    if max_residual.is_nan() {
        return Err(LinalgError::EigenNotConverged {
            converged,
            wanted,
            residual: max_residual,
        });
    }
    Ok(CheckedPairs {
        eigen: GeneralizedEigen {
            values,
            vectors,
            residuals,
            zero_energy,
            sturm: None,
        },
        converged,
        max_residual,
    })
}
