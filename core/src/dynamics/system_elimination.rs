//! The block elimination of the system's saddle-point equations (see
//! [`System::accelerations`]).

use nalgebra::{DMatrix, DVector, Matrix3};

use super::{
    Body, DynamicsError, State, System,
    constraint_rows::ConstraintRows,
    evaluation_workspace::{BodyElimination, SaddlePointWorkspace},
};
use crate::{
    Error, Result,
    linalg::{LinalgError, block_saddle_point_solve, reshape, resize},
};

/// The `candidates` constraint rows that touch the modal coordinates (`c_z`, their columns)
/// into `active`: each looked for at the column that was nonzero at the last call first
/// (`hints`), along the whole row only when that one is zero.
fn active_rows(
    c_z: nalgebra::DMatrixView<'_, f64>,
    candidates: &[usize],
    hints: &mut Vec<usize>,
    active: &mut Vec<usize>,
) {
    let k = c_z.ncols();
    active.clear();
    hints.resize(candidates.len(), 0);
    for (&r, hint) in candidates.iter().zip(hints.iter_mut()) {
        let row = c_z.row(r);
        let touches = (*hint < k && row[*hint] != 0.0)
            || match row.iter().position(|&x| x != 0.0) {
                Some(j) => {
                    *hint = j;
                    true
                }
                None => false,
            };
        if touches {
            active.push(r);
        }
    }
}

/// $[M_{fz}; C_z]X = W_{:, ..6 + n_a}^TX$ into `product` ((6 + `na`) × (7 + `na`)): one SIMD
/// product (faer's kernels), where nalgebra's `tr_mul` takes a dot product per entry (which
/// dominated the elimination on the plank's 90 modal coordinates).
fn coupling_product(w: &DMatrix<f64>, x: &DMatrix<f64>, na: usize, product: &mut DMatrix<f64>) {
    let k = w.nrows();
    reshape(product, 6 + na, 7 + na);
    let wf = faer::MatRef::from_column_major_slice(w.as_slice(), k, 7 + na);
    let xf = faer::MatRef::from_column_major_slice(x.as_slice(), k, 7 + na);
    faer::linalg::matmul::matmul(
        faer::MatMut::from_column_major_slice_mut(product.as_mut_slice(), 6 + na, 7 + na),
        faer::Accum::Replace,
        wf.subcols(0, 6 + na).transpose(),
        xf,
        1.0,
        faer::Par::Seq,
    );
}

impl System {
    /// $x$ of $\begin{bmatrix} M & C^T \\ C & 0\end{bmatrix}
    /// \begin{bmatrix} x \\ \lambda\end{bmatrix} = \begin{bmatrix} f \\ g\end{bmatrix}$
    /// with $f = Q$ when `forces` (the accelerations) or $f = 0$ (the mass-weighted
    /// correction of [`Self::project`]), by the block elimination of
    /// [`Self::accelerations`], into `ws.x`; `moments` are the bodies' $H_c$ at `s`
    /// ([`Self::modal_moments`]).
    pub(super) fn saddle_point(
        &self,
        s: &State,
        moments: &[Vec<Matrix3<f64>>],
        rows: ConstraintRows<'_>,
        forces: bool,
        ws: &mut SaddlePointWorkspace,
    ) -> Result<()> {
        let (c, g) = (rows.c, rows.g);
        let nb = self.bodies.len();
        let nr = c.nrows();
        let nf = 6 * nb;
        let n = nf + nr;
        // Every entry the elimination writes is overwritten below (the frame blocks and the
        // frame–constraint blocks) or accumulated into the constraint block, which alone is
        // cleared; the frame blocks of two bodies stay zero from allocation. A workspace of
        // another layout of the same size is cleared whole.
        if ws.kkt.shape() == (n, n) && ws.kkt_frames == nf {
            ws.kkt.view_mut((nf, nf), (nr, nr)).fill(0.0);
        } else {
            ws.kkt = DMatrix::zeros(n, n);
            ws.kkt_frames = nf;
        }
        resize(&mut ws.rhs, n);
        let (kkt, rhs) = (&mut ws.kkt, &mut ws.rhs);
        rhs.rows_mut(nf, nr).copy_from(g);
        // The largest diagonal entry of the frame blocks before elimination: the scale
        // the eliminated frame block's pivots are judged against.
        let mut frame_scale = 0.0f64;
        for (b, (body, work)) in self.bodies.iter().zip(ws.bodies.iter_mut()).enumerate() {
            self.body_blocks_into(b, s, &moments[b], forces, &mut work.blocks);
            let blocks = &work.blocks;
            frame_scale = frame_scale.max(blocks.m_ff.diagonal().max());
            let (vo, fo) = (self.v_off[b], 6 * b);
            kkt.view_mut((fo, fo), (6, 6)).copy_from(&blocks.m_ff);
            rhs.rows_mut(fo, 6).copy_from(&blocks.q.rows(0, 6));
            let c_f = c.columns(vo, 6);
            kkt.view_mut((nf, fo), (nr, 6)).copy_from(&c_f);
            kkt.view_mut((fo, nf), (6, nr)).copy_from(&c_f.transpose());
            let Body::Flexible(fb) = body else {
                continue;
            };
            let k = fb.modes();
            let c_z = c.columns(vo + 6, k);
            // Only the constraint rows that touch the modal coordinates (a joint on another
            // body has none here), looked for among those that may: at the column that was
            // nonzero at the last call first, along the whole row only when that one is zero
            // (the scan of every row was a twentieth of a full model's simulation).
            active_rows(
                c_z,
                &rows.modal_rows[b],
                &mut work.nonzero_hint,
                &mut work.active,
            );
            let active = &work.active;
            let na = active.len();
            // W = [M_zf, C_z^T, Q_z] and X = M_zz^-1 W (k × (7 + active rows)).
            reshape(&mut work.w, k, 7 + na);
            let w = &mut work.w;
            w.columns_mut(0, 6).tr_copy_from(&blocks.m_fz);
            for (i, &r) in active.iter().enumerate() {
                w.column_mut(6 + i).tr_copy_from(&c_z.row(r));
            }
            w.column_mut(6 + na).copy_from(&blocks.q.rows(6, k));
            reshape(&mut work.x, k, 7 + na);
            fb.m_zz_inverse.solve_into(w, &mut work.x);
            let x = &work.x;
            // [M_fz; C_z] X = W[:, ..6 + na]^T X, subtracted from the frame and constraint
            // rows and their right-hand side.
            // One SIMD product (faer's kernels): nalgebra's `tr_mul` takes a dot product per
            // entry, which dominated the elimination on the plank's 90 modal coordinates.
            coupling_product(w, x, na, &mut work.product);
            let product = &work.product;
            let place = |p: usize| if p < 6 { fo + p } else { nf + active[p - 6] };
            for p in 0..6 + na {
                let row = place(p);
                for q in 0..6 + na {
                    kkt[(row, place(q))] -= product[(p, q)];
                }
                rhs[row] -= product[(p, 6 + na)];
            }
        }
        ws.factored = false;
        let solution = block_saddle_point_solve(kkt, rhs, nf, frame_scale, &mut ws.blocks);
        // The force column is this right-hand side's (zero without forces).
        self.recover(solution, true, &mut ws.bodies, &mut ws.x)?;
        ws.factored = true;
        Ok(())
    }

