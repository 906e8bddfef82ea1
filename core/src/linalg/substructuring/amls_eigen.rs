//! The lowest eigenpairs of a large body by multi-level substructuring
//! ([`MultilevelSubstructures`]), refined until each passes the residual check the other
//! solvers' pairs pass, and their count proved by a Sturm sequence check.
//!
//! The projected pencil $(\mathrm{diag}(\mu), M_A)$ is solved dense; its lowest $s$ pairs
//! (the wanted ones and a guard) are expanded to the body, $X = TY$. AMLS's truncation leaves
//! them accurate to about $(\lambda/\omega_c^2)$. The refinement closes the rest with the block
//! factor AMLS already built: Rayleigh–Ritz with the body's own $K$ and $M$ on the span of the
//! Ritz vectors $X_k$, their images $K_\sigma^{-1}MX_k$ and the previous $X_{k-1}$ (LOBPCG's
//! three blocks with the exact inverse as its preconditioner), until every wanted pair passes.

use std::time::Instant;

use faer::{Mat, MatRef};

use super::{AmlsParameters, MultilevelSubstructures, SubstructureTree};
use crate::error::LinalgError;
use crate::linalg::Result;
use crate::linalg::dense::{
    GeneralizedEigen, PairSelection, ZERO_ENERGY_RATIO, eigenvalue_scale, fix_sign,
    generalized_eigen_selected, hz_from_eigenvalue, m_orthonormal, m_orthonormal_basis,
};
#[cfg(doc)]
use crate::linalg::eigen::PartialEigenParameters;
use crate::linalg::eigen::sturm_count;
use crate::linalg::sparse::{
    MassMatrix, PairResiduals, ResidualCheck, SparseSymmetric, SymbolicFactor, pair_residuals,
};

/// A column of the refinement's search space whose $M$-norm falls below this share of its
/// norm when the columns before it are projected out adds nothing but round-off.
const BASIS_DROP: f64 = 1e-10;

/// How [`amls_lowest_modes`] solves and refines.
#[derive(Debug, Clone, PartialEq)]
pub struct AmlsEigenParameters {
    /// The reduction (the first cut-off, the shift, the leaves).
    pub reduction: AmlsParameters,
    /// Pairs carried beside the wanted ones through the refinement (their Ritz values also
    /// place the Sturm shift).
    pub guard: usize,
    /// Largest accepted relative residual $\|K\varphi - \lambda M\varphi\| / \|K\varphi\|$.
    pub tolerance: f64,
    /// The relative precision $K$ and $M$ are known to (at least ε): residuals below what it
    /// allows pass (see [`PartialEigenParameters::data_precision`]).
    pub data_precision: f64,
    /// The cut-off at least this multiple of the highest pair carried (wanted and guard): a
    /// reduction whose projected pairs reach higher is made again with the cut-off raised.
    pub cutoff_ratio: f64,
    /// Reductions tried before the last cut-off is kept as it is.
    pub max_reductions: usize,
    /// Refinement steps before it gives up.
    pub max_iterations: usize,
}

impl Default for AmlsEigenParameters {
    fn default() -> Self {
        Self {
            reduction: AmlsParameters::default(),
            guard: 16,
            cutoff_ratio: 2.0,
            max_reductions: 3,
            tolerance: 1e-8,
            data_precision: f64::EPSILON,
            max_iterations: 60,
        }
    }
}

impl AmlsEigenParameters {
    /// What the pairs' residuals are checked to.
    fn residual_check(&self) -> ResidualCheck {
        ResidualCheck {
            tolerance: self.tolerance,
            data_precision: self.data_precision,
        }
    }
}

