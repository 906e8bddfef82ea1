//! The interior problem of a partitioned body (Eq. 6.1): K_ii factored once, the static
//! constraint modes (Eq. 6.3), the fixed-interface modes (Eq. 6.11), on the dense path
//! (small bodies) or the sparse one (refined meshes), and what each step cost.

use std::time::Instant;

use faer::{Mat, MatRef, sparse::SparseColMat};

use super::{
    BoundaryCoordinates, Column, ColumnKind, Eigensolver, ModeSelection, ReductionError,
    ReleasableFactor, RigidInterface, SolverPath,
    amls_free_modes::{AmlsProblem, amls_pairs, first_cutoff_hz},
    free_body_solver::{FreeBodyParameters, SturmPencil, sturm_checked},
    partition::{Partition, free_rigid_motions},
};
use crate::{
    Error, Progress, Result,
    error::{FreeMotion, LinalgError},
    fem::{FeModel, RigidMotions},
    linalg::{
        AmlsEigenParameters, GeneralizedEigen, IndefiniteFactor, MassMatrix, PairSelection,
        PartialEigenParameters, SparseSymmetric, SymbolicFactor, SymmetricFactor,
        generalized_eigen_selected, multifrontal_inertia, negative_shift, nested_dissection,
    },
};

/// Wall time (s) and sizes of the phases of one reduction.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ReductionStatistics {
    /// Whether the sparse path ran.
    pub sparse: bool,
    /// Symbolic analysis and numeric factorisation of $K_{ii}$ (or $K_{ii} - \sigma M_{ii}$), s.
    pub factorization_s: f64,
    /// Constraint modes $-K_{ii}^{-1}K_{ib}$ (Eq. 6.3), s.
    pub constraint_modes_s: f64,
    /// Fixed-interface eigenproblem (partial or complete), s.
    pub eigen_s: f64,
    /// Entries of the Cholesky factor (0 when none was formed).
    pub factor_nnz: usize,
    /// Flops of the numeric factorisation (0 on the dense path).
    pub factor_flops: f64,
    /// Block solves of the partial eigensolver.
    pub eigen_block_solves: usize,
    /// Largest residual $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$ of the partial
    /// eigensolver's pairs (0 on the dense path).
    pub eigen_max_residual: f64,
    /// The solver of the fixed-interface pairs on the sparse path.
    pub eigensolver: Eigensolver,
    /// AMLS's reductions, when it made them.
    pub amls_reductions: usize,
}

/// Interior DOF up to which [`SolverPath::Auto`] stays dense: there a complete dense
/// eigenproblem costs milliseconds and is the fastest route.
pub const DENSE_INTERIOR_LIMIT: usize = 600;

/// Interior DOF up to which a complete dense eigenproblem is attempted at all (mode
/// condensation's thesis route, modal truncation with a frequency cut-off): ~n³/3 flops and
/// 8n² bytes, about a minute and 130 MB at this size.
pub const COMPLETE_EIGEN_LIMIT: usize = 4000;

/// Backward error a static response $K_{ii}^{-1}F$ meets ([`InteriorProblem::static_response`]).
pub const STATIC_RESPONSE_TOLERANCE: f64 = 1e-10;

/// The interior problem of one boundary set: $K_{ii}$, $M_{ii}$, $K_{ib}$ and, once needed,
/// the factor of $K_{ii}$ shared by the constraint modes and the eigensolver.
pub struct InteriorProblem<'a> {
    model: &'a FeModel,
    /// The split.
    pub partition: Partition,
    sparse: bool,
    k_ii: SparseSymmetric,
    m_ii: MassMatrix,
    k_ib: SparseColMat<usize, f64>,
    /// The boundary coordinates $u_b = R\,q$.
    boundary: BoundaryCoordinates,
    /// $K_{ib}R$, dense, once needed.
    k_ib_r: Option<Mat<f64>>,
    factor: Option<(SymmetricFactor, f64)>,
    /// The pattern analysis of the factored matrix (sparse path), for the Sturm check.
    symbolic: Option<SymbolicFactor>,
    free_motions: Option<Vec<FreeMotion>>,
    partial_modes: Option<GeneralizedEigen>,
    /// The solver of the fixed-interface pairs on the sparse path.
    eigensolver: Eigensolver,
    /// Phase timings and sizes so far.
    pub statistics: ReductionStatistics,
    progress: Progress,
}