    /// $x$ of [`Self::saddle_point`] with $f = 0$ and the constraint right-hand side `g`
    /// (the mass-weighted correction of [`Self::project`]), from the factors the last
    /// successful `saddle_point` left in `ws`: the system $M$ and $C$ of that call's state
    /// and rows, for the cost of the triangular solves and the recovery of the modal
    /// coordinates. At that state it is the correction a new `saddle_point` gives, to the
    /// bit ($f = 0$ makes the eliminated right-hand side $[0; g]$ exactly).
    pub(super) fn resolve_saddle_point(
        &self,
        g: &DVector<f64>,
        ws: &mut SaddlePointWorkspace,
    ) -> Result<()> {
        let nf = 6 * self.bodies.len();
        if !ws.factored || ws.kkt.nrows() != nf + g.len() {
            return Err(DynamicsError::Misuse {
                what: "a correction from factors no evaluation of this system left",
            }
            .into());
        }
        resize(&mut ws.rhs, nf + g.len());
        ws.rhs.rows_mut(0, nf).fill(0.0);
        ws.rhs.rows_mut(nf, g.len()).copy_from(g);
        let solution = ws.blocks.resolve(&ws.rhs);
        self.recover(solution, false, &mut ws.bodies, &mut ws.x)
    }

    /// The velocity-coordinate solution `x` from the reduced system's `solution` (frame
    /// unknowns, then multipliers): the frame rows as they are, each deformable body's modal
    /// rows recovered from its elimination $X = M_{zz}^{-1}[M_{zf}, C_z^T, Q_z]$, its
    /// force column read when `forces` (else $f = 0$: the column is not this right-hand
    /// side's).
    fn recover(
        &self,
        solution: &DVector<f64>,
        forces: bool,
        bodies: &mut [BodyElimination],
        x: &mut DVector<f64>,
    ) -> Result<()> {
        let nf = 6 * self.bodies.len();
        let lambda = solution.rows(nf, solution.len() - nf);
        resize(x, self.nv());
        let vdot = x;
        for (b, (body, work)) in self.bodies.iter().zip(bodies.iter_mut()).enumerate() {
            let (vo, fo) = (self.v_off[b], 6 * b);
            let a_f = solution.rows(fo, 6);
            vdot.rows_mut(vo, 6).copy_from(&a_f);
            // A deformable body's modal coordinates were eliminated: recovered here.
            if matches!(body, Body::Flexible(_)) {
                let (x, active) = (&work.x, &work.active);
                let (k, na) = (x.nrows(), active.len());
                let z_dd = &mut work.frame_part;
                resize(z_dd, k);
                // X_{:, 6 + na} - X_{:, ..6} a_f (the force column 0 without forces), then
                // minus λ_r times each active column.
                z_dd.gemv(1.0, &x.columns(0, 6), &a_f, 0.0);
                if forces {
                    for (z, &xr) in z_dd.iter_mut().zip(x.column(6 + na).iter()) {
                        *z = xr - *z;
                    }
                } else {
                    for z in z_dd.iter_mut() {
                        *z = 0.0 - *z;
                    }
                }
                for (i, &r) in active.iter().enumerate() {
                    z_dd.axpy(-lambda[r], &x.column(6 + i), 1.0);
                }
                vdot.rows_mut(vo + 6, k).copy_from(z_dd);
            }
        }
        if vdot.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Error::Linalg(LinalgError::SingularMatrix {
                matrix: "system mass and constraints".into(),
                rcond: None,
            }))
        }
    }
}
