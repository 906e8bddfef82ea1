//! The slow half of the external-body tests (see `tests/reproduce/external_bodies.rs`): every
//! reduction method against SciPy/LAPACK on the committed bodies from gmsh + scikit-fem, rigid
//! interfaces against SciPy's transformed body and against tying every ring DOF afterwards.

use std::path::PathBuf;

use flexmodes::{
    linalg::max_abs,
    reduction::{
        CONSTRAINT_COUPLING_TOLERANCE, Method, ModeSelection, ReducedMatrices, ReductionRequest,
        SolverPath, reduce,
    },
};
use serde_json::Value;

use super::checks;

const BODIES: [&str; 3] = ["steel-link", "flange-hub", "steel-rod"];

use super::checks::committed_body as body;

#[test]
fn reduced_frequencies_match_lapack_on_scipys_reduction() {
    for name in BODIES {
        let (body, reference) = body(name);
        checks::check_reductions(name, &body, &reference);
    }
}

#[test]
fn craig_bampton_reduced_matrices_from_their_pieces_equal_the_full_products() {
    let (body, _) = body("steel-link");
    let model = &body.model;
    for set in ["bore_a", "bore_b"] {
        let parameters = ReductionRequest {
            boundary_nodes: body.node_sets[set].clone(),
            modes: ModeSelection::Count(10),
            solver: SolverPath::Auto,
            ..Default::default()
        };
        for method in [
            Method::CraigBampton,
            Method::Guyan,
            Method::ModeCondensation,
        ] {
            let basis = reduce(model, &parameters.with_method(method)).unwrap();
            let pieces = ReducedMatrices::of(model, &basis);
            // MC's boundary columns are not static constraint modes: the general products.
            assert_eq!(pieces.structured, method != Method::ModeCondensation);
            assert!(pieces.constraint_coupling <= CONSTRAINT_COUPLING_TOLERANCE);
            for (name, a, b) in [
                ("K_r", &pieces.k, basis.reduced_stiffness(model)),
                ("M_r", &pieces.m, basis.reduced_mass(model)),
            ] {
                assert_eq!((a.nrows(), a.ncols()), (b.nrows(), b.ncols()));
                let top = max_abs(b.as_ref());
                let diff = max_abs((a - &b).as_ref());
                assert!(
                    diff <= 1e-9 * top,
                    "{set} {method:?} {name}: {diff:.1e} of {top:.1e}"
                );
            }
        }
    }
}

/// Rigid (RBE2) interfaces on bores of external bodies, against SciPy's Craig–Bampton of the
/// body transformed by hand, u_s = u_m + θ_m × (x_s − x_m)
/// (`assets/generate/rbe2_reference.py`, written to `rbe2_reference.json`): one bore and two
/// interfaces at once, in m–kg–s and mm–t–s.
#[test]
fn rigid_interfaces_match_scipys_transformed_body() {
    use flexmodes::{
        analysis::reduced_modes,
        reduction::{ColumnKind, RigidInterface},
    };
    for name in ["steel-link", "flange-hub"] {
        let (body, _) = body(name);
        let model = &body.model;
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/bodies")
            .join(name)
            .join("rbe2_reference.json");
        let reference: Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        for case in reference["cases"].as_array().unwrap() {
            let names: Vec<String> = case["interfaces"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_str().unwrap().to_string())
                .collect();
            let modes = case["modes"].as_u64().unwrap() as usize;
            let what = format!("{name} rbe2:{}", names.join(",rbe2:"));
            let spec: Vec<String> = names.iter().map(|n| format!("rbe2:{n}")).collect();
            let (boundary, sets) = body.boundary_with_interfaces(&spec).unwrap();
            let interfaces: Vec<RigidInterface> = sets
                .iter()
                .map(|set| RigidInterface::at_centroid(model, &set.name, &set.nodes).unwrap())
                .collect();
            // The master points are the sets' centroids, as SciPy placed them.
            let masters = case["master_points"].as_array().unwrap();
            assert_eq!(masters.len(), interfaces.len());
            for (i, m) in interfaces.iter().zip(masters) {
                assert_eq!(checks::floats(m).len(), 3);
                for (a, b) in i.master.iter().zip(checks::floats(m)) {
                    assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{what}");
                }
            }
            // The product's route (the masters are the boundary coordinates, six right-hand
            // sides per interface) gives the basis of every ring DOF's constraint mode tied
            // afterwards: same labels, same Ψ. Checked for every fixed-interface method; CB and
            // Guyan then against SciPy.
            let direct_and_tied =
                |method| direct_and_tied(model, (&boundary, &interfaces), (method, modes), &what);
            for method in [Method::ModalTruncation, Method::ModeCondensation] {
                let direct = direct_and_tied(method);
                assert_eq!(
                    direct.size(),
                    6 * interfaces.len() + modes,
                    "{what} {method}"
                );
            }
            for (method, key) in [(Method::CraigBampton, "cb_hz"), (Method::Guyan, "guyan_hz")] {
                let basis = direct_and_tied(method);
                let masters = basis.columns_of(|k| matches!(k, ColumnKind::RigidInterface { .. }));
                assert_eq!(masters.len(), 6 * interfaces.len(), "{what}");
                let expected_size = 6 * interfaces.len()
                    + if method == Method::CraigBampton {
                        modes
                    } else {
                        0
                    };
                assert_eq!(basis.size(), expected_size, "{what}");
                // Zero energy judged against the body's own scale, as `export` does (Guyan on
                // one rigid interface is a rigid body: six zero-energy modes and nothing else).
                let eig = reduced_modes(model, &basis).unwrap();
                let threshold = flexmodes::analysis::zero_energy_threshold_hz(model);
                let all = eig.hz();
                let zero = flexmodes::analysis::zero_energy_below(&all, threshold);
                assert_eq!(zero, 6, "{what} {method}: zero-energy modes");
                let expected = checks::floats(&case[key]);
                let hz = &all[zero..];
                assert_eq!(hz.len(), expected.len() - 6, "{what} {method}");
                let count = hz.len().min(20);
                checks::assert_relative(
                    &format!("{what} {method}"),
                    &hz[..count],
                    &expected[6..6 + count],
                    1e-8,
                );
                // The ring moves rigidly: on every tied node each master column is the rigid
                // motion of its DOF about the master point, to round-off.
                ring_moves_rigidly(model, &basis, (&interfaces, &masters), &what);
            }
        }
    }
}

