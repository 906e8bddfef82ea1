//! `plank-symmetry`: §5.3.3, the plank hung under four rigid links, nodal-fixed versus mean axes.

use crate::dynamics::{IntegratorParameters, Simulation, System};
use crate::record::method_color;
use nalgebra::Vector3;
use serde_json::{Map, json};

use crate::dynamics::AxisKind;
use crate::models::{
    PLANK_BOUNDARY, PlankVariant as Variant, plank_body, plank_nodal_fixed, plank_setup,
    plank_system, symmetry_history,
};
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    slab::sim_visuals::{
        SimulatedBody, body_trajectory, frame_axes, health_series, simulation_layout, times,
    },
    slab::slab_sims::run_key,
};
use crate::{
    Result,
    analysis::{max_energy_drift, max_position_violation, max_until},
    dynamics::{AxisType, simulate},
    fem::{SlabParameters, plank},
    record::{Geometry, Layout, Visual},
    reduction::Method,
    report::{Cell, Report, Table, sig},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "plank-symmetry",
    recording_cost: 9,
    summary: "§5.3.3 plank hung under four rigid links: nodal-fixed axes lose the mirror \
              symmetry after the chains snap taut, mean axes keep it",
    sections: "§5.3.3, ch. 8",
    controls: crate::scenes::scene_info::SceneControls {
        methods: &[Method::NoReduction, Method::CraigBampton],
        modes: Some(6),
        axes: &[AxisKind::NodalFixed, AxisKind::Mean],
        end_time: Some(END_TIME),
        ..crate::scenes::scene_info::SceneControls::NONE
    },
};

const END_TIME: f64 = 1.5;
/// A time safely before the chains straighten, s.
const SNAP_TIME: f64 = 0.45;

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let variants = study_variants(opts)?;
    let modes = opts.modes_or_default(&INFO);
    let model = plank(&SlabParameters::default());
    let params = opts.integrator_parameters(&INFO)?;
    let mut report = Report::new(INFO.name);
    insert_parameters(&mut report, &params, modes);
    let mut defects = Map::new();
    let mut defects_before = Map::new();
    let mut walls = Map::new();
    let mut table = Table::new(&[
        "method",
        "axes",
        &format!("max defect before {SNAP_TIME} s, m"),
        "max defect, m",
        "max energy drift, J",
        "max Φ violation",
        "wall s",
    ])
    .rank_lower(&[2, 3]);
    let geometry = Geometry::of(&model);
    // The plank swings metres; its deflections are drawn true to scale unless asked otherwise.
    let deflection = opts.deformation_scale_or(INFO.name, || 1.0)?;
    let mut visuals = Vec::new();
    // The variants' integrations are independent: as many at once as the options allow.
    let runs = crate::work_pool::run_concurrently(
        &variants,
        opts.concurrent_integrations,
        &opts.progress,
        |v, progress| {
            let key = run_key(INFO.name, v.method, v.axes, &PLANK_BOUNDARY, modes, &params);
            opts.cache.get_or_run(key, || {
                progress.phase(&format!("{} with {} axes", v.method.name(), v.axes.id()))?;
                let body = plank_body(&model, v, modes)?;
                let (system, state) = plank_system(body)?;
                let sim = simulate(&system, &state, &params, progress)?;
                Ok((system, sim))
            })
        },
    );
    let runs = runs.into_iter().collect::<Result<Vec<_>>>()?;
    for (v, run) in variants.iter().zip(&runs) {
        let (system, sim) = (&run.0, &run.1);
        let hist = symmetry_history(system, sim);
        let max_defect = max_until(sim, &hist[2], f64::INFINITY);
        // Before the chains snap taut (free fall lasts about 0.49 s).
        let before = max_until(sim, &hist[2], SNAP_TIME);
        let key = if v.method == Method::NoReduction {
            v.axes.id().to_string()
        } else {
            format!("{}_{}", v.method.id(), v.axes.id())
        };
        defects_before.insert(key.clone(), json!(before));
        defects.insert(key.clone(), json!(max_defect));
        walls.insert(key.clone(), json!(sig(sim.wall_time_s)));
        let drift = max_energy_drift(sim);
        let viol = max_position_violation(sim);
        table.push(vec![
            Cell::text(v.method.id().to_uppercase()),
            Cell::text(v.axes.id()),
            Cell::number(
                before,
                flexmodes_core::report::readable(before, 3).to_string(),
            ),
            Cell::number(
                max_defect,
                flexmodes_core::report::readable(max_defect, 3).to_string(),
            ),
            Cell::number(
                drift,
                flexmodes_core::report::readable(drift, 3).to_string(),
            ),
            Cell::number(viol, flexmodes_core::report::readable(viol, 2).to_string()),
            Cell::number(sim.wall_time_s, format!("{:.2}", sim.wall_time_s)),
        ]);
        visuals.extend(variant_visuals(
            v, system, sim, &hist, &geometry, deflection,
        ));
    }
    report.results.insert(
        "max_symmetry_defect_m".into(),
        serde_json::Value::Object(defects),
    );
    report.results.insert(
        "symmetry_defect_before_snap_m".into(),
        serde_json::Value::Object(defects_before),
    );
    report
        .results
        .insert("wall_time_s".into(), serde_json::Value::Object(walls));
    report.table = report.add_table(table);
    let markdown = plank_text(&params, &report.table);
    let layout = plank_layout();
    Ok(SceneOutput::new(report, markdown, visuals, layout).on_timeline("sim_time"))
}

