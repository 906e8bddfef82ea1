//! The lowest free-free pairs of a large unrestrained body, by routes that fall back on each
//! other, each result checked pair by pair and by a Sturm count.
//!
//! $K$ is singular, so the factor is of $K - \sigma M$ with $\sigma < 0$. Two things decide
//! whether the elastic pairs come out accurate:
//!
//! 1. **The null space must be the stored pencil's own.** Rigid motions built from the node
//!    coordinates are $K$'s null space only as far as the data: coordinates written with six
//!    digits, or $K$ with fourteen (CalculiX) leave $KR = E \ne 0$, and the true near-null
//!    vectors are $R + \sum_j c_j\varphi_j$ with $c_j \sim \|E\|/\lambda_j$. Deflating $R$ as if
//!    exact then puts errors of that size into every elastic pair. So the null space is first
//!    *refined*: inverse subspace iteration $Z \leftarrow (K - \sigma M)^{-1}MZ$ from $R$ (or
//!    from random vectors when the coordinates do not give $R$) with Rayleigh–Ritz on $(K, M)$,
//!    which damps the elastic part by $|\sigma|/(\lambda_j - \sigma)$ per step; the pairs below
//!    the zero-energy threshold are then deflated exactly.
//! 2. **Left to the iteration, the null vectors cost the elastic pairs $\varepsilon
//!    \lambda_{max}/|\sigma|$** (the factor's error along them, $10^{-6}$ when
//!    $\sigma = -10^{-10}\lambda_{max}$), which is why they are deflated and never iterated.
//!
//! Routes, in order, each checked by [`lowest_modes`]' residual test on the original pencil:
//! (1) the small shift of [`negative_shift`] with the refined null space deflated; (2) a shift
//! from the body's spectrum, $\sigma = -\tilde\lambda_1/2$ with $\tilde\lambda_1$ the lowest
//! elastic Ritz value of the refinement, more restarts and a larger block; (3) the complete
//! dense solve for bodies of up to [`COMPLETE_EIGEN_LIMIT`] DOF. The error, when every route
//! fails, lists each route and its worst residual. An accepted set is Sturm-checked
//! ([`sturm_count`]); a count above the pairs found retries with more pairs, then fails with
//! [`LinalgError::MissedModes`].

use faer::{Mat, MatRef};

use super::{COMPLETE_EIGEN_LIMIT, ReleasableFactor};
use crate::{
    Error, Result,
    error::{EigenAttempt, EigenRoute, LinalgError},
    fem::{FeModel, RigidMotions},
    linalg::{
        GeneralizedEigen, MassMatrix, PartialEigenParameters, PartialEigenStatistics,
        SparseSymmetric, SturmCount, SymbolicFactor, SymmetricFactor, ZERO_ENERGY_RATIO,
        eigenvalue_scale, generalized_eigen, hz_from_eigenvalue, lowest_modes, m_orthonormal,
        negative_shift, nested_dissection, next_uniform, sturm_count,
    },
};

/// Multiple of the data's precision $\delta$ (the rigid-motion defect) times $\lambda_{max}$
/// below which a refined null vector's eigenvalue counts as zero: 11-digit matrices (Nastran's
/// large field) put the rigid eigenvalues at ~$10^{-10}\lambda_{max}$, above the round-off
/// threshold [`ZERO_ENERGY_RATIO`] of exact data.
const NULL_PRECISION_FACTOR: f64 = 16.0;

/// Settings of [`free_body_pairs`].
#[derive(Debug, Clone, PartialEq)]
pub struct FreeBodyParameters {
    /// Steps of inverse subspace iteration refining rigid motions known from the geometry.
    pub null_steps_from_geometry: usize,
    /// Steps when the null space starts from random vectors.
    pub null_steps_from_random: usize,
    /// Extra columns beyond the expected null space (they estimate the lowest elastic
    /// eigenvalue and catch a mechanism).
    pub null_extra: usize,
    /// Retries with more pairs when the Sturm count finds modes the solver missed.
    pub sturm_retries: usize,
    /// Seed of the random start vectors.
    pub seed: u64,
}

