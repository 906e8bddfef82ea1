//! `beam-mean-axes`: §8.4–8.5, a reduced beam evaluated with mean axes against the full model.

use crate::record::{REFERENCE, method_color};
use serde_json::json;

use super::beam_run::BeamRun;
use crate::dynamics::AxisKind;
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    mode_visuals::{columns, mode_set, undeformed},
};
use crate::{
    Result,
    analysis::{MeanAxesEvaluation, evaluate_with_mean_axes},
    fem::FeModel,
    linalg::{identity, max_abs_diff, principal_angles},
    record::{Layout, Visual},
    reduction::{
        Method, ModeSelection, Partition, ReductionRequest, constraint_modes,
        fixed_interface_modes, reduce,
    },
    report::{Cell, Report, Table, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "beam-mean-axes",
    recording_cost: 0,
    summary: "§8.4-8.5 mode condensation with mean axes: constraint and normal modes of the \
              reduced beam against the full model",
    sections: "§8.4, §8.5",
    controls: crate::scenes::SceneControls {
        axes: &[AxisKind::Mean],
        ..super::beam_run::beam_controls(&[
            Method::ModeCondensation,
            Method::CraigBampton,
            Method::ModalTruncation,
            Method::Guyan,
        ])
    },
};

const AVAILABLE: [Method; 4] = [
    Method::ModeCondensation,
    Method::CraigBampton,
    Method::ModalTruncation,
    Method::Guyan,
];

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let run = BeamRun::new(opts, &INFO, (&AVAILABLE, &[Method::ModeCondensation]))?;
    let mut report = run.report(&INFO);
    let (methods, boundary, kept, model, part) = run.into_parts();
    // The full model's constraint modes (Eq. 8.37) and fixed-interface modes (Eq. 8.38).
    let full_c = part.assemble(
        identity(part.b.len()).as_ref(),
        constraint_modes(&model, &part)?.as_ref(),
    );
    let fi = fixed_interface_modes(&model, &part)?;
    let full_hz = fi.hz();
    let mut table = Table::new(&[
        "method",
        "constraint modes: max diff to full",
        "normal modes with mean axes, Hz",
        "largest angle to full normal modes, rad",
    ])
    .rank_lower(&[1, 3]);
    let mut visuals = vec![undeformed(&model)];
    let mut tabs = Vec::new();
    let mut normal_tabs = Vec::new();
    for (i, &m) in methods.iter().enumerate() {
        let basis = reduce(
            &model,
            &ReductionRequest {
                method: m,
                boundary_nodes: boundary.clone(),
                modes: ModeSelection::Count(kept),
                ..Default::default()
            },
        )?;
        let ev = evaluate_with_mean_axes(&model, &basis, &part)?;
        let static_diff = max_abs_diff(ev.constraint_modes.as_ref(), full_c.as_ref());
        let n = ev.normal_modes.ncols().min(fi.vectors.ncols());
        let full_n = part.assemble(
            faer::Mat::<f64>::zeros(part.b.len(), n).as_ref(),
            fi.vectors.subcols(0, n),
        );
        let angle = if n > 0 {
            principal_angles(ev.normal_modes.subcols(0, n), full_n.as_ref())?
                .into_iter()
                .fold(0.0, f64::max)
        } else {
            0.0
        };
        insert_method(&mut report, &mut table, (i, m), &ev, (static_diff, angle));
        let (sets, [constraint_tab, normal_tab]) = method_views(&model, &part, m, &ev);
        visuals.extend(sets);
        tabs.push(constraint_tab);
        normal_tabs.push(normal_tab);
    }
    let full_modes: Vec<(Vec<f64>, String)> = columns(&full_c)
        .into_iter()
        .zip(&part.b)
        .map(|(u, &dof)| (u, format!("full constraint {}", model.dof_label(dof))))
        .collect();
    visuals.extend(mode_set(&model, "full_constraint", &full_modes, REFERENCE));
    tabs.push(Layout::view3d("full", "/modes/full_constraint"));
    report
        .results
        .insert("full_fixed_interface_hz".into(), json!(sig_vec(&full_hz)));
    report.table = format!(
        "{}\nFull model, fixed interface {boundary:?}: {} Hz (published for MC: 3.10366, \
         12.3283 Hz; constraint modes: linear interpolation between nodes 1 and 5).\n",
        report.add_table(table),
        crate::report::fmt_hz(&full_hz[..full_hz.len().min(4)]),
    );
    let markdown = scene_text(&boundary, kept, &report.table);
    let views = Layout::tab_rows(vec![tabs, normal_tabs]);
    Ok(SceneOutput::beside_text(report, markdown, visuals, views)
        .on_timeline("phase")
        .y_up())
}

