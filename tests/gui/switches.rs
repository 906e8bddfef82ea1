//! Switches as a user makes them: the recording after any switches equals a fresh one, the
//! persisted controls, a user's body simulated, the layout kept where the views are the same.

use egui_kittest::kittest::Queryable;
use flexmodes::{gui::Controls, record::RecordingDigest, reduction::Method, scenes::SceneId};
use rerun::external::egui::{self, accesskit::Role};

use super::{harness_with, paths, settle};

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
    let rows = same_as_the_command_line(&h, link, &methods);
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

/// The explorer's shown simulation of the body at `link` by `methods` is the one the command
/// line's path makes with nothing kept between runs: the same rows of the table (timings left
/// out) and the same entities. Its rows.
fn same_as_the_command_line(
    h: &egui_kittest::Harness<'static, flexmodes::gui::Explorer>,
    link: &str,
    methods: &[Method],
) -> Vec<String> {
    use flexmodes::{
        Progress,
        body_file::ImportedBody,
        scenes::{RunCache, body_simulation::simulated},
    };
    let shown = h.state().current.as_ref().unwrap();
    let simulation = h.state().controls.simulation.clone().unwrap();
    assert_eq!(simulation.end, 0.1);
    let body = ImportedBody::load(link).unwrap();
    let alone = simulated(
        &body,
        &simulation.simulation().unwrap(),
        (methods, h.state().controls.modes),
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
    rows
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
