//! The sparse path against the dense one, the partial eigensolver's residuals, mode
//! condensation's two routes, the refined slab and how the factor's fill grows.

use faer::Mat;
use flexmodes::error::FreeMotion;
use flexmodes::linalg::LinalgError;
use flexmodes::reduction::ReductionError;
use flexmodes::{
    analysis::{elastic_hz, free_free_modes, lowest_free_free_modes},
    error::CoreError as Error,
    fem::{HEX8_LOCAL_NODES, SlabParameters, Triplets, hex8_stiffness, slab},
    linalg::{
        MassMatrix, PartialEigenParameters, SparseSymmetric, SymbolicFactor, SymmetricFactor,
        generalized_eigen, lowest_modes, principal_angles,
    },
    reduction::{
        InteriorProblem, Method, ModeCondensationRoute, ModeSelection, ReductionRequest,
        SolverPath, reduce,
    },
};

const APP_B_CORNERS: [usize; 4] = [16, 18, 28, 30];

#[test]
fn sparse_and_dense_paths_agree_on_the_app_b_slab() {
    let model = slab(&SlabParameters::default());
    for method in [
        Method::Guyan,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ] {
        for modes in [2, 6, 12] {
            let run = |solver| {
                reduce(
                    &model,
                    &ReductionRequest {
                        method,
                        boundary_nodes: APP_B_CORNERS.to_vec(),
                        modes: ModeSelection::Count(modes),
                        solver,
                        ..Default::default()
                    },
                )
                .unwrap()
            };
            let (dense, sparse) = (run(SolverPath::Dense), run(SolverPath::Sparse));
            assert!(!dense.statistics.sparse && sparse.statistics.sparse);
            let (hd, hs) = (dense.normal_hz(), sparse.normal_hz());
            assert_eq!(hd.len(), hs.len(), "{method:?} {modes}");
            for (a, b) in hd.iter().zip(&hs) {
                assert!((a - b).abs() <= 1e-10 * a, "{method:?} {modes}: {a} vs {b}");
            }
            let angles = principal_angles(dense.psi.as_ref(), sparse.psi.as_ref()).unwrap();
            assert_eq!(
                angles.len(),
                dense.size(),
                "{method:?}: both bases full rank"
            );
            let worst = angles.iter().copied().fold(0.0f64, f64::max);
            assert!(worst < 1e-8, "{method:?} {modes}: largest angle {worst:e}");
        }
    }
}

#[test]
fn partial_eigensolver_matches_the_dense_solver_with_small_residuals() {
    // Refined slabs small enough for a dense reference: the lowest 12 fixed-interface modes.
    for bricks in [[6, 3, 2], [8, 4, 2]] {
        let p = SlabParameters::refined(bricks).unwrap();
        let model = slab(&p);
        let corners = p.bottom_corners();
        let mut problem = InteriorProblem::new(&model, &corners, SolverPath::Sparse).unwrap();
        let partial = problem.kept_modes(ModeSelection::Count(12)).unwrap();
        assert!(problem.statistics.eigen_max_residual < 1e-8);
        assert!(problem.statistics.eigen_block_solves > 0);
        // Independent check: the dense generalized eigenproblem of the same blocks.
        let part = &problem.partition;
        let k = model.k_dense();
        let k_ii = Mat::from_fn(part.i.len(), part.i.len(), |r, c| k[(part.i[r], part.i[c])]);
        let m_ii = model.m.principal_block(&part.i).to_dense();
        let dense = generalized_eigen(k_ii.as_ref(), m_ii.as_ref(), "reference").unwrap();
        assert_eq!(partial.values.len(), 12);
        for (j, (&a, &b)) in partial.values.iter().zip(&dense.values).enumerate() {
            assert!(
                (a - b).abs() <= 1e-10 * b,
                "{bricks:?} mode {j}: {a} vs {b}"
            );
        }
        // Residual and mass normalisation of every returned pair, computed here.
        let kv = model
            .k
            .principal_block(&part.i)
            .mul(partial.vectors.as_ref());
        let mv = model
            .m
            .principal_block(&part.i)
            .mul(partial.vectors.as_ref());
        for j in 0..12 {
            let r = Mat::from_fn(kv.nrows(), 1, |i, _| {
                kv[(i, j)] - partial.values[j] * mv[(i, j)]
            });
            let rel = r.norm_l2() / kv.col(j).norm_l2();
            assert!(rel < 1e-8, "{bricks:?} mode {j}: residual {rel:e}");
            let norm = partial.vectors.col(j).transpose() * mv.col(j);
            assert!((norm - 1.0).abs() < 1e-10);
        }
    }
}