/// On every tied node of each interface, each of its six master columns of `basis` (`masters`,
/// the columns' indices) is the rigid motion of the node's DOF about the master point.
fn ring_moves_rigidly(
    model: &flexmodes::fem::FeModel,
    basis: &flexmodes::reduction::Basis,
    (interfaces, masters): (&[flexmodes::reduction::RigidInterface], &[usize]),
    what: &str,
) {
    for (k, interface) in interfaces.iter().enumerate() {
        let cols = &masters[6 * k..6 * k + 6];
        for (q, &c) in cols.iter().enumerate() {
            let (mut t, mut w) = ([0.0; 3], [0.0; 3]);
            if q < 3 {
                t[q] = 1.0
            } else {
                w[q - 3] = 1.0
            }
            for &node in &interface.nodes {
                let x = model.position(model.node_index(node).unwrap());
                let r: [f64; 3] = std::array::from_fn(|d| x[d] - interface.master[d]);
                let dofs = model.dofs_of_nodes(&[node]).unwrap();
                let expected: [f64; 3] = std::array::from_fn(|a| {
                    t[a] + [
                        w[1] * r[2] - w[2] * r[1],
                        w[2] * r[0] - w[0] * r[2],
                        w[0] * r[1] - w[1] * r[0],
                    ][a]
                });
                for a in 0..3 {
                    let got = basis.psi[(dofs[a], c)];
                    assert!(
                        (got - expected[a]).abs() <= 1e-12,
                        "{what}: node {node} column {q}: {got} vs {}",
                        expected[a]
                    );
                }
            }
        }
    }
}

/// The basis of `method` with its rigid interfaces made by the product's route (the masters
/// as boundary coordinates) and the same basis tied afterwards: same labels, same Ψ.
fn direct_and_tied(
    model: &flexmodes::fem::FeModel,
    (boundary, interfaces): (&[usize], &[flexmodes::reduction::RigidInterface]),
    (method, modes): (Method, usize),
    what: &str,
) -> flexmodes::reduction::Basis {
    use flexmodes::reduction::{InteriorProblem, reduce_interior, tie_rigid_interfaces};
    let mut problem = InteriorProblem::new(model, boundary, SolverPath::Auto)
        .unwrap()
        .with_rigid_interfaces(interfaces)
        .unwrap();
    let direct = reduce_interior(
        &mut problem,
        &ReductionRequest::of(method).modes(ModeSelection::Count(modes)),
    )
    .unwrap();
    let parameters = ReductionRequest {
        boundary_nodes: boundary.to_vec(),
        modes: ModeSelection::Count(modes),
        solver: SolverPath::Auto,
        ..Default::default()
    };
    let tied = tie_rigid_interfaces(
        model,
        reduce(model, &parameters.with_method(method)).unwrap(),
        interfaces,
    )
    .unwrap();
    let labels = |b: &flexmodes::reduction::Basis| -> Vec<String> {
        b.columns.iter().map(|c| c.label.clone()).collect()
    };
    assert_eq!(labels(&direct), labels(&tied), "{what} {method}");
    let scale = flexmodes::linalg::max_abs(tied.psi.as_ref());
    let gap = flexmodes::linalg::max_abs_diff(direct.psi.as_ref(), tied.psi.as_ref());
    assert!(
        gap <= 1e-10 * scale,
        "{what} {method}: Ψ differs by {gap:e}"
    );
    direct
}