/// Where an AMLS solve spent its effort.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AmlsStatistics {
    /// Reductions made (more than one when the first cut-off was too low).
    pub reductions: usize,
    /// The cut-off of the last, Hz.
    pub cutoff_hz: f64,
    /// Modes the substructures kept (the projected problem's size).
    pub projected: usize,
    /// Entries of the block factor.
    pub factor_entries: usize,
    /// Refinement steps.
    pub iterations: usize,
    /// The worst residual of the wanted pairs before refinement.
    pub unrefined_residual: f64,
    /// The largest relative error of the wanted elastic eigenvalues before refinement (AMLS's
    /// own accuracy at its cut-off), against the refined ones.
    pub unrefined_value_error: f64,
    /// The worst after.
    pub max_residual: f64,
    /// Seconds: the reduction, the projected solve, the refinement, the Sturm check.
    pub seconds: [f64; 4],
}

/// The lowest `wanted` pairs of $K\varphi = \lambda M\varphi$ by AMLS over `tree`, refined to
/// `params.tolerance` and counted by the Sturm check (ascending, $M$-orthonormal).
///
/// `null_space`, when given, spans known eigenvectors of eigenvalue 0 (a free body's rigid
/// motions, as [`crate::linalg::eigen::lowest_modes`] takes them): they are the first pairs, and the refinement
/// keeps every other vector $M$-orthogonal to them (the shifted solve would amplify their
/// round-off by $\lambda/|\sigma|$).
///
/// Fails with [`LinalgError::CutoffTooLow`] when the substructures keep fewer modes than
/// asked, [`LinalgError::EigenNotConverged`] when the refinement stops short of the tolerance,
/// [`LinalgError::MissedModes`] when the Sturm count finds more eigenvalues below the top pair
/// than were found, and with the reduction's and the dense solvers' errors.
pub fn amls_lowest_modes(
    k: &SparseSymmetric,
    m: &MassMatrix,
    tree: &SubstructureTree,
    wanted: usize,
    null_space: Option<MatRef<'_, f64>>,
    params: &AmlsEigenParameters,
) -> Result<(GeneralizedEigen, AmlsStatistics)> {
    let n = k.dim();
    let mut stats = AmlsStatistics::default();
    let null = null_space
        .map(|v| m_orthonormal(v.subcols(0, v.ncols().min(wanted)).to_owned(), m))
        .unwrap_or_else(|| Mat::zeros(n, 0));
    let z = null.ncols();
    let m_null = m.mul(null.as_ref());
    let elastic = wanted - z;
    let (reduced, projected, s, cutoff_hz) =
        reduce_below_cutoff((k, m, tree), (wanted, z), params, &mut stats)?;
    stats.cutoff_hz = cutoff_hz;
    stats.projected = reduced.modes();
    stats.factor_entries = reduced.factor_entries();
    let clock = Instant::now();
    // The lowest z projected pairs approximate the null space, which is given exactly.
    let x = reduced.expand(projected.vectors.subcols(z, s));
    stats.seconds[1] += clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let scale = eigenvalue_scale((0..n).map(|j| (k.get(j, j), m.get(j, j))));
    let (values, vectors, residuals) = refine(
        (k, m, &reduced),
        x,
        (&null, &m_null),
        (s, elastic, scale),
        params,
        &mut stats,
    )?;
    stats.seconds[2] = clock.elapsed().as_secs_f64();
    // The null vectors' own pairs: their Rayleigh quotients and backward errors.
    // (Their K-block is round-off: no Rayleigh–Ritz, each vector's own quotient.)
    let k_null = k.mul(null.as_ref());
    let null_values: Vec<f64> = (0..z)
        .map(|j| null.col(j).transpose() * k_null.col(j))
        .collect();
    let null_residuals = pair_residuals(
        k,
        &null_values,
        null.as_ref(),
        (k_null.as_ref(), m_null.as_ref()),
        z,
        params.residual_check(),
    )
    .residuals;
    let mut all_values = null_values;
    all_values.extend_from_slice(&values[..elastic]);
    let clock = Instant::now();
    let symbolic = SymbolicFactor::analyse(k.shifted(m, 0.0).as_faer())?;
    let sturm = sturm_count(k, m, &symbolic, &all_values, &values[elastic..])?;
    stats.seconds[3] = clock.elapsed().as_secs_f64();
    if sturm.missed() > 0 {
        return Err(LinalgError::MissedModes {
            missed: sturm.missed(),
            below: sturm.below,
            found: sturm.found,
            hz: hz_from_eigenvalue(sturm.shift),
        });
    }
    let zero_energy = all_values
        .iter()
        .take_while(|&&l| l.abs() <= ZERO_ENERGY_RATIO * scale)
        .count();
    let mut all_vectors = Mat::<f64>::zeros(n, wanted);
    all_vectors.subcols_mut(0, z).copy_from(&null);
    all_vectors
        .subcols_mut(z, elastic)
        .copy_from(vectors.subcols(0, elastic));
    let mut all_residuals = null_residuals;
    all_residuals.extend_from_slice(&residuals[..elastic]);
    Ok((
        GeneralizedEigen {
            values: all_values,
            vectors: all_vectors,
            residuals: all_residuals,
            zero_energy,
            sturm: Some(sturm),
        },
        stats,
    ))
}

