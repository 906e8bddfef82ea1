//! The generalised symmetric-definite eigenproblem $K\Psi = M\Psi\Lambda$, solved densely and
//! checked pair by pair.
//!
//! With $D = \mathrm{diag}(M)^{-1/2}$ (balancing: every DOF gets unit mass whatever its unit,
//! metres or millimetres, translations or rotations) and $s = \max|DKD|$ (scaling),
//!
//! $$\tilde K = DKD/s,\quad \tilde M = DMD = LL^T,\quad C = L^{-1}\tilde K L^{-T},\quad
//! CU = U\Theta,\quad \Psi = DL^{-T}U,\quad \Lambda = s\,\Theta.$$
//!
//! $C$ goes through [`symmetric_eigen`](super::symmetric_eigen()) (scaled again, checked, faer
//! then nalgebra). Every pair of the original pencil is then checked by its normwise backward
//! error
//!
//! $$\eta_j = \frac{\|K\psi_j - \lambda_j M\psi_j\|_2}{(\|K\|_1 + |\lambda_j|\,\|M\|_1)\,
//! \|\psi_j\|_2} \le 10^{-10}$$
//!
//! and the vectors by $\max|\Psi^TM\Psi - I| \le 10^{-8}$; a result that fails falls back to
//! the next kernel, and when none passes the solve fails with
//! `LinalgError::EigenCheckFailed`.
//!
//! Pairs with $|\lambda| \le 10^{-12}\lambda_{max}$ count as zero-energy (rigid-body motions or
//! mechanisms): a dense solve's rigid eigenvalues are round-off of $\varepsilon\lambda_{max}$,
//! so the threshold is the pencil's own, means the same in m–kg–s and mm–t–s, and does not
//! change when a coordinate is scaled (a reduced model's mass-normalised modal coordinates
//! beside its constraint modes).

use crate::error::LinalgError;
use faer::{Mat, MatRef, Side};

use super::{SymmetricEigenKernel, orthonormality_defect, symmetric_eigen_prefix};
use crate::error::{MatrixLabel, PencilPart};
use crate::linalg::Result;

/// Largest accepted normwise backward error $\eta_j$ of a dense generalised eigenpair.
pub const PENCIL_BACKWARD_ERROR: f64 = 1e-10;

/// Largest accepted $\max|\Psi^TM\Psi - I|$ of dense generalised eigenvectors.
pub const MASS_ORTHONORMALITY: f64 = 1e-8;

/// Eigenvalues $|\lambda| \le$ this $\cdot\,\lambda_{max}$ count as zero-energy, with
/// $\lambda_{max}$ the pencil's largest eigenvalue (dense solves) or its estimate
/// [`eigenvalue_scale`] (a body's partial solves).
///
/// Rigid-body eigenvalues of a dense solve are round-off, a few $\varepsilon\lambda_{max}$
/// ($\le 10^{-15}\lambda_{max}$ on the test bodies); those of the partial solver, whose
/// rigid motions enter exact, $10^{-18}$ of it. The lowest elastic eigenvalue of the three
/// P2-tetrahedral parts in tests/bodies lies at $2\cdot10^{-7}$, $10^{-6}$ and (a slender rod
/// with one badly shaped element) $3.5\cdot 10^{-11}$ of $\lambda_{max}$.
pub const ZERO_ENERGY_RATIO: f64 = 1e-12;

/// Eigenpairs of $K\Psi = M\Psi\Lambda$, eigenvalues ascending, vectors mass-normalised
/// ($\Psi^T M \Psi = I$) with a deterministic sign (see [`fix_sign`]).
#[derive(Debug, Clone)]
pub struct GeneralizedEigen {
    /// Eigenvalues $\omega^2$ in (rad/s)², ascending.
    pub values: Vec<f64>,
    /// Mass-normalised eigenvectors, one per column.
    pub vectors: Mat<f64>,
    /// Each pair's relative residual: $\|K\psi - \lambda M\psi\| / \|K\psi\|$ for an elastic
    /// pair, the backward error $\eta$ (above) for a zero-energy one (whose $K\psi$ is
    /// round-off).
    pub residuals: Vec<f64>,
    /// How many leading pairs have zero energy (rigid-body motions, mechanisms).
    pub zero_energy: usize,
    /// The Sturm sequence check of a partial solve (none for a complete dense solve, which
    /// misses nothing by construction): how many eigenvalues lie below a shift just above the
    /// pairs found, and how many the solver found there.
    pub sturm: Option<crate::linalg::eigen::SturmCount>,
}

