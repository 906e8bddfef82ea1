//! The companion papers' methods against independent computations: MacNeal–Rubin's residual
//! flexibility, Benfield–Hruda's loading limits, moment matching's moments, balanced
//! truncation's bound and Gregory's approximation of the Hankel singular values, and
//! Witteveen's statics and modes under supports changed after reduction.

use faer::{
    Mat, MatRef, Side,
    linalg::solvers::{DenseSolveCore, Solve},
};
use flexmodes::reduction::ReductionError;
use flexmodes::reduction::{Method, ReductionRequest, reduce};
use flexmodes::{
    analysis::{StaticLoadCase, full_static_response, modes_in_band, pair_modes},
    error::CoreError as Error,
    fem::{
        BeamParameters, Direction, DualSpinParameters, FeModel, FrameSection, NodeDof,
        OverhangFrameParameters, beam, dual_spin, frame, overhang_frame,
    },
    linalg::{generalized_eigen, identity, max_abs, solve_lyapunov},
    models::{
        CantileverIo, CbSets, DualSpinSets, assemble, full_synthesis, mode_set_bases,
        witteveen_bases,
    },
    reduction::{
        BalancedBasisParameters, InterfaceLoading, IoMap, LoadedInterface, MacNealRubinParameters,
        ModalModel, ModeSelection, MomentMatchingParameters, Partition, RestrainedRitzModel,
        balanced_basis, balanced_truncation, benfield_hruda, fixed_interface_modes, macneal_rubin,
        modal_gramians, modal_influence, moment_matching,
    },
};

/// A free-free 3-D frame (SI units): a bent line of `n` elements with a skew end, so no
/// symmetry hides a term.
fn free_frame(n: usize) -> FeModel {
    let mut nodes: Vec<[f64; 3]> = (0..=n).map(|i| [0.1 * i as f64, 0.0, 0.0]).collect();
    nodes.push([0.1 * n as f64 + 0.05, 0.08, 0.03]);
    nodes.push([0.1 * n as f64 + 0.07, 0.2, 0.05]);
    let up = [0.0, 0.0, 1.0];
    let mut elements: Vec<([usize; 2], [f64; 3])> = (0..n).map(|i| ([i, i + 1], up)).collect();
    elements.push(([n, n + 1], up));
    elements.push(([n + 1, n + 2], [1.0, 0.0, 0.0]));
    let section = FrameSection::rectangle(0.02, 0.01, 210e9, 80e9, 7800.0);
    frame("free frame", nodes, &elements, &section).unwrap()
}

/// The DOF not in `held` and the stiffness and mass blocks on them.
fn free_blocks(model: &FeModel, held: &[usize]) -> (Vec<usize>, Mat<f64>, Mat<f64>) {
    let free: Vec<usize> = (0..model.dof_count())
        .filter(|d| !held.contains(d))
        .collect();
    let (k, m) = (model.k_dense(), model.m_dense());
    let kf = Mat::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let mf = Mat::from_fn(free.len(), free.len(), |i, j| m[(free[i], free[j])]);
    (free, kf, mf)
}

fn dense_inverse(a: MatRef<'_, f64>) -> Mat<f64> {
    a.partial_piv_lu().inverse()
}

/// $P^TGP$ built here from its definition (Eqs. 13–14), independently of the library.
fn elastic_flexibility(model: &FeModel, r_set: &[usize]) -> Mat<f64> {
    let n = model.dof_count();
    let (k, m) = (model.k_dense(), model.m_dense());
    let kept: Vec<usize> = (0..n).filter(|d| !r_set.contains(d)).collect();
    let kk = Mat::from_fn(kept.len(), kept.len(), |i, j| k[(kept[i], kept[j])]);
    let inv = dense_inverse(kk.as_ref());
    let mut g = Mat::<f64>::zeros(n, n);
    for (a, &i) in kept.iter().enumerate() {
        for (b, &j) in kept.iter().enumerate() {
            g[(i, j)] = inv[(a, b)];
        }
    }
    // Rigid modes, mass-normalised: the zero-frequency eigenvectors of the full problem.
    let eig = generalized_eigen(k.as_ref(), m.as_ref(), "free").unwrap();
    let phi_r = eig.vectors.subcols(0, 6).to_owned();
    let p = identity(n) - &m * &phi_r * phi_r.transpose();
    p.transpose() * &g * &p
}

