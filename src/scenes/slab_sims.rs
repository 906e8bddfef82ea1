//! `slab-sim1`, `slab-sim2`, `slab-sim3`: the time simulations of §7.2 for every method.

use crate::record::{REFERENCE_GHOST, method_color};
use serde_json::{Map, Value, json};

use super::{
    SceneInfo, SceneOptions, SceneOutput,
    sim_visuals::{
        body_trajectory, deformation_scale, frame_axes, ghost_trajectory, health_series,
        simulation_layout, times,
    },
};
use crate::dynamics::AxisKind;
use crate::fem::NodeIndex;
use crate::models::{
    DrivenTables, PROBE_NODE, SIM1_END, SIM2_END, SIM3_END, SLAB_BOUNDARY, Scenario,
    default_boundary, probe_history, record_driving_tables, slab_body, slab_node, slab_system,
};
use crate::{
    Progress, Result,
    analysis::{max_position_violation, relative_rms},
    dynamics::{AxisType, IntegrationScheme, IntegratorParameters, Simulation, System, simulate},
    fem::{FeModel, SlabParameters, slab},
    record::{Geometry, Layout, Visual},
    reduction::{Method, NodalFixedAxes},
    report::{Cell, Report, Table, sig},
};

/// The options of the three slab simulations; `end` is the default interval, s.
const fn sim_controls(end: f64) -> super::scene_info::SceneControls {
    super::scene_info::SceneControls {
        methods: &METHODS,
        boundary: &SLAB_BOUNDARY,
        modes: Some(6),
        axes: &AxisKind::ALL,
        end_time: Some(end),
        refine: Some(super::slab_modes::APP_B_BRICKS),
    }
}

pub const INFO_1: SceneInfo = SceneInfo {
    id: "slab-sim1",
    summary: "§7.2.2 slab held at six coordinates under gravity: node 8's deflections by NR, \
              MT, CB, MC and GR over time",
    sections: "§7.2.2",
    controls: sim_controls(SIM1_END),
};

pub const INFO_2: SceneInfo = SceneInfo {
    id: "slab-sim2",
    summary: "§7.2.3 slab pinned at nodes 16, 18 with node 30 driven on the orbit of Eq. 7.10: \
              node 8's deflections by every method",
    sections: "§7.2.3",
    controls: sim_controls(SIM2_END),
};

impl super::run_cache::CacheWeight for DrivenTables {
    fn bytes(&self) -> usize {
        self.values
            .iter()
            .flatten()
            .map(|v| std::mem::size_of::<f64>() * v.len())
            .sum()
    }
}

pub const INFO_3: SceneInfo = SceneInfo {
    id: "slab-sim3",
    summary: "§7.2.4 slab driven at nodes 16, 18, 28, 30 by accelerations recorded from the \
              two-link simulation of Fig. 7-12(b)",
    sections: "§7.2.4",
    controls: sim_controls(SIM3_END),
};

/// Node 8's local directions, as entity paths and report keys name them.
const DIRECTIONS: [&str; 3] = ["xi", "eta", "zeta"];

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

