//! The slab simulations' views: one lane per method with its ghost, label, body, histories
//! and health series, and the speed–accuracy chart.

use crate::record::{REFERENCE_GHOST, method_color};

use crate::fem::NodeIndex;
use crate::models::slab_node;
use crate::scenes::slab::sim_visuals::{
    SimulatedBody, body_trajectory, frame_axes, ghost_trajectory, health_series, times,
};
use crate::{
    Result,
    analysis::relative_rms,
    dynamics::AxisType,
    fem::FeModel,
    record::{Geometry, Visual},
    reduction::Method,
};

use crate::scenes::slab::slab_sim_report::{DIRECTIONS, Run};

/// Speed against accuracy: x = wall time relative to NR, y = mean relative RMS error of node
/// 8 (a 2D view grows y downward: the fast, accurate corner is top left). `None` without NR.
pub(super) fn speed_accuracy(runs: &[Run], reference: Option<&[Vec<f64>; 3]>) -> Option<Visual> {
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
pub(super) fn lanes(
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
            SimulatedBody {
                system,
                sim,
                body: 0,
            },
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
            SimulatedBody {
                system,
                sim,
                body: 0,
            },
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
                SimulatedBody {
                    system,
                    sim,
                    body: 0,
                },
                format!("world/slab/frame/{}", axes.id()),
                1.0,
            ));
        }
    }
    Ok(())
}
