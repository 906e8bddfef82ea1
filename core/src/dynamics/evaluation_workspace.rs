//! Buffers an integration reuses from one evaluation of the equations of motion to the next,
//! so that a step allocates nothing whose size the system already fixes.

use nalgebra::{DMatrix, DVector, Matrix6};

use super::{System, constraint_rows::Rows};
use crate::linalg::BlockSaddlePointWorkspace;

/// One body's rows of the mass matrix and forces (see [`System::accelerations`]).
#[derive(Debug, Clone)]
pub(super) struct BodyBlocks {
    /// Frame block $M_{ff}$ (translations, then body-axis rotations).
    pub(super) m_ff: Matrix6<f64>,
    /// Frame–modal coupling $M_{fz}$, 6 × k (6 × 0 for a rigid body).
    pub(super) m_fz: DMatrix<f64>,
    /// Generalised forces $Q$, frame then modal.
    pub(super) q: DVector<f64>,
    /// The modal forces as they are summed (k entries).
    pub(super) q_z: DVector<f64>,
    /// The modal velocity-dependent inertia forces (k entries).
    pub(super) a_z: DVector<f64>,
    /// Scratch of the Coriolis sums, one 3 × 3 per mode.
    pub(super) coriolis: Vec<nalgebra::Matrix3<f64>>,
    /// Scratch of a stiffened body's $K_{\sigma,i}z$ (k entries).
    pub(super) coupling: DVector<f64>,
}

impl BodyBlocks {
    /// Blocks of a body with `k` modal coordinates, zero.
    pub(super) fn zeros(k: usize) -> Self {
        Self {
            m_ff: Matrix6::zeros(),
            m_fz: DMatrix::zeros(6, k),
            q: DVector::zeros(6 + k),
            q_z: DVector::zeros(k),
            a_z: DVector::zeros(k),
            coriolis: Vec::new(),
            coupling: DVector::zeros(k),
        }
    }
}

/// One body's part of the block elimination of [`System::accelerations`].
#[derive(Debug, Clone)]
pub(super) struct BodyElimination {
    pub(super) blocks: BodyBlocks,
    /// The constraint rows that touch its modal coordinates.
    pub(super) active: Vec<usize>,
    /// Per row that may touch them, the modal column found nonzero at the last call: looked
    /// at first.
    pub(super) nonzero_hint: Vec<usize>,
    /// $W = [M_{zf}, C_z^T, Q_z]$, k × (7 + active rows).
    pub(super) w: DMatrix<f64>,
    /// $X = M_{zz}^{-1} W$.
    pub(super) x: DMatrix<f64>,
    /// $W_{:, :6+n_a}^T X$, (6 + active rows) × (7 + active rows).
    pub(super) product: DMatrix<f64>,
    /// $X_{:, :6}\,\dot v_f$, then the modal accelerations.
    pub(super) frame_part: DVector<f64>,
}

/// Buffers of [`System::accelerations`]' block elimination.
#[derive(Debug, Clone)]
pub(super) struct SaddlePointWorkspace {
    pub(super) kkt: DMatrix<f64>,
    /// The frame rows of `kkt`'s layout (6 per body).
    pub(super) kkt_frames: usize,
    pub(super) rhs: DVector<f64>,
    pub(super) bodies: Vec<BodyElimination>,
    pub(super) blocks: BlockSaddlePointWorkspace,
    /// The solution $x$ (accelerations, or a correction in velocity coordinates).
    pub(super) x: DVector<f64>,
    /// Whether `blocks` and `bodies` hold the factors of the last system solved (a
    /// [`System::saddle_point`] that succeeded), for [`System::resolve_saddle_point`].
    pub(super) factored: bool,
}

/// Everything one integration reuses between evaluations: the constraint rows, the block
/// elimination's matrices and its solution.
#[derive(Debug, Clone)]
pub struct EvaluationWorkspace {
    /// Per body, the rows that may touch its modal coordinates ([`System::modal_rows`]).
    pub(super) modal_rows: Vec<Vec<usize>>,
    pub(super) rows: Rows,
    /// The holonomic rows of `rows` and their residuals (the position projection).
    pub(super) holonomic_c: DMatrix<f64>,
    pub(super) holonomic_phi: DVector<f64>,
    pub(super) holonomic_modal_rows: Vec<Vec<usize>>,
    /// Each row's position among the holonomic rows.
    pub(super) position: Vec<usize>,
    pub(super) residual: DVector<f64>,
    /// The elimination of the evaluations and the velocity projection (every row).
    pub(super) saddle: SaddlePointWorkspace,
    /// The elimination of the position projection (the holonomic rows only): its own
    /// buffers, so that neither is reshaped, zeroed and refilled at every step when the
    /// two have different rows (mean axes' rotational rows are not holonomic).
    pub(super) held_saddle: SaddlePointWorkspace,
    /// Evaluations of the equations of motion made with these buffers.
    pub(super) evaluations: usize,
}

impl EvaluationWorkspace {
    /// Buffers sized for `system`.
    pub fn new(system: &System) -> Self {
        let bodies = system
            .bodies
            .iter()
            .map(|body| {
                let k = body.velocity_count() - 6;
                BodyElimination {
                    blocks: BodyBlocks::zeros(k),
                    active: Vec::new(),
                    nonzero_hint: Vec::new(),
                    w: DMatrix::zeros(0, 0),
                    x: DMatrix::zeros(0, 0),
                    product: DMatrix::zeros(0, 0),
                    frame_part: DVector::zeros(k),
                }
            })
            .collect();
        let saddle = SaddlePointWorkspace {
            kkt: DMatrix::zeros(0, 0),
            kkt_frames: 0,
            rhs: DVector::zeros(0),
            bodies,
            blocks: BlockSaddlePointWorkspace::default(),
            x: DVector::zeros(system.nv()),
            factored: false,
        };
        Self {
            modal_rows: system.modal_rows(),
            rows: Rows::empty(),
            holonomic_c: DMatrix::zeros(0, 0),
            holonomic_phi: DVector::zeros(0),
            holonomic_modal_rows: Vec::new(),
            position: Vec::new(),
            residual: DVector::zeros(0),
            held_saddle: saddle.clone(),
            saddle,
            evaluations: 0,
        }
    }

    /// The last solution: accelerations after [`System::accelerations`], the correction after
    /// a projection step.
    pub(super) fn solution(&self) -> &DVector<f64> {
        &self.saddle.x
    }
}
