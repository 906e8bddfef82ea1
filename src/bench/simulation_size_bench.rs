//! `flexmodes bench slab-sim1 --sizes 4x2x1,8x4x2,12x6x3`: the online cost of each method in
//! a slab simulation against the size of the refined slab. Where reduction earns its keep:
//! the full model's cost grows with the mesh, a reduced model's stays that of its few
//! coordinates (only the recovery of node 8 and the constraints see the mesh).
//!
//! Timings are wall-clock seconds measured in one run on this machine; they are reported,
//! never asserted.

use std::time::Instant;

use serde_json::{Map, Value, json};

use crate::{
    Progress, Result,
    analysis::relative_rms,
    bench::{SizeBench, growth_exponent},
    dynamics::{AxisType, IntegratorParameters, simulate},
    fem::{FeModel, SlabParameters, slab},
    models::{
        PROBE_NODE, Scenario, default_boundary, probe_history, slab_body, slab_node, slab_system,
    },
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::{Method, NodalFixedAxes},
    report::{Report, markdown_table, sig},
};

/// Simulated interval of each run, s (the online cost is per simulated second).
pub const SIZES_RUN_S: f64 = 0.5;
/// Kept normal modes of MT, CB and MC (§7.2).
const KEPT_MODES: usize = 6;
/// The methods timed, the full model first (the reference of the errors).
const METHODS: [Method; 5] = [
    Method::NoReduction,
    Method::Guyan,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
];

/// One method on one mesh.
#[derive(Debug, Clone, PartialEq)]
struct SizePoint {
    method: Method,
    coordinates: usize,
    offline_s: f64,
    online_s_per_sim_s: f64,
    rel_rms_error: f64,
    steps: usize,
}

/// Every method of [`METHODS`] simulated on one mesh, NR first (the others' reference);
/// `(first, count)` number the points in the progress messages.
fn points_on_mesh(
    scenario: &Scenario,
    model: &FeModel,
    params: &IntegratorParameters,
    (first, count): (usize, usize),
    progress: &Progress,
) -> Result<Vec<SizePoint>> {
    let axes = AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let boundary = default_boundary(model);
    let probe = slab_node(model, PROBE_NODE);
    let mut reference: Option<[Vec<f64>; 3]> = None;
    let mut points = Vec::new();
    for (j, &method) in METHODS.iter().enumerate() {
        progress.phase(&format!(
            "point {} of {count}: {} on {} DOF",
            first + j + 1,
            method.id(),
            model.dof_count()
        ))?;
        let start = Instant::now();
        let body = slab_body(model, method, axes, &boundary, KEPT_MODES)?;
        let offline_s = start.elapsed().as_secs_f64();
        let coordinates = body.modes();
        let (system, state) = slab_system(scenario, body)?;
        let sim = simulate(&system, &state, params, progress)?;
        let history = probe_history(&system, &sim, probe);
        let rel_rms_error = match &reference {
            Some(r) => {
                (0..3)
                    .map(|d| relative_rms(&history[d], &r[d]))
                    .sum::<f64>()
                    / 3.0
            }
            None => 0.0,
        };
        if reference.is_none() {
            reference = Some(history);
        }
        points.push(SizePoint {
            method,
            coordinates,
            offline_s,
            online_s_per_sim_s: sim.wall_time_s / SIZES_RUN_S,
            rel_rms_error,
            steps: sim.steps,
        });
    }
    Ok(points)
}

