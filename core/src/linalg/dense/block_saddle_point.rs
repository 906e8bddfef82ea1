//! The range-space method for a multibody system's saddle-point system, body by body: every
//! clearly definite 6 × 6 frame block eliminated, what is left solved whole (the frame blocks
//! of the mass matrix couple only through the constraints).

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

use super::buffers::resize;
use super::kept_system::{KeptSystem, ScaledSchur};
use super::range_space::{FRAME_BLOCK, RANGE_SPACE_FRAME_PIVOT, pivots_ok};
use super::saddle_point::saddle_point_solve;

/// The saddle-point system $\begin{bmatrix} A & B^T \\ B & -D\end{bmatrix}
/// \begin{bmatrix} x \\ \lambda\end{bmatrix} = \begin{bmatrix} f \\ g\end{bmatrix}$ whose
/// leading `nf` × `nf` block $A$ is block diagonal in 6 × 6 blocks $A_b$ (a multibody system's
/// frame blocks: bodies couple only through the constraints $B$), by the range-space method
/// applied body by body. Every $A_b$ that is clearly positive definite is eliminated,
/// $x_b = A_b^{-1}(f_b - B_b^T\lambda)$, which adds $-B_bA_b^{-1}B_b^T$ to the constraint block
/// only on the rows $B_b$ touches (a link's two joints, not the whole system). What remains is
/// solved whole:
///
/// - no block left: $S = D + \sum_b B_bA_b^{-1}B_b^T$ is positive definite when the
///   constraints are independent, and $\lambda = S^{-1}(\sum_b B_bA_b^{-1}f_b - g)$ by a
///   Jacobi-scaled Cholesky factorisation (the frame block $M_{ff} - M_{fz}M_{zz}^{-1}M_{zf}$
///   is a Schur complement of the positive definite mass matrix: the common case);
/// - blocks left (a frame block that is round-off because Ψ holds the rigid motions, Eq. 3.38
///   on mean axes) and $S$ definite: the multipliers are eliminated in turn,
///   $(A_S + B_S^TS^{-1}B_S)\,x_S = f_S + B_S^TS^{-1}g$ (the constraint rows, the axis
///   conditions among them, fix the kept frames), again by Cholesky factorisations;
/// - otherwise ($S$ or that matrix not clearly definite: redundant constraints, rows only a
///   kept block touches): the reduced saddle-point system of the kept blocks and all
///   constraint rows by [`saddle_point_solve`] (scaled $LBL^T$, or the pseudo-inverse).
///
/// A block is clearly definite when its Cholesky factor's squared pivots all exceed
/// `RANGE_SPACE_FRAME_PIVOT` of `frame_scale` (the largest diagonal entry of the frame
/// blocks before the modal coordinates were eliminated: a mass or a moment of inertia) and
/// `RANGE_SPACE_PIVOT` of its largest one. The elimination is exact, so the solution is the
/// one [`saddle_point_solve`] finds for the whole system (tested to round-off); it costs a few
/// 6 × 6 solves per body where the indefinite factorisation of the whole costs
/// $O((n_f + n_r)^3)$.
///
/// The solution is written into `ws` (buffers kept from one call to the next) and returned;
/// the factors stay in `ws`, so [`BlockSaddlePointWorkspace::resolve`] solves the same
/// system for another right-hand side at the cost of the triangular solves.
pub fn block_saddle_point_solve<'w>(
    kkt: &DMatrix<f64>,
    rhs: &DVector<f64>,
    nf: usize,
    frame_scale: f64,
    ws: &'w mut BlockSaddlePointWorkspace,
) -> &'w DVector<f64> {
    solve_by_blocks(kkt, rhs, nf, frame_scale, ws);
    &ws.out
}

/// Buffers [`block_saddle_point_solve`] reuses from one call to the next, and the factors of
/// the last system it solved.
#[derive(Debug, Clone, Default)]
pub struct BlockSaddlePointWorkspace {
    /// The order of the factored system and its frame rows; `None` before a factorisation.
    factored: Option<(usize, usize)>,
    /// The constraint block after elimination and its right-hand side.
    schur: DMatrix<f64>,
    g: DVector<f64>,
    /// The frame blocks kept in the reduced system.
    kept: Vec<usize>,
    /// The eliminated frame blocks: the first `eliminated` of `blocks`.
    blocks: Vec<EliminatedBlock>,
    eliminated: usize,
    /// How what is left after the elimination is solved.
    reduced: ReducedSolve,
    /// The factor of $S$.
    scaled_schur: ScaledSchur,
    /// The kept blocks' system when blocks are kept.
    kept_system: KeptSystem,
    /// The solution.
    out: DVector<f64>,
}