/// K_ii, M_ii and the sparse factor of K_ii of the 6 × 3 × 2 slab held at its bottom corners.
fn interior_of_6_3_2() -> (SparseSymmetric, MassMatrix, SymmetricFactor) {
    let p = SlabParameters::refined([6, 3, 2]).unwrap();
    let model = slab(&p);
    let corners = p.bottom_corners();
    let problem = InteriorProblem::new(&model, &corners, SolverPath::Sparse).unwrap();
    let part = &problem.partition;
    let k_ii = model.k.principal_block(&part.i);
    let m_ii: MassMatrix = model.m.principal_block(&part.i);
    let symbolic = SymbolicFactor::analyse(k_ii.as_faer()).unwrap();
    let factor = SymmetricFactor::sparse(k_ii.as_faer(), &symbolic, "K_ii").unwrap();
    (k_ii, m_ii, factor)
}

#[test]
fn partial_eigensolver_reports_how_far_it_got() {
    let (k_ii, m_ii, factor) = interior_of_6_3_2();
    // No restart allowed and an unreachable tolerance: a named error with the counts.
    let params = PartialEigenParameters {
        max_restarts: 0,
        ritz_tolerance: 1e-30,
        ..Default::default()
    };
    match lowest_modes(&k_ii, &m_ii, &factor, 0.0, 10, None, &params).unwrap_err() {
        LinalgError::EigenNotConverged {
            converged,
            wanted,
            residual,
        } => {
            assert_eq!(wanted, 10);
            assert!(converged < 10);
            assert!(residual > 0.0 && residual.is_finite());
        }
        e => panic!("{e}"),
    }
}

#[test]
fn a_loose_ritz_tolerance_is_tightened_until_the_residuals_pass() {
    let (k_ii, m_ii, factor) = interior_of_6_3_2();
    let loose = PartialEigenParameters {
        ritz_tolerance: 1e-4,
        residual_tolerance: 1e-10,
        ..Default::default()
    };
    let (eig, stats) = lowest_modes(&k_ii, &m_ii, &factor, 0.0, 10, None, &loose).unwrap();
    assert!(stats.max_residual <= 1e-10, "{:e}", stats.max_residual);
    // The same pairs as with the default tolerance.
    let (reference, _) =
        lowest_modes(&k_ii, &m_ii, &factor, 0.0, 10, None, &Default::default()).unwrap();
    assert_eq!(eig.values.len(), 10);
    for (a, b) in eig.values.iter().zip(&reference.values) {
        assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
    }
    // A Ritz tolerance of 1e-4 alone would have stopped with residuals far above 1e-10.
    let unchecked = PartialEigenParameters {
        ritz_tolerance: 1e-4,
        residual_tolerance: 1.0,
        ..Default::default()
    };
    let (_, early) = lowest_modes(&k_ii, &m_ii, &factor, 0.0, 10, None, &unchecked).unwrap();
    assert!(early.max_residual > 1e-8, "{:e}", early.max_residual);
}

