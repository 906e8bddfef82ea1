//! Matrices as FE codes write them: a bar assembled by scikit-fem (P2 tetrahedra, consistent
//! mass), written by SciPy's `hb_write` in Harwell–Boeing (RUA) in a shuffled equation order
//! with an ANSYS-style DOF map, and its Matrix Market twin in node order
//! (`assets/generate/hb_body.py`): both import to the same body.

use std::path::PathBuf;

use flexmodes::{body_file::ImportedBody, body_file::parse_dof_map, fem::DofMap};

fn bar(file: &str) -> ImportedBody {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/bodies/hb-bar")
        .join(file);
    ImportedBody::load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn harwell_boeing_with_a_dof_map_imports_to_its_matrix_market_twin() {
    same_body(&bar("body-hb.toml"), &bar("body.toml"));
}

/// The same matrices as Abaqus matrix-input lines (node, DOF, node, DOF, value; the lower
/// triangle in the shuffled equation order) import to the twin too.
#[test]
fn abaqus_matrix_input_imports_to_its_matrix_market_twin() {
    same_body(&bar("body-abaqus.toml"), &bar("body.toml"));
}

/// The same matrices as Nastran DMIG cards written by pyNastran (large field, double precision:
/// 11 significant digits, `assets/generate/nastran_body.py`) import to the twin to that
/// precision, and to the same frequencies to 3e-8.
#[test]
fn nastran_dmig_imports_to_its_matrix_market_twin() {
    let (dmig, mm) = (bar("body-dmig.toml"), bar("body.toml"));
    same_body_to(&dmig, &mm, 1e-10);
    let hz = |b: &ImportedBody| {
        flexmodes::linalg::generalized_eigen(
            b.model.k.to_dense().as_ref(),
            b.model.m.to_dense().as_ref(),
            "bar",
        )
        .unwrap()
        .hz()
    };
    let (a, b) = (hz(&dmig), hz(&mm));
    for i in 6..16 {
        // 11 digits an entry move the bar's first elastic frequency by 9.5e-9 (K's rows
        // cancel to ~1e-3 of their entries on the lowest modes).
        assert!(
            (a[i] - b[i]).abs() < 3e-8 * b[i],
            "mode {i}: {} vs {}",
            a[i],
            b[i]
        );
    }
}

/// The same matrices as Nastran OUTPUT4 files written by NASA's pyyeti in the shuffled
/// equation order, placed by the DOF map (`assets/generate/op4_body.py`): binary double
/// precision in the sparse "bigmat" form, and ASCII with K in non-bigmat strings and M dense.
/// Both import to the twin exactly.
#[test]
fn op4_binary_and_ascii_import_to_their_matrix_market_twin() {
    let mm = bar("body.toml");
    same_body(&bar("body-op4.toml"), &mm);
    same_body(&bar("body-op4-ascii.toml"), &mm);
}

/// `convert --format` writes each format flexmodes reads in full precision: the bar read from
/// its DMIG cards, written as Abaqus lines, as DMIG cards and as Matrix Market, reads back to
/// the same matrices exactly, node sets kept.
#[test]
fn convert_writes_every_format_it_reads_back() {
    use flexmodes::body_file::{MatrixFormat, write_files, write_imported_body};
    let source = bar("body-dmig.toml");
    for (format, compress) in [
        (MatrixFormat::Abaqus, false),
        (MatrixFormat::NastranDmig, true),
        (MatrixFormat::MatrixMarket, false),
    ] {
        let scratch = crate::scratch::Scratch::new(&format!("convert-{format:?}"));
        let dir = scratch.join("out");
        write_files(
            &dir,
            &write_imported_body(&source, compress, format).unwrap(),
        )
        .unwrap();
        let back = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
        same_body_to(&back, &source, 0.0);
        std::fs::remove_dir_all(&dir).unwrap();
    }
    let e = write_imported_body(&source, false, MatrixFormat::HarwellBoeing).unwrap_err();
    assert!(e.to_string().contains("read, not written"), "{e}");
}

/// `import` on the DMIG twin: its 11-digit entries leave K's rigid motions a residual force
/// (K R ≈ 2e-10 |K||R|); the partial eigensolver's residual check allows for that measured
/// precision (and only that much), so the body imports with six zero-energy modes and the
/// twin's frequencies, where the exact twin's pairs stay checked to round-off.
#[test]
fn a_dmig_body_of_eleven_digits_imports_with_its_precision_stated() {
    let summary = |b: &ImportedBody| flexmodes::models::import_summary(b).unwrap();
    let (dmig, _) = summary(&bar("body-dmig.toml"));
    let (exact, _) = summary(&bar("body.toml"));
    let defect = dmig["rigid_motion_defect"].as_f64().unwrap();
    assert!(defect > 1e-11 && defect < 1e-9, "{defect}");
    assert!(exact["rigid_motion_defect"].as_f64().unwrap() < 1e-14);
    assert_eq!(dmig["zero_energy_modes"], 6);
    let list = |v: &serde_json::Value, k: &str| -> Vec<f64> {
        v[k].as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (a, b) = (
        list(&dmig, "lowest_elastic_hz"),
        list(&exact, "lowest_elastic_hz"),
    );
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 3e-8 * y, "{x} vs {y}");
    }
    assert!(
        list(&dmig, "lowest_elastic_residuals")
            .iter()
            .all(|&r| r <= 1e-6)
    );
    assert!(
        list(&exact, "lowest_elastic_residuals")
            .iter()
            .all(|&r| r <= 1e-10)
    );
}

