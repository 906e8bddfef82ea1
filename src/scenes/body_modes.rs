//! `modes`: any body from a body file (`--body FILE` or `builtin:NAME`; the L-bracket by
//! default) reduced on its interfaces by the methods of `models::BodyReducer` (Guyan, modal
//! truncation, Craig–Bampton and mode condensation by default; MacNeal–Rubin, Benfield–Hruda,
//! moment matching and balanced truncation on request), each model's frequencies and MAC
//! against the full body's, and the principal angles between the bases and its lowest modes.

use std::time::Instant;

use serde_json::{Map, Value, json};

use super::{
    SceneInfo, SceneOptions, SceneOutput, frequency_bars::FrequencyBars, mode_visuals::undeformed,
};
use crate::analysis::pair_modes;
use crate::models::{
    BODY_METHODS, BodyInterfaces, BodyReducer, INTERFACE_MODE_SWEEP, InterfaceResponse,
    interface_reduction_sweep, modes_up_to,
};
use crate::record::{LogLogChart, LogLogSeries};
use crate::reduction::{Basis, ColumnKind, ReductionError};
use crate::{
    Error, Result,
    body_file::{BodyHandle, ImportedBody},
    linalg::{GeneralizedEigen, principal_angles},
    models::FULL_MODES,
    record::Layout,
    reduction::{Method, ModeSelection},
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
/// The lowest elastic modes whose frequency error and subspace angle the table shows (every
/// error is in the JSON, paired by order).
const COMPARED_MODES: usize = 6;

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

    opts.progress.phase("full body's lowest modes")?;
    let started = Instant::now();
    let full = modes_up_to(model, opts.band_hz, FULL_MODES, &opts.progress)?;
    let full_s = started.elapsed().as_secs_f64();
    crate::models::refuse_mechanism(model, &full)?;
    let full_hz = full.elastic_hz();
    let elastic = GeneralizedEigen {
        values: full.modes.values[full.zero_modes..].to_vec(),
        vectors: full
            .modes
            .vectors
            .subcols(full.zero_modes, full_hz.len())
            .to_owned(),
        residuals: full.modes.residuals[full.zero_modes..].to_vec(),
        zero_energy: 0,
        sturm: None,
    };

    let mut reducer = BodyReducer::new(
        model,
        BodyInterfaces {
            boundary: boundary.clone(),
            rigid: opts.rigid_interfaces.clone(),
            averaging: opts.averaging_interfaces.clone(),
            interface_modes: opts.interface_modes,
        },
        &full,
        full_s,
        opts.progress.clone(),
    )?;
    // The full body's interface response over --band, and each model's below.
    let response = match opts.band_hz {
        Some(top) => Some(InterfaceResponse::of_full_body(
            model,
            reducer.loads()?,
            top,
            &full.elastic_hz(),
            &opts.progress,
        )?),
        None => None,
    };
    let mut responses = Vec::new();
    // The constraint and fixed-interface modes, when a boundary holds the body (rbe3
    // interfaces alone hold nothing).
    let held = if boundary.is_empty() {
        None
    } else {
        let problem = reducer.problem()?;
        Some((
            problem.constraint_shapes(super::slab_mode_views::MAX_DRAWN_CONSTRAINT_MODES)?,
            problem.kept_modes(ModeSelection::Count(kept))?,
        ))
    };
    let fi_hz = held.as_ref().map_or(Vec::new(), |(_, fi)| fi.hz());
    let fi_residuals = held
        .as_ref()
        .map_or(Vec::new(), |(_, fi)| fi.residuals.clone());

    let mut reduced = Map::new();
    let mut errors = Map::new();
    let mut angles = Map::new();
    let mut mac = Map::new();
    let mut rigid_max = Map::new();
    let mut reduced_residuals = Map::new();
    let mut reduced_zero = Map::new();
    let mut residual_lines = vec![
        format!(
            "full body: {}; missed modes: {}",
            residual_note(&full_hz, &full.elastic_residuals()),
            crate::models::missed_note(&full.modes)
        ),
        format!("fixed-interface: {}", residual_note(&fi_hz, &fi_residuals)),
    ];
    let mut sizes = Map::new();
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
    let mut visuals = Vec::new();
    if body.has_coordinates {
        visuals.push(undeformed(model));
    }
    let mut bars = Vec::new();
    let mut freq_bars = FrequencyBars::new(COMPARED_MODES);
    freq_bars.push(Method::NoReduction, &full_hz);
    // The full body's rigid and lowest elastic modes each basis should contain.
    let compared =
        (full.zero_modes + full_hz.len().min(COMPARED_MODES)).min(full.modes.vectors.ncols());
    let target = full.modes.vectors.subcols(0, compared);
    let mut cb_basis: Option<Basis> = None;
    let mut notes = Vec::new();
    for &m in &methods {
        let model_of = match reducer.reduce(m, kept) {
            Ok(r) => r,
            Err(
                e @ (Error::Reduction(ReductionError::MethodNeedsContext { .. })
                | Error::Linalg(crate::linalg::LinalgError::EigenCheckFailed { .. })),
            ) => {
                // A method that cannot apply to this body, or whose reduced pairs fail their
                // check: said in its row, not computed, never printed as if right.
                let mut row = vec![Cell::text(m.id().to_uppercase()), Cell::text("–")];
                row.push(Cell::text(format!("not computed: {e}")));
                row.extend((0..5).map(|_| Cell::text("–")));
                table.push(row);
                notes.push(format!("{}: {e}", m.id().to_uppercase()));
                continue;
            }
            Err(e) => return Err(e),
        };
        if let Some(note) = &model_of.note {
            notes.push(format!("{}: {note}", m.id().to_uppercase()));
        }
        if let Some(r) = &response {
            responses.push((m, r.of_model(model, &model_of.basis)?));
        }
        let elapsed = model_of.offline_s;
        if m == Method::CraigBampton {
            cb_basis = Some(if opts.interface_modes.is_some() {
                reducer.reduce_keeping_constraint_modes(m, kept)?.basis
            } else {
                model_of.basis.clone()
            });
        }
        let (basis, eig, skip) = (&model_of.basis, &model_of.modes, model_of.zero_modes);
        let rigid_hz = model_of.rigid_hz_max();
        let hz = model_of.elastic_hz();
        let hz_residuals = model_of.elastic_residuals();
        let rel = model_of.relative_errors(&full_hz);
        // A model with fewer elastic modes than compared has no error over them: said, not
        // ranked (a rigid interface under Guyan is a rigid body).
        let compared_modes = COMPARED_MODES.min(full_hz.len());
        let worst = if rel.len() >= compared_modes {
            rel.iter()
                .take(COMPARED_MODES)
                .fold(0.0f64, |a, e| a.max(e.abs()))
        } else {
            f64::NAN
        };
        let angle = principal_angles(basis.psi.as_ref(), target)?
            .into_iter()
            .fold(0.0f64, f64::max);
        // MAC of the full body's first elastic modes against the reduced model's expanded
        // ones (the lowest 2 × compared of them, paired by best MAC).
        let candidates = hz.len().min(2 * COMPARED_MODES);
        let expanded = basis.psi.as_ref() * eig.vectors.subcols(skip, candidates);
        let compared_full: Vec<usize> = (0..full_hz.len().min(COMPARED_MODES)).collect();
        let pairs = pair_modes(
            elastic.vectors.as_ref(),
            &full_hz,
            &compared_full,
            expanded.as_ref(),
            &hz[..candidates],
        );
        let macs: Vec<f64> = pairs.iter().map(|p| p.mac).collect();
        let min_mac = if candidates == 0 {
            f64::NAN
        } else {
            macs.iter().copied().fold(1.0, f64::min)
        };
        mac.insert(m.id().into(), json!(sig_vec(&macs)));
        reduced.insert(m.id().into(), json!(sig_vec(&hz)));
        reduced_residuals.insert(m.id().into(), json!(sig_vec(&hz_residuals)));
        reduced_zero.insert(m.id().into(), json!(skip));
        residual_lines.push(format!(
            "{}: {}",
            m.id().to_uppercase(),
            residual_note(&hz, &hz_residuals)
        ));
        errors.insert(m.id().into(), json!(sig_vec(&rel)));
        angles.insert(m.id().into(), json!(sig(angle)));
        rigid_max.insert(m.id().into(), json!(sig(rigid_hz)));
        sizes.insert(m.id().into(), json!(basis.size()));
        table.push(vec![
            Cell::text(m.id().to_uppercase()),
            Cell::number(basis.size() as f64, format!("{dofs} × {}", basis.size())),
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
            Cell::number(elapsed, format!("{elapsed:.3}")),
        ]);
        freq_bars.push(m, &hz);
    }

    visuals.extend(freq_bars.visuals());
    bars.insert(0, freq_bars.layout());

    let mut report = Report::new(INFO.id);
    let p = &mut report.parameters;
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
    r.insert("reduced_hz".into(), Value::Object(reduced));
    r.insert(
        "free_free_residuals".into(),
        json!(sig_vec(&full.elastic_residuals())),
    );
    r.insert(
        "fixed_interface_residuals".into(),
        json!(sig_vec(&fi_residuals)),
    );
    r.insert("reduced_residuals".into(), Value::Object(reduced_residuals));
    r.insert(
        "reduced_zero_energy_modes".into(),
        Value::Object(reduced_zero),
    );
    // How many characteristic constraint modes the interface needs (Castanier–Tan–Pierre).
    let mut sweep_md = String::new();
    let mut sweep_table = None;
    if let Some(cb) = &cb_basis
        && cb.columns_of(|k| *k == ColumnKind::Constraint).len() > INTERFACE_MODE_SWEEP[0]
    {
        opts.progress.phase("interface reduction sweep")?;
        let points = interface_reduction_sweep(model, cb, &full, COMPARED_MODES)?;
        let mut sweep = Table::new(&["interface shapes", "size", "max rel. error, first 6 modes"]);
        let mut chart = Vec::new();
        for p in &points {
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
        r.insert(
            "interface_reduction".into(),
            json!(
                points
                    .iter()
                    .map(|p| json!({
                        "interface_modes": p.interface_modes,
                        "size": p.size,
                        "max_rel_error": sig(p.worst_error),
                    }))
                    .collect::<Vec<_>>()
            ),
        );
        visuals.extend(
            LogLogChart {
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
            .visuals(),
        );
        bars.push(Layout::Spatial2D {
            name: "interface shapes: error against size".into(),
            origin: "/charts/interface_reduction".into(),
        });
        sweep_md = format!(
            "\nInterface reduction (Craig–Bampton with the interface's constraint modes \
             replaced by N characteristic constraint modes, Castanier–Tan–Pierre; \
             `--interface-modes N`{}):\n\n{}",
            match opts.interface_modes {
                Some(n) => format!(
                    "; the models above use N = {n} where they have constraint modes (GR, CB), \
                     MT and MC keep their boundary columns"
                ),
                None => String::new(),
            },
            sweep.markdown()
        );
        sweep_table = Some(sweep);
    }
    r.insert("rel_error".into(), Value::Object(errors));
    r.insert("max_principal_angle_rad".into(), Value::Object(angles));
    r.insert("mac".into(), Value::Object(mac));
    r.insert("basis_size".into(), Value::Object(sizes));
    r.insert("zero_energy_hz_max".into(), Value::Object(rigid_max));
    r.insert("full_modes_s".into(), json!(sig(full_s)));
    r.insert("method_notes".into(), json!(notes));
    opts.progress
        .phase("modal influence across the interfaces")?;
    let (influence, influence_json, influence_text) =
        super::body_influence::influence_table(&mut reducer, kept)?;
    r.insert("interface_influence".into(), influence_json);
    let summary = table.markdown();
    report.add_table(table);
    if let Some(sweep) = sweep_table {
        report.add_table(sweep);
    }
    let influence_md = format!("\n\n{influence_text}\n\n{}", influence.markdown());
    report.add_table(influence);
    let response_md = match &response {
        Some(r) => {
            let (table, json, chart, view, text) =
                super::body_response::response_table(r, &responses)?;
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
        notes.iter().map(|n| format!("\n- {n}")).collect::<String>(),
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
    let layout = if let (true, Some(((shapes, labels), fi))) = (body.has_coordinates, &held) {
        let (mode_visuals, l) = super::slab_mode_views::slab_mode_views(
            model,
            &reducer.problem()?.partition,
            shapes,
            labels,
            fi,
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
