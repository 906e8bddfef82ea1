//! Rigid and deformable bodies with their mass matrices and generalised forces.

use super::DynamicsError;
use crate::error::MatrixLabel;
use crate::linalg::LinalgError;
use faer::Mat;
use nalgebra::{DMatrix, DVector, Dyn, IsContiguous, Matrix3, Matrix3xX, Storage, Vector3};

use super::{AxisType, FreeFrameStiffening, InertiaInvariants, inertia_invariants::Modal};
use crate::{
    Error, Result,
    fem::{BrickElements, DofMap, FeModel},
    linalg::{MassMatrix, SparseSymmetric},
    reduction::Basis,
};

/// A rigid body whose frame sits at its mass centre.
#[derive(Debug, Clone)]
pub struct RigidBody {
    /// Name used in entity paths.
    pub name: String,
    /// Mass, kg.
    pub mass: f64,
    /// Inertia about the mass centre in body axes, kg m².
    pub inertia: Matrix3<f64>,
    /// Points drawn as a polyline (body frame, m), e.g. a link's two ends.
    pub outline: Vec<Vector3<f64>>,
}

impl RigidBody {
    /// A slender rod of `length` (m) and `mass` (kg) along the body x axis, with a thin
    /// radius so the axial inertia is not exactly zero.
    pub fn rod(name: &str, length: f64, mass: f64) -> Self {
        let radius = 0.01 * length;
        let it = mass * (3.0 * radius * radius + length * length) / 12.0;
        let ia = mass * radius * radius / 2.0;
        Self {
            name: name.into(),
            mass,
            inertia: Matrix3::from_diagonal(&Vector3::new(ia, it, it)),
            outline: vec![
                Vector3::new(-length / 2.0, 0.0, 0.0),
                Vector3::new(length / 2.0, 0.0, 0.0),
            ],
        }
    }
}

/// A deformable body on a floating frame, $d_j = r + A(\bar s_j + \Psi_j z)$ (Eq. 3.14 with
/// Eq. 5.12), with a lumped mass matrix.
///
/// [`FlexibleBody::new`] is the one place a reduced body gets its frame: nodal-fixed axes
/// remove the anchored columns of Ψ (Table 4-1) and put the origin at node i; mean and
/// principal axes put the origin at the mass centre, and [`crate::dynamics::System`] adds
/// their six condition rows (Table 4-2, §4.3) for every such body it is given.
#[derive(Debug, Clone)]
pub struct FlexibleBody {
    /// The finite-element model (its node positions in model coordinates).
    pub model: FeModel,
    /// The reduction basis the body is simulated with (nodal-fixed columns removed).
    pub basis: Basis,
    /// Axis conditions.
    pub axes: AxisType,
    /// Frame origin in model coordinates, m.
    pub origin: Vector3<f64>,
    /// Undeformed node positions in the body frame, $\bar s_j$, m.
    pub s_bar: Vec<Vector3<f64>>,
    /// Lumped node masses, kg.
    pub masses: Vec<f64>,
    /// Per-node rows of Ψ, $\Psi_j$ (3 × k).
    pub psi_nodes: Vec<Matrix3xX<f64>>,
    /// For each node, the columns where $\Psi_j$ is nonzero when they are at most a quarter of
    /// k (no reduction: a node's own three), `None` when $\Psi_j$ is dense. A point's
    /// kinematics then cost its nonzero columns, not k, at every evaluation.
    psi_support: Vec<Option<Box<[usize]>>>,
    /// $\Psi^T M \Psi$.
    pub m_zz: DMatrix<f64>,
    /// $\Psi^T K \Psi$.
    pub k_zz: DMatrix<f64>,
    /// $K_{zz}$ stored sparse when fewer than a quarter of its entries are nonzero (no
    /// reduction: the element stiffness pattern), so the elastic force costs the nonzeros and
    /// not $k^2$.
    k_zz_sparse: Option<SparseSymmetric>,
    /// $(\Psi^T M \Psi)^{-1}$ as a factorisation, computed once: the modal mass block is
    /// constant, so the equations of motion eliminate the modal accelerations with it.
    pub m_zz_inverse: ModalMassInverse,
    /// The inertia invariants, computed once.
    pub invariants: InertiaInvariants,
    /// The geometric stiffness of the frame's loads ([`FreeFrameStiffening`]), when the body
    /// was given it ([`Self::with_stiffening`]): its dynamic stiffening.
    pub stiffening: Option<FreeFrameStiffening>,
}

