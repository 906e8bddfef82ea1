//! `modes`: any body from a body file (`--body FILE` or `builtin:NAME`; the L-bracket by
//! default) reduced on its interfaces by the methods of `models::BodyReducer` (Guyan, modal
//! truncation, Craig–Bampton and mode condensation by default; MacNeal–Rubin, Benfield–Hruda,
//! moment matching and balanced truncation on request), each model's frequencies and MAC
//! against the full body's, and the principal angles between the bases and its lowest modes.

use serde_json::{Map, Value, json};

use super::body_influence::influence_count;
use super::{
    SceneInfo, SceneOptions, SceneOutput, frequency_bars::FrequencyBars, mode_visuals::undeformed,
};
use crate::models::{
    BALANCED_ZETA, BODY_METHODS, BODY_MODES_COMPARED, BodyInterfaces, BodyModesParameters,
    BodyModesStudy, MethodMeasure, body_modes_study,
};
use crate::record::{LogLogChart, LogLogSeries};
use crate::{
    Result,
    body_file::{BodyHandle, ImportedBody},
    models::FULL_MODES,
    record::Layout,
    reduction::Method,
    report::{Cell, Report, Table, fmt_hz, residual_note, sig, sig_vec},
};

/// The body shown when no `--body` is given.
pub const DEFAULT_BODY: &str = "builtin:l-bracket";

pub const INFO: SceneInfo = SceneInfo {
    id: "modes",
    summary: "any body from a body file (--body FILE; the L-bracket by default): every method \
              on its interfaces (node sets, rbe2:, rbe3:) against the full body's frequencies",
    sections: "§6.2–6.5 on a body of your own",
    controls: super::scene_info::SceneControls {
        methods: &AVAILABLE,
        boundary: &[],
        modes: Some(10),
        axes: &[],
        end_time: None,
        refine: None,
    },
};

