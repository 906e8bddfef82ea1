//! A statically determinate support of a free solid body (the r-set of MacNeal–Rubin,
//! Spanos–Tsuha Eq. 11): 3-2-1 translations of three interior nodes far apart.

use crate::error::{RSetName, RSetProblem};
use crate::{
    Result,
    error::ReductionError,
    fem::{Direction, FeModel, NodeDof, NodeIndex},
    reduction::{Basis, MacNealRubinParameters, ModeSelection, macneal_rubin},
};

/// MacNeal–Rubin's basis of a free body with the interface `boundary` (1-based nodes): `kept`
/// free-interface modes and the residual flexibility, the rigid motions held for the
/// flexibility by the [`three_two_one_support`] of the interior nodes (Spanos–Tsuha Eq. 11).
pub fn macneal_rubin_on_body(model: &FeModel, boundary: &[usize], kept: usize) -> Result<Basis> {
    macneal_rubin(
        model,
        &MacNealRubinParameters {
            interface: model.dofs_of_nodes(boundary)?,
            r_set: three_two_one_support(model, boundary)?,
            modes: ModeSelection::Count(kept),
            held: Vec::new(),
        },
    )
}

/// Six translational DOF of three nodes outside `excluded` (1-based) that hold every rigid
/// motion of the body and no more: all three of the node A farthest from the mass centre, the
/// two of the node B farthest from A least aligned with AB, and the one of the node C farthest
/// from the line AB most aligned with the normal of the plane ABC. An error names why when the
/// body has fewer than three such nodes or they lie on a line.
pub fn three_two_one_support(model: &FeModel, excluded: &[usize]) -> Result<Vec<usize>> {
    let invalid = |problem| ReductionError::InvalidRSet {
        set: RSetName::Support321,
        problem,
    };
    let candidates: Vec<NodeIndex> = (0..model.node_count())
        .map(NodeIndex)
        .filter(|n| !excluded.contains(&n.number()))
        .collect();
    if candidates.len() < 3 {
        return Err(invalid(RSetProblem::TooFewNodes {
            nodes: candidates.len(),
        })
        .into());
    }
    let x = |n: NodeIndex| model.position(n);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let farthest = |score: &dyn Fn(NodeIndex) -> f64| {
        candidates
            .iter()
            .copied()
            .max_by(|&p, &q| score(p).total_cmp(&score(q)))
            .expect("three candidates")
    };
    let centre = model.mass_centre();
    let a = farthest(&|n| {
        let d = sub(x(n), centre);
        dot(d, d)
    });
    let b = farthest(&|n| {
        let d = sub(x(n), x(a));
        dot(d, d)
    });
    let ab = sub(x(b), x(a));
    let c = farthest(&|n| {
        let w = cross(ab, sub(x(n), x(a)));
        dot(w, w)
    });
    let normal = cross(ab, sub(x(c), x(a)));
    let size = dot(ab, ab).sqrt();
    if dot(normal, normal).sqrt() <= 1e-9 * size * size {
        return Err(invalid(RSetProblem::Collinear).into());
    }
    let axes = [Direction::X, Direction::Y, Direction::Z];
    let dof = |n: NodeIndex, d: Direction| model.node_dof(n.number(), NodeDof::Translation(d));
    let mut out = axes
        .iter()
        .map(|&d| dof(a, d))
        .collect::<Result<Vec<_>>>()?;
    // B: the two directions least aligned with AB.
    let mut by_alignment: Vec<(f64, Direction)> = axes
        .iter()
        .enumerate()
        .map(|(k, &d)| (ab[k].abs(), d))
        .collect();
    by_alignment.sort_by(|p, q| p.0.total_cmp(&q.0));
    for &(_, d) in &by_alignment[..2] {
        out.push(dof(b, d)?);
    }
    // C: the direction most aligned with the plane's normal.
    let k = (0..3)
        .max_by(|&p, &q| normal[p].abs().total_cmp(&normal[q].abs()))
        .unwrap_or(2);
    out.push(dof(c, axes[k])?);
    Ok(out)
}
