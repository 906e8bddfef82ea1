//! Every reduction method on bodies another FE code made (gmsh + scikit-fem P2 tetrahedra,
//! consistent mass; the link in m–kg–s, the hub in mm–t–s), against SciPy's free-free
//! frequencies written with the bodies and against what each method must satisfy whatever
//! code computes it: Rayleigh–Ritz bounds, exact zero-energy counts, the shifted static
//! response a moment-matching basis contains (checked by sparse products, no solve), and the
//! span of the modes balanced truncation balances.

use faer::{Mat, linalg::solvers::Solve};
use flexmodes::{
    Progress,
    analysis::count_zero_energy_modes,
    models::{BodyInterfaces, BodyReducer},
    reduction::{
        InterfaceLoads, Method, ModalBalancedParameters, MomentMatchingParameters, ReductionError,
        lowest_free_modes, modal_balanced_basis, moment_matching,
    },
};

use super::external_bodies::checks::{
    self, committed_body as body, first_rbe2_interface as rbe2_interfaces,
};

/// A free body's moment-matching basis about a real s0 > 0, led by its rigid-body modes,
/// contains the exact response to the interface loads, $x = (K + s_0^2 M)^{-1} B$: the Galerkin
/// solution in the basis satisfies the full equations, checked by sparse products alone.
#[test]
fn moment_matching_on_a_free_body_contains_the_shifted_static_response() {
    for name in ["steel-link", "flange-hub"] {
        let (body, reference) = body(name);
        let model = &body.model;
        let interfaces = rbe2_interfaces(&body, &reference);
        let loads = InterfaceLoads::of(model, &[], &interfaces.rigid, &[]).unwrap();
        assert_eq!(loads.count(), 6);
        let free = lowest_free_modes(model, 1).unwrap();
        let rigid = free.vectors.subcols(0, 6).to_owned();
        let s0 = free.values[6].sqrt();
        let labels = (1..=6).map(|k| format!("rigid {k}")).collect();
        let mm = moment_matching(
            model,
            &MomentMatchingParameters {
                blocks: 2,
                s0,
                loads: Some((loads.matrix.clone(), loads.labels.clone())),
                leading: Some((rigid, labels)),
                ..Default::default()
            },
        )
        .unwrap();
        assert!(mm.deflated.is_empty(), "{name}: {:?}", mm.deflated);
        let psi = &mm.basis.psi;
        assert_eq!(psi.ncols(), 18, "{name}: 6 rigid + 2 blocks of 6");
        // A = K + s0² M applied by sparse products.
        let apply = |x: &Mat<f64>| {
            let kx = model.k.mul(x.as_ref());
            let mx = model.m.mul(x.as_ref());
            Mat::from_fn(x.nrows(), x.ncols(), |i, j| {
                kx[(i, j)] + s0 * s0 * mx[(i, j)]
            })
        };
        let a_psi = apply(psi);
        let a_r = psi.transpose() * &a_psi;
        let b_r = psi.transpose() * &loads.matrix;
        let y = a_r.as_ref().partial_piv_lu().solve(b_r.as_ref());
        let x = psi * &y;
        let residual = &apply(&x) - &loads.matrix;
        for c in 0..6 {
            let r = (0..residual.nrows())
                .map(|i| residual[(i, c)].powi(2))
                .sum::<f64>()
                .sqrt();
            let b = (0..residual.nrows())
                .map(|i| loads.matrix[(i, c)].powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(r <= 1e-7 * b, "{name} load {c}: ‖Ax − b‖/‖b‖ = {:e}", r / b);
        }
    }
}

/// Balanced truncation built on N free-free modes and keeping all N vectors spans those modes:
/// its reduced frequencies are SciPy's lowest N (and its vectors are Euclidean-orthonormal,
/// as a symmetric gramian's eigenvectors are); keeping fewer, the gramian values descend.
#[test]
fn balanced_truncation_on_a_body_spans_the_modes_it_balances() {
    let (body, reference) = body("flange-hub");
    let model = &body.model;
    let interfaces = rbe2_interfaces(&body, &reference);
    let loads = InterfaceLoads::of(model, &[], &interfaces.rigid, &[]).unwrap();
    let free = lowest_free_modes(model, 12).unwrap();
    let elastic = flexmodes::linalg::GeneralizedEigen {
        values: free.values[6..].to_vec(),
        vectors: free.vectors.subcols(6, 12).to_owned(),
        residuals: free.residuals[6..].to_vec(),
        zero_energy: 0,
        sturm: None,
    };
    let omega1 = elastic.values[0].sqrt();
    let parameters = |vectors| ModalBalancedParameters {
        vectors,
        alpha: 0.02 / omega1,
    };
    let all = modal_balanced_basis(
        free.vectors.subcols(0, 6),
        &elastic,
        &loads,
        &parameters(12),
    )
    .unwrap();
    let eig = flexmodes::analysis::reduced_modes(model, &all).unwrap();
    let expected = checks::floats(&reference["free_free_hz"]);
    checks::assert_relative("BT(12 of 12) hub", &eig.hz()[6..], &expected[6..18], 1e-7);
    // Euclidean-orthogonal (a symmetric gramian's eigenvectors), each scaled to unit M-norm.
    let bt = all.psi.subcols(6, 12);
    let gram = bt.transpose() * bt;
    for i in 0..12 {
        for j in 0..12 {
            let cosine = gram[(i, j)] / (gram[(i, i)] * gram[(j, j)]).sqrt();
            let e = if i == j { 1.0 } else { 0.0 };
            assert!((cosine - e).abs() < 1e-10, "cos(v{i}, v{j}) = {cosine}");
        }
    }
    let mass = all.reduced_mass(model);
    for i in 6..18 {
        assert!(
            (mass[(i, i)] - 1.0).abs() < 1e-10,
            "M-norm² of v{i}: {}",
            mass[(i, i)]
        );
    }
    let four =
        modal_balanced_basis(free.vectors.subcols(0, 6), &elastic, &loads, &parameters(4)).unwrap();
    let values: Vec<f64> = four
        .columns
        .iter()
        .filter_map(|c| match c.kind {
            flexmodes::reduction::ColumnKind::Balanced { value } => Some(value),
            _ => None,
        })
        .collect();
    assert_eq!(values.len(), 4);
    assert!(
        values.windows(2).all(|w| w[0] >= w[1] && w[1] > 0.0),
        "{values:?}"
    );
}

/// An averaging (RBE3) master reads the weighted least-squares rigid motion of its ring:
/// exactly a rigid motion of the ring about the master, and for any field the fit an
/// independent solve (nalgebra's SVD of the weighted rigid-motion matrix) gives.
#[test]
fn an_averaging_interface_reads_the_weighted_rigid_fit_of_its_ring() {
    use flexmodes::reduction::AveragingInterface;
    let (body, _) = body("steel-link");
    let model = &body.model;
    let nodes = body.node_sets["bore_a"].clone();
    let weights: Vec<f64> = (0..nodes.len()).map(|k| 1.0 + (k % 3) as f64).collect();
    let rbe3 =
        AveragingInterface::at_centroid(model, "bore_a", &nodes, Some(weights.clone())).unwrap();
    let a = rbe3.averaging_matrix(model).unwrap();
    // The ring's rigid-motion matrix, written out here from the node positions.
    let dofs = model.dofs_of_nodes(&nodes).unwrap();
    let r = nalgebra::DMatrix::<f64>::from_fn(dofs.len(), 6, |row, q| {
        let node = model.node_index(nodes[row / 3]).unwrap();
        let x = model.position(node);
        let d = [
            x[0] - rbe3.master[0],
            x[1] - rbe3.master[1],
            x[2] - rbe3.master[2],
        ];
        let axis = row % 3;
        if q < 3 {
            if q == axis { 1.0 } else { 0.0 }
        } else {
            // (e_{q-3} × d)_axis
            let w = q - 3;
            let e = |i: usize| if i == w { 1.0 } else { 0.0 };
            let cross = [
                e(1) * d[2] - e(2) * d[1],
                e(2) * d[0] - e(0) * d[2],
                e(0) * d[1] - e(1) * d[0],
            ];
            cross[axis]
        }
    });
    let a_ring = nalgebra::DMatrix::<f64>::from_fn(6, dofs.len(), |q, c| a[(q, dofs[c])]);
    let ar = &a_ring * &r;
    for i in 0..6 {
        for j in 0..6 {
            let e = if i == j { 1.0 } else { 0.0 };
            assert!(
                (ar[(i, j)] - e).abs() < 1e-9,
                "AR [{i},{j}] = {}",
                ar[(i, j)]
            );
        }
    }
    // A pseudo-random field on the ring against the weighted least-squares fit.
    let mut rng = super::common::Rng::new(7);
    let u = nalgebra::DVector::<f64>::from_fn(dofs.len(), |_, _| rng.unit() - 0.5);
    let sqrt_w = nalgebra::DVector::<f64>::from_fn(dofs.len(), |row, _| weights[row / 3].sqrt());
    let rw = nalgebra::DMatrix::<f64>::from_fn(dofs.len(), 6, |i, j| sqrt_w[i] * r[(i, j)]);
    let uw = u.component_mul(&sqrt_w);
    let fit = rw.svd(true, true).solve(&uw, 1e-14).unwrap();
    let read = &a_ring * &u;
    for q in 0..6 {
        assert!(
            (read[q] - fit[q]).abs() <= 1e-9 * fit.amax(),
            "master DOF {q}: {} against the fit {}",
            read[q],
            fit[q]
        );
    }
}

/// An averaging interface adds no stiffness: moment matching loaded through it converges to
/// the free body's frequencies (SciPy's, 1e-8 with six blocks), while the same ring tied
/// rigidly (RBE2) keeps Craig–Bampton above them whatever the kept modes. A fixed-interface
/// method on an averaging interface is refused by name.
#[test]
fn an_averaging_interface_adds_no_stiffness() {
    use flexmodes::{error::CoreError as Error, reduction::AveragingInterface};
    let (body, reference) = body("steel-link");
    let model = &body.model;
    let scipy = checks::floats(&reference["free_free_hz"]);
    let nodes = body.node_sets["bore_a"].clone();
    let full = count_zero_energy_modes(model, 10).unwrap();
    let averaging = BodyInterfaces {
        boundary: Vec::new(),
        rigid: Vec::new(),
        averaging: vec![AveragingInterface::at_centroid(model, "bore_a", &nodes, None).unwrap()],
        interface_modes: None,
    };
    let mut reducer = BodyReducer::new(model, averaging, &full, 0.0, Progress::default()).unwrap();
    let mm = reducer.reduce(Method::MomentMatching, 36).unwrap();
    assert_eq!(mm.zero_modes, 6);
    assert_eq!(mm.basis.size(), 6 + 36);
    checks::assert_relative(
        "MM through rbe3",
        &mm.elastic_hz()[..6],
        &scipy[6..12],
        1e-8,
    );
    for m in [Method::CraigBampton, Method::Guyan, Method::MacNealRubin] {
        match reducer.reduce(m, 10) {
            Err(Error::Reduction(ReductionError::MethodNeedsContext { needs, .. })) => {
                assert!(needs.contains("rbe3"), "{needs}")
            }
            other => panic!(
                "{m:?} on an rbe3 interface: {:?}",
                other.map(|r| r.basis.size())
            ),
        }
    }
    let tied = rbe2_interfaces(&body, &reference);
    let mut reducer = BodyReducer::new(model, tied, &full, 0.0, Progress::default()).unwrap();
    let cb = reducer.reduce(Method::CraigBampton, 36).unwrap();
    let first = cb.elastic_hz()[0];
    assert!(
        first > scipy[6] * (1.0 + 1e-3),
        "the tied ring stiffens: {first} against the free {}",
        scipy[6]
    );
}

/// Gregory's influence from the hub's bore (tied, six master loads): the hub is nearly
/// axisymmetric, so each pair of its repeated bending modes (8440/8441 Hz, 8905/8915 Hz) carries
/// nearly the same influence, and the two lowest modes (4739 and 4912 Hz, which a rigid bore
/// wrench barely excites) carry under 1e-3 of the largest: the modes moment matching and
/// balanced truncation leave out on this interface.
#[test]
fn interface_influence_sees_the_hubs_symmetry() {
    let (body, reference) = body("flange-hub");
    let model = &body.model;
    let full = count_zero_energy_modes(model, 10).unwrap();
    let mut reducer = BodyReducer::new(
        model,
        rbe2_interfaces(&body, &reference),
        &full,
        0.0,
        Progress::default(),
    )
    .unwrap();
    let (hz, influence) = reducer.interface_influence(12, 0.01).unwrap();
    assert_eq!(hz.len(), 12);
    let scipy = checks::floats(&reference["free_free_hz"]);
    checks::assert_relative("influence modes", &hz, &scipy[6..18], 1e-7);
    let s = &influence.sigma;
    let top = s.iter().copied().fold(0.0, f64::max);
    for (a, b) in [(3, 4), (5, 6)] {
        let ratio = s[a] / s[b];
        assert!(
            (0.8..1.25).contains(&ratio),
            "modes {} and {}: {} vs {}",
            a + 1,
            b + 1,
            s[a],
            s[b]
        );
    }
    assert!(s[0] < 1e-3 * top && s[1] < 1e-3 * top, "{s:?}");
    assert_eq!(influence.ranking()[0], 5, "the 8905 Hz mode carries most");
}

/// The full body's interface response, $L^T(K - \omega^2M)^{-1}L$ by a sparse $LDL^T$ per
/// frequency (refined and checked), against moment matching's with six Krylov blocks about
/// the lowest elastic ω (a sparse Cholesky of $K + s_0^2M$ and a dense reduced solve): two
/// computations that share no factor agree to 1e-6 over the band, off resonance; Benfield–
/// Hruda's free modes alone miss the residual flexibility and are off by more than 1e-3.
#[test]
fn the_full_interface_response_matches_moment_matching() {
    use flexmodes::analysis::{
        full_dynamic_compliance, off_resonance_frequencies, reduced_dynamic_compliance,
    };
    let (body, reference) = body("steel-link");
    let model = &body.model;
    let full = count_zero_energy_modes(model, 10).unwrap();
    let mut reducer = BodyReducer::new(
        model,
        rbe2_interfaces(&body, &reference),
        &full,
        0.0,
        Progress::default(),
    )
    .unwrap();
    let loads = reducer.loads().unwrap();
    let hz = off_resonance_frequencies(16_000.0, 12, &full.elastic_hz());
    assert!(hz.len() >= 10, "{hz:?}");
    let h =
        full_dynamic_compliance(model, loads.matrix.as_ref(), &hz, &Progress::default()).unwrap();
    let mut error = |m: Method, k: usize| {
        let reduced = reducer.reduce(m, k).unwrap();
        reduced_dynamic_compliance(model, &reduced.basis, loads.matrix.as_ref(), &hz)
            .unwrap()
            .relative_magnitude_error(&h)
            .unwrap()
    };
    let mm = error(Method::MomentMatching, 36);
    assert!(mm < 1e-6, "MM against the sparse LDLᵀ response: {mm:e}");
    let bh = error(Method::BenfieldHruda, 12);
    assert!(bh > 1e-3, "free modes alone: {bh:e}");
}
