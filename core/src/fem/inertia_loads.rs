//! The unit inertia loads of a body on a moving frame: the forces $-M a(x)$ that the frame's
//! own motion puts on every particle of the undeformed body (Lin's thesis Eq. 3.14's
//! $\ddot R$, $\dot\omega \times s$ and $\omega \times (\omega \times s)$ terms, and gravity).
//!
//! A frame with origin acceleration $a_0$ (less gravity), angular velocity $\omega$ and
//! angular acceleration $\alpha$ accelerates the particle at $s$ by
//! $$a(s) = a_0 + \alpha \times s + \omega \times (\omega \times s)
//! = a_0 + \alpha \times s + (\omega\omega^T - |\omega|^2 I)\,s,$$
//! linear in twelve coefficients: $a_{0,x}, a_{0,y}, a_{0,z}$, $\alpha_x, \alpha_y,
//! \alpha_z$ and the six products $\omega_i\omega_j$, $i \le j$. Each coefficient's field
//! times $M$ is one unit load; every inertia load of the frame is a combination of the
//! twelve, whatever its motion. Their span does not depend on the point $s$ is measured from
//! (moving it adds translations), so it is measured from the nodes' centroid, scaled by the
//! body's size: loads of comparable magnitude, whatever the units.

use std::fmt;

use faer::Mat;

use super::{Direction, FeModel, NodeDof};

/// One of the twelve unit inertia loads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum InertiaLoadCase {
    /// A linear acceleration of the frame (or gravity) along an axis.
    Linear(Direction),
    /// An angular acceleration about an axis.
    Angular(Direction),
    /// The centrifugal load of the product $\omega_i\omega_j$ ($i \le j$).
    Centrifugal(Direction, Direction),
}

impl InertiaLoadCase {
    /// The twelve cases in a fixed order: linear x, y, z; angular x, y, z; centrifugal
    /// xx, yy, zz, xy, yz, zx.
    pub const ALL: [Self; 12] = {
        use Direction::{X, Y, Z};
        [
            Self::Linear(X),
            Self::Linear(Y),
            Self::Linear(Z),
            Self::Angular(X),
            Self::Angular(Y),
            Self::Angular(Z),
            Self::Centrifugal(X, X),
            Self::Centrifugal(Y, Y),
            Self::Centrifugal(Z, Z),
            Self::Centrifugal(X, Y),
            Self::Centrifugal(Y, Z),
            Self::Centrifugal(Z, X),
        ]
    };

    /// The acceleration (translation) and angular acceleration (rotation) this unit case
    /// gives a particle at `s` (body axes, measured from the reference point).
    pub fn field(self, s: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let unit = |d: Direction| {
            let mut e = [0.0; 3];
            e[d.index()] = 1.0;
            e
        };
        match self {
            Self::Linear(d) => (unit(d), [0.0; 3]),
            Self::Angular(d) => {
                let e = unit(d);
                (cross(e, s), e)
            }
            // The coefficient of ω_iω_j in ω(ω·s) − |ω|²s.
            Self::Centrifugal(i, j) if i == j => {
                let mut a = s.map(|x| -x);
                a[i.index()] += s[i.index()];
                (a, [0.0; 3])
            }
            Self::Centrifugal(i, j) => {
                let mut a = [0.0; 3];
                a[i.index()] += s[j.index()];
                a[j.index()] += s[i.index()];
                (a, [0.0; 3])
            }
        }
    }
}

impl fmt::Display for InertiaLoadCase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Linear(d) => write!(f, "a_{}", d.name()),
            Self::Angular(d) => write!(f, "α_{}", d.name()),
            Self::Centrifugal(i, j) => write!(f, "ω_{}ω_{}", i.name(), j.name()),
        }
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A field of particle accelerations on a body's DOF: per node, the translation from the
/// node's position (about `origin`, divided by `scale`) and the rotation, in the order the
/// body's [`super::DofMap`] gives (a DOF the field does not reach stays zero).
pub fn acceleration_field(
    model: &FeModel,
    origin: [f64; 3],
    scale: f64,
    field: impl Fn([f64; 3]) -> ([f64; 3], [f64; 3]),
) -> Vec<f64> {
    let per = model.dofs.per_node();
    let mut out = vec![0.0; model.dof_count()];
    for (node, p) in model.nodes.iter().enumerate() {
        let s = [0, 1, 2].map(|a| (p[a] - origin[a]) / scale);
        let (t, r) = field(s);
        for (k, dof) in model.dofs.node_dofs().iter().enumerate() {
            out[node * per + k] = match dof {
                NodeDof::Translation(d) => t[d.index()],
                NodeDof::Rotation(d) => r[d.index()] / scale,
            };
        }
    }
    out
}

