//! The lowest eigenpairs of $K\Phi = M\Phi\Lambda$ for large sparse $K$ and $M$: block
//! shift-invert Lanczos with full re-orthogonalisation in the $M$ inner product and thick
//! restart, on one factorisation of $K - \sigma M$.
//!
//! The operator $A = (K - \sigma M)^{-1} M$ is self-adjoint in the $M$ inner product; its
//! largest eigenvalues $\theta = 1/(\lambda - \sigma)$ belong to the eigenvalues $\lambda$
//! nearest above $\sigma$. The basis $V$ ($V^T M V = I$) grows by blocks $A V_j$, each made
//! $M$-orthogonal to all of $V$ twice (classical Gram–Schmidt, repeated); $A V$ is kept, so the
//! Rayleigh quotient $T = V^T M A V$ is formed exactly instead of trusting the three-term
//! recurrence. When the basis is full, it restarts from the best Ritz vectors plus the last
//! block, whose span holds every Ritz residual (thick restart). Every returned pair is checked
//! by its residual $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$.

use crate::error::LinalgError;
use faer::{Mat, MatRef};

use super::checked_pairs::{
    CheckedPairs, RitzPairs, ShiftedPencil, refined_pairs, ritz_values_above,
};

use crate::linalg::dense::{GeneralizedEigen, eigenvalue_scale, symmetric_eigen};

use crate::linalg::Result;
use crate::linalg::sparse::{MassMatrix, SparseSymmetric, SymmetricFactor};

/// Settings of [`lowest_modes`].
#[derive(Debug, Clone, PartialEq)]
pub struct PartialEigenParameters {
    /// Vectors per Lanczos block (right-hand sides per solve).
    pub block_size: usize,
    /// Largest basis, as a multiple of the wanted count (at least `wanted + 4·block_size`).
    pub basis_factor: usize,
    /// Restarts before giving up.
    pub max_restarts: usize,
    /// Ritz pairs count as converged when $\|A u - \theta u\|_M \le$ this $\cdot\,\theta$;
    /// tightened tenfold (down to $10^{-14}$) while a converged set fails the residual check.
    pub ritz_tolerance: f64,
    /// Largest accepted $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$ of a returned pair.
    pub residual_tolerance: f64,
    /// Seed of the deterministic start block.
    pub seed: u64,
    /// The relative precision K and M are known to (at least ε): a residual within
    /// $4\,\delta\,\||K||\varphi|\| / \|K\varphi\|$ is as small as the data allows (matrices
    /// written with 11 digits cannot give a pair better than that). Measured from the data,
    /// e.g. by [`crate::fem::FeModel::rigid_motion_defect`].
    pub data_precision: f64,
}

impl Default for PartialEigenParameters {
    fn default() -> Self {
        Self {
            block_size: 4,
            basis_factor: 3,
            max_restarts: 50,
            ritz_tolerance: 1e-10,
            residual_tolerance: 1e-8,
            seed: 0x5eed_f1e7,
            data_precision: f64::EPSILON,
        }
    }
}

/// Relative Ritz residual below which a set of pairs that stopped improving (by half over two
/// restarts) is handed to the residual check on the original pencil.
const STALLED_RITZ: f64 = 1e-6;

/// What the solver did (operation counts, for tests and the bench).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartialEigenStatistics {
    /// Restarts of the basis.
    pub restarts: usize,
    /// Block solves with the factor.
    pub block_solves: usize,
    /// Largest basis size used.
    pub basis_size: usize,
    /// Largest residual $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$ of the returned pairs.
    pub max_residual: f64,
    /// The Ritz values above the returned pairs, ascending, (rad/s)²: upper bounds of the next
    /// eigenvalues (for the Sturm check, [`super::sturm_count`]).
    pub ritz_above: Vec<f64>,
}

/// Multiple of $\varepsilon\,\lambda_{max}\,\theta$ that a Ritz residual
/// $\|Au - \theta u\|_M/\theta$ can reach: each solve with the factor of $K - \sigma M$ errs
/// by about $\varepsilon\lambda_{max}/(\lambda - \sigma)$ in the direction of an eigenvector
/// of eigenvalue $\lambda$ (a backward-stable factor of a matrix whose largest eigenvalue is
/// $\lambda_{max}$), so a tolerance below it can never be met.
const ATTAINABLE_RITZ: f64 = 64.0;

