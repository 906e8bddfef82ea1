//! Automated multi-level substructuring (AMLS, Bennighof and Lehoucq 2004): component mode
//! synthesis applied at every node of a [`SubstructureTree`], the leaves first.
//!
//! Each node's unknowns $P$ are eliminated from its front $F = P \cup B$ ($B$: the unknowns of
//! its ancestors that its subtree touches), the children's Schur complements added in. With
//! $K_\sigma = K - \sigma M$ (positive definite: $\sigma$ below the lowest eigenvalue, negative
//! for a free body), the static part and the front's updates are
//!
//! $$\Phi = -K_{PP}^{-1}K_{PB},\quad
//! \hat K_{BB} = K_{BB} + K_{BP}\Phi,\quad
//! N = M_{PB} + M_{PP}\Phi,\quad
//! \hat M_{BB} = M_{BB} + M_{BP}\Phi + \Phi^T N,$$
//!
//! and the node's fixed-interface modes $K_{PP}\psi = \mu M_{PP}\psi$ with $\mu$ below the
//! cut-off $\omega_c^2 - \sigma$ are kept: $x_P = \Psi y + \Phi x_B$. In the kept coordinates
//! $K_\sigma$ is $\mathrm{diag}(\mu)$ (the static part is $K$-orthogonal to the modes), and
//! $M$ is the identity but for the coupling of each node's modes with its descendants' modes:
//! a descendant mode's coupling row $C_d = [C_{dP}, C_{dB}]$ over the front becomes
//! $C_{dP}\Psi$ (with this node's modes) and $C_{dB} + C_{dP}\Phi$ (passed up), and the new
//! modes' rows are $\Psi^T N$.
//!
//! With every mode kept the transformation is a congruence: the projected pencil has the
//! body's eigenvalues exactly. The stored $\Phi$ and the factors of $K_{PP}$ are the block
//! $LDL^T$ factor of $K_\sigma$ in the tree's order: [`MultilevelSubstructures::solve_in_place`]
//! applies $K_\sigma^{-1}$ with them.

use faer::{Mat, MatRef, linalg::solvers::Llt};

use crate::linalg::dense::{GeneralizedEigen, PairSelection, generalized_eigen_selected};

use super::SubstructureTree;
use super::amls_parameters::AmlsParameters;
use super::substructure_front::{
    Eliminated, Update, assemble_front, assembled_mass, descendant_coupling, eliminate,
    leaf_modes_by_node, node_modes, product,
};

use crate::linalg::sparse::{MassMatrix, SparseSymmetric};

use crate::linalg::Result;

/// One eliminated node: its part of the block factor and its kept modes.
pub(super) struct Front {
    /// $P$: the node's unknowns.
    pub(super) unknowns: Vec<usize>,
    /// $B$: its ancestors' unknowns its subtree touches, in the elimination order.
    pub(super) boundary: Vec<usize>,
    /// $K_{PP} = LL^T$ after its descendants' elimination.
    pub(super) factor: Llt<f64>,
    /// $\Phi = -K_{PP}^{-1}K_{PB}$, $|P| \times |B|$.
    pub(super) phi: Mat<f64>,
    /// $\Psi$: the kept modes, $M_{PP}$-orthonormal, $|P| \times k$.
    pub(super) modes: Mat<f64>,
    /// The index of its first mode among all kept ones.
    pub(super) first_mode: usize,
}

/// A body reduced by AMLS: the kept modes of every node of its substructure tree, the
/// projected pencil $(\mathrm{diag}(\mu), M_A)$ and the block factor of $K_\sigma$.
pub struct MultilevelSubstructures {
    pub(super) dim: usize,
    shift: f64,
    pub(super) fronts: Vec<Front>,
    /// $\mu$ of each kept mode ($K_\sigma$'s projection), in the order of the coordinates.
    stiffness: Vec<f64>,
    /// $M_A$, symmetric, unit diagonal.
    mass: Mat<f64>,
}