/// The reduction, again with a higher cut-off while the projected problem's highest pair (the
/// guard's top) lies above the cut-off over `cutoff_ratio`: AMLS is accurate only well below
/// its cut-off, and the first cut-off is a guess. The reduced body, its lowest `z + s` projected
/// pairs (`z` null vectors, `s` the elastic ones and the guard), `s`, and the last cut-off, Hz.
fn reduce_below_cutoff(
    (k, m, tree): (&SparseSymmetric, &MassMatrix, &SubstructureTree),
    (wanted, z): (usize, usize),
    params: &AmlsEigenParameters,
    stats: &mut AmlsStatistics,
) -> Result<(MultilevelSubstructures, GeneralizedEigen, usize, f64)> {
    let n = k.dim();
    let elastic = wanted - z;
    let mut reduction = params.reduction.clone();
    let (reduced, projected, s) = loop {
        stats.reductions += 1;
        let retry = stats.reductions < params.max_reductions;
        let clock = Instant::now();
        let reduced = MultilevelSubstructures::new(k, m, tree, &reduction)?;
        stats.seconds[0] += clock.elapsed().as_secs_f64();
        let r = reduced.modes();
        let needed = (wanted + params.guard).min(n);
        if r < needed && retry {
            // Too few modes to carry: the next cut-off from the count the projected problem
            // holds below this one, as a solid's eigenvalue count grows (N ∝ f³), with the
            // margin the ratio asks for (doubled at least).
            let below = projected_count_below(&reduced, reduction.cutoff_hz)?;
            let growth = (needed as f64 / below.max(1) as f64).cbrt();
            reduction.cutoff_hz *= (1.1 * params.cutoff_ratio * growth).max(2.0);
            continue;
        }
        if r < wanted {
            return Err(LinalgError::CutoffTooLow {
                kept: r,
                wanted,
                hz: reduction.cutoff_hz,
            });
        }
        let s = (elastic + params.guard).min(r - z);
        let clock = Instant::now();
        let projected = reduced.projected_pairs(PairSelection::Lowest(z + s))?;
        stats.seconds[1] += clock.elapsed().as_secs_f64();
        let top_hz = hz_from_eigenvalue(projected.values[z + s - 1] + reduction.shift);
        if params.cutoff_ratio * top_hz > reduction.cutoff_hz && retry {
            reduction.cutoff_hz = 1.05 * params.cutoff_ratio * top_hz;
            continue;
        }
        break (reduced, projected, s);
    };
    Ok((reduced, projected, s, reduction.cutoff_hz))
}