/// How the system left after the elimination of the definite frame blocks is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum ReducedSolve {
    /// No block kept, $S$ definite: its scaled Cholesky factor.
    #[default]
    Schur,
    /// No block kept, $S$ not clearly definite: [`saddle_point_solve`] of $S$.
    IndefiniteSchur,
    /// Blocks kept, $S$ and the kept frames' dual matrix definite: the multipliers
    /// eliminated in turn ([`KeptSystem::dual_solve`]).
    Dual,
    /// Blocks kept, otherwise: the reduced saddle-point system ([`KeptSystem::reduced_solve`]).
    Reduced,
}

impl BlockSaddlePointWorkspace {
    /// The solution for the right-hand side `rhs` of the system the last
    /// [`block_saddle_point_solve`] with this workspace factored, from its factors: the
    /// same numbers a new [`block_saddle_point_solve`] of that system gives, to the bit,
    /// for the cost of the triangular solves.
    ///
    /// # Panics
    /// Before a factorisation, or for a right-hand side of another length.
    pub fn resolve(&mut self, rhs: &DVector<f64>) -> &DVector<f64> {
        self.solve_factored(rhs);
        &self.out
    }

    /// Eliminates every clearly definite frame block of `kkt` and factors what is left (see
    /// [`block_saddle_point_solve`]).
    fn factor(&mut self, kkt: &DMatrix<f64>, nf: usize, frame_scale: f64) -> BlockRoute {
        let n = kkt.nrows();
        assert!(
            nf.is_multiple_of(FRAME_BLOCK) && nf <= n && kkt.ncols() == n,
            "block_saddle_point_solve: {n} × {} system, {nf} frame rows",
            kkt.ncols(),
        );
        let nr = n - nf;
        // The constraint block after elimination (−D − Σ B_b A_b⁻¹ B_bᵀ).
        if self.schur.shape() != (nr, nr) {
            self.schur = DMatrix::zeros(nr, nr);
        }
        self.schur.copy_from(&kkt.view((nf, nf), (nr, nr)));
        let schur = &mut self.schur;
        self.kept.clear();
        self.eliminated = 0;
        let entries = kkt.as_slice();
        for b in 0..nf / FRAME_BLOCK {
            let o = FRAME_BLOCK * b;
            let a = Matrix6::from_fn(|i, j| kkt[(o + i, o + j)]);
            let Some(chol) = a.cholesky().filter(|c| {
                let pivots = c.l_dirty().diagonal();
                pivots
                    .iter()
                    .all(|p| p * p > RANGE_SPACE_FRAME_PIVOT * frame_scale)
                    && pivots_ok(pivots.iter().copied())
            }) else {
                self.kept.push(b);
                continue;
            };
            // The block's coupling B_b: column o + j of the constraint rows, contiguous.
            let coupling: [&[f64]; FRAME_BLOCK] =
                std::array::from_fn(|j| &entries[(o + j) * n + nf..(o + j + 1) * n]);
            if self.blocks.len() == self.eliminated {
                self.blocks.push(EliminatedBlock::default());
            }
            let block = &mut self.blocks[self.eliminated];
            self.eliminated += 1;
            block.first = o;
            block.active.clear();
            block
                .active
                .extend((0..nr).filter(|&r| coupling.iter().any(|column| column[r] != 0.0)));
            block.rows.clear();
            block.rows.extend(
                block
                    .active
                    .iter()
                    .map(|&r| Vector6::from_fn(|j, _| coupling[j][r])),
            );
            block.y.clear();
            block.y.extend(block.rows.iter().map(|row| chol.solve(row)));
            for (&ri, bi) in block.active.iter().zip(&block.rows) {
                for (&rj, yj) in block.active.iter().zip(&block.y) {
                    schur[(ri, rj)] -= bi.dot(yj);
                }
            }
            block.chol = Some(chol);
        }
        let schur = &self.schur;
        self.reduced = if self.kept.is_empty() {
            if self.scaled_schur.factor(schur) {
                ReducedSolve::Schur
            } else {
                ReducedSolve::IndefiniteSchur
            }
        } else {
            self.kept_system.gather(kkt, nf, &self.kept);
            if self
                .kept_system
                .dual_factor(&mut self.scaled_schur, schur, frame_scale)
            {
                ReducedSolve::Dual
            } else {
                ReducedSolve::Reduced
            }
        };
        self.factored = Some((n, nf));
        BlockRoute {
            kept: self.kept.len(),
            definite_schur: matches!(self.reduced, ReducedSolve::Schur | ReducedSolve::Dual),
        }
    }

