//! The full body on a driven frame, sparse: its operators on the DOF outside the clamped ring
//! ([`super::DrivenFrameBody`] holds it), $G = ME$ and $H = ME^2$ applied node by node from
//! $M$ (which must be $M_s \otimes I_3$), the factor of $c_mM + c_kK$ kept while its
//! coefficients stay.

use faer::MatRef;
use nalgebra::Vector3;

use super::{DynamicsError, combination::Combination, frame_coordinates::FrameCoordinates};
use crate::{
    Error, Result,
    fem::{DofMap, FeModel},
    linalg::{MassMatrix, SparseSymmetric, SymbolicFactor, SymmetricFactor},
};

/// Largest relative difference between a node's three direction masses, and of a coupling
/// between two directions, for the mass matrix to count as $M_s \otimes I_3$.
pub const ISOTROPIC_MASS_TOLERANCE: f64 = 1e-9;

/// The full body, sparse.
#[derive(Debug)]
pub struct SparseDriven {
    /// Coordinates: the DOF outside the clamped ring, then the pinned rings' rotations.
    pub(super) coords: FrameCoordinates,
    pub(super) k_ff: SparseSymmetric,
    pub(super) m: MassMatrix,
    pub(super) m_ff: MassMatrix,
    pub(super) axis: Vector3<f64>,
    pub(super) symbolic: SymbolicFactor,
    /// The geometric stiffness of the centrifugal load per unit rate² on the coordinates
    /// (a body's preloaded stiffness, [`crate::body_file::Preload`]), if set.
    pub(super) centrifugal: Option<SparseSymmetric>,
    /// $(c_m, c_k)$ and the factor of $c_m M + c_k K$.
    pub(super) factor: Option<((f64, f64), SymmetricFactor)>,
}

/// Checks that `m` is $M_s \otimes I_3$ on a node-major solid DOF map.
pub(super) fn check_isotropic(model: &FeModel) -> Result<()> {
    if model.dofs != DofMap::solid() {
        return Err(DynamicsError::NotSolid {
            body: (&model.name).into(),
            frame: "driven",
        }
        .into());
    }
    let unequal = |node: usize, other: Option<usize>| -> Error {
        DynamicsError::MassNotIsotropic {
            body: (&model.name).into(),
            node,
            other,
        }
        .into()
    };
    match &model.m {
        MassMatrix::Lumped(d) => {
            for j in 0..d.len() / 3 {
                let m = d[3 * j];
                if (1..3).any(|a| (d[3 * j + a] - m).abs() > ISOTROPIC_MASS_TOLERANCE * m.abs()) {
                    return Err(unequal(j + 1, None));
                }
            }
        }
        MassMatrix::Consistent(m) => {
            let a = m.as_faer();
            let scale = m.max_abs();
            for j in 0..a.ncols() {
                let rows = a.symbolic().row_idx_of_col_raw(j);
                let vals = a.val_of_col(j);
                for (&i, &v) in rows.iter().zip(vals) {
                    let (pi, di) = (i / 3, i % 3);
                    let (pj, dj) = (j / 3, j % 3);
                    let twin = if di == dj {
                        // The same entry for the other two directions of the node pair.
                        (1..3)
                            .map(|s| {
                                let d = (di + s) % 3;
                                m.get(3 * pi + d, 3 * pj + d)
                            })
                            .map(|w| (w - v).abs())
                            .fold(0.0, f64::max)
                    } else {
                        v.abs()
                    };
                    if twin > ISOTROPIC_MASS_TOLERANCE * scale {
                        return Err(unequal(pi + 1, Some(pj + 1)));
                    }
                }
            }
        }
    }
    Ok(())
}

/// $y_j = e \times x_j$ per node (`twice`: $e \times (e \times x_j)$).
fn cross_nodes(axis: &Vector3<f64>, x: &[f64], twice: bool) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    for (xj, yj) in x.chunks_exact(3).zip(y.chunks_exact_mut(3)) {
        let v = Vector3::new(xj[0], xj[1], xj[2]);
        let mut w = axis.cross(&v);
        if twice {
            w = axis.cross(&w);
        }
        yj.copy_from_slice(w.as_slice());
    }
    y
}

pub(super) fn mul_mass(m: &MassMatrix, x: &[f64]) -> Vec<f64> {
    let y = m.mul(MatRef::from_column_major_slice(x, x.len(), 1));
    (0..x.len()).map(|i| y[(i, 0)]).collect()
}

impl SparseDriven {
    fn extend(&self, x: &[f64]) -> Vec<f64> {
        self.coords.extend(x)
    }

    pub(super) fn restrict(&self, full: &[f64]) -> Vec<f64> {
        self.coords.restrict(full)
    }

    /// $M E^p x$ on the free DOF (p = 1: G, p = 2: H) for a full-length `x`.
    pub(super) fn frame_full(&self, x_full: &[f64], twice: bool) -> Vec<f64> {
        self.restrict(&mul_mass(&self.m, &cross_nodes(&self.axis, x_full, twice)))
    }

