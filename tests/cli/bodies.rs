//! A user's body from the command line: `import`, `export`, `convert`, and refusals that
//! write nothing.

use crate::common::{flexmodes, json, temp_dir};

#[test]
fn import_report_and_export_a_body_file() {
    // import: the summary of a built-in body, as JSON.
    let v = json(&["import", "builtin:l-bracket", "--json"]);
    assert_eq!(v["dofs"], 1314);
    assert_eq!(v["zero_energy_modes"], 6);
    assert_eq!(v["node_sets"]["bolt_hole"], 24);
    let first = v["lowest_elastic_hz"][0].as_f64().unwrap();
    assert!(first > 1000.0 && first < 10000.0, "{first}");

    // report modes on a body copied to disk, the interface named by its set.
    let dir = app_b_slab_on_disk("body");
    let body = dir.join("body.toml");
    let body = body.to_str().unwrap();
    let v = json(&[
        "report",
        "modes",
        "--body",
        body,
        "--boundary",
        "bottom_corners",
        "--method",
        "cb,gr",
        "--modes",
        "6",
        "--json",
    ]);
    assert_eq!(
        v["parameters"]["boundary"],
        serde_json::json!([16, 18, 28, 30])
    );
    // The imported body is the built-in App. B slab: Craig-Bampton's frequencies equal what
    // slab-modes computes on its own body (7.49872 Hz first), to the 9 digits JSON carries.
    let builtin = json(&["report", "slab-modes", "--method", "cb", "--json"]);
    let expected = builtin["results"]["reduced_hz"]["cb"].as_array().unwrap();
    let imported = v["results"]["reduced_hz"]["cb"].as_array().unwrap();
    assert!(expected.len() >= 6 && imported.len() >= 6);
    for (a, b) in imported.iter().zip(expected).take(6) {
        let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
        assert!((a - b).abs() <= 1e-8 * b, "{a} vs {b}");
    }
}