impl GeneralizedEigen {
    /// Frequencies in Hz ($\sqrt{\max(\lambda,0)}/2\pi$), in the order of `values`.
    pub fn hz(&self) -> Vec<f64> {
        self.values.iter().map(|&l| hz_from_eigenvalue(l)).collect()
    }

    /// Frequencies of the elastic pairs (after the zero-energy ones), Hz.
    pub fn elastic_hz(&self) -> Vec<f64> {
        self.hz()[self.zero_energy.min(self.values.len())..].to_vec()
    }

    /// Relative residuals of the elastic pairs, in the order of [`Self::elastic_hz`].
    pub fn elastic_residuals(&self) -> Vec<f64> {
        self.residuals[self.zero_energy.min(self.residuals.len())..].to_vec()
    }

    /// The worst relative residual of all pairs (0 for none).
    pub fn max_residual(&self) -> f64 {
        self.residuals.iter().copied().fold(0.0, f64::max)
    }

    /// The largest relative difference of the elastic eigenvalues of two solves of one pencil,
    /// paired by order after the zero-energy pairs of either (their values are round-off in
    /// both); 0 when neither has an elastic pair.
    pub fn elastic_values_apart(&self, other: &Self) -> f64 {
        self.values
            .iter()
            .zip(&other.values)
            .skip(self.zero_energy.max(other.zero_energy))
            .map(|(a, b)| (a - b).abs() / b.abs())
            .fold(0.0f64, f64::max)
    }

    /// The first `count` pairs.
    pub fn first(&self, count: usize) -> Self {
        let count = count.min(self.values.len());
        Self {
            values: self.values[..count].to_vec(),
            vectors: self.vectors.subcols(0, count).to_owned(),
            residuals: self.residuals[..count.min(self.residuals.len())].to_vec(),
            zero_energy: self.zero_energy.min(count),
            sturm: self.sturm,
        }
    }
}

/// $f = \sqrt{\max(\lambda, 0)} / 2\pi$ in Hz for an eigenvalue $\lambda = \omega^2$.
pub fn hz_from_eigenvalue(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// An estimate of $\lambda_{max}$ from the diagonal pairs $(K_{ii}, M_{ii})$, in (rad/s)²:
/// $\max_i K_{ii}/M_{ii}$ (within a factor of 3 of $\lambda_{max}$ on the test bodies). It
/// scales as eigenvalues do under a change of units or of one coordinate.
pub fn eigenvalue_scale(diagonal: impl Iterator<Item = (f64, f64)>) -> f64 {
    diagonal
        .map(|(k, m)| k / m)
        .filter(|r| r.is_finite())
        .fold(0.0f64, f64::max)
}

/// Which of a dense problem's ascending pairs a caller keeps: only those are checked and
/// returned ([`generalized_eigen_selected`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PairSelection {
    /// Every pair.
    All,
    /// The lowest ones, at most this many.
    Lowest(usize),
    /// The lowest `always` pairs (a free body's rigid motions), then those up to `hz`
    /// ([`hz_from_eigenvalue`] of each at most it).
    UpToHz {
        /// The cut-off, Hz.
        hz: f64,
        /// Pairs kept whatever their frequency.
        always: usize,
    },
}

impl PairSelection {
    /// How many of the ascending `values` it keeps.
    pub fn count(self, values: &[f64]) -> usize {
        match self {
            Self::All => values.len(),
            Self::Lowest(k) => k.min(values.len()),
            Self::UpToHz { hz, always } => {
                let always = always.min(values.len());
                always
                    + values[always..]
                        .iter()
                        .take_while(|&&l| hz_from_eigenvalue(l) <= hz)
                        .count()
            }
        }
    }
}

/// Solves $K\Psi = M\Psi\Lambda$ for symmetric $K$ and symmetric positive definite $M$, as the
/// module says: balanced, scaled, checked, with a fallback kernel.
///
/// `what` names the problem in errors ("fixed-interface", "free-free", ...).
pub fn generalized_eigen(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    what: impl Into<MatrixLabel>,
) -> Result<GeneralizedEigen> {
    generalized_eigen_selected(k, m, what, PairSelection::All)
}

