//! Diagonalisation of a Ritz-reduced model with modal damping (Spanos–Tsuha Eqs. 28–34) and
//! its actuator-to-sensor frequency response.

use super::ReductionError;
use crate::error::DofSetProblem;
use faer::{Mat, MatRef, c64, linalg::solvers::Solve};

use crate::{
    Error, Result,
    linalg::{GeneralizedEigen, generalized_eigen},
};

/// Where a structure is driven and observed, as DOF indices (0-based) of the full body:
/// unit forces at `inputs` (the columns of P, Eq. 30), displacements at
/// `displacement_outputs` (rows of $H_1$) and velocities at `velocity_outputs` (rows of $H_2$,
/// Eq. 31). The output vector stacks the displacement outputs, then the velocity outputs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IoMap {
    /// Input DOF (actuators).
    pub inputs: Vec<usize>,
    /// DOF whose displacement is measured.
    pub displacement_outputs: Vec<usize>,
    /// DOF whose velocity is measured.
    pub velocity_outputs: Vec<usize>,
}

impl IoMap {
    /// Number of outputs y.
    pub fn output_count(&self) -> usize {
        self.displacement_outputs.len() + self.velocity_outputs.len()
    }

    /// Checks every DOF against a body of `dofs` DOF.
    pub fn check(&self, dofs: usize) -> Result<()> {
        if self.inputs.is_empty() || self.output_count() == 0 {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: "input/output".into(),
                problem: DofSetProblem::NoInputOrOutput,
            }));
        }
        for (set, list) in [
            ("input", &self.inputs),
            ("displacement output", &self.displacement_outputs),
            ("velocity output", &self.velocity_outputs),
        ] {
            if let Some(&d) = list.iter().find(|&&d| d >= dofs) {
                return Err(Error::Reduction(ReductionError::InvalidDofSet {
                    set: set.into(),
                    problem: DofSetProblem::OutOfRange {
                        dof: d,
                        count: dofs,
                    },
                }));
            }
        }
        Ok(())
    }
}

/// A structure in modal coordinates $\xi$ with uniform modal damping (Eqs. 32–34):
///
/// $$\ddot\xi + 2\zeta\Omega\dot\xi + \Omega^2\xi = Bu,\qquad y = C_1\xi + C_2\dot\xi,$$
///
/// $B = [\Phi\Psi]^T P$, $C_1 = H_1[\Phi\Psi]$, $C_2 = H_2[\Phi\Psi]$, with $\Psi$ the
/// mass-normalised eigenvectors of the reduced pair $(\Phi^TK\Phi, \Phi^TM\Phi)$ (Eqs. 28–29).
#[derive(Debug, Clone)]
pub struct ModalModel {
    /// Mass-normalised mode shapes on the body's DOF, $\Phi\Psi$ (n × p).
    pub shapes: Mat<f64>,
    /// Natural frequencies $\omega_i$, rad/s, ascending (0 for rigid-body modes).
    pub omega: Vec<f64>,
    /// The modal damping ratio ζ of every elastic mode.
    pub zeta: f64,
    /// Number of rigid-body modes (the first ones).
    pub rigid: usize,
    /// $B$, p × inputs (Eq. 34).
    pub b: Mat<f64>,
    /// $C_1$, outputs × p.
    pub c1: Mat<f64>,
    /// $C_2$, outputs × p.
    pub c2: Mat<f64>,
}

/// An eigenvalue below this fraction of the largest is a rigid-body mode.
const RIGID_FRACTION: f64 = 1e-9;

impl ModalModel {
    /// Diagonalises the reduced model $\tilde K = \Phi^TK\Phi$, $\tilde M = \Phi^TM\Phi$ of a
    /// basis `phi` (n × r; `phi` = I for the full model) and maps the I/O through the shapes.
    pub fn new(
        k_reduced: MatRef<'_, f64>,
        m_reduced: MatRef<'_, f64>,
        phi: MatRef<'_, f64>,
        io: &IoMap,
        zeta: f64,
    ) -> Result<Self> {
        io.check(phi.nrows())?;
        let eig = generalized_eigen(k_reduced, m_reduced, "reduced")?;
        Self::of_eigen(&eig, phi, io, zeta)
    }

