//! `simulate` and `campbell`: a user's body driven and spun from the command line.

use crate::common::{flexmodes, json, temp_dir};

/// `simulate` on the committed rod: the full body and CB, MC run one spin-up; the JSON has a
/// history per model sampled at the same times, CB and MC agree to round-off, and a motion it
/// does not know is a usage error naming the known one.
#[test]
fn simulate_runs_the_full_body_and_its_reductions_alike() {
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-rod/body.toml"
    );
    let v = json(&[
        "simulate",
        "--body",
        body,
        "--drive",
        "rbe2:end_a",
        "--method",
        "nr,cb,mc",
        "--modes",
        "10",
        "--end",
        "0.04",
        "--ramp",
        "0.04",
        "--dt",
        "1e-3",
        "--samples",
        "8",
        "--json",
    ]);
    let times = v["times"].as_array().unwrap();
    assert_eq!(times.len(), 9, "t = 0 and eight samples");
    let runs = v["runs"].as_array().unwrap();
    let models: Vec<&str> = runs.iter().map(|r| r["model"].as_str().unwrap()).collect();
    assert_eq!(models, ["NR", "CB 10", "MC 10"]);
    for r in runs {
        assert_eq!(r["outputs"][0].as_array().unwrap().len(), times.len());
        assert_eq!(r["reaction"].as_array().unwrap().len(), times.len());
    }
    assert!(runs[0]["history_error"].is_null());
    let (cb, mc) = (&runs[1], &runs[2]);
    let e = cb["history_error"].as_f64().unwrap();
    assert!(e < 1e-3, "CB 10 against NR: {e}");
    let diff = (e - mc["history_error"].as_f64().unwrap()).abs();
    assert!(diff < 1e-8, "CB and MC: {diff}");
    let (a, b) = (
        cb["lowest_hz"].as_f64().unwrap(),
        mc["lowest_hz"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-8 * a, "lowest Hz: CB {a}, MC {b}");

    let out = flexmodes(&[
        "simulate",
        "--body",
        body,
        "--drive",
        "rbe2:end_a",
        "--motion",
        "orbit",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("spin-up"));
}

/// `bench simulate` on the rod: one point with the factor's size, GMRES iterations per step
/// and CB's history error against the full body; without --drive it is refused by name.
#[test]
fn bench_simulate_times_the_full_body_per_step() {
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-rod/body.toml"
    );
    let v = json(&[
        "bench",
        "simulate",
        "--body",
        body,
        "--drive",
        "rbe2:end_a",
        "--json",
    ]);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 1);
    let p = &points[0];
    assert_eq!(p["dof"], 3702);
    assert_eq!(p["free"], 3702 - 3 * 76, "the ring's 76 nodes clamped");
    assert!(p["factor_nnz"].as_u64().unwrap() > 3702);
    let its = p["gmres_iterations_per_step"].as_f64().unwrap();
    assert!((1.0..20.0).contains(&its), "{its}");
    assert!(p["cb_history_error"].as_f64().unwrap() < 1e-2);
    assert!(v["nr_time_exponent"].is_null(), "one size fits no exponent");

    let out = flexmodes(&["bench", "simulate", "--body", body]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--drive"));
}

/// A part whose mass holds entries where its stiffness holds none (scikit-fem's structured
/// mesh, eyes carved: 16 k of 173 k mass entries): the full body's effective matrix and the
/// free-free solve both work on the union of the patterns (once, the first panicked in faer
/// and the second stalled at 4.6e-6).
#[test]
fn simulate_and_import_a_part_whose_mass_pattern_exceeds_its_stiffness() {
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/skfem-eyebar-mm/body.toml"
    );
    let summary = json(&["import", body, "--json"]);
    assert_eq!(summary["zero_energy_modes"], 6);
    assert_eq!(summary["missed_modes"], 0);
    let v = json(&[
        "simulate",
        "--body",
        body,
        "--drive",
        "rbe2:eye_a",
        "--method",
        "nr,cb",
        "--modes",
        "4",
        "--end",
        "0.004",
        "--ramp",
        "0.004",
        "--dt",
        "1e-3",
        "--samples",
        "4",
        "--json",
    ]);
    let models: Vec<&str> = v["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["model"].as_str().unwrap())
        .collect();
    assert_eq!(models, ["NR", "CB 4"]);
}

/// A spinning part from the command line: `campbell` prints its frequencies against the spin
/// with the [preload]'s stiffening (CalculiX's own at 1 000 rad/s, 636.314 Hz, to its printed
/// digits) and says when it is off; `simulate` says which; `export` writes the geometric
/// stiffness per unit rate² projected on Ψ (kg_r.mtx, named in model.json) unless told not to.
#[test]
fn a_spinning_part_from_the_command_line() {
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/bodies/spun-lever/body.toml"
    );
    let v = json(&[
        "campbell",
        "--body",
        body,
        "--drive",
        "rbe2:root",
        "--rates",
        "0,1000",
        "--method",
        "nr",
        "--count",
        "2",
        "--json",
    ]);
    assert_eq!(v["stiffening"], "on");
    let first = v["curves"][0]["hz"][1][0].as_f64().unwrap();
    assert!((first - 636.3141).abs() < 2e-4 * 636.3141, "{first}");
    let off = json(&[
        "campbell",
        "--body",
        body,
        "--drive",
        "rbe2:root",
        "--rates",
        "1000",
        "--method",
        "nr",
        "--count",
        "1",
        "--stiffening",
        "off",
        "--json",
    ]);
    assert_eq!(off["stiffening"], "off");
    assert!(off["curves"][0]["hz"][0][0].as_f64().unwrap() < 0.99 * first);
    let sim = flexmodes(&[
        "simulate",
        "--body",
        body,
        "--drive",
        "rbe2:root",
        "--rate",
        "1000",
        "--ramp",
        "0.005",
        "--end",
        "0.005",
        "--dt",
        "1e-4",
        "--method",
        "nr,cb",
        "--modes",
        "4",
    ]);
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    let text = String::from_utf8_lossy(&sim.stdout);
    assert!(text.contains("Dynamic stiffening: on"), "{text}");
}

#[test]
fn a_spun_parts_export_carries_its_preload_stiffness_when_asked() {
    let body = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/bodies/spun-lever/body.toml"
    );
    let scratch = temp_dir("spun-export");
    for (flag, written) in [("on", true), ("off", false)] {
        let out = scratch.join(flag);
        let run = flexmodes(&[
            "export",
            "--body",
            body,
            "--method",
            "cb",
            "--boundary",
            "rbe2:root",
            "--modes",
            "6",
            "--out",
            out.to_str().unwrap(),
            "--stiffening",
            flag,
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert_eq!(out.join("kg_r.mtx").exists(), written);
        let model: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("model.json")).unwrap())
                .unwrap();
        assert_eq!(
            model["stiffening"].is_object(),
            written,
            "{}",
            model["stiffening"]
        );
        if written {
            assert_eq!(model["stiffening"]["preload_rate_rad_s"], 1000.0);
            assert_eq!(model["stiffening"]["held_dofs"], 27);
        }
    }
}