    pub(super) fn mul(&self, c: Combination, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        let mut add = |z: Vec<f64>, s: f64| y.iter_mut().zip(z).for_each(|(y, z)| *y += s * z);
        if c.m != 0.0 {
            add(mul_mass(&self.m_ff, x), c.m);
        }
        if c.k != 0.0 {
            let kx = self
                .k_ff
                .mul(MatRef::from_column_major_slice(x, x.len(), 1));
            add((0..x.len()).map(|i| kx[(i, 0)]).collect(), c.k);
        }
        if let (Some(kg), true) = (&self.centrifugal, c.sigma[0] != 0.0) {
            let kx = kg.mul(MatRef::from_column_major_slice(x, x.len(), 1));
            add((0..x.len()).map(|i| kx[(i, 0)]).collect(), c.sigma[0]);
        }
        if c.g != 0.0 || c.h != 0.0 {
            let full = self.extend(x);
            if c.g != 0.0 {
                add(self.frame_full(&full, false), c.g);
            }
            if c.h != 0.0 {
                add(self.frame_full(&full, true), c.h);
            }
        }
        y
    }

    /// $\|(|c_m||M| + |c_k||K|)|x|\|$, the scale of the round-off in a product with the
    /// effective matrix (its small frame terms left out).
    pub(super) fn abs_norm(&self, c: Combination, x: &[f64]) -> f64 {
        let n = x.len();
        let ax: Vec<f64> = x.iter().map(|v| v.abs()).collect();
        let col = MatRef::from_column_major_slice(&ax, n, 1);
        let k = self.k_ff.abs_mul(col);
        let m: Vec<f64> = match &self.m_ff {
            MassMatrix::Lumped(d) => d.iter().zip(&ax).map(|(d, x)| d.abs() * x).collect(),
            MassMatrix::Consistent(m) => {
                let y = m.abs_mul(col);
                (0..n).map(|i| y[(i, 0)]).collect()
            }
        };
        (0..n)
            .map(|i| (c.m.abs() * m[i] + c.k.abs() * k[(i, 0)]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// $H = M E^2$ on the coordinates, sparse: $M_s \otimes \tilde e^2$ from the entries of
    /// $M$ between the x directions of two nodes (the mass is $M_s \otimes I_3$, checked when
    /// the body was made).
    pub(super) fn h_matrix(&self) -> SparseSymmetric {
        let e = self.axis;
        let ee = e * e.transpose() - nalgebra::Matrix3::identity();
        let n = self.coords.dofs();
        let mut entries = Vec::new();
        let mut add = |p: usize, q: usize, m: f64| {
            for a in 0..3 {
                for b in 0..3 {
                    if ee[(a, b)] != 0.0 {
                        entries.push((3 * p + a, 3 * q + b, m * ee[(a, b)]));
                    }
                }
            }
        };
        match &self.m {
            MassMatrix::Lumped(d) => (0..n / 3).for_each(|p| add(p, p, d[3 * p])),
            MassMatrix::Consistent(m) => {
                let a = m.as_faer();
                for j in (0..a.ncols()).step_by(3) {
                    let rows = a.symbolic().row_idx_of_col_raw(j);
                    for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
                        if i % 3 == 0 {
                            add(i / 3, j / 3, v);
                        }
                    }
                }
            }
        }
        self.coords
            .project(&SparseSymmetric::from_triplets(n, &entries))
    }

    /// $K + \Omega^2(H + K_{\sigma,1})$ on the coordinates: the stiffness of the body spun
    /// steadily at `rate` (rad/s) in the turning frame.
    pub(super) fn spun_stiffness(&self, rate: f64) -> SparseSymmetric {
        let w2 = rate * rate;
        let mut entries = Vec::new();
        let mut take = |a: &SparseSymmetric, c: f64| {
            let inner = a.as_faer();
            for j in 0..inner.ncols() {
                let rows = inner.symbolic().row_idx_of_col_raw(j);
                for (&i, &v) in rows.iter().zip(inner.val_of_col(j)) {
                    entries.push((i, j, c * v));
                }
            }
        };
        take(&self.k_ff, 1.0);
        if w2 != 0.0 {
            take(&self.h_matrix(), w2);
            if let Some(kg) = &self.centrifugal {
                take(kg, w2);
            }
        }
        SparseSymmetric::from_triplets(self.k_ff.dim(), &entries)
    }

    /// The factor of $c_m M + c_k K$, kept while the coefficients stay.
    pub(super) fn factor(&mut self, c_m: f64, c_k: f64) -> Result<&SymmetricFactor> {
        let same = self.factor.as_ref().is_some_and(|(c, _)| *c == (c_m, c_k));
        if !same {
            self.factor = None;
            let a = if c_k == 0.0 {
                return Err(DynamicsError::Misuse {
                    what: "the sparse effective matrix needs a stiffness part",
                }
                .into());
            } else {
                self.k_ff.shifted(&self.m_ff, -c_m / c_k)
            };
            let f = SymmetricFactor::sparse(a.as_faer(), &self.symbolic, "K + c M (free DOF)")?;
            self.factor = Some(((c_m, c_k), f));
        }
        Ok(&self.factor.as_ref().expect("set above").1)
    }
}