#[test]
fn inertia_relief_flexibility_equals_the_elastic_modes_flexibility() {
    let model = free_frame(5);
    let n = model.dof_count();
    let eig =
        generalized_eigen(model.k_dense().as_ref(), model.m_dense().as_ref(), "free").unwrap();
    assert!(eig.values[5] < 1e-6 * eig.values[6], "six rigid modes");
    let phi_e = eig.vectors.subcols(6, n - 6);
    let flex = phi_e
        * Mat::from_fn(n - 6, n - 6, |i, j| {
            if i == j { 1.0 / eig.values[6 + i] } else { 0.0 }
        })
        * phi_e.transpose();
    // Any statically determinate r-set gives the same PᵀGP: node 1's six DOF, or node 3's.
    for r_node in [0usize, 2] {
        let r_set: Vec<usize> = (0..6).map(|d| r_node * 6 + d).collect();
        let ptgp = elastic_flexibility(&model, &r_set);
        let rel = max_abs((&ptgp - &flex).as_ref()) / max_abs(flex.as_ref());
        assert!(rel < 1e-8, "r-set at node {}: {rel:e}", r_node + 1);
    }
}

#[test]
fn residual_modes_are_the_residual_flexibility_orthogonal_to_the_kept_modes() {
    let model = free_frame(5);
    let n = model.dof_count();
    let interface: Vec<usize> = (0..6).map(|d| 5 * 6 + d).collect();
    let r_set: Vec<usize> = (0..6).collect();
    let kept = 4;
    let basis = macneal_rubin(
        &model,
        &MacNealRubinParameters {
            interface: interface.clone(),
            r_set: r_set.clone(),
            modes: ModeSelection::Count(kept),
            held: vec![],
        },
    )
    .unwrap();
    assert_eq!(basis.size(), 6 + kept + interface.len());
    let psi = &basis.psi;
    let free = psi.subcols(0, 6 + kept);
    let residual = psi.subcols(6 + kept, interface.len());
    // M- and K-orthogonal to every kept free-interface mode (rigid ones included for M; their
    // K-products vanish anyway): as cosines in each inner product.
    let (k, m) = (model.k_dense(), model.m_dense());
    let cosine = |a: &Mat<f64>, x: MatRef<'_, f64>, y: MatRef<'_, f64>| {
        let xy = x.transpose() * a * y;
        let xx = x.transpose() * a * x;
        let yy = y.transpose() * a * y;
        let mut worst = 0.0f64;
        for i in 0..x.ncols() {
            for j in 0..y.ncols() {
                worst = worst.max(xy[(i, j)].abs() / (xx[(i, i)] * yy[(j, j)]).sqrt());
            }
        }
        worst
    };
    let mo = cosine(&m, free, residual);
    let ko = cosine(&k, free.subcols(6, kept), residual);
    assert!(mo < 1e-8, "M: {mo:e}");
    assert!(ko < 1e-8, "K: {ko:e}");
    // The test can fail: the residual modes are not orthogonal to a dropped free mode.
    let eig_all = generalized_eigen(k.as_ref(), m.as_ref(), "free").unwrap();
    let dropped = eig_all.vectors.subcols(6 + kept, 1);
    assert!(cosine(&m, dropped, residual) > 1e-4);
    // Eq. (12) from scratch: [PᵀGP − Φ_e Ω_e⁻² Φ_eᵀ] F.
    let eig = eig_all;
    let phi_k = eig.vectors.subcols(6, kept);
    let f = Mat::from_fn(n, interface.len(), |r, c| {
        if r == interface[c] { 1.0 } else { 0.0 }
    });
    let kept_flex = phi_k
        * Mat::from_fn(kept, kept, |i, j| {
            if i == j { 1.0 / eig.values[6 + i] } else { 0.0 }
        })
        * phi_k.transpose();
    let expected = (elastic_flexibility(&model, &r_set) - kept_flex) * &f;
    let rel = max_abs((residual - &expected).as_ref()) / max_abs(expected.as_ref());
    assert!(rel < 1e-7, "{rel:e}");
    // Statically complete for interface loads: the inertia-relief response PᵀGP f to any
    // interface load lies in the span of the MR basis.
    let load = Mat::from_fn(n, 1, |r, _| {
        interface
            .iter()
            .position(|&d| d == r)
            .map_or(0.0, |c| (c as f64 * 0.7).sin() + 0.3)
    });
    let u = elastic_flexibility(&model, &r_set) * &load;
    let z = (psi.transpose() * psi)
        .llt(Side::Lower)
        .unwrap()
        .solve(psi.transpose() * &u);
    let fit = psi * &z - &u;
    assert!(
        max_abs(fit.as_ref()) < 1e-8 * max_abs(u.as_ref()),
        "{:e}",
        max_abs(fit.as_ref())
    );
}