/// Refines the expanded Ritz vectors `x` until every elastic pair's residual passes: LOBPCG's
/// three blocks (the current Ritz vectors, their images under $K_\sigma^{-1}M$ and the step),
/// with AMLS's block factor as the exact inverse, every vector kept $M$-orthogonal to the
/// `null` vectors. The values, vectors and residuals of the `s` pairs (`elastic` wanted); the
/// statistics say the iterations, the unrefined residual and value error.
fn refine(
    (k, m, reduced): (&SparseSymmetric, &MassMatrix, &MultilevelSubstructures),
    x: Mat<f64>,
    (null, m_null): (&Mat<f64>, &Mat<f64>),
    (s, elastic, scale): (usize, usize, f64),
    params: &AmlsEigenParameters,
    stats: &mut AmlsStatistics,
) -> Result<(Vec<f64>, Mat<f64>, Vec<f64>)> {
    let n = k.dim();
    let mut iteration = 0;
    // The search space: the current Ritz vectors, their images under K_σ⁻¹M and the previous
    // Ritz vectors (LOBPCG's three blocks, with the exact inverse as its preconditioner).
    let mut blocks = vec![x];
    let mut unrefined = Vec::new();
    let (values, vectors, residuals) = loop {
        let columns: usize = blocks.iter().map(|b| b.ncols()).sum();
        let mut space = Mat::<f64>::zeros(n, columns);
        let mut at = 0;
        for block in &blocks {
            space.subcols_mut(at, block.ncols()).copy_from(block);
            at += block.ncols();
        }
        for _ in 0..2 {
            let coefficients = m_null.transpose() * &space;
            space -= null * &coefficients;
        }
        let basis = m_orthonormal_basis(space.as_ref(), m, BASIS_DROP)?;
        drop(space);
        if basis.ncols() < s {
            return Err(LinalgError::EigenNotConverged {
                converged: 0,
                wanted: elastic,
                residual: f64::INFINITY,
            });
        }
        let (values, vectors, checked) = rayleigh_ritz(k, m, basis.as_ref(), s, scale, params)?;
        let residuals = checked.residuals;
        let worst = residuals[..elastic].iter().fold(0.0f64, |a, &b| a.max(b));
        let passed = checked.passed[..elastic].iter().all(|&p| p);
        if iteration == 0 {
            stats.unrefined_residual = worst;
            unrefined = values[..elastic].to_vec();
        }
        stats.max_residual = worst;
        if passed {
            break (values, vectors, residuals);
        }
        if iteration == params.max_iterations {
            return Err(LinalgError::EigenNotConverged {
                converged: checked.passed[..elastic].iter().filter(|&&p| p).count(),
                wanted: elastic,
                residual: worst,
            });
        }
        iteration += 1;
        // Soft locking: the image and the step only of the pairs still short of the
        // tolerance (and the guard's, which set how fast the others converge).
        let active: Vec<usize> = (0..vectors.ncols())
            .filter(|&j| j >= elastic || !checked.passed[j])
            .collect();
        let pick = |a: &Mat<f64>| Mat::from_fn(n, active.len(), |i, c| a[(i, active[c])]);
        let m_vectors = m.mul(vectors.as_ref());
        let mut image = pick(&m_vectors);
        reduced.solve_in_place(image.as_mut());
        // The step's direction: what the new Ritz vectors hold beyond the previous ones
        // (M-orthogonal to them; the previous vectors themselves would lie along the new ones
        // to round-off and drop out of the basis).
        let previous = blocks.swap_remove(0);
        let overlap = m_vectors.transpose() * &previous;
        let direction = &previous * overlap.transpose();
        let step = pick(&(&vectors - &direction));
        blocks = vec![vectors, image, step];
    };
    stats.iterations = iteration;
    stats.unrefined_value_error = unrefined
        .iter()
        .zip(&values)
        .map(|(a, b)| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE))
        .fold(0.0f64, f64::max);
    Ok((values, vectors, residuals))
}

/// How many eigenvalues of the projected pencil lie below `hz` (all its pairs solved: called
/// when the reduction kept too few modes to carry, so the problem is small).
fn projected_count_below(reduced: &MultilevelSubstructures, hz: f64) -> Result<usize> {
    let all = reduced.projected_pairs(PairSelection::All)?;
    Ok(all
        .values
        .iter()
        .filter(|&&v| hz_from_eigenvalue(v + reduced.shift()) <= hz)
        .count())
}

