//! `modes`: any body from a body file (`--body FILE` or `builtin:NAME`; the L-bracket by
//! default) reduced on its interfaces by the methods of `models::BodyReducer` (Guyan, modal
//! truncation, Craig–Bampton and mode condensation by default; MacNeal–Rubin, Benfield–Hruda,
//! moment matching and balanced truncation on request), each model's frequencies and MAC
//! against the full body's, and the principal angles between the bases and its lowest modes.
//! Asked for a simulation (the explorer's `simulate`), the body driven through an interface
//! instead, as `flexmodes simulate` drives it.

use crate::models::{
    BALANCED_ZETA, BODY_METHODS, BODY_MODES_COMPARED, BodyInterfaces, BodyModesParameters,
    BodyModesStudy, DRIVEN_METHODS, InterfaceResponse, body_modes_study,
};
use crate::scenes::body::body_influence::influence_count;
use crate::scenes::body::body_modes_report::{method_rows, run_parameters, sweep_section};
use crate::scenes::body::body_modes_text::{BodyTables, body_text, scene_text};
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput, body::body_simulation::simulated,
    frequency_bars::FrequencyBars, mode_visuals::undeformed,
};
use crate::{
    Result,
    body_file::{BodyHandle, ImportedBody},
    fem::FeModel,
    models::FULL_MODES,
    record::{Layout, Visual},
    reduction::Method,
    report::{Report, residual_note},
};

/// The body shown when no `--body` is given.
pub const DEFAULT_BODY: &str = "builtin:l-bracket";

pub const INFO: SceneInfo = SceneInfo {
    name: "modes",
    recording_cost: 5,
    summary: "any body from a body file (--body FILE; the L-bracket by default): every method \
              on its interfaces (node sets, rbe2:, rbe3:) against the full body's frequencies",
    sections: "§6.2–6.5 on a body of your own",
    controls: crate::scenes::scene_info::SceneControls {
        methods: &AVAILABLE,
        modes: Some(10),
        body: true,
        ..crate::scenes::scene_info::SceneControls::NONE
    },
};

const AVAILABLE: [Method; 8] = BODY_METHODS;
/// Driven unless `--method` says otherwise (with the full body, `simulate`'s default).
const DRIVEN_DEFAULT: [Method; 2] = [Method::CraigBampton, Method::ModeCondensation];
/// Computed unless `--method` says otherwise.
const DEFAULT_METHODS: [Method; 4] = [
    Method::Guyan,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
];

/// The body of a run: `--body`, or [`DEFAULT_BODY`].
pub fn body_of(opts: &SceneOptions) -> Result<BodyHandle> {
    match &opts.body {
        Some(b) => Ok(b.clone()),
        None => Ok(BodyHandle(std::sync::Arc::new(ImportedBody::load(
            DEFAULT_BODY,
        )?))),
    }
}

/// The body driven through one interface (the explorer's `simulate`): the methods whose
/// boundary columns hold the driven ring still.
fn run_driven(
    body: &crate::body_file::ImportedBody,
    simulation: &crate::scenes::body::body_simulation::BodySimulation,
    opts: &SceneOptions,
) -> Result<SceneOutput> {
    let methods = opts.methods_or(INFO.name, &DRIVEN_METHODS, &DRIVEN_DEFAULT)?;
    let modes = opts.modes_or_default(&INFO);
    simulated(
        body,
        simulation,
        (&methods, modes),
        &opts.progress,
        &opts.cache,
        opts.concurrent_integrations,
    )
}

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let body = body_of(opts)?;
    match &opts.simulation {
        Some(simulation) => run_driven(&body, simulation, opts),
        None => run_modes(&body, opts),
    }
}

