//! The desktop explorer's panel driven headless with egui_kittest (feature `gui`): controls
//! recompute on the worker, results replace the recording, errors keep the last good one.
#![cfg(feature = "gui")]

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use flexmodes::gui::{Controls, Explorer};
use rerun::external::egui::{self};

mod body_panel;
mod scene_controls;
mod switches;

/// The explorer's panel with `controls`, applying its commands after each frame.
pub(crate) fn harness_with(controls: Controls) -> Harness<'static, Explorer> {
    Harness::new_ui_state(
        |ui: &mut egui::Ui, e: &mut Explorer| {
            e.poll();
            let commands = e.panel_ui(ui);
            e.apply(commands);
        },
        Explorer::new(controls),
    )
}

pub(crate) fn harness(scene: &str) -> Harness<'static, Explorer> {
    harness_with(Controls::for_scene(scene.parse().unwrap()))
}

/// The explorer's panel on the `modes` scene of body file `body`.
pub(crate) fn body_harness(body: &str) -> Harness<'static, Explorer> {
    harness_with(Controls::for_body(body).unwrap())
}

/// Steps frames until the worker is done (the UI never blocks on it).
pub(crate) fn settle(h: &mut Harness<'static, Explorer>) {
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

pub(crate) fn paths(h: &Harness<'static, Explorer>) -> Vec<String> {
    h.state().current.as_ref().unwrap().entity_paths.clone()
}

/// `poll()`'s first `Some`, polled every millisecond until `limit_s` seconds after `start`;
/// fails naming `what` it waited for.
pub(crate) fn wait_for<T>(
    what: &str,
    start: Instant,
    limit_s: u64,
    mut poll: impl FnMut() -> Option<T>,
) -> T {
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
pub(crate) fn next_result(
    w: &flexmodes::gui::Worker,
    start: Instant,
    limit_s: u64,
) -> flexmodes::gui::Finished {
    wait_for("a result", start, limit_s, || w.poll())
}

/// slab-sim1 with the full model alone over `end_time` s: slow enough to be caught running.
pub(crate) fn full_model_sim1(end_time: f64) -> flexmodes::scenes::SceneOptions {
    flexmodes::scenes::SceneOptions {
        methods: Some(vec![flexmodes::reduction::Method::NoReduction]),
        end_time: Some(end_time),
        ..Default::default()
    }
}
