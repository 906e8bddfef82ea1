//! A user's body in the panel, every scene's default controls, and the requests the explorer
//! anticipates.

use std::time::Instant;

use egui_kittest::kittest::Queryable;
use flexmodes::{
    gui::{Controls, Explorer},
    reduction::Method,
    scenes::SceneId,
};
use rerun::external::egui::accesskit::Role;

use super::{body_harness, full_model_sim1, harness, next_result, paths, settle, wait_for};

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
    assert!(error.to_string().contains("K_ii is singular"), "{error}");
    // Typed: the scene's error, and under it the reduction's with its data.
    match &error {
        flexmodes::gui::ExplorerError::Scene { scene, error } => {
            assert_eq!(*scene, SceneId::Modes);
            assert!(
                matches!(
                    **error,
                    flexmodes::Error::Core(flexmodes::error::CoreError::Reduction(
                        flexmodes::reduction::ReductionError::SingularInterior { .. }
                    ))
                ),
                "{error:?}"
            );
        }
        other => panic!("not the scene's error: {other:?}"),
    }
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
}

#[test]
fn a_bolt_hole_tied_or_averaged_reduces_each_method_as_it_can() {
    let mut h = body_harness("builtin:l-bracket");
    settle(&mut h);
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
    assert!(
        error.to_string().contains("/nonexistent/body.toml"),
        "{error}"
    );
    assert!(
        matches!(error, flexmodes::gui::ExplorerError::Settings(_)),
        "a body that does not load is the panel's settings: {error:?}"
    );
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
