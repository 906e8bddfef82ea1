//! The ladder of component mode synthesis on one free body, from one level to many: Guyan
//! condensation onto the nested-dissection tree's root separator, Craig–Bampton on the same
//! interface (its two halves' fixed-interface modes below a cut-off added), and multi-level
//! substructuring (AMLS; Bennighof & Lehoucq, SIAM J. Sci. Comput. 25(6), 2004), where every
//! part and every separator of the tree keeps only its own modes below the cut-off. Each is
//! compared with the body's lowest elastic free-free frequencies; AMLS is then refined to the
//! residual every solver's pairs pass and timed against flexmodes' Lanczos on the same body.

use crate::reduction::{Method, ReductionRequest, reduce_interior};
use std::time::Instant;

use crate::{
    Result,
    analysis::reduced_modes,
    error::MatrixLabel,
    fem::{FeModel, SlabParameters, slab},
    linalg::{
        AmlsEigenParameters, AmlsParameters, AmlsStatistics, GeneralizedEigen, LinalgError,
        MultilevelSubstructures, PairSelection, SubstructureTree, amls_lowest_modes,
        hz_from_eigenvalue, negative_shift,
    },
    reduction::{
        FreeBodyParameters, InteriorProblem, ModeSelection, Partition, SolverPath, free_body_pairs,
    },
};

/// The ladder's body and cut-offs.
#[derive(Debug, Clone, PartialEq)]
pub struct SubstructuringParameters {
    /// The App. B slab (4 × 2 × 1 m) meshed with this many bricks along x, y, z.
    pub bricks: [usize; 3],
    /// Elastic free-free modes compared (the lowest).
    pub wanted: usize,
    /// The tree's parts hold at most this many unknowns.
    pub leaf: usize,
    /// Cut-offs, as multiples of the highest compared frequency: each rung is built at each.
    pub cutoff_ratios: Vec<f64>,
    /// The cut-off (a multiple as above) whose kept modes the tree's parts report, and the
    /// refined AMLS solve's first guess.
    pub shown_ratio: f64,
    /// Pairs the refined AMLS solve carries beside the wanted ones.
    pub guard: usize,
}

impl Default for SubstructuringParameters {
    fn default() -> Self {
        Self {
            bricks: [12, 6, 3],
            wanted: 6,
            leaf: 100,
            cutoff_ratios: vec![1.5, 2.0, 2.5, 3.0],
            shown_ratio: 3.0,
            guard: 8,
        }
    }
}

/// One reduced model of the ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct LadderPoint {
    /// Cut-off of the kept modes, Hz (infinite for Guyan: none kept).
    pub cutoff_hz: f64,
    /// The reduced model's coordinates.
    pub coordinates: usize,
    /// Its lowest elastic frequencies, Hz (at most the compared count).
    pub hz: Vec<f64>,
    /// The largest relative error of those against the body's, paired by order; `None` when
    /// the model has fewer elastic frequencies than were compared.
    pub error: Option<f64>,
}

/// One part of the substructure tree (a leaf or a separator).
#[derive(Debug, Clone, PartialEq)]
pub struct TreePart {
    /// Depth in the tree (0: the root separator).
    pub level: usize,
    /// Whether it is a leaf (a part with no separator inside).
    pub leaf: bool,
    /// Its unknowns (DOF).
    pub unknowns: usize,
    /// The modes it keeps below the shown cut-off.
    pub modes: usize,
    /// The mesh nodes (0-based) whose DOF it holds.
    pub nodes: Vec<usize>,
}

/// AMLS refined against Lanczos on the same body.
#[derive(Debug, Clone, PartialEq)]
pub struct RefinedComparison {
    /// AMLS's counts, residuals and phases.
    pub statistics: AmlsStatistics,
    /// AMLS, wall seconds.
    pub amls_s: f64,
    /// Lanczos (`free_body_pairs`), wall seconds.
    pub lanczos_s: f64,
    /// The largest relative difference of their elastic eigenvalues.
    pub apart: f64,
    /// Eigenvalues the Sturm check found below AMLS's top pair and AMLS did not.
    pub missed: usize,
}

/// The ladder, the tree and the refined comparison.
#[derive(Debug, Clone)]
pub struct SubstructuringStudy {
    /// Its set-up.
    pub parameters: SubstructuringParameters,
    /// The body.
    pub model: FeModel,
    /// The body's lowest elastic frequencies, Hz (Lanczos, residual- and Sturm-checked).
    pub reference_hz: Vec<f64>,
    /// The tree's parts, in the tree's postorder (the root last).
    pub parts: Vec<TreePart>,
    /// Guyan onto the root separator.
    pub guyan: LadderPoint,
    /// Craig–Bampton on the root separator, one point per cut-off.
    pub craig_bampton: Vec<LadderPoint>,
    /// AMLS over the whole tree, unrefined, one point per cut-off.
    pub amls: Vec<LadderPoint>,
    /// The refined AMLS solve against Lanczos.
    pub refined: RefinedComparison,
}

