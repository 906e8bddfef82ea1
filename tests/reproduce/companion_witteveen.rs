//! Witteveen's methods against independent computations: statics of CB, MM and BT for the
//! loads of the inputs and outputs, moment matching's moments, balanced truncation's bound,
//! Gregory's approximation of the Hankel singular values, modes under supports changed after
//! reduction, and component synthesis.

use faer::{Mat, linalg::solvers::Solve};
use flexmodes::reduction::ReductionError;
use flexmodes::reduction::{Method, ReductionRequest, reduce};
use flexmodes::{
    analysis::{StaticLoadCase, full_static_response, modes_in_band, pair_modes},
    error::CoreError as Error,
    fem::{
        BeamParameters, Direction, DualSpinParameters, FrameSection, NodeDof,
        OverhangFrameParameters, beam, dual_spin, frame, overhang_frame,
    },
    linalg::{generalized_eigen, max_abs, solve_lyapunov},
    models::{
        CantileverIo, CbSets, DualSpinSets, assemble, full_synthesis, mode_set_bases,
        witteveen_bases,
    },
    reduction::{
        BalancedBasisParameters, IoMap, ModalModel, ModeSelection, MomentMatchingParameters,
        Partition, RestrainedRitzModel, balanced_basis, balanced_truncation, modal_gramians,
        modal_influence, moment_matching,
    },
};

use super::companion::free_blocks;

/// Witteveen's structure, a coarse mesh for speed.
fn witteveen() -> (flexmodes::fem::OverhangFrame, CantileverIo) {
    let frame = overhang_frame(&OverhangFrameParameters {
        element_length: 50.0,
        ..Default::default()
    })
    .unwrap();
    let io = CantileverIo::of(&frame).unwrap();
    (frame, io)
}

#[test]
fn cb_and_mm_are_exact_in_statics_for_io_loads_and_bt_is_not() {
    let (frame, io) = witteveen();
    let model = &frame.model;
    let methods = [
        flexmodes::reduction::Method::CraigBampton,
        flexmodes::reduction::Method::MomentMatching,
        flexmodes::reduction::Method::BalancedTruncation,
    ];
    let (bases, deflated) = witteveen_bases(&frame, &io, &methods).unwrap();
    assert_eq!(deflated, 0);
    assert!(bases.iter().all(|b| b.size() == 14));
    let ioo = io.io();
    // Seeded loads on the seven I/O DOF in variant 1, and on B in variant 2 (A held).
    for (variant, loads) in [
        (
            1,
            (0..7)
                .map(|k| (ioo[k], 10.0 * ((k as f64 * 1.3).sin() + 0.2)))
                .collect::<Vec<_>>(),
        ),
        (1, vec![(io.a[0], 1000.0)]),
        (2, vec![(io.bz, 10.0)]),
    ] {
        let (held, _) = io.variant(variant);
        let mut load = vec![0.0; model.dof_count()];
        for (d, f) in &loads {
            load[*d] = *f;
        }
        let full = full_static_response(
            model,
            &StaticLoadCase {
                held: held.iter().map(|&d| (d, 0.0)).collect(),
                load: load.clone(),
            },
        )
        .unwrap();
        let peak = full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for basis in &bases {
            let u = RestrainedRitzModel::new(model, basis.psi.as_ref(), &held, &[])
                .unwrap()
                .static_response(&load)
                .unwrap();
            assert_eq!(u.len(), full.len());
            let err = u
                .iter()
                .zip(&full)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                / peak;
            let id = basis.method.id();
            if id == "bt" {
                if loads.len() == 1 && variant == 1 {
                    // LC 2: no BT vector has a dominant x displacement.
                    assert!(err > 0.01, "BT in LC 2: {err:e}");
                }
            } else {
                assert!(err < 1e-10, "{id} variant {variant}: {err:e}");
            }
        }
    }
}

