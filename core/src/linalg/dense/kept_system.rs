//! What [`block_saddle_point_solve`](super::block_saddle_point_solve) solves after the
//! definite frame blocks are eliminated: the scaled Cholesky factor of the constraint block
//! $S$ and the system of the frame blocks it kept.

use nalgebra::{DMatrix, DVector};

use super::buffers::{reshape, resize};
use super::range_space::{FRAME_BLOCK, RANGE_SPACE_FRAME_PIVOT, pivots_ok};
use super::saddle_point::saddle_point_solve;
use super::small_cholesky::SmallCholesky;

/// The Jacobi-scaled Cholesky factor of $S$, given the constraint block `neg_s` $= -S$ of
/// [`block_saddle_point_solve`], when $S$ is clearly positive definite (squared pivots above
/// `RANGE_SPACE_PIVOT` of the largest after scaling, so constraint rows of different units
/// compare); refused otherwise (redundant constraints, or rows only a kept block touches).
#[derive(Debug, Clone, Default)]
pub(super) struct ScaledSchur {
    cholesky: SmallCholesky,
    scale: Vec<f64>,
}

impl ScaledSchur {
    /// Factors $S = -$`neg_s`; `false` when it is not clearly definite.
    pub(super) fn factor(&mut self, neg_s: &DMatrix<f64>) -> bool {
        let nr = neg_s.nrows();
        let Self { cholesky, scale } = self;
        scale.clear();
        scale.extend((0..nr).map(|i| {
            let d = -neg_s[(i, i)];
            if d > 0.0 { 1.0 / d.sqrt() } else { 1.0 }
        }));
        cholesky.factor(nr, |i, j| -neg_s[(i, j)] * scale[i] * scale[j])
            && (nr == 0 || pivots_ok(cholesky.diagonal()))
    }

    /// $x \leftarrow S^{-1}x$.
    pub(super) fn solve_in_place(&self, x: &mut [f64]) {
        self.forward_in_place(x);
        self.backward_in_place(x);
    }

    /// $x \leftarrow L^{-1}Dx$ where $DSD = LL^T$ ($D$ the Jacobi scaling): with
    /// $Y = L^{-1}DB$, $B^TS^{-1}B = Y^TY$.
    pub(super) fn forward_in_place(&self, x: &mut [f64]) {
        for (v, s) in x.iter_mut().zip(&self.scale) {
            *v *= s;
        }
        self.cholesky.forward_in_place(x);
    }

    /// $x \leftarrow DL^{-T}x$: with [`Self::forward_in_place`], $S^{-1}x$.
    pub(super) fn backward_in_place(&self, x: &mut [f64]) {
        self.cholesky.backward_in_place(x);
        for (v, s) in x.iter_mut().zip(&self.scale) {
            *v *= s;
        }
    }
}

/// The kept frame blocks of [`block_saddle_point_solve`], their coupling to every constraint
/// row, their forces, the factors and the solution: buffers kept from one call to the next.
#[derive(Debug, Clone, Default)]
pub(super) struct KeptSystem {
    /// $A_S$, $B_S$ and $f_S$ of the kept blocks.
    a_s: DMatrix<f64>,
    b_s: DMatrix<f64>,
    f_s: DVector<f64>,
    /// $Y_B = L^{-1}DB_S$ ($DSD = LL^T$).
    columns: DMatrix<f64>,
    /// $y_g = L^{-1}Dg$.
    y_g: DVector<f64>,
    /// The factor of $A_S + B_S^TS^{-1}B_S$.
    dual: SmallCholesky,
    /// The kept frames' unknowns and the multipliers.
    pub(super) x: DVector<f64>,
    pub(super) lambda: DVector<f64>,
}

impl KeptSystem {
    /// $A_S$ and $B_S$ of the `kept` blocks from the system.
    pub(super) fn gather(&mut self, kkt: &DMatrix<f64>, nf: usize, kept: &[usize]) {
        let (top, nr) = (FRAME_BLOCK * kept.len(), kkt.nrows() - nf);
        reshape(&mut self.a_s, top, top);
        self.a_s.fill(0.0);
        reshape(&mut self.b_s, nr, top);
        for (i, &b) in kept.iter().enumerate() {
            let (o, ko) = (FRAME_BLOCK * b, FRAME_BLOCK * i);
            self.a_s
                .view_mut((ko, ko), (FRAME_BLOCK, FRAME_BLOCK))
                .copy_from(&kkt.view((o, o), (FRAME_BLOCK, FRAME_BLOCK)));
            self.b_s
                .columns_mut(ko, FRAME_BLOCK)
                .copy_from(&kkt.view((nf, o), (nr, FRAME_BLOCK)));
        }
    }

