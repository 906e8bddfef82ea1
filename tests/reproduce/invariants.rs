//! Physical and algebraic invariants of the bodies and every reduction method.

use faer::Side;
use flexmodes::{
    analysis::{PROFILE_DELTA, elastic_hz, fit_least_squares, free_free_modes, reduced_hz},
    fem::{BeamParameters, FeModel, SlabParameters, beam, hex8_stiffness, plank, slab},
    linalg::{MassMatrix, SparseSymmetric, max_abs, principal_angles, symmetry_defect},
    reduction::{
        Basis, EitelbergParameters, Method, ModeSelection, NodalFixedAxes, Partition,
        ReductionRequest, TableConfiguration, eitelberg, fixed_interface_modes, reduce,
    },
};

use crate::common::Rng;

fn bodies() -> Vec<FeModel> {
    vec![
        beam(&BeamParameters::default()),
        slab(&SlabParameters::default()),
        plank(&SlabParameters::default()),
    ]
}

#[test]
fn rigid_body_modes_are_in_the_null_space_of_k() {
    for model in bodies() {
        let r = model.rigid_body_modes();
        let kr = model.k.mul(r.as_ref());
        let rel = max_abs(kr.as_ref()) / (model.k.max_abs() * max_abs(r.as_ref()));
        assert!(rel < 1e-12, "{}: |K R| relative {rel:e}", model.name);
    }
}

#[test]
fn stiffness_is_symmetric_positive_semidefinite_with_rigid_rank_deficiency() {
    for model in bodies() {
        assert!(model.k.symmetry_defect() < 1e-14, "{}", model.name);
        let eig = model
            .k_dense()
            .self_adjoint_eigenvalues(Side::Lower)
            .unwrap();
        let largest = eig.last().copied().unwrap();
        let zero = eig.iter().filter(|&&l| l.abs() < 1e-10 * largest).count();
        assert!(
            eig[0] > -1e-10 * largest,
            "{}: negative eigenvalue {}",
            model.name,
            eig[0]
        );
        let expected = if model.name == "beam" { 3 } else { 6 };
        assert_eq!(zero, expected, "{}: zero eigenvalues", model.name);
        let hz = elastic_hz(&free_free_modes(&model).unwrap());
        assert_eq!(hz.len(), model.dof_count() - expected, "{}", model.name);
    }
}

#[test]
fn slab_and_plank_are_one_body_rotated() {
    let (s, p) = (slab(&Default::default()), plank(&Default::default()));
    let a = elastic_hz(&free_free_modes(&s).unwrap());
    let b = elastic_hz(&free_free_modes(&p).unwrap());
    assert_eq!(a.len(), b.len());
    assert_eq!(a.len(), 3 * 30 - 6);
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-9 * x, "{x} vs {y}");
    }
    // §5.3.3 geometry: node 22 behind node 7, nodes 3 and 15 the top corners of the front.
    let n = |j: usize| p.nodes[j - 1];
    assert_eq!([n(22)[0], n(22)[2]], [n(7)[0], n(7)[2]]);
    assert!(n(22)[1] > n(7)[1]);
    let top = p.nodes.iter().map(|q| q[2]).fold(f64::MIN, f64::max);
    assert_eq!(n(3)[2], top);
    assert_eq!(n(15)[2], top);
    assert_eq!(n(3)[1], 0.0);
    assert_eq!(n(15)[1], 0.0);
}

#[test]
fn distorted_brick_keeps_rigid_modes_and_scales_with_size() {
    let mut rng = Rng::new(7);
    for trial in 0..20 {
        let mut x = flexmodes::fem::HEX8_LOCAL_NODES.map(|p| p.map(|c| 0.5 * (c + 1.0)));
        for p in &mut x {
            for c in p.iter_mut() {
                *c += 0.15 * rng.unit();
            }
        }
        let e = 1e6 * (1.0 + rng.unit().abs());
        let k = hex8_stiffness(&x, e, 0.3);
        assert!(symmetry_defect(k.as_ref()) < 1e-12, "trial {trial}");
        let model = FeModel {
            name: "brick".into(),
            dofs: flexmodes::fem::DofMap::solid(),
            nodes: x.to_vec(),
            edges: vec![],
            k: SparseSymmetric::from_dense(k.as_ref()),
            m: MassMatrix::Lumped(vec![1.0; 24]),
            rigid_motions: flexmodes::fem::RigidMotions::FromGeometry,
        };
        let r = model.rigid_body_modes();
        let rel = max_abs((&k * &r).as_ref()) / max_abs(k.as_ref());
        assert!(
            rel < 1e-10,
            "trial {trial}: rigid modes strain the brick ({rel:e})"
        );
        // K scales linearly with size (K ~ E L).
        let s = 1.0 + 2.0 * rng.unit().abs();
        let xs = x.map(|p| p.map(|c| c * s));
        let ks = hex8_stiffness(&xs, e, 0.3);
        let diff = max_abs((&ks - &k * faer::Scale(s)).as_ref()) / max_abs(ks.as_ref());
        assert!(diff < 1e-12, "trial {trial}: scaling {diff:e}");
    }
}

