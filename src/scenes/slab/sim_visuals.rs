//! Visuals shared by the simulation scenes: a body's motion, its frame, the default layout.

use crate::{
    dynamics::{Simulation, System},
    record::{Color, Geometry, Layout, Visual},
};

/// Times of the samples, s.
pub fn times(sim: &Simulation) -> Vec<f64> {
    sim.samples.iter().map(|s| s.t).collect()
}

/// Largest drawn elastic deflection as a fraction of the body's size: what a student can see.
const VISIBLE_DEFLECTION: f64 = 0.1;

/// The factor that draws the largest elastic deflection of body `body` over all `runs` at
/// about [`VISIBLE_DEFLECTION`] of `size` (m), rounded down to 1, 2 or 5 × 10ⁿ; never below 1
/// (deflections already visible are drawn true to scale). One factor for all runs of a view,
/// so methods compare.
pub fn deformation_scale<'a>(
    runs: impl IntoIterator<Item = (&'a System, &'a Simulation)>,
    body: usize,
    size: f64,
) -> f64 {
    let mut largest = 0.0f64;
    for (system, sim) in runs {
        for s in &sim.samples {
            largest = largest.max(system.largest_deflection(body, &s.state));
        }
    }
    display_scale(largest, size)
}

/// The factor that draws a largest deflection `largest` at about [`VISIBLE_DEFLECTION`] of
/// `size` (same unit), rounded down to 1, 2 or 5 × 10ⁿ; never below 1.
pub fn display_scale(largest: f64, size: f64) -> f64 {
    if largest <= 0.0 || !largest.is_finite() {
        return 1.0;
    }
    let wanted = VISIBLE_DEFLECTION * size / largest;
    if wanted <= 1.0 {
        return 1.0;
    }
    let decade = 10f64.powf(wanted.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&f| f <= wanted)
        .unwrap_or(decade)
}

/// One body of a simulated system: the system, its simulation and the body's index.
#[derive(Clone, Copy)]
pub struct SimulatedBody<'a> {
    pub system: &'a System,
    pub sim: &'a Simulation,
    pub body: usize,
}

/// The deformable body `body` (its nodes drawn with `geometry`) over `sim_time`, its elastic
/// deflection drawn `scale` times (0: the undeformed ghost moving with the frame).
pub fn body_trajectory(
    SimulatedBody { system, sim, body }: SimulatedBody<'_>,
    path: String,
    geometry: &Geometry,
    color: Color,
    scale: f64,
) -> Visual {
    let positions = sim
        .samples
        .iter()
        .map(|s| {
            system
                .node_positions_scaled(body, &s.state, scale)
                .into_iter()
                .take(geometry.nodes.len())
                .map(|p| [p.x, p.y, p.z])
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

/// The frame of `body` at every sample: origins (m) and the columns of its rotation matrix.
#[allow(clippy::type_complexity)]
fn placements(
    system: &System,
    sim: &Simulation,
    body: usize,
) -> (Vec<[f64; 3]>, Vec<[[f64; 3]; 3]>) {
    sim.samples
        .iter()
        .map(|s| {
            let (r, a) = system.placement(body, &s.state);
            (
                [r.x, r.y, r.z],
                [0, 1, 2].map(|c| [a[(0, c)], a[(1, c)], a[(2, c)]]),
            )
        })
        .unzip()
}

/// Deformable body `body` undeformed and carried by its frame over `sim_time` (the ghost
/// beside its deflected drawing): its outline once in body coordinates, the frame's
/// placement per time.
pub fn ghost_trajectory(
    SimulatedBody { system, sim, body }: SimulatedBody<'_>,
    path: String,
    geometry: &Geometry,
    color: Color,
) -> Visual {
    let local = match &system.bodies[body] {
        crate::dynamics::Body::Flexible(fb) => Geometry {
            nodes: fb.s_bar.iter().map(|p| [p.x, p.y, p.z]).collect(),
            strips: geometry.strips.clone(),
        },
        crate::dynamics::Body::Rigid(_) => geometry.clone(),
    };
    let (translations, rotations) = placements(system, sim, body);
    Visual::RigidTrajectory {
        path,
        geometry: local,
        times: times(sim),
        translations,
        rotations,
        color,
    }
}

/// The floating frame of `body` over `sim_time` as three arrows of `length` m.
pub fn frame_axes(
    SimulatedBody { system, sim, body }: SimulatedBody<'_>,
    path: String,
    length: f64,
) -> Visual {
    let (origins, axes) = placements(system, sim, body);
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

/// The largest position-constraint violation (as log₁₀ of metres) and the total energy over
/// time, at `plots/constraint_violation/<suffix>` and `plots/energy/<suffix>`.
pub fn health_series(sim: &Simulation, suffix: &str, color: Color) -> [Visual; 2] {
    [
        Visual::Series {
            path: format!("plots/constraint_violation/{suffix}"),
            times: times(sim),
            // As a power of ten: the violations are round-off (1e-16 to 1e-12 m), which the
            // viewer's linear axis prints as rows of zeros.
            values: sim
                .samples
                .iter()
                .map(|s| s.position_violation.max(1e-18).log10())
                .collect(),
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