/// [`generalized_eigen`] returning only the pairs `selection` keeps. The complete problem is
/// solved, but only the kept pairs are transformed back and checked (both checks, with the
/// whole problem's tolerances): for the modes below a cut-off, $n^2k$ instead of $n^3$.
pub fn generalized_eigen_selected(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    what: impl Into<MatrixLabel>,
    selection: PairSelection,
) -> Result<GeneralizedEigen> {
    let what: MatrixLabel = what.into();
    let n = k.nrows();
    assert_eq!((k.ncols(), m.nrows(), m.ncols()), (n, n, n));
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: vec![],
            vectors: Mat::zeros(0, 0),
            residuals: vec![],
            zero_energy: 0,
            sturm: None,
        });
    }
    check_finite((k, m), &what)?;
    // Balancing by the mass diagonal (M is positive definite, so M_ii > 0 unless it is not).
    let d = mass_balancing(m, &what)?;
    let kb = Mat::from_fn(n, n, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]) * d[i] * d[j]);
    let s = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max(kb[(i, j)].abs()));
    let s = if s > 0.0 { s } else { 1.0 };
    let k_tilde = Mat::from_fn(n, n, |i, j| kb[(i, j)] / s);
    let m_tilde = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]) * d[i] * d[j]);
    let llt = m_tilde
        .llt(Side::Lower)
        .map_err(|_| LinalgError::NotPositiveDefinite {
            matrix: what.part(PencilPart::Mass),
        })?;
    let l = llt.L();
    // C = L^{-1} K̃ L^{-T}: two triangular solves.
    let mut x = k_tilde;
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(c.as_mut());

    let norm_k = norm1(k);
    let norm_m = norm1(m);
    let mut worst = f64::INFINITY;
    for kernel in [SymmetricEigenKernel::Faer, SymmetricEigenKernel::Nalgebra] {
        // C's eigenvalues times s are the problem's.
        let keep =
            |theta: &[f64]| selection.count(&theta.iter().map(|t| t * s).collect::<Vec<_>>());
        let standard = match symmetric_eigen_prefix(c.as_ref(), what.clone(), &[kernel], &keep) {
            Ok(e) => e,
            Err(LinalgError::EigenCheckFailed { residual, .. }) => {
                worst = worst.min(residual);
                continue;
            }
            Err(e) => return Err(e),
        };
        let mut vectors = standard.vectors;
        l.transpose()
            .solve_upper_triangular_in_place(vectors.as_mut());
        for j in 0..vectors.ncols() {
            for i in 0..n {
                vectors[(i, j)] *= d[i];
            }
            fix_sign(vectors.as_mut().col_mut(j));
        }
        let values: Vec<f64> = standard.values.iter().map(|&t| t * s).collect();
        // The whole spectrum's scale (kept pairs or not): what zero energy is judged against.
        let scale = standard.largest * s;
        let check = check_pencil(k, m, &values, vectors.as_ref(), norm_k, norm_m, scale);
        if check.backward_error <= PENCIL_BACKWARD_ERROR
            && check.orthonormality <= MASS_ORTHONORMALITY
        {
            return Ok(GeneralizedEigen {
                values,
                vectors,
                residuals: check.residuals,
                zero_energy: check.zero_energy,
                sturm: None,
            });
        }
        worst = worst.min(
            (check.backward_error / PENCIL_BACKWARD_ERROR)
                .max(check.orthonormality / MASS_ORTHONORMALITY)
                * PENCIL_BACKWARD_ERROR,
        );
    }
    Err(LinalgError::EigenCheckFailed {
        what,
        residual: worst,
        tolerance: PENCIL_BACKWARD_ERROR,
    })
}

/// Every entry of the pencil finite; the first that is not is named.
fn check_finite((k, m): (MatRef<'_, f64>, MatRef<'_, f64>), what: &MatrixLabel) -> Result<()> {
    let n = k.nrows();
    for (part, a) in [(PencilPart::Stiffness, k), (PencilPart::Mass, m)] {
        for j in 0..n {
            for i in 0..n {
                if !a[(i, j)].is_finite() {
                    return Err(LinalgError::NotFinite {
                        what: what.part(part),
                        row: i,
                        col: j,
                    });
                }
            }
        }
    }
    Ok(())
}

