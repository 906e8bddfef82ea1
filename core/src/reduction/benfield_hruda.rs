//! Benfield–Hruda reduction (Spanos–Tsuha Eqs. 18–22): normal modes of a component whose
//! interface carries the constraint-mode mass and stiffness of the components attached to it.

use super::ReductionError;
use crate::error::{DofSetName, DofSetProblem};
use faer::Mat;

use super::{
    Basis, COMPLETE_EIGEN_LIMIT, Column, ColumnKind, Method, ModeSelection, Partition,
    ReductionStatistics, SolverPath, interior_problem::InteriorProblem,
};
use crate::{Error, Result, fem::FeModel, linalg::generalized_eigen};

/// The interface loading of Eqs. (19)–(20): $\Psi^{B\,T}M^B\Psi^B$ and
/// $\Psi^{B\,T}K^B\Psi^B$ (kg, N/m), in the order of the interface DOF.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceLoading {
    /// Added interface mass, i × i.
    pub mass: Mat<f64>,
    /// Added interface stiffness, i × i (zero for a statically determinate interface).
    pub stiffness: Mat<f64>,
}

impl InterfaceLoading {
    /// The loading by component B through its interface DOF `interface_b` (the same physical
    /// DOF, in the same order, as the loaded component's), B's DOF `held_b` held at zero:
    /// B's constraint modes $\Psi^B_{ni} = [I;\ -K_{jj}^{B\,-1}K^B_{ji}]$ (Eq. 21) reduce its
    /// mass and stiffness to the interface. For a statically determinate interface they are
    /// B's rigid-body modes and the stiffness loading vanishes.
    pub fn of_component(
        model_b: &FeModel,
        interface_b: &[usize],
        held_b: &[usize],
    ) -> Result<Self> {
        let partition = Partition::from_dofs(model_b, interface_b, held_b)?;
        let mut problem = InteriorProblem::on(model_b, partition, SolverPath::Auto)?;
        let psi_ji = problem.constraint_modes()?;
        let p = &problem.partition;
        let psi = p.assemble(p.unit_top(0).as_ref(), psi_ji.as_ref());
        let sym = |a: Mat<f64>| {
            let n = a.nrows();
            Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
        };
        Ok(Self {
            mass: sym(psi.transpose() * model_b.m.mul(psi.as_ref())),
            stiffness: sym(psi.transpose() * model_b.k.mul(psi.as_ref())),
        })
    }

    /// The loading by a rigid body of `mass` (kg) and inertia `inertia` (kg m², about its
    /// mass centre `centre`, m) attached at the 6-DOF node at `point` (x, y, z, θx, θy, θz):
    /// with $c$ = centre − point and $\tilde c$ its cross-product matrix,
    /// $M = \begin{bmatrix} mI & -m\tilde c \\ m\tilde c & J - m\tilde c^2 \end{bmatrix}$,
    /// no stiffness.
    pub fn rigid_body(
        mass: f64,
        inertia: [[f64; 3]; 3],
        centre: [f64; 3],
        point: [f64; 3],
    ) -> Self {
        let c = [
            centre[0] - point[0],
            centre[1] - point[1],
            centre[2] - point[2],
        ];
        let cx = [[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]];
        let m = Mat::from_fn(6, 6, |i, j| match (i / 3, j / 3) {
            (0, 0) => {
                if i == j {
                    mass
                } else {
                    0.0
                }
            }
            (0, 1) => -mass * cx[i][j - 3],
            (1, 0) => mass * cx[i - 3][j],
            _ => {
                let (a, b) = (i - 3, j - 3);
                let cxcx: f64 = (0..3).map(|k| cx[a][k] * cx[k][b]).sum();
                inertia[a][b] - mass * cxcx
            }
        });
        Self {
            mass: m,
            stiffness: Mat::zeros(6, 6),
        }
    }
}

/// One loaded interface of the component: its DOF and what the neighbours add there.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedInterface {
    /// The interface DOF of the loaded component (0-based), in the loading's order.
    pub dofs: Vec<usize>,
    /// What the attached component adds there.
    pub loading: InterfaceLoading,
}

/// $\Phi^{BH}$: the lowest normal modes of $(\mathcal{K}^A, \mathcal{M}^A)$, the component's
/// own matrices with each interface's loading added on its DOF (Eqs. 18–20, 22). Several
/// interfaces (several neighbours) add their loadings, the straightforward generalisation the
/// paper mentions but does not give. `modes` counts every loaded mode, rigid ones included,
/// or keeps those up to a frequency. Dense: components up to [`COMPLETE_EIGEN_LIMIT`] DOF.
///
/// `held` DOF (a component grounded elsewhere) are held at zero: zero rows of the basis.
pub fn benfield_hruda(
    model: &FeModel,
    interfaces: &[LoadedInterface],
    held: &[usize],
    modes: ModeSelection,
) -> Result<Basis> {
    let n = model.dof_count();
    if n > COMPLETE_EIGEN_LIMIT {
        return Err(Error::TooLarge {
            method: "Benfield-Hruda",
            step: Some("dense loaded eigenproblem"),
            dofs: n,
            limit: COMPLETE_EIGEN_LIMIT,
        });
    }
    let mut k = model.k_dense();
    let mut m = model.m_dense();
    for (c, face) in interfaces.iter().enumerate() {
        let ni = face.dofs.len();
        if face.loading.mass.nrows() != ni || face.loading.stiffness.nrows() != ni {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: DofSetName::Numbered {
                    what: "interface",
                    number: c + 1,
                },
                problem: DofSetProblem::Shape {
                    what: "rows of its loading",
                    found: if face.loading.mass.nrows() != ni {
                        face.loading.mass.nrows()
                    } else {
                        face.loading.stiffness.nrows()
                    },
                    expected: ni,
                },
            }));
        }
        let mut taken = vec![0u8; n];
        super::partition::check_dof_set(
            model,
            DofSetName::Numbered {
                what: "interface",
                number: c + 1,
            },
            &face.dofs,
            &mut taken,
            1,
        )?;
        for (a, &da) in face.dofs.iter().enumerate() {
            for (b, &db) in face.dofs.iter().enumerate() {
                k[(da, db)] += face.loading.stiffness[(a, b)];
                m[(da, db)] += face.loading.mass[(a, b)];
            }
        }
    }
    if !held.is_empty() {
        let mut taken = vec![0u8; n];
        super::partition::check_dof_set(model, "held", held, &mut taken, 1)?;
    }
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let k = Mat::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let m = Mat::from_fn(free.len(), free.len(), |i, j| m[(free[i], free[j])]);
    let started = std::time::Instant::now();
    let eig = generalized_eigen(k.as_ref(), m.as_ref(), "loaded-interface")?;
    let hz = eig.hz();
    let kept = modes.count(&hz)?;
    let mut psi = Mat::<f64>::zeros(n, kept);
    for c in 0..kept {
        for (r, &d) in free.iter().enumerate() {
            psi[(d, c)] = eig.vectors[(r, c)];
        }
    }
    let statistics = ReductionStatistics {
        eigen_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    };
    Ok(Basis {
        method: Method::BenfieldHruda,
        psi,
        columns: (0..kept)
            .map(|j| Column {
                kind: ColumnKind::Loaded { hz: hz[j] },
                dof: None,
                label: format!("loaded {} ({:.4} Hz)", j + 1, hz[j]),
            })
            .collect(),
        statistics,
    })
}