    /// [`Self::new`] from the reduced model's checked eigenpairs `eig`, when they are needed
    /// for more than the I/O (the shapes drawn on every DOF): one eigensolution, not two.
    pub fn of_eigen(
        eig: &GeneralizedEigen,
        phi: MatRef<'_, f64>,
        io: &IoMap,
        zeta: f64,
    ) -> Result<Self> {
        io.check(phi.nrows())?;
        let shapes = phi * &eig.vectors;
        let top = eig.values.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
        let rigid = eig
            .values
            .iter()
            .take_while(|&&v| v <= RIGID_FRACTION * top)
            .count();
        let omega: Vec<f64> = eig
            .values
            .iter()
            .enumerate()
            .map(|(i, &v)| if i < rigid { 0.0 } else { v.max(0.0).sqrt() })
            .collect();
        Ok(Self::from_shapes(shapes, omega, rigid, io, zeta))
    }

    /// A modal model driven by load vectors `loads` (n × inputs, over all DOF: an interface's
    /// master loads, say) and observed at the same places, collocated: $B = \Phi^TL$,
    /// $C_1 = L^T\Phi$ (the work-conjugate displacements), no velocity outputs.
    pub fn from_loads(
        shapes: Mat<f64>,
        omega: Vec<f64>,
        rigid: usize,
        loads: MatRef<'_, f64>,
        zeta: f64,
    ) -> Self {
        let b = shapes.transpose() * loads;
        let c1 = b.transpose().to_owned();
        let c2 = Mat::zeros(c1.nrows(), c1.ncols());
        Self {
            shapes,
            omega,
            zeta,
            rigid,
            b,
            c1,
            c2,
        }
    }

    /// A modal model from mass-normalised shapes and their frequencies (rad/s).
    pub fn from_shapes(
        shapes: Mat<f64>,
        omega: Vec<f64>,
        rigid: usize,
        io: &IoMap,
        zeta: f64,
    ) -> Self {
        let p = omega.len();
        let b = Mat::from_fn(p, io.inputs.len(), |i, j| shapes[(io.inputs[j], i)]);
        let nd = io.displacement_outputs.len();
        let y = io.output_count();
        let c1 = Mat::from_fn(y, p, |r, i| {
            if r < nd {
                shapes[(io.displacement_outputs[r], i)]
            } else {
                0.0
            }
        });
        let c2 = Mat::from_fn(y, p, |r, i| {
            if r >= nd {
                shapes[(io.velocity_outputs[r - nd], i)]
            } else {
                0.0
            }
        });
        Self {
            shapes,
            omega,
            zeta,
            rigid,
            b,
            c1,
            c2,
        }
    }

    /// Number of modes p.
    pub fn mode_count(&self) -> usize {
        self.omega.len()
    }

    /// Natural frequencies, Hz.
    pub fn hz(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect()
    }

    /// The model with only the modes `keep` (indices, in the order given).
    pub fn keep(&self, keep: &[usize]) -> Self {
        let mut order = keep.to_vec();
        order.sort_unstable();
        order.dedup();
        let rigid = order.iter().filter(|&&i| i < self.rigid).count();
        Self {
            shapes: Mat::from_fn(self.shapes.nrows(), order.len(), |r, c| {
                self.shapes[(r, order[c])]
            }),
            omega: order.iter().map(|&i| self.omega[i]).collect(),
            zeta: self.zeta,
            rigid,
            b: Mat::from_fn(order.len(), self.b.ncols(), |r, c| self.b[(order[r], c)]),
            c1: Mat::from_fn(self.c1.nrows(), order.len(), |r, c| self.c1[(r, order[c])]),
            c2: Mat::from_fn(self.c2.nrows(), order.len(), |r, c| self.c2[(r, order[c])]),
        }
    }

