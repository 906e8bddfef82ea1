//! `export --exudyn` on a body no flexmodes code made (the steel rod: gmsh + scikit-fem,
//! consistent mass): the files Exudyn's adapter reads, read back and checked against SciPy's
//! clamped frequencies (`assets/generate/driven_reference.py`), and the refusals. The
//! simulation cross-check against Exudyn itself is `assets/python/test_exudyn_crosscheck.py`.

use std::path::{Path, PathBuf};

use faer::Mat;
use flexmodes::error::ExportProblem;
use flexmodes::{
    body_file::{ImportedBody, read_matrix_market, read_npy},
    export::{EXUDYN_FORMAT, ExportParameters, export},
    linalg::generalized_eigen,
    reduction::{Method, RigidInterface},
};
use serde_json::Value;

fn rod() -> (ImportedBody, Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/steel-rod");
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    let reference =
        serde_json::from_str(&std::fs::read_to_string(dir.join("driven_reference.json")).unwrap())
            .unwrap();
    (body, reference)
}

fn ring(body: &ImportedBody, set: &str) -> RigidInterface {
    RigidInterface::at_centroid(&body.model, set, &body.node_sets[set]).unwrap()
}

fn npy(path: &Path) -> Mat<f64> {
    let (rows, cols, data) = read_npy(&std::fs::read(path).unwrap()).unwrap();
    assert_eq!(data.len(), rows * cols);
    Mat::from_fn(rows, cols, |i, j| data[i + j * rows])
}

fn dense(path: &Path) -> Mat<f64> {
    let mm = read_matrix_market(path).unwrap();
    let mut a = Mat::zeros(mm.rows, mm.cols);
    for (i, j, v) in mm.expanded() {
        a[(i, j)] += v;
    }
    a
}

#[test]
fn exudyn_files_hold_the_clamped_rod() {
    let (body, reference) = rod();
    let scratch = crate::scratch::Scratch::new("exudyn");
    let dir = scratch.join("out");
    let end_a = ring(&body, "end_a");
    let parameters = ExportParameters {
        rigid_interfaces: vec![end_a.clone()],
        exudyn: true,
        ..Default::default()
    };
    let summary = export(
        &body,
        Method::CraigBampton,
        &end_a.nodes,
        8,
        &dir,
        &parameters,
    )
    .unwrap();
    let exudyn = summary.exudyn.as_ref().unwrap();
    assert_eq!(
        (exudyn.frame.as_str(), exudyn.mode_type),
        ("end_a", "NormalModes")
    );

    let folder = dir.join("exudyn");
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(folder.join("body.json")).unwrap()).unwrap();
    assert_eq!(doc["format"], EXUDYN_FORMAT);
    let nodes = npy(&folder.join("nodes.npy"));
    let n = body.model.node_count();
    assert_eq!((nodes.nrows(), nodes.ncols()), (n, 3));
    for (i, p) in body.model.nodes.iter().enumerate() {
        assert_eq!([nodes[(i, 0)], nodes[(i, 1)], nodes[(i, 2)]], *p);
    }
    let (k, m, psi) = (
        dense(&folder.join("stiffness.mtx")),
        dense(&folder.join("mass.mtx")),
        npy(&folder.join("modes.npy")),
    );
    assert_eq!(
        (k.nrows(), m.nrows(), psi.nrows(), psi.ncols()),
        (3 * n, 3 * n, 3 * n, 8)
    );
    // The mass read back: a unit translation's kinetic mass is the body's.
    let mass = translational_mass(&m);
    let total = body.model.total_mass();
    assert!((mass - total).abs() < 1e-12 * total, "{mass} vs {total}");
    // The frame's ring never moves; nothing else is held.
    let ring_nodes: Vec<usize> = doc["frame"]["node_numbers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(ring_nodes.len(), end_a.nodes.len());
    for &node in &ring_nodes {
        for a in 0..3 {
            assert!((0..8).all(|j| psi[(3 * node + a, j)] == 0.0));
        }
    }
    // The pencil of the files: its frequencies are the rod's clamped ones (SciPy's eigsh on
    // the clamped full rod), and body.json says the same.
    let k_r = psi.transpose() * &k * &psi;
    let m_r = psi.transpose() * &m * &psi;
    let hz = generalized_eigen(k_r.as_ref(), m_r.as_ref(), "read back")
        .unwrap()
        .hz();
    let scipy: Vec<f64> = reference["clamped_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    for (i, f) in hz.iter().enumerate() {
        assert!(
            (f - scipy[i]).abs() < 1e-8 * scipy[i],
            "mode {i}: {f} vs SciPy {}",
            scipy[i]
        );
        let said = doc["hz"][i].as_f64().unwrap();
        // Summation order alone moves the lowest one by ~3e-10 (ΨᵀKΨ cancels ~4 digits).
        assert!(
            (f - said).abs() < 1e-9 * f,
            "mode {i}: {f} vs body.json {said}"
        );
    }
    let sets: Vec<&str> = doc["node_sets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(sets, ["end_a", "end_b"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// $e_x^TMe_x$: the kinetic mass of a unit translation along x of a body whose `m` is
/// ordered node by node, x y z.
fn translational_mass(m: &Mat<f64>) -> f64 {
    let n = m.nrows();
    let ones_x: Vec<f64> = (0..n).map(|i| if i % 3 == 0 { 1.0 } else { 0.0 }).collect();
    (0..n)
        .map(|i| ones_x[i] * (0..n).map(|j| m[(i, j)] * ones_x[j]).sum::<f64>())
        .sum()
}

#[test]
fn exudyn_export_refuses_by_name_and_writes_nothing() {
    let (body, _) = rod();
    let scratch = crate::scratch::Scratch::new("exudyn-refused");
    let dir = scratch.join("out");
    let end_a = ring(&body, "end_a");
    let exudyn = |rigid: Vec<RigidInterface>| ExportParameters {
        rigid_interfaces: rigid,
        exudyn: true,
        ..Default::default()
    };
    let cases: [(Method, usize, ExportParameters, ExportProblem, &str); 2] = [
        // A plain node set: no frame to attach.
        (
            Method::CraigBampton,
            6,
            exudyn(vec![]),
            ExportProblem::NoFrameInterface,
            "rigid interface",
        ),
        // Guyan on the drive alone: only the frame's rigid motions.
        (
            Method::Guyan,
            0,
            exudyn(vec![end_a.clone()]),
            ExportProblem::NothingElastic {
                ring: "end_a".into(),
            },
            "nothing elastic is left",
        ),
    ];
    for (method, modes, parameters, problem, says) in cases {
        let error = export(&body, method, &end_a.nodes, modes, &dir, &parameters).unwrap_err();
        let text = error.to_string();
        match &error {
            flexmodes::error::CoreError::Reduction(
                flexmodes::reduction::ReductionError::NotExportable {
                    to: "Exudyn",
                    problem: found,
                },
            ) => assert_eq!(found, &problem, "{text}"),
            other => panic!("not a refused export: {other}"),
        }
        assert!(
            text.contains("cannot export for Exudyn") && text.contains(says),
            "{text}"
        );
        assert!(!dir.exists(), "a refused export wrote {}", dir.display());
    }
}
