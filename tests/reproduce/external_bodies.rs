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
mod checks;

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