/// What the study ran with: its interval and integrator, the plank's drop, CB's boundary and
/// kept modes.
fn insert_parameters(report: &mut Report, params: &IntegratorParameters, modes: usize) {
    report
        .parameters
        .insert("end_time_s".into(), json!(params.end_time));
    crate::scenes::slab::slab_sims::insert_integrator(report, params);
    report
        .parameters
        .insert("drop_m".into(), json!(plank_setup().drop));
    report
        .parameters
        .insert("cb_boundary".into(), json!(PLANK_BOUNDARY));
    report.parameters.insert("modes".into(), json!(modes));
}

/// The plank in 3-D with the health plots as tabs (where their titles fit), above the
/// histories of nodes 3 and 15 and the symmetry defect.
fn plank_layout() -> Layout {
    let mut plots = Vec::new();
    for name in ["x_node3", "x_node15", "symmetry_defect"] {
        plots.push(Layout::TimeSeries {
            name: name.into(),
            origin: format!("/plots/plank/{name}"),
        });
    }
    // The health plots as tabs of the large top view, where their titles fit.
    let health = [
        Layout::TimeSeries {
            name: "energy".into(),
            origin: "/plots/energy".into(),
        },
        Layout::TimeSeries {
            name: "log₁₀ |Φ|, m".into(),
            origin: "/plots/constraint_violation".into(),
        },
    ];
    let mut top = vec![Layout::Spatial3D {
        name: "plank".into(),
        origin: "/world".into(),
        contents: vec!["$origin/**".into()],
    }];
    top.extend(health);
    simulation_layout(Layout::Tabs(top), plots)
}

/// The study's variants (NR on nodal-fixed and mean axes, CB on mean axes) that `--method`
/// and `--axes` leave; none left is a named error.
fn study_variants(opts: &SceneOptions) -> Result<Vec<Variant>> {
    let nodal = AxisType::NodalFixed(plank_nodal_fixed());
    let mut variants = vec![
        Variant {
            method: Method::NoReduction,
            axes: nodal,
        },
        Variant {
            method: Method::NoReduction,
            axes: AxisType::Mean,
        },
        Variant {
            method: Method::CraigBampton,
            axes: AxisType::Mean,
        },
    ];
    if let Some(ms) = &opts.methods {
        variants.retain(|v| ms.contains(&v.method));
    }
    if let Some(a) = opts.axes {
        variants.retain(|v| v.axes.kind() == a);
    }
    if variants.is_empty() {
        return Err(crate::Error::InvalidOption {
            option: "--method, --axes",
            scene: Some(INFO.name),
            reason: "the study runs nr with nodal_fixed and mean axes and cb with mean axes; \
                     the --method/--axes filter left none"
                .into(),
        });
    }
    Ok(variants)
}

