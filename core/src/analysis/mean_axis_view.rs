//! A displacement field seen from mean axes (§4.2, linearised): the frame that follows the
//! body's rigid motion in the mass metric, so that the deformation it sees carries neither
//! linear nor angular momentum, $P^T M u_e = 0$ (Eqs. 4.20–4.21 for small rotations of the
//! frame), with $P$ the rigid-body modes. A field $u$ in any frame splits into the mean frame's
//! motion $q = (P^T M P)^{-1}P^TMu$ and the deformation $u_e = u - Pq$ it sees.

use crate::error::MatrixLabel;
use faer::{Mat, MatRef, Side, linalg::solvers::Solve};

use crate::{Result, error::LinalgError, fem::FeModel};

/// The projection onto a body's mean axes.
#[derive(Debug, Clone)]
pub struct MeanAxisView {
    /// Rigid-body modes about the mass centre, n × r.
    p: Mat<f64>,
    /// $MP$, n × r.
    mp: Mat<f64>,
    /// $(P^T M P)^{-1}$, r × r.
    gram_inverse: Mat<f64>,
}

impl MeanAxisView {
    /// The view of `model` (its M and node positions).
    pub fn of(model: &FeModel) -> Result<Self> {
        let p = super::rigid_modes_about_mass_centre(model);
        let mp = model.m.mul(p.as_ref());
        let gram = p.transpose() * &mp;
        let r = gram.nrows();
        let llt = gram
            .llt(Side::Lower)
            .map_err(|_| LinalgError::NotPositiveDefinite {
                matrix: MatrixLabel::of_body("rigid-body mass P^T M P", model.name.clone()),
            })?;
        let gram_inverse = llt.solve(Mat::<f64>::identity(r, r));
        Ok(Self {
            p,
            mp,
            gram_inverse,
        })
    }

    /// The mean frame's rigid motion $q$ for the field `u` (translations, then rotations
    /// about the mass centre).
    pub fn rigid_part(&self, u: &[f64]) -> Vec<f64> {
        let ptmu = self.mp.transpose() * MatRef::from_column_major_slice(u, u.len(), 1);
        let q = &self.gram_inverse * ptmu;
        (0..q.nrows()).map(|i| q[(i, 0)]).collect()
    }

    /// The deformation seen from mean axes, $u - Pq$.
    pub fn deformation(&self, u: &[f64]) -> Vec<f64> {
        let q = self.rigid_part(u);
        let mut out = u.to_vec();
        for (k, qk) in q.iter().enumerate() {
            let col = self.p.col(k);
            out.iter_mut()
                .enumerate()
                .for_each(|(i, o)| *o -= col[i] * qk);
        }
        out
    }

    /// The rows of $P$ averaged over the given DOF triples (one node's x, y, z each): the
    /// mean rigid motion of a node set per unit of each rigid coordinate, 3 × r.
    pub fn mean_rows(&self, dofs: &[usize]) -> Vec<Vec<f64>> {
        let nodes = (dofs.len() / 3).max(1) as f64;
        (0..3)
            .map(|a| {
                (0..self.p.ncols())
                    .map(|k| dofs.chunks_exact(3).map(|t| self.p[(t[a], k)]).sum::<f64>() / nodes)
                    .collect()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};

    /// On the App. B slab: a rigid motion is all frame (no deformation); any field's
    /// deformation carries no momentum ($P^TMu_e = 0$); the split is a projection.
    #[test]
    fn rigid_motions_vanish_and_deformation_carries_no_momentum() {
        let model = slab(&SlabParameters::default());
        let view = MeanAxisView::of(&model).unwrap();
        let n = model.dof_count();
        let p = model.rigid_body_modes();
        for k in 0..p.ncols() {
            let u: Vec<f64> = (0..n).map(|i| p[(i, k)]).collect();
            let e = view.deformation(&u);
            let scale = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(e.iter().all(|x| x.abs() < 1e-12 * scale), "rigid mode {k}");
        }
        let u: Vec<f64> = (0..n)
            .map(|i| ((i * 37 % 101) as f64 - 50.0) * 1e-4)
            .collect();
        let e = view.deformation(&u);
        let momentum = view.rigid_part(&e);
        let scale = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            momentum.iter().all(|q| q.abs() < 1e-10 * scale),
            "{momentum:?}"
        );
        let twice = view.deformation(&e);
        assert!(
            twice
                .iter()
                .zip(&e)
                .all(|(a, b)| (a - b).abs() < 1e-12 * scale)
        );
    }
}
