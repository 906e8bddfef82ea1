//! The coordinates of a full body on a driven frame: the DOF outside the clamped drive ring,
//! then three rotations per pinned ring. A pinned ring moves rigidly with its master, whose
//! translations are held in the frame (a spherical joint to the carrier): its DOF follow
//! $u_s = \theta_m \times (x_s - x_m)$. The map $u = Tx$ from coordinates to nodal
//! displacements is sparse; operators become $T^T A T$.

use super::DynamicsError;
use faer::{Mat, MatRef};

use crate::{
    Result,
    linalg::{MassMatrix, SparseSymmetric},
};

/// A ring pinned to the frame: its DOF and, per DOF, its motion under each unit rotation of
/// the master (the rows of the ring's rotation matrix).
#[derive(Debug, Clone, PartialEq)]
pub struct PinnedRing {
    /// The ring's name (for messages).
    pub name: String,
    /// The ring's DOF, 0-based.
    pub dofs: Vec<usize>,
    /// Per DOF: $\partial u_s / \partial \theta_m$ (three coefficients).
    pub rows: Vec<[f64; 3]>,
}

/// What a DOF is in the coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    Free(usize),
    Pinned { ring: usize, row: usize },
    Clamped,
}

/// The map between coordinates and nodal displacements (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameCoordinates {
    n: usize,
    free: Vec<usize>,
    pins: Vec<PinnedRing>,
    roles: Vec<Role>,
}

impl FrameCoordinates {
    /// `n` DOF, `clamped` held, `pins` pinned (a DOF in two of them is an error).
    pub fn new(n: usize, clamped: &[usize], pins: Vec<PinnedRing>) -> Result<Self> {
        let mut roles = vec![Role::Free(0); n];
        for &d in clamped {
            roles[d] = Role::Clamped;
        }
        for (p, pin) in pins.iter().enumerate() {
            assert_eq!(pin.dofs.len(), pin.rows.len(), "one row per pinned DOF");
            for (r, &d) in pin.dofs.iter().enumerate() {
                if roles[d] != Role::Free(0) {
                    return Err(DynamicsError::RingsOverlap {
                        ring: (&pin.name).into(),
                        dof: d + 1,
                    }
                    .into());
                }
                roles[d] = Role::Pinned { ring: p, row: r };
            }
        }
        let mut free = Vec::new();
        for (d, role) in roles.iter_mut().enumerate() {
            if *role == Role::Free(0) {
                *role = Role::Free(free.len());
                free.push(d);
            }
        }
        Ok(Self {
            n,
            free,
            pins,
            roles,
        })
    }

    /// Coordinates: free DOF and three per pinned ring.
    pub fn dim(&self) -> usize {
        self.free.len() + 3 * self.pins.len()
    }

    /// DOF of the body.
    pub fn dofs(&self) -> usize {
        self.n
    }

    /// The free DOF, ascending.
    pub fn free(&self) -> &[usize] {
        &self.free
    }