impl Default for FreeBodyParameters {
    fn default() -> Self {
        Self {
            null_steps_from_geometry: 2,
            null_steps_from_random: 5,
            null_extra: 3,
            sturm_retries: 2,
            seed: 0x0dd_ba11,
        }
    }
}

/// The `wanted` lowest pairs of `model`'s pencil (an unrestrained body: rigid motions first),
/// by the routes of this module; `sturm` is set on the result of a partial solve.
pub fn free_body_pairs(
    model: &FeModel,
    wanted: usize,
    params: &FreeBodyParameters,
) -> Result<GeneralizedEigen> {
    let n = model.dof_count();
    let (k, m) = (&model.k, &model.m);
    let scale = eigenvalue_scale((0..n).map(|j| (k.get(j, j), m.get(j, j))));
    let sigma0 = negative_shift(k, m);
    let shifted = k.shifted(m, sigma0);
    let coords = model.dof_positions();
    let order = nested_dissection(shifted.as_faer(), &coords);
    let symbolic = SymbolicFactor::analyse_ordered(shifted.as_faer(), order.as_deref())?;
    let factor0 =
        SymmetricFactor::sparse(shifted.as_faer(), &symbolic, "shifted stiffness K - σM")?;
    drop(shifted);

    let (null, data_precision) = free_null_space(model, &factor0, scale, params)?;
    let null_count = null.vectors.ncols().min(wanted);
    let null_vectors = null.vectors.subcols(0, null_count).to_owned();

    let mut failed = Vec::new();
    let base = PartialEigenParameters {
        data_precision,
        ..Default::default()
    };
    // Route 1: the small shift, the refined null space deflated.
    let route1 = EigenRoute::SmallShift {
        shift: sigma0,
        null_vectors: null_count,
    };
    let shifted0 = || {
        SymmetricFactor::sparse(
            k.shifted(m, sigma0).as_faer(),
            &symbolic,
            "shifted stiffness K - σM",
        )
    };
    let mut factor0 = ReleasableFactor::new(factor0, shifted0);
    let pencil = SturmPencil {
        k,
        m,
        symbolic: &symbolic,
    };
    match sturm_checked(
        pencil,
        &mut factor0,
        sigma0,
        wanted,
        null_vectors.as_ref(),
        &base,
        params.sturm_retries,
    ) {
        Ok((eigen, _)) => return Ok(eigen),
        Err(e) => failed.push(attempt(route1, wanted, e)?),
    }
    drop(factor0);
    // Route 2: a shift from the spectrum, a larger block, more restarts.
    if let Some(lowest) = null.lowest_elastic
        && -0.5 * lowest < sigma0
    {
        let sigma1 = -0.5 * lowest;
        let route2 = EigenRoute::SpectrumShift {
            shift: sigma1,
            block: SPECTRUM_SHIFT_BLOCK,
            restarts: SPECTRUM_SHIFT_RESTARTS,
        };
        let result = spectrum_shift_route(
            pencil,
            (sigma1, wanted),
            null_vectors.as_ref(),
            &base,
            params.sturm_retries,
        );
        match result {
            Ok((eigen, _)) => return Ok(eigen),
            Err(e) => failed.push(attempt(route2, wanted, e)?),
        }
    }
    // Route 3: the complete dense solve of a body small enough.
    if n <= COMPLETE_EIGEN_LIMIT {
        let route3 = EigenRoute::CompleteDense;
        match generalized_eigen(
            model.k_dense().as_ref(),
            model.m_dense().as_ref(),
            "free-free",
        ) {
            Ok(all) => return Ok(all.first(wanted)),
            Err(e) => failed.push(attempt(route3, wanted, e.into())?),
        }
    }
    Err(Error::Linalg(LinalgError::EigenRoutesFailed {
        wanted,
        routes: failed,
    }))
}