/// Builds the ladder on the refined slab and refines AMLS at the shown cut-off.
pub fn substructuring_study(params: &SubstructuringParameters) -> Result<SubstructuringStudy> {
    let model = slab(&SlabParameters::refined(params.bricks)?);
    let wanted = params.wanted;
    let rigid = model.dofs.rigid_body_count();
    let started = Instant::now();
    let reference = free_body_pairs(&model, rigid + wanted, &FreeBodyParameters::default())?;
    let lanczos_s = started.elapsed().as_secs_f64();
    let reference_hz: Vec<f64> = reference.elastic_hz().into_iter().take(wanted).collect();
    let top_hz = *reference_hz.last().unwrap_or(&0.0);
    // A slab's nodes have positions, so nested dissection has something to cut by.
    let tree = model.substructure_tree(params.leaf).ok_or_else(|| {
        crate::Error::Linalg(LinalgError::DecompositionFailed {
            what: MatrixLabel::of_body("nested dissection of K", model.name.clone()),
        })
    })?;
    let cutoffs: Vec<f64> = params.cutoff_ratios.iter().map(|r| r * top_hz).collect();
    let shift = negative_shift(&model.k, &model.m);

    let (guyan, craig_bampton) = one_level(&model, &tree, &cutoffs, &reference_hz)?;

    // Every level.
    let mut amls = Vec::new();
    let shown_hz = params.shown_ratio * top_hz;
    let mut shown_modes = None;
    // The shown cut-off is one of the ladder's when its ratio is (as by default).
    let extra = (!params.cutoff_ratios.contains(&params.shown_ratio)).then_some(shown_hz);
    for (i, &hz) in cutoffs.iter().chain(extra.iter()).enumerate() {
        let reduced = MultilevelSubstructures::new(
            &model.k,
            &model.m,
            &tree,
            &AmlsParameters {
                cutoff_hz: hz,
                shift,
                ..AmlsParameters::default()
            },
        )?;
        if hz == shown_hz {
            shown_modes = Some(reduced.modes_per_node());
        }
        if i < cutoffs.len() {
            amls.push(amls_point(&reduced, hz, rigid, &reference_hz)?);
        }
    }
    let parts = tree_parts(&model, &tree, &shown_modes.unwrap_or_default());

    let started = Instant::now();
    let rigid_modes = model.rigid_body_modes();
    let (refined, statistics) = amls_lowest_modes(
        &model.k,
        &model.m,
        &tree,
        rigid + wanted,
        Some(rigid_modes.as_ref()),
        &AmlsEigenParameters {
            reduction: AmlsParameters {
                cutoff_hz: shown_hz,
                shift,
                ..AmlsParameters::default()
            },
            guard: params.guard,
            ..AmlsEigenParameters::default()
        },
    )?;
    let amls_s = started.elapsed().as_secs_f64();
    let apart = refined.elastic_values_apart(&reference);
    Ok(SubstructuringStudy {
        parameters: params.clone(),
        reference_hz,
        parts,
        guyan,
        craig_bampton,
        amls,
        refined: RefinedComparison {
            statistics,
            amls_s,
            lanczos_s,
            apart,
            missed: refined.sturm.map_or(0, |s| s.missed()),
        },
        model,
    })
}

/// One level: the root separator is the interface. Guyan's point, and Craig–Bampton's at each
/// cut-off.
fn one_level(
    model: &FeModel,
    tree: &SubstructureTree,
    cutoffs: &[f64],
    reference_hz: &[f64],
) -> Result<(LadderPoint, Vec<LadderPoint>)> {
    let root = &tree.nodes()[tree.root()];
    let mut problem = InteriorProblem::on(
        model,
        Partition::from_dofs(model, &root.unknowns, &[])?,
        SolverPath::Auto,
    )?;
    let guyan_basis = reduce_interior(&mut problem, &ReductionRequest::of(Method::Guyan))?;
    let guyan = ladder_point(
        f64::INFINITY,
        guyan_basis.size(),
        &reduced_modes(model, &guyan_basis)?,
        reference_hz,
    );
    let mut craig_bampton = Vec::new();
    // The highest cut-off first: the lower ones' modes are its first ones (kept by the
    // interior problem), not solved again.
    for &hz in cutoffs.iter().rev() {
        let basis = reduce_interior(
            &mut problem,
            &ReductionRequest::of(Method::CraigBampton).modes(ModeSelection::UpToHz(hz)),
        )?;
        craig_bampton.push(ladder_point(
            hz,
            basis.size(),
            &reduced_modes(model, &basis)?,
            reference_hz,
        ));
    }
    craig_bampton.reverse();
    drop(problem);
    Ok((guyan, craig_bampton))
}