fn same_body(hb: &ImportedBody, mm: &ImportedBody) {
    same_body_to(hb, mm, 1e-15);
}

fn same_body_to(hb: &ImportedBody, mm: &ImportedBody, tolerance: f64) {
    assert_eq!(hb.model.dof_count(), mm.model.dof_count());
    assert_eq!(hb.model.dof_count(), 1539);
    let (k_hb, k_mm) = (hb.model.k.to_dense(), mm.model.k.to_dense());
    let (m_hb, m_mm) = (hb.model.m.to_dense(), mm.model.m.to_dense());
    let n = k_mm.nrows();
    let (mut dk, mut dm, mut sk, mut sm) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for j in 0..n {
        for i in 0..n {
            dk = dk.max((k_hb[(i, j)] - k_mm[(i, j)]).abs());
            dm = dm.max((m_hb[(i, j)] - m_mm[(i, j)]).abs());
            sk = sk.max(k_mm[(i, j)].abs());
            sm = sm.max(m_mm[(i, j)].abs());
        }
    }
    assert!(dk <= tolerance * sk, "K differs by {dk:e} of {sk:e}");
    assert!(dm <= tolerance * sm, "M differs by {dm:e} of {sm:e}");
    assert_eq!(hb.node_sets, mm.node_sets);
}

/// A DOF map names what it cannot place: a DOF the body does not have, an equation twice, a
/// node DOF without an equation.
#[test]
fn a_dof_map_names_what_it_cannot_place() {
    let dofs = DofMap::solid();
    let good = " Matrix Eqn   Node   DOF\n 1 2 UX\n 2 2 UY\n 3 2 UZ\n 4 1 UX\n 5 1 UY\n 6 1 UZ\n";
    assert_eq!(
        parse_dof_map(good.as_bytes(), "k.mapping", &dofs, 2).unwrap(),
        vec![3, 4, 5, 0, 1, 2]
    );
    let rotation = good.replace(" 6 1 UZ", " 6 1 ROTX");
    let e = parse_dof_map(rotation.as_bytes(), "k.mapping", &dofs, 2).unwrap_err();
    assert!(
        e.to_string().contains("k.mapping:7") && e.to_string().contains("node 1"),
        "{e}"
    );
    let twice = good.replace(" 6 1 UZ", " 6 1 UY");
    let e = parse_dof_map(twice.as_bytes(), "k.mapping", &dofs, 2).unwrap_err();
    assert!(e.to_string().contains("already has equation 5"), "{e}");
    let missing = good.replace(" 6 1 UZ\n", "");
    let e = parse_dof_map(missing.as_bytes(), "k.mapping", &dofs, 2).unwrap_err();
    assert!(
        e.to_string().contains("node 1 DOF `z` has no equation"),
        "{e}"
    );
}