impl std::fmt::Debug for MultilevelSubstructures {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MultilevelSubstructures")
            .field("dim", &self.dim)
            .field("nodes", &self.fronts.len())
            .field("modes", &self.stiffness.len())
            .finish()
    }
}

impl MultilevelSubstructures {
    /// Reduces $(K, M)$ over `tree` (of the same unknowns) as the module says.
    ///
    /// Fails with [`LinalgError::NonPositivePivot`] when a node's $K_{PP}$ is not positive
    /// definite (the shift is not below the lowest eigenvalue) and with the eigensolvers'
    /// errors (see [`leaf_modes`](super::leaf_modes), [`generalized_eigen_selected`]).
    pub fn new(
        k: &SparseSymmetric,
        m: &MassMatrix,
        tree: &SubstructureTree,
        params: &AmlsParameters,
    ) -> Result<Self> {
        let n = k.dim();
        assert_eq!(m.dim(), n, "K and M of one body");
        let nodes = tree.nodes();
        // Every node's front: its unknowns and the ancestors' its subtree touches through K or M.
        let mut boundaries = match m {
            MassMatrix::Consistent(mm) => tree.boundaries(&[k.as_faer(), mm.as_faer()]),
            MassMatrix::Lumped(_) => tree.boundaries(&[k.as_faer()]),
        };
        let sigma = params.shift;
        let mu_cutoff = (2.0 * std::f64::consts::PI * params.cutoff_hz).powi(2) - sigma;
        let mut leaf_modes_of = leaf_modes_by_node(k, m, tree, params)?;
        let mut pending: Vec<Vec<Update>> = (0..nodes.len()).map(|_| Vec::new()).collect();
        let mut local = vec![usize::MAX; n];
        let mut fronts = Vec::with_capacity(nodes.len());
        let mut stiffness = Vec::new();
        let mut blocks: Vec<(Vec<usize>, usize, Mat<f64>)> = Vec::new();
        for (j, node) in nodes.iter().enumerate() {
            let updates = std::mem::take(&mut pending[j]);
            let unknowns = &node.unknowns;
            let boundary = std::mem::take(&mut boundaries[j]);
            let (p, q) = (unknowns.len(), boundary.len());
            let front = assemble_front((k, m, sigma), (unknowns, &boundary), updates, &mut local);
            let eliminated = eliminate(&front, p, unknowns)?;
            let par = eliminated.par;
            // The node's modes below the cut-off (values of K_σ's block: μ = λ - σ).
            let modes = node_modes(
                leaf_modes_of[j].take(),
                (eliminated.k_pp.as_ref(), front.mf.submatrix(0, 0, p, p)),
                (sigma, mu_cutoff),
                &mut stiffness,
            )?;
            let kept = modes.ncols();
            let first_mode = stiffness.len() - kept;
            let descendants = front.descendant_modes.len();
            // The descendants' couplings: with this node's modes, and on to B.
            if descendants > 0 && kept > 0 {
                let block = descendant_coupling(&front, p, modes.as_ref(), par);
                blocks.push((front.descendant_modes.clone(), first_mode, block));
            }
            let Eliminated {
                factor,
                phi,
                k_bb,
                n_pb,
                m_bb,
                ..
            } = eliminated;
            if let Some(parent) = node.parent.filter(|_| q > 0) {
                let mut up_coupling = Mat::<f64>::zeros(descendants + kept, q);
                up_coupling
                    .submatrix_mut(0, 0, descendants, q)
                    .copy_from(front.coupling.submatrix(0, p, descendants, q));
                product(
                    up_coupling.submatrix_mut(0, 0, descendants, q),
                    front.coupling.submatrix(0, 0, descendants, p),
                    phi.as_ref(),
                    par,
                );
                product(
                    up_coupling.submatrix_mut(descendants, 0, kept, q),
                    modes.transpose(),
                    n_pb.as_ref(),
                    par,
                );
                let mut modes_up = front.descendant_modes;
                modes_up.extend(first_mode..first_mode + kept);
                pending[parent].push(Update {
                    boundary: boundary.clone(),
                    k: k_bb,
                    m: m_bb,
                    coupling: up_coupling,
                    modes: modes_up,
                });
            }
            fronts.push(Front {
                unknowns: unknowns.clone(),
                boundary,
                factor,
                phi,
                modes,
                first_mode,
            });
        }
        let mass = assembled_mass(stiffness.len(), &blocks);
        Ok(Self {
            dim: n,
            shift: sigma,
            fronts,
            stiffness,
            mass,
        })
    }