#[test]
fn export_writes_a_body_files_model_with_and_without_residual_vectors() {
    let dir = app_b_slab_on_disk("export");
    let body = dir.join("body.toml");
    let body = body.to_str().unwrap();
    // Craig–Bampton's first frequency on the App. B slab, as slab-modes reports it.
    let builtin = json(&["report", "slab-modes", "--method", "cb", "--json"]);
    let cb = builtin["results"]["reduced_hz"]["cb"][0].as_f64().unwrap();
    // export: the files, and a second export replacing the folder.
    let out_dir = dir.join("cb");
    let out = flexmodes(&[
        "export",
        "--body",
        body,
        "--method",
        "cb",
        "--modes",
        "6",
        "--out",
        out_dir.to_str().unwrap(),
        "--timings",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["psi.npy", "k_r.mtx", "m_r.mtx", "model.json"] {
        assert!(out_dir.join(f).is_file(), "{f}");
    }
    // --timings names every phase on stderr; stdout says how many zero-energy modes.
    let stderr = String::from_utf8_lossy(&out.stderr);
    for phase in [
        "factorisation",
        "constraint modes",
        "reduced matrices",
        "write Ψ",
        "total",
        "peak resident memory",
    ] {
        assert!(stderr.contains(phase), "{phase} missing from {stderr}");
    }
    assert!(String::from_utf8_lossy(&out.stdout).contains("zero-energy mode(s)"));
    let model: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("model.json")).unwrap()).unwrap();
    // On by default: the twelve inertia loads' residual vectors after CB's 18 columns, named.
    assert_eq!(model["size"], 30);
    let kinds: Vec<&str> = model["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["kind"].as_str().unwrap())
        .collect();
    assert_eq!(
        kinds.iter().filter(|k| **k == "inertia_residual").count(),
        12
    );
    assert!(
        kinds[18..].iter().all(|k| *k == "inertia_residual"),
        "{kinds:?}"
    );
    // More columns, the same space and more: a lower (Rayleigh–Ritz) first frequency.
    let first = model["reduced_elastic_hz"][0].as_f64().unwrap();
    assert!(first <= cb * (1.0 + 1e-10), "{first} {cb}");
    // Off: the thesis' CB, as the report computed it.
    let plain_dir = dir.join("cb-plain");
    let out = flexmodes(&[
        "export",
        "--body",
        body,
        "--method",
        "cb",
        "--modes",
        "6",
        "--residual-vectors",
        "off",
        "--out",
        plain_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plain: serde_json::Value =
        serde_json::from_slice(&std::fs::read(plain_dir.join("model.json")).unwrap()).unwrap();
    assert_eq!(plain["size"], 18);
    assert!((plain["reduced_elastic_hz"][0].as_f64().unwrap() - cb).abs() <= 1e-8 * cb);
}

/// The App. B slab's body file and matrices copied into a fresh folder.
fn app_b_slab_on_disk(tag: &str) -> crate::scratch::Scratch {
    let dir = temp_dir(tag);
    for f in ["body.toml", "k.mtx", "m.mtx", "nodes.csv", "edges.csv"] {
        let bytes = flexmodes::assets::get(&format!("bodies/app-b-slab/{f}")).unwrap();
        std::fs::write(dir.join(f), bytes).unwrap();
    }
    dir
}

#[test]
fn a_broken_body_file_writes_nothing_and_misplaced_body_options_are_refused() {
    let dir = app_b_slab_on_disk("broken-body");
    let body = dir.join("body.toml");
    let body = body.to_str().unwrap();
    // A broken body file: exit 1, the file and line on stderr, nothing written.
    std::fs::write(
        dir.join("k.mtx"),
        "%%MatrixMarket matrix coordinate real symmetric\n90 90 1\n91 1 1.0\n",
    )
    .unwrap();
    let bad_out = dir.join("never");
    let out = flexmodes(&[
        "export",
        "--body",
        body,
        "--method",
        "cb",
        "--out",
        bad_out.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("k.mtx:3") && err.contains("(91, 1)"), "{err}");
    assert!(!bad_out.exists());
    // --body on a thesis scene, and a set name without a body.
    let out = flexmodes(&["report", "slab-modes", "--body", "builtin:l-bracket"]);
    assert_eq!(out.status.code(), Some(1));
    let out = flexmodes(&["report", "slab-modes", "--boundary", "bottom_corners"]);
    assert_eq!(out.status.code(), Some(2), "a usage error");
    assert!(String::from_utf8_lossy(&out.stderr).contains("node set names need --body"));
}

#[test]
fn export_bench_times_the_whole_process_and_says_when_the_peer_cannot_run() {
    let v = json(&[
        "bench",
        "--body",
        "builtin:l-bracket",
        "--boundary",
        "bolt_hole",
        "--modes",
        "6",
        "--repeats",
        "2",
        "--peer",
        "/nonexistent/peers_body_cb.py",
        "--json",
    ]);
    assert_eq!(v["bench"], "export");
    let runs = v["flexmodes_s"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert!(runs.iter().all(|s| s.as_f64().unwrap() > 0.0));
    // The frequencies the timed export wrote: ten elastic ones, ascending.
    let hz: Vec<f64> = v["flexmodes_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_f64().unwrap())
        .collect();
    assert_eq!(hz.len(), 10);
    assert!(
        hz.windows(2).all(|w| w[0] <= w[1]) && hz[0] > 1000.0,
        "{hz:?}"
    );
    assert!(v["peer"].is_null());
    assert!(
        v["peer_skipped"]
            .as_str()
            .unwrap()
            .contains("/nonexistent/peers_body_cb.py")
    );
}

#[test]
fn export_macneal_rubin_of_an_external_body() {
    // Free-interface modes and residual flexibility: 6 + 10 + 660 columns; the reduced model
    // holds the kept free-free modes, so its frequencies are SciPy's full-body ones.
    let body = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/bodies/steel-link");
    let scratch = temp_dir("mr");
    let out = scratch.join("out");
    let run = flexmodes(&[
        "export",
        "--body",
        &format!("{body}/body.toml"),
        "--method",
        "mr",
        "--boundary",
        "bore_a",
        "--modes",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("model.json")).unwrap()).unwrap();
    assert_eq!(model["size"], 676);
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{body}/reference.json")).unwrap())
            .unwrap();
    let full = reference["free_free_hz"].as_array().unwrap();
    let got = model["reduced_elastic_hz"].as_array().unwrap();
    assert!(got.len() >= 10 && full.len() >= 16);
    for k in 0..10 {
        let (a, b) = (got[k].as_f64().unwrap(), full[6 + k].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-7 * b, "mode {k}: {a} vs {b}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `convert` writes a Harwell–Boeing body with its DOF map as a node-major Matrix Market body
/// that imports like the twin the generator wrote (same mass, frequencies, node sets, units);
/// the flanged hub keeps its mm–t–s units.
#[test]
fn convert_writes_what_was_read_as_a_matrix_market_body() {
    let dir = temp_dir("convert");
    let hb = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/hb-bar/body-hb.toml"
    );
    let twin = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/bodies/hb-bar/body.toml");
    let out = flexmodes(&["convert", hb, "--out", dir.to_str().unwrap(), "--compress"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let converted = json(&["import", dir.join("body.toml").to_str().unwrap(), "--json"]);
    let original = json(&["import", twin, "--json"]);
    for key in [
        "total_mass",
        "zero_energy_modes",
        "node_sets",
        "units",
        "dofs",
    ] {
        assert_eq!(converted[key], original[key], "{key}");
    }
    let (a, b) = (
        converted["lowest_elastic_hz"].as_array().unwrap(),
        original["lowest_elastic_hz"].as_array().unwrap(),
    );
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
        assert!((x - y).abs() < 1e-9 * y, "{x} against {y}");
    }
    let hub = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/flange-hub/body.toml"
    );
    let dir = temp_dir("convert-hub");
    let out = flexmodes(&["convert", hub, "--out", dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("body.toml")).unwrap();
    assert!(
        text.contains("length = \"mm\"") && text.contains("mass = \"t\""),
        "{text}"
    );
}

/// Bad requests of the carrying-out commands are named errors with a failing exit code and
/// leave nothing behind: an Exudyn export without a rigid interface for its frame, and OP4 as
/// an output format.
#[test]
fn carrying_out_refuses_by_name_and_writes_nothing() {
    let scratch = temp_dir("refused-exudyn");
    let dir = scratch.join("out");
    let rod = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-rod/body.toml"
    );
    let out = flexmodes(&[
        "export",
        "--body",
        rod,
        "--method",
        "cb",
        "--boundary",
        "end_a",
        "--modes",
        "4",
        "--out",
        dir.to_str().unwrap(),
        "--exudyn",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("cannot export for Exudyn"),
        "{stderr}"
    );
    assert!(!dir.exists());
    let out = flexmodes(&[
        "convert",
        rod,
        "--out",
        dir.to_str().unwrap(),
        "--format",
        "op4",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("OP4 is read, not written"),
        "{stderr}"
    );
    assert!(!dir.exists());
}
