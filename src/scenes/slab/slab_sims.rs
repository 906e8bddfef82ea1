//! `slab-sim1`, `slab-sim2`, `slab-sim3`: the time simulations of §7.2 for every method.

use serde_json::json;

use crate::dynamics::AxisKind;
use crate::models::{
    DrivenTables, PROBE_NODE, SIM1_END, SIM2_END, SIM3_END, SLAB_BOUNDARY, Scenario,
    default_boundary, probe_history, record_driving_tables, slab_body, slab_node, slab_system,
};
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    slab::sim_visuals::{deformation_scale, simulation_layout},
};
use crate::{
    Progress, Result,
    dynamics::{AxisType, IntegratorParameters, Simulation, System, simulate},
    fem::{BrickElements, FeModel, SlabParameters, slab},
    record::{Geometry, Layout, Visual},
    reduction::{Method, NodalFixedAxes},
    report::Report,
};

pub use crate::scenes::slab::slab_sim_report::insert_integrator;
use crate::scenes::slab::slab_sim_report::{
    DIRECTIONS, Run, ScenarioSettings, errors_table, scenario_parameters, scenario_text,
};
use crate::scenes::slab::slab_sim_views::{lanes, speed_accuracy};

/// The options of the three slab simulations; `end` is the default interval, s.
const fn sim_controls(end: f64) -> crate::scenes::scene_info::SceneControls {
    crate::scenes::scene_info::SceneControls {
        methods: &METHODS,
        boundary: &SLAB_BOUNDARY,
        modes: Some(6),
        axes: &AxisKind::ALL,
        end_time: Some(end),
        refine: Some(crate::scenes::slab::slab_modes::APP_B_BRICKS),
        stiffening: true,
        ..crate::scenes::scene_info::SceneControls::NONE
    }
}

pub const INFO_1: SceneInfo = SceneInfo {
    name: "slab-sim1",
    recording_cost: 5,
    summary: "§7.2.2 slab held at six coordinates under gravity: node 8's deflections by NR, \
              MT, CB, MC and GR over time",
    sections: "§7.2.2",
    controls: sim_controls(SIM1_END),
};

pub const INFO_2: SceneInfo = SceneInfo {
    name: "slab-sim2",
    recording_cost: 8,
    summary: "§7.2.3 slab pinned at nodes 16, 18 with node 30 driven on the orbit of Eq. 7.10: \
              node 8's deflections by every method",
    sections: "§7.2.3",
    controls: sim_controls(SIM2_END),
};

impl crate::scenes::run_cache::CacheWeight for DrivenTables {
    fn bytes(&self) -> usize {
        self.values
            .iter()
            .flatten()
            .map(|v| std::mem::size_of::<f64>() * v.len())
            .sum()
    }
}

pub const INFO_3: SceneInfo = SceneInfo {
    name: "slab-sim3",
    recording_cost: 6,
    summary: "§7.2.4 slab driven at nodes 16, 18, 28, 30 by accelerations recorded from the \
              two-link simulation of Fig. 7-12(b)",
    sections: "§7.2.4",
    controls: sim_controls(SIM3_END),
};

const METHODS: [Method; 5] = [
    Method::NoReduction,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
    Method::Guyan,
];

/// Parses `--axes` for the dynamic scenes.
pub fn axis_type(kind: Option<AxisKind>) -> AxisType {
    match kind.unwrap_or(AxisKind::NodalFixed) {
        AxisKind::NodalFixed => AxisType::NodalFixed(NodalFixedAxes::slab_default()),
        AxisKind::Mean => AxisType::Mean,
        AxisKind::Principal => AxisType::Principal,
    }
}

/// What determines one method's time integration in a scene (the [`RunCache`](crate::scenes::RunCache) key): boundary
/// nodes matter to every method but NR, kept modes to MT, CB and MC only.
pub fn run_key(
    scene: &'static str,
    method: Method,
    axes: AxisType,
    boundary: &[usize],
    modes: usize,
    params: &IntegratorParameters,
) -> String {
    let boundary = if method == Method::NoReduction {
        &[][..]
    } else {
        boundary
    };
    let modes = match method {
        Method::NoReduction | Method::Guyan => 0,
        _ => modes,
    };
    format!(
        "{scene}/{}/{axes:?}/{boundary:?}/{modes}/{:x}/{:?}/{:?}",
        method.id(),
        params.end_time.to_bits(),
        params.scheme,
        params.fixed_step.map(f64::to_bits)
    )
}