/// The body's modes under every method asked for, on its interface.
fn run_modes(body: &BodyHandle, opts: &SceneOptions) -> Result<SceneOutput> {
    let model = &body.model;
    let methods = opts.methods_or(INFO.name, &AVAILABLE, &DEFAULT_METHODS)?;
    let boundary = match &opts.boundary {
        Some(b) => b.clone(),
        None => body.default_interface_nodes()?.to_vec(),
    };
    let kept = opts.modes_or_default(&INFO);
    let dofs = model.dof_count();

    let study = study_of(model, opts, (&boundary, &methods), kept)?;
    let full_hz = study.full.elastic_hz();
    let fi_hz = study
        .held
        .as_ref()
        .map_or(Vec::new(), |h| h.fixed_interface.hz());
    let fi_residuals = study
        .held
        .as_ref()
        .map_or(Vec::new(), |h| h.fixed_interface.residuals.clone());

    let mut residual_lines = vec![
        full_residual_line(&study.full),
        format!("fixed-interface: {}", residual_note(&fi_hz, &fi_residuals)),
    ];
    let mut visuals: Vec<Visual> = body
        .has_coordinates
        .then(|| undeformed(model))
        .into_iter()
        .collect();
    let mut bars = Vec::new();
    let mut freq_bars = FrequencyBars::new(BODY_MODES_COMPARED);
    freq_bars.push(Method::NoReduction, &full_hz);
    let mut rows = method_rows(&study.methods, &study.notes, dofs, &mut freq_bars);
    residual_lines.append(&mut rows.residual_lines);

    visuals.extend(freq_bars.visuals());
    bars.insert(0, freq_bars.layout());

    let mut report = Report::new(INFO.name);
    report
        .parameters
        .extend(run_parameters(body, &boundary, opts, kept, &methods));
    let r = &mut report.results;
    rows.insert_frequencies(r, &study.full, (&full_hz, &fi_hz), &fi_residuals, model);
    // How many characteristic constraint modes the interface needs (Castanier–Tan–Pierre).
    let mut sweep_md = String::new();
    let mut sweep_table = None;
    if let Some(points) = &study.sweep {
        let section = sweep_section(points, opts.interface_modes);
        r.insert("interface_reduction".into(), section.json);
        visuals.extend(section.visuals);
        bars.push(section.view);
        sweep_md = section.markdown;
        sweep_table = Some(section.table);
    }
    rows.insert_measures(r, study.full_s);
    let (influence, influence_json, influence_text) =
        crate::scenes::body::body_influence::influence_table(
            &study.influence,
            study.influence_count,
            kept,
        );
    r.insert("interface_influence".into(), influence_json);
    let summary = rows.table.markdown();
    report.add_table(rows.table);
    if let Some(sweep) = sweep_table {
        report.add_table(sweep);
    }
    let influence_md = format!("\n\n{influence_text}\n\n{}", influence.markdown());
    report.add_table(influence);
    let response_md = response_section(
        &mut report,
        study.response.as_ref(),
        &rows.responses,
        (&mut visuals, &mut bars),
    )?;
    let tables = BodyTables {
        summary: &summary,
        residuals: &residual_lines,
        notes: &rows.notes,
        sweep: &sweep_md,
        influence: &influence_md,
        response: &response_md,
    };
    report.table = body_text(
        body,
        &boundary,
        opts,
        kept,
        &study.full,
        (&full_hz, &fi_hz),
        &tables,
    );
    let markdown = scene_text(body, kept, &freq_bars.caption(), &report.table);
    let (mode_visuals, layout) = views(body, study.held.as_ref(), &study.elastic, kept, bars);
    visuals.extend(mode_visuals);
    Ok(SceneOutput::new(report, markdown, visuals, layout).on_timeline("phase"))
}

/// The full body's residuals and the modes its Sturm count says were missed.
fn full_residual_line(full: &crate::analysis::ZeroEnergyCount) -> String {
    format!(
        "full body: {}; missed modes: {}",
        residual_note(&full.elastic_hz(), &full.elastic_residuals()),
        crate::models::missed_note(&full.modes)
    )
}

/// The body's modes under every method of `methods` on the interface `boundary`, `kept`
/// modes each, with the sweep, influence and response the options ask for.
fn study_of(
    model: &FeModel,
    opts: &SceneOptions,
    (boundary, methods): (&[usize], &[Method]),
    kept: usize,
) -> Result<BodyModesStudy> {
    Ok(body_modes_study(
        model,
        &BodyModesParameters {
            interfaces: BodyInterfaces {
                boundary: boundary.to_vec(),
                rigid: opts.rigid_interfaces.clone(),
                averaging: opts.averaging_interfaces.clone(),
                interface_modes: opts.interface_modes,
            },
            methods: methods.to_vec(),
            kept,
            band_hz: opts.band_hz,
            full_modes: FULL_MODES,
            drawn_constraint_modes:
                crate::scenes::slab::slab_mode_views::MAX_DRAWN_CONSTRAINT_MODES,
        },
        (influence_count(kept), BALANCED_ZETA),
        &opts.progress,
    )?)
}

/// The interface response's table and text (into `report`), its chart and view, when the
/// options asked for one; empty text otherwise.
fn response_section(
    report: &mut Report,
    response: Option<&InterfaceResponse>,
    responses: &[(Method, crate::analysis::FrequencyResponse)],
    (visuals, bars): (&mut Vec<Visual>, &mut Vec<Layout>),
) -> Result<String> {
    Ok(match response {
        Some(r) => {
            let (table, json, chart, view, text) =
                crate::scenes::body::body_response::response_table(r, responses)?;
            report.results.insert("interface_response".into(), json);
            visuals.extend(chart);
            bars.push(view);
            let md = format!("\n\n{text}\n\n{}", table.markdown());
            report.add_table(table);
            md
        }
        None => String::new(),
    })
}

/// The body's mode shapes drawn beside the charts when it has coordinates and a boundary
/// holds it; otherwise the charts (the frequencies, and the interface sweep and response where
/// asked for) at full width beside the text.
fn views(
    body: &ImportedBody,
    held: Option<&crate::models::HeldModes>,
    elastic: &crate::linalg::GeneralizedEigen,
    kept: usize,
    bars: Vec<Layout>,
) -> (Vec<crate::record::Visual>, Layout) {
    let model = &body.model;
    if let (true, Some(h)) = (body.has_coordinates, held) {
        let (mode_visuals, l) = crate::scenes::slab::slab_mode_views::slab_mode_views(
            crate::scenes::slab::slab_mode_views::ModeViews {
                model,
                part: &h.partition,
                constraint: &h.constraint_shapes.0,
                constraint_labels: &h.constraint_shapes.1,
                fixed_interface: &h.fixed_interface,
                free_free: elastic,
                shown_free_free: FULL_MODES,
                kept,
                first_tab: "free_free",
                charts: bars,
            },
        );
        (mode_visuals, l)
    } else {
        // No geometry to draw: the charts (the frequencies, and the interface sweep and
        // response where asked for) stacked at full width beside the text.
        (
            Vec::new(),
            Layout::beside_text(Layout::Vertical(bars, vec![])),
        )
    }
}