#[test]
fn mode_condensation_routes_span_one_space() {
    for (bricks, boundary) in [
        ([4, 2, 1], APP_B_CORNERS.to_vec()),
        (
            [8, 4, 2],
            SlabParameters::refined([8, 4, 2])
                .unwrap()
                .bottom_corners()
                .to_vec(),
        ),
    ] {
        let model = slab(&SlabParameters::refined(bricks).unwrap());
        for modes in [0, 3, 8] {
            let run = |route, path| {
                reduce(
                    &model,
                    &ReductionRequest::of(Method::ModeCondensation)
                        .boundary(&boundary)
                        .modes(ModeSelection::Count(modes))
                        .solver(path)
                        .route(route),
                )
                .unwrap()
            };
            let complete = run(ModeCondensationRoute::Complete, SolverPath::Dense);
            for path in [SolverPath::Dense, SolverPath::Sparse] {
                let kept = run(ModeCondensationRoute::KeptModes, path);
                assert_eq!(kept.size(), complete.size());
                let angles = principal_angles(complete.psi.as_ref(), kept.psi.as_ref()).unwrap();
                assert_eq!(angles.len(), complete.size());
                let worst = angles.iter().copied().fold(0.0f64, f64::max);
                assert!(worst < 1e-8, "{bricks:?} {modes} {path:?}: {worst:e}");
                // Not only the span: the condensed boundary columns themselves agree.
                let scale = complete.psi.norm_max();
                let diff = (&complete.psi - &kept.psi).norm_max();
                assert!(diff < 1e-8 * scale, "{bricks:?} {modes} {path:?}: {diff:e}");
            }
        }
    }
}

/// The App. B slab assembled the old way, element by element into a dense matrix, with the
/// mass lumped by hand: an independent reference for the pattern-then-values assembly.
#[test]
fn refine_4_2_1_is_exactly_the_app_b_slab() {
    let p = SlabParameters::refined([4, 2, 1]).unwrap();
    assert_eq!(p, SlabParameters::default());
    let model = slab(&p);
    assert_eq!(model.dof_count(), 90);
    assert_eq!(p.bottom_corners(), APP_B_CORNERS);
    // Reference: same node positions, bricks found from them, dense triplet assembly.
    let mut t = Triplets::new(90);
    let mut mass = vec![0.0; 90];
    let node_at = |q: [f64; 3]| {
        model
            .nodes
            .iter()
            .position(|x| (0..3).all(|d| (x[d] - q[d]).abs() < 1e-12))
            .unwrap()
    };
    for ix in 0..4 {
        for iy in 0..2 {
            let conn = HEX8_LOCAL_NODES.map(|l| {
                node_at([
                    ix as f64 + 0.5 * (l[0] + 1.0),
                    iy as f64 + 0.5 * (l[1] + 1.0),
                    0.5 * (l[2] + 1.0),
                ])
            });
            let x = conn.map(|c| model.nodes[c]);
            let ke = hex8_stiffness(&x, 0.2e6, 0.33);
            let dofs: Vec<usize> = conn
                .iter()
                .flat_map(|&c| [3 * c, 3 * c + 1, 3 * c + 2])
                .collect();
            t.add_element(&dofs, &ke);
            for &c in &conn {
                for d in 0..3 {
                    mass[3 * c + d] += 62.4 / 8.0 / 8.0;
                }
            }
        }
    }
    let reference = t.to_dense();
    let k = model.k_dense();
    let scale = reference.norm_max();
    for i in 0..90 {
        for j in 0..90 {
            let sym = 0.5 * (reference[(i, j)] + reference[(j, i)]);
            assert!((k[(i, j)] - sym).abs() <= 1e-12 * scale, "K[{i},{j}]");
        }
        assert_eq!(model.m.get(i, i), mass[i], "M[{i},{i}]");
    }
    assert!(model.m.is_lumped());
}