/// The inverse of a constant modal mass block $M_{zz} = \Psi^T M \Psi$: a reciprocal
/// diagonal when $M_{zz}$ is diagonal (no reduction, or mass-normalised modes), the explicit
/// inverse otherwise (formed once from a Cholesky factor). The equations of motion apply it
/// to $7 + n_c$ columns at every evaluation; one $k \times k$ product does that several
/// times faster than two triangular solves per column on the few dozen coordinates of a
/// reduced body.
#[derive(Debug, Clone)]
pub enum ModalMassInverse {
    /// $1 / M_{zz,ii}$.
    Diagonal(DVector<f64>),
    /// $M_{zz}^{-1}$, dense.
    Dense(DMatrix<f64>),
}

impl ModalMassInverse {
    /// Inverts `m_zz`; `body` names it in the error when it is not positive definite (the
    /// basis' columns are dependent) or the inverse fails its residual check
    /// ($\|M_{zz}M_{zz}^{-1} - I\|_{\max} \le 10^{-8}$).
    pub fn new(m_zz: &DMatrix<f64>, body: &str) -> Result<Self> {
        let n = m_zz.nrows();
        let off_diagonal = (0..n).any(|i| (0..n).any(|j| i != j && m_zz[(i, j)] != 0.0));
        let singular = |rcond: Option<f64>| {
            Error::Linalg(LinalgError::SingularMatrix {
                matrix: MatrixLabel::of_body("modal mass Ψ^T M Ψ", body),
                rcond,
            })
        };
        if !off_diagonal {
            let d = m_zz.diagonal();
            if d.iter().any(|&x| x <= 0.0) {
                return Err(singular(None));
            }
            return Ok(Self::Diagonal(d.map(|x| 1.0 / x)));
        }
        let inverse = m_zz
            .clone()
            .cholesky()
            .ok_or_else(|| singular(None))?
            .inverse();
        let residual = (m_zz * &inverse - DMatrix::<f64>::identity(n, n)).amax();
        if residual.is_nan() || residual > 1e-8 {
            return Err(singular(Some(1.0 / (m_zz.amax() * inverse.amax()))));
        }
        Ok(Self::Dense(inverse))
    }

    /// $M_{zz}^{-1} B$ into `out`, of `b`'s shape.
    pub fn solve_into(&self, b: &DMatrix<f64>, out: &mut DMatrix<f64>) {
        match self {
            Self::Diagonal(d) => {
                assert_eq!(
                    out.shape(),
                    b.shape(),
                    "ModalMassInverse::solve_into: shapes"
                );
                let k = d.len();
                assert_eq!(
                    b.nrows(),
                    k,
                    "ModalMassInverse::solve_into: {} rows for {k}",
                    b.nrows()
                );
                if k == 0 {
                    return;
                }
                // One pass, column by column (k rows each).
                for (o, b) in out
                    .as_mut_slice()
                    .chunks_exact_mut(k)
                    .zip(b.as_slice().chunks_exact(k))
                {
                    for ((o, b), d) in o.iter_mut().zip(b).zip(d.as_slice()) {
                        *o = b * d;
                    }
                }
            }
            // faer's small-matrix kernels, sequential: nalgebra's `mul_to` packs its operands
            // into buffers it allocates at every call, once per evaluation of an integration.
            Self::Dense(inverse) => {
                assert!(
                    out.shape() == b.shape() && inverse.ncols() == b.nrows(),
                    "ModalMassInverse::solve_into: shapes"
                );
                let (k, n) = b.shape();
                faer::linalg::matmul::matmul(
                    faer::MatMut::from_column_major_slice_mut(out.as_mut_slice(), k, n),
                    faer::Accum::Replace,
                    faer::MatRef::from_column_major_slice(inverse.as_slice(), k, k),
                    faer::MatRef::from_column_major_slice(b.as_slice(), k, n),
                    1.0,
                    faer::Par::Seq,
                );
            }
        }
    }
}