const AVAILABLE: [Method; 8] = BODY_METHODS;
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

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    opts.check_axes(INFO.id, &[])?;
    let body = body_of(opts)?;
    let model = &body.model;
    let methods = opts.methods_or(INFO.id, &AVAILABLE, &DEFAULT_METHODS)?;
    let boundary = match &opts.boundary {
        Some(b) => b.clone(),
        None => body.default_interface_nodes()?.to_vec(),
    };
    let kept = opts.modes_or_default(&INFO);
    let dofs = model.dof_count();

    let study = body_modes_study(
        model,
        &BodyModesParameters {
            interfaces: BodyInterfaces {
                boundary: boundary.clone(),
                rigid: opts.rigid_interfaces.clone(),
                averaging: opts.averaging_interfaces.clone(),
                interface_modes: opts.interface_modes,
            },
            methods: methods.clone(),
            kept,
            band_hz: opts.band_hz,
            full_modes: FULL_MODES,
            drawn_constraint_modes: super::slab_mode_views::MAX_DRAWN_CONSTRAINT_MODES,
        },
        (influence_count(kept), BALANCED_ZETA),
        &opts.progress,
    )?;
    let BodyModesStudy {
        full,
        full_s,
        elastic,
        held,
        methods: study_methods,
        notes: study_notes,
        sweep,
        response,
        influence,
        influence_count: ranked,
    } = study;
    let full_hz = full.elastic_hz();
    let fi_hz = held.as_ref().map_or(Vec::new(), |h| h.fixed_interface.hz());
    let fi_residuals = held
        .as_ref()
        .map_or(Vec::new(), |h| h.fixed_interface.residuals.clone());

    let mut residual_lines = vec![
        format!(
            "full body: {}; missed modes: {}",
            residual_note(&full_hz, &full.elastic_residuals()),
            crate::models::missed_note(&full.modes)
        ),
        format!("fixed-interface: {}", residual_note(&fi_hz, &fi_residuals)),
    ];
    let mut visuals = Vec::new();
    if body.has_coordinates {
        visuals.push(undeformed(model));
    }
    let mut bars = Vec::new();
    let mut freq_bars = FrequencyBars::new(BODY_MODES_COMPARED);
    freq_bars.push(Method::NoReduction, &full_hz);
    let rows = method_rows(&study_methods, &study_notes, dofs, &mut freq_bars);
    residual_lines.extend(rows.residual_lines);

    visuals.extend(freq_bars.visuals());
    bars.insert(0, freq_bars.layout());

    let mut report = Report::new(INFO.id);
    report
        .parameters
        .extend(run_parameters(&body, &boundary, opts, kept, &methods));
    let r = &mut report.results;
    r.insert("dofs".into(), json!(dofs));
    r.insert("nnz".into(), json!(model.stiffness_nnz()));
    r.insert("zero_energy_modes".into(), json!(full.zero_modes));
    r.insert(
        "missed_modes".into(),
        json!(full.modes.sturm.map_or(0, |c| c.missed())),
    );
    r.insert("free_free_hz".into(), json!(sig_vec(&full_hz)));
    r.insert("fixed_interface_hz".into(), json!(sig_vec(&fi_hz)));
    r.insert("reduced_hz".into(), Value::Object(rows.reduced));
    r.insert(
        "free_free_residuals".into(),
        json!(sig_vec(&full.elastic_residuals())),
    );
    r.insert(
        "fixed_interface_residuals".into(),
        json!(sig_vec(&fi_residuals)),
    );
    r.insert(
        "reduced_residuals".into(),
        Value::Object(rows.reduced_residuals),
    );
    r.insert(
        "reduced_zero_energy_modes".into(),
        Value::Object(rows.reduced_zero),
    );
    // How many characteristic constraint modes the interface needs (Castanier–Tan–Pierre).
    let mut sweep_md = String::new();
    let mut sweep_table = None;
    if let Some(points) = &sweep {
        let section = sweep_section(points, opts.interface_modes);
        r.insert("interface_reduction".into(), section.json);
        visuals.extend(section.visuals);
        bars.push(section.view);
        sweep_md = section.markdown;
        sweep_table = Some(section.table);
    }
    r.insert("rel_error".into(), Value::Object(rows.errors));
    r.insert("max_principal_angle_rad".into(), Value::Object(rows.angles));
    r.insert("mac".into(), Value::Object(rows.mac));
    r.insert("basis_size".into(), Value::Object(rows.sizes));
    r.insert("zero_energy_hz_max".into(), Value::Object(rows.rigid_max));
    r.insert("full_modes_s".into(), json!(sig(full_s)));
    r.insert("method_notes".into(), json!(rows.notes));
    let (influence, influence_json, influence_text) =
        super::body_influence::influence_table(&influence, ranked, kept);
    r.insert("interface_influence".into(), influence_json);
    let summary = rows.table.markdown();
    report.add_table(rows.table);
    if let Some(sweep) = sweep_table {
        report.add_table(sweep);
    }
    let influence_md = format!("\n\n{influence_text}\n\n{}", influence.markdown());
    report.add_table(influence);
    let response_md = match &response {
        Some(r) => {
            let (table, json, chart, view, text) =
                super::body_response::response_table(r, &rows.responses)?;
            report.results.insert("interface_response".into(), json);
            visuals.extend(chart);
            bars.push(view);
            let md = format!("\n\n{text}\n\n{}", table.markdown());
            report.add_table(table);
            md
        }
        None => String::new(),
    };
    let units = &body.units;
    report.table = format!(
        "Body `{}` ({}): {dofs} DOF, {} stiffness entries, {} zero-energy mode(s); units {}, \
         {}, {}. Interface {} node(s) {}{}, {kept} kept modes.\n\n{summary}\nFull body, \
         lowest elastic: {}\n\nFixed-interface: {}\n\nEigen residuals \
         (‖Kφ − λMφ‖/‖Kφ‖ of every printed frequency): {}\n{}{sweep_md}{influence_md}{response_md}",
        model.name,
        body.location.display(),
        model.stiffness_nnz(),
        full.zero_modes,
        units.length,
        units.mass,
        units.force,
        boundary.len(),
        if boundary.len() <= 12 {
            format!("{boundary:?}")
        } else {
            format!(
                "{:?} … {:?}",
                &boundary[..6],
                &boundary[boundary.len() - 3..]
            )
        },
        opts.rigid_interfaces
            .iter()
            .map(|i| format!(
                "; rbe2 `{}`: {} nodes tied to a master at ({})",
                i.name,
                i.nodes.len(),
                i.master.map(|x| format!("{}", sig(x))).join(", ")
            ))
            .chain(opts.averaging_interfaces.iter().map(|i| format!(
                "; rbe3 `{}`: {} nodes averaged into a master at ({}), loading it and free",
                i.name,
                i.nodes.len(),
                i.master.map(|x| format!("{}", sig(x))).join(", ")
            )))
            .collect::<String>(),
        fmt_hz(&full_hz),
        fmt_hz(&fi_hz[..fi_hz.len().min(8)]),
        residual_lines.join("; "),
        rows.notes
            .iter()
            .map(|n| format!("\n- {n}"))
            .collect::<String>(),
    );
    let markdown = format!(
        "# modes: {}\n\n{}\n\nEvery method reduces the same body on the same interface: \
         Guyan keeps only the interface (static constraint modes), modal truncation the \
         interface movements and the {kept} lowest fixed-interface modes, Craig–Bampton the \
         constraint modes and those modes, mode condensation the same space in its own \
         coordinates. MacNeal–Rubin keeps free-interface modes and the residual flexibility of the \
         interface DOF; Benfield–Hruda the modes of the body with its interfaces loaded; moment \
         matching Krylov vectors of the interface loads; balanced truncation the dominant \
         vectors of the interface loads' position gramian (each says below what it took). \
         \"max rel. error\" compares each model's six lowest elastic frequencies \
         with the full body's, paired by order; the angle is the largest principal angle between the basis \
         and the full body's zero-energy and six lowest elastic modes (0: contained). \"rigid \
         modes at\" is the highest frequency a reduced model gives its rigid-body motions, \
         which should be zero: round-off in the method's coordinates lifts it. {}\n\n{}",
        model.name,
        body.description,
        freq_bars.caption(),
        report.table
    );
    let layout = if let (true, Some(h)) = (body.has_coordinates, &held) {
        let (mode_visuals, l) = super::slab_mode_views::slab_mode_views(
            model,
            &h.partition,
            &h.constraint_shapes.0,
            &h.constraint_shapes.1,
            &h.fixed_interface,
            &elastic,
            FULL_MODES,
            kept,
            "free_free",
            bars,
        );
        visuals.extend(mode_visuals);
        l
    } else {
        // No geometry to draw: the charts (the frequencies, and the interface sweep and
        // response where asked for) stacked at full width beside the text.
        Layout::Horizontal(
            vec![Layout::Vertical(bars, vec![]), Layout::scene_text()],
            vec![3.0, 2.0],
        )
    };
    Ok(SceneOutput {
        report,
        markdown,
        visuals,
        layout,
        timeline: Some("phase".into()),
        y_up: false,
    })
}