#[test]
fn free_free_frequency_falls_under_nested_refinement_with_consistent_mass() {
    // Compatible trilinear bricks with consistent mass are Rayleigh-Ritz: each doubling
    // contains the coarser space, so every frequency falls.
    let mut previous: Option<Vec<f64>> = None;
    for bricks in [[4, 2, 1], [8, 4, 2], [16, 8, 4]] {
        let p = SlabParameters {
            consistent_mass: true,
            ..SlabParameters::refined(bricks).unwrap()
        };
        let model = slab(&p);
        assert!(!model.m.is_lumped());
        assert!((model.total_mass() - 62.4).abs() < 1e-9, "{bricks:?}");
        let f = elastic_hz(&lowest_free_free_modes(&model, 3).unwrap());
        assert_eq!(f.len(), 3);
        if let Some(prev) = &previous {
            for (k, (a, b)) in f.iter().zip(prev).enumerate() {
                assert!(a < b, "{bricks:?} mode {}: {a} Hz after {b} Hz", k + 1);
            }
        }
        previous = Some(f);
    }
}

#[test]
fn lumped_slab_free_free_frequency_rises_from_below() {
    // The thesis' lumped masses lower the frequencies: on the App. B slab the first one comes
    // out below the refined values (measured: 7.07, 8.53, 8.65 Hz), unlike the consistent-mass
    // bound above. The sparse route (rigid motions deflated) equals the dense one.
    let mut firsts = Vec::new();
    for bricks in [[4, 2, 1], [8, 4, 2], [16, 8, 4]] {
        let model = slab(&SlabParameters::refined(bricks).unwrap());
        firsts.push(elastic_hz(&lowest_free_free_modes(&model, 1).unwrap())[0]);
    }
    assert_eq!(firsts.len(), 3);
    assert!(firsts[0] < firsts[1] && firsts[1] < firsts[2], "{firsts:?}");
    let model = slab(&SlabParameters::refined([8, 4, 2]).unwrap());
    let dense = elastic_hz(&free_free_modes(&model).unwrap());
    let sparse = elastic_hz(&lowest_free_free_modes(&model, 8).unwrap());
    assert_eq!(sparse.len(), 8);
    for (a, b) in sparse.iter().zip(&dense) {
        assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
    }
}

#[test]
fn factor_fill_grows_sub_quadratically() {
    // Three refinements, each doubling the bricks along every axis (~8× the DOF): a dense
    // factor would grow as n², a banded one as n^(5/3); nested-dissection-like orderings give
    // about n^(4/3). Assert the fitted exponent stays well below 2.
    let mut points = Vec::new();
    for bricks in [[4, 2, 1], [8, 4, 2], [16, 8, 4]] {
        let p = SlabParameters::refined(bricks).unwrap();
        let model = slab(&p);
        let basis = reduce(
            &model,
            &ReductionRequest::of(Method::CraigBampton)
                .boundary(&p.bottom_corners())
                .modes(ModeSelection::Count(4))
                .solver(SolverPath::Sparse),
        )
        .unwrap();
        assert!(basis.statistics.factor_nnz > 0);
        points.push((model.dof_count() as f64, basis.statistics.factor_nnz as f64));
    }
    assert_eq!(points.len(), 3);
    let exponent = |a: (f64, f64), b: (f64, f64)| (b.1 / a.1).ln() / (b.0 / a.0).ln();
    let last = exponent(points[1], points[2]);
    assert!(
        last < 1.75,
        "fill exponent {last:.2} between the two finest meshes"
    );
    assert!(
        last > 1.0,
        "fill cannot grow slower than the matrix itself ({last:.2})"
    );
}