impl<'a> InteriorProblem<'a> {
    /// Splits `model` by `boundary_nodes` and extracts the blocks; `path` chooses dense or
    /// sparse linear algebra.
    pub fn new(model: &'a FeModel, boundary_nodes: &[usize], path: SolverPath) -> Result<Self> {
        Self::on(model, Partition::new(model, boundary_nodes)?, path)
    }

    /// The interior problem of a given split (for instance a DOF-wise one with held DOF,
    /// [`Partition::from_dofs`]).
    pub fn on(model: &'a FeModel, partition: Partition, path: SolverPath) -> Result<Self> {
        let sparse = match path {
            SolverPath::Dense => false,
            SolverPath::Sparse => true,
            SolverPath::Auto => partition.i.len() > DENSE_INTERIOR_LIMIT,
        };
        let k_ii = model.k.principal_block(&partition.i);
        let m_ii = model.m.principal_block(&partition.i);
        let k_ib = model.k.block(&partition.i, &partition.b);
        let boundary = BoundaryCoordinates::plain(partition.b.len());
        Ok(Self {
            model,
            partition,
            sparse,
            k_ii,
            m_ii,
            k_ib,
            boundary,
            k_ib_r: None,
            factor: None,
            symbolic: None,
            free_motions: None,
            partial_modes: None,
            eigensolver: Eigensolver::Lanczos,
            progress: Progress::default(),
            statistics: ReductionStatistics {
                sparse,
                ..Default::default()
            },
        })
    }

    /// The fixed-interface pairs on the sparse path by `solver` (Lanczos by default; AMLS over
    /// the interior's own nested-dissection tree when asked, `export --eigensolver amls`).
    pub fn with_eigensolver(mut self, solver: Eigensolver) -> Self {
        self.eigensolver = solver;
        self.statistics.eigensolver = solver;
        self
    }

    /// Reports each phase (factorisation, constraint modes, eigensolve) to `progress` and stops
    /// with [`Error::Cancelled`] at the next phase boundary once it is cancelled.
    pub fn with_progress(mut self, progress: Progress) -> Self {
        self.progress = progress;
        self
    }

    /// Ties the nodes of each of `interfaces` (all boundary nodes) to its master's six DOF:
    /// the boundary coordinates become the plain boundary DOF and six per master (see
    /// [`BoundaryCoordinates`]), so their constraint modes take six right-hand sides per
    /// interface instead of three per tied node.
    pub fn with_rigid_interfaces(mut self, interfaces: &[RigidInterface]) -> Result<Self> {
        if !interfaces.is_empty() {
            self.boundary = BoundaryCoordinates::tied(self.model, &self.partition.b, interfaces)?;
            self.k_ib_r = None;
        }
        Ok(self)
    }

    /// Number of boundary coordinates (boundary DOF when no rigid interface ties them).
    pub fn boundary_coordinates(&self) -> usize {
        self.boundary.count()
    }

    /// The boundary rows of a basis: $R$ followed by `extra` zero columns.
    pub fn boundary_top(&self, extra: usize) -> Mat<f64> {
        self.boundary.top(extra)
    }

    /// Column descriptions of the boundary coordinates: `kind` and `prefix` for plain
    /// boundary DOF, `rbe2 NAME x … θz` for a master's.
    pub fn boundary_columns(&self, kind: ColumnKind, prefix: &str) -> Vec<Column> {
        self.boundary
            .columns(self.model, &self.partition.b, kind, prefix)
    }

    /// Whether the sparse path runs.
    pub fn is_sparse(&self) -> bool {
        self.sparse
    }

    /// Interior DOF.
    pub fn interior_dofs(&self) -> usize {
        self.partition.i.len()
    }

