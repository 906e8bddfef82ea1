//! The desktop explorer's panel driven headless with egui_kittest (feature `gui`): controls
//! recompute on the worker, results replace the recording, errors keep the last good one.
#![cfg(feature = "gui")]

use std::time::{Duration, Instant};

use egui_kittest::{Harness, kittest::Queryable};
use flexmodes::{
    gui::{Controls, Explorer},
    record::RecordingDigest,
    reduction::Method,
    scenes::SceneId,
};
use rerun::external::egui::{self, accesskit::Role};

/// The explorer's panel with `controls`, applying its commands after each frame.
fn harness_with(controls: Controls) -> Harness<'static, Explorer> {
    Harness::new_ui_state(
        |ui: &mut egui::Ui, e: &mut Explorer| {
            e.poll();
            let commands = e.panel_ui(ui);
            e.apply(commands);
        },
        Explorer::new(controls),
    )
}

fn harness(scene: &str) -> Harness<'static, Explorer> {
    harness_with(Controls::for_scene(scene.parse().unwrap()))
}

/// The explorer's panel on the `modes` scene of body file `body`.
fn body_harness(body: &str) -> Harness<'static, Explorer> {
    harness_with(Controls::for_body(body).unwrap())
}

/// Steps frames until the worker is done (the UI never blocks on it).
fn settle(h: &mut Harness<'static, Explorer>) {
    let start = Instant::now();
    loop {
        h.step();
        if !h.state().is_computing() {
            h.step();
            return;
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "computation did not finish"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn paths(h: &Harness<'static, Explorer>) -> Vec<String> {
    h.state().current.as_ref().unwrap().entity_paths.clone()
}

/// `poll()`'s first `Some`, polled every millisecond until `limit_s` seconds after `start`;
/// fails naming `what` it waited for.
fn wait_for<T>(what: &str, start: Instant, limit_s: u64, mut poll: impl FnMut() -> Option<T>) -> T {
    loop {
        if let Some(v) = poll() {
            return v;
        }
        assert!(
            start.elapsed() < Duration::from_secs(limit_s),
            "waited {limit_s} s for {what}"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// The worker's next finished request, polled until `limit_s` seconds after `start`.
fn next_result(
    w: &flexmodes::gui::Worker,
    start: Instant,
    limit_s: u64,
) -> flexmodes::gui::Finished {
    wait_for("a result", start, limit_s, || w.poll())
}

/// slab-sim1 with the full model alone over `end_time` s: slow enough to be caught running.
fn full_model_sim1(end_time: f64) -> flexmodes::scenes::SceneOptions {
    flexmodes::scenes::SceneOptions {
        methods: Some(vec![flexmodes::reduction::Method::NoReduction]),
        end_time: Some(end_time),
        ..Default::default()
    }
}

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
    assert!(err.contains("K_ii is singular"), "{err}");
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

#[test]
fn a_body_file_opens_with_its_node_sets_as_interface_choices() {
    let mut h = body_harness("builtin:app-b-slab");
    settle(&mut h);
    assert_eq!(h.state().controls.scene, SceneId::Modes);
    let report = &h.state().current.as_ref().unwrap().report;
    // The body file's default interface: the four bottom corners.
    assert_eq!(
        report.parameters["boundary"],
        serde_json::json!([16, 18, 28, 30])
    );
    // Its node sets are offered; picking one recomputes on it. Nodes 5 and 11 alone leave the
    // rotation about their line free: the error is shown, the last recording stays.
    h.get_by_label("guyan_extra").click();
    settle(&mut h);
    assert_eq!(h.state().controls.boundary, "guyan_extra");
    let error = h.state().error.clone().expect("a singular interface");
    assert!(error.contains("K_ii is singular"), "{error}");
    h.get_by_label("top_centre").click();
    settle(&mut h);
    assert!(h.state().error.is_some(), "one node restrains nothing");
    h.get_by_label("bottom_corners").click();
    settle(&mut h);
    assert!(h.state().error.is_none());
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(
        report.parameters["boundary"],
        serde_json::json!([16, 18, 28, 30])
    );
    // The other built-in body; a missing file is an error and the last recording stays.
    h.get_by_label("l-bracket").click();
    settle(&mut h);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.results["dofs"], 1314);
    assert!(h.query_by_label("bolt_hole").is_some());
    // The bolt hole tied to one master node (RBE2): each boundary-based model sees it as six
    // coordinates, Craig–Bampton six plus its kept modes.
    let kept = h.state().controls.modes;
    h.get_by_label("rbe2:bolt_hole").click();
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert_eq!(h.state().controls.boundary, "rbe2:bolt_hole");
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(
        report.results["basis_size"]["cb"],
        6 + kept,
        "{:?}",
        report.results
    );
    assert_eq!(report.results["basis_size"]["gr"], 6);
    assert_eq!(
        report.parameters["rigid_interfaces"][0]["name"],
        "bolt_hole"
    );
    // Every method of a body is offered and ticked; the hole averaged into a master (RBE3)
    // loads the body through it: moment matching computes, the fixed-interface methods say
    // why not.
    for m in ["GR", "MT", "CB", "MC", "MR", "BH", "MM", "BT"] {
        assert!(
            h.query_by_role_and_label(Role::CheckBox, m).is_some(),
            "{m} offered"
        );
        assert!(
            h.state()
                .controls
                .methods
                .contains(&m.to_lowercase().parse::<Method>().unwrap()),
            "{m} ticked"
        );
    }
    h.get_by_label("rbe3:bolt_hole").click();
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(
        report.parameters["averaging_interfaces"][0]["name"],
        "bolt_hole"
    );
    assert!(
        report.results["basis_size"]["mm"].as_u64().unwrap_or(0) > 6,
        "{:?} {:?}",
        h.state().controls.methods,
        report.results
    );
    assert!(report.results["basis_size"].get("cb").is_none());
    let notes = report.results["method_notes"].as_array().unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.as_str().unwrap().starts_with("CB:") && n.as_str().unwrap().contains("rbe3")),
        "{notes:?}"
    );
    h.state_mut().controls.body = Some("/nonexistent/body.toml".into());
    h.state_mut().request();
    h.step();
    let error = h.state().error.clone().unwrap();
    assert!(error.contains("/nonexistent/body.toml"), "{error}");
    assert!(h.state().current.is_some());
}

/// Every scene opens with its default controls (including those without method choices: the
/// failures scene runs with fixed settings), shows a recording and no error, and its views'
/// tab titles fit the explorer's viewer at 1 280 × 800 (by the layout's estimate of title
/// widths).
#[test]
fn every_scene_opens_with_its_default_controls_and_its_titles_fit() {
    let mut cut = Vec::new();
    for id in flexmodes::scenes::all_ids() {
        let mut h = harness(id.as_str());
        settle(&mut h);
        assert!(h.state().error.is_none(), "{id}: {:?}", h.state().error);
        assert!(!paths(&h).is_empty(), "{id}: the recording has no entities");
        let layout = &h.state().current.as_ref().unwrap().blueprint.layout;
        for t in layout.cut_titles(flexmodes::gui::VIEWER_AREA) {
            cut.push(format!("{id}: {t}"));
        }
    }
    assert!(cut.is_empty(), "tab titles cut at 1 280 × 800: {cut:#?}");
}

#[test]
fn the_explorer_anticipates_one_mode_more_or_fewer_and_unticked_methods() {
    let mut c = Controls::for_scene(SceneId::SlabSim1);
    c.methods.retain(|&m| m != Method::ModalTruncation);
    let modes = c.modes;
    assert!(modes > 0);
    let next = Explorer::new(c.clone()).likely_next();
    assert_eq!(next.len(), 3, "{next:?}");
    assert!(
        next.iter()
            .any(|n| n.modes == modes + 1 && n.methods == c.methods)
    );
    assert!(
        next.iter()
            .any(|n| n.modes == modes - 1 && n.methods == c.methods)
    );
    assert!(next.iter().any(|n| n.modes == modes
        && n.methods.len() == c.methods.len() + 1
        && n.methods.contains(&Method::ModalTruncation)));
    // Everything else stays as the user set it.
    for n in &next {
        assert_eq!(
            (&n.scene, &n.boundary, n.end_time),
            (&c.scene, &c.boundary, c.end_time)
        );
    }
    // Mode scenes integrate nothing: nothing to anticipate.
    let modes_scene = Explorer::new(Controls::for_scene(SceneId::BeamModes));
    assert!(modes_scene.likely_next().is_empty());
}

#[test]
fn an_anticipated_request_is_served_from_the_cache() {
    use flexmodes::{gui::Worker, reduction::Method, scenes::SceneOptions};
    let mut w = Worker::new();
    let options = SceneOptions {
        methods: Some(vec![Method::CraigBampton]),
        modes: Some(4),
        end_time: Some(0.1),
        ..Default::default()
    };
    w.anticipate(SceneId::SlabSim1, vec![options.clone()]);
    let start = Instant::now();
    wait_for("the anticipation", start, 120, || {
        (w.anticipated() >= 1).then_some(())
    });
    let cached = w.cached();
    assert!(cached > 0, "the anticipation kept its integration");
    let request = w.submit(1, SceneId::SlabSim1, options);
    let finished = next_result(&w, Instant::now(), 120);
    assert!(finished.result.is_ok());
    assert_eq!(w.cached(), cached, "no new cache entry");
    // The request's own progress saw no integration start: CB came from the cache.
    let started = request.reading().map_or(0, |r| r.simulations);
    assert_eq!(started, 0, "the request integrated anew");
}

#[test]
fn a_request_stops_a_running_anticipation() {
    use flexmodes::{gui::Worker, scenes::SceneOptions};
    let mut w = Worker::new();
    w.anticipate(
        SceneId::SlabSim1,
        vec![full_model_sim1(20.0), full_model_sim1(20.0)],
    );
    let start = Instant::now();
    let running = wait_for("a running anticipation", start, 120, || {
        w.anticipation()
            .filter(|p| p.reading().is_some_and(|r| r.time > 0.0))
    });
    w.submit(1, SceneId::BeamModes, SceneOptions::default());
    assert!(running.is_cancelled());
    assert!(next_result(&w, start, 120).result.is_ok());
    // The anticipating thread stops at the cancelled integration's next output step and
    // starts nothing else: neither request ran to its end.
    wait_for("the anticipation to stop", Instant::now(), 30, || {
        w.anticipation().is_none().then_some(())
    });
    assert_eq!(w.anticipated(), 0);
    assert!(running.reading().unwrap().time < 20.0);
}

/// An imported body offers every method in the explorer, as the CLI does, and all eight are
/// computed when ticked (the L-bracket, a body from a body file).
#[test]
fn an_imported_body_offers_and_computes_every_method() {
    let mut h = body_harness("builtin:l-bracket");
    settle(&mut h);
    for id in ["GR", "MT", "CB", "MC", "MR", "BH", "MM", "BT"] {
        assert!(
            h.query_all_by_label(id).next().is_some(),
            "no control for {id}"
        );
    }
    let report = &h.state().current.as_ref().unwrap().report;
    let methods: Vec<String> = report.parameters["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap().to_string())
        .collect();
    assert_eq!(methods, ["gr", "mt", "cb", "mc", "mr", "bh", "mm", "bt"]);
    let reduced = report.results["reduced_hz"].as_object().unwrap();
    assert_eq!(reduced.len(), 8, "{:?}", reduced.keys().collect::<Vec<_>>());
}

/// The recording shown after `switches` applied one after the other (each waited for), and
/// the digest of a fresh explorer's recording of the final controls.
fn switched_and_fresh(
    controls: Controls,
    switches: &[flexmodes::gui::Change],
) -> (RecordingDigest, RecordingDigest, Controls) {
    let mut h = harness_with(controls);
    settle(&mut h);
    let first = RecordingDigest::of(&h.state().current.as_ref().unwrap().messages);
    for change in switches {
        h.state_mut()
            .apply(vec![flexmodes::gui::Command::Set(change.clone())]);
        settle(&mut h);
        assert!(
            h.state().error.is_none(),
            "{change:?}: {:?}",
            h.state().error
        );
    }
    let last = h.state().controls.clone();
    let switched = RecordingDigest::of(&h.state().current.as_ref().unwrap().messages);
    let mut fresh = harness_with(last.clone());
    settle(&mut fresh);
    let fresh = RecordingDigest::of(&fresh.state().current.as_ref().unwrap().messages);
    // The switches changed the recording: the comparison can fail.
    assert!(
        first.difference(&fresh, &[]).is_some(),
        "{switches:?} changed nothing"
    );
    (switched, fresh, last)
}

/// After a sequence of switches (methods unticked and ticked, modes changed, axes changed),
/// the recording shown holds exactly the entities of a fresh recording of the final
/// selection, with the same contents (the wall times of the text, of the report and of the
/// speed–accuracy chart apart), and its layout is the fresh one's: a removed method leaves no entity, view
/// or tab behind, and integrations served from the cache equal integrations run anew.
#[test]
fn after_any_switches_the_recording_equals_a_fresh_one() {
    use flexmodes::{dynamics::AxisKind, gui::Change, reduction::Method};
    let timed = ["/scene", "/report", "/metrics/speed_accuracy"];
    let cases: Vec<(Controls, Vec<Change>, Option<&str>)> = vec![
        (
            Controls::for_scene(SceneId::SlabSim1),
            vec![
                Change::Method(Method::Guyan, false),
                Change::Modes(5),
                Change::Method(Method::Guyan, true),
                Change::Method(Method::ModalTruncation, false),
                Change::Axes(Some(AxisKind::Mean)),
                Change::Modes(6),
            ],
            Some("mt"),
        ),
        (
            Controls::for_scene(SceneId::SlabModes),
            vec![
                Change::Method(Method::CraigBampton, false),
                Change::Modes(3),
                Change::Method(Method::Guyan, false),
                Change::Method(Method::CraigBampton, true),
            ],
            Some("gr"),
        ),
        (
            Controls::for_body("builtin:l-bracket").unwrap(),
            vec![
                Change::Method(Method::MacNealRubin, false),
                Change::Boundary("rbe2:bolt_hole".into()),
                Change::Method(Method::BenfieldHruda, false),
                Change::Modes(6),
            ],
            None,
        ),
    ];
    for (controls, switches, removed) in cases {
        let scene = controls.scene;
        let (switched, fresh, last) = switched_and_fresh(controls, &switches);
        if let Some(d) = switched.difference(&fresh, &timed) {
            panic!("{scene} after {switches:?} ({last:?}): {d}");
        }
        assert!(!switched.recording.is_empty() && !switched.blueprint.is_empty());
        if let Some(m) = removed {
            let left: Vec<&str> = switched
                .entities()
                .into_iter()
                .filter(|p| p.split('/').any(|part| part == m))
                .collect();
            assert!(left.is_empty(), "{scene}: {m} left {left:?}");
        }
    }
}

#[test]
fn the_persisted_controls_name_methods_and_integrator_by_id_and_read_older_settings() {
    let mut c = Controls::for_scene(SceneId::SlabSim1);
    c.methods = vec![Method::CraigBampton, Method::ModeCondensation];
    c.integrator = Some("gen-alpha".parse().unwrap());
    let text = serde_json::to_string(&c).unwrap();
    assert!(text.contains(r#""methods":["cb","mc"]"#), "{text}");
    assert!(text.contains(r#""integrator":"gen-alpha""#), "{text}");
    assert_eq!(serde_json::from_str::<Controls>(&text).unwrap(), c);
    // Earlier versions wrote the defaults as empty strings.
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["integrator"] = "".into();
    value["body"] = "".into();
    let older: Controls = serde_json::from_value(value.clone()).unwrap();
    assert_eq!((older.integrator, older.body), (None, None));
    // An id no version wrote is refused (the explorer then starts from the defaults).
    value["methods"] = serde_json::json!(["cb", "xx"]);
    assert!(serde_json::from_value::<Controls>(value).is_err());
}

/// The table's rows without the columns that are timings (offline s, online s and their
/// ratio, found by their titles), for comparing two runs of the same study.
fn untimed_rows(table: &str) -> Vec<String> {
    let cells = |l: &str| -> Vec<String> { l.split('|').map(|c| c.trim().to_string()).collect() };
    let mut lines = table.lines().filter(|l| l.starts_with("| "));
    let header = cells(lines.next().expect("a header row"));
    let timed: Vec<usize> = ["offline s", "online s", "NR online / online"]
        .iter()
        .map(|t| header.iter().position(|h| h == t).expect("a timing column"))
        .collect();
    lines
        .map(|l| {
            cells(l)
                .into_iter()
                .enumerate()
                .filter(|(k, _)| !timed.contains(k))
                .map(|(_, c)| c)
                .collect::<Vec<_>>()
                .join("|")
        })
        .collect()
}

/// A user's body driven from the panel: the committed steel link (6 972 DOF, two bores) spun
/// up by one bore, the full body against the reduced models; the recording is the one
/// `flexmodes simulate --save` writes for the same choices, a method ticked on joins the runs
/// already made, and unticking `simulate` asks for the body's modes again.
#[test]
fn the_explorer_simulates_a_users_body_from_its_panel() {
    use flexmodes::{
        Progress,
        body_file::ImportedBody,
        scenes::{RunCache, body_simulation::simulated},
    };
    let link = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bodies/steel-link/body.toml"
    );
    // The body's modes by Craig–Bampton alone first (all eight methods on 6 972 DOF would
    // only lengthen the test).
    let mut h = harness_with(Controls {
        methods: vec![Method::CraigBampton],
        ..Controls::for_body(link).unwrap()
    });
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert_eq!(h.state().current.as_ref().unwrap().report.scene, "modes");
    h.get_by_label("simulate: drive an interface").click();
    h.step();
    h.step();
    // The body file's default interface is the drive; the interval shortened at once (the
    // second-long run the click started is superseded).
    let simulation = h.state().controls.simulation.clone().expect("simulating");
    assert_eq!(simulation.drive, "bore_a");
    assert_eq!(h.state().save_path, "simulate.rrd");
    h.get_by_label("100 ms").click();
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let shown = h.state().current.as_ref().unwrap();
    assert_eq!(shown.report.scene, "simulate");
    let methods = h.state().controls.methods.clone();
    assert_eq!(methods, [Method::CraigBampton, Method::ModeCondensation]);
    for lane in ["nr", "cb_10", "mc_10"] {
        let path = format!("world/body/{lane}/deformed");
        assert!(shown.entity_paths.contains(&path), "{path} missing");
    }
    assert!(!paths(&h).iter().any(|p| p.starts_with("world/body/mt")));
    // The same study on the command line's path (nothing kept between runs).
    let simulation = h.state().controls.simulation.clone().unwrap();
    assert_eq!(simulation.end, 0.1);
    let body = ImportedBody::load(link).unwrap();
    let alone = simulated(
        &body,
        &simulation.simulation().unwrap(),
        (&methods, h.state().controls.modes),
        &Progress::new(),
        &RunCache::default(),
        1,
    )
    .unwrap();
    let rows = untimed_rows(&shown.report.table);
    assert_eq!(rows.len(), 3, "{}", shown.report.table);
    assert_eq!(rows, untimed_rows(&alone.report.table));
    // The speed–accuracy chart's labels follow the timings; every other entity is the same.
    let untimed = |paths: Vec<String>| -> Vec<String> {
        paths
            .into_iter()
            .filter(|p| !p.starts_with("bench/error_vs_online"))
            .collect()
    };
    let alone_paths = alone.visuals.iter().map(|v| v.path().to_string()).collect();
    assert_eq!(untimed(shown.entity_paths.clone()), untimed(alone_paths));
    // Modal truncation ticked on: its run joins the ones already made (the full body's
    // history unchanged, to the digit).
    h.get_by_label("MT").click();
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let now = untimed_rows(&h.state().current.as_ref().unwrap().report.table);
    assert_eq!(now.len(), 4);
    assert_eq!(now[0], rows[0], "the full body's row");
    assert!(now.iter().any(|r| r.starts_with("|MT 10|")), "{now:?}");
    assert!(paths(&h).contains(&"world/body/mt_10/deformed".to_string()));
    // A method that cannot hold the driven ring is not offered while simulating.
    assert!(h.query_by_role_and_label(Role::CheckBox, "MM").is_none());
    // Guyan keeps nothing but interfaces: with the other bore kept (tied rigidly, free in the
    // simulation) it runs beside CB; the full body's run is the one already made.
    h.get_by_label("MT").click();
    settle(&mut h);
    h.get_by_label("MC").click();
    settle(&mut h);
    h.get_by_role_and_label(Role::CheckBox, "rbe2:bore_b")
        .click();
    settle(&mut h);
    h.get_by_label("GR").click();
    settle(&mut h);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert_eq!(
        h.state().controls.simulation.as_ref().unwrap().kept,
        ["bore_b"]
    );
    let kept = untimed_rows(&h.state().current.as_ref().unwrap().report.table);
    assert_eq!(kept.len(), 3, "{kept:?}");
    assert_eq!(kept[0], rows[0], "the full body's row");
    assert!(kept.iter().any(|r| r.starts_with("|GR|")), "{kept:?}");
    // Unticked, the body's modes are asked for again with every method offered (their
    // recomputation, seen above, is not waited for).
    h.get_by_label("simulate: drive an interface").click();
    h.step();
    h.step();
    assert!(h.state().controls.simulation.is_none());
    assert!(h.state().is_computing());
    assert!(h.query_by_role_and_label(Role::CheckBox, "MM").is_some());
}

/// The panel's simulation choices are `flexmodes simulate`'s defaults; a blank drive or a
/// value that is not positive is a named error.
#[test]
fn the_simulation_controls_are_simulates_defaults_and_bad_values_are_named() {
    use flexmodes::{
        gui::{DriveMotion, SimulationControls},
        models::DrivenBodyParameters,
    };
    let c = SimulationControls::for_drive("bore_a");
    let s = c.simulation().unwrap();
    let d = DrivenBodyParameters::default();
    assert_eq!(s.parameters.drive, "rbe2:bore_a");
    assert_eq!((s.parameters.rate, s.parameters.ramp), (d.rate, d.ramp));
    assert_eq!(s.parameters.integration, d.integration);
    assert!(s.parameters.shake.is_none() && s.full_body);
    let shaken = SimulationControls {
        motion: DriveMotion::Shake,
        end: 0.25,
        ..c.clone()
    }
    .simulation()
    .unwrap();
    assert_eq!(shaken.parameters.rate, 0.0);
    // Kept interfaces become the reduced models' rigid interfaces; the drive is never one.
    let kept = SimulationControls {
        kept: vec!["bore_b".into(), "bore_a".into()],
        ..c.clone()
    }
    .simulation()
    .unwrap();
    assert_eq!(kept.parameters.boundary, ["rbe2:bore_b"]);
    assert!(s.parameters.boundary.is_empty());
    assert_eq!(shaken.parameters.shake, Some(([1.0, 0.0, 0.0], 1e-3, 50.0)));
    assert_eq!(shaken.parameters.integration.output_every, 2);
    for bad in [
        SimulationControls {
            drive: " ".into(),
            ..c.clone()
        },
        SimulationControls {
            end: 0.0,
            ..c.clone()
        },
        SimulationControls {
            rate: f64::NAN,
            ..c.clone()
        },
    ] {
        let e = bad.simulation().unwrap_err().to_string();
        assert!(e.starts_with("invalid simulate in scene `modes`"), "{e}");
    }
}

/// A recording of `controls` as the explorer hands it to the viewer: messages (the recording
/// `suffix`, its layout as the default blueprint) and what that blueprint holds.
fn offer_of(controls: &Controls, suffix: &str) -> flexmodes::gui::Offer {
    let out = flexmodes::scenes::get(controls.scene)
        .execute(&controls.options().unwrap())
        .unwrap();
    let recorder = flexmodes::record::Recorder {
        recording_suffix: Some(suffix.into()),
        default_blueprint_only: true,
        viewer_area: Some(flexmodes::gui::VIEWER_AREA),
    };
    flexmodes::gui::Offer {
        messages: recorder.messages(&out).unwrap(),
        blueprint: recorder.blueprint_key(&out),
    }
}

/// A switch keeps what the user made of the layout (views resized, moved, hidden, a camera
/// turned: the active blueprint) when the new recording has the same views and what each
/// shows lies within its framing, and replaces it with the new layout otherwise (other views,
/// or contents a kept camera would not show).
#[test]
fn a_switch_keeps_the_users_layout_when_the_views_are_the_same() {
    use rerun::external::{
        re_log_channel::{LogSource, log_channel},
        re_viewer::external::re_viewer_context::{SystemCommand, command_channel},
    };
    let (tx, rx) = log_channel(LogSource::Sdk);
    let (commands, received) = command_channel();
    // Not atomic (no screenshots headless), layouts kept as the atomic explorer keeps them.
    let mut handoff = flexmodes::gui::ViewerHandoff::new(tx, commands, false).keeping_layouts(true);
    let ctx = egui::Context::default();
    // Offers a recording, lets the "viewer" take every message in, and returns whether the
    // switch to it cleared the active layout.
    let mut switch_to = |offer: flexmodes::gui::Offer| -> bool {
        let messages = offer.messages.len();
        handoff.offer(&ctx, offer);
        let mut taken = 0;
        while rx.try_recv().is_ok() {
            taken += 1;
        }
        assert_eq!(taken, messages, "every message reaches the viewer");
        assert!(
            handoff.step(&ctx),
            "the recording is shown once all of it is in"
        );
        let mut cleared = false;
        while let Some((_, command)) = received.recv_system() {
            cleared |= matches!(command, SystemCommand::ClearActiveBlueprint);
        }
        cleared
    };
    let slab = Controls::for_scene(SceneId::SlabModes);
    let mut without_mt = slab.clone();
    without_mt.methods.retain(|&m| m != Method::ModalTruncation);
    let mut more = without_mt.clone();
    more.modes += 1;
    let (first, method_switch) = (offer_of(&slab, "1"), offer_of(&without_mt, "2"));
    let modes_switch = offer_of(&more, "3");
    let key = |o: &flexmodes::gui::Offer| o.blueprint.clone();
    assert!(
        key(&first).frames(&key(&method_switch)),
        "MT unticked changes no view of slab-modes and nothing they frame"
    );
    assert_eq!(key(&first).layout, key(&modes_switch).layout);
    assert!(
        !key(&method_switch).frames(&key(&modes_switch)),
        "a seventh fixed-interface mode is drawn in a new row, beyond the view's framing"
    );
    assert!(switch_to(first), "the first recording brings its layout");
    assert!(
        !switch_to(method_switch),
        "the same views framing the same: the user's arrangement of them stays"
    );
    assert!(
        switch_to(modes_switch),
        "contents beyond the framing: the new layout frames them"
    );
    let beam = offer_of(&Controls::for_scene(SceneId::BeamModes), "4");
    assert!(
        switch_to(beam),
        "other views: the new layout replaces the active one"
    );
}