#[test]
fn singular_interior_names_the_free_motions_without_an_eigenproblem() {
    let model = slab(&SlabParameters::default());
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[16])
            .modes(ModeSelection::Count(2))
            .solver(SolverPath::Sparse),
    )
    .unwrap_err();
    match e {
        Error::Reduction(ReductionError::SingularInterior {
            rank_deficiency,
            ref free_motions,
            ..
        }) => {
            assert_eq!(rank_deficiency, 3);
            // Three rotations, each about an axis through node 16 at the origin, about
            // three independent unit axes; the message names them so.
            assert_eq!(free_motions.len(), 3, "{e}");
            let mut axes = Vec::new();
            for motion in free_motions {
                match motion {
                    FreeMotion::Rotation {
                        axis,
                        point,
                        node: Some(16),
                    } => {
                        assert_eq!(*point, [0.0; 3], "{e}");
                        let norm = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
                        assert!((norm - 1.0).abs() < 1e-12, "{e}");
                        axes.push(nalgebra::Vector3::from(*axis));
                    }
                    other => panic!("{other}: not a rotation through node 16 ({e})"),
                }
            }
            let volume = axes[0].cross(&axes[1]).dot(&axes[2]).abs();
            assert!(volume > 0.99, "axes {axes:?} are not independent");
            let message = e.to_string();
            assert_eq!(message.matches("rotation about").count(), 3, "{message}");
            assert_eq!(
                message
                    .matches("through node 16 at (0.000, 0.000, 0.000)")
                    .count(),
                3,
                "{message}"
            );
        }
        e => panic!("{e}"),
    }
    // Nodes 16 and 30 leave the rotation about the diagonal through them.
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[16, 30])
            .modes(ModeSelection::Count(2))
            .solver(SolverPath::Sparse),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Reduction(ReductionError::SingularInterior {
                rank_deficiency: 1,
                ..
            })
        ),
        "{e}"
    );
    let text = e.to_string();
    let axis = 1.0 / 20f64.sqrt();
    assert!(
        text.contains(&format!("({:.3}, {:.3}, 0.000)", 4.0 * axis, 2.0 * axis))
            || text.contains(&format!("({:.3}, {:.3}, 0.000)", -4.0 * axis, -2.0 * axis)),
        "{text}"
    );
}

#[test]
fn eitelberg_refuses_large_bodies_by_name() {
    let model = slab(&SlabParameters::refined([16, 8, 4]).unwrap());
    let e = reduce(
        &model,
        &ReductionRequest {
            method: Method::Eitelberg,
            boundary_nodes: SlabParameters::refined([16, 8, 4])
                .unwrap()
                .bottom_corners()
                .to_vec(),
            ..Default::default()
        },
    )
    .unwrap_err();
    match e {
        Error::TooLarge { dofs, limit, .. } => {
            assert_eq!(dofs, model.dof_count());
            assert!(dofs > limit);
        }
        e => panic!("{e}"),
    }
}

/// `--timings` splits a reduction into phases: the factorisation, the constraint modes and
/// the fixed-interface eigensolve are each counted once, so together they never exceed the
/// reduction's wall time (the constraint modes had counted the factorisation they triggered).
#[test]
fn a_sparse_reductions_phases_add_up_to_at_most_its_time() {
    for bricks in [[8, 4, 2], [12, 6, 3]] {
        let p = SlabParameters::refined(bricks).unwrap();
        let model = slab(&p);
        let started = std::time::Instant::now();
        let basis = reduce(
            &model,
            &ReductionRequest {
                method: Method::CraigBampton,
                boundary_nodes: p.bottom_corners().to_vec(),
                modes: ModeSelection::Count(6),
                solver: SolverPath::Sparse,
                ..Default::default()
            },
        )
        .unwrap();
        let wall = started.elapsed().as_secs_f64();
        let s = &basis.statistics;
        assert!(s.factorization_s > 0.0 && s.constraint_modes_s > 0.0 && s.eigen_s > 0.0);
        let phases = s.factorization_s + s.constraint_modes_s + s.eigen_s;
        assert!(
            phases <= wall,
            "{bricks:?}: factorisation {} + constraint modes {} + eigensolve {} = {phases} s \
             over the {wall} s the reduction took",
            s.factorization_s,
            s.constraint_modes_s,
            s.eigen_s
        );
    }
}
