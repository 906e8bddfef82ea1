//! Bodies written back and read again: the export round trip, units and interfaces kept, a
//! body from matrices against its body file.

use flexmodes::body_file::BodyFileError;
use std::path::PathBuf;

use faer::Mat;
use flexmodes::{
    analysis::{count_zero_energy_modes, reduced_modes},
    body_file::{ImportedBody, read_matrix_market, write_files},
    error::CoreError as Error,
    fem::{RigidMotions, SlabParameters},
    linalg::generalized_eigen,
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
};

use super::body_file::scratch;

#[test]
fn export_round_trip_gives_the_same_frequencies() {
    let body = ImportedBody::load("builtin:l-bracket").unwrap();
    let scratch_dir = scratch("export");
    let dir = scratch_dir.join("cb");
    let boundary = body.boundary(&["bolt_hole".into()]).unwrap();
    let summary = flexmodes::export::export(
        &body,
        Method::CraigBampton,
        &boundary,
        8,
        &dir,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(summary.shape, [1314, 24 * 3 + 8]);
    assert_eq!(summary.zero_energy, 6);
    assert_eq!(summary.residuals.len(), summary.hz.len());
    assert!(summary.residuals.iter().all(|&r| r < 1e-8));
    let read = |f: &str| {
        let mm = read_matrix_market(&dir.join(f)).unwrap();
        let mut a = Mat::<f64>::zeros(mm.rows, mm.cols);
        for (i, j, v) in mm.expanded() {
            a[(i, j)] = v;
        }
        a
    };
    let (k, m) = (read("k_r.mtx"), read("m_r.mtx"));
    let (rows, cols, values) =
        flexmodes::body_file::read_npy(&std::fs::read(dir.join("psi.npy")).unwrap()).unwrap();
    assert_eq!(values.len(), rows * cols);
    let psi = Mat::from_fn(rows, cols, |i, j| values[j * rows + i]);
    // In memory, independently of the files.
    let basis = reduce(
        &body.model,
        &ReductionRequest {
            method: Method::CraigBampton,
            boundary_nodes: boundary,
            modes: ModeSelection::Count(8),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(
        (psi.nrows(), psi.ncols()),
        (basis.psi.nrows(), basis.psi.ncols())
    );
    for j in 0..psi.ncols() {
        for i in 0..psi.nrows() {
            assert_eq!(psi[(i, j)], basis.psi[(i, j)], "Ψ is written exactly");
        }
    }
    let from_files = generalized_eigen(k.as_ref(), m.as_ref(), "re-imported")
        .unwrap()
        .hz();
    let in_memory = reduced_modes(&body.model, &basis).unwrap().hz();
    assert_eq!(from_files.len(), in_memory.len());
    for (a, b) in from_files.iter().zip(&in_memory).skip(6) {
        assert!((a - b).abs() <= 1e-12 * b, "{a} vs {b}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("model.json")).unwrap()).unwrap();
    let hz = json["reduced_elastic_hz"].as_array().unwrap();
    assert_eq!(hz.len(), from_files.len() - 6);
    assert!((hz[0].as_f64().unwrap() - from_files[6]).abs() < 1e-6 * from_files[6]);
    assert_eq!(json["columns"].as_array().unwrap().len(), 80);
    // The rigid-body mass matrix: total mass on the translations, M symmetric positive.
    let mass = json["inertia"]["mass"].as_f64().unwrap();
    assert!((mass - body.model.total_mass()).abs() < 1e-12 * mass);
    // A second export replaces the folder as a whole; no temporary folder is left.
    let base_end = body.boundary(&["base_end".into()]).unwrap();
    let text = flexmodes::export::ExportParameters {
        psi_format: flexmodes::export::PsiFormat::MatrixMarket,
        ..Default::default()
    };
    flexmodes::export::export(&body, Method::Guyan, &base_end, 0, &dir, &text).unwrap();
    // Ψ as Matrix Market text when asked, the same numbers.
    let guyan_psi = read("psi.mtx");
    assert_eq!(guyan_psi.ncols(), base_end.len() * 3);
    assert!(!dir.join("psi.npy").exists());
    let leftovers: Vec<_> = std::fs::read_dir(dir.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(leftovers, vec!["cb".to_string()]);
}

#[test]
fn the_app_b_bricks_and_the_plank_set_up_are_read_from_the_assets() {
    let printed = crate::common::asset_rows("thesis/slab-bricks-app-b.txt");
    let bricks = flexmodes::fem::slab_bricks(&SlabParameters::default());
    assert_eq!(printed.len(), 8);
    assert_eq!(bricks.len(), printed.len());
    for (b, row) in bricks.iter().zip(&printed) {
        let one_based: Vec<f64> = b.iter().map(|&n| (n + 1) as f64).collect();
        assert_eq!(&one_based, row);
    }
    let setup = flexmodes::models::plank_setup();
    assert_eq!(setup.hanging_nodes, [3, 15]);
    assert_eq!((setup.force_node, setup.force), (22, 250.0));
    assert_eq!((setup.link_length, setup.link_mass), (2.0, 1.0));
    // The defaults the thesis bodies are built with come from the same files.
    let beam = flexmodes::fem::BeamParameters::default();
    assert_eq!((beam.elements, beam.second_moment), (4, 1.0417e-6));
    let s = SlabParameters::default();
    assert_eq!(
        (s.bricks, s.total_mass, s.poisson_ratio),
        ([4, 2, 1], 62.4, 0.33)
    );
}

/// A body written back (`convert`) keeps its units, node sets and declared interfaces: the
/// flanged hub (mm–t–s) with an rbe2 joint at a given master and an rbe3 ring with weights
/// reads back with the same interfaces, units and matrices.
#[test]
fn a_body_written_back_keeps_its_units_and_interfaces() {
    use flexmodes::body_file::{InterfaceKind, InterfaceSpec, write_imported_body};
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/flange-hub/body.toml");
    let mut body = ImportedBody::load(path.to_str().unwrap()).unwrap();
    let bolt = body.node_sets["bolt_1"].len();
    body.interfaces.insert(
        "joint".into(),
        InterfaceSpec {
            kind: InterfaceKind::Rbe2,
            node_set: "bore".into(),
            master: Some([0.5, -0.25, 20.0]),
            weights: None,
        },
    );
    body.interfaces.insert(
        "sensor".into(),
        InterfaceSpec {
            kind: InterfaceKind::Rbe3,
            node_set: "bolt_1".into(),
            master: None,
            weights: Some((0..bolt).map(|k| 1.0 + 0.125 * k as f64).collect()),
        },
    );
    let dir = scratch("written-back");
    write_files(
        &dir,
        &write_imported_body(&body, true, Default::default()).unwrap(),
    )
    .unwrap();
    let back = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    assert_eq!(back.interfaces, body.interfaces);
    assert_eq!(back.units, body.units);
    assert_eq!(back.node_sets, body.node_sets);
    assert_eq!(back.model.k.nnz(), body.model.k.nnz());
    let (a, b) = (back.model.k.diagonal(), body.model.k.diagonal());
    assert!(
        a.iter().zip(&b).all(|(x, y)| x == y),
        "K written in round-trip form"
    );
}

/// A body handed over in memory (Python's `flexmodes.Body`) is the body its file gives: the
/// L-bracket's K and M as one triangle, as the full symmetric matrix and in any entry order
/// give its frequencies to round-off; each bad input is refused by name with its data.
#[test]
fn a_body_from_matrices_equals_its_body_file_and_is_checked_alike() {
    use flexmodes::body_file::{BodyMatrices, MatrixEntries, lower_entries, mass_lower_entries};
    let file = ImportedBody::load("builtin:l-bracket").unwrap();
    let model = &file.model;
    let n = model.dof_count();
    let k_lower = lower_entries(&model.k);
    let m_lower = mass_lower_entries(&model.m);
    let full = |lower: &[(usize, usize, f64)]| -> Vec<(usize, usize, f64)> {
        let mut out = Vec::new();
        for &(i, j, v) in lower.iter().rev() {
            out.push((j, i, v));
            if i != j {
                out.push((i, j, v));
            }
        }
        out
    };
    let square = |entries: Vec<(usize, usize, f64)>| MatrixEntries {
        rows: n,
        cols: n,
        entries,
    };
    let given = |k: Vec<_>, m: Vec<_>| BodyMatrices {
        name: "bracket".into(),
        stiffness: square(k),
        mass: square(m),
        nodes: Some(model.nodes.clone()),
        node_sets: file.node_sets.clone(),
        default_interface: file.default_interface.clone(),
        ..BodyMatrices::default()
    };
    let reference = count_zero_energy_modes(model, 8).unwrap().elastic_hz();
    for (k, m) in [
        (k_lower.clone(), m_lower.clone()),
        (full(&k_lower), full(&m_lower)),
    ] {
        let body = ImportedBody::from_matrices(given(k, m)).unwrap();
        assert_eq!(body.model.dof_count(), n);
        assert_eq!(body.model.rigid_motions, RigidMotions::FromGeometry);
        assert_eq!(
            body.default_interface_nodes().unwrap(),
            file.default_interface_nodes().unwrap()
        );
        let hz = count_zero_energy_modes(&body.model, 8)
            .unwrap()
            .elastic_hz();
        for (a, b) in hz.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-10 * b, "{a} against {b}");
        }
    }
    let kind = |e: Error| match e {
        Error::BodyFile(b) => b,
        other => panic!("not a body error: {other}"),
    };
    // A NaN, named by its place in the entry list.
    let mut k = k_lower.clone();
    k[9].2 = f64::NAN;
    match kind(ImportedBody::from_matrices(given(k, m_lower.clone())).unwrap_err()) {
        BodyFileError::NonFiniteEntry { line, path, .. } => {
            assert_eq!(line, 10);
            assert_eq!(path, std::path::Path::new("K of bracket"));
        }
        other => panic!("{other}"),
    }
    // Both triangles, not symmetric: the worst entry, 1-based.
    let mut k = full(&k_lower);
    let at = k.iter().position(|&(i, j, _)| i == 40 && j == 3).unwrap();
    k[at].2 += 1e-3 * k_lower.iter().fold(0.0f64, |a, e| a.max(e.2.abs()));
    match kind(ImportedBody::from_matrices(given(k, m_lower.clone())).unwrap_err()) {
        BodyFileError::NotSymmetric { row, col, .. } => {
            assert_eq!((row.min(col), row.max(col)), (4, 41))
        }
        other => panic!("{other}"),
    }
    // A node set past the last node; an index past the matrix.
    let mut sets = given(k_lower.clone(), m_lower.clone());
    sets.node_sets.insert("far".into(), vec![1, n / 3 + 1]);
    match kind(ImportedBody::from_matrices(sets).unwrap_err()) {
        BodyFileError::NodeSetOutOfRange { node, .. } => assert_eq!(node, n / 3 + 1),
        other => panic!("{other}"),
    }
    let mut k = k_lower.clone();
    k.push((n, 0, 1.0));
    assert!(matches!(
        kind(ImportedBody::from_matrices(given(k, m_lower)).unwrap_err()),
        BodyFileError::MatrixIndexOutOfRange { row, .. } if row == n + 1
    ));
}