    /// The solution for `rhs` from the factors of [`Self::factor`], into `out`.
    fn solve_factored(&mut self, rhs: &DVector<f64>) {
        let Some((n, nf)) = self.factored else {
            panic!("BlockSaddlePointWorkspace: a solve before a factorisation");
        };
        assert_eq!(
            rhs.len(),
            n,
            "block_saddle_point_solve: {} right-hand side entries for {n} rows",
            rhs.len()
        );
        let nr = n - nf;
        resize(&mut self.g, nr);
        self.g.copy_from(&rhs.rows(nf, nr));
        let g = &mut self.g;
        for block in &mut self.blocks[..self.eliminated] {
            let chol = block.chol.as_ref().expect("factored with the block");
            block.a_f = chol.solve(&Vector6::from_fn(|i, _| rhs[block.first + i]));
            for (&ri, bi) in block.active.iter().zip(&block.rows) {
                g[ri] -= bi.dot(&block.a_f);
            }
        }
        resize(&mut self.out, n);
        self.out.as_mut_slice().fill(0.0);
        let (out, schur, g) = (&mut self.out, &self.schur, &self.g);
        match self.reduced {
            ReducedSolve::Schur => {
                let lambda = &mut out.as_mut_slice()[nf..];
                for (l, gi) in lambda.iter_mut().zip(g.iter()) {
                    *l = -gi;
                }
                self.scaled_schur.solve_in_place(lambda);
            }
            ReducedSolve::IndefiniteSchur => {
                out.as_mut_slice()[nf..].copy_from_slice(saddle_point_solve(schur, g).as_slice());
            }
            ReducedSolve::Dual | ReducedSolve::Reduced => {
                let system = &mut self.kept_system;
                system.gather_forces(rhs, &self.kept);
                let solved =
                    self.reduced == ReducedSolve::Dual && system.dual_solve(&self.scaled_schur, g);
                if !solved {
                    system.reduced_solve(schur, g);
                }
                for (i, &b) in self.kept.iter().enumerate() {
                    out.rows_mut(FRAME_BLOCK * b, FRAME_BLOCK)
                        .copy_from(&system.x.rows(FRAME_BLOCK * i, FRAME_BLOCK));
                }
                out.rows_mut(nf, nr).copy_from(&system.lambda);
            }
        }
        // x_b = A_b⁻¹ f_b − A_b⁻¹ B_bᵀ λ for every eliminated block.
        for block in &self.blocks[..self.eliminated] {
            let mut x = block.a_f;
            for (&r, yr) in block.active.iter().zip(&block.y) {
                x -= yr * out[nf + r];
            }
            out.rows_mut(block.first, FRAME_BLOCK).copy_from(&x);
        }
    }
}

/// How [`block_saddle_point_solve`] solved a system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct BlockRoute {
    /// Frame blocks left in the reduced system (not clearly definite).
    kept: usize,
    /// Whether $S$ was definite, so only Cholesky factorisations were needed (with blocks
    /// kept: the multipliers eliminated in turn, see [`KeptSystem::dual_solve`]).
    definite_schur: bool,
}

/// [`block_saddle_point_solve`] and the route it took.
fn solve_by_blocks(
    kkt: &DMatrix<f64>,
    rhs: &DVector<f64>,
    nf: usize,
    frame_scale: f64,
    ws: &mut BlockSaddlePointWorkspace,
) -> BlockRoute {
    let route = ws.factor(kkt, nf, frame_scale);
    ws.solve_factored(rhs);
    route
}