impl FlexibleBody {
    /// Bytes the body holds on the heap, estimated from its arrays: the model's $K$ and $M$
    /// (16 bytes per stored entry: value and index), the basis Ψ and its per-node rows, the
    /// dense modal blocks $M_{zz}$, $K_{zz}$ and $M_{zz}^{-1}$, the sparse $K_{zz}$ and the
    /// inertia invariants. Names, edges and column descriptions are left out. Without
    /// reduction on a refined slab the dense $k \times k$ blocks dominate: about 200 MB at
    /// 2 295 DOF.
    pub fn heap_bytes(&self) -> usize {
        const F64: usize = std::mem::size_of::<f64>();
        let model = 16 * self.model.k.nnz()
            + match &self.model.m {
                MassMatrix::Lumped(d) => F64 * d.len(),
                MassMatrix::Consistent(m) => 16 * m.nnz(),
            }
            + 3 * F64 * (self.model.nodes.len() + self.s_bar.len())
            + F64 * self.masses.len();
        let basis = F64 * self.basis.psi.nrows() * self.basis.psi.ncols()
            + self.psi_nodes.iter().map(|p| F64 * p.len()).sum::<usize>()
            + self.stiffening.as_ref().map_or(0, |s| s.heap_bytes());
        let modal = F64 * (self.m_zz.len() + self.k_zz.len())
            + self.k_zz_sparse.as_ref().map_or(0, |k| 16 * k.nnz())
            + match &self.m_zz_inverse {
                ModalMassInverse::Diagonal(d) => F64 * d.len(),
                ModalMassInverse::Dense(m) => F64 * m.len(),
            };
        model + basis + modal + self.invariants.heap_bytes()
    }

