//! `bench`: speed against accuracy, sizes, threads and eigensolvers, measured in one run.

use crate::common::{flexmodes, json, temp_dir};

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
    points.iter().for_each(point_is_complete);
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
    stability_is_checked(&v, points.len());
    assert_eq!(flexmodes(&["bench", "beam-modes"]).status.code(), Some(1));
}

/// A bench point's costs, error, size and Pareto flag are all there.
fn point_is_complete(p: &serde_json::Value) {
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

/// Every predicted critical step of the bench `v` (of `points` points) is checked: bounded 10 %
/// below it, diverged at 3×, and the full model's the smallest.
fn stability_is_checked(v: &serde_json::Value, points: usize) {
    // Every predicted critical step is checked: bounded 10 % below it, diverged at 3×.
    let stability = v["stability"].as_object().unwrap();
    assert_eq!(3 * stability.len(), points);
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