/// What determines one method's time integration in a scene (the [`RunCache`](super::RunCache) key): boundary
/// nodes matter to every method but NR, kept modes to MT, CB and MC only.
pub fn run_key(
    scene: &str,
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

/// The integrator a simulation ran with, in the report's parameters: `integrator` (`dp5` or
/// `gen-alpha`), `dt_s` (the fixed step, or null for adaptive steps) and, for generalized-α,
/// `rho_inf`.
pub fn insert_integrator(report: &mut Report, params: &IntegratorParameters) {
    report
        .parameters
        .insert("integrator".into(), json!(params.scheme.id()));
    report
        .parameters
        .insert("dt_s".into(), json!(params.step()));
    if let IntegrationScheme::GeneralizedAlpha { spectral_radius } = params.scheme {
        report
            .parameters
            .insert("rho_inf".into(), json!(spectral_radius));
    }
}

/// Runs every requested method of a scenario.
pub fn run_scenario(
    info: &SceneInfo,
    scenario: Scenario,
    opts: &SceneOptions,
) -> Result<SceneOutput> {
    let methods = opts.methods_or(info.id, &METHODS, &METHODS)?;
    let axes = axis_type(opts.axes);
    let modes = opts.modes_or_default(info);
    let bricks = opts.refine.unwrap_or(super::slab_modes::APP_B_BRICKS);
    let model = slab(&SlabParameters::refined(bricks)?);
    let boundary = opts
        .boundary
        .clone()
        .unwrap_or_else(|| default_boundary(&model));
    let probe = slab_node(&model, PROBE_NODE);
    let params = opts.integrator_parameters(info)?;
    let integrate = |m: Method, progress: &Progress| {
        let key = format!(
            "{}/{bricks:?}",
            run_key(info.id, m, axes, &boundary, modes, &params)
        );
        opts.cache.get_or_run(key, || {
            progress.phase(&format!("{} integration", m.name()))?;
            let body = slab_body(&model, m, axes, &boundary, modes)?;
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
    let mut report = Report::new(info.id);
    scenario_parameters(
        &mut report,
        &boundary,
        modes,
        axes,
        &params,
        bricks,
        &model,
        &methods,
    );
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
    let geometry = Geometry::of(&model);
    let mut visuals = vec![Visual::Wireframe {
        path: "world/slab/undeformed".into(),
        geometry: geometry.clone(),
        color: [150, 150, 150, 90],
        label: None,
    }];
    visuals.extend(speed_accuracy(&runs, reference.as_ref()));
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
    // Deflections of a few cm on a 4 m slab: drawn magnified, one factor for every method.
    let scale = opts.deformation_scale_or(info.id, || {
        deformation_scale(
            runs.iter().map(|(_, system, sim, _)| (*system, *sim)),
            0,
            model.size(),
        )
    })?;
    lanes(
        &mut visuals,
        &runs,
        &model,
        &geometry,
        &methods,
        axes,
        scale,
    )?;
    let view = if scale != 1.0 {
        format!("slab lanes (×{scale}; grey: undeformed)")
    } else {
        "slab lanes (grey: undeformed)".to_string()
    };
    report
        .results
        .insert("deformation_scale".into(), json!(scale));
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
    let layout = simulation_layout(top, plot_views);
    Ok(SceneOutput {
        report,
        markdown,
        visuals,
        layout,
        timeline: Some("sim_time".into()),
        y_up: false,
    })
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
        format!("{}/tables/{axes:?}/{:x}", INFO_3.id, end.to_bits()),
        || record_driving_tables(axes, end, &opts.progress),
    )?;
    run_scenario(&INFO_3, Scenario::Driven((*tables).clone()), opts)
}

/// One run of a scenario: the method, its system and simulation (borrowed from the run cache)
/// and node 8's local deflection history along ξ, η, ζ.
type Run<'a> = (Method, &'a System, &'a Simulation, [Vec<f64>; 3]);

/// Node 8's relative RMS errors against NR and each run's cost, into `report`'s results and
/// its table.
fn errors_table(
    report: &mut Report,
    runs: &[Run],
    reference: Option<&[Vec<f64>; 3]>,
    params: &IntegratorParameters,
) {
    let mut errors = Map::new();
    let mut walls = Map::new();
    let mut table = Table::new(&[
        "method",
        "rel. RMS ξ",
        "rel. RMS η",
        "rel. RMS ζ",
        "coordinates",
        "wall s",
        if matches!(params.scheme, IntegrationScheme::DormandPrince) {
            "steps / rejected"
        } else {
            "steps / Newton its"
        },
        "max Φ violation",
    ])
    .rank_lower(&[1, 2, 3]);
    for (m, system, sim, hist) in runs {
        walls.insert(m.id().into(), json!(sig(sim.wall_time_s)));
        let mut e = Map::new();
        let mut cells = vec![Cell::text(m.id().to_uppercase())];
        if let Some(r) = reference {
            for a in 0..3 {
                let v = relative_rms(&hist[a], &r[a]);
                e.insert(DIRECTIONS[a].into(), json!(sig(v)));
                // NR is the reference: its zero is not ranked.
                cells.push(if *m == Method::NoReduction {
                    Cell::text(format!("{v:.4}"))
                } else {
                    Cell::number(v, format!("{v:.4}"))
                });
            }
            errors.insert(m.id().into(), Value::Object(e));
        } else {
            cells.extend([Cell::text("-"), Cell::text("-"), Cell::text("-")]);
        }
        let max_pos = max_position_violation(sim);
        cells.push(Cell::text(format!("{}", system.nv())));
        cells.push(Cell::number(
            sim.wall_time_s,
            format!("{:.3}", sim.wall_time_s),
        ));
        cells.push(Cell::text(match params.scheme {
            IntegrationScheme::DormandPrince => format!("{} / {}", sim.steps, sim.rejected),
            _ => format!("{} / {}", sim.steps, sim.newton_iterations),
        }));
        cells.push(Cell::number(max_pos, format!("{max_pos:.1e}")));
        table.push(cells);
    }
    report
        .results
        .insert("rel_rms_error".into(), Value::Object(errors));
    report
        .results
        .insert("wall_time_s".into(), Value::Object(walls));
    report.table = report.add_table(table);
}

/// The scene's text: what was integrated and how, and the table.
fn scenario_text(
    info: &SceneInfo,
    model: &FeModel,
    bricks: [usize; 3],
    params: &IntegratorParameters,
    opts: &SceneOptions,
    methods: usize,
    table: &str,
) -> String {
    let probe = slab_node(model, PROBE_NODE);
    format!(
        "# {}\n\n{}\n\nThe slab: {} bricks, {} DOF{}. Every method is integrated by {}, Euler \
         parameters renormalised and positions and velocities projected onto the \
         constraints after each step (velocities by the correction of least kinetic energy, \
         which no choice of basis changes), so differences come from the bases alone: CB and \
         MC span one space, and on the App. B slab their errors agree to 1e-4 in every \
         simulation and axis type. There, with the default explicit scheme, the NR \
         reference's own integration error (against a rerun at rtol 1e-10) stays at least 100 \
         times below the smallest error these tables print; tests check both. The implicit \
         generalized-α scheme is second order: its integration error falls fourfold when \
         --dt is halved, and at 0.25 ms it stays within 5e-4 of the explicit histories of \
         simulation 1 (tested). Coordinates are the six of the frame plus the modal ones. \
         Errors are \
         the relative RMS of node 8's local deflection against NR over the interval.{}\n\n{}",
        info.id,
        info.summary,
        bricks.map(|b| b.to_string()).join(" × "),
        model.dof_count(),
        if bricks == super::slab_modes::APP_B_BRICKS {
            " (App. B)".to_string()
        } else {
            format!(
                " (refined; nodes {} are App. B's 16, 18, 28, 30 and node {probe} is App. B's \
                 node 8, the top-face centre)",
                default_boundary(model)
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        },
        params.describe(),
        match opts.concurrent_integrations.min(methods) {
            0 | 1 => String::new(),
            n => format!(
                " The integrations ran up to {n} at a time, one thread each: a wall time is \
                 its own thread's (`flexmodes bench` times them one after the other)."
            ),
        },
        table
    )
}

/// Speed against accuracy: x = wall time relative to NR, y = mean relative RMS error of node
/// 8 (a 2D view grows y downward: the fast, accurate corner is top left). `None` without NR.
fn speed_accuracy(runs: &[Run], reference: Option<&[Vec<f64>; 3]>) -> Option<Visual> {
    let (Some(r), Some(nr)) = (reference, runs.iter().find(|r| r.0 == Method::NoReduction)) else {
        return None;
    };
    {
        let nr_wall = nr.2.wall_time_s.max(1e-9);
        let (mut points, mut labels, mut colors) = (Vec::new(), Vec::new(), Vec::new());
        for (m, _, sim, hist) in runs {
            let err = (0..3).map(|a| relative_rms(&hist[a], &r[a])).sum::<f64>() / 3.0;
            let speed = sim.wall_time_s / nr_wall;
            points.push([speed, err]);
            labels.push(format!("{}: {speed:.2}× NR time, error {err:.3}", m.id()));
            colors.push(method_color(*m));
        }
        // Both axes on [0, 1] (time relative to NR, error relative to the worst method), so
        // the chart is square whatever the magnitudes; the labels carry the values.
        let worst = points.iter().map(|p| p[1]).fold(1e-12, f64::max);
        for p in &mut points {
            p[1] /= worst;
        }
        Some(Visual::Scatter {
            path: "metrics/speed_accuracy".into(),
            points,
            labels,
            colors,
        })
    }
}

/// One lane per method, then each method's body, histories and health series.
#[allow(clippy::too_many_arguments)]
fn lanes(
    visuals: &mut Vec<Visual>,
    runs: &[Run],
    model: &FeModel,
    geometry: &Geometry,
    methods: &[Method],
    axes: AxisType,
    scale: f64,
) -> Result<()> {
    // One lane per method, side by side along y (1.5 slab widths apart), each with its own
    // undeformed ghost carried by its frame and a label above App. B node 16's starting place:
    // bodies of different methods never hide one another.
    let width = {
        let ys = geometry.nodes.iter().map(|p| p[1]);
        ys.clone().fold(f64::MIN, f64::max) - ys.fold(f64::MAX, f64::min)
    };
    let label_node = model.node_index(slab_node(model, 16))?;
    for (k, (m, system, sim, _)) in runs.iter().enumerate() {
        let lane = format!("world/slab/{}", m.id());
        visuals.push(Visual::Offset {
            path: lane.clone(),
            translation: [0.0, -1.5 * width * k as f64, 0.0],
        });
        visuals.push(ghost_trajectory(
            system,
            sim,
            0,
            format!("{lane}/undeformed_ghost"),
            geometry,
            REFERENCE_GHOST,
        ));
        if let Some(first) = sim.samples.first() {
            // Above the body's highest point at the start, over node 16's corner.
            let p = system.node_position(0, label_node, &first.state);
            let top = (0..geometry.nodes.len())
                .map(|j| system.node_position(0, NodeIndex(j), &first.state).z)
                .fold(f64::MIN, f64::max);
            visuals.push(Visual::Label3D {
                path: format!("{lane}/label"),
                position: [p.x, p.y, top + 0.3 * width],
                text: m.id().to_uppercase(),
                color: method_color(*m),
            });
        }
    }
    for (m, system, sim, hist) in runs {
        let times = times(sim);
        visuals.extend(health_series(sim, m.id(), method_color(*m)));
        visuals.push(body_trajectory(
            system,
            sim,
            0,
            format!("world/slab/{}/{}", m.id(), axes.id()),
            geometry,
            method_color(*m),
            scale,
        ));
        for (a, dir) in DIRECTIONS.iter().enumerate() {
            visuals.push(Visual::Series {
                path: format!("plots/node8/delta_{dir}/{}", m.id()),
                times: times.clone(),
                values: hist[a].clone(),
                name: m.id().into(),
                color: method_color(*m),
            });
        }
        if *m == methods[0] {
            visuals.push(frame_axes(
                system,
                sim,
                0,
                format!("world/slab/frame/{}", axes.id()),
                1.0,
            ));
        }
    }
    Ok(())
}

/// What the scenario ran with, into `report`'s parameters.
#[allow(clippy::too_many_arguments)]
fn scenario_parameters(
    report: &mut Report,
    boundary: &[usize],
    modes: usize,
    axes: AxisType,
    params: &IntegratorParameters,
    bricks: [usize; 3],
    model: &FeModel,
    methods: &[Method],
) {
    report.parameters.insert("boundary".into(), json!(boundary));
    report.parameters.insert("modes".into(), json!(modes));
    report.parameters.insert("axes".into(), json!(axes.id()));
    report
        .parameters
        .insert("end_time_s".into(), json!(params.end_time));
    insert_integrator(report, params);
    report.parameters.insert("bricks".into(), json!(bricks));
    report
        .parameters
        .insert("dofs".into(), json!(model.dof_count()));
    report.parameters.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
}
