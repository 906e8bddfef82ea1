//! A body's lowest free-free pairs by multi-level substructuring ([`amls_lowest_modes`]) or
//! by shift-invert Lanczos ([`free_body_pairs`]): the route `--eigensolver` picks, each
//! result naming the route that made it.

use faer::Mat;

use crate::{
    Error, Result,
    fem::{FeModel, RigidMotions},
    linalg::{
        AmlsEigenParameters, AmlsParameters, AmlsStatistics, GeneralizedEigen, MassMatrix,
        PairSelection, SparseSymmetric, SubstructureTree, ZERO_ENERGY_RATIO, amls_lowest_modes,
        eigenvalue_scale, generalized_eigen_selected, hz_from_eigenvalue, m_orthonormal_basis,
        negative_shift,
    },
};

use super::{
    ReductionError,
    free_body_solver::{FreeBodyParameters, free_body_pairs},
};

/// The parts of the AMLS tree hold at most this many unknowns: leaves of this size are
/// solved on their own (dense below 400 unknowns, by the partial solver above), and the
/// separators between them stay small next to the factor's top fronts.
pub const AMLS_LEAF: usize = 1500;

/// Rigid motions from the coordinates are handed to AMLS as exact eigenvectors of eigenvalue
/// 0 only when $K$ annihilates them to this share of the data (an assembled body's round-off);
/// otherwise (a matrix written with fewer digits) AMLS finds them as pairs like the others.
const EXACT_NULL_SPACE: f64 = 1e-12;

/// The first cut-off is this many times the guessed frequency times the cut-off ratio: the
/// guess errs low ([`first_cutoff_hz`]), and a second reduction costs as much as the first.
const FIRST_GUESS_MARGIN: f64 = 2.0;

/// Which solver finds a body's lowest free-free pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Eigensolver {
    /// Shift-invert block Lanczos on one sparse factor of $K - \sigma M$ (the default: faster
    /// than AMLS at every size measured on two cores, docs/amls.md).
    #[default]
    Lanczos,
    /// Multi-level substructuring over the body's nested-dissection tree, refined to the
    /// same residual check and Sturm-counted.
    Amls,
}

impl Eigensolver {
    /// Every solver, the default first.
    pub const ALL: [Eigensolver; 2] = [Eigensolver::Lanczos, Eigensolver::Amls];

    /// The name on the command line (`lanczos`, `amls`).
    pub fn id(self) -> &'static str {
        match self {
            Eigensolver::Lanczos => "lanczos",
            Eigensolver::Amls => "amls",
        }
    }

    /// The route as a sentence names it.
    pub fn name(self) -> &'static str {
        match self {
            Eigensolver::Lanczos => "shift-invert Lanczos",
            Eigensolver::Amls => "multi-level substructuring (AMLS), refined",
        }
    }
}

impl std::str::FromStr for Eigensolver {
    type Err = crate::error::UnknownId;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        Eigensolver::ALL
            .into_iter()
            .find(|e| e.id() == s.trim())
            .ok_or_else(|| {
                crate::error::UnknownId::new(
                    "eigensolver",
                    s.trim(),
                    &Eigensolver::ALL.map(Eigensolver::id),
                )
            })
    }
}

/// The lowest `wanted` free-free pairs (rigid ones first) by `solver`, with AMLS's statistics
/// when it made them.
pub fn free_pairs_by(
    model: &FeModel,
    wanted: usize,
    solver: Eigensolver,
) -> Result<(GeneralizedEigen, Option<AmlsStatistics>)> {
    match solver {
        Eigensolver::Lanczos => Ok((
            free_body_pairs(model, wanted, &FreeBodyParameters::default())?,
            None,
        )),
        Eigensolver::Amls => {
            let (pairs, stats) = amls_free_pairs(model, wanted)?;
            Ok((pairs, Some(stats)))
        }
    }
}

/// The lowest `wanted` free-free pairs by AMLS over the body's tree (parts of at most
/// [`AMLS_LEAF`] unknowns, a quarter of a smaller body), the first
/// cut-off guessed from the body itself ([`first_cutoff_hz`]) and raised by
/// [`amls_lowest_modes`] as far as the pairs carried need. Every pair passes the residual
/// check and the Sturm count proves none missed.
///
/// A body without node coordinates has nothing to cut by:
/// [`ReductionError::MethodNeedsContext`].
pub fn amls_free_pairs(
    model: &FeModel,
    wanted: usize,
) -> Result<(GeneralizedEigen, AmlsStatistics)> {
    let defect =
        (model.rigid_motions == RigidMotions::FromGeometry).then(|| model.rigid_motion_defect());
    let rigid = model.rigid_body_modes();
    let null = defect
        .filter(|&d| d <= EXACT_NULL_SPACE)
        .map(|_| rigid.as_ref());
    amls_pairs(
        &model.k,
        &model.m,
        &model.dof_positions(),
        AmlsProblem {
            wanted,
            null,
            data_precision: defect.unwrap_or(0.0).max(f64::EPSILON),
            guess_hz: first_cutoff_hz(model, wanted + AmlsEigenParameters::default().guard),
        },
    )
}