    /// Builds the body on its floating frame from a model and a reduction basis (all of the
    /// basis' columns; nodal-fixed axes remove theirs here).
    pub fn new(model: FeModel, basis: Basis, axes: AxisType) -> Result<Self> {
        if model.dofs != DofMap::solid() {
            return Err(DynamicsError::NotSolid {
                body: (&model.name).into(),
                frame: "floating",
            }
            .into());
        }
        let n = model.node_count();
        let not_lumped = || -> Error {
            DynamicsError::MassNotLumped {
                body: (&model.name).into(),
            }
            .into()
        };
        let MassMatrix::Lumped(diagonal) = &model.m else {
            return Err(not_lumped());
        };
        let mut masses = Vec::with_capacity(n);
        for j in 0..n {
            let m = diagonal[3 * j];
            if (1..3).any(|a| (diagonal[3 * j + a] - m).abs() > 1e-12 * m.abs().max(1.0)) {
                return Err(not_lumped());
            }
            masses.push(m);
        }
        let (basis, origin) = match axes {
            AxisType::NodalFixed(nf) => {
                let o = model.position(model.node_index(nf.origin)?);
                (nf.apply(&model, &basis)?, Vector3::new(o[0], o[1], o[2]))
            }
            AxisType::Mean | AxisType::Principal => (basis, Vector3::from(model.mass_centre())),
        };
        let k = basis.size();
        let s_bar: Vec<Vector3<f64>> = model
            .nodes
            .iter()
            .map(|p| Vector3::new(p[0], p[1], p[2]) - origin)
            .collect();
        let psi = &basis.psi;
        let psi_nodes: Vec<Matrix3xX<f64>> = (0..n)
            .map(|j| Matrix3xX::from_fn(k, |a, c| psi[(3 * j + a, c)]))
            .collect();
        let psi_support = psi_nodes
            .iter()
            .map(|p| {
                let columns: Vec<usize> = (0..k)
                    .filter(|&c| p.column(c).iter().any(|&x| x != 0.0))
                    .collect();
                (4 * columns.len() <= k).then(|| columns.into_boxed_slice())
            })
            .collect();
        let to_na = |m: &Mat<f64>| DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)]);
        let m_zz = to_na(&basis.reduced_mass(&model));
        let k_zz = to_na(&basis.reduced_stiffness(&model));
        let invariants = InertiaInvariants::new(&masses, &s_bar, &psi_nodes);
        let m_zz_inverse = ModalMassInverse::new(&m_zz, &model.name)?;
        let nonzeros = k_zz.iter().filter(|&&x| x != 0.0).count();
        let k_zz_sparse = (4 * nonzeros < k * k).then(|| {
            SparseSymmetric::from_dense(faer::MatRef::from_column_major_slice(
                k_zz.as_slice(),
                k,
                k,
            ))
        });
        Ok(Self {
            model,
            basis,
            axes,
            origin,
            s_bar,
            masses,
            psi_nodes,
            psi_support,
            m_zz,
            k_zz,
            k_zz_sparse,
            m_zz_inverse,
            invariants,
            stiffening: None,
        })
    }

    /// The body with the dynamic stiffening of its frame's loads, formed from the stresses of
    /// its mesh `elements` ([`FreeFrameStiffening::new`] on its own basis, axes and origin).
    pub fn with_stiffening(mut self, elements: &BrickElements) -> Result<Self> {
        self.stiffening = Some(FreeFrameStiffening::new(
            &self.model,
            elements,
            &self.axes,
            self.origin,
            &self.basis,
        )?);
        Ok(self)
    }

    /// The elastic force $K_{zz} z$ (N in modal units).
    pub fn elastic_force<S: Storage<f64, Dyn> + IsContiguous>(&self, z: &Modal<S>) -> DVector<f64> {
        let mut f = DVector::zeros(z.len());
        self.subtract_elastic_force(z, &mut f);
        -f
    }

    /// `out` $\mathrel{-}= K_{zz} z$: the sparse $K_{zz}$ (no reduction) by its stored entries,
    /// without a temporary.
    pub fn subtract_elastic_force<S: Storage<f64, Dyn> + IsContiguous>(
        &self,
        z: &Modal<S>,
        out: &mut DVector<f64>,
    ) {
        match &self.k_zz_sparse {
            Some(k) => k.sub_mul_vector(z.as_slice(), out.as_mut_slice()),
            None => out.gemv(-1.0, &self.k_zz, z, 1.0),
        }
    }

    /// Number of modal coordinates.
    pub fn modes(&self) -> usize {
        self.m_zz.nrows()
    }

    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        self.invariants.mass
    }

    /// $\sum_j m_j \Psi_j$ (3 × k): the translational mean-axis rows (Eq. 4.20).
    pub fn p_sum(&self) -> &Matrix3xX<f64> {
        &self.invariants.p_sum
    }

    /// The columns where node `j`'s $\Psi_j$ is nonzero, when they are few (see
    /// `psi_support`); `None` when $\Psi_j$ is dense.
    pub fn psi_columns(&self, j: usize) -> Option<&[usize]> {
        self.psi_support[j].as_deref()
    }

    /// Local deflection of node `j`, $\Psi_j z$ (over its nonzero columns only when they are
    /// few: the same sum, without its zero terms).
    pub fn deflection<S: Storage<f64, Dyn>>(&self, j: usize, z: &Modal<S>) -> Vector3<f64> {
        let psi = &self.psi_nodes[j];
        match self.psi_columns(j) {
            Some(columns) => columns
                .iter()
                .fold(Vector3::zeros(), |u, &c| u + psi.column(c) * z[c]),
            None => psi * z,
        }
    }

    /// $\Psi_j^T f$ for a force $f$ on node `j` in body axes, added to `out` (k): only the
    /// nonzero columns when they are few.
    pub fn add_nodal_force(&self, j: usize, force: &Vector3<f64>, out: &mut DVector<f64>) {
        let psi = &self.psi_nodes[j];
        match self.psi_columns(j) {
            Some(columns) => {
                for &c in columns {
                    out[c] += psi.column(c).dot(force);
                }
            }
            None => out.gemv_tr(1.0, psi, force, 1.0),
        }
    }

    /// $\bar b_j = \bar s_j + \Psi_j z$.
    pub fn b<S: Storage<f64, Dyn>>(&self, j: usize, z: &Modal<S>) -> Vector3<f64> {
        self.s_bar[j] + self.deflection(j, z)
    }

    /// Body inertia about the frame origin in body axes, $\sum m_j \tilde b_j^T \tilde b_j$.
    pub fn inertia<S: Storage<f64, Dyn>>(&self, z: &Modal<S>) -> Matrix3<f64> {
        self.invariants.inertia(z)
    }
}

/// A body of the system.
#[derive(Debug, Clone)]
pub enum Body {
    /// Rigid, 6 DOF.
    Rigid(RigidBody),
    /// Deformable, 6 + k DOF.
    Flexible(Box<FlexibleBody>),
}

impl Body {
    /// Position coordinates: r (3), Euler parameters (4), modal coordinates.
    pub fn position_count(&self) -> usize {
        match self {
            Body::Rigid(_) => 7,
            Body::Flexible(f) => 7 + f.modes(),
        }
    }

    /// Velocity coordinates: $\dot r$ (3), body-axis angular velocity $\bar\omega$ (3), $\dot z$.
    pub fn velocity_count(&self) -> usize {
        self.position_count() - 1
    }

    /// Name used in entity paths.
    pub fn name(&self) -> &str {
        match self {
            Body::Rigid(r) => &r.name,
            Body::Flexible(f) => &f.model.name,
        }
    }

    /// Bytes the body holds on the heap, estimated from its matrices (see
    /// [`FlexibleBody::heap_bytes`]); a rigid body's few points count as nothing.
    pub fn heap_bytes(&self) -> usize {
        match self {
            Body::Rigid(_) => 0,
            Body::Flexible(f) => f.heap_bytes(),
        }
    }
}
