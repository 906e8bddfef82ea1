//! The lowest pairs of a body spun steadily on its driven frame, Coriolis coupling left out
//! (as the FE codes' prestressed frequency steps leave it):
//! $$(K + \Omega^2(H + K_{\sigma,1}))\,\varphi = \omega^2 M\varphi$$
//! on the coordinates outside the clamped ring. A reduced body (a few hundred coordinates)
//! is solved densely; the full body, whatever its size, by the sparse route: shift-invert
//! block Lanczos on the factor of the spun stiffness and the Sturm count of the pairs found
//! ([`crate::reduction`]'s free-body route without a null space). Above a divergence speed
//! the spin's softening passes the stiffness and the spun stiffness is indefinite: the
//! count of its negative eigenvalues (the inertia of an $LDL^T$ factor) says so.

use faer::Mat;

use crate::{
    Error, Result,
    dynamics::{Combination, DrivenFrameBody},
    error::LinalgError,
    linalg::{
        GeneralizedEigen, MassMatrix, PairSelection, PartialEigenParameters, SparseSymmetric,
        SymbolicFactor, SymmetricFactor, generalized_eigen_selected, inertia_at,
    },
    reduction::{FreeBodyParameters, ReleasableFactor, SturmPencil, sturm_checked},
};

/// Coordinates up to which a spun body is solved densely (its operators formed column by
/// column): reduced models, and small full bodies.
pub const CAMPBELL_DENSE_LIMIT: usize = 2000;

/// The pairs of one spun body at one rate.
#[derive(Debug, Clone)]
pub struct SpinningPairs {
    /// $\omega^2$, (rad/s)², ascending; negative ones are unstable (divergence).
    pub values: Vec<f64>,
    /// Mass-normalised vectors in the body's coordinates, one per value (for tracking
    /// curves from rate to rate by MAC).
    pub vectors: Mat<f64>,
    /// Eigenvalues below zero: 0 while the spun stiffness is positive definite.
    pub unstable: usize,
    /// The route: `dense` or `sparse Lanczos, Sturm-checked`.
    pub route: &'static str,
}

impl SpinningPairs {
    /// Frequencies, Hz; an unstable pair's is negative, $-\sqrt{-\omega^2}/2\pi$.
    pub fn hz(&self) -> Vec<f64> {
        self.values
            .iter()
            .map(|&l| l.signum() * l.abs().sqrt() / (2.0 * std::f64::consts::PI))
            .collect()
    }
}

/// The lowest `count` pairs of `body` spun at `rate` (rad/s), every pair checked by its
/// residual; the full body past [`CAMPBELL_DENSE_LIMIT`] coordinates by the sparse route,
/// whose pairs are also Sturm-counted. A spun stiffness with negative eigenvalues on the
/// sparse route gives no pairs, only their count (`unstable`).
pub fn spinning_pairs(body: &DrivenFrameBody, rate: f64, count: usize) -> Result<SpinningPairs> {
    let n = body.dim();
    if n > CAMPBELL_DENSE_LIMIT
        && let Some((k, m)) = body.spun_pencil(rate)
    {
        return sparse_pairs(&k, m, count.min(n / 4));
    }
    let mut stiffness = Combination {
        k: 1.0,
        h: rate * rate,
        ..Default::default()
    };
    stiffness.sigma[0] = rate * rate;
    let mass = Combination {
        m: 1.0,
        ..Default::default()
    };
    let symmetric = |a: Mat<f64>| Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let e = generalized_eigen_selected(
        symmetric(body.dense_matrix(stiffness)).as_ref(),
        symmetric(body.dense_matrix(mass)).as_ref(),
        "body spinning on the driven frame",
        PairSelection::Lowest(count),
    )?;
    let unstable = e.values.iter().filter(|&&l| l < 0.0).count();
    Ok(SpinningPairs {
        values: e.values,
        vectors: e.vectors,
        unstable,
        route: "dense",
    })
}

