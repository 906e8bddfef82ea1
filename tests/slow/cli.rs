//! The slow half of `tests/cli.rs`: `report modes`, `export` and `bench modes` on the committed
//! external bodies, each a whole reduction of a 7 k–10 k-DOF part by the debug binary.

use super::cli_common::{flexmodes, json, nalgebra_hz, temp_dir};

#[test]
fn report_modes_reduces_an_external_bodys_interface() {
    // The steel link's 220-node bore (660 DOF) reduced to 12 characteristic constraint modes:
    // CB has 12 + 10 coordinates and SciPy's frequencies (rbe2_reference.py --ccm); GR keeps
    // 12 shapes; the sweep ends at plain CB, its error never rising as shapes are added.
    let body = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/bodies/steel-link");
    let v = json(&[
        "report",
        "modes",
        "--body",
        &format!("{body}/body.toml"),
        "--boundary",
        "bore_a",
        "--modes",
        "10",
        "--interface-modes",
        "12",
        "--json",
    ]);
    let r = &v["results"];
    assert_eq!(r["basis_size"]["cb"], 22);
    assert_eq!(r["basis_size"]["gr"], 12);
    let reference: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(format!("{body}/ccm_reference.json")).unwrap(),
    )
    .unwrap();
    let case = reference["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["interface_modes"] == 12)
        .unwrap();
    let expected: Vec<f64> = case["hz"].as_array().unwrap()[6..]
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let cb: Vec<f64> = r["reduced_hz"]["cb"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(cb.len(), expected.len());
    for (a, b) in cb.iter().zip(&expected) {
        // The report prints nine significant digits.
        assert!((a - b).abs() <= 1e-8 * b, "{a} vs {b}");
    }
    let sweep = r["interface_reduction"].as_array().unwrap();
    assert_eq!(sweep.len(), 7, "6 … 192 shapes, then all 660");
    assert_eq!(sweep.last().unwrap()["size"], 670);
    let errors: Vec<f64> = sweep
        .iter()
        .map(|p| p["max_rel_error"].as_f64().unwrap())
        .collect();
    for w in errors.windows(2) {
        assert!(w[1] <= w[0] * (1.0 + 1e-6), "{errors:?}");
    }
}

#[test]
fn report_modes_pairs_the_full_bodys_modes_by_mac() {
    // MacNeal–Rubin keeps the free-free modes themselves: MAC 1 to round-off. Craig–Bampton
    // with ten fixed-interface modes on the bore represents them closely but not exactly.
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-link/body.toml"
    );
    let v = json(&[
        "report",
        "modes",
        "--body",
        body,
        "--boundary",
        "bore_a",
        "--method",
        "cb,mr",
        "--json",
    ]);
    let mac = |m: &str| -> Vec<f64> {
        v["results"]["mac"][m]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (mr, cb) = (mac("mr"), mac("cb"));
    assert_eq!(mr.len(), 6);
    assert_eq!(cb.len(), 6);
    assert!(mr.iter().all(|&m| (1.0 - m).abs() < 1e-8), "{mr:?}");
    assert!(cb.iter().all(|&m| m > 0.99 && m <= 1.0 + 1e-12), "{cb:?}");
    assert!(
        cb.iter().any(|&m| m < 1.0 - 1e-4),
        "CB is not exact: {cb:?}"
    );
}

#[test]
fn report_modes_compares_interface_responses_over_a_band() {
    // The link's bore tied to a master: moment matching with 36 columns reproduces the full
    // body's interface response (sparse LDLᵀ per frequency) to 1e-6 over 0–16 kHz, BH's free
    // modes alone do not; --band belongs to the body scene only.
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-link/body.toml"
    );
    let v = json(&[
        "report",
        "modes",
        "--body",
        body,
        "--boundary",
        "rbe2:bore_a",
        "--method",
        "mm,bh",
        "--modes",
        "36",
        "--band",
        "16000",
        "--json",
    ]);
    let r = &v["results"]["interface_response"];
    let hz = r["hz"].as_array().unwrap();
    assert!(hz.len() >= 20 && hz.len() <= 24, "{hz:?}");
    let mm = r["rel_error"]["mm"].as_f64().unwrap();
    let bh = r["rel_error"]["bh"].as_f64().unwrap();
    assert!(mm < 1e-6, "MM {mm:e}");
    assert!(bh > 1e-3, "BH {bh:e}");
    let out = flexmodes(&["report", "slab-modes", "--band", "100"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--band"));
}

#[test]
fn export_every_load_built_method_of_an_external_body() {
    // Benfield–Hruda (a body alone: its free-interface modes), moment matching and balanced
    // truncation on the hub's bore tied to a master (mm–t–s): each printed frequency equals
    // nalgebra's on the written K_r, M_r to 1e-8, after exactly six zero-energy modes; BH's
    // equal SciPy's free-free ones.
    let body = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/bodies/flange-hub");
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{body}/reference.json")).unwrap())
            .unwrap();
    let scipy: Vec<f64> = reference["free_free_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    for (method, size) in [("bh", 16), ("mm", 18), ("bt", 16)] {
        let out = temp_dir(&format!("export-{method}"));
        let run = flexmodes(&[
            "export",
            "--body",
            &format!("{body}/body.toml"),
            "--method",
            method,
            "--boundary",
            "rbe2:bore",
            "--modes",
            "10",
            "--out",
            out.join("model").to_str().unwrap(),
        ]);
        assert!(
            run.status.success(),
            "{method}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        let dir = out.join("model");
        let model: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("model.json")).unwrap())
                .unwrap();
        assert_eq!(model["size"], size, "{method}");
        assert_eq!(model["reduced_zero_energy_modes"], 6, "{method}");
        let printed: Vec<f64> = model["reduced_elastic_hz"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(printed.len(), size - 6, "{method}");
        let lapack = nalgebra_hz(&dir);
        assert_eq!(lapack.len(), size);
        for (k, (a, b)) in printed.iter().zip(&lapack[6..]).enumerate() {
            assert!((a - b).abs() <= 1e-8 * b, "{method} mode {k}: {a} vs {b}");
        }
        if method == "bh" {
            for (k, (a, b)) in printed.iter().zip(&scipy[6..]).enumerate() {
                assert!((a - b).abs() <= 1e-7 * b, "bh mode {k}: {a} vs SciPy {b}");
            }
        }
        std::fs::remove_dir_all(&out).unwrap();
    }
}

/// The bench's `advice` names, per method, the smallest measured model of `points` within its
/// tolerance (1 %), or none when none is.
fn advice_is_the_smallest_within(advice: &serde_json::Value, points: &[serde_json::Value]) {
    let error = |p: &serde_json::Value| p["freq_rel_error"].as_f64().unwrap_or(f64::INFINITY);
    assert_eq!(advice["tolerance"], 0.01);
    for a in advice["smallest"].as_array().unwrap() {
        let m = a["method"].as_str().unwrap();
        let within: Vec<_> = points
            .iter()
            .filter(|p| p["method"] == m && error(p) <= 0.01)
            .collect();
        match a["coordinates"].as_u64() {
            Some(c) => {
                let smallest = within
                    .iter()
                    .map(|p| p["coordinates"].as_u64().unwrap())
                    .min()
                    .unwrap();
                assert_eq!(c, smallest, "{m}");
            }
            None => assert!(within.is_empty(), "{m}: {within:?}"),
        }
    }
}

#[test]
fn bench_modes_charts_every_method_on_an_external_body() {
    let body = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/bodies/steel-link");
    let out = temp_dir("bench-body");
    let rrd = out.join("bench.rrd");
    let v = json(&[
        "bench",
        "modes",
        "--body",
        &format!("{body}/body.toml"),
        "--boundary",
        "rbe2:bore_a",
        "--modes",
        "4,8",
        "--band",
        "16000",
        "--json",
        "--save",
        rrd.to_str().unwrap(),
    ]);
    // The full body's modes up to 16 kHz: SciPy's six lowest elastic ones (15.55 kHz is the
    // sixth, 16.78 kHz the seventh).
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(format!("{body}/reference.json")).unwrap())
            .unwrap();
    let scipy = reference["free_free_hz"].as_array().unwrap();
    let hz = v["reference"]["hz"].as_array().unwrap();
    assert_eq!(hz.len(), 6);
    for (a, b) in hz.iter().zip(&scipy[6..12]) {
        let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
        assert!((a - b).abs() <= 1e-8 * b, "{a} vs {b}");
    }
    // GR once, six methods at two counts; MacNeal–Rubin refused by name on a rigid interface.
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 1 + 6 * 2);
    let refused = v["not_applicable"].as_array().unwrap();
    assert_eq!(refused.len(), 1);
    assert_eq!(refused[0]["method"], "mr");
    let point = |m: &str, k: u64| {
        points
            .iter()
            .find(|p| p["method"] == m && p["modes"] == k)
            .unwrap_or_else(|| panic!("{m} {k}"))
    };
    for (m, k, size) in [
        ("gr", 0, 6),
        ("cb", 4, 10),
        ("cb", 8, 14),
        ("bh", 8, 14),
        ("mm", 4, 12),
        ("mm", 8, 18),
        ("bt", 8, 14),
    ] {
        assert_eq!(point(m, k)["coordinates"], size, "{m} {k}");
    }
    // A body alone: BH keeps its free-free modes, exact to round-off; CB with 4 modes has
    // only 4 elastic modes for 6 compared: no error, not on the front.
    assert!(point("bh", 8)["freq_rel_error"].as_f64().unwrap() < 1e-7);
    assert!(point("bh", 8)["min_mac"].as_f64().unwrap() > 0.9999);
    assert!(point("cb", 4)["freq_rel_error"].is_null());
    assert_eq!(point("cb", 4)["pareto"], false);
    // The front: no point both cheaper and more accurate than one on it.
    let cost = |p: &serde_json::Value| p["offline_s"].as_f64().unwrap();
    let error = |p: &serde_json::Value| p["freq_rel_error"].as_f64().unwrap_or(f64::INFINITY);
    let front: Vec<_> = points.iter().filter(|p| p["pareto"] == true).collect();
    assert!(!front.is_empty());
    for f in &front {
        assert!(
            !points
                .iter()
                .any(|p| cost(p) < cost(f) && error(p) < error(f) * (1.0 - 1e-3)),
            "{f} is dominated"
        );
    }
    // The advice names, per method, the smallest measured model within the tolerance.
    advice_is_the_smallest_within(&v["advice"], points);
    // With a band every model's interface response is compared with the full body's.
    for p in points {
        for key in ["frf_rel_error", "static_rel_error"] {
            let e = p[key].as_f64().unwrap_or(f64::NAN);
            assert!(e.is_finite() && e >= 0.0, "{key}: {p}");
        }
    }
    assert_eq!(&std::fs::read(&rrd).unwrap()[..3], b"RRF");
    std::fs::remove_dir_all(&out).unwrap();
}