/// $1/\sqrt{M_{ii}}$ per row; a diagonal entry that is not positive is named.
fn mass_balancing(m: MatRef<'_, f64>, what: &MatrixLabel) -> Result<Vec<f64>> {
    let n = m.nrows();
    let mut d = vec![0.0; n];
    for (i, di) in d.iter_mut().enumerate() {
        let mii = m[(i, i)];
        if mii <= 0.0 {
            return Err(LinalgError::NonPositivePivot {
                matrix: what.part(PencilPart::Mass),
                index: i,
            });
        }
        *di = 1.0 / mii.sqrt();
    }
    Ok(d)
}

/// $\|A\|_1$, the largest absolute column sum.
fn norm1(a: MatRef<'_, f64>) -> f64 {
    (0..a.ncols())
        .map(|j| (0..a.nrows()).map(|i| a[(i, j)].abs()).sum::<f64>())
        .fold(0.0f64, f64::max)
}

/// The checks of a dense generalised eigen-solution.
#[derive(Debug, Clone)]
pub struct PencilCheck {
    /// The worst normwise backward error $\eta_j$.
    pub backward_error: f64,
    /// $\max|\Psi^TM\Psi - I|$.
    pub orthonormality: f64,
    /// Each pair's relative residual (see [`GeneralizedEigen::residuals`]).
    pub residuals: Vec<f64>,
    /// Leading pairs with $|\lambda| \le$ [`ZERO_ENERGY_RATIO`] $\cdot$ scale.
    pub zero_energy: usize,
}

/// Checks eigenpairs $(\lambda_j, \psi_j)$ of $(K, M)$: backward errors, relative residuals,
/// mass-orthonormality and the zero-energy count against `scale` ($\lambda_{max}$ or its
/// estimate).
pub fn check_pencil(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    values: &[f64],
    vectors: MatRef<'_, f64>,
    norm_k: f64,
    norm_m: f64,
    scale: f64,
) -> PencilCheck {
    let count = values.len();
    assert_eq!(vectors.ncols(), count, "one vector per eigenvalue");
    let kv = k * vectors;
    let mv = m * vectors;
    let zero_energy = values
        .iter()
        .take_while(|&&l| l.abs() <= ZERO_ENERGY_RATIO * scale)
        .count();
    let mut backward_error = 0.0f64;
    let mut residuals = Vec::with_capacity(count);
    for (j, &lambda) in values.iter().enumerate() {
        let mut r2 = 0.0;
        let mut k2 = 0.0;
        let mut v2 = 0.0;
        for i in 0..vectors.nrows() {
            r2 += (kv[(i, j)] - lambda * mv[(i, j)]).powi(2);
            k2 += kv[(i, j)].powi(2);
            v2 += vectors[(i, j)].powi(2);
        }
        let r = r2.sqrt();
        let eta = r / ((norm_k + lambda.abs() * norm_m) * v2.sqrt()).max(f64::MIN_POSITIVE);
        let relative = if j < zero_energy {
            eta
        } else {
            r / k2.sqrt().max(f64::MIN_POSITIVE)
        };
        backward_error = nan_max(backward_error, eta);
        residuals.push(if relative.is_nan() {
            f64::INFINITY
        } else {
            relative
        });
    }
    let orthonormality = orthonormality_defect(vectors, mv.as_ref());
    PencilCheck {
        backward_error,
        orthonormality,
        residuals,
        zero_energy,
    }
}

fn nan_max(a: f64, b: f64) -> f64 {
    if b.is_nan() { f64::INFINITY } else { a.max(b) }
}

/// Fixes a vector's sign deterministically: the first entry whose magnitude exceeds $10^{-8}$
/// of the largest is made positive. ("Largest entry positive" is ambiguous for antisymmetric
/// modes, whose largest entries come in ± pairs.)
pub fn fix_sign(mut v: faer::ColMut<'_, f64>) {
    let largest = (0..v.nrows()).fold(0.0f64, |a, i| a.max(v[i].abs()));
    if largest == 0.0 {
        return;
    }
    if let Some(i) = (0..v.nrows()).find(|&i| v[i].abs() > 1e-8 * largest)
        && v[i] < 0.0
    {
        for r in 0..v.nrows() {
            v[r] = -v[r];
        }
    }
}
