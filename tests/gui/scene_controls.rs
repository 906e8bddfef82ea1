//! A scene's controls recompute on the worker: methods, modes, the boundary, the mesh, the end
//! time, the integrator and the stiffening; newer requests cancel running ones.

use std::time::{Duration, Instant};

use egui_kittest::kittest::Queryable;
use flexmodes::{reduction::Method, scenes::SceneId};
use rerun::external::egui::accesskit::Role;

use super::{full_model_sim1, harness, next_result, paths, settle, wait_for};

#[test]
fn toggling_a_method_and_changing_modes_recompute_the_recording() {
    let mut h = harness("beam-profiles");
    settle(&mut h);
    assert!(paths(&h).iter().any(|p| p == "profiles/profile1/cb"));
    // The panel shows the table: profile 1 errors of CB and MC, 0.0826 as published.
    assert_eq!(h.query_all_by_label("0.0826").count(), 2);

    h.get_by_role_and_label(Role::CheckBox, "CB").click();
    h.step();
    assert!(h.state().is_computing(), "the click starts a computation");
    settle(&mut h);
    let p = paths(&h);
    assert!(!p.iter().any(|p| p.ends_with("/cb")), "CB removed: {p:?}");
    assert!(p.iter().any(|p| p == "profiles/profile1/mc"));

    h.get_by_label("more modes").click();
    settle(&mut h);
    assert_eq!(h.state().controls.modes, 3);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["modes"], 3);
    let e = report
        .result("profile2_error.mc")
        .unwrap()
        .as_f64()
        .unwrap();
    // The new number is on the panel (formatted as in the table).
    assert!(h.query_all_by_label(&format!("{e:.4}")).count() >= 1);
    assert!((e - 0.0612).abs() > 1e-4, "three modes change the fit");
    assert!(h.state().error.is_none());
}

#[test]
fn a_singular_boundary_is_shown_and_the_last_recording_kept() {
    let mut h = harness("slab-modes");
    settle(&mut h);
    let before = h.state().current.as_ref().unwrap().report.clone();
    h.state_mut().edits.boundary = "16".into();
    h.get_by_label("apply boundary").click();
    settle(&mut h);
    let err = h.state().error.clone().expect("an error is shown");
    assert!(err.to_string().contains("K_ii is singular"), "{err}");
    h.get_by_label_contains("K_ii is singular");
    h.get_by_label("the last good recording stays on screen");
    assert_eq!(h.state().current.as_ref().unwrap().report, before);

    h.get_by_label("reset boundary").click();
    settle(&mut h);
    assert!(h.state().error.is_none());
    assert_eq!(h.state().controls.boundary, "16,18,28,30");
}

#[test]
fn a_newer_request_abandons_a_running_reduction_at_its_next_phase() {
    use flexmodes::{gui::Worker, scenes::SceneOptions};
    let mut w = Worker::new();
    // A refined slab (6 825 DOF) goes through assembly, factorisation, constraint modes,
    // eigensolve, the other methods and the free-free modes; a worker that ran requests in
    // order would finish all of them before the newer request's result.
    let slow = SceneOptions {
        refine: Some([24, 12, 6]),
        ..Default::default()
    };
    let first = w.submit(1, SceneId::SlabModes, slow);
    let start = Instant::now();
    let at_cancel = wait_for("a phase", start, 120, || first.phase_reading());
    let second = w.submit(2, SceneId::BeamModes, SceneOptions::default());
    assert!(first.is_cancelled() && !second.is_cancelled());
    let finished = next_result(&w, start, 300);
    assert_eq!(
        finished.generation, 2,
        "the abandoned request reports nothing"
    );
    assert!(finished.result.is_ok());
    // The first request stopped at the phase boundary after the cancel (a cancel that lands
    // between a boundary's check and its start lets one more phase begin).
    let last = first.phase_reading().unwrap();
    assert!(
        last.number <= at_cancel.number + 1,
        "ran on from phase {} ({}) to {} ({})",
        at_cancel.number,
        at_cancel.name,
        last.number,
        last.name
    );
    assert_ne!(last.name, "free-free modes");
}

#[test]
fn the_slab_mesh_is_a_control_and_long_reductions_show_their_phase() {
    let mut h = harness("slab-modes");
    settle(&mut h);
    assert_eq!(h.state().controls.refine, vec![4, 2, 1]);
    h.get_by_label("mesh").click();
    // Let the popup finish opening so the items are where they will be clicked.
    for _ in 0..10 {
        h.step();
    }
    h.get_by_label("24×12×6 (6825 DOF)").click();
    let start = Instant::now();
    let mut phases = Vec::new();
    while h.state().is_computing() || phases.is_empty() {
        h.step();
        if let Some(node) = h.query_by_label_contains("phase ") {
            let text = format!("{node:?}");
            if !phases.contains(&text) {
                phases.push(text);
            }
        }
        assert!(start.elapsed() < Duration::from_secs(300), "no result");
        std::thread::sleep(Duration::from_millis(2));
    }
    settle(&mut h);
    assert!(
        !phases.is_empty(),
        "a phase was shown while the reduction ran"
    );
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["refine"], serde_json::json!([24, 12, 6]));
    assert_eq!(report.result("dofs").unwrap(), 6825);
    // The App. B node numbers do not apply to the refined mesh: the bottom corners do.
    assert_eq!(report.parameters["boundary"].as_array().unwrap().len(), 4);
}

