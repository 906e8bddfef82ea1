//! Bodies no flexmodes code made: quadratic tetrahedra meshed by gmsh, stiffness and consistent
//! mass assembled by scikit-fem, one part in m–kg–s and one in mm–t–s, with bore holes as node
//! sets (`assets/generate/make_bodies.py`). Reference values were computed by SciPy (ARPACK
//! shift-invert, LAPACK `eigh` on the reduced matrices) when the bodies were written, and are
//! read from each body's `reference.json`.

use std::path::PathBuf;

use flexmodes::{
    analysis::{count_zero_energy_modes, reduced_modes},
    body_file::ImportedBody,
    linalg::max_abs,
    reduction::{
        CONSTRAINT_COUPLING_TOLERANCE, ColumnKind, Method, ModeSelection, ReducedMatrices,
        ReductionParameters, SolverPath, reduce,
    },
};
use serde_json::Value;

const BODIES: [&str; 3] = ["steel-link", "flange-hub", "steel-rod"];

fn body(name: &str) -> (ImportedBody, Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/bodies")
        .join(name);
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let reference: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json")).unwrap())
            .unwrap();
    (body, reference)
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn assert_relative(what: &str, computed: &[f64], reference: &[f64], tol: f64) {
    assert_eq!(
        computed.len(),
        reference.len(),
        "{what}: {computed:?} against {reference:?}"
    );
    for (j, (c, r)) in computed.iter().zip(reference).enumerate() {
        let e = (c - r).abs() / r.abs();
        assert!(
            e <= tol,
            "{what} [{j}]: {c} against {r} (relative {e:.1e} > {tol:.0e})"
        );
    }
}

#[test]
fn free_free_frequencies_and_zero_energy_modes_match_scipy() {
    for name in BODIES {
        let (body, reference) = body(name);
        assert_eq!(
            body.model.dof_count() as u64,
            reference["dofs"].as_u64().unwrap()
        );
        let full = count_zero_energy_modes(&body.model, 12).unwrap();
        assert_eq!(full.zero_modes, 6, "{name}: zero-energy modes");
        assert_eq!(
            full.zero_modes as u64,
            reference["zero_energy_modes"].as_u64().unwrap()
        );
        let expected = floats(&reference["free_free_hz"]);
        let elastic = full.elastic_hz();
        assert!(elastic.len() >= 12, "{name}: {elastic:?}");
        assert_relative(
            &format!("{name} free-free Hz"),
            &elastic[..12],
            &expected[6..18],
            1e-6,
        );
        // Every printed pair carries its residual, and none is above the flag.
        assert_eq!(full.modes.residuals.len(), full.modes.values.len());
        assert!(
            full.modes.max_residual() < 1e-6,
            "{name}: {:.1e}",
            full.modes.max_residual()
        );
    }
}

#[test]
fn mass_properties_from_the_consistent_mass_match_scipy() {
    for name in BODIES {
        let (body, reference) = body(name);
        let p = body.model.mass_properties();
        let mass = reference["mass"].as_f64().unwrap();
        assert!(
            (p.mass - mass).abs() <= 1e-10 * mass,
            "{name}: mass {} vs {mass}",
            p.mass
        );
        let size = body.model.size();
        let centre = floats(&reference["centre_of_mass"]);
        for d in 0..3 {
            assert!(
                (p.centre[d] - centre[d]).abs() <= 1e-10 * size,
                "{name}: centre {:?} vs {centre:?}",
                p.centre
            );
        }
        let inertia: Vec<Vec<f64>> = reference["inertia_about_centre"]
            .as_array()
            .unwrap()
            .iter()
            .map(floats)
            .collect();
        let top = inertia.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        assert_eq!(inertia.len(), 3);
        for (k, row) in inertia.iter().enumerate() {
            assert_eq!(row.len(), 3);
            for (l, expected) in row.iter().enumerate() {
                assert!(
                    (p.inertia[k][l] - expected).abs() <= 1e-9 * top,
                    "{name}: J[{k}][{l}] {} vs {expected}",
                    p.inertia[k][l],
                );
            }
        }
        // The mass centre of the model is the consistent mass', not its diagonal's.
        assert_eq!(body.model.mass_centre(), p.centre);
    }
}

#[test]
fn reduced_frequencies_match_lapack_on_scipys_reduction() {
    for name in BODIES {
        let (body, reference) = body(name);
        let model = &body.model;
        for case in reference["cases"].as_array().unwrap() {
            let set = case["boundary"].as_str().unwrap();
            let modes = case["modes"].as_u64().unwrap() as usize;
            let boundary = body.node_sets[set].clone();
            let parameters = ReductionParameters {
                boundary_nodes: boundary,
                modes: ModeSelection::Count(modes),
                solver: SolverPath::Auto,
            };
            let what = format!("{name} on {set}");
            let cb = reduce(model, Method::CraigBampton, &parameters).unwrap();
            // Fixed-interface frequencies, from the basis' own columns.
            let fixed: Vec<f64> = cb
                .columns
                .iter()
                .filter_map(|c| match c.kind {
                    ColumnKind::Normal { hz } => Some(hz),
                    _ => None,
                })
                .collect();
            assert_relative(
                &format!("{what}: fixed-interface Hz"),
                &fixed,
                &floats(&case["fixed_interface_hz"]),
                1e-8,
            );
            let expected_cb = floats(&case["cb_hz"]);
            let cb_eig = reduced_modes(model, &cb).unwrap();
            assert_eq!(cb_eig.zero_energy, 6, "{what}: CB zero-energy modes");
            let cb_hz = cb_eig.elastic_hz();
            let count = (expected_cb.len() - 6).min(cb_hz.len()).min(20);
            assert_relative(
                &format!("{what}: CB Hz"),
                &cb_hz[..count],
                &expected_cb[6..6 + count],
                1e-8,
            );
            let gr = reduce(model, Method::Guyan, &parameters).unwrap();
            let gr_eig = reduced_modes(model, &gr).unwrap();
            assert_eq!(gr_eig.zero_energy, 6, "{what}: GR zero-energy modes");
            let expected_gr = floats(&case["guyan_hz"]);
            let count = (expected_gr.len() - 6).min(20);
            assert_relative(
                &format!("{what}: GR Hz"),
                &gr_eig.elastic_hz()[..count],
                &expected_gr[6..6 + count],
                1e-8,
            );
            // Mode condensation spans Craig–Bampton's space.
            let mc = reduce(model, Method::ModeCondensation, &parameters).unwrap();
            let mc_eig = reduced_modes(model, &mc).unwrap();
            assert_eq!(mc_eig.zero_energy, 6, "{what}: MC zero-energy modes");
            let n = cb_hz.len().min(20);
            assert_relative(
                &format!("{what}: MC against CB"),
                &mc_eig.elastic_hz()[..n],
                &cb_hz[..n],
                1e-6,
            );
        }
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