/// Characteristic constraint modes (Castanier–Tan–Pierre) on the link's bore against SciPy's
/// (`rbe2_reference.py --ccm`, written to `ccm_reference.json`): CB with the bore's 660
/// boundary DOF reduced to n_c shapes, for several n_c; six shapes span the bore's rigid
/// motions, so they give what a rigid interface gives; the frequencies fall towards plain
/// CB's as n_c grows.
#[test]
fn characteristic_constraint_modes_match_scipy() {
    use flexmodes::{
        analysis::reduced_modes,
        reduction::{RigidInterface, reduce_interface, tie_rigid_interfaces},
    };
    let (body, _) = body("steel-link");
    let model = &body.model;
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/bodies/steel-link/ccm_reference.json");
    let reference: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let set = reference["interface"].as_str().unwrap();
    let bore = body.node_sets[set].clone();
    let cases = reference["cases"].as_array().unwrap();
    let modes = cases[0]["modes"].as_u64().unwrap() as usize;
    let parameters = ReductionRequest {
        boundary_nodes: bore.clone(),
        modes: ModeSelection::Count(modes),
        solver: SolverPath::Auto,
        ..Default::default()
    };
    let cb = reduce(model, &parameters.with_method(Method::CraigBampton)).unwrap();
    assert_eq!(
        3 * bore.len(),
        reference["boundary_dofs"].as_u64().unwrap() as usize
    );
    let plain = reduced_modes(model, &cb).unwrap().elastic_hz();
    let mut previous: Option<Vec<f64>> = None;
    for case in cases {
        let nc = case["interface_modes"].as_u64().unwrap() as usize;
        let reduced = reduce_interface(model, cb.clone(), nc).unwrap();
        assert_eq!(reduced.size(), nc + modes);
        let eig = reduced_modes(model, &reduced).unwrap();
        assert_eq!(eig.zero_energy, 6, "n_c {nc}");
        let hz = eig.elastic_hz();
        let expected = checks::floats(&case["hz"]);
        assert_eq!(hz.len(), expected.len() - 6, "n_c {nc}");
        let count = hz.len().min(20);
        checks::assert_relative(
            &format!("CCM n_c {nc}"),
            &hz[..count],
            &expected[6..6 + count],
            1e-8,
        );
        // Rayleigh–Ritz on nested spaces: more shapes, lower frequencies, never below plain CB.
        assert!(plain.len() >= 6);
        for k in 0..6 {
            assert!(hz[k] >= plain[k] * (1.0 - 1e-10), "n_c {nc} mode {k}");
            if let Some(p) = &previous {
                assert!(hz[k] <= p[k] * (1.0 + 1e-10), "n_c {nc} mode {k}");
            }
        }
        previous = Some(hz.to_vec());
        if nc == 6 {
            let rigid = RigidInterface::at_centroid(model, set, &bore).unwrap();
            let tied = tie_rigid_interfaces(model, cb.clone(), &[rigid]).unwrap();
            let rbe2 = reduced_modes(model, &tied).unwrap().elastic_hz();
            assert_eq!(rbe2.len(), hz.len());
            checks::assert_relative("CCM 6 = RBE2", &hz[..count], &rbe2[..count], 1e-8);
        }
    }
    // A basis without constraint modes, and more shapes than boundary DOF, are named errors.
    let mt = reduce(model, &parameters.with_method(Method::ModalTruncation)).unwrap();
    assert!(reduce_interface(model, mt, 6).is_err());
    assert!(reduce_interface(model, cb, 3 * bore.len() + 1).is_err());
}

/// MacNeal–Rubin on a body another code made, with the r-set chosen by
/// `models::three_two_one_support`: free-interface modes (6 rigid + 10 elastic) and one
/// residual-flexibility mode per interface DOF; its reduced model contains the kept free-free
/// modes, so its lowest elastic frequencies equal SciPy's full-body ones.
#[test]
fn macneal_rubin_on_external_bodies_keeps_the_free_free_frequencies() {
    use flexmodes::{
        analysis::reduced_modes,
        models::three_two_one_support,
        reduction::{MacNealRubinParameters, macneal_rubin},
    };
    for name in ["steel-link", "flange-hub"] {
        let (body, reference) = body(name);
        let model = &body.model;
        let set = reference["cases"][0]["boundary"].as_str().unwrap();
        let interface = body.node_sets[set].clone();
        let r_set = three_two_one_support(model, &interface).unwrap();
        assert_eq!(r_set.len(), 6, "{name}");
        let mr = macneal_rubin(
            model,
            &MacNealRubinParameters {
                interface: model.dofs_of_nodes(&interface).unwrap(),
                r_set,
                modes: ModeSelection::Count(10),
                held: Vec::new(),
            },
        )
        .unwrap();
        assert_eq!(mr.size(), 16 + 3 * interface.len(), "{name}");
        let eig = reduced_modes(model, &mr).unwrap();
        let threshold = flexmodes::analysis::zero_energy_threshold_hz(model);
        let all = eig.hz();
        let zero = flexmodes::analysis::zero_energy_below(&all, threshold);
        assert_eq!(zero, 6, "{name}");
        let expected = checks::floats(&reference["free_free_hz"]);
        // The reference holds 6 zero-energy and 12 elastic free-free frequencies.
        assert_eq!(expected.len(), 18, "{name}");
        checks::assert_relative(
            &format!("{name} MR"),
            &all[zero..zero + 10],
            &expected[6..16],
            1e-7,
        );
    }
}