/// The `wanted` lowest eigenpairs of $K\Phi = M\Phi\Lambda$ above the shift `sigma`
/// ($\sigma = 0$ for a positive definite $K$), given `factor` $= \mathrm{chol}(K - \sigma M)$.
///
/// Eigenvalues are ascending in (rad/s)², vectors mass-normalised with the sign rule of
/// [`fix_sign`]. Fails with `LinalgError::EigenNotConverged` (how many pairs converged, at what
/// residual) when the restarts run out or a returned pair's residual is too large.
///
/// `null_space`, when given, spans known eigenvectors of eigenvalue 0 (a free body's rigid
/// motions, $KR = 0$): they enter the basis exact, with $AR = R/(0 - \sigma)$, and count
/// among the `wanted` pairs. Left to the iteration they would converge first but, their θ
/// being far above the elastic ones, cost the elastic pairs their relative accuracy.
pub fn lowest_modes(
    k: &SparseSymmetric,
    m: &MassMatrix,
    factor: &SymmetricFactor,
    sigma: f64,
    wanted: usize,
    null_space: Option<MatRef<'_, f64>>,
    params: &PartialEigenParameters,
) -> Result<(GeneralizedEigen, PartialEigenStatistics)> {
    let n = k.dim();
    assert_eq!((m.dim(), factor.dim()), (n, n));
    let b = params.block_size.max(1);
    let max_basis = (params.basis_factor * wanted)
        .max(wanted + 4 * b)
        .div_ceil(b)
        * b;
    if wanted == 0 {
        return Ok((no_pairs(n), PartialEigenStatistics::default()));
    }
    if max_basis + b > n {
        return Err(LinalgError::TooManyPairs { wanted, dof: n });
    }
    let mut stats = PartialEigenStatistics {
        basis_size: max_basis,
        ..Default::default()
    };
    // A = (K - σM)⁻¹M, applied to a block through its image MV (kept beside V).
    let solve = |mv: MatRef<'_, f64>| factor.solve(mv);
    let attainable = ATTAINABLE_RITZ
        * f64::EPSILON
        * eigenvalue_scale((0..n).map(|j| (k.get(j, j), m.get(j, j))));

    let mut rng = params.seed;
    let mut basis = Basis::starting(
        n,
        (max_basis, b),
        (null_space, wanted),
        (sigma, m),
        &mut rng,
    );
    let known = basis.known;
    let pencil = ShiftedPencil {
        k,
        m,
        sigma,
        params,
    };
    let mut ritz_tolerance = params.ritz_tolerance;
    let mut ritz_history: Vec<f64> = Vec::new();
    loop {
        stats.block_solves += basis.expand(b, max_basis, &solve, m, &mut rng);
        let step = basis.rayleigh_ritz(sigma)?;
        let (theta, ritz) = (&step.theta, &step.ritz);
        let step_pairs = RitzPairs {
            theta,
            ritz,
            wanted,
            known,
        };
        let relative = step.relative_residuals(m, wanted);
        let converged = converged_ritz(&relative, theta, ritz_tolerance, attainable);
        let worst_ritz = relative.iter().copied().fold(0.0f64, f64::max);
        // The Ritz residuals stop falling where the solves' round-off, ε λ_max/(λ - σ) of
        // the body, is reached: then the pairs are as good as this factor makes them, and
        // the check on the original pencil decides.
        let stalled = stalled(&ritz_history, worst_ritz);
        ritz_history.push(worst_ritz);
        if stalled && converged < wanted {
            let checked = refined_pairs(&pencil, factor, &step_pairs)?;
            if checked.converged == wanted {
                stats.block_solves += 1;
                return Ok(accepted(checked, stats, (sigma, theta, wanted)));
            }
        }
        if converged == wanted {
            let checked = refined_pairs(&pencil, factor, &step_pairs)?;
            stats.block_solves += 1;
            if checked.converged == wanted {
                return Ok(accepted(checked, stats, (sigma, theta, wanted)));
            }
            if ritz_tolerance <= 1e-14 || stats.restarts == params.max_restarts {
                return Err(not_converged(&checked, wanted));
            }
            ritz_tolerance *= 0.1;
        }
        if stats.restarts == params.max_restarts {
            // The error names the residual users know, ‖Kφ − λMφ‖/‖Kφ‖ of the pairs as they
            // stand, and how many of them meet the tolerance.
            let checked = refined_pairs(&pencil, factor, &step_pairs)?;
            return Err(not_converged(&checked, wanted));
        }
        stats.restarts += 1;
        // Thick restart: keep the best Ritz vectors and their images, then the pending block.
        basis.restart(
            (wanted + (max_basis - wanted) / 2).min(max_basis - b) / b * b,
            &step,
        );
    }
}