/// Runs every requested method of a scenario.
pub fn run_scenario(
    info: &SceneInfo,
    scenario: Scenario,
    opts: &SceneOptions,
) -> Result<SceneOutput> {
    let methods = opts.methods_or(info.name, &METHODS, &METHODS)?;
    let axes = axis_type(opts.axes);
    let modes = opts.modes_or_default(info);
    let bricks = opts
        .refine
        .unwrap_or(crate::scenes::slab::slab_modes::APP_B_BRICKS);
    let model = slab(&SlabParameters::refined(bricks)?);
    let boundary = opts
        .boundary
        .clone()
        .unwrap_or_else(|| default_boundary(&model));
    let probe = slab_node(&model, PROBE_NODE);
    let params = opts.integrator_parameters(info)?;
    let stiffened = opts.stiffening.unwrap_or(false);
    let elements = stiffened
        .then(|| SlabParameters::refined(bricks).map(|p| BrickElements::of_slab(&p)))
        .transpose()?;
    let integrate = |m: Method, progress: &Progress| {
        let key = format!(
            "{}/{bricks:?}/{}",
            run_key(info.name, m, axes, &boundary, modes, &params),
            if stiffened { "stiffened" } else { "linear" }
        );
        opts.cache.get_or_run(key, || {
            progress.phase(&format!("{} integration", m.name()))?;
            let mut body = slab_body(&model, m, axes, &boundary, modes)?;
            if let Some(elements) = &elements {
                body = body.with_stiffening(elements)?;
            }
            let (system, state) = slab_system(&scenario, body)?;
            let sim = simulate(&system, &state, &params, progress)?;
            Ok((system, sim))
        })
    };
    let integrated = crate::work_pool::run_concurrently(
        &methods,
        opts.concurrent_integrations,
        &opts.progress,
        integrate,
    );
    let integrated = integrated.into_iter().collect::<Result<Vec<_>>>()?;
    // Borrowed from the cache's entries: a switch copies no samples.
    let runs: Vec<(Method, &System, &Simulation, [Vec<f64>; 3])> = methods
        .iter()
        .zip(&integrated)
        .map(|(&m, run)| (m, &run.0, &run.1, probe_history(&run.0, &run.1, probe)))
        .collect();
    let mut report = Report::new(info.name);
    let settings = ScenarioSettings {
        methods: &methods,
        axes,
        modes,
        bricks,
        boundary: &boundary,
        params: &params,
    };
    scenario_parameters(&mut report, &settings, &model);
    report
        .parameters
        .insert("stiffening".into(), json!(stiffened));
    let reference = runs
        .iter()
        .find(|r| r.0 == Method::NoReduction)
        .map(|r| r.3.clone());
    errors_table(&mut report, &runs, reference.as_ref(), &params);
    let markdown = scenario_text(
        info,
        &model,
        bricks,
        &params,
        opts,
        methods.len(),
        &report.table,
    );
    // Deflections of a few cm on a 4 m slab: drawn magnified, one factor for every method.
    let scale = opts.deformation_scale_or(info.name, || {
        deformation_scale(
            runs.iter().map(|(_, system, sim, _)| (*system, *sim)),
            0,
            model.size(),
        )
    })?;
    let visuals = scenario_visuals(&runs, reference.as_ref(), &model, (&methods, axes), scale)?;
    report
        .results
        .insert("deformation_scale".into(), json!(scale));
    let layout = scenario_layout(&visuals, scale);
    Ok(SceneOutput::new(report, markdown, visuals, layout).on_timeline("sim_time"))
}

/// The undeformed slab, the speed–accuracy chart against the full model's `reference`
/// history, and one lane per method seen from `axes`, drawn `scale` times.
fn scenario_visuals(
    runs: &[Run],
    reference: Option<&[Vec<f64>; 3]>,
    model: &FeModel,
    (methods, axes): (&[Method], AxisType),
    scale: f64,
) -> Result<Vec<Visual>> {
    let geometry = Geometry::of(model);
    let mut visuals = vec![Visual::Wireframe {
        path: "world/slab/undeformed".into(),
        geometry: geometry.clone(),
        color: [150, 150, 150, 90],
        label: None,
    }];
    visuals.extend(speed_accuracy(runs, reference));
    lanes(&mut visuals, runs, model, &geometry, methods, axes, scale)?;
    Ok(visuals)
}

/// The scenario's views: the slab lanes (drawn `scale` times) with the speed–accuracy chart
/// and the health plots as tabs, above the three deflections of node 8.
fn scenario_layout(visuals: &[Visual], scale: f64) -> Layout {
    // The three deflections side by side under the lanes; the health plots are tabs of the
    // large top view, where their titles fit a 1280 × 800 window.
    let plot_views: Vec<Layout> = DIRECTIONS
        .iter()
        .map(|dir| Layout::TimeSeries {
            name: format!(
                "δ{} node 8, m",
                match *dir {
                    "xi" => "ξ",
                    "eta" => "η",
                    _ => "ζ",
                }
            ),
            origin: format!("/plots/node8/delta_{dir}"),
        })
        .collect();
    let health = [
        Layout::TimeSeries {
            name: "log₁₀ |Φ|, m".into(),
            origin: "/plots/constraint_violation".into(),
        },
        Layout::TimeSeries {
            name: "energy".into(),
            origin: "/plots/energy".into(),
        },
    ];
    let view = if scale != 1.0 {
        format!("slab lanes (×{scale}; grey: undeformed)")
    } else {
        "slab lanes (grey: undeformed)".to_string()
    };
    // The speed–accuracy chart as a tab of the large top view, where its labels fit.
    let mut top = vec![Layout::view3d(&view, "/world/slab")];
    if visuals.iter().any(|v| v.path() == "metrics/speed_accuracy") {
        top.push(Layout::Spatial2D {
            name: "speed vs accuracy".into(),
            origin: "/metrics/speed_accuracy".into(),
        });
    }
    top.extend(health);
    let top = Layout::Tabs(top);
    simulation_layout(top, plot_views)
}

pub fn run_sim1(opts: &SceneOptions) -> Result<SceneOutput> {
    run_scenario(&INFO_1, Scenario::HeldAtSix, opts)
}

pub fn run_sim2(opts: &SceneOptions) -> Result<SceneOutput> {
    run_scenario(&INFO_2, Scenario::Orbit, opts)
}

pub fn run_sim3(opts: &SceneOptions) -> Result<SceneOutput> {
    let axes = axis_type(opts.axes);
    let end = opts.end_time_or_default(&INFO_3)?;
    let tables = opts.cache.get_or_run(
        format!("{}/tables/{axes:?}/{:x}", INFO_3.name, end.to_bits()),
        || record_driving_tables(axes, end, &opts.progress).map_err(crate::Error::from),
    )?;
    run_scenario(&INFO_3, Scenario::Driven((*tables).clone()), opts)
}