    /// The body's unknowns.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// $\sigma$ of $K_\sigma = K - \sigma M$.
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// The kept modes (the projected problem's size).
    pub fn modes(&self) -> usize {
        self.stiffness.len()
    }

    /// $\mu$ of each kept mode: the projected $K_\sigma$ is $\mathrm{diag}(\mu)$.
    pub fn projected_stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// $M_A$, the projected mass.
    pub fn projected_mass(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }

    /// How many modes each tree node keeps.
    pub fn modes_per_node(&self) -> Vec<usize> {
        self.fronts.iter().map(|f| f.modes.ncols()).collect()
    }

    /// The pairs of the projected pencil $(\mathrm{diag}(\mu), M_A)$ that `selection` keeps,
    /// solved dense and residual-checked: eigenvalues of $K_\sigma$'s projection,
    /// $\mu = \lambda - \sigma$ (add [`Self::shift`] for the body's), vectors in projected
    /// coordinates ([`Self::expand`] maps them to the body).
    pub fn projected_pairs(&self, selection: PairSelection) -> Result<GeneralizedEigen> {
        let mu = self.projected_stiffness();
        let r = mu.len();
        let k_a = Mat::from_fn(r, r, |i, j| if i == j { mu[i] } else { 0.0 });
        generalized_eigen_selected(
            k_a.as_ref(),
            self.projected_mass(),
            "AMLS projected",
            selection,
        )
    }