/// Runs `scene` (slab-sim1 or slab-sim2) on every mesh of `sizes` with the explicit scheme
/// (adaptive steps) over [`SIZES_RUN_S`].
pub fn bench_sim_sizes(
    scene: &'static str,
    sizes: &[[usize; 3]],
    progress: &Progress,
) -> Result<SizeBench> {
    let scenario = super::bench_scenario(scene)?;
    let params = IntegratorParameters {
        end_time: SIZES_RUN_S,
        ..Default::default()
    };
    let mut per_size: Vec<(usize, [usize; 3], Vec<SizePoint>)> = Vec::new();
    let count = sizes.len() * METHODS.len();
    for (s, &bricks) in sizes.iter().enumerate() {
        let model = slab(&SlabParameters::refined(bricks)?);
        let first = s * METHODS.len();
        let points = points_on_mesh(&scenario, &model, &params, (first, count), progress)?;
        per_size.push((model.dof_count(), bricks, points));
    }
    let series_of = |m: Method| -> Vec<(f64, f64)> {
        per_size
            .iter()
            .filter_map(|(dofs, _, pts)| {
                pts.iter()
                    .find(|p| p.method == m)
                    .map(|p| (*dofs as f64, p.online_s_per_sim_s))
            })
            .collect()
    };
    let mut exponents = Map::new();
    for m in METHODS {
        if let Some(e) = growth_exponent(&series_of(m)) {
            exponents.insert(m.id().into(), json!(sig(e)));
        }
    }
    let mut rows = Vec::new();
    for (dofs, bricks, pts) in &per_size {
        let nr = pts[0].online_s_per_sim_s;
        for p in pts {
            rows.push(vec![
                format!("{}×{}×{}", bricks[0], bricks[1], bricks[2]),
                dofs.to_string(),
                p.method.id().into(),
                p.coordinates.to_string(),
                format!("{}", flexmodes_core::report::readable(p.offline_s, 3)),
                format!("{:.3}", p.online_s_per_sim_s),
                format!("{:.1}", nr / p.online_s_per_sim_s),
                format!("{:.4}", p.rel_rms_error),
                p.steps.to_string(),
            ]);
        }
    }
    let exponent_text: Vec<String> = exponents
        .iter()
        .filter_map(|(m, e)| e.as_f64().map(|e| format!("{} {e:.2}", m.to_uppercase())))
        .collect();
    let table = format!(
        "{scene} over {SIZES_RUN_S} s on each mesh, Dormand–Prince 5(4) with adaptive steps, \
         MT/CB/MC with {KEPT_MODES} kept modes, nodal-fixed axes. Speed-up against NR on the \
         same mesh; error: node 8's mean relative RMS against NR on the same mesh. Online cost \
         grows as DOF^k with k: {}.\n\n{}",
        exponent_text.join(", "),
        markdown_table(
            &[
                "bricks",
                "DOF",
                "method",
                "coordinates",
                "offline s",
                "online s per sim s",
                "speed-up vs NR",
                "rel. RMS error",
                "steps",
            ],
            &rows,
        )
    );
    let value = json!({
        "scene": scene,
        "run_s": SIZES_RUN_S,
        "sizes": per_size.iter().map(|(dofs, bricks, pts)| json!({
            "bricks": bricks,
            "dofs": dofs,
            "points": pts.iter().map(|p| json!({
                "method": p.method.id(),
                "modes": if p.method.keeps_normal_modes() { KEPT_MODES } else { 0 },
                "coordinates": p.coordinates,
                "offline_s": sig(p.offline_s),
                "online_s_per_sim_s": sig(p.online_s_per_sim_s),
                "rel_rms_error": sig(p.rel_rms_error),
                "steps": p.steps,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "online_growth_exponent": Value::Object(exponents),
    });
    let visuals = LogLogChart {
        path: "bench/online_cost".into(),
        x_unit: "DOF".into(),
        y_unit: "online s per simulated s".into(),
        series: METHODS
            .iter()
            .map(|&m| LogLogSeries {
                id: m.id().into(),
                label: m.id().to_uppercase(),
                color: method_color(m),
                points: series_of(m),
                line: true,
            })
            .collect(),
        x_linear: false,
    }
    .visuals();
    let mut report = Report::new(&format!("bench-{scene}-sizes"));
    report.table = table.clone();
    let recording = RecordingContent {
        report,
        markdown: format!("# bench {scene} --sizes\n\n{table}"),
        visuals,
        layout: Layout::Horizontal(
            vec![
                Layout::Spatial2D {
                    name: "online s per simulated s against DOF (log–log)".into(),
                    origin: "/bench/online_cost".into(),
                },
                Layout::Text {
                    name: "table".into(),
                    origin: "/scene".into(),
                },
            ],
            vec![1.3, 1.0],
        ),
        timeline: None,
        y_up: false,
    };
    Ok(SizeBench {
        value,
        table,
        recording,
    })
}