#[test]
fn moment_matching_matches_the_first_2m_moments() {
    let (frame, io) = witteveen();
    let model = &frame.model;
    let (held, _) = io.variant(1);
    let ioo = io.io();
    let (free, kf, mf) = free_blocks(model, &held);
    let b1 = Mat::from_fn(
        free.len(),
        7,
        |r, c| if free[r] == ioo[c] { 1.0 } else { 0.0 },
    );
    // H(s) = C₁(s²M + K)⁻¹B₁ = Σ_j (−s²)^j C₁(K⁻¹M)^j K⁻¹B₁: moments in s².
    let moments = |k: &Mat<f64>, m: &Mat<f64>, b: &Mat<f64>, c: &Mat<f64>, count: usize| {
        let lu = k.partial_piv_lu();
        let mut x = lu.solve(b);
        let mut out = Vec::new();
        for _ in 0..count {
            out.push(c * &x);
            x = lu.solve(m * &x);
        }
        out
    };
    let full = moments(&kf, &mf, &b1, &b1.transpose().to_owned(), 4);
    let mut unmatched = Vec::new();
    for blocks in [1usize, 2] {
        let mm = moment_matching(
            model,
            &MomentMatchingParameters {
                inputs: ioo.clone(),
                held: held.clone(),
                blocks,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(mm.deflated.is_empty());
        assert_eq!(mm.basis.size(), 7 * blocks);
        let v = Mat::from_fn(free.len(), mm.basis.size(), |r, c| {
            mm.basis.psi[(free[r], c)]
        });
        let (kr, mr) = (v.transpose() * &kf * &v, v.transpose() * &mf * &v);
        let reduced = moments(&kr, &mr, &(v.transpose() * &b1), &(b1.transpose() * &v), 4);
        assert_eq!(full.len(), reduced.len());
        for (j, (f, r)) in full.iter().zip(&reduced).enumerate() {
            let rel = max_abs((f - r).as_ref()) / max_abs(f.as_ref());
            if j < 2 * blocks {
                assert!(rel < 1e-8, "{blocks} blocks, moment {j}: {rel:e}");
            } else {
                unmatched.push(rel);
            }
        }
    }
    // One block (the static shapes) leaves moments 2 and 3 unmatched: the test can tell.
    assert_eq!(unmatched.len(), 2);
    assert!(unmatched.iter().all(|&r| r > 1e-6), "{unmatched:?}");
}

#[test]
fn krylov_deflation_is_stated_not_silent() {
    // Three free DOF and two blocks of two inputs: the space is exhausted after three vectors.
    let model = beam(&BeamParameters::default());
    let held: Vec<usize> = (0..model.dof_count())
        .filter(|d| ![3, 4, 5].contains(d))
        .collect();
    let mm = moment_matching(
        &model,
        &MomentMatchingParameters {
            inputs: vec![3, 4],
            held,
            blocks: 3,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(mm.basis.size(), 3);
    assert!(!mm.deflated.is_empty());
    assert!(mm.deflated.iter().all(|d| d.ratio < 1e-8));
}

/// A clamped 3-D frame's modal model with damping `zeta`, SISO or with several channels.
fn clamped_modal(zeta: f64, io: &IoMap, modes: usize) -> ModalModel {
    let n = 12;
    let nodes: Vec<[f64; 3]> = (0..=n).map(|i| [0.1 * i as f64, 0.0, 0.0]).collect();
    let elements: Vec<([usize; 2], [f64; 3])> =
        (0..n).map(|i| ([i, i + 1], [0.0, 1.0, 0.0])).collect();
    let section = FrameSection::rectangle(0.03, 0.01, 210e9, 80e9, 7800.0);
    let model = frame("clamped", nodes, &elements, &section).unwrap();
    let part = Partition::new(&model, &[1]).unwrap();
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[1])
            .modes(ModeSelection::Count(modes)),
    )
    .unwrap();
    // Clamp node 1: keep only the fixed-interface columns (zero on the clamp).
    let keep: Vec<usize> = (part.b.len()..cb.size()).collect();
    let phi = Mat::from_fn(model.dof_count(), keep.len(), |r, c| cb.psi[(r, keep[c])]);
    let k = phi.transpose() * model.k_dense() * &phi;
    let m = phi.transpose() * model.m_dense() * &phi;
    ModalModel::new(k.as_ref(), m.as_ref(), phi.as_ref(), io, zeta).unwrap()
}

#[test]
fn balanced_truncation_error_bound_holds_on_the_computed_frf() {
    let tip = |d: usize| 12 * 6 + d;
    let io = IoMap {
        inputs: vec![tip(2), 6 * 6 + 1],
        displacement_outputs: vec![tip(2)],
        velocity_outputs: vec![6 * 6 + 1],
    };
    let modal = clamped_modal(0.02, &io, 8);
    let (w, v, ss) = modal_gramians(&modal).unwrap();
    // The Hankel singular values are √λ(WV) (Eq. 40): an independent eigen solve.
    let wv = &w * &v;
    let mut lambda: Vec<f64> = wv
        .eigenvalues()
        .unwrap()
        .iter()
        .map(|l| l.re.max(0.0).sqrt())
        .collect();
    lambda.sort_by(|a, b| b.total_cmp(a));
    // And the gramians solve their equations by the eigenvector method too.
    let w2 = solve_lyapunov(ss.a.as_ref(), (&ss.b * ss.b.transpose()).as_ref()).unwrap();
    assert!(max_abs((&w - &w2).as_ref()) < 1e-7 * max_abs(w.as_ref()));
    for states in [4, 8, 12] {
        let bt = balanced_truncation(&modal, states).unwrap();
        assert_eq!(bt.hankel_singular_values.len(), lambda.len());
        for (a, b) in bt.hankel_singular_values.iter().zip(&lambda) {
            assert!((a - b).abs() < 1e-6 * lambda[0], "{a} vs {b}");
        }
        assert_eq!(bt.reduced.order(), states);
        // max over a fine grid (every natural frequency included) of σ_max(G − G_k).
        let top = modal.hz().last().copied().unwrap() * 1.3;
        let hz = flexmodes::analysis::band_frequencies(0.1, top, 3000, &modal.hz());
        let mut worst = 0.0f64;
        for f in hz {
            let w = 2.0 * std::f64::consts::PI * f;
            let d = modal.frf(w) - bt.frf(w);
            let s = d.singular_values().unwrap()[0];
            worst = worst.max(s);
        }
        assert!(
            worst <= bt.error_bound * (1.0 + 1e-9),
            "{states}: {worst:e} > {:e}",
            bt.error_bound
        );
        // And the bound is not vacuous: within a factor 20 of what is seen.
        assert!(
            worst > bt.error_bound / 20.0,
            "{states}: {worst:e} ≪ {:e}",
            bt.error_bound
        );
    }
    // No damping, no gramian.
    let undamped = clamped_modal(0.0, &io, 4);
    assert!(matches!(
        balanced_truncation(&undamped, 2),
        Err(Error::Reduction(ReductionError::NoModalDamping { .. }))
    ));
    assert!(matches!(
        modal_influence(&undamped),
        Err(Error::Reduction(ReductionError::NoModalDamping { .. }))
    ));
}

#[test]
fn gregory_coefficients_approximate_the_hankel_singular_values() {
    // The companion notes' single-mode check: ζ = 0.01, ω = 3, three inputs, two outputs
    // with rate terms. We pick b, c₁, c₂ (the notes do not print theirs) and compare with the
    // exact pair from the gramians.
    let single = ModalModel {
        shapes: Mat::zeros(1, 1),
        omega: vec![3.0],
        zeta: 0.01,
        rigid: 0,
        b: Mat::from_fn(1, 3, |_, j| [0.4, -0.7, 1.1][j]),
        c1: Mat::from_fn(2, 1, |i, _| [0.9, -0.3][i]),
        c2: Mat::from_fn(2, 1, |i, _| [0.05, 0.2][i]),
    };
    let sigma = modal_influence(&single).unwrap().sigma[0];
    let hsv = balanced_truncation(&single, 2)
        .unwrap()
        .hankel_singular_values;
    assert_eq!(hsv.len(), 2);
    for h in &hsv {
        assert!((sigma - h).abs() < 0.01 * h, "{sigma} vs {h}");
    }
    // A clamped frame, lightly damped, displacement outputs (Eq. 46): every mode's σ within a
    // few per cent of its exact pair (matched by value), when Eq. (45) holds.
    let tip = 12 * 6 + 2;
    let io = IoMap {
        inputs: vec![tip, 8 * 6 + 1],
        displacement_outputs: vec![tip, 8 * 6 + 1],
        velocity_outputs: vec![],
    };
    let modal = clamped_modal(0.002, &io, 6);
    let inf = modal_influence(&modal).unwrap();
    assert!(inf.closeness < 0.1, "Eq. 45: {}", inf.closeness);
    let exact = balanced_truncation(&modal, 2)
        .unwrap()
        .hankel_singular_values;
    assert_eq!(exact.len(), 2 * inf.sigma.len());
    let mut approx = inf.sigma.clone();
    approx.sort_by(|a, b| b.total_cmp(a));
    for (i, s) in approx.iter().enumerate() {
        for h in [exact[2 * i], exact[2 * i + 1]] {
            assert!((s - h).abs() < 0.03 * h, "σ{}: {s:e} vs {h:e}", i + 1);
        }
    }
}

#[test]
fn cb_reproduces_the_full_modes_in_band_when_a_is_clamped_after_reduction() {
    let (frame, io) = witteveen();
    let model = &frame.model;
    let (bases, _) =
        witteveen_bases(&frame, &io, &[flexmodes::reduction::Method::CraigBampton]).unwrap();
    let (held, masses) = io.variant(2);
    // The reference by an independent route: the free DOF's dense eigenproblem.
    let (free, kf, mf) = free_blocks(model, &held);
    let eig = generalized_eigen(kf.as_ref(), mf.as_ref(), "variant 2").unwrap();
    let shapes = Mat::from_fn(model.dof_count(), free.len(), |r, c| {
        free.iter()
            .position(|&d| d == r)
            .map_or(0.0, |q| eig.vectors[(q, c)])
    });
    let hz = eig.hz();
    let band = modes_in_band(&hz, 0.0, 200.0, "variant 2").unwrap();
    assert!(band.len() >= 3, "{hz:?}");
    let reduced = RestrainedRitzModel::new(model, bases[0].psi.as_ref(), &held, &masses).unwrap();
    assert_eq!(reduced.removed, 6);
    let modes = reduced.modes().unwrap();
    let pairs = pair_modes(
        shapes.as_ref(),
        &hz,
        &band,
        modes.vectors.as_ref(),
        &modes.hz(),
    );
    assert_eq!(pairs.len(), band.len());
    for p in &pairs {
        assert!(p.frequency_error.abs() < 0.005, "{p:?}");
        assert!(
            p.frequency_error > -1e-9,
            "a Ritz model errs upwards: {p:?}"
        );
        assert!(p.mac > 0.99, "{p:?}");
    }
    // A band above every mode is a named error.
    assert!(matches!(
        modes_in_band(&hz, 1e7, 2e7, "variant 2"),
        Err(Error::Reduction(ReductionError::EmptyBand { .. }))
    ));
}

#[test]
fn balanced_basis_needs_damping_and_existing_dofs() {
    let (frame, io) = witteveen();
    let model = &frame.model;
    let p = BalancedBasisParameters {
        inputs: io.io(),
        held: io.clamp.clone(),
        vectors: 14,
        alpha: 0.0,
    };
    assert!(matches!(
        balanced_basis(model, &p),
        Err(Error::Reduction(ReductionError::NoViscousDamping {
            alpha: 0.0
        }))
    ));
    let bad = BalancedBasisParameters {
        inputs: vec![model.dof_count() + 3],
        alpha: 1e-4,
        ..p
    };
    assert!(matches!(
        balanced_basis(model, &bad),
        Err(Error::Reduction(ReductionError::InvalidDofSet { .. }))
    ));
    // A node without the DOF asked for: the plane beam has no z.
    let beam = beam(&BeamParameters::default());
    assert!(matches!(
        beam.node_dof(2, NodeDof::Translation(Direction::Z)),
        Err(Error::NoSuchDof { .. })
    ));
}

#[test]
fn component_synthesis_with_identity_bases_is_the_assembled_body() {
    let ds = dual_spin(&DualSpinParameters {
        boom_elements: 3,
        column_elements: 4,
        arm_elements: 2,
        ..Default::default()
    })
    .unwrap();
    let sets = DualSpinSets::of(&ds).unwrap();
    let syn = full_synthesis(&ds, &sets).unwrap();
    let eig = generalized_eigen(syn.k.as_ref(), syn.m.as_ref(), "synthesis").unwrap();
    // The same structure assembled as one body, its base held: an independent route.
    let model = &ds.assembly;
    let base: Vec<usize> = (0..6).map(|d| ds.ground * 6 + d).collect();
    let (free, kf, mf) = free_blocks(model, &base);
    assert_eq!(free.len(), syn.size());
    let direct = generalized_eigen(kf.as_ref(), mf.as_ref(), "assembly").unwrap();
    assert_eq!(eig.values.len(), direct.values.len());
    for (i, (a, b)) in eig.values.iter().zip(&direct.values).take(30).enumerate() {
        assert!((a - b).abs() < 1e-8 * b, "mode {}: {a} vs {b}", i + 1);
    }
    // A reduced synthesis is a Ritz model of the same structure: it errs upwards.
    let cb = CbSets::of(&ds, &sets).unwrap();
    let [rotor, stator] =
        mode_set_bases(&ds, &sets, flexmodes::reduction::Method::CraigBampton, &cb).unwrap();
    let red = assemble(&ds, rotor, stator).unwrap();
    let red_eig = generalized_eigen(red.k.as_ref(), red.m.as_ref(), "cb").unwrap();
    assert!(!red_eig.values.is_empty() && red_eig.values.len() < direct.values.len());
    for (i, (a, b)) in red_eig.values.iter().zip(&direct.values).enumerate() {
        assert!(*a >= b * (1.0 - 1e-9), "mode {}: {a} below {b}", i + 1);
    }
}