/// The sparse route of [`spinning_pairs`] on the pencil `(k, m)`.
fn sparse_pairs(k: &SparseSymmetric, m: &MassMatrix, count: usize) -> Result<SpinningPairs> {
    let n = k.dim();
    // The pattern of K − σM for every σ: the factor's and the Sturm counts'.
    let symbolic = SymbolicFactor::analyse(k.shifted(m, -1.0).as_faer())?;
    let a = k.shifted(m, 0.0);
    let factor = match SymmetricFactor::sparse(a.as_faer(), &symbolic, "spun stiffness") {
        Ok(f) => f,
        Err(e) => {
            // Not positive definite: how many eigenvalues lie below zero.
            let below = inertia_at(k, m, &symbolic, 0.0)?;
            if below == 0 {
                return Err(e.into());
            }
            return Ok(SpinningPairs {
                values: Vec::new(),
                vectors: Mat::zeros(n, 0),
                unstable: below,
                route: "sparse LDLᵀ inertia",
            });
        }
    };
    let mut releasable = ReleasableFactor::new(factor, || {
        SymmetricFactor::sparse(k.shifted(m, 0.0).as_faer(), &symbolic, "spun stiffness")
    });
    let null = Mat::<f64>::zeros(n, 0);
    let (eigen, _): (GeneralizedEigen, _) = sturm_checked(
        SturmPencil {
            k,
            m,
            symbolic: &symbolic,
        },
        &mut releasable,
        0.0,
        count,
        null.as_ref(),
        &PartialEigenParameters::default(),
        FreeBodyParameters::default().sturm_retries,
    )?;
    if eigen.values.len() < count {
        return Err(Error::Linalg(LinalgError::TooManyPairs {
            wanted: count,
            dof: n,
        }));
    }
    Ok(SpinningPairs {
        values: eigen.values,
        vectors: eigen.vectors,
        unstable: 0,
        route: "sparse Lanczos, Sturm-checked",
    })
}

/// The MAC of two mass-normalised vector sets in one mass metric:
/// $\mathrm{MAC}_{ij} = (\varphi_i^T M \psi_j)^2$, given $M\psi$.
fn mac(previous: &Mat<f64>, m_current: &Mat<f64>) -> Mat<f64> {
    let p: Mat<f64> = previous.transpose() * m_current;
    Mat::from_fn(p.nrows(), p.ncols(), |i, j| p[(i, j)] * p[(i, j)])
}

/// The order that carries each curve from one rate to the next: for every curve (a column
/// of `previous`), the column of `current` with the largest MAC, taken greedily from the
/// best-matched pair down, and that MAC; `m_current` is $M$ times the current vectors. Curves with no
/// column left get `None`.
pub fn track_by_mac(previous: &Mat<f64>, m_current: &Mat<f64>) -> Vec<Option<(usize, f64)>> {
    let mac = mac(previous, m_current);
    let (rows, cols) = (mac.nrows(), mac.ncols());
    let mut pairs: Vec<(usize, usize, f64)> = (0..rows)
        .flat_map(|i| (0..cols).map(move |j| (i, j)))
        .map(|(i, j)| (i, j, mac[(i, j)]))
        .collect();
    pairs.sort_by(|a, b| b.2.total_cmp(&a.2));
    let mut out = vec![None; rows];
    let mut taken = vec![false; cols];
    for (i, j, v) in pairs {
        if out[i].is_none() && !taken[j] {
            out[i] = Some((j, v));
            taken[j] = true;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two modes that cross: tracked by MAC, each curve keeps its shape although the sorted
    /// order swaps.
    #[test]
    fn curves_follow_their_shapes_through_a_crossing() {
        // M = I; shapes e0, e1; at the next rate the values swap places in sorted order.
        let previous = Mat::from_fn(3, 2, |i, j| if i == j { 1.0 } else { 0.0 });
        let current = Mat::from_fn(3, 2, |i, j| match (i, j) {
            (1, 0) => 1.0,
            (0, 1) => -1.0,
            _ => 0.0,
        });
        let order = track_by_mac(&previous, &current);
        assert_eq!(order[0].map(|o| o.0), Some(1));
        assert_eq!(order[1].map(|o| o.0), Some(0));
        assert!(order.iter().all(|o| (o.unwrap().1 - 1.0).abs() < 1e-15));
    }
}