/// The interface-reduction sweep as the `modes` scene shows it.
struct SweepSection {
    table: Table,
    json: Value,
    visuals: Vec<crate::record::Visual>,
    view: Layout,
    markdown: String,
}

/// The sweep's table, JSON, log–log chart and text; `interface_modes` is the count the
/// scene's models use, if any.
fn sweep_section(
    points: &[crate::models::InterfaceReductionPoint],
    interface_modes: Option<usize>,
) -> SweepSection {
    let mut sweep = Table::new(&["interface shapes", "size", "max rel. error, first 6 modes"]);
    let mut chart = Vec::new();
    for p in points {
        let shapes = p
            .interface_modes
            .map_or("all (plain CB)".to_string(), |n| n.to_string());
        sweep.push(vec![
            Cell::text(shapes),
            Cell::number(p.size as f64, format!("{}", p.size)),
            Cell::number(p.worst_error, format!("{:.3e}", p.worst_error)),
        ]);
        if p.worst_error.is_finite() && p.worst_error > 0.0 {
            chart.push((p.size as f64, p.worst_error));
        }
    }
    let json = json!(
        points
            .iter()
            .map(|p| json!({
                "interface_modes": p.interface_modes,
                "size": p.size,
                "max_rel_error": sig(p.worst_error),
            }))
            .collect::<Vec<_>>()
    );
    let visuals = LogLogChart {
        path: "charts/interface_reduction".into(),
        x_unit: "coordinates".into(),
        y_unit: "max rel. error".into(),
        series: vec![LogLogSeries {
            id: "cb".into(),
            label: "CB, N characteristic constraint modes".into(),
            color: crate::record::method_color(Method::CraigBampton),
            points: chart,
            line: true,
        }],
        x_linear: false,
    }
    .visuals();
    let view = Layout::Spatial2D {
        name: "interface shapes: error against size".into(),
        origin: "/charts/interface_reduction".into(),
    };
    let markdown = format!(
        "\nInterface reduction (Craig–Bampton with the interface's constraint modes \
         replaced by N characteristic constraint modes, Castanier–Tan–Pierre; \
         `--interface-modes N`{}):\n\n{}",
        match interface_modes {
            Some(n) => format!(
                "; the models above use N = {n} where they have constraint modes (GR, CB), \
                 MT and MC keep their boundary columns"
            ),
            None => String::new(),
        },
        sweep.markdown()
    );
    SweepSection {
        table: sweep,
        json,
        visuals,
        view,
        markdown,
    }
}

/// The run's parameters as the report shows them: the body, its interface (plain, rbe2 and
/// rbe3 items), the kept modes and the methods.
fn run_parameters(
    body: &ImportedBody,
    boundary: &[usize],
    opts: &SceneOptions,
    kept: usize,
    methods: &[Method],
) -> Map<String, Value> {
    let mut p = Map::new();
    p.insert("body".into(), json!(body.location.display()));
    p.insert("boundary".into(), json!(boundary));
    p.insert(
        "rigid_interfaces".into(),
        json!(
            opts.rigid_interfaces
                .iter()
                .map(|i| json!({"name": i.name, "kind": "rbe2", "master": i.master, "nodes": i.nodes.len()}))
                .collect::<Vec<_>>()
        ),
    );
    p.insert(
        "averaging_interfaces".into(),
        json!(
            opts.averaging_interfaces
                .iter()
                .map(|i| json!({"name": i.name, "kind": "rbe3", "master": i.master, "nodes": i.nodes.len()}))
                .collect::<Vec<_>>()
        ),
    );
    p.insert("modes".into(), json!(kept));
    p.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
    p
}