fn all_bases(model: &FeModel, boundary: &[usize], modes: usize) -> Vec<Basis> {
    let p = ReductionRequest {
        boundary_nodes: boundary.to_vec(),
        modes: ModeSelection::Count(modes),
        ..Default::default()
    };
    [
        Method::NoReduction,
        Method::Guyan,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ]
    .iter()
    .map(|&m| reduce(model, &p.with_method(m)).unwrap())
    .collect()
}

/// Seeded random boundary sets that restrain the slab (at least three non-collinear nodes).
fn random_slab_boundaries(rng: &mut Rng, count: usize) -> Vec<Vec<usize>> {
    let mut out = vec![vec![16, 18, 28, 30], vec![1, 13, 16, 28]];
    while out.len() < count {
        let n = 3 + rng.below(4);
        let mut set = Vec::new();
        while set.len() < n {
            let node = 1 + rng.below(30);
            if !set.contains(&node) {
                set.push(node);
            }
        }
        let model = slab(&Default::default());
        if Partition::new(&model, &set)
            .and_then(|p| flexmodes::reduction::constraint_modes(&model, &p))
            .is_ok()
        {
            out.push(set);
        }
    }
    out
}

#[test]
fn reduced_models_keep_the_rigid_motions_and_bound_the_frequencies_from_above() {
    let mut rng = Rng::new(42);
    let beam = beam(&BeamParameters::default());
    let slab = slab(&SlabParameters::default());
    let mut cases: Vec<(&FeModel, Vec<usize>, usize)> = vec![
        (&beam, vec![1, 5], 2),
        (&beam, vec![1, 3, 5], 1),
        (&beam, vec![2, 4], 3),
    ];
    for b in random_slab_boundaries(&mut rng, 6) {
        cases.push((&slab, b, 1 + rng.below(8)));
    }
    for (model, boundary, modes) in cases {
        let rigid = model.rigid_body_modes().ncols();
        let solid = model.name != beam.name;
        assert_eq!(rigid, if solid { 6 } else { 3 });
        let full = free_free_modes(model).unwrap().hz();
        for basis in all_bases(model, &boundary, modes) {
            let what = format!("{} {} {boundary:?}", model.name, basis.method.id());
            let m = basis.reduced_mass(model);
            // Independent columns: M_r positive definite.
            assert!(
                m.llt(Side::Lower).is_ok(),
                "{what}: M_r not positive definite"
            );
            // Rayleigh–Ritz: the i-th reduced frequency bounds the i-th full one from above.
            let red = flexmodes::analysis::reduced_modes(model, &basis)
                .unwrap()
                .hz();
            assert_eq!(red.len(), basis.size(), "{what}");
            assert!(!red.is_empty() && red.len() <= full.len(), "{what}");
            for (i, (r, f)) in red.iter().zip(&full).enumerate() {
                assert!(
                    *r >= f * (1.0 - 1e-9) - 1e-6,
                    "{what}: mode {i} {r} Hz below {f} Hz"
                );
            }
            // Static constraint modes span the rigid motions (Eq. 6.8): every method built on
            // them keeps all rigid-body modes at zero frequency. Modal truncation's boundary
            // columns move the boundary alone (Eq. 6.17), so it cannot keep them all (§7.1),
            // and on the slab it keeps none.
            let zero = red.iter().filter(|&&f| f < 1e-3).count();
            if basis.method == Method::ModalTruncation {
                assert!(zero < rigid, "{what}: {red:?}");
                if solid {
                    assert_eq!(zero, 0, "{what}: {red:?}");
                }
            } else {
                assert_eq!(zero, rigid, "{what}: {red:?}");
            }
        }
    }
}

