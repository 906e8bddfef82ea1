//! The corpus of external bodies (`assets/generate/corpus.py`): bodies from scikit-fem's own
//! structured meshes, gmsh + scikit-fem, FElupe and CalculiX, each imported and checked against
//! the reference values its toolchain computed when it was written (SciPy/ARPACK with two
//! shifts; CalculiX's own `*FREQUENCY` output). The large bodies (30 k+ DOF) are not committed
//! and make these tests slow, so they run in their own binary on a folder the generator wrote
//! (the small ones, in tests/corpus/, are checked by `cargo test` too):
//!
//! ```sh
//! pip install -r assets/generate/requirements.txt && apt-get install calculix-ccx
//! python3 assets/generate/corpus.py --out target/corpus
//! FLEXMODES_CORPUS=target/corpus cargo test --test corpus -- --ignored --nocapture
//! ```

use std::path::PathBuf;

#[path = "external/checks.rs"]
#[allow(dead_code)]
mod checks;

#[test]
#[ignore = "needs the generated corpus: FLEXMODES_CORPUS=DIR (see the module doc)"]
fn every_corpus_body_imports_with_its_reference_frequencies() {
    let dir = PathBuf::from(
        std::env::var("FLEXMODES_CORPUS")
            .expect("FLEXMODES_CORPUS names the folder assets/generate/corpus.py wrote"),
    );
    let bodies = checks::corpus_bodies(&dir);
    assert!(
        bodies.len() >= 8,
        "{}: {} bodies",
        dir.display(),
        bodies.len()
    );
    let mut toolchains = std::collections::BTreeSet::new();
    for body in &bodies {
        let reference = checks::corpus_reference(body);
        let toolchain = reference["toolchain"].as_str().unwrap_or("").to_string();
        toolchains.insert(toolchain.split(' ').next().unwrap().to_string());
        let (hz, seconds) = checks::check_corpus_dir(body);
        println!(
            "{}: {}, {} DOF, first elastic {hz:.6} Hz, solve {seconds:.2} s (SciPy eigsh when \
             the body was made: {:.2} s)",
            body.file_name().unwrap().to_string_lossy(),
            toolchain,
            reference["dofs"],
            reference["scipy_eigsh_s"].as_f64().unwrap_or(f64::NAN)
        );
    }
    assert!(toolchains.len() >= 3, "{toolchains:?}");
}

/// Every corpus body CalculiX also wrote spinning (`[preload]`, reference `spinning_hz`: the
/// lever held at its bore and spun about the bore's axis): the full body's six lowest
/// frequencies in the turning frame at both rates equal CalculiX's own prestressed ones to
/// 2e-4, and CB with 20 modes within 2e-3; the stiffening scaled with the rate² from the one
/// preloaded run.
#[test]
#[ignore = "needs the generated corpus: FLEXMODES_CORPUS=DIR (see the module doc)"]
fn spun_corpus_bodies_spin_at_calculix_frequencies() {
    use flexmodes::{
        Progress,
        body_file::ImportedBody,
        models::{BodyCampbellParameters, body_campbell},
        reduction::Method,
    };
    let dir = PathBuf::from(
        std::env::var("FLEXMODES_CORPUS")
            .expect("FLEXMODES_CORPUS names the folder assets/generate/corpus.py wrote"),
    );
    let mut spun = 0;
    for body_dir in checks::corpus_bodies(&dir) {
        let reference = checks::corpus_reference(&body_dir);
        let Some(ccx) = reference.get("spinning_hz") else {
            continue;
        };
        let ccx: Vec<Vec<f64>> = serde_json::from_value(ccx.clone()).unwrap();
        let three =
            |key: &str| -> [f64; 3] { serde_json::from_value(reference[key].clone()).unwrap() };
        let body = ImportedBody::load(body_dir.join("body.toml").to_str().unwrap()).unwrap();
        let rates: Vec<f64> = serde_json::from_value(reference["rates_rad_s"].clone()).unwrap();
        let started = std::time::Instant::now();
        let table = body_campbell(
            &body,
            &BodyCampbellParameters {
                drive: reference["spin_drive"].as_str().unwrap().into(),
                axis: three("spin_axis"),
                axis_point: Some(three("spin_axis_point")),
                rates: rates.clone(),
                count: 6,
                models: vec![(Method::CraigBampton, 20)],
                stiffening: true,
                full: true,
                residual_vectors: true,
            },
            &Progress::new(),
        )
        .unwrap();
        assert!(table.stiffened);
        let mut worst = [0.0f64; 2];
        for (r, expected) in ccx.iter().enumerate() {
            for (m, &f) in expected.iter().take(6).enumerate() {
                for (k, tol) in [(0, 2e-4), (1, 2e-3)] {
                    // CalculiX prints its frequencies ascending; the curves follow shapes.
                    let got = checks::ascending(&table.curves[k].hz[r])[m];
                    let rel = (got - f).abs() / f;
                    worst[k] = worst[k].max(rel);
                    assert!(
                        rel < tol,
                        "{}: model {k} rate {} mode {m}: {got} against CalculiX's {f}",
                        body_dir.display(),
                        rates[r]
                    );
                }
            }
        }
        println!(
            "{}: {} DOF spun at {rates:?} rad/s: NR within {:.1e}, CB 20 within {:.1e} of CalculiX's \
             prestressed frequencies ({:.1} s)",
            body_dir.file_name().unwrap().to_string_lossy(),
            body.model.dof_count(),
            worst[0],
            worst[1],
            started.elapsed().as_secs_f64()
        );
        spun += 1;
    }
    assert!(spun >= 1, "{}: no spun body", dir.display());
}