/// The per-method part of the `modes` scene's report: its table rows, JSON maps, residual
/// lines, notes and responses; each model's frequencies added to `freq_bars`.
struct MethodRows {
    table: Table,
    reduced: Map<String, Value>,
    errors: Map<String, Value>,
    angles: Map<String, Value>,
    mac: Map<String, Value>,
    rigid_max: Map<String, Value>,
    reduced_residuals: Map<String, Value>,
    reduced_zero: Map<String, Value>,
    sizes: Map<String, Value>,
    residual_lines: Vec<String>,
    notes: Vec<String>,
    responses: Vec<(Method, crate::analysis::FrequencyResponse)>,
}

fn method_rows(
    methods: &[(Method, std::result::Result<MethodMeasure, String>)],
    model_notes: &[(Method, String)],
    dofs: usize,
    freq_bars: &mut FrequencyBars,
) -> MethodRows {
    let mut reduced = Map::new();
    let mut errors = Map::new();
    let mut angles = Map::new();
    let mut mac = Map::new();
    let mut rigid_max = Map::new();
    let mut reduced_residuals = Map::new();
    let mut reduced_zero = Map::new();
    let mut sizes = Map::new();
    let mut residual_lines = Vec::new();
    let mut table = Table::new(&[
        "model",
        "size",
        "lowest elastic Hz",
        "max rel. error, first 6 modes",
        "min MAC, first 6 modes",
        "largest angle to full modes (rad)",
        "rigid modes at ≤ Hz",
        "s",
    ])
    .rank_lower(&[3, 5, 6]);
    let mut notes = Vec::new();
    let mut responses = Vec::new();
    for (m, measured) in methods {
        let m = *m;
        let q = match measured {
            Ok(q) => q,
            Err(e) => {
                let mut row = vec![Cell::text(m.id().to_uppercase()), Cell::text("–")];
                row.push(Cell::text(format!("not computed: {e}")));
                row.extend((0..5).map(|_| Cell::text("–")));
                table.push(row);
                notes.push(format!("{}: {e}", m.id().to_uppercase()));
                continue;
            }
        };
        if let Some((_, note)) = model_notes.iter().find(|(n, _)| *n == m) {
            notes.push(format!("{}: {note}", m.id().to_uppercase()));
        }
        if let Some(r) = &q.response {
            responses.push((m, r.clone()));
        }
        let (hz, hz_residuals) = (&q.hz, &q.residuals);
        mac.insert(m.id().into(), json!(sig_vec(&q.macs)));
        reduced.insert(m.id().into(), json!(sig_vec(hz)));
        reduced_residuals.insert(m.id().into(), json!(sig_vec(hz_residuals)));
        reduced_zero.insert(m.id().into(), json!(q.zero_modes));
        residual_lines.push(format!(
            "{}: {}",
            m.id().to_uppercase(),
            residual_note(hz, hz_residuals)
        ));
        errors.insert(m.id().into(), json!(sig_vec(&q.rel_errors)));
        angles.insert(m.id().into(), json!(sig(q.max_angle)));
        rigid_max.insert(m.id().into(), json!(sig(q.rigid_hz_max)));
        sizes.insert(m.id().into(), json!(q.size));
        let (worst, min_mac, angle, rigid_hz) =
            (q.worst_error, q.min_mac, q.max_angle, q.rigid_hz_max);
        table.push(vec![
            Cell::text(m.id().to_uppercase()),
            Cell::number(q.size as f64, format!("{dofs} × {}", q.size)),
            Cell::text(fmt_hz(&hz[..hz.len().min(5)])),
            if worst.is_nan() {
                Cell::text(format!("{} elastic mode(s) only", hz.len()))
            } else {
                Cell::number(worst, format!("{worst:.2e}"))
            },
            if min_mac.is_nan() {
                Cell::text("–")
            } else {
                Cell::number(min_mac, format!("{min_mac:.4}"))
            },
            Cell::number(angle, format!("{angle:.2e}")),
            Cell::number(rigid_hz, format!("{rigid_hz:.2e}")),
            Cell::number(q.offline_s, format!("{:.3}", q.offline_s)),
        ]);
        freq_bars.push(m, hz);
    }
    MethodRows {
        table,
        reduced,
        errors,
        angles,
        mac,
        rigid_max,
        reduced_residuals,
        reduced_zero,
        sizes,
        residual_lines,
        notes,
        responses,
    }
}
