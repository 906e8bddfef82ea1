//! Scenes from the command line: `list`, `report`, `record`, usage errors and exit codes.

use crate::SCENES;
use crate::common::{flexmodes, json, temp_dir};

#[test]
fn list_names_every_scene() {
    // The list above is the registry's, whole: a scene added must be added here too.
    let mut registry: Vec<&str> = flexmodes::scenes::SceneId::ALL
        .iter()
        .map(|id| id.as_str())
        .collect();
    let mut listed = SCENES.to_vec();
    registry.sort_unstable();
    listed.sort_unstable();
    assert_eq!(listed, registry);
    let out = flexmodes(&["list"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for id in SCENES {
        assert!(
            text.lines().any(|l| l.starts_with(id)),
            "{id} missing:\n{text}"
        );
    }
    // The summaries start in one column, whatever the length of the id.
    let columns: Vec<usize> = text
        .lines()
        .map(|l| {
            let id = l.split_whitespace().next().unwrap();
            id.len() + l[id.len()..].find(|c: char| c != ' ').unwrap()
        })
        .collect();
    assert!(
        columns.windows(2).all(|w| w[0] == w[1]),
        "{columns:?}\n{text}"
    );
}

#[test]
fn report_beam_modes_with_boundary_1_4_5() {
    let v = json(&["report", "beam-modes", "--boundary", "1,4,5", "--json"]);
    assert_eq!(v["scene"], "beam-modes");
    assert_eq!(v["parameters"]["boundary"], serde_json::json!([1, 4, 5]));
    let g = v["results"]["guyan_c_hz"].as_array().unwrap();
    let fi = v["results"]["fixed_interface_hz"].as_array().unwrap();
    // Three nodes, six DOF: three rigid and three elastic Guyan modes; four interior DOF.
    assert_eq!(g.len(), 3);
    assert_eq!(fi.len(), 4);
}

#[test]
fn report_slab_modes_with_boundary_and_modes() {
    let v = json(&[
        "report",
        "slab-modes",
        "--boundary",
        "1,13,16,28",
        "--modes",
        "4",
        "--json",
    ]);
    let r = &v["results"];
    let count = |x: &serde_json::Value| x.as_array().map_or(0, Vec::len);
    // 90 DOF, four boundary nodes (12 DOF), four kept modes: every elastic free-free mode
    // (90 - 6 rigid), every fixed-interface mode (90 - 12), and the elastic modes of each
    // reduced model: CB and MC 12 + 4 - 6 rigid, Guyan 18 masters (App. B's nodes 5 and 11
    // added) - 6, modal truncation's 16 columns none of which is a rigid motion.
    assert_eq!(count(&r["free_free_hz"]), 84);
    assert_eq!(count(&r["fixed_interface_hz"]), 78);
    for (m, elastic) in [("mt", 16), ("cb", 10), ("mc", 10), ("gr", 12)] {
        assert_eq!(count(&r["reduced_hz"][m]), elastic, "{m}");
    }
    assert_eq!(r["basis_size"]["cb"], serde_json::json!([90, 16]));
    assert_eq!(v["parameters"]["modes"], 4);
}

#[test]
fn errors_exit_1_with_the_cause_and_usage_errors_exit_2() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["report", "beam-modes", "--boundary", "1,9"],
            "node 9 is out of range",
        ),
        (
            &["report", "slab-modes", "--boundary", "16"],
            "K_ii is singular",
        ),
        (
            &["report", "beam-modes", "--modes", "9"],
            "9 normal modes requested",
        ),
        (
            &["report", "beam-modes", "--axes", "mean"],
            "unknown or unsupported axis type",
        ),
        (
            &["report", "slab-sim1", "--end-time=0"],
            "end time 0 s must lie in (0, 60] s",
        ),
    ];
    for (args, msg) in cases {
        let out = flexmodes(args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(
            err.starts_with("error: ") && err.contains(msg),
            "{args:?}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    }
    // A scene id is checked as the arguments are parsed: a usage error that names the known
    // scenes.
    let out = flexmodes(&["report", "no-such-scene"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("unknown scene `no-such-scene`") && err.contains("slab-mode-sets"),
        "{err}"
    );
    for args in [
        &["report"][..],
        &["report", "beam-modes", "--method", "xx"],
        &["report", "slab-sim1", "--axes", "tilted"],
        &["report", "beam-modes", "--boundary", "a"],
        &["frobnicate"],
    ] {
        assert_eq!(flexmodes(args).status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn record_writes_every_scene_and_failures_write_nothing() {
    let dir = temp_dir("record");
    let out = flexmodes(&[
        "record",
        "--all",
        "--timings",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // --timings: one row per scene on stderr, costliest first, wall = computing + writing.
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains(&format!("record timings: {} scene(s) on ", SCENES.len())),
        "{stderr}"
    );
    let rows: Vec<(String, f64, f64, f64)> = stderr
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| scene"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let number = |i: usize| {
                cells[i]
                    .parse::<f64>()
                    .unwrap_or_else(|e| panic!("{l}: {e}"))
            };
            (cells[1].to_string(), number(2), number(3), number(4))
        })
        .collect();
    assert_eq!(rows.len(), SCENES.len(), "{stderr}");
    for id in SCENES {
        assert!(rows.iter().any(|r| r.0 == id), "{id} timed: {stderr}");
    }
    for (id, wall, computing, writing) in &rows {
        // Each printed to 0.01 s: the sum agrees within the rounding of three numbers.
        assert!(
            (wall - computing - writing).abs() <= 0.016,
            "{id}: {wall} = {computing} + {writing}"
        );
    }
    assert!(
        rows.windows(2).all(|w| w[0].1 >= w[1].1),
        "sorted by cost: {stderr}"
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    for id in SCENES {
        let f = dir.join(format!("{id}.rrd"));
        let bytes = std::fs::read(&f).unwrap();
        assert!(bytes.starts_with(b"RRF"), "{id}: not an rrd stream");
        assert!(
            stdout.contains(&format!("# {id}")),
            "result table of {id} printed"
        );
    }
    // Every recording's report against the committed baseline (tests/data/reports): a wall
    // time missing from report_diff::TIMING_KEYS differs from the baseline's run to run and
    // is caught here. At 1e-6 above 1e-8, not CI's 1e-12: another CPU's vector kernels round
    // residuals and defects differently, and this is the README's test command.
    let baseline = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/reports");
    let diff = flexmodes(&[
        "diff",
        baseline,
        dir.to_str().unwrap(),
        "--rtol",
        "1e-6",
        "--floor",
        "1e-8",
    ]);
    assert!(
        diff.status.success(),
        "{}{}",
        String::from_utf8_lossy(&diff.stdout),
        String::from_utf8_lossy(&diff.stderr)
    );
}

#[test]
fn a_failing_record_keeps_the_old_file_and_a_typo_writes_nothing() {
    let dir = temp_dir("record-fails");
    // A failing run leaves an existing file untouched and no temporary file behind.
    let target = dir.join("keep.rrd");
    std::fs::write(&target, b"previous").unwrap();
    let out = flexmodes(&[
        "record",
        "slab-modes",
        "--boundary",
        "16",
        "--save",
        target.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read(&target).unwrap(), b"previous");
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
    // A typo among several scenes fails before anything is written.
    let dir2 = temp_dir("typo");
    let out = flexmodes(&[
        "record",
        "beam-modes",
        "nope",
        "--out",
        dir2.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(&dir2).unwrap().count(), 0);
}

#[test]
fn report_dynamic_scenes_json() {
    let v = json(&["report", "slab-sim1", "--method", "nr,cb", "--json"]);
    // --method nr,cb: exactly the two methods; NR is the reference the errors are taken
    // against, CB's error is small (0.024-0.034 in the thesis' ranking of simulation 1).
    let methods: Vec<&String> = v["results"]["rel_rms_error"]
        .as_object()
        .unwrap()
        .keys()
        .collect();
    assert_eq!(methods, ["cb", "nr"]);
    for d in ["xi", "eta", "zeta"] {
        let e = v["results"]["rel_rms_error"]["cb"][d].as_f64().unwrap();
        assert!(e > 0.01 && e < 0.05, "{d}: {e}");
    }
    assert!(v["results"]["wall_time_s"]["cb"].as_f64().unwrap() > 0.0);
    let v = json(&["report", "plank-symmetry", "--method", "cb", "--json"]);
    let d = v["results"]["max_symmetry_defect_m"]["cb_mean"]
        .as_f64()
        .unwrap();
    assert!(d < 1e-6, "{d}");
    let v = json(&["report", "beam-mean-axes", "--json"]);
    assert_eq!(
        v["results"]["constraint_modes"].as_array().unwrap().len(),
        10
    );
    assert_eq!(v["results"]["normal_hz"].as_array().unwrap().len(), 2);
}

#[test]
fn the_integrator_is_chosen_per_run() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "report",
            "slab-sim1",
            "--method",
            "nr,cb",
            "--end-time",
            "0.5",
        ];
        args.extend_from_slice(extra);
        args.push("--json");
        json(&args)
    };
    let explicit = run(&[]);
    assert_eq!(explicit["parameters"]["integrator"], "dp5");
    assert!(explicit["parameters"]["dt_s"].is_null());
    let implicit = run(&[
        "--integrator",
        "gen-alpha",
        "--dt",
        "0.00025",
        "--rho-inf",
        "0.9",
    ]);
    assert_eq!(implicit["parameters"]["integrator"], "gen-alpha");
    assert_eq!(implicit["parameters"]["dt_s"].as_f64(), Some(0.00025));
    assert_eq!(implicit["parameters"]["rho_inf"].as_f64(), Some(0.9));
    // One reduction error whichever scheme integrates it (second order at 0.25 ms).
    for d in ["xi", "eta", "zeta"] {
        let a = explicit["results"]["rel_rms_error"]["cb"][d]
            .as_f64()
            .unwrap();
        let b = implicit["results"]["rel_rms_error"]["cb"][d]
            .as_f64()
            .unwrap();
        assert!((a - b).abs() <= 0.02 * a, "{d}: dp5 {a}, gen-alpha {b}");
    }
    // Bad choices: an unknown scheme and ρ∞ with dp5 are usage errors; a step out of range
    // and the integrator of a scene without simulation are named errors.
    for (args, code, says) in [
        (
            vec!["report", "slab-sim1", "--integrator", "rk4"],
            2,
            "unknown integrator",
        ),
        (
            vec![
                "report",
                "slab-sim1",
                "--integrator",
                "dp5",
                "--rho-inf",
                "0.5",
            ],
            2,
            "--rho-inf",
        ),
        (
            vec!["report", "slab-sim1", "--dt", "0"],
            1,
            "step 0 s must lie in",
        ),
        (
            vec![
                "report",
                "slab-sim1",
                "--integrator",
                "gen-alpha",
                "--rho-inf",
                "1.5",
            ],
            1,
            "spectral radius",
        ),
        (
            vec!["report", "slab-modes", "--integrator", "gen-alpha"],
            1,
            "it applies to slab-sim1, slab-sim2, slab-sim3, plank-symmetry",
        ),
    ] {
        let out = flexmodes(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    }
}