/// A reduced model's point: its lowest elastic frequencies against the body's.
fn ladder_point(
    cutoff_hz: f64,
    coordinates: usize,
    modes: &GeneralizedEigen,
    reference_hz: &[f64],
) -> LadderPoint {
    let hz: Vec<f64> = modes
        .elastic_hz()
        .into_iter()
        .take(reference_hz.len())
        .collect();
    LadderPoint {
        cutoff_hz,
        coordinates,
        error: frequency_error(&hz, reference_hz),
        hz,
    }
}

/// AMLS's unrefined point: the projected pencil's lowest elastic pairs.
fn amls_point(
    reduced: &MultilevelSubstructures,
    cutoff_hz: f64,
    rigid: usize,
    reference_hz: &[f64],
) -> Result<LadderPoint> {
    let count = (rigid + reference_hz.len()).min(reduced.modes());
    let pairs = reduced.projected_pairs(PairSelection::Lowest(count))?;
    // The projected pencil is shifted: its rigid pairs sit at -σ, not at round-off, so they
    // are told by position (the body's `rigid` come first).
    let hz: Vec<f64> = pairs
        .values
        .iter()
        .skip(rigid)
        .map(|&mu| hz_from_eigenvalue(mu + reduced.shift()))
        .collect();
    Ok(LadderPoint {
        cutoff_hz,
        coordinates: reduced.modes(),
        error: frequency_error(&hz, reference_hz),
        hz,
    })
}

/// The largest relative error of `hz` against `reference`, paired by order; `None` when
/// `hz` has fewer.
fn frequency_error(hz: &[f64], reference: &[f64]) -> Option<f64> {
    (hz.len() >= reference.len()).then(|| {
        hz.iter()
            .zip(reference)
            .map(|(a, b)| (a - b).abs() / b)
            .fold(0.0f64, f64::max)
    })
}

/// The tree's parts with their mesh nodes (a node goes to the part holding its first DOF) and
/// the modes each keeps (`modes`, per tree node; zero where not given).
fn tree_parts(model: &FeModel, tree: &SubstructureTree, modes: &[usize]) -> Vec<TreePart> {
    let node_of = tree.node_of();
    let mut nodes: Vec<Vec<usize>> = vec![Vec::new(); tree.nodes().len()];
    let mut seen = vec![false; model.node_count()];
    for (d, &part) in node_of.iter().enumerate() {
        let node = model.dof_node(d).0.get();
        if !seen[node] {
            seen[node] = true;
            nodes[part].push(node);
        }
    }
    tree.nodes()
        .iter()
        .zip(nodes)
        .enumerate()
        .map(|(i, (t, nodes))| TreePart {
            level: t.level,
            leaf: t.children.is_empty(),
            unknowns: t.unknowns.len(),
            modes: modes.get(i).copied().unwrap_or(0),
            nodes,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rung_is_an_upper_bound_that_tightens_with_its_cutoff_and_amls_refines_to_lanczos() {
        let params = SubstructuringParameters {
            bricks: [8, 4, 2],
            wanted: 6,
            leaf: 40,
            ..SubstructuringParameters::default()
        };
        let study = substructuring_study(&params).unwrap();
        let dofs = study.model.dof_count();
        // The parts hold every unknown and every mesh node once.
        assert_eq!(study.parts.iter().map(|p| p.unknowns).sum::<usize>(), dofs);
        let mut nodes: Vec<usize> = study.parts.iter().flat_map(|p| p.nodes.clone()).collect();
        nodes.sort_unstable();
        assert_eq!(nodes, (0..study.model.node_count()).collect::<Vec<_>>());
        assert!(study.parts.iter().filter(|p| p.leaf).count() >= 4);
        assert_eq!(study.parts.last().map(|p| p.level), Some(0));
        // Rayleigh–Ritz: every reduced frequency lies above the body's, pair by pair.
        let rungs = std::iter::once(&study.guyan)
            .chain(&study.craig_bampton)
            .chain(&study.amls);
        for point in rungs {
            for (a, b) in point.hz.iter().zip(&study.reference_hz) {
                assert!(*a >= b * (1.0 - 1e-9), "{a} Hz below the body's {b} Hz");
            }
        }
        let errors = |points: &[LadderPoint]| -> Vec<f64> {
            points.iter().map(|p| p.error.unwrap()).collect()
        };
        let (cb, amls) = (errors(&study.craig_bampton), errors(&study.amls));
        // Guyan keeps no interior mode: worse than every CB model on its interface.
        assert!(
            study.guyan.error.unwrap() > cb[0],
            "{:?} {cb:?}",
            study.guyan
        );
        // A higher cut-off keeps more modes: the errors fall (nested spaces for CB).
        for e in [&cb, &amls] {
            assert!(e.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-9)), "{e:?}");
        }
        // Refined, AMLS has the body's eigenvalues and misses none.
        let r = &study.refined;
        assert_eq!(r.missed, 0);
        assert!(r.apart < 1e-8, "{}", r.apart);
        assert!(r.statistics.max_residual <= 1e-8);
    }
}
