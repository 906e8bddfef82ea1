//! `beam-profiles`: the deformed-profile experiments of §7.1.

use crate::record::{REFERENCE, method_color};
use serde_json::{Map, Value, json};

use super::beam_run::BeamRun;
use crate::scenes::{SceneInfo, SceneOptions, SceneOutput, mode_visuals::undeformed};
use crate::{
    Result,
    analysis::{PROFILE_DELTA, fit_given_modal_coordinates, fit_least_squares},
    record::{Geometry, Layout, Visual},
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
    report::{Cell, Report, Table, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "beam-profiles",
    recording_cost: 0,
    summary: "§7.1 deformed profiles of the beam: the same z* (profile 1) and a least-squares \
              fit (profile 2) by MT, CB and MC against the reference deflection",
    sections: "§7.1",
    controls: super::beam_run::beam_controls(&[
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ]),
};

const AVAILABLE: [Method; 3] = [
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
];

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let (methods, boundary, kept, model, part) =
        BeamRun::new(opts, &INFO, (&AVAILABLE, &AVAILABLE))?.into_parts();
    let params = ReductionRequest {
        boundary_nodes: boundary.clone(),
        modes: ModeSelection::Count(kept),
        ..Default::default()
    };
    let delta = PROFILE_DELTA;

    let mut report = Report::new(INFO.name);
    report.parameters.insert("boundary".into(), json!(boundary));
    report.parameters.insert("modes".into(), json!(kept));
    report.parameters.insert("delta".into(), json!(delta));
    let (mut e1, mut e2, mut d1, mut d2) = (Map::new(), Map::new(), Map::new(), Map::new());
    let mut table =
        Table::new(&["method", "profile 1 ‖δ*−δ‖, m", "profile 2 ‖δ*−δ‖, m"]).rank_lower(&[1, 2]);
    let geometry = Geometry::of(&model);
    let mut visuals = vec![undeformed(&model)];
    for (profile, offset) in [("profile1", 0.0), ("profile2", -0.6)] {
        visuals.push(Visual::Offset {
            path: format!("profiles/{profile}"),
            translation: [0.0, offset, 0.0],
        });
        visuals.push(Visual::Wireframe {
            path: format!("profiles/{profile}/reference"),
            geometry: geometry.with_nodes(model.displaced(&delta, 1.0)),
            color: REFERENCE,
            label: None,
        });
    }
    for &m in &methods {
        let basis = reduce(&model, &params.with_method(m))?;
        let p1 = fit_given_modal_coordinates(&model, &basis, &part, &delta)?;
        let p2 = fit_least_squares(&basis, &delta)?;
        e1.insert(m.id().into(), json!(sig(p1.error)));
        e2.insert(m.id().into(), json!(sig(p2.error)));
        d1.insert(m.id().into(), json!(sig_vec(&p1.delta)));
        d2.insert(m.id().into(), json!(sig_vec(&p2.delta)));
        table.push(vec![
            Cell::text(m.id().to_uppercase()),
            Cell::number(p1.error, format!("{:.4}", p1.error)),
            Cell::number(p2.error, format!("{:.4}", p2.error)),
        ]);
        for (profile, fit) in [("profile1", &p1), ("profile2", &p2)] {
            visuals.push(Visual::Wireframe {
                path: format!("profiles/{profile}/{}", m.id()),
                geometry: geometry.with_nodes(model.displaced(&fit.delta, 1.0)),
                color: method_color(m),
                label: None,
            });
        }
    }
    report
        .results
        .insert("profile1_error".into(), Value::Object(e1));
    report
        .results
        .insert("profile2_error".into(), Value::Object(e2));
    report
        .results
        .insert("profile1_delta".into(), Value::Object(d1));
    report
        .results
        .insert("profile2_delta".into(), Value::Object(d2));
    report.table = format!(
        "{}\nPublished (§7.1): profile 1 MT 0.1569, CB 0.0826, MC 0.0826; profile 2 MT 0.1569, \
         CB 0.0612, MC 0.0612.\n",
        report.add_table(table)
    );
    let markdown = format!(
        "# beam-profiles\n\n§7.1 on the App. A beam with boundary nodes {boundary:?} and {kept} \
         kept normal modes. The reference δ (Eq. 7.1, grey) is pinned at node 1 and on a roller \
         at node 5. Colours: reference grey, MT red, CB blue, MC green (drawn over CB, \
         which it equals). **Profile 1** (top) gives every method the same z* = {{δ_b; z_n^k}}; \
         **profile 2** (below) fits δ by least squares. Modal truncation's boundary columns \
         cannot move interior nodes, so its interior stays at ξ = 0; Craig-Bampton and mode \
         condensation coincide (one column space).\n\n{}",
        report.table
    );
    let views = Layout::view3d("profiles", "/profiles");
    Ok(SceneOutput::beside_text(report, markdown, visuals, views).y_up())
}