/// The body's refined null space from its geometric rigid motions (when its K was made from
/// its coordinates), and the precision its matrices are known to: the coordinates' rigid-motion
/// defect, at least ε.
fn free_null_space(
    model: &FeModel,
    factor0: &SymmetricFactor,
    scale: f64,
    params: &FreeBodyParameters,
) -> Result<(NullSpace, f64)> {
    let (k, m) = (&model.k, &model.m);
    let geometric =
        (model.rigid_motions == RigidMotions::FromGeometry).then(|| model.rigid_body_modes());
    let data_precision = if geometric.is_some() {
        model.rigid_motion_defect().max(f64::EPSILON)
    } else {
        f64::EPSILON
    };
    let null = refined_null_space(
        k,
        m,
        factor0,
        geometric.as_ref().map(|r| r.as_ref()),
        model.dofs.rigid_body_count(),
        // Matrices known to δ leave their rigid eigenvalues at ~δ λmax, not at round-off.
        scale * ZERO_ENERGY_RATIO.max(NULL_PRECISION_FACTOR * data_precision),
        params,
    )?;
    Ok((null, data_precision))
}

/// The second route: the shift `sigma1` from the spectrum (half the lowest elastic Ritz value
/// below zero), a larger block and more restarts than `base`, Sturm-checked.
fn spectrum_shift_route(
    pencil: SturmPencil<'_>,
    (sigma1, wanted): (f64, usize),
    null_vectors: MatRef<'_, f64>,
    base: &PartialEigenParameters,
    retries: usize,
) -> Result<(GeneralizedEigen, PartialEigenStatistics)> {
    let factor1 = || {
        SymmetricFactor::sparse(
            pencil.k.shifted(pencil.m, sigma1).as_faer(),
            pencil.symbolic,
            "K - σM",
        )
    };
    factor1().map_err(Error::from).and_then(|made| {
        sturm_checked(
            pencil,
            &mut ReleasableFactor::new(made, factor1),
            sigma1,
            wanted,
            null_vectors.as_ref(),
            &PartialEigenParameters {
                block_size: SPECTRUM_SHIFT_BLOCK,
                max_restarts: SPECTRUM_SHIFT_RESTARTS,
                ..base.clone()
            },
            retries,
        )
    })
}

/// Vectors per Lanczos block on the second route (the first takes
/// [`PartialEigenParameters::default`]'s 4).
const SPECTRUM_SHIFT_BLOCK: usize = 8;

/// Restarts allowed on the second route (the first takes the default 50).
const SPECTRUM_SHIFT_RESTARTS: usize = 150;

/// A route's failure as an attempt; errors that are not convergence failures (memory, a
/// factor that is not positive definite) end the search.
fn attempt(route: EigenRoute, wanted: usize, e: Error) -> Result<EigenAttempt> {
    match e {
        Error::Linalg(LinalgError::EigenNotConverged {
            converged,
            wanted,
            residual,
        }) => Ok(EigenAttempt {
            route,
            converged,
            wanted,
            residual,
            missed: None,
        }),
        Error::Linalg(LinalgError::MissedModes { missed, .. }) => Ok(EigenAttempt {
            route,
            converged: wanted.saturating_sub(missed),
            wanted,
            residual: f64::NAN,
            missed: Some(missed),
        }),
        Error::Linalg(LinalgError::EigenCheckFailed { residual, .. }) => Ok(EigenAttempt {
            route,
            converged: 0,
            wanted,
            residual,
            missed: None,
        }),
        other => Err(other),
    }
}

/// A pencil $(K, M)$ and the symbolic factorisation of $K - \sigma M$ its Sturm counts use.
#[derive(Clone, Copy)]
pub(crate) struct SturmPencil<'a> {
    pub k: &'a SparseSymmetric,
    pub m: &'a MassMatrix,
    pub symbolic: &'a SymbolicFactor,
}