    /// $G(j\omega) = \sum_i (c_{1i} + j\omega c_{2i})\, b_i / (\omega_i^2 - \omega^2 +
    /// 2j\zeta\omega_i\omega)$, outputs × inputs, at `omega` rad/s (> 0 when the model has
    /// rigid-body modes, whose terms are $(c_{1i} + j\omega c_{2i}) b_i / (-\omega^2)$).
    pub fn frf(&self, omega: f64) -> Mat<c64> {
        let (y, u) = (self.c1.nrows(), self.b.ncols());
        let mut g = Mat::<c64>::zeros(y, u);
        for i in 0..self.mode_count() {
            let wi = self.omega[i];
            let den = c64::new(wi * wi - omega * omega, 2.0 * self.zeta * wi * omega);
            let inv = c64::new(1.0, 0.0) / den;
            for r in 0..y {
                let c = c64::new(self.c1[(r, i)], omega * self.c2[(r, i)]) * inv;
                for s in 0..u {
                    g[(r, s)] += c * self.b[(i, s)];
                }
            }
        }
        g
    }

    /// The elastic modes in first-order form with interleaved states $(\xi_i, \dot\xi_i)$:
    /// the 2 × 2 blocks $A_i = [0\ 1;\ -\omega_i^2\ -2\zeta\omega_i]$ (Eq. 35), $\mathcal B$
    /// (2p_e × inputs) and $\mathcal C$ (outputs × 2p_e).
    pub fn elastic_state_space(&self) -> StateSpace {
        let elastic: Vec<usize> = (self.rigid..self.mode_count()).collect();
        let pe = elastic.len();
        let blocks: Vec<[[f64; 2]; 2]> = elastic
            .iter()
            .map(|&i| {
                let w = self.omega[i];
                [[0.0, 1.0], [-w * w, -2.0 * self.zeta * w]]
            })
            .collect();
        let a = Mat::from_fn(2 * pe, 2 * pe, |r, c| {
            if r / 2 == c / 2 {
                blocks[r / 2][r % 2][c % 2]
            } else {
                0.0
            }
        });
        let b = Mat::from_fn(2 * pe, self.b.ncols(), |r, s| {
            if r % 2 == 1 {
                self.b[(elastic[r / 2], s)]
            } else {
                0.0
            }
        });
        let c = Mat::from_fn(self.c1.nrows(), 2 * pe, |r, s| {
            let i = elastic[s / 2];
            if s % 2 == 0 {
                self.c1[(r, i)]
            } else {
                self.c2[(r, i)]
            }
        });
        StateSpace {
            a,
            b,
            c,
            blocks: Some(blocks),
        }
    }
}

/// $\dot\chi = A\chi + \mathcal B u$, $y = \mathcal C\chi$.
#[derive(Debug, Clone)]
pub struct StateSpace {
    /// A, n × n.
    pub a: Mat<f64>,
    /// $\mathcal B$, n × inputs.
    pub b: Mat<f64>,
    /// $\mathcal C$, outputs × n.
    pub c: Mat<f64>,
    /// The 2 × 2 diagonal blocks when A is block diagonal (modal form).
    pub blocks: Option<Vec<[[f64; 2]; 2]>>,
}

impl StateSpace {
    /// Number of states.
    pub fn order(&self) -> usize {
        self.a.nrows()
    }

    /// $G(j\omega) = \mathcal C (j\omega I - A)^{-1}\mathcal B$ by a dense LU solve.
    pub fn frf(&self, omega: f64) -> Mat<c64> {
        let n = self.order();
        if n == 0 {
            return Mat::zeros(self.c.nrows(), self.b.ncols());
        }
        let lhs = Mat::from_fn(n, n, |r, c| {
            let d = if r == c { omega } else { 0.0 };
            c64::new(-self.a[(r, c)], d)
        });
        let rhs = Mat::from_fn(n, self.b.ncols(), |r, c| c64::new(self.b[(r, c)], 0.0));
        let x = lhs.partial_piv_lu().solve(&rhs);
        let c = Mat::from_fn(self.c.nrows(), n, |r, s| c64::new(self.c[(r, s)], 0.0));
        &c * &x
    }
}
