//! The command line as users and CI run it: exit codes, JSON keys, atomic writes.

#[path = "common/cli.rs"]
#[allow(dead_code)]
mod common;
#[path = "common/scratch.rs"]
mod scratch;

use common::{flexmodes, json, temp_dir};

const SCENES: [&str; 15] = [
    "beam-modes",
    "slab-modes",
    "beam-profiles",
    "beam-eitelberg",
    "slab-sim1",
    "slab-sim2",
    "slab-sim3",
    "plank-symmetry",
    "beam-mean-axes",
    "failures",
    "modes",
    "slab-mode-sets",
    "cantilever-variants",
    "spin-up",
    "amls",
];

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
            "apply to the simulations only",
        ),
    ] {
        let out = flexmodes(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    }
}

#[test]
fn bench_reports_speed_and_accuracy_points() {
    let dir = temp_dir("bench-charts");
    let charts = dir.join("bench.rrd");
    let v = json(&[
        "bench",
        "--json",
        "--repeats",
        "1",
        "--save",
        charts.to_str().unwrap(),
    ]);
    // The charts: error against cost and against kept modes, written whole.
    let bytes = std::fs::read(&charts).expect("bench --save writes the recording");
    assert!(bytes.len() > 10_000, "{} bytes", bytes.len());
    assert_eq!(&bytes[..4], b"RRF2", "a Rerun file");
    assert_eq!(v["scene"], "slab-sim1");
    assert_eq!(v["dofs"], 90);
    let points = v["points"].as_array().unwrap();
    assert!(points.len() >= 10);
    for p in points {
        for key in [
            "offline_s",
            "online_s_per_sim_s",
            "rel_rms_error",
            "dofs",
            "modes",
        ] {
            assert!(p[key].is_number(), "{key} in {p}");
        }
        assert!(p["pareto"].is_boolean(), "{p}");
    }
    // Every point with three settings: Dormand-Prince at the scenes' tolerance and at the
    // loose one, and generalized-alpha.
    let scene_rtol = flexmodes::dynamics::IntegratorParameters::default().rtol;
    let loose_rtol = flexmodes::bench::LOOSE_RTOL;
    let setting = |p: &serde_json::Value| (p["integrator"].clone(), p["rtol"].as_f64());
    for (scheme, rtol) in [
        ("dp5", Some(scene_rtol)),
        ("dp5", Some(loose_rtol)),
        ("gen-alpha", None),
    ] {
        let n = points
            .iter()
            .filter(|p| setting(p) == (serde_json::json!(scheme), rtol))
            .count();
        assert_eq!(3 * n, points.len(), "{scheme} {rtol:?}");
    }
    // At the loose tolerance the step is no longer set by the error control but by
    // stability: every reduced model then takes fewer steps than the full model, whose stiff
    // modes bound its step (an operation count, not a time).
    let loose_steps = |method: &str, modes: u64| {
        points
            .iter()
            .find(|p| {
                p["method"] == method
                    && p["modes"] == modes
                    && p["rtol"].as_f64() == Some(loose_rtol)
            })
            .and_then(|p| p["steps"].as_u64())
            .unwrap_or_else(|| panic!("{method} {modes}: no loose run"))
    };
    let nr_steps = loose_steps("nr", 0);
    for (method, modes) in [("cb", 6), ("mc", 6), ("cb", 2), ("gr", 0)] {
        let steps = loose_steps(method, modes);
        assert!(
            steps < nr_steps,
            "{method} {modes}: {steps} against NR's {nr_steps}"
        );
    }
    // The Pareto flags agree with the points' own cost and error (errors equal to three
    // significant digits count as equal: CB and MC differ by round-off only); the rule itself
    // is tested on hand-made fronts in bench::pareto.
    let three = flexmodes::bench::three_digits;
    let cost_error: Vec<(f64, f64)> = points
        .iter()
        .map(|p| {
            (
                p["online_s_per_sim_s"].as_f64().unwrap(),
                three(p["rel_rms_error"].as_f64().unwrap()),
            )
        })
        .collect();
    let flags = flexmodes::bench::pareto_flags(&cost_error);
    assert_eq!(flags.len(), points.len());
    for (p, flag) in points.iter().zip(flags) {
        assert_eq!(p["pareto"], flag, "{p}");
    }
    // The most accurate point (the reference) is always on the front.
    assert!(points.iter().any(|p| p["pareto"] == true));
    // Accuracy (not speed) may be asserted: Craig-Bampton converges as modes are added.
    let cb: Vec<f64> = points
        .iter()
        .filter(|p| {
            p["method"] == "cb"
                && p["integrator"] == "dp5"
                && p["rtol"].as_f64() == Some(scene_rtol)
        })
        .map(|p| p["rel_rms_error"].as_f64().unwrap())
        .collect();
    assert_eq!(cb.len(), 4);
    assert!(cb.windows(2).all(|w| w[1] < w[0]), "{cb:?}");
    // Every predicted critical step is checked: bounded 10 % below it, diverged at 3×.
    let stability = v["stability"].as_object().unwrap();
    assert_eq!(3 * stability.len(), points.len());
    for (m, s) in stability {
        assert_eq!(s["run_below_ok"], true, "{m}: {s}");
        assert_eq!(s["run_above_diverged"], true, "{m}: {s}");
        // The implicit scheme takes the step that breaks the explicit one.
        assert_eq!(s["implicit_above_bounded"], true, "{m}: {s}");
    }
    // Reduction buys the explicit scheme a larger step: the full model's is the smallest.
    let nr = v["stability"]["nr"]["critical_dt_s"].as_f64().unwrap();
    assert!(
        stability
            .values()
            .all(|s| s["critical_dt_s"].as_f64().unwrap() >= nr)
    );
    for m in ["nr", "gr", "cb_6"] {
        assert!(
            v["stability"][m]["critical_dt_s"].as_f64().unwrap() > 0.0,
            "{m}"
        );
        assert!(
            v["stability"][m]["highest_hz"].as_f64().unwrap() > 0.0,
            "{m}"
        );
    }
    assert_eq!(flexmodes(&["bench", "beam-modes"]).status.code(), Some(1));
}