/// The lowest `count` Ritz pairs of $(K, M)$ on the span of `x`, ascending, $M$-orthonormal,
/// with the residual check every sparse solver's pairs pass ([`pair_residuals`]).
fn rayleigh_ritz(
    k: &SparseSymmetric,
    m: &MassMatrix,
    x: MatRef<'_, f64>,
    count: usize,
    scale: f64,
    params: &AmlsEigenParameters,
) -> Result<(Vec<f64>, Mat<f64>, PairResiduals)> {
    let kx = k.mul(x);
    let mx = m.mul(x);
    let k_r = x.transpose() * &kx;
    let m_r = x.transpose() * &mx;
    let small = generalized_eigen_selected(
        k_r.as_ref(),
        m_r.as_ref(),
        "AMLS Rayleigh–Ritz",
        PairSelection::Lowest(count),
    )?;
    let mut vectors = x * &small.vectors;
    let kv = &kx * &small.vectors;
    let mv = &mx * &small.vectors;
    let zero_energy = small
        .values
        .iter()
        .take_while(|&&l| l.abs() <= ZERO_ENERGY_RATIO * scale)
        .count();
    let checked = pair_residuals(
        k,
        &small.values,
        vectors.as_ref(),
        (kv.as_ref(), mv.as_ref()),
        zero_energy,
        params.residual_check(),
    );
    for j in 0..vectors.ncols() {
        fix_sign(vectors.as_mut().col_mut(j));
    }
    Ok((small.values, vectors, checked))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};
    use crate::linalg::dense::generalized_eigen;
    use crate::linalg::sparse::negative_shift;

    #[test]
    fn refined_pairs_equal_the_dense_pencils_and_none_is_missed() {
        for (bricks, leaf, cutoff_hz, wanted) in
            [([8, 4, 2], 60, 15.0, 12), ([12, 6, 3], 150, 45.0, 20)]
        {
            let model = slab(&SlabParameters::refined(bricks).unwrap());
            let tree = model.substructure_tree(leaf).unwrap();
            let params = AmlsEigenParameters {
                reduction: AmlsParameters {
                    cutoff_hz,
                    shift: negative_shift(&model.k, &model.m),
                    ..AmlsParameters::default()
                },
                ..AmlsEigenParameters::default()
            };
            let rigid = model.rigid_body_modes();
            let (eigen, stats) = amls_lowest_modes(
                &model.k,
                &model.m,
                &tree,
                wanted,
                Some(rigid.as_ref()),
                &params,
            )
            .unwrap();
            let expected = generalized_eigen(
                model.k.to_dense().as_ref(),
                model.m.to_dense().as_ref(),
                "test body",
            )
            .unwrap();
            assert_eq!(eigen.values.len(), wanted);
            assert_eq!(
                eigen.zero_energy, 6,
                "{bricks:?}: the free body's rigid motions"
            );
            let top = expected.values.last().unwrap().abs();
            for (i, (a, b)) in eigen.values.iter().zip(&expected.values).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-8 * b.abs() + 1e-12 * top,
                    "{bricks:?} pair {i}: {a} against {b}"
                );
            }
            assert!(eigen.max_residual() <= params.tolerance);
            let sturm = eigen.sturm.unwrap();
            assert_eq!((sturm.missed(), sturm.below), (0, wanted), "{bricks:?}");
            // AMLS alone: upper bounds within a few per cent at twice the pairs carried.
            assert!(stats.unrefined_value_error < 0.05, "{stats:?}");
            // The refinement did work: the substructures alone were not this accurate.
            assert!(
                stats.unrefined_residual > 1e3 * stats.max_residual,
                "{stats:?}"
            );
            assert!(
                stats.iterations >= 1 && stats.projected < model.dof_count(),
                "{stats:?}"
            );
            // A first cut-off below twice the pairs carried is raised, once at least.
            let carried = hz_from_eigenvalue(expected.values[wanted + params.guard - 1]);
            assert!(stats.cutoff_hz >= 2.0 * carried * (1.0 - 1e-3), "{stats:?}");
            if cutoff_hz < 2.0 * carried {
                assert!(stats.reductions >= 2, "{stats:?}");
            }
        }
    }
}
