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
