//! Gregory's modal influence coefficients (Spanos–Tsuha Eqs. 44–46): closed-form
//! approximations of the Hankel singular values of a lightly damped modal model, used to rank
//! modes by how much they carry from the actuators to the sensors.

use super::ModalModel;
use super::ReductionError;
use crate::{Error, Result};

/// The influence coefficient of every mode of a [`ModalModel`] and the closeness check of
/// Eq. (45) that says whether the approximation can be trusted.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalInfluence {
    /// $\sigma_i$ per mode (Eq. 44), in the model's mode order; `f64::INFINITY` for a
    /// rigid-body mode (it is always kept).
    pub sigma: Vec<f64>,
    /// The largest $\max(\zeta_i,\zeta_j)\max(\omega_i,\omega_j)/|\omega_i-\omega_j|$ over
    /// pairs of elastic modes (Eq. 45; ≪ 1 for the approximation to hold).
    pub closeness: f64,
    /// The pair of modes (indices) where `closeness` is reached.
    pub closest_pair: Option<(usize, usize)>,
}

impl ModalInfluence {
    /// Mode indices by decreasing influence (rigid-body modes first), ties by frequency.
    pub fn ranking(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.sigma.len()).collect();
        order.sort_by(|&a, &b| self.sigma[b].total_cmp(&self.sigma[a]).then(a.cmp(&b)));
        order
    }

    /// The `count` most influential modes, in ascending mode order.
    pub fn most_influential(&self, count: usize) -> Vec<usize> {
        let mut keep: Vec<usize> = self.ranking().into_iter().take(count).collect();
        keep.sort_unstable();
        keep
    }
}

/// $$\sigma_i \approx \frac{\sqrt{b_i b_i^T\,[c_{1i}^Tc_{1i} + \omega_i^2 c_{2i}^Tc_{2i}]}}
/// {4\zeta_i\omega_i^2}$$ (Eq. 44), with $b_i$ row i of B and $c_{1i}$, $c_{2i}$ column i of
/// $C_1$, $C_2$. With displacement outputs only it is $\|G_i(0)\|_F / (4\zeta_i)$ (Eq. 46),
/// $G_i(0) = c_{1i}b_i/\omega_i^2$ the mode's static contribution. Gregory derives it for a
/// lightly damped mode well separated from the others; Eq. (45) measures how far that holds.
///
/// A model without damping has no finite Hankel singular values: `ReductionError::NoModalDamping`.
pub fn modal_influence(model: &ModalModel) -> Result<ModalInfluence> {
    if model.zeta <= 0.0 || !model.zeta.is_finite() {
        return Err(Error::Reduction(ReductionError::NoModalDamping {
            zeta: model.zeta,
            needs: "modal influence coefficients (they divide by the damping ratio)",
        }));
    }
    let p = model.mode_count();
    let sq = |v: f64| v * v;
    let sigma: Vec<f64> = (0..p)
        .map(|i| {
            if i < model.rigid {
                return f64::INFINITY;
            }
            let w = model.omega[i];
            let bb: f64 = (0..model.b.ncols()).map(|s| sq(model.b[(i, s)])).sum();
            let c1: f64 = (0..model.c1.nrows()).map(|r| sq(model.c1[(r, i)])).sum();
            let c2: f64 = (0..model.c2.nrows()).map(|r| sq(model.c2[(r, i)])).sum();
            (bb * (c1 + w * w * c2)).sqrt() / (4.0 * model.zeta * w * w)
        })
        .collect();
    let mut closeness = 0.0f64;
    let mut closest_pair = None;
    for i in model.rigid..p {
        for j in (i + 1)..p {
            let (wi, wj) = (model.omega[i], model.omega[j]);
            let gap = (wi - wj).abs();
            let c = if gap == 0.0 {
                f64::INFINITY
            } else {
                model.zeta * wi.max(wj) / gap
            };
            if closest_pair.is_none() || c > closeness {
                closeness = c;
                closest_pair = Some((i, j));
            }
        }
    }
    Ok(ModalInfluence {
        sigma,
        closeness,
        closest_pair,
    })
}