    /// $u = Tx$.
    pub fn extend(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.dim(), "one value per coordinate");
        let nf = self.free.len();
        let mut u = vec![0.0; self.n];
        for (&d, &v) in self.free.iter().zip(x) {
            u[d] = v;
        }
        for (p, pin) in self.pins.iter().enumerate() {
            let theta = &x[nf + 3 * p..nf + 3 * p + 3];
            for (&d, row) in pin.dofs.iter().zip(&pin.rows) {
                u[d] = row[0] * theta[0] + row[1] * theta[1] + row[2] * theta[2];
            }
        }
        u
    }

    /// $T^T y$.
    pub fn restrict(&self, y: &[f64]) -> Vec<f64> {
        assert_eq!(y.len(), self.n, "one value per DOF");
        let mut x: Vec<f64> = self.free.iter().map(|&d| y[d]).collect();
        for pin in &self.pins {
            let mut t = [0.0; 3];
            for (&d, row) in pin.dofs.iter().zip(&pin.rows) {
                for k in 0..3 {
                    t[k] += row[k] * y[d];
                }
            }
            x.extend_from_slice(&t);
        }
        x
    }

    /// The coordinates a DOF contributes to, with their coefficients.
    fn contributions(&self, d: usize) -> Vec<(usize, f64)> {
        match self.roles[d] {
            Role::Free(i) => vec![(i, 1.0)],
            Role::Pinned { ring, row } => {
                let base = self.free.len() + 3 * ring;
                let r = self.pins[ring].rows[row];
                (0..3).map(|k| (base + k, r[k])).collect()
            }
            Role::Clamped => Vec::new(),
        }
    }

    /// $T^T A T$ (the principal block of the free DOF when nothing is pinned).
    pub fn project(&self, a: &SparseSymmetric) -> SparseSymmetric {
        if self.pins.is_empty() {
            return a.principal_block(&self.free);
        }
        let inner = a.as_faer();
        let mut entries = Vec::with_capacity(inner.compute_nnz());
        for j in 0..self.n {
            let cj = self.contributions(j);
            if cj.is_empty() {
                continue;
            }
            let rows = inner.symbolic().row_idx_of_col_raw(j);
            for (&i, &v) in rows.iter().zip(inner.val_of_col(j)) {
                for &(ci, wi) in &self.contributions(i) {
                    for &(cj, wj) in &cj {
                        entries.push((ci, cj, v * wi * wj));
                    }
                }
            }
        }
        SparseSymmetric::from_triplets(self.dim(), &entries)
    }

    /// $T^T M T$: a lumped M stays lumped when nothing is pinned.
    pub fn project_mass(&self, m: &MassMatrix) -> MassMatrix {
        match m {
            MassMatrix::Lumped(_) if self.pins.is_empty() => m.principal_block(&self.free),
            MassMatrix::Lumped(d) => {
                let entries: Vec<(usize, usize, f64)> =
                    d.iter().enumerate().map(|(i, &v)| (i, i, v)).collect();
                MassMatrix::Consistent(
                    self.project(&SparseSymmetric::from_triplets(d.len(), &entries)),
                )
            }
            MassMatrix::Consistent(a) => MassMatrix::Consistent(self.project(a)),
        }
    }

    /// The coordinates of each column of `psi` (nodal rows): $x$ with $Tx = \psi$, checked —
    /// a column that moves the clamped ring, or moves a pinned ring otherwise than by a
    /// rotation about its master, cannot be simulated on this frame.
    pub fn coordinates_of(&self, psi: MatRef<'_, f64>) -> Result<Mat<f64>> {
        assert_eq!(psi.nrows(), self.n, "Ψ has a row per DOF");
        let mut out = Mat::zeros(self.dim(), psi.ncols());
        for c in 0..psi.ncols() {
            let col: Vec<f64> = (0..self.n).map(|i| psi[(i, c)]).collect();
            let scale = col.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            // Least squares per pinned ring: (RᵀR) θ = Rᵀ ψ_ring.
            let mut x: Vec<f64> = self.free.iter().map(|&d| col[d]).collect();
            for pin in &self.pins {
                let mut normal = nalgebra::Matrix3::<f64>::zeros();
                let mut rhs = nalgebra::Vector3::<f64>::zeros();
                for (&d, r) in pin.dofs.iter().zip(&pin.rows) {
                    let r = nalgebra::Vector3::from(*r);
                    normal += r * r.transpose();
                    rhs += r * col[d];
                }
                let theta = normal
                    .try_inverse()
                    .map(|inv| inv * rhs)
                    .unwrap_or_else(nalgebra::Vector3::zeros);
                x.extend_from_slice(theta.as_slice());
            }
            let back = self.extend(&x);
            if let Some((i, _)) = back
                .iter()
                .zip(&col)
                .enumerate()
                .find(|(_, (b, c))| (*b - *c).abs() > 1e-10 * scale.max(f64::MIN_POSITIVE))
            {
                return Err(DynamicsError::BasisMovesHeldDof {
                    column: c + 1,
                    dof: i + 1,
                    motion: col[i],
                }
                .into());
            }
            for (i, v) in x.into_iter().enumerate() {
                out[(i, c)] = v;
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T and Tᵀ are adjoint, TᵀAT equals the dense product, and a column T x is recovered.
    #[test]
    fn the_map_its_adjoint_and_the_projection_agree() {
        let n = 12;
        // A ring of two nodes (DOF 6..12) pinned about the origin, DOF 0..3 clamped.
        let positions = [[1.0, 0.5, 0.0], [0.0, -1.0, 2.0]];
        let mut dofs = Vec::new();
        let mut rows = Vec::new();
        for (j, r) in positions.iter().enumerate() {
            for a in 0..3 {
                dofs.push(6 + 3 * j + a);
                let mut row = [0.0; 3];
                for (k, v) in row.iter_mut().enumerate() {
                    let mut e = [0.0; 3];
                    e[k] = 1.0;
                    let cross = [
                        e[1] * r[2] - e[2] * r[1],
                        e[2] * r[0] - e[0] * r[2],
                        e[0] * r[1] - e[1] * r[0],
                    ];
                    *v = cross[a];
                }
                rows.push(row);
            }
        }
        let pin = PinnedRing {
            name: "ring".into(),
            dofs,
            rows,
        };
        let t = FrameCoordinates::new(n, &[0, 1, 2], vec![pin]).unwrap();
        assert_eq!(t.dim(), 3 + 3);
        let a_dense = Mat::from_fn(n, n, |i, j| {
            let (i, j) = (i as f64, j as f64);
            if i == j {
                10.0 + i
            } else {
                1.0 / (1.0 + (i - j).abs())
            }
        });
        let a = SparseSymmetric::from_dense(a_dense.as_ref());
        let tm = Mat::from_fn(n, t.dim(), |i, c| {
            let mut e = vec![0.0; t.dim()];
            e[c] = 1.0;
            t.extend(&e)[i]
        });
        let expected = tm.transpose() * &a_dense * &tm;
        let projected = t.project(&a).to_dense();
        for i in 0..t.dim() {
            for j in 0..t.dim() {
                assert!((projected[(i, j)] - expected[(i, j)]).abs() < 1e-12);
            }
        }
        let x: Vec<f64> = (0..t.dim()).map(|i| 0.3 * i as f64 - 0.7).collect();
        let y: Vec<f64> = (0..n).map(|i| (i * i) as f64 * 0.01).collect();
        let lhs: f64 = t.extend(&x).iter().zip(&y).map(|(a, b)| a * b).sum();
        let rhs: f64 = t.restrict(&y).iter().zip(&x).map(|(a, b)| a * b).sum();
        assert!((lhs - rhs).abs() < 1e-12 * lhs.abs().max(1.0));
        let u = t.extend(&x);
        let psi = Mat::from_fn(n, 1, |i, _| u[i]);
        let back = t.coordinates_of(psi.as_ref()).unwrap();
        assert!((0..t.dim()).all(|i| (back[(i, 0)] - x[i]).abs() < 1e-12));
        // A column that translates the pinned ring is refused.
        let mut bad = psi.clone();
        bad[(6, 0)] += 1.0;
        assert!(t.coordinates_of(bad.as_ref()).is_err());
    }
}