    /// $K_{ib}R$, dense (interior × boundary coordinates; $K_{ib}$ itself when no rigid
    /// interface ties the boundary).
    pub fn k_ib(&mut self) -> MatRef<'_, f64> {
        if self.k_ib_r.is_none() {
            self.k_ib_r = Some(self.boundary.times(&self.k_ib));
        }
        self.k_ib_r.as_ref().expect("set above").as_ref()
    }

    /// Whether the boundary restrains every rigid-body motion, i.e. $K_{ii}$ is invertible;
    /// otherwise `ReductionError::SingularInterior` naming the free motions. Decided from the rigid
    /// motions restricted to the boundary DOF (rank of a b × 6 matrix), no eigenproblem.
    /// A body whose rigid motions are [`RigidMotions::Unknown`] passes; its factorisation
    /// decides.
    pub fn check_restraint(&mut self) -> Result<()> {
        if self.model.rigid_motions == RigidMotions::Unknown {
            return Ok(());
        }
        if self.free_motions.is_none() {
            self.free_motions = Some(free_rigid_motions(self.model, &self.partition)?);
        }
        let free = self.free_motions.as_ref().expect("set above");
        if free.is_empty() {
            return Ok(());
        }
        Err(Error::Reduction(ReductionError::SingularInterior {
            boundary_nodes: self.partition.boundary_nodes.clone(),
            rank_deficiency: free.len(),
            free_motions: free.clone(),
            needed: self.model.dofs.rigid_body_count(),
        }))
    }

    /// The factor of $K_{ii} - \sigma M_{ii}$: $\sigma = 0$ when the boundary restrains the
    /// body, a small negative shift otherwise (modal truncation does not need $K_{ii}$
    /// invertible, only its eigenvectors).
    fn factor(&mut self) -> Result<&(SymmetricFactor, f64)> {
        if self.factor.is_none() {
            self.progress.phase("factorisation of K_ii")?;
            let started = Instant::now();
            let sigma = if self.check_restraint().is_ok() {
                0.0
            } else {
                negative_shift(&self.k_ii, &self.m_ii)
            };
            // On the union of K_ii's and M_ii's patterns even for σ = 0, so the Sturm check's
            // K_ii - σ'M_ii shares this analysis. With σ = 0 on a pattern that already holds
            // M_ii's, that is K_ii itself: no copy of it beside the factor being formed.
            let a = &*self.k_ii.shifted_or_same(&self.m_ii, sigma);
            let f = if self.sparse {
                // Geometric nested dissection on the interior DOF's node positions.
                let coords: Vec<[f64; 3]> = self
                    .partition
                    .i
                    .iter()
                    .map(|&d| self.model.dof_position(d))
                    .collect();
                let order = nested_dissection(a.as_faer(), &coords);
                let symbolic = SymbolicFactor::analyse_ordered(a.as_faer(), order.as_deref())?;
                let f = SymmetricFactor::sparse(a.as_faer(), &symbolic, "interior stiffness K_ii")?;
                self.statistics.factor_flops = symbolic.flops();
                self.symbolic = Some(symbolic);
                f
            } else {
                SymmetricFactor::dense(a.to_dense().as_ref(), "interior stiffness K_ii")?
            };
            self.statistics.factor_nnz = f.factor_nnz();
            self.statistics.factorization_s += started.elapsed().as_secs_f64();
            self.factor = Some((f, sigma));
        }
        Ok(self.factor.as_ref().expect("set above"))
    }

    /// The interior stiffness $K_{ii}$.
    pub fn interior_stiffness(&self) -> &SparseSymmetric {
        &self.k_ii
    }

    /// The interior mass $M_{ii}$.
    pub fn interior_mass(&self) -> &MassMatrix {
        &self.m_ii
    }

    /// $K_{ii}^{-1}F$, the static response to interior loads $F$ (interior × loads) with the
    /// whole boundary held, on the shared factor. Only a boundary that restrains the body
    /// has one ([`Self::check_restraint`]); each column's backward error
    /// $\|f - K_{ii}x\| / (\|K_{ii}\|_{\max}\,\|x\|_1 + \|f\|)$ is checked against
    /// $10^{-10}$ ([`LinalgError::SolveInaccurate`] naming the worst).
    pub fn static_response(&mut self, loads: MatRef<'_, f64>) -> Result<Mat<f64>> {
        self.check_restraint()?;
        self.factor()?;
        let (f, _) = self.factor.as_ref().expect("factored above");
        let x = f.solve(loads);
        let kx = self.k_ii.mul(x.as_ref());
        let scale = self.k_ii.max_abs();
        let mut worst = 0.0_f64;
        for j in 0..x.ncols() {
            let (mut r, mut b, mut x1) = (0.0_f64, 0.0_f64, 0.0_f64);
            for i in 0..x.nrows() {
                r += (loads[(i, j)] - kx[(i, j)]).powi(2);
                b += loads[(i, j)].powi(2);
                x1 += x[(i, j)].abs();
            }
            let e = r.sqrt() / (scale * x1 + b.sqrt()).max(f64::MIN_POSITIVE);
            worst = if e.is_nan() { f64::NAN } else { worst.max(e) };
        }
        if worst.is_nan() || worst > STATIC_RESPONSE_TOLERANCE {
            return Err(LinalgError::SolveInaccurate {
                matrix: "interior stiffness K_ii (static response)".into(),
                residual: worst,
                tolerance: STATIC_RESPONSE_TOLERANCE,
            }
            .into());
        }
        Ok(x)
    }

    /// Static constraint modes' interior part $\Psi_s = -K_{ii}^{-1}K_{ib}R$ (Eq. 6.3): one
    /// factorisation, the boundary coordinates as right-hand sides.
    pub fn constraint_modes(&mut self) -> Result<Mat<f64>> {
        self.progress.phase("constraint modes")?;
        let started = Instant::now();
        let factoring = self.statistics.factorization_s;
        let psi_s = self.solve_constraint_modes(usize::MAX)?;
        // The factorisation, when this call made it, is its own phase.
        let factored = self.statistics.factorization_s - factoring;
        self.statistics.constraint_modes_s += started.elapsed().as_secs_f64() - factored;
        Ok(psi_s)
    }

    /// The first `count` constraint modes as whole-body shapes $[R;\,-K_{ii}^{-1}K_{ib}R]$ (only
    /// those are solved for, for a view), and the labels of every boundary coordinate (a
    /// boundary DOF's, or `rbe2 NAME x … θz`).
    pub fn constraint_shapes(&mut self, count: usize) -> Result<(Mat<f64>, Vec<String>)> {
        let bottom = self.solve_constraint_modes(count)?;
        let top = self.boundary.top(0);
        let shapes = self
            .partition
            .assemble(top.subcols(0, bottom.ncols()), bottom.as_ref());
        let labels = self
            .boundary_columns(ColumnKind::Constraint, "")
            .into_iter()
            .map(|c| c.label.trim().to_string())
            .collect();
        Ok((shapes, labels))
    }

    /// $-K_{ii}^{-1}K_{ib}R$ for the first `count` boundary coordinates (all of them at most).
    fn solve_constraint_modes(&mut self, count: usize) -> Result<Mat<f64>> {
        self.check_restraint()?;
        self.factor()?;
        let count = count.min(self.boundary.count());
        // −K_ib R formed here (not kept) and solved in place: one n_i × count block in memory,
        // where the kept K_ib R, the solve's copy and the negated result held three (1.3 GB
        // for the 1 386 ring DOF of a 38 k-DOF part).
        let mut x = match &self.k_ib_r {
            Some(k_ib_r) => k_ib_r.subcols(0, count).to_owned(),
            None => self.boundary.times(&self.k_ib),
        };
        if x.ncols() > count {
            x = x.subcols(0, count).to_owned();
        }
        for j in 0..x.ncols() {
            for v in x.col_mut(j).iter_mut() {
                *v = -*v;
            }
        }
        let (f, _) = self.factor.as_ref().expect("factored above");
        // K_ib R is nonzero only on the rows next to the boundary: a wide solve's forward half
        // visits only the supernodes those rows reach (29 % of L for the eye-bar's 1 386-DOF
        // ring).
        f.solve_in_place(x.as_mut());
        Ok(x)
    }

    /// Every fixed-interface normal mode, $[\Psi_n, \Lambda_n] = \mathrm{eig}(K_{ii}, M_{ii})$
    /// (Eq. 6.11), by a complete dense eigenproblem whatever the path (mode condensation's
    /// route of §6.5, whose n³ cost this makes visible). Beyond [`COMPLETE_EIGEN_LIMIT`]
    /// interior DOF it is [`Error::TooLarge`].
    pub fn complete_modes(&mut self, method: &'static str) -> Result<GeneralizedEigen> {
        self.dense_modes(method, PairSelection::All)
    }

    /// The pairs `selection` keeps of the complete dense interior problem: solved whole, only
    /// the kept pairs transformed back and checked.
    fn dense_modes(
        &mut self,
        method: &'static str,
        selection: PairSelection,
    ) -> Result<GeneralizedEigen> {
        let n = self.interior_dofs();
        if n > COMPLETE_EIGEN_LIMIT {
            return Err(Error::TooLarge {
                method,
                step: Some("complete interior eigenproblem"),
                dofs: n,
                limit: COMPLETE_EIGEN_LIMIT,
            });
        }
        self.progress.phase("complete interior eigenproblem")?;
        let started = Instant::now();
        let eig = generalized_eigen_selected(
            self.k_ii.to_dense().as_ref(),
            self.m_ii.to_dense().as_ref(),
            "fixed-interface",
            selection,
        );
        self.statistics.eigen_s += started.elapsed().as_secs_f64();
        Ok(eig?)
    }

    /// The kept fixed-interface modes (Eq. 6.11), ascending and mass-normalised: the complete
    /// dense eigenproblem on the dense path, the partial shift-invert solver on the sparse one.
    pub fn kept_modes(&mut self, selection: ModeSelection) -> Result<GeneralizedEigen> {
        let n = self.interior_dofs();
        if !self.sparse {
            // The count and the cut-off are checked before the solve.
            let pairs = selection.pairs(n, 0)?;
            return self.dense_modes("fixed-interface modes", pairs);
        }
        match selection {
            ModeSelection::Count(k) => {
                if k > n {
                    return Err(Error::Reduction(ReductionError::TooManyModes {
                        requested: k,
                        available: n,
                    }));
                }
                self.partial(k)
            }
            ModeSelection::UpToHz(hz) => {
                // Validates the cut-off before any work.
                selection.count(&[])?;
                // How many lie below it, from the inertia of K_ii - ω_c²M_ii (Sylvester): one
                // factorisation, then one partial solve for exactly that many pairs, where
                // doubling a guess from 8 solved up to twice as many, several times over.
                let below = self.count_below(hz)?;
                if below > n / 4 {
                    return Err(Error::Reduction(ReductionError::TooManyModes {
                        requested: below,
                        available: n / 4,
                    }));
                }
                if below == 0 {
                    return Ok(GeneralizedEigen {
                        values: Vec::new(),
                        vectors: Mat::zeros(n, 0),
                        residuals: Vec::new(),
                        zero_energy: 0,
                        sturm: None,
                    });
                }
                let eig = self.partial(below)?;
                // A pair at the cut-off to round-off may fall either side of it.
                let kept = selection.count(&eig.hz())?;
                Ok(first_modes(&eig, kept))
            }
        }
    }

    /// Eigenvalues of $(K_{ii}, M_{ii})$ below `hz`: the negative pivots of
    /// $K_{ii} - (2\pi f)^2 M_{ii}$'s $LDL^T$ elimination, without storing its factor where
    /// the elimination stays stable ([`multifrontal_inertia`]), else by the stored factor.
    fn count_below(&self, hz: f64) -> Result<usize> {
        let omega2 = (2.0 * std::f64::consts::PI * hz).powi(2);
        let shifted = self.k_ii.shifted(&self.m_ii, omega2);
        let symbolic = SymbolicFactor::analyse(shifted.as_faer())?;
        if let Some(inertia) = multifrontal_inertia(&shifted, &symbolic)?
            && inertia.trusted()
        {
            return Ok(inertia.negative);
        }
        Ok(
            IndefiniteFactor::factor(shifted, &symbolic, "interior K_ii - ω_c²M_ii")?
                .negative_pivots(),
        )
    }

    fn partial(&mut self, wanted: usize) -> Result<GeneralizedEigen> {
        if let Some(cached) = &self.partial_modes
            && cached.values.len() >= wanted
        {
            return Ok(first_modes(cached, wanted));
        }
        if self.eigensolver == Eigensolver::Amls {
            return self.amls_partial(wanted);
        }
        self.factor()?;
        self.progress.phase("fixed-interface eigensolve")?;
        let started = Instant::now();
        let (f, sigma) = self.factor.take().expect("factored above");
        let symbolic = self
            .symbolic
            .as_ref()
            .expect("the sparse path keeps its analysis");
        let (k_ii, m_ii) = (&self.k_ii, &self.m_ii);
        // A large factor is released before the Sturm count's LDLᵀ and made again only when
        // needed (a retry here, or a later solve, by `factor`).
        let mut factor = ReleasableFactor::new(f, || {
            SymmetricFactor::sparse(
                k_ii.shifted_or_same(m_ii, sigma).as_faer(),
                symbolic,
                "interior stiffness K_ii",
            )
        });
        // Every partial solve is Sturm-checked; a count above the pairs found retries with
        // more pairs, then fails naming the modes missed.
        let checked = sturm_checked(
            SturmPencil {
                k: k_ii,
                m: m_ii,
                symbolic,
            },
            &mut factor,
            sigma,
            wanted,
            Mat::<f64>::zeros(self.k_ii.dim(), 0).as_ref(),
            &PartialEigenParameters::default(),
            FreeBodyParameters::default().sturm_retries,
        );
        let remake_s = factor.remake_s;
        self.factor = factor.into_held().map(|f| (f, sigma));
        self.statistics.factorization_s += remake_s;
        let (eig, stats) = checked?;
        self.statistics.eigen_block_solves += stats.block_solves;
        let kept = self.keep_partial(eig, started, stats.max_residual);
        // A factor made again is the factorisation's time, not the eigensolve's.
        self.statistics.eigen_s -= remake_s;
        Ok(kept)
    }

    /// Keeps `eig` as the partial solve's pairs, with the time since `started` and its worst
    /// residual in the statistics.
    fn keep_partial(
        &mut self,
        eig: GeneralizedEigen,
        started: Instant,
        max_residual: f64,
    ) -> GeneralizedEigen {
        self.statistics.eigen_s += started.elapsed().as_secs_f64();
        self.statistics.eigen_max_residual = self.statistics.eigen_max_residual.max(max_residual);
        self.partial_modes = Some(eig.clone());
        eig
    }

    /// The `wanted` lowest fixed-interface pairs by AMLS over the interior's own tree (parts
    /// of at most [`super::AMLS_LEAF`] unknowns, a quarter of a smaller interior), the first
    /// cut-off from the free body's guess (fixed-interface frequencies lie above the free ones, so
    /// the guess errs low), refined and Sturm-counted like every AMLS solve.
    fn amls_partial(&mut self, wanted: usize) -> Result<GeneralizedEigen> {
        self.progress.phase("fixed-interface eigensolve (AMLS)")?;
        let started = Instant::now();
        let coords: Vec<[f64; 3]> = self
            .partition
            .i
            .iter()
            .map(|&d| self.model.dof_position(d))
            .collect();
        let (eig, stats) = amls_pairs(
            &self.k_ii,
            &self.m_ii,
            &coords,
            AmlsProblem {
                wanted,
                null: None,
                data_precision: f64::EPSILON,
                guess_hz: first_cutoff_hz(
                    self.model,
                    wanted + AmlsEigenParameters::default().guard,
                ),
            },
        )?;
        self.statistics.amls_reductions += stats.reductions;
        Ok(self.keep_partial(eig, started, stats.max_residual))
    }
}

/// Fixed-interface (fixed-constraint) normal modes, $[\Psi_n, \Lambda_n] =
/// \mathrm{eig}(K_{ii}, M_{ii})$ (Eq. 6.11), mass-normalised, ascending: every mode (dense).
pub fn fixed_interface_modes(model: &FeModel, p: &Partition) -> Result<GeneralizedEigen> {
    let mut problem = InteriorProblem::new(model, &p.boundary_nodes, SolverPath::Dense)?;
    problem.complete_modes("fixed-interface modes")
}

/// Static constraint modes' interior part $\Psi_s = -K_{ii}^{-1}K_{ib}$ (Eq. 6.3).
pub fn constraint_modes(model: &FeModel, p: &Partition) -> Result<Mat<f64>> {
    InteriorProblem::new(model, &p.boundary_nodes, SolverPath::Auto)?.constraint_modes()
}

fn first_modes(all: &GeneralizedEigen, kept: usize) -> GeneralizedEigen {
    all.first(kept)
}
