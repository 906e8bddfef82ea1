//! The planar beam of App. A: Euler–Bernoulli elements, rotations removed by Guyan condensation.

use faer::{Mat, Side, prelude::Solve};

use super::{DofMap, FeModel, RigidMotions, Triplets};
use crate::linalg::{MassMatrix, SparseSymmetric, select};

/// Parameters of the App. A beam. Defaults are the thesis values.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamParameters {
    /// Length, m.
    pub length: f64,
    /// Cross-section area, m² (b·h = 0.1 × 0.05).
    pub area: f64,
    /// Area moment of inertia, m⁴. The thesis prints bh³/12 rounded to 1.0417e-6, and its
    /// tables were made with the rounded value, so the default is the rounded one.
    pub second_moment: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Number of elements (nodes = elements + 1).
    pub elements: usize,
    /// Total mass, kg, lumped half of each element's share to its two end nodes.
    pub total_mass: f64,
}

impl Default for BeamParameters {
    /// The App. A values, read from the embedded `assets/thesis/beam-app-a.toml`.
    fn default() -> Self {
        crate::assets::parameters("thesis/beam-app-a.toml")
    }
}

/// Builds the beam along x with nodes 1..=elements+1, two translational DOF per node.
///
/// Each element carries $(u, v, \theta)$ at both ends; after assembly the rotations are
/// condensed statically, $K = K_{tt} - K_{tr}K_{rr}^{-1}K_{rt}$ (App. A, Eq. 6.8).
pub fn beam(p: &BeamParameters) -> FeModel {
    let ne = p.elements.max(1);
    let nn = ne + 1;
    let le = p.length / ne as f64;
    let ea = p.youngs_modulus * p.area / le;
    let ei = p.youngs_modulus * p.second_moment;
    let (l, l2, l3) = (le, le * le, le * le * le);
    let bend = [
        [12.0, 6.0 * l, -12.0, 6.0 * l],
        [6.0 * l, 4.0 * l2, -6.0 * l, 2.0 * l2],
        [-12.0, -6.0 * l, 12.0, -6.0 * l],
        [6.0 * l, 2.0 * l2, -6.0 * l, 4.0 * l2],
    ];
    // Element DOF order (u1, v1, th1, u2, v2, th2).
    let mut ke = Mat::<f64>::zeros(6, 6);
    ke[(0, 0)] = ea;
    ke[(3, 3)] = ea;
    ke[(0, 3)] = -ea;
    ke[(3, 0)] = -ea;
    let bdofs = [1, 2, 4, 5];
    for a in 0..4 {
        for b in 0..4 {
            ke[(bdofs[a], bdofs[b])] = ei / l3 * bend[a][b];
        }
    }
    let mut t = Triplets::new(3 * nn);
    for e in 0..ne {
        let dofs: Vec<usize> = (0..6).map(|a| 3 * e + a).collect();
        t.add_element(&dofs, &ke);
    }
    let k3 = t.to_dense();
    let trans: Vec<usize> = (0..nn).flat_map(|i| [3 * i, 3 * i + 1]).collect();
    let rot: Vec<usize> = (0..nn).map(|i| 3 * i + 2).collect();
    let k_tt = select(k3.as_ref(), &trans, &trans);
    let k_tr = select(k3.as_ref(), &trans, &rot);
    let k_rr = select(k3.as_ref(), &rot, &rot);
    // K_rr is positive definite for any beam (rotations alone always strain it).
    let llt = k_rr
        .llt(Side::Lower)
        .expect("rotational stiffness of a beam is positive definite");
    let k = &k_tt - &k_tr * llt.solve(k_tr.transpose());
    let k = Mat::from_fn(2 * nn, 2 * nn, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]));

    let me = p.total_mass / ne as f64;
    let mut m = vec![0.0; 2 * nn];
    for e in 0..ne {
        for node in [e, e + 1] {
            for d in 0..2 {
                m[2 * node + d] += 0.5 * me;
            }
        }
    }
    FeModel {
        name: "beam".into(),
        dofs: DofMap::planar(),
        nodes: (0..nn).map(|i| [i as f64 * le, 0.0, 0.0]).collect(),
        edges: (0..ne).map(|e| [e, e + 1]).collect(),
        // The condensed stiffness couples every translation (a dense 2nn × 2nn block).
        k: SparseSymmetric::from_dense(k.as_ref()),
        m: MassMatrix::Lumped(m),
        rigid_motions: RigidMotions::FromGeometry,
    }
}