/// The checked pairs returned, with their worst residual and the Ritz values above them
/// (what the Sturm count's shift is placed by) in the statistics.
fn accepted(
    checked: CheckedPairs,
    mut stats: PartialEigenStatistics,
    (sigma, theta, wanted): (f64, &[f64], usize),
) -> (GeneralizedEigen, PartialEigenStatistics) {
    stats.max_residual = checked.max_residual;
    stats.ritz_above = ritz_values_above(sigma, theta, wanted);
    (checked.eigen, stats)
}

/// The pairs as they stand did not all converge: how many meet the tolerance, and the worst
/// residual ‖Kφ − λMφ‖/‖Kφ‖.
fn not_converged(checked: &CheckedPairs, wanted: usize) -> LinalgError {
    LinalgError::EigenNotConverged {
        converged: checked.converged,
        wanted,
        residual: checked.max_residual,
    }
}

/// No pairs, of a body of `n` unknowns.
fn no_pairs(n: usize) -> GeneralizedEigen {
    GeneralizedEigen {
        values: vec![],
        vectors: Mat::zeros(n, 0),
        residuals: vec![],
        zero_energy: 0,
        sturm: None,
    }
}

/// How many leading Ritz pairs have converged: their `relative` residuals within the Ritz
/// tolerance, or within what the solves attain for their θ.
fn converged_ritz(relative: &[f64], theta: &[f64], tolerance: f64, attainable: f64) -> usize {
    relative
        .iter()
        .zip(theta)
        .take_while(|&(&r, &t)| r <= tolerance.max(attainable * t.abs()))
        .count()
}

/// Whether the worst Ritz residual has stopped falling (below [`STALLED_RITZ`], and above
/// half of each of the last two).
fn stalled(history: &[f64], worst: f64) -> bool {
    worst <= STALLED_RITZ
        && history.len() >= 2
        && history[history.len() - 2..]
            .iter()
            .all(|&previous| worst > 0.5 * previous)
}

/// The Lanczos basis $V$ ($M$-orthonormal), $MV$, and $AV$ for its first `with_a` columns;
/// the first `known` columns are known null vectors.
struct Basis {
    v: Mat<f64>,
    mv: Mat<f64>,
    av: Mat<f64>,
    cols: usize,
    with_a: usize,
    known: usize,
}

/// One Rayleigh–Ritz step: the Ritz values θ (descending, the known pairs first), the small
/// problem's vectors $Y$, the Ritz vectors $VY$ and their images $AVY$.
struct RitzStep {
    theta: Vec<f64>,
    y: Mat<f64>,
    ritz: Mat<f64>,
    a_ritz: Mat<f64>,
}