#[test]
fn save_writes_a_recording() {
    let mut h = harness("beam-eitelberg");
    settle(&mut h);
    let path = std::env::temp_dir().join(format!("flexmodes-gui-{}.rrd", std::process::id()));
    h.state_mut().save_path = path.display().to_string();
    h.get_by_label("save .rrd").click();
    h.step();
    let bytes = std::fs::read(&path).unwrap();
    assert!(bytes.starts_with(b"RRF"));
    let _ = std::fs::remove_file(path);
}

#[test]
fn the_end_time_of_a_simulation_can_be_changed() {
    let mut h = harness("slab-sim1");
    h.state_mut().controls.methods = vec![Method::CraigBampton];
    h.state_mut().controls.end_time = 0.5;
    h.get_by_label("shorter").click();
    settle(&mut h);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["end_time_s"], 0.25);
    assert!(paths(&h).iter().any(|p| p == "plots/node8/delta_zeta/cb"));
    // The drawn deflection: automatic first, then doubled from it by the panel.
    let auto = report.results["deformation_scale"].as_f64().unwrap();
    assert!(auto >= 1.0);
    h.get_by_label("×2").click();
    settle(&mut h);
    assert_eq!(h.state().controls.deformation_scale, 2.0 * auto);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(
        report.results["deformation_scale"].as_f64(),
        Some(2.0 * auto)
    );
    h.get_by_label("auto").click();
    settle(&mut h);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.results["deformation_scale"].as_f64(), Some(auto));
}

#[test]
fn the_integrator_of_a_simulation_is_a_control() {
    let mut h = harness("slab-sim1");
    h.state_mut().controls.methods = vec![Method::CraigBampton];
    h.state_mut().controls.end_time = 0.25;
    h.get_by_label("gen-alpha").click();
    settle(&mut h);
    assert_eq!(
        h.state().controls.integrator.map(|s| s.id()),
        Some("gen-alpha")
    );
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["integrator"], "gen-alpha");
    assert_eq!(report.parameters["dt_s"].as_f64(), Some(0.001));
    h.get_by_label("dp5").click();
    settle(&mut h);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["integrator"], "dp5");
    // Both integrations are kept, and the panel says so with their weight (the count may
    // grow meanwhile: the explorer anticipates the next click).
    let kept = h.state().anticipation_counts().1;
    assert!(kept >= 2, "{kept}");
    h.get_by_label_contains(" integration(s) kept, ");
    // A scene without a simulation offers no integrator.
    let h = harness("slab-modes");
    assert!(h.query_by_label("gen-alpha").is_none());
}

#[test]
fn the_dynamic_stiffening_of_a_slab_simulation_is_a_control() {
    let mut h = harness("slab-sim2");
    h.state_mut().controls.methods = vec![Method::CraigBampton];
    h.state_mut().controls.end_time = 0.25;
    h.get_by_label("dynamic stiffening").click();
    settle(&mut h);
    assert!(h.state().controls.stiffening);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["stiffening"], true);
    h.get_by_label("dynamic stiffening").click();
    settle(&mut h);
    assert!(!h.state().controls.stiffening);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["stiffening"], false);
    // A scene that takes no stiffening offers no switch.
    let h = harness("slab-modes");
    assert!(h.query_by_label("dynamic stiffening").is_none());
}

#[test]
fn a_newer_request_cancels_a_running_simulation() {
    use flexmodes::{gui::Worker, scenes::SceneOptions};
    let mut w = Worker::new();
    let first = w.submit(1, SceneId::SlabSim1, full_model_sim1(1.0));
    let start = Instant::now();
    wait_for("progress", start, 120, || {
        first.reading().filter(|r| r.time > 0.0)
    });
    let second = w.submit(2, SceneId::BeamModes, SceneOptions::default());
    assert!(first.is_cancelled() && !second.is_cancelled());
    let finished = next_result(&w, start, 120);
    // The cancelled request reports nothing; the full-order run stopped short of its end.
    assert_eq!(finished.generation, 2);
    assert!(finished.result.is_ok());
    let r = first.reading().unwrap();
    assert!(r.time < 1.0, "{r:?}");
}

#[test]
fn a_running_simulation_shows_its_simulated_time() {
    let mut h = harness("slab-sim1");
    h.state_mut().controls.methods = vec![Method::NoReduction];
    // Longer than the scene's default (whose run the first request may have cached), and long
    // enough that a frame of a loaded machine sees it running: the full model's 8 s.
    h.state_mut().controls.end_time = 8.0;
    h.get_by_label("more modes").click();
    let start = Instant::now();
    loop {
        h.step();
        if h.query_by_label_contains("simulation 1: t = ").is_some() {
            break;
        }
        assert!(
            h.state().is_computing(),
            "finished before any progress showed"
        );
        assert!(start.elapsed() < Duration::from_secs(120), "no progress");
        std::thread::sleep(Duration::from_millis(2));
    }
    settle(&mut h);
    assert!(h.query_by_label_contains("simulation 1: t = ").is_none());
}