/// What [`amls_pairs`] is asked for beside the pencil.
pub(super) struct AmlsProblem<'a> {
    /// Pairs wanted.
    pub(super) wanted: usize,
    /// Known eigenvectors of eigenvalue 0 (a free body's rigid motions), if exact.
    pub(super) null: Option<faer::MatRef<'a, f64>>,
    /// The relative precision of $K$ and $M$.
    pub(super) data_precision: f64,
    /// The guessed frequency of the highest pair carried, Hz ([`first_cutoff_hz`]).
    pub(super) guess_hz: f64,
}

/// The lowest pairs of $(K, M)$ by AMLS over the tree of the unknowns at `coords` (parts of at
/// most [`AMLS_LEAF`] unknowns, a quarter of a smaller problem, so that every leaf is held by
/// a separator: a whole free body's K is singular), the first cut-off
/// [`FIRST_GUESS_MARGIN`] times the cut-off ratio times the guess, raised by up to four
/// reductions. Without coordinates to cut by: [`ReductionError::MethodNeedsContext`].
pub(super) fn amls_pairs(
    k: &SparseSymmetric,
    m: &MassMatrix,
    coords: &[[f64; 3]],
    problem: AmlsProblem<'_>,
) -> Result<(GeneralizedEigen, AmlsStatistics)> {
    let leaf = AMLS_LEAF.min(coords.len() / 4).max(1);
    let tree = SubstructureTree::new(k.as_faer(), coords, leaf).ok_or(Error::Reduction(
        ReductionError::MethodNeedsContext {
            method: "multi-level substructuring (--eigensolver amls)",
            needs: "node coordinates to cut the body by (this body's nodes all sit at one point)",
        },
    ))?;
    let defaults = AmlsEigenParameters::default();
    let params = AmlsEigenParameters {
        reduction: AmlsParameters {
            cutoff_hz: FIRST_GUESS_MARGIN * defaults.cutoff_ratio * problem.guess_hz,
            shift: negative_shift(k, m),
            ..AmlsParameters::default()
        },
        data_precision: problem.data_precision,
        // The guess errs low: room for the reductions that raise it.
        max_reductions: 4,
        ..defaults
    };
    Ok(amls_lowest_modes(
        k,
        m,
        &tree,
        problem.wanted,
        problem.null,
        &params,
    )?)
}

/// A guess of the `count`-th eigenfrequency (Hz) from the body alone, the smaller of two
/// estimates:
///
/// - Weyl's law for a solid: the eigenvalue count below $\lambda$ grows like
///   $n(\lambda/s)^{3/2}$ with $s$ the median of $K_{jj}/M_{jj}$ (a node's own frequency
///   squared), so $\lambda_N \approx s\,(N/n)^{2/3}$. On refined slabs of 1 k–28 k DOF the true
///   $\lambda_N$ is 0.7–2.1 times this; on the committed tetrahedral bodies it is far too
///   high (their consistent masses' diagonals are small, their meshes graded): alone, it
///   had AMLS keep 138–789 modes for 33 pairs.
/// - The lowest Rayleigh–Ritz value $\lambda_R$ of smooth fields (every monomial of the node
///   coordinates up to degree two in each translation, the rigid motions' energy left
///   out), an upper bound of the lowest elastic eigenvalue near it, grown as a solid's
///   count: $\lambda_N \approx \lambda_R\,N_e^{2/3}$ with $N_e$ the elastic pairs counted.
///   Slender and thin bodies' eigenvalues grow faster than a solid's, so this errs low.
///
/// A guess too low costs AMLS one more reduction; one too high, a large projected problem.
pub fn first_cutoff_hz(model: &FeModel, count: usize) -> f64 {
    let n = model.dof_count();
    let mut ratios: Vec<f64> = (0..n)
        .map(|j| model.k.get(j, j) / model.m.get(j, j))
        .filter(|r| r.is_finite() && *r > 0.0)
        .collect();
    if ratios.is_empty() {
        // No DOF with stiffness and mass (a body file's readers refuse one): any guess does,
        // the retries set the cut-off.
        return 1.0;
    }
    let middle = ratios.len() / 2;
    let (_, median, _) = ratios.select_nth_unstable_by(middle, f64::total_cmp);
    let share = (count as f64 / n.max(1) as f64).min(1.0);
    let weyl = *median * share.powf(2.0 / 3.0);
    let elastic = count.saturating_sub(model.dofs.rigid_body_count()).max(1);
    let smooth = smooth_field_eigenvalue(model)
        .map_or(f64::INFINITY, |l| l * (elastic as f64).powf(2.0 / 3.0));
    hz_from_eigenvalue(weyl.min(smooth))
}