/// A frame block eliminated by [`block_saddle_point_solve`].
#[derive(Debug, Clone, Default)]
struct EliminatedBlock {
    /// Its first row.
    first: usize,
    /// The constraint rows it couples to.
    active: Vec<usize>,
    /// $B_b$ on those rows, one row each.
    rows: Vec<Vector6<f64>>,
    /// The Cholesky factor of $A_b$.
    chol: Option<nalgebra::Cholesky<f64, nalgebra::U6>>,
    /// $A_b^{-1}B_b^T$, one column per active row.
    y: Vec<Vector6<f64>>,
    /// $A_b^{-1}f_b$.
    a_f: Vector6<f64>,
}
#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded saddle-point system: A = GGᵀ + I·a_shift (nf × nf), B (nr × nf), D = HHᵀ.
    /// [`solve_by_blocks`] with a fresh workspace: the solution and the route.
    fn solved_by_blocks(
        kkt: &DMatrix<f64>,
        rhs: &DVector<f64>,
        nf: usize,
        frame_scale: f64,
    ) -> (DVector<f64>, BlockRoute) {
        let mut ws = BlockSaddlePointWorkspace::default();
        let route = solve_by_blocks(kkt, rhs, nf, frame_scale, &mut ws);
        // A workspace that solved other systems before (other shapes, other routes) gives
        // the same solution: nothing of the last call leaks into the next.
        let mut used = BlockSaddlePointWorkspace::default();
        for (blocks, singular, nr) in [(3, vec![1], 8), (1, vec![], 2), (4, vec![0, 2], 12)] {
            let (k, r) = block_system(blocks, nr, &singular, 99);
            solve_by_blocks(&k, &r, FRAME_BLOCK * blocks, 1.0, &mut used);
        }
        assert_eq!(solve_by_blocks(kkt, rhs, nf, frame_scale, &mut used), route);
        assert_eq!(used.out, ws.out, "a reused workspace");
        // Another right-hand side solved from the factors is that system solved anew, to the
        // bit, on every route; and the first right-hand side again gives the first solution.
        let other = rhs.map(|v| 0.5 - 2.0 * v) + DVector::from_fn(rhs.len(), |i, _| i as f64);
        let mut fresh = BlockSaddlePointWorkspace::default();
        assert_eq!(
            solve_by_blocks(kkt, &other, nf, frame_scale, &mut fresh),
            route
        );
        assert_eq!(used.resolve(&other), &fresh.out, "another right-hand side");
        assert_eq!(
            used.resolve(rhs),
            &ws.out,
            "the first right-hand side again"
        );
        (ws.out, route)
    }

    fn saddle_system(nf: usize, nr: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let g = DMatrix::from_fn(nf, nf, |_, _| next());
        let a = &g * g.transpose() + DMatrix::identity(nf, nf) * 0.1;
        let b = DMatrix::from_fn(nr, nf, |_, _| next());
        let h = DMatrix::from_fn(nr, 2, |_, _| next());
        let d = &h * h.transpose();
        let n = nf + nr;
        let mut kkt = DMatrix::zeros(n, n);
        kkt.view_mut((0, 0), (nf, nf)).copy_from(&a);
        kkt.view_mut((nf, 0), (nr, nf)).copy_from(&b);
        kkt.view_mut((0, nf), (nf, nr)).copy_from(&b.transpose());
        kkt.view_mut((nf, nf), (nr, nr)).copy_from(&(-d));
        let rhs = DVector::from_fn(n, |_, _| next());
        (kkt, rhs)
    }

    /// A seeded system whose frame block is block diagonal in `blocks` 6 × 6 blocks, each
    /// coupled to a few of the `nr` constraint rows (as a link is to its two joints); the
    /// blocks in `singular` have rank 3 and round-off size (Ψ holding the rigid motions).
    fn block_system(
        blocks: usize,
        nr: usize,
        singular: &[usize],
        seed: u64,
    ) -> (DMatrix<f64>, DVector<f64>) {
        let (dense, rhs) = saddle_system(FRAME_BLOCK * blocks, nr, seed);
        let nf = FRAME_BLOCK * blocks;
        let mut kkt = dense.clone();
        for b in 0..blocks {
            let o = FRAME_BLOCK * b;
            for i in 0..nf {
                if i / FRAME_BLOCK != b {
                    for j in o..o + FRAME_BLOCK {
                        kkt[(i, j)] = 0.0;
                        kkt[(j, i)] = 0.0;
                    }
                }
            }
            if singular.contains(&b) {
                let g = dense.view((o, 0), (FRAME_BLOCK, 3)).into_owned();
                let a = &g * g.transpose() * 1e-13;
                kkt.view_mut((o, o), (FRAME_BLOCK, FRAME_BLOCK))
                    .copy_from(&a);
            }
            // Each block touches the rows r with (r + b) % 3 != 0 (two rows in three), every
            // row at least one block.
            for r in 0..nr {
                if (r + b) % 3 == 0 && blocks > 1 {
                    for j in o..o + FRAME_BLOCK {
                        kkt[(nf + r, j)] = 0.0;
                        kkt[(j, nf + r)] = 0.0;
                    }
                }
            }
        }
        (kkt, rhs)
    }

    #[test]
    fn block_elimination_agrees_with_the_indefinite_factorisation() {
        for blocks in [1, 2, 5] {
            // Independent constraints: S is definite while B has rank nr (D has rank 2).
            for nr in [0, 3, 6, 10]
                .into_iter()
                .filter(|&nr| nr <= FRAME_BLOCK * blocks)
            {
                for seed in 0..4 {
                    let (kkt, rhs) = block_system(blocks, nr, &[], seed + 10 * nr as u64);
                    let nf = FRAME_BLOCK * blocks;
                    let (fast, route) = solved_by_blocks(&kkt, &rhs, nf, 1.0);
                    assert_eq!(
                        route,
                        BlockRoute {
                            kept: 0,
                            definite_schur: true
                        },
                        "{blocks}/{nr}"
                    );
                    let reference = saddle_point_solve(&kkt, &rhs);
                    assert_eq!(fast.len(), reference.len());
                    let n = (nf + nr) as f64;
                    let residual = (&kkt * &fast - &rhs).amax();
                    assert!(residual < 1e-9 * n, "{blocks}/{nr}: residual {residual:e}");
                    let gap = (&fast - &reference).amax() / reference.amax();
                    assert!(gap < 1e-8 * n, "{blocks}/{nr}: {gap:e}");
                }
            }
        }
    }

    #[test]
    fn singular_frame_blocks_stay_in_the_indefinite_solve() {
        // Blocks of round-off against the frame scale (Ψ holding the rigid motions) among
        // definite ones: they are kept, the others eliminated, and the solution is the whole
        // system's. The constraint rows fix the kept frames (at least six rows per kept block
        // touch it, as the axis conditions do).
        // Alone, the kept block leaves S = D of rank 2 (LBLᵀ); beside eliminated blocks S is
        // definite and the multipliers are eliminated in turn.
        for (blocks, singular, nr, definite) in [
            (1, vec![0], 8, false),
            (3, vec![1], 8, true),
            (4, vec![0, 2], 12, true),
        ] {
            let (kkt, rhs) = block_system(blocks, nr, &singular, 3 + blocks as u64);
            let nf = FRAME_BLOCK * blocks;
            let (fast, route) = solved_by_blocks(&kkt, &rhs, nf, 1.0);
            assert_eq!(
                route,
                BlockRoute {
                    kept: singular.len(),
                    definite_schur: definite
                },
                "{blocks}"
            );
            let reference = saddle_point_solve(&kkt, &rhs);
            let residual = (&kkt * &fast - &rhs).amax() / rhs.amax();
            let gap = (&fast - &reference).amax() / reference.amax();
            assert!(
                residual < 1e-8,
                "{blocks}: residual {residual:e}, {route:?}, reference residual {:e}, gap {gap:e}",
                (&kkt * &reference - &rhs).amax() / rhs.amax()
            );
            assert!(gap < 1e-7, "{blocks}: {gap:e}");
        }
        // The frame scale decides what round-off is: the same definite block against a scale
        // 1e12 times larger is kept.
        let (kkt, rhs) = block_system(2, 4, &[], 5);
        assert_eq!(solved_by_blocks(&kkt, &rhs, 12, 1e12).1.kept, 2);
    }

    #[test]
    fn redundant_constraints_take_the_pseudo_inverse_with_the_same_motion() {
        // A constraint row repeated: S is singular, the multipliers are not unique, the
        // accelerations x are, and they satisfy every row.
        let (mut kkt, mut rhs) = block_system(3, 6, &[], 9);
        let nf = 18;
        for j in 0..nf {
            let v = kkt[(nf + 1, j)];
            kkt[(nf + 4, j)] = v;
            kkt[(j, nf + 4)] = v;
        }
        for j in nf..nf + 6 {
            kkt[(nf + 4, j)] = 0.0;
            kkt[(j, nf + 4)] = 0.0;
            kkt[(nf + 1, j)] = 0.0;
            kkt[(j, nf + 1)] = 0.0;
        }
        rhs[nf + 4] = rhs[nf + 1];
        let (fast, route) = solved_by_blocks(&kkt, &rhs, nf, 1.0);
        assert!(!route.definite_schur, "{route:?}");
        let reference = saddle_point_solve(&kkt, &rhs);
        let gap = (fast.rows(0, nf) - reference.rows(0, nf)).amax() / reference.amax();
        assert!(gap < 1e-8, "{gap:e}");
        let residual = (&kkt * &fast - &rhs).amax() / rhs.amax();
        assert!(residual < 1e-8, "{residual:e}");
    }
}
