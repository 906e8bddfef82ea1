//! Boundary conditions changed after reduction (Witteveen §4.1, variants 2 and 3): DOF held at
//! zero and point masses applied to a Ritz-reduced model only, its basis left as it was.

use super::ReductionError;
use crate::error::DofSetProblem;
use crate::linalg::LinalgError;
use faer::{Mat, MatRef, linalg::solvers::Solve};

use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{GeneralizedEigen, generalized_eigen},
};

/// A Ritz model $x = Vz$ under new supports: $V_hz = 0$ on the held DOF is solved by the null
/// space $N$ of $V_h$ ($z = Nw$, so the model is reduced once more to $VN$), and a point mass
/// $m$ on DOF d adds $m\,v_d^Tv_d$ to $\tilde M$ ($v_d$ row d of $VN$).
///
/// A retained physical coordinate (a Craig–Bampton boundary DOF) simply disappears; a
/// non-physical basis (Krylov, balanced) loses the combinations that move the held DOF.
#[derive(Debug, Clone)]
pub struct RestrainedRitzModel {
    /// $VN$, n × r' (zero rows on the held DOF, to round-off).
    pub basis: Mat<f64>,
    /// $\tilde K = (VN)^TK(VN)$.
    pub k: Mat<f64>,
    /// $\tilde M = (VN)^TM(VN)$ plus the point masses.
    pub m: Mat<f64>,
    /// How many generalised coordinates the supports removed.
    pub removed: usize,
}

impl RestrainedRitzModel {
    /// Restrains the Ritz model of `basis` (n × r) on `model`: `held` DOF at zero, and
    /// `point_masses` (DOF, mass) added. `ReductionError::InvalidDofSet` for a DOF out of range;
    /// `LinalgError::SingularMatrix` when the supports leave no coordinate.
    pub fn new(
        model: &FeModel,
        basis: MatRef<'_, f64>,
        held: &[usize],
        point_masses: &[(usize, f64)],
    ) -> Result<Self> {
        let n = model.dof_count();
        if let Some(&d) = held
            .iter()
            .chain(point_masses.iter().map(|(d, _)| d))
            .find(|&&d| d >= n)
        {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: "restrained".into(),
                problem: DofSetProblem::OutOfRange { dof: d, count: n },
            }));
        }
        let r = basis.ncols();
        let scale = crate::linalg::max_abs(basis).max(f64::MIN_POSITIVE);
        let vh = Mat::from_fn(held.len(), r, |i, j| basis[(held[i], j)]);
        let null = crate::linalg::null_space(vh.as_ref(), 1e-10 * scale)?;
        if null.ncols() == 0 {
            return Err(Error::Linalg(LinalgError::SingularMatrix {
                matrix: "restrained Ritz model (the supports hold every coordinate)".into(),
                rcond: None,
            }));
        }
        let v = basis * &null;
        let k = symmetric(v.transpose() * model.k.mul(v.as_ref()));
        let mut m = symmetric(v.transpose() * model.m.mul(v.as_ref()));
        for &(d, mass) in point_masses {
            for i in 0..v.ncols() {
                for j in 0..v.ncols() {
                    m[(i, j)] += mass * v[(d, i)] * v[(d, j)];
                }
            }
        }
        Ok(Self {
            removed: r - null.ncols(),
            basis: v,
            k,
            m,
        })
    }

    /// The static response $x = VN\tilde K^{-1}(VN)^Tf$ to a load on every DOF.
    pub fn static_response(&self, load: &[f64]) -> Result<Vec<f64>> {
        let v = &self.basis;
        assert_eq!(load.len(), v.nrows(), "load length against the body's DOF");
        let rhs = Mat::from_fn(v.ncols(), 1, |i, _| {
            (0..v.nrows()).map(|d| v[(d, i)] * load[d]).sum::<f64>()
        });
        let llt = self.k.llt(faer::Side::Lower).map_err(|_| {
            Error::Linalg(LinalgError::NotPositiveDefinite {
                matrix: "restrained reduced stiffness".into(),
            })
        })?;
        let z = llt.solve(&rhs);
        Ok((0..v.nrows())
            .map(|d| (0..v.ncols()).map(|i| v[(d, i)] * z[(i, 0)]).sum())
            .collect())
    }

    /// The natural modes, expanded to the body's DOF ($VN\Psi$, mass-normalised).
    pub fn modes(&self) -> Result<GeneralizedEigen> {
        let eig = generalized_eigen(self.k.as_ref(), self.m.as_ref(), "restrained reduced")?;
        Ok(GeneralizedEigen {
            vectors: &self.basis * &eig.vectors,
            ..eig
        })
    }
}

fn symmetric(a: Mat<f64>) -> Mat<f64> {
    let n = a.nrows();
    Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}