/// The lowest Rayleigh–Ritz eigenvalue above zero energy of $(K, M)$ on the span of smooth
/// displacement fields: each translation direction times each monomial of the centred node
/// coordinates up to degree two (30 fields in space), dependent ones dropped. `None` when no
/// value lies above the zero-energy threshold (or the span is empty).
fn smooth_field_eigenvalue(model: &FeModel) -> Option<f64> {
    let n = model.dof_count();
    let per = model.dofs.per_node();
    let translations = model.dofs.translations();
    let count = model.node_count().max(1) as f64;
    let mut centre = [0.0; 3];
    for p in &model.nodes {
        for (c, x) in centre.iter_mut().zip(p) {
            *c += x / count;
        }
    }
    let size = model.size().max(f64::MIN_POSITIVE);
    let monomial = |k: usize, p: &[f64; 3]| -> f64 {
        let x = [0, 1, 2].map(|i| (p[i] - centre[i]) / size);
        match k {
            0 => 1.0,
            1..=3 => x[k - 1],
            4..=6 => x[k - 4] * x[k - 4],
            7 => x[0] * x[1],
            8 => x[1] * x[2],
            _ => x[2] * x[0],
        }
    };
    let fields = translations.len() * 10;
    let f = Mat::from_fn(n, fields, |row, c| {
        let (node, o) = (row / per, row % per);
        let (t, k) = (c / 10, c % 10);
        if translations[t].1 == o {
            monomial(k, &model.nodes[node])
        } else {
            0.0
        }
    });
    let basis = m_orthonormal_basis(f.as_ref(), &model.m, 1e-8).ok()?;
    if basis.ncols() == 0 {
        return None;
    }
    let k_r = basis.transpose() * model.k.mul(basis.as_ref());
    let k_r = Mat::from_fn(k_r.nrows(), k_r.ncols(), |i, j| {
        0.5 * (k_r[(i, j)] + k_r[(j, i)])
    });
    let identity = Mat::<f64>::identity(k_r.nrows(), k_r.ncols());
    let ritz = generalized_eigen_selected(
        k_r.as_ref(),
        identity.as_ref(),
        "smooth fields",
        PairSelection::All,
    )
    .ok()?;
    let scale = eigenvalue_scale((0..n).map(|j| (model.k.get(j, j), model.m.get(j, j))));
    ritz.values
        .into_iter()
        .find(|&l| l > ZERO_ENERGY_RATIO * scale)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};

    #[test]
    fn amls_and_lanczos_give_one_bodys_pairs_and_say_which_made_them() {
        for bricks in [[8, 4, 2], [12, 6, 3]] {
            let model = slab(&SlabParameters::refined(bricks).unwrap());
            let (lanczos, none) = free_pairs_by(&model, 16, Eigensolver::Lanczos).unwrap();
            let (amls, stats) = free_pairs_by(&model, 16, Eigensolver::Amls).unwrap();
            assert!(none.is_none());
            let stats = stats.unwrap();
            assert!(stats.reductions >= 1 && stats.max_residual <= 1e-8);
            assert_eq!(amls.zero_energy, 6);
            assert_eq!(amls.sturm.map(|s| s.missed()), Some(0));
            for (a, b) in amls.values.iter().zip(&lanczos.values).skip(6) {
                assert!((a - b).abs() <= 1e-9 * b, "{a} against {b}");
            }
            // The guess lies within the measured band of the true frequency (0.7–2.1 in λ).
            let guess = first_cutoff_hz(&model, 16);
            let truth = hz_from_eigenvalue(*lanczos.values.last().unwrap());
            assert!(
                guess > 0.5 * truth && guess < 1.6 * truth,
                "{guess} against {truth}"
            );
        }
    }
}
