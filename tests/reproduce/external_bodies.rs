//! Bodies no flexmodes code made: quadratic tetrahedra meshed by gmsh, stiffness and consistent
//! mass assembled by scikit-fem: a steel link in m–kg–s, a flanged hub in mm–t–s and a slender
//! rod with a badly shaped element, with bore holes as node sets
//! (`assets/generate/make_bodies.py`). Reference values were computed by SciPy (ARPACK
//! shift-invert, LAPACK `eigh` on the reduced matrices) when the bodies were written, and are
//! read from each body's `reference.json`.

use std::path::PathBuf;

use flexmodes::{
    body_file::ImportedBody,
    linalg::max_abs,
    reduction::{
        CONSTRAINT_COUPLING_TOLERANCE, Method, ModeSelection, ReducedMatrices, ReductionParameters,
        SolverPath, reduce,
    },
};
use serde_json::Value;

#[path = "../external/checks.rs"]
pub(crate) mod checks;

const BODIES: [&str; 3] = ["steel-link", "flange-hub", "steel-rod"];

fn body(name: &str) -> (ImportedBody, Value) {
    checks::load(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/bodies")
            .join(name),
    )
}

#[test]
fn free_free_frequencies_and_zero_energy_modes_match_scipy() {
    for name in BODIES {
        let (body, reference) = body(name);
        checks::check_free_free(name, &body, &reference);
    }
}