/// One variant's plots (node 3's and 15's x and the defect), health series, plank, links and
/// frame.
fn variant_visuals(
    v: &Variant,
    system: &System,
    sim: &Simulation,
    hist: &[Vec<f64>; 3],
    geometry: &Geometry,
    deflection: f64,
) -> Vec<Visual> {
    let mut visuals = Vec::new();
    let times = times(sim);
    let color = if v.method == Method::NoReduction {
        match v.axes {
            AxisType::Mean => [60, 200, 110, 255],
            _ => [220, 60, 60, 255],
        }
    } else {
        method_color(v.method)
    };
    let suffix = format!("{}/{}", v.method.id(), v.axes.id());
    for (q, name) in [(0, "x_node3"), (1, "x_node15"), (2, "symmetry_defect")] {
        visuals.push(Visual::Series {
            path: format!("plots/plank/{name}/{suffix}"),
            times: times.clone(),
            values: hist[q].clone(),
            name: suffix.clone(),
            color,
        });
    }
    visuals.extend(health_series(sim, &suffix, color));
    visuals.push(body_trajectory(
        SimulatedBody {
            system,
            sim,
            body: 0,
        },
        format!("world/plank/{suffix}"),
        geometry,
        color,
        deflection,
    ));
    let link_geometry = Geometry {
        nodes: vec![[0.0; 3]; 8],
        strips: vec![vec![0, 1], vec![2, 3], vec![4, 5], vec![6, 7]],
    };
    let link_positions = sim
        .samples
        .iter()
        .map(|s| {
            let mut pts = Vec::new();
            for b in 1..5 {
                let (r, a) = system.placement(b, &s.state);
                for end in [-1.0, 1.0] {
                    let p = r + a * Vector3::new(end * plank_setup().link_length / 2.0, 0.0, 0.0);
                    pts.push([p.x, p.y, p.z]);
                }
            }
            pts
        })
        .collect();
    visuals.push(Visual::Trajectory {
        path: format!("world/links/{suffix}"),
        geometry: link_geometry,
        times: times.clone(),
        positions: link_positions,
        color: [200, 200, 200, 255],
    });
    visuals.push(frame_axes(
        SimulatedBody {
            system,
            sim,
            body: 0,
        },
        format!("world/plank/frame/{suffix}"),
        0.8,
    ));
    visuals
}

/// The scene's text: the setup the thesis leaves out, what the defect measures, the table.
fn plank_text(params: &IntegratorParameters, table: &str) -> String {
    format!(
        "# plank-symmetry\n\n§5.3.3: the App. B mesh standing as a plank (4 m wide, 2 m high, \
         1 m deep) hangs from its top front corners, nodes 3 and 15, each by a chain of two \
         rigid links (2 m, 1 kg) from fixed points; 250 N pull down at node 22 and gravity acts. \
         The thesis' figure with the initial configuration is missing: here each chain starts \
         folded outward in the front plane (anchors {height:.1} m above the corners, elbows \
         {out:.2} m outside), mirror-symmetric about x = 2 m, so the plank falls {drop} m and \
         the chains snap taut after about 0.5 s (\"hits the bottom\"). Everything is \
         symmetric, so x3 + x15 should stay 4 m: the defect is the largest \
         deviation, |x3 + x15 − 4 m|. The nodal-fixed frame (origin node 8, ξ \
         through node 14, η-plane through node 23) treats node 14's side differently; mean axes \
         (origin at the mass centre) treat all nodes alike. Craig-Bampton with boundary nodes \
         3, 15, 22 and mean axes shows reduction works with mean axes (chapter 8). \
         The system is conservative (fixed anchors, gravity, a constant force), so the energy \
         plot checks the integrator: {}, Euler parameters renormalised and joint positions \
         and velocities projected after every step.\n\n{}",
        params.describe(),
        table,
        height = 2.0 * plank_setup().link_length - plank_setup().drop,
        out = (plank_setup().link_length.powi(2)
            - (plank_setup().link_length - plank_setup().drop / 2.0).powi(2))
        .sqrt(),
        drop = plank_setup().drop,
    )
}
