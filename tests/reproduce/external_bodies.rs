//! Bodies no flexmodes code made: quadratic tetrahedra meshed by gmsh, stiffness and consistent
//! mass assembled by scikit-fem: a steel link in m–kg–s, a flanged hub in mm–t–s and a slender
//! rod with a badly shaped element, with bore holes as node sets
//! (`assets/generate/make_bodies.py`). Reference values were computed by SciPy (ARPACK
//! shift-invert, LAPACK `eigh` on the reduced matrices) when the bodies were written, and are
//! read from each body's `reference.json`.

use std::path::PathBuf;

use flexmodes::{
    body_file::ImportedBody,
    reduction::{Method, ModeSelection, ReductionRequest, SolverPath, reduce},
};

#[path = "../external/checks.rs"]
#[allow(dead_code)]
pub(crate) mod checks;

const BODIES: [&str; 3] = ["steel-link", "flange-hub", "steel-rod"];

use checks::committed_body as body;

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
fn npy_files_read_back_exactly() {
    use flexmodes::body_file::{npy_header, read_npy, write_npy};
    let dir = crate::scratch::Scratch::new("npy");
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

#[test]
fn a_rigid_interface_needs_boundary_columns() {
    use flexmodes::{
        error::CoreError as Error,
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
        &ReductionRequest {
            method: Method::CraigBampton,
            boundary_nodes: body.node_sets["bore_b"].clone(),
            modes: ModeSelection::Count(4),
            solver: SolverPath::Auto,
            ..Default::default()
        },
    )
    .unwrap();
    let e = tie_rigid_interfaces(model, basis, std::slice::from_ref(&interface)).unwrap_err();
    assert!(
        matches!(&e, Error::Reduction(ReductionError::InvalidDofSet {
            set: flexmodes::error::DofSetName::Interface { kind: "rbe2", name },
            ..
        }) if name == "bore_a"),
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
        matches!(&e, Error::Reduction(ReductionError::InvalidDofSet {
                set: flexmodes::error::DofSetName::Interface { kind: "rbe2", name },
                problem: flexmodes::error::DofSetProblem::NotBoundary { .. },
            }) if name == "bore_a"),
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

/// An interface declared in the body file (`[interfaces.NAME]`, kind `rbe2`, a master point)
/// is what `--boundary NAME` means. A rigid interface spans the ring's rigid motions whatever
/// the master point, so the frequencies equal those with the master at the centroid; the
/// master point itself is the file's. An `rbe3` interface and a missing node set are refused
/// with the file, the line and the reason.
#[test]
fn interfaces_declared_in_the_body_file() {
    use flexmodes::{
        error::CoreError as Error,
        error::{BodyFileError, BodySpecProblem},
        models::BodyInterfaces,
    };
    let source = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/steel-link");
    let dir = crate::scratch::Scratch::new("interfaces");
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
    let pin = BodyInterfaces::of(&body, &["pin".into()], None).unwrap();
    let (nodes, interfaces) = (pin.boundary, pin.rigid);
    assert_eq!(nodes, body.node_sets["bore_a"]);
    assert_eq!(interfaces.len(), 1);
    assert_eq!(interfaces[0].master, [-0.04, 0.0, 0.01]);
    let at_centroid = BodyInterfaces::of(&body, &["rbe2:bore_a".into()], None)
        .unwrap()
        .rigid;
    assert!(
        (at_centroid[0].master[2] - 0.01).abs() > 1e-4,
        "a different master point"
    );
    let model = &body.model;
    let parameters = ReductionRequest {
        boundary_nodes: nodes,
        modes: ModeSelection::Count(8),
        solver: SolverPath::Auto,
        ..Default::default()
    };
    let cb = reduce(model, &parameters.with_method(Method::CraigBampton)).unwrap();
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
    let load = BodyInterfaces::of(&body, &["load".into(), "rbe2:bore_b".into()], None).unwrap();
    assert_eq!(load.boundary, body.node_sets["bore_b"]);
    assert_eq!(load.averaging.len(), 1);
    assert_eq!(load.averaging[0].weights[..3], [1.0, 2.0, 3.0]);
    let e = write(&format!(
        "[interfaces.load]\nkind = \"rbe3\"\nnode_set = \"bore_a\"\nweights = [{}]\n",
        weights[1..].join(", ")
    ))
    .unwrap_err();
    // One weight short of the set's nodes: the count of each, named.
    assert!(
        matches!(
            &e,
            Error::BodyFile(BodyFileError::BodyFile {
                problem: BodySpecProblem::Weights { given, nodes, .. },
                ..
            }) if *given + 1 == *nodes
        ),
        "{e}"
    );
    let e = write("[interfaces.pin]\nkind = \"rbe2\"\nnode_set = \"nope\"\n").unwrap_err();
    assert!(e.to_string().contains("nope"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
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