/// [`lowest_modes`] followed by the Sturm count; a count above the pairs found retries with
/// that many more pairs (and two to spare), up to `params.sturm_retries` times. Returns the
/// `wanted` pairs (their `sturm` set) and the statistics of the last solve. A large `factor`
/// is released before each count's $LDL^T$ factorisation, so the two are never held at once,
/// and made again only for a retry ([`ReleasableFactor`]).
pub(crate) fn sturm_checked(
    pencil: SturmPencil<'_>,
    factor: &mut ReleasableFactor<'_>,
    sigma: f64,
    wanted: usize,
    null: MatRef<'_, f64>,
    partial: &PartialEigenParameters,
    retries: usize,
) -> Result<(GeneralizedEigen, PartialEigenStatistics)> {
    let SturmPencil { k, m, symbolic } = pencil;
    let mut asked = wanted;
    let mut last: Option<SturmCount> = None;
    for _ in 0..=retries {
        let (eigen, stats) = lowest_modes(k, m, factor.get()?, sigma, asked, Some(null), partial)?;
        factor.release_if_large();
        let count = sturm_count(k, m, symbolic, &eigen.values, &stats.ritz_above)?;
        if count.missed() == 0 {
            let mut eigen = eigen.first(wanted);
            eigen.sturm = Some(count);
            return Ok((eigen, stats));
        }
        asked += count.missed() + 2;
        last = Some(count);
        if asked + 8 > k.dim() / 2 {
            break;
        }
    }
    let count = last.expect("the loop ran");
    Err(Error::Linalg(LinalgError::MissedModes {
        missed: count.missed(),
        below: count.below,
        found: count.found,
        hz: hz_from_eigenvalue(count.shift),
    }))
}

/// The refined null space and the lowest elastic eigenvalue estimate.
struct NullSpace {
    /// M-orthonormal zero-energy vectors of the stored pencil.
    vectors: Mat<f64>,
    /// The lowest Ritz value above the zero-energy threshold, (rad/s)² (an upper bound of the
    /// lowest elastic eigenvalue).
    lowest_elastic: Option<f64>,
}

/// Inverse subspace iteration on $(K - \sigma M)^{-1}M$ from the geometric rigid motions (or
/// random vectors) and `extra` random columns, with Rayleigh–Ritz on $(K, M)$ after every step;
/// the Ritz vectors whose values lie below `threshold` ((rad/s)²) are the null space.
fn refined_null_space(
    k: &SparseSymmetric,
    m: &MassMatrix,
    factor: &SymmetricFactor,
    geometric: Option<MatRef<'_, f64>>,
    rigid_count: usize,
    threshold: f64,
    params: &FreeBodyParameters,
) -> Result<NullSpace> {
    let n = k.dim();
    let base = geometric.map_or(0, |r| r.ncols());
    let p = (rigid_count.max(base) + params.null_extra).min(n);
    let mut rng = params.seed;
    let mut z = Mat::from_fn(n, p, |_, _| next_uniform(&mut rng));
    if let Some(r) = geometric {
        z.subcols_mut(0, base).copy_from(r);
    }
    let steps = if geometric.is_some() {
        params.null_steps_from_geometry
    } else {
        params.null_steps_from_random
    };
    let mut values = Vec::new();
    for _ in 0..steps.max(1) {
        // The image is dominated by the null space (gain 1/|σ| against 1/λ): made
        // M-orthonormal before the Rayleigh–Ritz, so the extra columns keep their elastic part.
        let x = m_orthonormal(factor.solve(m.mul(z.as_ref()).as_ref()), m);
        let kx = k.mul(x.as_ref());
        let mx = m.mul(x.as_ref());
        let sym = |a: Mat<f64>| Mat::from_fn(p, p, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
        let small = generalized_eigen(
            sym(x.transpose() * &kx).as_ref(),
            sym(x.transpose() * &mx).as_ref(),
            "null-space Rayleigh-Ritz",
        )?;
        z = &x * &small.vectors;
        values = small.values;
    }
    let nulls = values.iter().take_while(|&&v| v.abs() <= threshold).count();
    Ok(NullSpace {
        vectors: z.subcols(0, nulls).to_owned(),
        lowest_elastic: values.get(nulls).copied().filter(|v| *v > threshold),
    })
}