    /// Entries of the block factor ($L_{PP}$'s lower triangles and the $\Phi$ blocks).
    pub fn factor_entries(&self) -> usize {
        self.fronts
            .iter()
            .map(|f| f.unknowns.len() * (f.unknowns.len() + 1) / 2 + f.phi.nrows() * f.phi.ncols())
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{FeModel, SlabParameters, slab};
    use crate::linalg::dense::generalized_eigen;
    use crate::linalg::sparse::negative_shift;

    fn slab_and_tree(bricks: [usize; 3], leaf: usize) -> (FeModel, SubstructureTree) {
        let model = slab(&SlabParameters::refined(bricks).unwrap());
        let tree = model.substructure_tree(leaf).unwrap();
        (model, tree)
    }

    /// The body's own eigenvalues, dense.
    fn dense_values(model: &FeModel) -> Vec<f64> {
        generalized_eigen(
            model.k.to_dense().as_ref(),
            model.m.to_dense().as_ref(),
            "test body",
        )
        .unwrap()
        .values
    }

    /// The projected pencil's eigenvalues (λ = μ + σ).
    fn projected_values(reduced: &MultilevelSubstructures) -> Vec<f64> {
        let mu = reduced.projected_stiffness();
        let r = mu.len();
        let k_a = Mat::from_fn(r, r, |i, j| if i == j { mu[i] } else { 0.0 });
        generalized_eigen(k_a.as_ref(), reduced.projected_mass(), "test projected")
            .unwrap()
            .values
            .iter()
            .map(|&v| v + reduced.shift())
            .collect()
    }

    #[test]
    fn with_every_mode_kept_the_projected_pencil_has_the_bodys_eigenvalues() {
        for (bricks, leaf) in [([4, 2, 1], 20), ([6, 3, 2], 40), ([8, 4, 2], 100)] {
            let (model, tree) = slab_and_tree(bricks, leaf);
            assert!(tree.levels() >= 3, "{bricks:?}: {} levels", tree.levels());
            let params = AmlsParameters {
                shift: negative_shift(&model.k, &model.m),
                ..AmlsParameters::default()
            };
            let reduced = MultilevelSubstructures::new(&model.k, &model.m, &tree, &params).unwrap();
            assert_eq!(reduced.modes(), model.dof_count());
            let expected = dense_values(&model);
            let top = expected.last().unwrap().abs();
            let got = projected_values(&reduced);
            assert_eq!(got.len(), expected.len());
            for (i, (a, b)) in got.iter().zip(&expected).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-10 * top + 1e-8 * b.abs(),
                    "{bricks:?} pair {i}: {a} against {b}"
                );
            }
        }
    }

    #[test]
    fn a_cut_off_keeps_upper_bounds_close_to_the_lowest_eigenvalues() {
        let (model, tree) = slab_and_tree([8, 4, 2], 60);
        let expected = dense_values(&model);
        let mut previous = usize::MAX;
        for cutoff_hz in [60.0, 45.0] {
            let params = AmlsParameters {
                cutoff_hz,
                shift: negative_shift(&model.k, &model.m),
                ..AmlsParameters::default()
            };
            let reduced = MultilevelSubstructures::new(&model.k, &model.m, &tree, &params).unwrap();
            let r = reduced.modes();
            assert!(
                r > 20 && r < model.dof_count() / 2 && r < previous,
                "{r} modes kept"
            );
            previous = r;
            assert_eq!(reduced.modes_per_node().iter().sum::<usize>(), r);
            let got = projected_values(&reduced);
            // Rayleigh–Ritz values of a subspace: above the true ones, and the lowest elastic
            // ones (up to a quarter of the cut-off) within a few per cent.
            let limit = (2.0 * std::f64::consts::PI * cutoff_hz / 4.0).powi(2);
            let mut close = 0;
            for (i, (a, b)) in got.iter().zip(&expected).enumerate().skip(6) {
                assert!(*a >= b * (1.0 - 1e-9), "pair {i}: {a} below {b}");
                if *b <= limit {
                    assert!(a / b - 1.0 <= 0.05, "pair {i}: {a} against {b}");
                    close += 1;
                }
            }
            assert!(
                close >= 2,
                "{close} pairs below a quarter of {cutoff_hz} Hz"
            );
        }
    }

    #[test]
    fn the_block_factor_solves_with_k_minus_sigma_m() {
        for (bricks, leaf) in [([4, 2, 1], 20), ([8, 4, 2], 60)] {
            let (model, tree) = slab_and_tree(bricks, leaf);
            let sigma = negative_shift(&model.k, &model.m);
            let params = AmlsParameters {
                cutoff_hz: 30.0,
                shift: sigma,
                ..AmlsParameters::default()
            };
            let reduced = MultilevelSubstructures::new(&model.k, &model.m, &tree, &params).unwrap();
            let n = model.dof_count();
            let b = Mat::from_fn(n, 3, |i, j| ((i * 7 + j * 13) % 11) as f64 - 5.0);
            let mut x = b.clone();
            reduced.solve_in_place(x.as_mut());
            let shifted = model.k.shifted(&model.m, sigma);
            let ax = shifted.mul(x.as_ref());
            let scale = shifted.abs_mul(x.as_ref());
            for j in 0..3 {
                let (mut r, mut s) = (0.0f64, 0.0f64);
                for i in 0..n {
                    r = r.max((ax[(i, j)] - b[(i, j)]).abs());
                    s = s.max(scale[(i, j)] + b[(i, j)].abs());
                }
                assert!(r <= 1e-9 * s, "{bricks:?}: residual {r} of {s}");
            }
        }
    }
}
