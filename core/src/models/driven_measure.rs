//! What a driven body's run is measured by: the map from a run's coordinates to the full
//! displacement field, the output sets' mean displacement and the reaction at the drive, and
//! the errors of one history against another.

use std::sync::Arc;

use faer::Mat;
use nalgebra::Vector3;

use crate::{
    analysis::MeanAxisView,
    dynamics::{Driving, FrameCoordinates},
    fem::FeModel,
    linalg::MassMatrix,
};

/// How a run's coordinates give the full displacement field.
#[derive(Debug, Clone)]
pub enum FieldMap {
    /// The full body's coordinates (free DOF, pinned rings' rotations).
    Full(Arc<FrameCoordinates>),
    /// A reduced body's basis Ψ (every DOF's row).
    Basis(Arc<Mat<f64>>),
}

impl FieldMap {
    /// The nodal displacements (node-major, every DOF) of coordinates `x`.
    pub fn field(&self, x: &[f64]) -> Vec<f64> {
        match self {
            FieldMap::Full(coords) => coords.extend(x),
            FieldMap::Basis(psi) => {
                assert_eq!(x.len(), psi.ncols(), "one coordinate per column of Ψ");
                let mut y = vec![0.0; psi.nrows()];
                for (c, &xc) in x.iter().enumerate() {
                    if xc != 0.0 {
                        let col = psi.col(c);
                        y.iter_mut()
                            .enumerate()
                            .for_each(|(i, y)| *y += col[i] * xc);
                    }
                }
                y
            }
        }
    }
}

/// What each sample is measured with: the output sets' DOF and the full field's pieces.
pub(super) struct Measure<'a> {
    pub(super) model: &'a FeModel,
    pub(super) s: Vec<f64>,
    /// The drive's master from the frame's origin (frame axes): moments are taken about it.
    pub(super) arm: Vector3<f64>,
    pub(super) axis: Vector3<f64>,
    pub(super) outputs: Vec<Vec<usize>>,
    pub(super) driving: Driving,
    /// Histories seen from mean axes: the view and, per output set, its rigid rows' mean.
    pub(super) mean_axes: Option<(MeanAxisView, Vec<Vec<Vec<f64>>>)>,
}

impl Measure<'_> {
    pub(super) fn output(&self, u_full: &[f64]) -> Vec<[f64; 3]> {
        let rigid = self
            .mean_axes
            .as_ref()
            .map(|(view, _)| view.rigid_part(u_full));
        self.outputs
            .iter()
            .enumerate()
            .map(|(o, dofs)| {
                let mut mean = [0.0; 3];
                for triple in dofs.chunks_exact(3) {
                    for a in 0..3 {
                        mean[a] += u_full[triple[a]] / (dofs.len() / 3) as f64;
                    }
                }
                if let (Some(q), Some((_, rows))) = (&rigid, &self.mean_axes) {
                    for (a, m) in mean.iter_mut().enumerate() {
                        *m -= rows[o][a].iter().zip(q).map(|(r, q)| r * q).sum::<f64>();
                    }
                }
                mean
            })
            .collect()
    }

    /// The reaction at the drive: the rate of the body's momentum less gravity, force and
    /// moment about the drive's master, from the nodal accelerations in frame axes
    /// $a = \ddot\theta\,e\times b + \dot\theta^2 e\times(e\times b) + 2\dot\theta\,e\times
    /// \dot u + \ddot u$, $b = s + u$.
    pub(super) fn reaction(&self, t: f64, u: &[f64], v: &[f64], a: &[f64]) -> [f64; 6] {
        let (rate, acceleration, g_body) = self.driving.at(t);
        let n = u.len();
        let mut acc = vec![0.0; n];
        for j in 0..n / 3 {
            let b = Vector3::new(
                self.s[3 * j] + u[3 * j],
                self.s[3 * j + 1] + u[3 * j + 1],
                self.s[3 * j + 2] + u[3 * j + 2],
            );
            let ud = Vector3::new(v[3 * j], v[3 * j + 1], v[3 * j + 2]);
            let e = self.axis;
            let x = e.cross(&b) * acceleration
                + e.cross(&e.cross(&b)) * (rate * rate)
                + e.cross(&ud) * (2.0 * rate)
                + Vector3::new(a[3 * j], a[3 * j + 1], a[3 * j + 2])
                - g_body;
            acc[3 * j..3 * j + 3].copy_from_slice(x.as_slice());
        }
        let w = mass_mul(&self.model.m, &acc);
        let mut out = [0.0; 6];
        for j in 0..n / 3 {
            let wj = Vector3::new(w[3 * j], w[3 * j + 1], w[3 * j + 2]);
            let b = Vector3::new(
                self.s[3 * j] + u[3 * j],
                self.s[3 * j + 1] + u[3 * j + 1],
                self.s[3 * j + 2] + u[3 * j + 2],
            );
            let m = (b - self.arm).cross(&wj);
            for q in 0..3 {
                out[q] += wj[q];
                out[3 + q] += m[q];
            }
        }
        out
    }
}

fn mass_mul(m: &MassMatrix, x: &[f64]) -> Vec<f64> {
    let y = m.mul(faer::MatRef::from_column_major_slice(x, x.len(), 1));
    (0..x.len()).map(|i| y[(i, 0)]).collect()
}

/// Per output, per sample.
pub(super) fn transpose(samples: Vec<Vec<[f64; 3]>>, outputs: usize) -> Vec<Vec<[f64; 3]>> {
    (0..outputs)
        .map(|o| samples.iter().map(|s| s[o]).collect())
        .collect()
}

fn norm3(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

fn diff3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// $\max_{o,t} |y_o(t) - y^{ref}_o(t)| / \max_{o,t} |y^{ref}_o(t)|$; the histories must be
/// sampled alike.
pub fn history_error(reference: &[Vec<[f64; 3]>], run: &[Vec<[f64; 3]>]) -> f64 {
    assert_eq!(reference.len(), run.len(), "outputs of the two runs");
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for (r, y) in reference.iter().zip(run) {
        assert_eq!(r.len(), y.len(), "samples of the two runs");
        for (&a, &b) in r.iter().zip(y) {
            largest = largest.max(norm3(a));
            worst = worst.max(norm3(diff3(a, b)));
        }
    }
    worst / largest.max(f64::MIN_POSITIVE)
}

/// The reaction force of the undeformed body on the frame at each sample.
pub(super) fn rigid_reaction(measure: &Measure<'_>, times: &[f64]) -> Vec<[f64; 3]> {
    let zero = vec![0.0; measure.s.len()];
    times
        .iter()
        .map(|&t| {
            let r = measure.reaction(t, &zero, &zero, &zero);
            [r[0], r[1], r[2]]
        })
        .collect()
}

pub(super) fn reaction_error(reference: &[[f64; 6]], run: &[[f64; 6]], rigid: &[[f64; 3]]) -> f64 {
    assert_eq!(reference.len(), run.len(), "samples of the two runs");
    assert_eq!(
        reference.len(),
        rigid.len(),
        "samples of the rigid reaction"
    );
    let force = |r: &[f64; 6]| [r[0], r[1], r[2]];
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for ((a, b), g) in reference.iter().zip(run).zip(rigid) {
        largest = largest.max(norm3(diff3(force(a), *g)));
        worst = worst.max(norm3(diff3(force(a), force(b))));
    }
    worst / largest.max(f64::MIN_POSITIVE)
}
