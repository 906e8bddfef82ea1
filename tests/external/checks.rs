//! Checks of a body no flexmodes code made against the reference values SciPy computed when
//! it was written (`assets/generate/make_bodies.py`): shared by the committed bodies' tests
//! (`tests/reproduce`) and the 30 k+-DOF body's slow test (`tests/slow_bodies.rs`).

use std::path::Path;

use flexmodes::{
    analysis::{count_zero_energy_modes, reduced_modes},
    body_file::ImportedBody,
    reduction::{ColumnKind, Method, ModeSelection, ReductionRequest, SolverPath, reduce},
};
use serde_json::Value;
use std::time::Instant;

/// The body in `dir` (its `body.toml`) and its `reference.json`.
/// A committed external body (`tests/bodies/<name>`) and its reference values.
pub fn committed_body(name: &str) -> (ImportedBody, Value) {
    load(
        &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/bodies")
            .join(name),
    )
}

/// The rigid interface of a body's first reference case: its boundary set tied to a master at
/// the set's centroid.
pub fn first_rbe2_interface(
    body: &ImportedBody,
    reference: &Value,
) -> flexmodes::models::BodyInterfaces {
    let set = reference["cases"][0]["boundary"].as_str().unwrap();
    let nodes = body.node_sets[set].clone();
    flexmodes::models::BodyInterfaces {
        boundary: nodes.clone(),
        rigid: vec![
            flexmodes::reduction::RigidInterface::at_centroid(&body.model, set, &nodes).unwrap(),
        ],
        averaging: Vec::new(),
        interface_modes: None,
    }
}

pub fn load(dir: &Path) -> (ImportedBody, Value) {
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let reference: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json")).unwrap())
            .unwrap();
    (body, reference)
}

pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

pub fn assert_relative(what: &str, computed: &[f64], reference: &[f64], tol: f64) {
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

/// Six zero-energy modes and the twelve lowest elastic free-free frequencies to 1e-6, every
/// pair with its residual below the flag.
pub fn check_free_free(name: &str, body: &ImportedBody, reference: &Value) {
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

/// Mass, mass centre and inertia about it from the consistent mass matrix.
pub fn check_mass_properties(name: &str, body: &ImportedBody, reference: &Value) {
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

/// For each reference case (a bore's node set, a mode count): fixed-interface, CB and GR
/// frequencies to 1e-8 of SciPy/LAPACK's, six zero-energy modes each, MC = CB to 1e-6.
pub fn check_reductions(name: &str, body: &ImportedBody, reference: &Value) {
    let model = &body.model;
    for case in reference["cases"].as_array().unwrap() {
        let set = case["boundary"].as_str().unwrap();
        let modes = case["modes"].as_u64().unwrap() as usize;
        let boundary = body.node_sets[set].clone();
        let parameters = ReductionRequest {
            boundary_nodes: boundary,
            modes: ModeSelection::Count(modes),
            solver: SolverPath::Auto,
            ..Default::default()
        };
        let what = format!("{name} on {set}");
        let cb = reduce(model, &parameters.with_method(Method::CraigBampton)).unwrap();
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
        let gr = reduce(model, &parameters.with_method(Method::Guyan)).unwrap();
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
        let mc = reduce(model, &parameters.with_method(Method::ModeCondensation)).unwrap();
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

pub fn corpus_reference(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json")).unwrap()).unwrap()
}

/// Imports `body.toml` in `dir` and checks its free-free pairs: six zero-energy modes, none
/// missed by the Sturm count, the twelve lowest elastic frequencies equal to the reference to
/// `tol`. Returns the elastic frequencies and the seconds the import's eigen solve took.
pub fn check_corpus_body(name: &str, toml: &Path, reference: &Value, tol: f64) -> (Vec<f64>, f64) {
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
    let expected = floats(&reference["free_free_hz"]);
    let elastic = count.elastic_hz();
    assert_relative(
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

/// The corpus bodies in `dir` (folders with a reference.json), sorted.
pub fn corpus_bodies(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut bodies: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("reference.json").exists())
        .collect();
    bodies.sort();
    bodies
}

/// A corpus body checked whole: its free-free pairs against SciPy's to 1e-6 and, for a
/// CalculiX body, against CalculiX's printed frequencies to 2e-6 and its converted twin's to
/// 1e-9. Returns the first elastic frequency and the solve's seconds.
pub fn check_corpus_dir(dir: &Path) -> (f64, f64) {
    let name = dir.file_name().unwrap().to_string_lossy().to_string();
    let reference = corpus_reference(dir);
    let (hz, seconds) = check_corpus_body(&name, &dir.join("body.toml"), &reference, 1e-6);
    if let Some(ccx) = reference.get("calculix_hz") {
        // CalculiX prints 7 digits; its first six are the rigid motions. Its own solve is not
        // always converged that far: where SciPy's pair of the same matrices differs from
        // CalculiX's print by more (2.7e-6 on the coarse block, mode 11), that mode's tolerance
        // is the measured disagreement, half again; every other mode keeps 2e-6.
        let ccx = floats(ccx);
        let scipy = floats(&reference["free_free_hz"]);
        assert_eq!(hz.len(), 12, "{name}");
        for j in 0..12 {
            let (c, s) = (ccx[6 + j], scipy[6 + j]);
            let disagreement = (s - c).abs() / s;
            if disagreement > 2e-6 {
                println!(
                    "{name}: CalculiX's printed mode {} differs from SciPy's by {disagreement:.1e}",
                    7 + j
                );
            }
            let tol = (1.5 * disagreement).max(2e-6);
            let e = (hz[j] - c).abs() / c;
            assert!(
                e <= tol,
                "{name} against CalculiX, mode {}: {} against {c} (relative {e:.1e} > {tol:.1e})",
                7 + j,
                hz[j]
            );
        }
        let (twin, _) =
            check_corpus_body(&name, &dir.join("converted/body.toml"), &reference, 1e-6);
        assert_relative(&format!("{name} direct vs converted"), &hz, &twin, 1e-9);
    }
    (hz[0], seconds)
}

/// `v` in ascending order (a Campbell curve row follows mode shapes; FE codes print their
/// frequencies sorted).
pub fn ascending(v: &[f64]) -> Vec<f64> {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v
}