    /// $f_S$ of the `kept` blocks from the right-hand side.
    pub(super) fn gather_forces(&mut self, rhs: &DVector<f64>, kept: &[usize]) {
        resize(&mut self.f_s, FRAME_BLOCK * kept.len());
        for (i, &b) in kept.iter().enumerate() {
            self.f_s
                .rows_mut(FRAME_BLOCK * i, FRAME_BLOCK)
                .copy_from(&rhs.rows(FRAME_BLOCK * b, FRAME_BLOCK));
        }
    }

    /// Factors the dual range-space step when $S$ is definite: $S$, $Y_B$ and
    /// $A_S + B_S^TS^{-1}B_S = A_S + Y_B^TY_B$, a positive definite system of six rows per
    /// kept block even where $A_S$ is round-off (Ψ holding the rigid motions: the axis
    /// conditions, among the rows, fix the frame). `false` when either matrix is not clearly
    /// definite (that of the kept frames also judged against `frame_scale`, as the blocks
    /// were); the indefinite factorisation of the reduced system then decides.
    pub(super) fn dual_factor(
        &mut self,
        schur: &mut ScaledSchur,
        neg_s: &DMatrix<f64>,
        frame_scale: f64,
    ) -> bool {
        if !schur.factor(neg_s) {
            return false;
        }
        let (m, nr) = (self.a_s.nrows(), neg_s.nrows());
        // Y_B = L⁻¹DB_S: half solves; the rest follows from Y_B and y_g alone.
        reshape(&mut self.columns, nr, m);
        self.columns.copy_from(&self.b_s);
        for j in 0..m {
            schur.forward_in_place(&mut self.columns.as_mut_slice()[j * nr..(j + 1) * nr]);
        }
        let y_b = &self.columns;
        // A mass matrix of the kept frames, its pivots against the frame blocks' scale too,
        // so frames the rows do not fix (round-off again) go to the indefinite solver.
        self.dual.factor(m, |i, j| {
            self.a_s[(i, j)] + y_b.column(i).dot(&y_b.column(j))
        }) && pivots_ok(self.dual.diagonal())
            && self
                .dual
                .diagonal()
                .all(|p| p * p > RANGE_SPACE_FRAME_PIVOT * frame_scale)
    }

    /// The kept frame blocks' $x_S$ and the multipliers from the factors of
    /// [`Self::dual_factor`] (the dual range-space step): $\lambda = S^{-1}(B_Sx_S - g)$
    /// and $(A_S + B_S^TS^{-1}B_S)\,x_S = f_S + B_S^TS^{-1}g$. `false` when the solution is
    /// not finite.
    pub(super) fn dual_solve(&mut self, schur: &ScaledSchur, g: &DVector<f64>) -> bool {
        let m = self.a_s.nrows();
        resize(&mut self.y_g, g.len());
        self.y_g.copy_from(g);
        schur.forward_in_place(self.y_g.as_mut_slice());
        let (y_b, y_g) = (&self.columns, &self.y_g);
        // x_S from f_S + B_SᵀS⁻¹g = f_S + Y_Bᵀy_g.
        resize(&mut self.x, m);
        self.x.copy_from(&self.f_s);
        self.x.gemv_tr(1.0, y_b, y_g, 1.0);
        self.dual.solve_in_place(self.x.as_mut_slice());
        // λ = S⁻¹(B_Sx_S − g) = DL⁻ᵀ(Y_Bx_S − y_g).
        resize(&mut self.lambda, g.len());
        self.lambda.copy_from(y_g);
        self.lambda.gemv(1.0, y_b, &self.x, -1.0);
        schur.backward_in_place(self.lambda.as_mut_slice());
        self.x
            .iter()
            .chain(self.lambda.iter())
            .all(|v| v.is_finite())
    }

    /// The reduced saddle-point system of the kept blocks and every constraint row by
    /// [`saddle_point_solve`] (redundant constraints, or frames the rows do not fix).
    pub(super) fn reduced_solve(&mut self, schur: &DMatrix<f64>, g: &DVector<f64>) {
        let (top, nr) = (self.a_s.nrows(), schur.nrows());
        let m = top + nr;
        let mut reduced = DMatrix::zeros(m, m);
        reduced.view_mut((0, 0), (top, top)).copy_from(&self.a_s);
        reduced.view_mut((top, 0), (nr, top)).copy_from(&self.b_s);
        reduced
            .view_mut((0, top), (top, nr))
            .tr_copy_from(&self.b_s);
        reduced.view_mut((top, top), (nr, nr)).copy_from(schur);
        let mut reduced_rhs = DVector::zeros(m);
        reduced_rhs.rows_mut(0, top).copy_from(&self.f_s);
        reduced_rhs.rows_mut(top, nr).copy_from(g);
        let solution = saddle_point_solve(&reduced, &reduced_rhs);
        self.x = solution.rows(0, top).into_owned();
        self.lambda = solution.rows(top, nr).into_owned();
    }
}