#[test]
fn craig_bampton_and_mode_condensation_span_one_space() {
    let mut rng = Rng::new(3);
    let beam = beam(&BeamParameters::default());
    let slab = slab(&SlabParameters::default());
    let mut cases: Vec<(&FeModel, Vec<usize>)> = vec![(&beam, vec![1, 5]), (&beam, vec![1, 3, 5])];
    for b in random_slab_boundaries(&mut rng, 5) {
        cases.push((&slab, b));
    }
    for (model, boundary) in cases {
        let part = Partition::new(model, &boundary).unwrap();
        for modes in [0, 1, 2, 4, part.i.len()] {
            let request = ReductionRequest::default()
                .boundary(&boundary)
                .modes(ModeSelection::Count(modes));
            let cb = reduce(model, &request.with_method(Method::CraigBampton)).unwrap();
            let mc = reduce(model, &request.with_method(Method::ModeCondensation)).unwrap();
            let angles = principal_angles(cb.psi.as_ref(), mc.psi.as_ref()).unwrap();
            assert_eq!(angles.len(), cb.size());
            let largest = angles.iter().copied().fold(0.0, f64::max);
            assert!(
                largest < 1e-6,
                "{} {boundary:?} {modes}: angle {largest:e}",
                model.name
            );
            // Same column space => the same reduced frequencies and the same least-squares δ.
            let (a, b) = (
                reduced_hz(model, &cb).unwrap(),
                reduced_hz(model, &mc).unwrap(),
            );
            assert_eq!(a.len(), b.len());
            assert!(!a.is_empty());
            for (x, y) in a.iter().zip(&b) {
                assert!((x - y).abs() <= 1e-7 * x.max(1.0), "{x} vs {y}");
            }
            if model.spatial_dim() == 2 {
                let (fa, fb) = (
                    fit_least_squares(&cb, &PROFILE_DELTA).unwrap(),
                    fit_least_squares(&mc, &PROFILE_DELTA).unwrap(),
                );
                assert_eq!(fa.delta.len(), fb.delta.len());
                assert!(!fa.delta.is_empty());
                for (x, y) in fa.delta.iter().zip(&fb.delta) {
                    assert!((x - y).abs() < 1e-10);
                }
            }
        }
    }
}

#[test]
fn limits_of_craig_bampton_and_mode_condensation() {
    let model = slab(&SlabParameters::default());
    let b = [16, 18, 28, 30];
    let g = reduce(&model, &ReductionRequest::of(Method::Guyan).boundary(&b)).unwrap();
    // No kept mode: CB is Guyan, and MC's Ψ_m turns into Ψ_s (footnote to §6.5.4).
    let none_kept = ReductionRequest::default()
        .boundary(&b)
        .modes(ModeSelection::Count(0));
    let cb0 = reduce(&model, &none_kept.with_method(Method::CraigBampton)).unwrap();
    let mc0 = reduce(&model, &none_kept.with_method(Method::ModeCondensation)).unwrap();
    assert!(max_abs((&cb0.psi - &g.psi).as_ref()) < 1e-12);
    assert!(max_abs((&mc0.psi - &g.psi).as_ref()) < 1e-9);
    // Every mode kept: Ψ_m = 0 (nothing deleted), the basis is square and exact.
    let all = Partition::new(&model, &b).unwrap().i.len();
    let mc = reduce(
        &model,
        &ReductionRequest::of(Method::ModeCondensation)
            .boundary(&b)
            .modes(ModeSelection::Count(all)),
    )
    .unwrap();
    let mt = reduce(
        &model,
        &ReductionRequest {
            method: Method::ModalTruncation,
            boundary_nodes: b.to_vec(),
            modes: ModeSelection::Count(all),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(max_abs((&mc.psi - &mt.psi).as_ref()) < 1e-12);
    let full = elastic_hz(&free_free_modes(&model).unwrap());
    let red = reduced_hz(&model, &mc).unwrap();
    assert_eq!(full.len(), red.len());
    assert_eq!(full.len(), 3 * 30 - 6);
    for (x, y) in full.iter().zip(&red) {
        assert!((x - y).abs() < 1e-8 * x);
    }
}

#[test]
fn guyan_constraint_modes_are_static_and_cb_stiffness_is_block_diagonal() {
    let model = slab(&SlabParameters::default());
    let b = [16, 18, 28, 30];
    let part = Partition::new(&model, &b).unwrap();
    let g = reduce(&model, &ReductionRequest::of(Method::Guyan).boundary(&b)).unwrap();
    // K Ψ_G: no interior force (Eq. 6.2, second row).
    let f = model.k.mul(g.psi.as_ref());
    let scale = max_abs(f.as_ref());
    for &i in &part.i {
        for j in 0..g.size() {
            assert!(f[(i, j)].abs() < 1e-10 * scale);
        }
    }
    // Eq. (6.20): Ψ_CB^T K Ψ_CB = diag(K_G, K̄_n^k) with K̄_n^k = Λ_n^k.
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&b)
            .modes(ModeSelection::Count(6)),
    )
    .unwrap();
    let k = cb.reduced_stiffness(&model);
    let nb = part.b.len();
    let lam = fixed_interface_modes(&model, &part).unwrap().values;
    let top = max_abs(k.as_ref());
    for i in 0..k.nrows() {
        for j in 0..k.ncols() {
            let expected = if i >= nb && j >= nb {
                if i == j { lam[i - nb] } else { 0.0 }
            } else if (i < nb) != (j < nb) {
                0.0
            } else {
                k[(i, j)]
            };
            assert!((k[(i, j)] - expected).abs() < 1e-10 * top, "K_CB[{i},{j}]");
        }
    }
    // Normal modes are mass-normalised with the deterministic sign.
    let m = cb.reduced_mass(&model);
    for i in nb..m.nrows() {
        assert!((m[(i, i)] - 1.0).abs() < 1e-12);
        let col = cb.column(i);
        let largest = col.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let first = col.iter().find(|v| v.abs() > 1e-8 * largest).unwrap();
        assert!(*first > 0.0);
    }
}