impl Basis {
    /// The starting basis of `max_basis` columns grown by blocks of `b`: the `null_space`'s
    /// vectors (at most `wanted`, exact, with their images at the shift `sigma`), then a
    /// random block.
    fn starting(
        n: usize,
        (max_basis, b): (usize, usize),
        (null_space, wanted): (Option<MatRef<'_, f64>>, usize),
        (sigma, m): (f64, &MassMatrix),
        rng: &mut u64,
    ) -> Self {
        let mut basis = Basis::new(n, max_basis, b);
        if let Some(r) = null_space {
            basis.seed_null_space(
                r.subcols(0, r.ncols().min(wanted).min(max_basis - 2 * b)),
                sigma,
                m,
                rng,
            );
        }
        let start = Mat::from_fn(n, b, |_, _| next_uniform(rng));
        basis.append(start, m, rng);
        basis
    }

    /// An empty basis of `max_basis` columns with images and a block of `b` beyond.
    fn new(n: usize, max_basis: usize, b: usize) -> Self {
        Self {
            v: Mat::zeros(n, max_basis + b),
            mv: Mat::zeros(n, max_basis + b),
            av: Mat::zeros(n, max_basis),
            cols: 0,
            with_a: 0,
            known: 0,
        }
    }

    /// The known null vectors `r` first, exact pairs with $AR = R/(0 - \sigma)$.
    fn seed_null_space(&mut self, r: MatRef<'_, f64>, sigma: f64, m: &MassMatrix, rng: &mut u64) {
        let n = self.v.nrows();
        self.cols = append_orthonormal(&mut self.v, &mut self.mv, 0, r.to_owned(), m, rng);
        for c in 0..self.cols {
            for i in 0..n {
                self.av[(i, c)] = self.v[(i, c)] / (0.0 - sigma);
            }
        }
        self.with_a = self.cols;
        self.known = self.cols;
    }

    /// `x` made $M$-orthonormal to the basis and appended.
    fn append(&mut self, x: Mat<f64>, m: &MassMatrix, rng: &mut u64) {
        self.cols += append_orthonormal(&mut self.v, &mut self.mv, self.cols, x, m, rng);
    }

    /// $A = (K - \sigma M)^{-1}M$ applied to the newest blocks of `b` columns (`solve` takes
    /// their images $MV$, already kept), each image orthogonalised and appended, until
    /// `max_basis` columns have images; returns the block solves.
    fn expand(
        &mut self,
        b: usize,
        max_basis: usize,
        solve: &dyn Fn(MatRef<'_, f64>) -> Mat<f64>,
        m: &MassMatrix,
        rng: &mut u64,
    ) -> usize {
        let mut solves = 0;
        while self.with_a + b <= max_basis {
            let mut w = solve(self.mv.subcols(self.with_a, b));
            solves += 1;
            let known = self.known;
            if known > 0 {
                // A maps the M-orthogonal complement of the null space onto itself; what the
                // solve puts into the null space is round-off, amplified by 1/|σ| (the
                // factor of K - σM is least accurate there). Removing it keeps the elastic
                // Ritz residuals from stalling at ε λ_max / |σ|.
                let coeffs = self.mv.subcols(0, known).transpose() * &w;
                w -= self.v.subcols(0, known) * &coeffs;
            }
            for j in 0..b {
                self.av.col_mut(self.with_a + j).copy_from(w.col(j));
            }
            self.with_a += b;
            if self.cols < max_basis + b {
                self.append(w, m, rng);
            }
        }
        solves
    }

    /// Rayleigh–Ritz on the columns whose images are known. The known null vectors are
    /// exact pairs (θ = 1/(0 - σ)) and the rest of the basis is M-orthogonal to them under
    /// the deflated A, so they stay out of the small eigenproblem: their θ, 1/|σ|, is
    /// λ/|σ| (1e5–1e8) times the elastic ones' and would cost those their accuracy.
    fn rayleigh_ritz(&self, sigma: f64) -> Result<RitzStep> {
        let (with_a, known) = (self.with_a, self.known);
        let vb = self.v.subcols(0, with_a);
        let free = with_a - known;
        let t = self.mv.subcols(known, free).transpose() * self.av.subcols(known, free);
        let t = Mat::from_fn(free, free, |i, j| 0.5 * (t[(i, j)] + t[(j, i)]));
        let evd = symmetric_eigen(t.as_ref(), "Lanczos Rayleigh quotient")?;
        // Descending θ: the known pairs first, then the others.
        let theta = (0..known)
            .map(|_| 1.0 / (0.0 - sigma))
            .chain((0..free).rev().map(|i| evd.values[i]))
            .collect();
        let y = Mat::from_fn(with_a, with_a, |r, c| match (r < known, c < known) {
            (true, true) if r == c => 1.0,
            (false, false) => evd.vectors[(r - known, free - 1 - (c - known))],
            _ => 0.0,
        });
        let ritz = vb * &y;
        let a_ritz = self.av.subcols(0, with_a) * &y;
        Ok(RitzStep {
            theta,
            y,
            ritz,
            a_ritz,
        })
    }

    /// Thick restart: the first `keep` Ritz vectors and their images, then the pending block.
    fn restart(&mut self, keep: usize, step: &RitzStep) {
        let (with_a, cols) = (self.with_a, self.cols);
        let pending = self.v.subcols(with_a, cols - with_a).to_owned();
        let pending_m = self.mv.subcols(with_a, cols - with_a).to_owned();
        let m_ritz = self.mv.subcols(0, with_a) * &step.y;
        for c in 0..keep {
            self.v.col_mut(c).copy_from(step.ritz.col(c));
            self.mv.col_mut(c).copy_from(m_ritz.col(c));
            self.av.col_mut(c).copy_from(step.a_ritz.col(c));
        }
        for c in 0..pending.ncols() {
            self.v.col_mut(keep + c).copy_from(pending.col(c));
            self.mv.col_mut(keep + c).copy_from(pending_m.col(c));
        }
        self.with_a = keep;
        self.cols = keep + pending.ncols();
    }
}

impl RitzStep {
    /// The first `wanted` Ritz pairs' residuals $\|AVy - \theta Vy\|_M / |\theta|$.
    fn relative_residuals(&self, m: &MassMatrix, wanted: usize) -> Vec<f64> {
        let n = self.ritz.nrows();
        let residual = Mat::from_fn(n, wanted, |r, c| {
            self.a_ritz[(r, c)] - self.theta[c] * self.ritz[(r, c)]
        });
        let m_residual = m.mul(residual.as_ref());
        (0..wanted)
            .map(|c| {
                let norm = residual.col(c).transpose() * m_residual.col(c);
                norm.max(0.0).sqrt() / self.theta[c].abs()
            })
            .collect()
    }
}

/// Makes the columns of `x` $M$-orthonormal to `v[:, ..cols]` and to each other, appends them
/// and returns how many were appended (a column that vanishes is replaced by a random one).
///
/// Block classical Gram–Schmidt, twice, against the basis already there (two matrix–matrix
/// products per pass instead of two matrix–vector products per column), then column by column
/// within the new block, twice (Kahan's rule).
fn append_orthonormal(
    v: &mut Mat<f64>,
    mv: &mut Mat<f64>,
    cols: usize,
    x: Mat<f64>,
    m: &MassMatrix,
    rng: &mut u64,
) -> usize {
    let room = v.ncols() - cols;
    let count = x.ncols().min(room);
    let mut x = x.subcols(0, count).to_owned();
    // The columns' M-norms before any projection, from one blocked product (the reference of
    // the test for a column that vanishes).
    let mx = m.mul(x.as_ref());
    let original: Vec<f64> = (0..count)
        .map(|j| (x.col(j).transpose() * mx.col(j)).max(0.0).sqrt())
        .collect();
    if cols > 0 {
        for _ in 0..2 {
            let coeffs = mv.subcols(0, cols).transpose() * &x;
            x -= v.subcols(0, cols) * &coeffs;
        }
    }
    for j in 0..count {
        let mut tries = 0;
        let mut reference = original[j];
        loop {
            // Against the new columns appended so far (all of them after a random restart).
            let from = if tries == 0 { cols } else { 0 };
            for _ in 0..2 {
                let filled = cols + j;
                if filled > from {
                    let coeffs = mv.subcols(from, filled - from).transpose() * x.col(j);
                    let proj = v.subcols(from, filled - from) * &coeffs;
                    let mut xj = x.col_mut(j);
                    xj -= &proj;
                }
            }
            // One product per column: its M-norm and, scaled, the image M v kept beside v.
            let mx = m.mul(x.col(j).as_mat());
            let norm = (x.col(j).transpose() * mx.col(0)).max(0.0).sqrt();
            if norm > 1e-10 * reference && norm > 0.0 {
                let target = cols + j;
                let scale = 1.0 / norm;
                v.col_mut(target).copy_from(x.col(j) * scale);
                mv.col_mut(target).copy_from(mx.col(0) * scale);
                break;
            }
            tries += 1;
            assert!(tries < 10, "random vectors keep falling into the basis");
            for i in 0..x.nrows() {
                x[(i, j)] = next_uniform(rng);
            }
            reference = m_norm(x.col(j).as_mat(), m);
        }
    }
    count
}

fn m_norm(x: MatRef<'_, f64>, m: &MassMatrix) -> f64 {
    let mx = m.mul(x);
    (x.col(0).transpose() * mx.col(0)).max(0.0).sqrt()
}

/// A uniform number in [−1, 1) from a xorshift64* state (the deterministic start vectors).
pub(crate) fn next_uniform(state: &mut u64) -> f64 {
    let mut s = *state;
    s ^= s >> 12;
    s ^= s << 25;
    s ^= s >> 27;
    *state = s;
    let bits = s.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
    bits as f64 / (1u64 << 52) as f64 - 1.0
}