/// The twelve unit inertia loads of a body, $M a_k(x)$, as the columns of one matrix (one
/// product with $M$).
#[derive(Debug, Clone)]
pub struct InertiaLoads {
    /// The cases, in column order.
    pub cases: Vec<InertiaLoadCase>,
    /// $M a_k$, DOF × cases (the body's force unit per its length unit and mass unit).
    pub matrix: Mat<f64>,
}

impl InertiaLoads {
    /// Every unit inertia load of `model` (fields about the nodes' centroid in units of the
    /// body's size).
    pub fn of(model: &FeModel) -> Self {
        let n = model.dof_count();
        let count = model.node_count().max(1) as f64;
        let centroid = [0, 1, 2].map(|a| model.nodes.iter().map(|p| p[a]).sum::<f64>() / count);
        let scale = model.size().max(f64::MIN_POSITIVE);
        let cases = InertiaLoadCase::ALL.to_vec();
        let mut fields = Mat::<f64>::zeros(n, cases.len());
        for (j, case) in cases.iter().enumerate() {
            let a = acceleration_field(model, centroid, scale, |s| case.field(s));
            for (i, v) in a.into_iter().enumerate() {
                fields[(i, j)] = v;
            }
        }
        Self {
            cases,
            matrix: model.m.mul(fields.as_ref()),
        }
    }

    /// Number of loads.
    pub fn count(&self) -> usize {
        self.cases.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{SlabParameters, slab};

    /// The twelve fields span every rigid acceleration field: a random frame motion's
    /// $a_0 + \alpha\times s + \omega\times(\omega\times s)$ is the combination with the
    /// coefficients $a_0$, $\alpha$, $\omega_i\omega_j$, for several points of reference.
    #[test]
    fn twelve_coefficients_give_every_rigid_acceleration_field() {
        let (a0, al, w) = ([0.3, -1.2, 2.0], [0.7, 0.1, -0.4], [1.5, -0.8, 0.6]);
        for s in [[0.0, 0.0, 0.0], [1.0, -2.0, 0.5], [-3.0, 0.25, 7.0]] {
            let wxs = cross(w, s);
            let expected: Vec<f64> = (0..3)
                .map(|k| a0[k] + cross(al, s)[k] + cross(w, wxs)[k])
                .collect();
            let coefficient = |c: InertiaLoadCase| match c {
                InertiaLoadCase::Linear(d) => a0[d.index()],
                InertiaLoadCase::Angular(d) => al[d.index()],
                InertiaLoadCase::Centrifugal(i, j) => w[i.index()] * w[j.index()],
            };
            let mut sum = [0.0; 3];
            for c in InertiaLoadCase::ALL {
                let (t, _) = c.field(s);
                (0..3).for_each(|k| sum[k] += coefficient(c) * t[k]);
            }
            for k in 0..3 {
                assert!(
                    (sum[k] - expected[k]).abs() <= 1e-12,
                    "{sum:?} {expected:?}"
                );
            }
        }
    }

    /// The translation loads sum to the body's mass in their direction; the names are the
    /// coefficients'.
    #[test]
    fn translation_loads_carry_the_mass() {
        let model = slab(&SlabParameters::default());
        let loads = InertiaLoads::of(&model);
        assert_eq!(loads.count(), 12);
        let mass: f64 = (0..model.dof_count())
            .step_by(3)
            .map(|i| loads.matrix[(i, 0)])
            .sum();
        assert!((mass - 62.4).abs() <= 1e-9 * 62.4, "{mass}");
        let names: Vec<String> = loads.cases.iter().map(|c| c.to_string()).collect();
        assert_eq!(names[0], "a_x");
        assert_eq!(names[5], "α_z");
        assert_eq!(names[11], "ω_zω_x");
    }
}
