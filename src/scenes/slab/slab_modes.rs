//! `slab-modes`: the App. B slab's free-free, constraint and fixed-interface modes and the
//! frequencies of each reduced model (§7.2.1).

use faer::Mat;
use serde_json::{Map, Value, json};

use crate::dynamics::AxisKind;
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    frequency_bars::{FrequencyBars, SHOWN_MODES},
    mode_visuals::undeformed,
    slab::slab_mode_views::{ModeViews, slab_mode_views},
};
use crate::{
    Result,
    analysis::{elastic_hz, free_free_modes, reduced_hz, reduced_modes},
    fem::{FeModel, SlabParameters, slab},
    linalg::GeneralizedEigen,
    record::{Layout, Visual},
    reduction::{
        Method, ModeSelection, NodalFixedAxes, Partition, ReductionRequest, constraint_modes,
        fixed_interface_modes, reduce,
    },
    report::{Report, Table, fmt_hz, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "slab-modes",
    recording_cost: 0,
    summary: "App. B slab: free-free, constraint and fixed-interface modes for boundary nodes \
              16, 18, 28, 30, and the frequencies of the MT, CB, MC and GR models",
    sections: "§7.2.1, App. B",
    controls: crate::scenes::scene_info::SceneControls {
        methods: &[
            Method::ModalTruncation,
            Method::CraigBampton,
            Method::ModeCondensation,
            Method::Guyan,
        ],
        boundary: &[16, 18, 28, 30],
        modes: Some(6),
        axes: &[AxisKind::NodalFixed],
        refine: Some(APP_B_BRICKS),
        ..crate::scenes::scene_info::SceneControls::NONE
    },
};

/// The App. B mesh: 4 × 2 × 1 bricks.
pub const APP_B_BRICKS: [usize; 3] = [4, 2, 1];
/// §7.2.1: Guyan adds two masters so it has as many coordinates as the others (18).
const EXTRA_GUYAN_MASTERS: [usize; 2] = [5, 11];
/// Free-free modes drawn (all frequencies are reported).
const SHOWN_FREE_FREE: usize = 12;
const AVAILABLE: [Method; 4] = [
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
    Method::Guyan,
];

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    if let Some(bricks) = opts.refine
        && bricks != APP_B_BRICKS
    {
        return crate::scenes::slab::slab_refined::run(opts, &INFO, bricks);
    }
    let methods = opts.methods_or(INFO.name, &AVAILABLE, &AVAILABLE)?;
    let boundary = opts.boundary_or_default(&INFO);
    let kept = opts.modes_or_default(&INFO);
    let model = slab(&SlabParameters::default());
    let part = Partition::new(&model, &boundary)?;
    let psi_s = constraint_modes(&model, &part)?;
    let fi = fixed_interface_modes(&model, &part)?;
    let fixed_interface_hz = fi.hz();
    let ff = free_free_modes(&model)?;
    let free_free_hz = elastic_hz(&ff);
    let mut gr_masters = boundary.clone();
    gr_masters.extend(EXTRA_GUYAN_MASTERS.iter().filter(|n| !boundary.contains(n)));
    let nodal_fixed = opts.axes == Some(AxisKind::NodalFixed);
    let axes = NodalFixedAxes::slab_default();

    let mut reduced = Map::new();
    let mut reduced_nf = Map::new();
    let mut sizes = Map::new();
    let mut rigid_counts = Map::new();
    let mut rows = vec![vec![
        "NR (90 × 90, 6 rigid)".to_string(),
        fmt_hz(&free_free_hz[..free_free_hz.len().min(8)]),
    ]];
    let mut visuals = vec![undeformed(&model)];
    let mut bars = FrequencyBars::new(SHOWN_MODES);
    bars.push(Method::NoReduction, &free_free_hz);
    for &m in &methods {
        let params = ReductionRequest {
            boundary_nodes: if m == Method::Guyan {
                gr_masters.clone()
            } else {
                boundary.clone()
            },
            modes: ModeSelection::Count(kept),
            ..Default::default()
        };
        let basis = reduce(&model, &params.with_method(m))?;
        let eig = reduced_modes(&model, &basis)?;
        rigid_counts.insert(m.id().into(), json!(eig.zero_energy));
        let hz = eig.elastic_hz();
        reduced.insert(m.id().into(), json!(sig_vec(&hz)));
        sizes.insert(m.id().into(), json!([basis.psi.nrows(), basis.psi.ncols()]));
        rows.push(vec![
            format!(
                "{} (90 × {}, {} rigid)",
                m.id().to_uppercase(),
                basis.size(),
                eig.zero_energy
            ),
            fmt_hz(&hz[..hz.len().min(8)]),
        ]);
        if nodal_fixed {
            let nf = axes.apply(&model, &basis)?;
            let hz_nf = reduced_hz(&model, &nf)?;
            reduced_nf.insert(m.id().into(), json!(sig_vec(&hz_nf)));
        }
        bars.push(m, &hz);
    }

    let mut report = Report::new(INFO.name);
    insert_parameters(
        &mut report,
        (&boundary, &gr_masters),
        kept,
        &methods,
        nodal_fixed.then_some(&axes),
    );
    let r = &mut report.results;
    super::slab_mode_results::insert_mode_results(
        r,
        (&free_free_hz, &fixed_interface_hz),
        reduced,
        sizes,
    );
    r.insert("rigid_body_modes".into(), Value::Object(rigid_counts));
    r.insert("total_mass_kg".into(), json!(model.total_mass()));
    if nodal_fixed {
        r.insert("nodal_fixed_hz".into(), Value::Object(reduced_nf));
    }
    report.table = format!(
        "Lowest elastic free-free frequencies, Hz (boundary {boundary:?}, {kept} kept modes, GR \
         masters {gr_masters:?}):\n\n{}\nFixed-interface: {}\n",
        report.add_table(Table::from_text(&["model", "Hz"], &rows)),
        fmt_hz(&fixed_interface_hz[..fixed_interface_hz.len().min(8)]),
    );
    let markdown = scene_text(&boundary, kept, &bars.caption(), &report.table);
    visuals.extend(bars.visuals());

    let (mode_visuals, layout) = mode_views(&model, &part, &psi_s, (&fi, &ff), kept, bars.layout());
    visuals.extend(mode_visuals);
    Ok(SceneOutput::new(report, markdown, visuals, layout).on_timeline("phase"))
}