#[test]
fn mode_selection_by_frequency_cut_off() {
    let model = beam(&BeamParameters::default());
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[1, 5])
            .modes(ModeSelection::UpToHz(13.0)),
    )
    .unwrap();
    // 3.10366 and 12.3283 Hz are below 13 Hz, 26.18 Hz is not.
    assert_eq!(cb.size(), 4 + 2);
    let none = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[1, 5])
            .modes(ModeSelection::UpToHz(1.0)),
    )
    .unwrap();
    assert_eq!(none.size(), 4);
}

#[test]
fn eitelberg_is_guyan_for_structures() {
    let model = beam(&BeamParameters::default());
    for masters in [vec![1, 3, 5], vec![1, 2, 5], vec![1, 5]] {
        let eit = eitelberg(&model, &masters, &EitelbergParameters::default()).unwrap();
        let g = reduced_hz(
            &model,
            &reduce(
                &model,
                &ReductionRequest::of(Method::Guyan).boundary(&masters),
            )
            .unwrap(),
        )
        .unwrap();
        assert_eq!(eit.hz.len(), g.len(), "{masters:?}");
        // R S R^T has a condition number near 1e11 (reported by the reduction), so the
        // restored matrix, and with it the frequencies, carry ~1e-5 relative round-off
        // whatever the Lyapunov solver (a Kronecker-product solve gave 3.5e-6 too).
        assert!(eit.gramian_condition > 1e9 && eit.gramian_condition < 1e13);
        for (x, y) in eit.hz.iter().zip(&g) {
            assert!((x - y).abs() < 1e-5 * y, "{masters:?}: {x} vs {y}");
        }
        // The footnote's coherence check: as many zero singular values before and after.
        assert_eq!(eit.zero_singular_values.0, eit.zero_singular_values.1);
    }
}

#[test]
fn nodal_fixed_column_removal_for_every_table_4_1_configuration() {
    let model = slab(&SlabParameters::default());
    // Node j on the axis and node k on the plane, chosen to fit each configuration's geometry
    // with the origin at node 16: ξ through 28, η through 18, ζ through 1.
    let on = |d: flexmodes::fem::Direction| match d {
        flexmodes::fem::Direction::X => 28,
        flexmodes::fem::Direction::Y => 18,
        flexmodes::fem::Direction::Z => 1,
    };
    let nr = reduce(
        &model,
        &ReductionRequest {
            method: Method::NoReduction,
            boundary_nodes: vec![16],
            modes: ModeSelection::Count(0),
            ..Default::default()
        },
    )
    .unwrap();
    let gr = reduce(
        &model,
        &ReductionRequest::of(Method::Guyan).boundary(&[16, 18, 28, 1]),
    )
    .unwrap();
    for cfg in TableConfiguration::ALL {
        let axes = NodalFixedAxes {
            origin: 16,
            axis_node: on(cfg.axis),
            plane_node: on(cfg.plane_with),
            configuration: cfg,
        };
        for basis in [&nr, &gr] {
            let nf = axes.apply(&model, basis).unwrap();
            assert_eq!(nf.size(), basis.size() - 6, "{cfg:?}");
            for (_, _, dof) in axes.anchored_dofs(&model).unwrap() {
                assert!((0..nf.size()).all(|j| nf.psi[(dof, j)] == 0.0));
            }
            // Six determinate anchors remove every rigid-body motion: K_r is definite.
            let k = nf.reduced_stiffness(&model);
            assert!(k.llt(Side::Lower).is_ok(), "{cfg:?} {}", basis.method.id());
        }
    }
    // §7.2: 90 × 84 for NR, 90 × 12 for CB with boundary 16, 18, 28, 30.
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[16, 18, 28, 30])
            .modes(ModeSelection::Count(6)),
    )
    .unwrap();
    assert_eq!(
        NodalFixedAxes::slab_default()
            .apply(&model, &cb)
            .unwrap()
            .size(),
        12
    );
    assert_eq!(
        NodalFixedAxes::slab_default()
            .apply(&model, &nr)
            .unwrap()
            .size(),
        84
    );
}
