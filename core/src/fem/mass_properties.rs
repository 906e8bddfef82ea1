//! Mass, mass centre and inertia tensor of a body from its complete mass matrix.

use faer::Mat;

use super::FeModel;

/// The rigid-body mass properties of a body, from the complete (lumped or consistent) $M$
/// acting on rigid fields: with $t_d$ the unit translation along $d$, $p_d$ the coordinate
/// field $x_d$ on the $d$ translations and $r_k(c)$ the small rotation about axis $k$ through
/// $c$,
///
/// $$m = t_x^TMt_x,\qquad c_d = t_d^TMp_d/m,\qquad J_{kl} = r_k(c)^TMr_l(c).$$
///
/// Exact for a consistent mass whose shape functions contain the linear fields (every
/// isoparametric element), and for a lumped one. Rotation DOF take part through the rigid
/// rotation fields, so a beam's or shell's rotary inertia is in $J$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Total mass, in the body's mass unit (kg, t, ...).
    pub mass: f64,
    /// Mass centre, in the body's length unit.
    pub centre: [f64; 3],
    /// Inertia tensor about the mass centre in the body's axes, mass × length²; for a planar
    /// body only $J_{zz}$ is meaningful.
    pub inertia: [[f64; 3]; 3],
}

impl MassProperties {
    /// The mass properties of `model` (see the type's documentation).
    pub fn of(model: &FeModel) -> Self {
        let n = model.dof_count();
        let per = model.dofs.per_node();
        let translations = model.dofs.translations();
        let field =
            |f: &dyn Fn(usize, usize) -> f64| Mat::from_fn(n, 1, |i, _| f(i / per, i % per));
        let dot_m = |a: &Mat<f64>, b: &Mat<f64>| (a.transpose() * model.m.mul(b.as_ref()))[(0, 0)];
        let mut mass = 0.0;
        let mut first = [0.0; 3];
        let mut counted = 0.0;
        for &(dir, offset) in &translations {
            let d = dir.index();
            let t = field(&|_, o| if o == offset { 1.0 } else { 0.0 });
            let p = field(&|node, o| {
                if o == offset {
                    model.nodes[node][d]
                } else {
                    0.0
                }
            });
            mass += dot_m(&t, &t);
            counted += 1.0;
            first[d] = dot_m(&t, &p);
        }
        let mass = if counted > 0.0 { mass / counted } else { 0.0 };
        let centre = if mass > 0.0 {
            first.map(|s| s / mass)
        } else {
            [0.0; 3]
        };
        // Rigid rotations about the centre, one per axis.
        let rotation = |k: usize| {
            let mut omega = [0.0; 3];
            omega[k] = 1.0;
            let dofs = model.dofs.node_dofs();
            field(&|node, o| {
                let x = model.nodes[node];
                let r = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
                dofs[o].rigid_motion(r, [0.0; 3], omega)
            })
        };
        let axes: Vec<usize> = if model.spatial_dim() == 2 {
            vec![2]
        } else {
            vec![0, 1, 2]
        };
        let fields: Vec<(usize, Mat<f64>)> = axes.iter().map(|&k| (k, rotation(k))).collect();
        let mut inertia = [[0.0; 3]; 3];
        for (k, rk) in &fields {
            for (l, rl) in &fields {
                inertia[*k][*l] = dot_m(rk, rl);
            }
        }
        Self {
            mass,
            centre,
            inertia,
        }
    }
}
