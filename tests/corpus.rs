//! The corpus of external bodies (`assets/generate/corpus.py`): bodies from scikit-fem's own
//! structured meshes, gmsh + scikit-fem, FElupe and CalculiX, each imported and checked against
//! the reference values its toolchain computed when it was written (SciPy/ARPACK with two
//! shifts; CalculiX's own `*FREQUENCY` output). Large bodies make these tests slow, so they run
//! in their own binary, on a folder the generator wrote:
//!
//! ```sh
//! pip install -r assets/generate/requirements.txt && apt-get install calculix-ccx
//! python3 assets/generate/corpus.py --out target/corpus
//! FLEXMODES_CORPUS=target/corpus cargo test --release --test corpus -- --ignored --nocapture
//! ```

use std::{
    path::{Path, PathBuf},
    time::Instant,
};

use flexmodes::{analysis::count_zero_energy_modes, body_file::ImportedBody};
use serde_json::Value;

#[path = "external/checks.rs"]
#[allow(dead_code)]
mod checks;

fn corpus() -> Vec<PathBuf> {
    let dir = std::env::var("FLEXMODES_CORPUS")
        .expect("FLEXMODES_CORPUS names the folder assets/generate/corpus.py wrote");
    let mut bodies: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("reference.json").exists())
        .collect();
    bodies.sort();
    assert!(!bodies.is_empty(), "{dir} holds no corpus body");
    bodies
}

fn reference(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json")).unwrap()).unwrap()
}

/// Imports `body.toml` in `dir` and checks its free-free pairs: six zero-energy modes, none
/// missed by the Sturm count, the twelve lowest elastic frequencies equal to the reference to
/// `tol`. Returns the elastic frequencies and the seconds the import's eigen solve took.
fn check_body(name: &str, toml: &Path, reference: &Value, tol: f64) -> (Vec<f64>, f64) {
    let body = ImportedBody::load(toml.to_str().unwrap())
        .unwrap_or_else(|e| panic!("{name}: {}: {e}", toml.display()));
    assert_eq!(
        body.model.dof_count() as u64,
        reference["dofs"].as_u64().unwrap(),
        "{name}"
    );
    let started = Instant::now();
    let count = count_zero_energy_modes(&body.model, 12)
        .unwrap_or_else(|e| panic!("{name}: the free-free solve failed: {e}"));
    let seconds = started.elapsed().as_secs_f64();
    assert_eq!(count.zero_modes, 6, "{name}: zero-energy modes");
    let sturm = count
        .modes
        .sturm
        .unwrap_or_else(|| panic!("{name}: no Sturm check"));
    assert_eq!(sturm.missed(), 0, "{name}: {sturm:?}");
    let expected = checks::floats(&reference["free_free_hz"]);
    let elastic = count.elastic_hz();
    checks::assert_relative(
        &format!("{name} free-free Hz"),
        &elastic[..12],
        &expected[6..18],
        tol,
    );
    assert!(
        count.modes.max_residual() < 1e-6,
        "{name}: worst residual {:.1e}",
        count.modes.max_residual()
    );
    (elastic[..12].to_vec(), seconds)
}

#[test]
#[ignore = "needs the generated corpus: FLEXMODES_CORPUS=DIR (see the module doc)"]
fn every_corpus_body_imports_with_its_reference_frequencies() {
    let bodies = corpus();
    let mut toolchains = std::collections::BTreeSet::new();
    for dir in &bodies {
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let reference = reference(dir);
        toolchains.insert(
            reference["toolchain"]
                .as_str()
                .unwrap_or("")
                .split(' ')
                .next()
                .unwrap()
                .to_string(),
        );
        let (hz, seconds) = check_body(&name, &dir.join("body.toml"), &reference, 1e-6);
        let scipy = reference["scipy_eigsh_s"].as_f64().unwrap_or(f64::NAN);
        println!(
            "{name}: {} DOF, {:.6} Hz first elastic, solve {seconds:.2} s (SciPy eigsh when \
             made: {scipy:.2} s, another run)",
            reference["dofs"], hz[0]
        );
        if let Some(ccx) = reference.get("calculix_hz") {
            // CalculiX prints 7 digits; its first six are the rigid motions.
            let ccx = checks::floats(ccx);
            checks::assert_relative(&format!("{name} against CalculiX"), &hz, &ccx[6..18], 2e-6);
            // The converted twin gives the same pairs.
            let (twin, _) = check_body(&name, &dir.join("converted/body.toml"), &reference, 1e-6);
            checks::assert_relative(&format!("{name} direct vs converted"), &hz, &twin, 1e-9);
        }
    }
    println!("toolchains: {toolchains:?}");
}
