//! Measures of a time integration (§7.2): deflection histories of a node, the relative RMS
//! error against a reference history, energy drift and constraint violation, and the mirror
//! symmetry defect of §5.3.3.

use crate::{
    dynamics::{Body, Simulation, System},
    fem::NodeIndex,
};

/// Local deflections (ξ, η, ζ) of `node` of deformable body `body` at every
/// sample, $\Psi_j z$ in the body frame, m.
pub fn node_deflection_history(
    system: &System,
    sim: &Simulation,
    body: usize,
    node: NodeIndex,
) -> [Vec<f64>; 3] {
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    let Some(Body::Flexible(fb)) = system.bodies.get(body) else {
        return out;
    };
    for s in &sim.samples {
        let d = fb.deflection(node.get(), &system.modal(body, &s.state));
        for a in 0..3 {
            out[a].push(d[a]);
        }
    }
    out
}

/// $\sqrt{\sum (x - r)^2 / \sum r^2}$ over two histories sampled at the same times (the
/// absolute RMS when the reference is zero).
///
/// # Panics
/// When the histories differ in length: they come from runs with one output grid.
pub fn relative_rms(x: &[f64], reference: &[f64]) -> f64 {
    assert_eq!(
        x.len(),
        reference.len(),
        "histories on different output grids"
    );
    let num: f64 = x
        .iter()
        .zip(reference)
        .map(|(a, b)| (a - b) * (a - b))
        .sum();
    let den: f64 = reference.iter().map(|b| b * b).sum();
    if den == 0.0 {
        num.sqrt()
    } else {
        (num / den).sqrt()
    }
}

/// Largest $|E(t) - E(0)|$ over the samples, J.
pub fn max_energy_drift(sim: &Simulation) -> f64 {
    let Some(first) = sim.samples.first() else {
        return 0.0;
    };
    sim.samples
        .iter()
        .map(|s| (s.energy - first.energy).abs())
        .fold(0.0, f64::max)
}

/// Largest position-level constraint violation over the samples.
pub fn max_position_violation(sim: &Simulation) -> f64 {
    sim.samples
        .iter()
        .map(|s| s.position_violation)
        .fold(0.0, f64::max)
}

/// Global x of two nodes of body `body` that mirror each other about the plane
/// $x = x_{mid}$, and the symmetry defect $|x_a + x_b - 2x_{mid}|$, per sample (m).
pub fn mirror_defect_history(
    system: &System,
    sim: &Simulation,
    body: usize,
    nodes: (NodeIndex, NodeIndex),
    mid_x: f64,
) -> [Vec<f64>; 3] {
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    for s in &sim.samples {
        let xa = system.node_position(body, nodes.0, &s.state).x;
        let xb = system.node_position(body, nodes.1, &s.state).x;
        out[0].push(xa);
        out[1].push(xb);
        out[2].push((xa + xb - 2.0 * mid_x).abs());
    }
    out
}

/// Largest value of `values` at samples up to time `until` (s).
pub fn max_until(sim: &Simulation, values: &[f64], until: f64) -> f64 {
    sim.samples
        .iter()
        .zip(values)
        .filter(|(s, _)| s.t <= until)
        .map(|(_, v)| *v)
        .fold(0.0, f64::max)
}