#[test]
fn a_bad_r_set_is_a_named_error() {
    let model = free_frame(5);
    let interface: Vec<usize> = (0..6).map(|d| 5 * 6 + d).collect();
    let run = |r_set: Vec<usize>| {
        macneal_rubin(
            &model,
            &MacNealRubinParameters {
                interface: interface.clone(),
                r_set,
                modes: ModeSelection::Count(2),
                held: vec![],
            },
        )
    };
    // Translations of one node only: the rotations stay free.
    match run(vec![0, 1, 2]) {
        Err(Error::Reduction(ReductionError::InvalidRSet { problem, .. })) => {
            assert!(
                matches!(problem, flexmodes::error::RSetProblem::Deficient { .. }),
                "{problem}"
            )
        }
        other => panic!("{other:?}"),
    }
    // Two full nodes: statically indeterminate.
    match run((0..12).collect()) {
        Err(Error::Reduction(ReductionError::InvalidRSet { problem, .. })) => {
            assert!(
                matches!(problem, flexmodes::error::RSetProblem::Redundant { .. }),
                "{problem}"
            )
        }
        other => panic!("{other:?}"),
    }
    // Overlapping the interface.
    assert!(matches!(
        run((30..36).collect()),
        Err(Error::Reduction(ReductionError::InvalidDofSet { .. }))
    ));
}

#[test]
fn benfield_hruda_spans_free_and_fixed_interface_limits() {
    let model = free_frame(5);
    let interface: Vec<usize> = (0..6).collect();
    let ni = interface.len();
    let eig =
        generalized_eigen(model.k_dense().as_ref(), model.m_dense().as_ref(), "free").unwrap();
    // No loading: the free-free modes.
    let none = LoadedInterface {
        dofs: interface.clone(),
        loading: InterfaceLoading {
            mass: Mat::zeros(ni, ni),
            stiffness: Mat::zeros(ni, ni),
        },
    };
    let bh = benfield_hruda(&model, &[none], &[], ModeSelection::Count(10)).unwrap();
    let k_r = bh.reduced_stiffness(&model);
    let m_r = bh.reduced_mass(&model);
    let red = generalized_eigen(k_r.as_ref(), m_r.as_ref(), "bh").unwrap();
    for i in 6..10 {
        let rel = (red.values[i] - eig.values[i]).abs() / eig.values[i];
        assert!(rel < 1e-9, "mode {i}: {rel:e}");
    }
    // A very stiff neighbour: the interface is clamped, so the loaded modes tend to the
    // fixed-interface ones (relative shift of order k_component / k_loading).
    let k_scale = model.k.max_abs();
    let stiff = LoadedInterface {
        dofs: interface.clone(),
        loading: InterfaceLoading {
            mass: Mat::zeros(ni, ni),
            stiffness: Mat::from_fn(ni, ni, |i, j| if i == j { 1e4 * k_scale } else { 0.0 }),
        },
    };
    let bh = benfield_hruda(&model, &[stiff], &[], ModeSelection::Count(4)).unwrap();
    let fixed = fixed_interface_modes(&model, &Partition::new(&model, &[1]).unwrap()).unwrap();
    let hz: Vec<f64> = bh
        .columns
        .iter()
        .filter_map(|c| match c.kind {
            flexmodes::reduction::ColumnKind::Loaded { hz } => Some(hz),
            _ => None,
        })
        .collect();
    assert_eq!(hz.len(), 4);
    for (i, (a, b)) in hz.iter().zip(fixed.hz()).enumerate() {
        assert!((a - b).abs() < 1e-3 * b, "mode {}: {a} vs {b}", i + 1);
    }
}

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

#[test]
fn mode_set_claims_of_spanos_tsuha_on_our_assembly() {
    let out = flexmodes::scenes::find("slab-mode-sets")
        .unwrap()
        .execute(&flexmodes::scenes::SceneOptions::default())
        .unwrap();
    let get = |k: &str| out.report.result(k).and_then(|v| v.as_f64()).unwrap();
    // Every mode set follows the full response within a few per cent of its peak over the band
    // of interest; MR, statically complete at the interfaces, best.
    for (id, limit) in [("cb", 0.03), ("mr", 0.01), ("bh", 0.1)] {
        let e = get(&format!("frf_rel_error.{id}"));
        assert!(e < limit, "{id}: {e}");
    }
    // The influence-ranked rotor modes keep the CB set's accuracy with far fewer modes; the
    // lowest as many do not.
    let (inf, low, cb) = (
        get("selection.influence"),
        get("selection.lowest"),
        get("frf_rel_error.cb"),
    );
    assert!(inf < 2.0 * cb, "{inf} vs CB {cb}");
    assert!(low > 10.0 * inf, "{low} vs {inf}");
    let kept = get("selection_kept");
    let all = get("rotor_elastic_modes");
    assert!(kept < 0.5 * all, "{kept} of {all}");
}