#[test]
fn mass_properties_from_the_consistent_mass_match_scipy() {
    for name in BODIES {
        let (body, reference) = body(name);
        checks::check_mass_properties(name, &body, &reference);
    }
}

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
        let parameters = ReductionParameters {
            boundary_nodes: body.node_sets[set].clone(),
            modes: ModeSelection::Count(10),
            solver: SolverPath::Auto,
        };
        for method in [
            Method::CraigBampton,
            Method::Guyan,
            Method::ModeCondensation,
        ] {
            let basis = reduce(model, method, &parameters).unwrap();
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

#[test]
fn npy_files_read_back_exactly() {
    use flexmodes::body_file::{npy_header, read_npy, write_npy};
    let dir = std::env::temp_dir().join(format!("flexmodes-npy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (rows, cols) in [(1, 1), (3, 2), (17, 5), (1000, 3)] {
        assert_eq!(npy_header(rows, cols).len() % 64, 0);
        let a = faer::Mat::from_fn(rows, cols, |i, j| {
            (i as f64 + 0.1)
                * 10f64.powi(j as i32 * 40 - 80)
                * if (i + j) % 2 == 0 { 1.0 } else { -1.0 }
        });
        let path = dir.join(format!("a{rows}x{cols}.npy"));
        write_npy(&path, a.as_ref()).unwrap();
        let (r, c, values) = read_npy(&std::fs::read(&path).unwrap()).unwrap();
        assert_eq!((r, c, values.len()), (rows, cols, rows * cols));
        for j in 0..cols {
            for i in 0..rows {
                assert_eq!(values[j * rows + i], a[(i, j)]);
            }
        }
    }
    // A truncated file is not read as a matrix.
    let bytes = std::fs::read(dir.join("a17x5.npy")).unwrap();
    assert!(read_npy(&bytes[..bytes.len() - 8]).is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Rigid (RBE2) interfaces on bores of external bodies, against SciPy's Craig–Bampton of the
/// body transformed by hand, u_s = u_m + θ_m × (x_s − x_m)
/// (`assets/generate/rbe2_reference.py`, written to `rbe2_reference.json`): one bore and two
/// interfaces at once, in m–kg–s and mm–t–s.
#[test]
fn rigid_interfaces_match_scipys_transformed_body() {
    use flexmodes::{
        analysis::reduced_modes,
        reduction::{
            ColumnKind, InteriorProblem, RigidInterface, reduce_interior, tie_rigid_interfaces,
        },
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
            let direct_and_tied = |method: Method| {
                let mut problem = InteriorProblem::new(model, &boundary, SolverPath::Auto)
                    .unwrap()
                    .with_rigid_interfaces(&interfaces)
                    .unwrap();
                let direct =
                    reduce_interior(method, &mut problem, ModeSelection::Count(modes)).unwrap();
                let parameters = ReductionParameters {
                    boundary_nodes: boundary.clone(),
                    modes: ModeSelection::Count(modes),
                    solver: SolverPath::Auto,
                };
                let tied = tie_rigid_interfaces(
                    model,
                    reduce(model, method, &parameters).unwrap(),
                    &interfaces,
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
            };
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
        }
    }
}

#[test]
fn a_rigid_interface_needs_boundary_columns() {
    use flexmodes::{
        Error,
        error::ReductionError,
        reduction::{RigidInterface, tie_rigid_interfaces},
    };
    let (body, _) = body("steel-link");
    let model = &body.model;
    let bore = body.node_sets["bore_a"].clone();
    let interface = RigidInterface::at_centroid(model, "bore_a", &bore).unwrap();
    // The bore is not in the boundary of this basis (bore_b is).
    let basis = reduce(
        model,
        Method::CraigBampton,
        &ReductionParameters {
            boundary_nodes: body.node_sets["bore_b"].clone(),
            modes: ModeSelection::Count(4),
            solver: SolverPath::Auto,
        },
    )
    .unwrap();
    let e = tie_rigid_interfaces(model, basis, std::slice::from_ref(&interface)).unwrap_err();
    assert!(
        matches!(&e, Error::Reduction(ReductionError::InvalidDofSet { set, .. }) if set.contains("bore_a")),
        "{e}"
    );
    // The same as boundary coordinates of an interior problem: the DOF is named.
    let problem = flexmodes::reduction::InteriorProblem::new(
        model,
        &body.node_sets["bore_b"],
        SolverPath::Auto,
    )
    .unwrap();
    let e = problem.with_rigid_interfaces(&[interface]).err().unwrap();
    assert!(
        matches!(&e, Error::Reduction(ReductionError::InvalidDofSet { set, reason })
            if set.contains("bore_a") && reason.contains("not a boundary DOF")),
        "{e}"
    );
    // A node in two interfaces, and an unknown set, are named.
    let spec = ["rbe2:bore_a".to_string(), "rbe2:bore_a".to_string()];
    assert!(matches!(
        body.boundary_with_interfaces(&spec),
        Err(Error::DuplicateNode { .. })
    ));
    assert!(
        body.boundary_with_interfaces(&["rbe2:nope".to_string()])
            .is_err()
    );
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
    let parameters = ReductionParameters {
        boundary_nodes: bore.clone(),
        modes: ModeSelection::Count(modes),
        solver: SolverPath::Auto,
    };
    let cb = reduce(model, Method::CraigBampton, &parameters).unwrap();
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
    let mt = reduce(model, Method::ModalTruncation, &parameters).unwrap();
    assert!(reduce_interface(model, mt, 6).is_err());
    assert!(reduce_interface(model, cb, 3 * bore.len() + 1).is_err());
}

/// An interface declared in the body file (`[interfaces.NAME]`, kind `rbe2`, a master point)
/// is what `--boundary NAME` means. A rigid interface spans the ring's rigid motions whatever
/// the master point, so the frequencies equal those with the master at the centroid; the
/// master point itself is the file's. An `rbe3` interface and a missing node set are refused
/// with the file, the line and the reason.
#[test]
fn interfaces_declared_in_the_body_file() {
    use flexmodes::{Error, error::BodyFileError, scenes::body_modes::body_boundary};
    let source = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/steel-link");
    let dir = std::env::temp_dir().join(format!("flexmodes-interfaces-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["k.mtx.gz", "m.mtx.gz", "nodes.csv", "edges.csv"] {
        std::fs::copy(source.join(f), dir.join(f)).unwrap();
    }
    let text = std::fs::read_to_string(source.join("body.toml")).unwrap();
    let write = |extra: &str| {
        std::fs::write(dir.join("body.toml"), format!("{text}\n{extra}")).unwrap();
        ImportedBody::load(&dir.join("body.toml").display().to_string())
    };
    let body = write(
        "[interfaces.pin]\nkind = \"rbe2\"\nnode_set = \"bore_a\"\nmaster = [-0.04, 0.0, 0.01]\n",
    )
    .unwrap();
    let pin = body_boundary(&body, &["pin".into()]).unwrap();
    let (nodes, interfaces) = (pin.boundary, pin.rigid);
    assert_eq!(nodes, body.node_sets["bore_a"]);
    assert_eq!(interfaces.len(), 1);
    assert_eq!(interfaces[0].master, [-0.04, 0.0, 0.01]);
    let at_centroid = body_boundary(&body, &["rbe2:bore_a".into()]).unwrap().rigid;
    assert!(
        (at_centroid[0].master[2] - 0.01).abs() > 1e-4,
        "a different master point"
    );
    let model = &body.model;
    let parameters = ReductionParameters {
        boundary_nodes: nodes,
        modes: ModeSelection::Count(8),
        solver: SolverPath::Auto,
    };
    let cb = reduce(model, Method::CraigBampton, &parameters).unwrap();
    let hz = |i: &[flexmodes::reduction::RigidInterface]| {
        let basis = flexmodes::reduction::tie_rigid_interfaces(model, cb.clone(), i).unwrap();
        flexmodes::analysis::reduced_modes(model, &basis)
            .unwrap()
            .elastic_hz()
    };
    let (given, centroid) = (hz(&interfaces), hz(&at_centroid));
    assert_eq!(given.len(), centroid.len());
    checks::assert_relative("master point", &given, &centroid, 1e-10);

    // An averaging interface: its nodes stay out of the boundary, its weights are read.
    let count = body.node_sets["bore_a"].len();
    let weights: Vec<String> = (0..count).map(|k| format!("{}", 1 + k % 3)).collect();
    let body = write(&format!(
        "[interfaces.load]\nkind = \"rbe3\"\nnode_set = \"bore_a\"\nweights = [{}]\n",
        weights.join(", ")
    ))
    .unwrap();
    let load = body_boundary(&body, &["load".into(), "rbe2:bore_b".into()]).unwrap();
    assert_eq!(load.boundary, body.node_sets["bore_b"]);
    assert_eq!(load.averaging.len(), 1);
    assert_eq!(load.averaging[0].weights[..3], [1.0, 2.0, 3.0]);
    let e = write(&format!(
        "[interfaces.load]\nkind = \"rbe3\"\nnode_set = \"bore_a\"\nweights = [{}]\n",
        weights[1..].join(", ")
    ))
    .unwrap_err();
    assert!(
        matches!(&e, Error::BodyFile(BodyFileError::BodyFile { reason, .. }) if reason.contains("weights")),
        "{e}"
    );
    let e = write("[interfaces.pin]\nkind = \"rbe2\"\nnode_set = \"nope\"\n").unwrap_err();
    assert!(e.to_string().contains("nope"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
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

/// The committed corpus bodies (tests/corpus/, written by assets/generate/corpus.py): a FElupe
/// block pair joined by a layer 1e5 times softer (a nearly free mechanism), scikit-fem's cube
/// of uniform hexahedra (repeated frequencies), scikit-fem's carved eye-bar in mm-t-s (its mass
/// pattern exceeds its stiffness's) and a CalculiX C3D10 block whose K and M
/// CalculiX wrote (read directly and as its converted twin, against CalculiX's own frequencies).
/// `.ci/run` checks the whole corpus, 30 k+-DOF bodies included (tests/corpus.rs).
#[test]
fn committed_corpus_bodies_import_with_their_reference_frequencies() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let bodies = checks::corpus_bodies(&dir);
    assert_eq!(bodies.len(), 4, "{bodies:?}");
    for body in &bodies {
        checks::check_corpus_dir(body);
    }
}