/// The scene's text: the slab, its views and the frequency chart's `caption`, above `table`.
fn scene_text(boundary: &[usize], kept: usize, caption: &str, table: &str) -> String {
    format!(
        "# slab-modes\n\nThe App. B slab (4 × 2 × 1 m, 8 trilinear bricks, 30 nodes, E = 0.2e6 Pa, \
         ν = 0.33, 62.4 kg lumped as Table B-1). Views: free-free elastic modes, the constraint \
         modes of boundary nodes {boundary:?} (unit boundary displacements, interior static), \
         the {kept} kept fixed-interface modes, and the full and reduced models' free-free \
         frequencies side by side. CB, MC and GR contain the six rigid-body motions and, being Ritz \
         approximations, are stiffer than the full model (Guyan most). MT does not: its \
         boundary columns move the boundary nodes alone, so it has no rigid-body mode and its \
         lowest frequencies are spoiled rigid-body motions, the failure §7.1 shows on the beam. \
         {}\n\n{}",
        caption, table
    )
}

/// The run's boundary and Guyan masters, kept modes, methods and nodal-fixed axes (when
/// asked for) into `report`.
fn insert_parameters(
    report: &mut Report,
    (boundary, gr_masters): (&[usize], &[usize]),
    kept: usize,
    methods: &[Method],
    nodal_fixed: Option<&NodalFixedAxes>,
) {
    report.parameters.insert("boundary".into(), json!(boundary));
    report
        .parameters
        .insert("guyan_masters".into(), json!(gr_masters));
    report.parameters.insert("modes".into(), json!(kept));
    report.parameters.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
    if let Some(axes) = nodal_fixed {
        report.parameters.insert(
            "axes".into(),
            json!({"type": "nodal_fixed", "origin": axes.origin, "axis_node": axes.axis_node, "plane_node": axes.plane_node}),
        );
    }
}

/// The slab's free-free, constraint ($\Psi_s$) and fixed-interface modes in tabs above the
/// frequency `chart`.
fn mode_views(
    model: &FeModel,
    part: &Partition,
    psi_s: &Mat<f64>,
    (fi, ff): (&GeneralizedEigen, &GeneralizedEigen),
    kept: usize,
    chart: Layout,
) -> (Vec<Visual>, Layout) {
    let shapes = part.assemble(part.unit_top(0).as_ref(), psi_s.as_ref());
    let labels: Vec<String> = part.b.iter().map(|&d| model.dof_label(d)).collect();
    slab_mode_views(ModeViews {
        model,
        part,
        constraint: &shapes,
        constraint_labels: &labels,
        fixed_interface: fi,
        free_free: ff,
        shown_free_free: SHOWN_FREE_FREE,
        kept,
        first_tab: "free_free",
        charts: vec![chart],
    })
}
