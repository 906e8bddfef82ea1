//! The companion papers' methods against independent computations: MacNeal–Rubin's residual
//! flexibility, Benfield–Hruda's loading limits and Spanos–Tsuha's mode-set claims (Witteveen's
//! in companion_witteveen.rs).

use faer::{
    Mat, MatRef, Side,
    linalg::solvers::{DenseSolveCore, Solve},
};
use flexmodes::reduction::ReductionError;
use flexmodes::{
    error::CoreError as Error,
    fem::{FeModel, FrameSection, frame},
    linalg::{generalized_eigen, identity, max_abs},
    reduction::{
        InterfaceLoading, LoadedInterface, MacNealRubinParameters, ModeSelection, Partition,
        benfield_hruda, fixed_interface_modes, macneal_rubin,
    },
};

/// A free-free 3-D frame (SI units): a bent line of `n` elements with a skew end, so no
/// symmetry hides a term.
pub(crate) fn free_frame(n: usize) -> FeModel {
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
pub(crate) fn free_blocks(model: &FeModel, held: &[usize]) -> (Vec<usize>, Mat<f64>, Mat<f64>) {
    let free: Vec<usize> = (0..model.dof_count())
        .filter(|d| !held.contains(d))
        .collect();
    let (k, m) = (model.k_dense(), model.m_dense());
    let kf = Mat::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let mf = Mat::from_fn(free.len(), free.len(), |i, j| m[(free[i], free[j])]);
    (free, kf, mf)
}

pub(crate) fn dense_inverse(a: MatRef<'_, f64>) -> Mat<f64> {
    a.partial_piv_lu().inverse()
}

/// $P^TGP$ built here from its definition (Eqs. 13–14), independently of the library.
pub(crate) fn elastic_flexibility(model: &FeModel, r_set: &[usize]) -> Mat<f64> {
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
pub(crate) fn inertia_relief_flexibility_equals_the_elastic_modes_flexibility() {
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
pub(crate) fn residual_modes_are_the_residual_flexibility_orthogonal_to_the_kept_modes() {
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
pub(crate) fn a_bad_r_set_is_a_named_error() {
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
pub(crate) fn benfield_hruda_spans_free_and_fixed_interface_limits() {
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
