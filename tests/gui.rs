//! The desktop explorer's panel driven headless with egui_kittest (feature `gui`): controls
//! recompute on the worker, results replace the recording, errors keep the last good one.
#![cfg(feature = "gui")]

use std::time::{Duration, Instant};

use egui_kittest::{Harness, kittest::Queryable};
use flexmodes::gui::{Controls, Explorer};
use rerun::external::egui::{self, accesskit::Role};

fn harness(scene: &str) -> Harness<'static, Explorer> {
    let explorer = Explorer::new(Controls::for_scene(scene).unwrap());
    Harness::new_ui_state(
        |ui: &mut egui::Ui, e: &mut Explorer| {
            e.poll();
            let commands = e.panel_ui(ui);
            e.apply(commands);
        },
        explorer,
    )
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
    h.state_mut().controls.boundary = "16".into();
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
fn a_newer_request_supersedes_a_running_one() {
    let mut h = harness("beam-modes");
    // Two changes before the first result: only the last one's result is applied.
    h.get_by_role_and_label(Role::CheckBox, "GR").click();
    h.step();
    h.get_by_role_and_label(Role::CheckBox, "MT").click();
    settle(&mut h);
    let p = paths(&h);
    assert!(!p.iter().any(|p| p.starts_with("modes/guyan_a")), "GR off");
    assert!(!p.iter().any(|p| p.starts_with("modes/boundary")), "MT off");
    assert!(p.iter().any(|p| p.starts_with("modes/craig_bampton")));
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
    h.state_mut().controls.methods = vec!["cb".into()];
    h.state_mut().controls.end_time = 0.5;
    h.get_by_label("shorter").click();
    settle(&mut h);
    let report = &h.state().current.as_ref().unwrap().report;
    assert_eq!(report.parameters["end_time_s"], 0.25);
    assert!(paths(&h).iter().any(|p| p == "plots/node8/delta_zeta/cb"));
}

#[test]
fn a_newer_request_cancels_a_running_simulation() {
    use flexmodes::{gui::Worker, reduction::Method, scenes::SceneOptions};
    let mut w = Worker::new();
    let slow = SceneOptions {
        methods: Some(vec![Method::NoReduction]),
        end_time: Some(1.0),
        ..Default::default()
    };
    let first = w.submit(1, "slab-sim1", slow, false);
    let start = Instant::now();
    while first.reading().is_none_or(|r| r.time <= 0.0) {
        assert!(start.elapsed() < Duration::from_secs(120), "no progress");
        std::thread::sleep(Duration::from_millis(1));
    }
    let second = w.submit(2, "beam-modes", SceneOptions::default(), false);
    assert!(first.is_cancelled() && !second.is_cancelled());
    let finished = loop {
        if let Some(f) = w.poll() {
            break f;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no result");
        std::thread::sleep(Duration::from_millis(1));
    };
    // The cancelled request reports nothing; the full-order run stopped short of its end.
    assert_eq!(finished.generation, 2);
    assert!(finished.result.is_ok());
    let r = first.reading().unwrap();
    assert!(r.time < 1.0, "{r:?}");
}

#[test]
fn a_running_simulation_shows_its_simulated_time() {
    let mut h = harness("slab-sim1");
    h.state_mut().controls.methods = vec!["nr".into()];
    h.state_mut().controls.end_time = 2.0;
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
