//! Bodies and states the dynamics' unit tests share.

use super::{AxisType, FlexibleBody, State, System};
use crate::{
    fem::{FeModel, SlabParameters, plank},
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
};

/// The §5.3.3 plank reduced by `method` (6 modes on the boundary nodes 3, 15 and 22) on
/// `axes`, and its model.
pub(super) fn reduced_plank(method: Method, axes: AxisType) -> (FeModel, FlexibleBody) {
    let model = plank(&SlabParameters::default());
    let basis = reduce(
        &model,
        &ReductionRequest {
            method,
            boundary_nodes: vec![3, 15, 22],
            modes: ModeSelection::Count(6),
            ..Default::default()
        },
    )
    .unwrap();
    let body = FlexibleBody::new(model.clone(), basis, axes).unwrap();
    (model, body)
}

/// Sets `state` moving and deformed: every velocity and every body's modal coordinates
/// nonzero, by fixed patterns (no randomness).
pub(super) fn set_in_motion(system: &System, state: &mut State) {
    for (i, v) in state.v.iter_mut().enumerate() {
        *v = ((i * 7919) % 13) as f64 / 13.0 - 0.4;
    }
    for b in 0..system.bodies.len() {
        let (qo, _) = system.offsets(b);
        for i in 7..system.bodies[b].position_count() {
            state.q[qo + i] += 1e-3 * ((i % 5) as f64 - 2.0);
        }
    }
}