#[test]
fn refined_slab_report_has_sizes_and_phase_timings() {
    let started = std::time::Instant::now();
    let v = json(&[
        "report",
        "slab-modes",
        "--refine",
        "12,6,3",
        "--modes",
        "8",
        "--json",
    ]);
    let wall_s = started.elapsed().as_secs_f64();
    let r = &v["results"];
    assert_eq!(r["dofs"], 3 * 13 * 7 * 4);
    assert!(r["nnz"].as_u64().unwrap() > 0);
    // The phases' times are seconds of this run: the factorisation, the constraint modes and
    // the eigensolve lie within the reduction's time, and assembly and reduction within the
    // process's wall time (a unit slip, ms for s, or a phase counted twice breaks these).
    let t = |key: &str| {
        let x = r["timing_s"][key].as_f64().unwrap();
        assert!(x.is_finite() && x >= 0.0, "{key}: {x}");
        x
    };
    let phases = t("factorization") + t("constraint_modes") + t("eigen");
    assert!(
        phases <= 1.001 * t("reduction") + 1e-6,
        "phases {phases} s against the reduction's {} s",
        t("reduction")
    );
    assert!(
        t("assembly") + t("reduction") <= wall_s,
        "assembly and reduction within the {wall_s} s the command took"
    );
    assert!(r["peak_memory_bytes"].as_u64().unwrap() > 0);
    let fi = r["fixed_interface_hz"].as_array().unwrap();
    assert_eq!(fi.len(), 20);
    // The four bottom corners of a 12×6×3 mesh (bottom layer numbered last).
    let layer = 13 * 7;
    let corners: Vec<usize> = [0, 6, 12 * 7, 12 * 7 + 6]
        .iter()
        .map(|c| 3 * layer + c + 1)
        .collect();
    assert_eq!(v["parameters"]["boundary"], serde_json::json!(corners));
    // 12 constraint modes + 8 normal modes, 6 of them rigid.
    assert_eq!(r["reduced_hz"]["cb"].as_array().unwrap().len(), 12 + 8 - 6);
    // Usage errors before any work: zero, negative, non-numeric, wrong count.
    for bad in ["0,1,1", "-1,2,2", "a,2,2", "4,2"] {
        let out = flexmodes(&["report", "slab-modes", "--refine", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--refine"), "{bad}: {err}");
    }
    // A mesh larger than the machine: a named error, exit 1.
    let out = flexmodes(&["report", "slab-modes", "--refine", "2000,2000,2000"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("GB"));
    // --refine on another scene.
    let out = flexmodes(&["report", "beam-modes", "--refine", "8,4,2"]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn bench_sizes_writes_the_log_log_chart() {
    let dir = temp_dir("bench-sizes");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("sizes.rrd");
    let v = json(&[
        "bench",
        "slab-modes",
        "--sizes",
        "8x4x2,4x2x1,12x6x3",
        "--json",
        "--save",
        file.to_str().unwrap(),
    ]);
    // Sizes run ascending whatever the order given.
    let points = v["points"].as_array().unwrap();
    let per_point =
        |key: &str| -> Vec<u64> { points.iter().map(|p| p[key].as_u64().unwrap()).collect() };
    let dofs = per_point("dofs");
    assert_eq!(dofs, [90, 405, 1092]);
    for m in ["gr", "mt", "cb", "mc", "mc_complete"] {
        assert_eq!(
            v["offline_s_against_dofs"][m].as_array().unwrap().len(),
            3,
            "{m}"
        );
        assert!(v["growth_exponent"][m].as_f64().is_some(), "{m}");
    }
    // The factor's fill grows with the mesh; 20 fixed-interface frequencies per size.
    let fill = per_point("factor_nnz");
    assert!(fill.windows(2).all(|w| w[1] > w[0]), "{fill:?}");
    for p in points {
        assert_eq!(p["fixed_interface_hz"].as_array().unwrap().len(), 20);
    }
    let bytes = std::fs::read(&file).unwrap();
    assert!(bytes.starts_with(b"RRF"), "an .rrd file");
    // Without --sizes, --save writes the charts of one simulation bench: not of two.
    let out = flexmodes(&[
        "bench",
        "slab-sim1",
        "slab-sim2",
        "--save",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("name one scene"));
}

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
    let dir = temp_dir("body");
    for f in ["body.toml", "k.mtx", "m.mtx", "nodes.csv", "edges.csv"] {
        let bytes = flexmodes::assets::get(&format!("bodies/app-b-slab/{f}")).unwrap();
        std::fs::write(dir.join(f), bytes).unwrap();
    }
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
    let cb = imported[0].as_f64().unwrap();

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
fn bench_slab_modes_reports_offline_cost_against_frequency_and_static_error() {
    let v = json(&["bench", "slab-modes", "--json"]);
    assert_eq!(v["scene"], "slab-modes");
    assert_eq!(v["dofs"], 90);
    let points = v["points"].as_array().unwrap();
    // GR, then MT, CB, MC with 2, 4, 6, 12 kept modes.
    assert_eq!(points.len(), 13);
    let find = |m: &str, k: u64| {
        points
            .iter()
            .find(|p| p["method"] == m && p["modes"] == k)
            .unwrap_or_else(|| panic!("no point {m} {k}"))
    };
    let err = |m: &str, k: u64, key: &str| find(m, k)[key].as_f64().unwrap();
    for p in points {
        for key in ["offline_s", "freq_rel_error", "static_rel_error"] {
            let x = p[key].as_f64().unwrap_or_else(|| panic!("{key} in {p}"));
            assert!(x >= 0.0 && x.is_finite(), "{key} in {p}");
        }
    }
    for k in [2, 4, 6, 12] {
        // One column space: one error.
        for key in ["freq_rel_error", "static_rel_error"] {
            let (cb, mc) = (err("cb", k, key), err("mc", k, key));
            assert!(
                (cb - mc).abs() <= 1e-6 * cb.max(1e-12),
                "{key} {k}: {cb} {mc}"
            );
        }
        // Modal truncation cannot take the support reactions into the body.
        assert!(err("mt", k, "static_rel_error") > 10.0 * err("cb", k, "static_rel_error"));
    }
    // More kept modes: closer frequencies (Rayleigh–Ritz on nested spaces).
    assert!(err("cb", 12, "freq_rel_error") <= err("cb", 6, "freq_rel_error"));
    assert!(err("cb", 6, "freq_rel_error") <= err("cb", 2, "freq_rel_error"));
    // The Pareto flags agree with the points' offline cost and worse error (to three digits).
    let three = flexmodes::bench::three_digits;
    let cost_error: Vec<(f64, f64)> = points
        .iter()
        .map(|p| {
            let e = p["freq_rel_error"]
                .as_f64()
                .unwrap()
                .max(p["static_rel_error"].as_f64().unwrap());
            (p["offline_s"].as_f64().unwrap(), three(e))
        })
        .collect();
    assert!(points.iter().any(|p| p["pareto"] == true));
    let flags = flexmodes::bench::pareto_flags(&cost_error);
    assert_eq!(flags.len(), points.len());
    for (p, flag) in points.iter().zip(flags) {
        assert_eq!(p["pareto"], flag, "{p}");
    }
    // The integrator belongs to the simulation benches.
    let out = flexmodes(&["bench", "slab-modes", "--integrator", "dp5"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("simulation benches"));
}

#[test]
fn bench_simulation_sizes_reports_online_cost_against_dof() {
    let v = json(&["bench", "slab-sim1", "--sizes", "8x4x2,4x2x1", "--json"]);
    assert_eq!(v["scene"], "slab-sim1");
    let sizes = v["sizes"].as_array().unwrap();
    let dofs: Vec<u64> = sizes.iter().map(|s| s["dofs"].as_u64().unwrap()).collect();
    assert_eq!(dofs, [90, 405], "ascending whatever the order given");
    for s in sizes {
        let points = s["points"].as_array().unwrap();
        let of = |m: &str| {
            points
                .iter()
                .find(|p| p["method"] == m)
                .unwrap_or_else(|| panic!("no {m} in {s}"))
        };
        assert_eq!(points.len(), 5);
        // The full model: every DOF but the six the nodal-fixed frame removes; the reference.
        let n = s["dofs"].as_u64().unwrap();
        assert_eq!(of("nr")["coordinates"], n - 6);
        assert_eq!(of("nr")["rel_rms_error"], 0.0);
        // Craig–Bampton keeps its 12 modal coordinates (18 columns less the six the frame
        // removes) whatever the mesh, and beats MT.
        assert_eq!(of("cb")["coordinates"], 12);
        let e = |m: &str| of(m)["rel_rms_error"].as_f64().unwrap();
        assert!(e("cb") > 0.0 && e("cb") < e("mt"), "{s}");
        for p in points {
            assert!(p["online_s_per_sim_s"].as_f64().unwrap() > 0.0, "{p}");
        }
    }
    for m in ["nr", "gr", "mt", "cb", "mc"] {
        assert!(v["online_growth_exponent"][m].is_number(), "{m}");
    }
    let out = flexmodes(&["bench", "slab-sim3", "--sizes", "4x2x1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--sizes times"));
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

/// `--threads 1,2` times each size with each count (the same frequencies either way), and
/// only that bench takes several counts; `export --timings` names the threads it used.
#[test]
fn thread_counts_are_compared_and_reported() {
    let v = json(&[
        "--threads",
        "1,2",
        "bench",
        "slab-modes",
        "--sizes",
        "12x6x3",
        "--repeats",
        "2",
        "--json",
    ]);
    let points = v["points"].as_array().unwrap();
    let threads: Vec<u64> = points
        .iter()
        .map(|p| p["threads"].as_u64().unwrap())
        .collect();
    assert_eq!(threads, [1, 2]);
    assert_eq!(v["repeats"], 2);
    assert_eq!(
        points[0]["fixed_interface_hz"],
        points[1]["fixed_interface_hz"]
    );
    assert!(points[0]["factor_flops"].as_f64().unwrap() > 0.0);
    assert!(v["offline_s_against_dofs"]["cb_2t"].is_array());

    let out = flexmodes(&["--threads", "1,2", "list"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("only `bench slab-modes --sizes`"), "{err}");
    let out = flexmodes(&["--threads", "0", "list"]);
    assert!(!out.status.success(), "zero threads is refused");

    let dir = temp_dir("threads-export");
    let out = flexmodes(&[
        "--threads",
        "1",
        "export",
        "--body",
        "builtin:l-bracket",
        "--method",
        "cb",
        "--modes",
        "4",
        "--timings",
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("1 thread(s)"), "{err}");
    assert!(
        err.contains("factorisation:") && err.contains(" %)"),
        "{err}"
    );
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

/// `import --eigensolver amls` on a committed body written by another FE code gives the
/// frequencies Lanczos gives, says which route made them, and misses none; `bench slab-modes
/// --eigensolver` times both solvers on a slab and finds their eigenvalues equal.
#[test]
fn amls_gives_lanczos_pairs_on_import_and_in_the_bench() {
    let body = "tests/bodies/hb-bar/body.toml";
    let lanczos = json(&["import", body, "--json"]);
    let amls = json(&["import", body, "--json", "--eigensolver", "amls"]);
    assert_eq!(lanczos["eigensolver"], "lanczos");
    assert_eq!(amls["eigensolver"], "amls");
    assert!(lanczos["amls"].is_null());
    assert!(amls["amls"]["reductions"].as_u64().unwrap() >= 1);
    assert_eq!(amls["missed_modes"], 0);
    assert_eq!(amls["zero_energy_modes"], lanczos["zero_energy_modes"]);
    let hz = |v: &serde_json::Value| -> Vec<f64> {
        v["lowest_elastic_hz"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (a, l) = (hz(&amls), hz(&lanczos));
    assert_eq!(a.len(), l.len());
    for (x, y) in a.iter().zip(&l) {
        // Both printed to six significant digits.
        assert!((x - y).abs() <= 1e-5 * y, "{x} against {y}");
    }

    let bench = json(&[
        "bench",
        "slab-modes",
        "--sizes",
        "8x4x2",
        "--eigensolver",
        "lanczos,amls",
        "--pairs",
        "10",
        "--json",
    ]);
    let points = bench["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for p in points {
        assert_eq!(p["sturm_missed"], 0);
        assert!(p["max_residual"].as_f64().unwrap() <= 1e-8);
        assert!(p["eigenvalues_apart"].as_f64().unwrap() <= 1e-9);
    }
    assert_eq!(points[1]["eigensolver"], "amls");
    assert!(points[1]["amls"]["projected"].as_u64().unwrap() >= 16);
    // export: CB's fixed-interface pairs of the L-bracket (1 290 interior DOF, the sparse
    // path) by AMLS equal Lanczos', and model.json names the route.
    let dir = temp_dir("amls-export");
    let mut hz = Vec::new();
    for solver in ["lanczos", "amls"] {
        let out = dir.join(solver);
        let run = flexmodes(&[
            "export",
            "--body",
            "builtin:l-bracket",
            "--method",
            "cb",
            "--boundary",
            "bolt_hole",
            "--modes",
            "6",
            "--eigensolver",
            solver,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let doc: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("model.json")).unwrap()).unwrap();
        assert_eq!(doc["eigensolver"], solver);
        assert_eq!(
            doc["amls_reductions"].as_u64().unwrap() > 0,
            solver == "amls"
        );
        hz.push(doc["reduced_elastic_hz"].as_array().unwrap().clone());
    }
    for (a, l) in hz[1].iter().zip(&hz[0]) {
        let (a, l) = (a.as_f64().unwrap(), l.as_f64().unwrap());
        assert!((a - l).abs() <= 1e-8 * l, "{a} against {l}");
    }
    // --eigensolver times the slab's pairs only.
    let out = flexmodes(&[
        "bench",
        "slab-sim1",
        "--sizes",
        "4x2x1",
        "--eigensolver",
        "amls",
    ]);
    assert_eq!(out.status.code(), Some(1));
}
