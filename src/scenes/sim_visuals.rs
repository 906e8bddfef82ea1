//! Visuals shared by the simulation scenes: a body's motion, its frame, the default layout.

use crate::{
    dynamics::{Simulation, System},
    record::{Color, Geometry, Layout, Visual},
};

/// Times of the samples, s.
pub fn times(sim: &Simulation) -> Vec<f64> {
    sim.samples.iter().map(|s| s.t).collect()
}

/// The deformable body `body` (its nodes drawn with `geometry`) over `sim_time`.
pub fn body_trajectory(
    system: &System,
    sim: &Simulation,
    body: usize,
    path: String,
    geometry: &Geometry,
    color: Color,
) -> Visual {
    let positions = sim
        .samples
        .iter()
        .map(|s| {
            (0..geometry.nodes.len())
                .map(|j| {
                    let p = system.node_position(body, j, &s.state);
                    [p.x, p.y, p.z]
                })
                .collect()
        })
        .collect();
    Visual::Trajectory {
        path,
        geometry: geometry.clone(),
        times: times(sim),
        positions,
        color,
    }
}

/// The floating frame of `body` over `sim_time` as three arrows of `length` m.
pub fn frame_axes(
    system: &System,
    sim: &Simulation,
    body: usize,
    path: String,
    length: f64,
) -> Visual {
    let (origins, axes) = sim
        .samples
        .iter()
        .map(|s| {
            let (r, a) = system.placement(body, &s.state);
            (
                [r.x, r.y, r.z],
                [0, 1, 2].map(|c| [a[(0, c)], a[(1, c)], a[(2, c)]]),
            )
        })
        .unzip();
    Visual::FrameAxes {
        path,
        times: times(sim),
        origins,
        axes,
        length,
    }
}

/// A 3D view over time-series views, beside the scene text.
pub fn simulation_layout(view: Layout, plots: Vec<Layout>) -> Layout {
    Layout::Horizontal(
        vec![
            Layout::Vertical(
                vec![view, Layout::Horizontal(plots, vec![])],
                vec![1.0, 1.0],
            ),
            Layout::scene_text(),
        ],
        vec![3.0, 1.0],
    )
}

/// The largest position-constraint violation and the total energy over time, at
/// `plots/constraint_violation/<suffix>` and `plots/energy/<suffix>`.
pub fn health_series(sim: &Simulation, suffix: &str, color: Color) -> [Visual; 2] {
    [
        Visual::Series {
            path: format!("plots/constraint_violation/{suffix}"),
            times: times(sim),
            values: sim.samples.iter().map(|s| s.position_violation).collect(),
            name: suffix.into(),
            color,
        },
        Visual::Series {
            path: format!("plots/energy/{suffix}"),
            times: times(sim),
            values: sim.samples.iter().map(|s| s.energy).collect(),
            name: suffix.into(),
            color,
        },
    ]
}