/// One method's constraint modes, normal frequencies and their differences to the full model
/// into the report (the first method's also under the stable keys) and its table row.
fn insert_method(
    report: &mut Report,
    table: &mut Table,
    (i, m): (usize, Method),
    ev: &MeanAxesEvaluation,
    (static_diff, angle): (f64, f64),
) {
    let cm: Vec<Vec<f64>> = (0..ev.constraint_modes.nrows())
        .map(|r| {
            (0..ev.constraint_modes.ncols())
                .map(|c| sig(ev.constraint_modes[(r, c)]))
                .collect()
        })
        .collect();
    // The first method gives the stable keys; every method is reported under its id.
    if i == 0 {
        report.results.insert("constraint_modes".into(), json!(cm));
        report
            .results
            .insert("normal_hz".into(), json!(sig_vec(&ev.normal_hz)));
    }
    report.results.insert(
        m.id().into(),
        json!({
            "constraint_modes": cm,
            "normal_hz": sig_vec(&ev.normal_hz),
            "static_max_diff_vs_full": static_diff,
            "normal_modes_max_angle_vs_full_rad": angle,
        }),
    );
    table.push(vec![
        Cell::text(m.id().to_uppercase()),
        Cell::number(
            static_diff,
            flexmodes_core::report::readable(static_diff, 2).to_string(),
        ),
        Cell::text(crate::report::fmt_hz(&ev.normal_hz)),
        Cell::number(
            angle,
            flexmodes_core::report::readable(angle, 2).to_string(),
        ),
    ]);
}

/// The scene's text above its `table`.
fn scene_text(boundary: &[usize], kept: usize, table: &str) -> String {
    format!(
        "# beam-mean-axes\n\n§8.4-8.5: the App. A beam reduced with boundary nodes {boundary:?} \
         and {kept} kept modes, its frame on the mean axes (origin at the mass centre). The \
         transformation matrix is built the conventional (nodal-fixed) way; the mean-axis \
         conditions enter as Lagrange multipliers. The static problem (Eq. 8.44) gives the \
         constraint modes as absolute displacements, the constrained eigenproblem (Eq. 8.45) \
         the normal modes. Mode condensation reproduces the full model's constraint modes \
         exactly and its two lowest fixed-interface frequencies: mode shapes prepared for \
         nodal-fixed axes work with mean axes. Views: each method's constraint modes (top tabs, with \
         the full model's) and normal modes (bottom tabs), on the mean axes.\n\n{}",
        table
    )
}

/// One method's constraint modes and normal modes on the mean axes, drawn in its colour, and
/// their two tabs (constraint modes above, normal modes below). Titles are short enough for a
/// 1280 × 800 window; the entity paths keep the full set names.
fn method_views(
    model: &FeModel,
    part: &Partition,
    m: Method,
    ev: &MeanAxesEvaluation,
) -> (Vec<Visual>, [Layout; 2]) {
    let color = method_color(m);
    let cm_modes: Vec<(Vec<f64>, String)> = columns(&ev.constraint_modes)
        .into_iter()
        .zip(&part.b)
        .map(|(u, &dof)| (u, format!("constraint {}", model.dof_label(dof))))
        .collect();
    let set_c = format!("{}_mean_constraint", m.id());
    let mut visuals = mode_set(model, &set_c, &cm_modes, color);
    let nm: Vec<(Vec<f64>, String)> = columns(&ev.normal_modes)
        .into_iter()
        .zip(&ev.normal_hz)
        .enumerate()
        .map(|(k, (u, f))| (u, format!("normal {}: {f:.6} Hz", k + 1)))
        .collect();
    let set_n = format!("{}_mean_normal", m.id());
    visuals.extend(mode_set(model, &set_n, &nm, color));
    let id = m.id().to_uppercase();
    (
        visuals,
        [
            Layout::view3d(&id, &format!("/modes/{set_c}")),
            Layout::view3d(&id, &format!("/modes/{set_n}")),
        ],
    )
}
