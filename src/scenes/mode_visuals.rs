//! Shared drawing helpers: mode sets laid out side by side, colours per method.

use crate::{
    fem::FeModel,
    record::{Color, Geometry, REFERENCE, Visual},
};

/// Largest displayed displacement of an animated mode, as a fraction of the body's size.
const MODE_AMPLITUDE: f64 = 0.15;

/// Per-node displacement of a DOF vector, scaled so its largest nodal displacement is
/// [`MODE_AMPLITUDE`] of the body size (a zero vector stays zero).
pub fn display_shape(model: &FeModel, u: &[f64]) -> Vec<[f64; 3]> {
    let mut per_node: Vec<[f64; 3]> = (0..model.node_count())
        .map(|i| {
            let mut d = [0.0; 3];
            let base = i * model.dofs.per_node();
            for (dir, o) in model.dofs.translations() {
                d[dir.index()] = u[base + o];
            }
            d
        })
        .collect();
    let largest = per_node
        .iter()
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0f64, f64::max);
    if largest > 0.0 {
        let s = MODE_AMPLITUDE * model.size() / largest;
        for d in &mut per_node {
            for v in d.iter_mut() {
                *v *= s;
            }
        }
    }
    per_node
}

/// Where mode `k` (0-based) of a set is placed, so a set reads like the thesis' figures.
fn slot(model: &FeModel, k: usize) -> [f64; 3] {
    if model.spatial_dim() == 2 {
        // Two columns, so a set of seven modes is about as wide as it is tall and the
        // default camera of a wide view frames all of it.
        [
            1.4 * model.size() * (k % 2) as f64,
            -0.5 * model.size() * (k / 2) as f64,
            0.0,
        ]
    } else {
        // Three columns in a wall facing the camera (rows stacked along z, not receding along
        // y), so neither the bodies nor their labels overlap on screen and the view is filled
        // from top to bottom; a gap of half the body's size between neighbours.
        let ext = |d: usize| {
            let lo = model
                .nodes
                .iter()
                .map(|p| p[d])
                .fold(f64::INFINITY, f64::min);
            let hi = model
                .nodes
                .iter()
                .map(|p| p[d])
                .fold(f64::NEG_INFINITY, f64::max);
            hi - lo
        };
        let gap = 0.5 * model.size();
        [
            (ext(0) + gap) * (k % 3) as f64,
            0.0,
            -(ext(2) + gap) * (k / 3) as f64,
        ]
    }
}

/// `modes/<set>/<k>` for each `(dof vector, label)`, animated over `phase`.
pub fn mode_set(
    model: &FeModel,
    set: &str,
    modes: &[(Vec<f64>, String)],
    color: Color,
) -> Vec<Visual> {
    let geometry = Geometry::of(model);
    let mut out = Vec::new();
    for (k, (u, label)) in modes.iter().enumerate() {
        let path = format!("modes/{set}/{}", k + 1);
        out.push(Visual::Offset {
            path: path.clone(),
            translation: slot(model, k),
        });
        out.push(Visual::Mode {
            path,
            geometry: geometry.clone(),
            shape: display_shape(model, u),
            label: label.clone(),
            color,
        });
    }
    out
}

/// `world/<body>/undeformed`.
pub fn undeformed(model: &FeModel) -> Visual {
    Visual::Wireframe {
        path: format!("world/{}/undeformed", model.name),
        geometry: Geometry::of(model),
        color: REFERENCE,
        label: None,
    }
}

/// The columns of a matrix as DOF vectors.
pub fn columns(m: &faer::Mat<f64>) -> Vec<Vec<f64>> {
    (0..m.ncols())
        .map(|j| (0..m.nrows()).map(|i| m[(i, j)]).collect())
        .collect()
}
