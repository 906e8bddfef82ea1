//! Where the system's points are and how they move: a body's frame and deformation, nodal
//! positions and accelerations, and a point's kinematics as constraint rows need them.

use std::ops::Range;

use nalgebra::{DMatrix, DVector, DVectorView, Matrix3, Vector3, Vector4};

use super::{
    Attachment, Body, State, System,
    rotation::{rotation_matrix, skew},
};
use crate::fem::NodeIndex;

/// One body's frame and deformation at an instant; the modal coordinates are views into the
/// state, so reading a frame allocates nothing.
pub(super) struct Frame<'a> {
    pub(super) r: Vector3<f64>,
    pub(super) p: Vector4<f64>,
    pub(super) a: Matrix3<f64>,
    pub(super) z: DVectorView<'a, f64>,
    pub(super) rd: Vector3<f64>,
    pub(super) w: Vector3<f64>,
    pub(super) zd: DVectorView<'a, f64>,
}

/// Kinematics of one point: its position and the velocity-dependent part of its
/// acceleration; the partial velocities (3 × nv) are written by [`System::point`] into the
/// rows the caller gives.
pub(super) struct PointKin {
    pub(super) d: Vector3<f64>,
    pub(super) aq: Vector3<f64>,
    /// The rotation of the point's body (the identity for the ground).
    pub(super) a: Matrix3<f64>,
    /// $-A\tilde b$: the point's partial velocity in its body's angular velocity.
    pub(super) arm: Matrix3<f64>,
}

impl System {
    pub(super) fn frame<'a>(&self, b: usize, s: &'a State) -> Frame<'a> {
        let (qo, vo) = (self.q_off[b], self.v_off[b]);
        let k = self.bodies[b].position_count() - 7;
        let p = Vector4::new(s.q[qo + 3], s.q[qo + 4], s.q[qo + 5], s.q[qo + 6]);
        Frame {
            r: Vector3::new(s.q[qo], s.q[qo + 1], s.q[qo + 2]),
            a: rotation_matrix(&p),
            p,
            z: s.q.rows(qo + 7, k),
            rd: Vector3::new(s.v[vo], s.v[vo + 1], s.v[vo + 2]),
            w: Vector3::new(s.v[vo + 3], s.v[vo + 4], s.v[vo + 5]),
            zd: s.v.rows(vo + 6, k),
        }
    }

    /// Absolute acceleration of a node, $\ddot d_j = L_j\dot v + a_q$ (Eq. 3.17), from the
    /// accelerations `vdot` of [`System::accelerations`].
    pub fn node_acceleration(
        &self,
        b: usize,
        node: NodeIndex,
        s: &State,
        vdot: &DVector<f64>,
    ) -> Vector3<f64> {
        let mut l = DMatrix::zeros(3, self.nv());
        let at = Attachment::Node { body: b, node };
        let p = self.point_kinematics(&at, s);
        self.add_point_rows(&at, &p, 1.0, &mut l, (0, None), &mut Vec::new());
        l * vdot + p.aq
    }

    /// Global position of a node of a deformable body.
    pub fn node_position(&self, b: usize, node: NodeIndex, s: &State) -> Vector3<f64> {
        let f = self.frame(b, s);
        match &self.bodies[b] {
            Body::Flexible(fb) => f.r + f.a * fb.b(node.get(), &f.z),
            Body::Rigid(_) => f.r,
        }
    }

    /// Position of `node` of body `b` with its elastic deflection (relative to the body frame)
    /// multiplied by `scale`: 1 is [`Self::node_position`], 0 the rigidly moved undeformed
    /// node (for drawing deflections too small to see, and the ghost beside them).
    pub fn node_position_scaled(
        &self,
        b: usize,
        node: NodeIndex,
        s: &State,
        scale: f64,
    ) -> Vector3<f64> {
        let f = self.frame(b, s);
        match &self.bodies[b] {
            Body::Flexible(fb) => {
                f.r + f.a * (fb.s_bar[node.get()] + fb.deflection(node.get(), &f.z) * scale)
            }
            Body::Rigid(_) => f.r,
        }
    }

    /// Positions of every node of deformable body `b`, their elastic deflections multiplied
    /// by `scale` as in [`Self::node_position_scaled`]: the frame is read once for all nodes.
    /// Empty for a rigid body.
    pub fn node_positions_scaled(&self, b: usize, s: &State, scale: f64) -> Vec<Vector3<f64>> {
        let f = self.frame(b, s);
        match &self.bodies[b] {
            Body::Flexible(fb) => (0..fb.s_bar.len())
                .map(|j| f.r + f.a * (fb.s_bar[j] + fb.deflection(j, &f.z) * scale))
                .collect(),
            Body::Rigid(_) => Vec::new(),
        }
    }

    /// The largest elastic deflection $\max_j |\Psi_j z|$ of deformable body `b`'s nodes, m
    /// (0 for a rigid body).
    pub fn largest_deflection(&self, b: usize, s: &State) -> f64 {
        let f = self.frame(b, s);
        match &self.bodies[b] {
            Body::Flexible(fb) => (0..fb.s_bar.len())
                .map(|j| fb.deflection(j, &f.z).norm())
                .fold(0.0, f64::max),
            Body::Rigid(_) => 0.0,
        }
    }

    /// Frame position and orientation of body `b`.
    pub fn placement(&self, b: usize, s: &State) -> (Vector3<f64>, Matrix3<f64>) {
        let f = self.frame(b, s);
        (f.r, f.a)
    }

    /// Modal coordinates of body `b`.
    pub fn modal(&self, b: usize, s: &State) -> DVector<f64> {
        self.frame(b, s).z.into_owned()
    }

    /// A point's position, the velocity-dependent part of its acceleration, and what its
    /// partial velocities are made of ([`Self::add_point_rows`] writes them as rows of $L$,
    /// Eq. 3.17).
    pub(super) fn point_kinematics(&self, att: &Attachment, s: &State) -> PointKin {
        match *att {
            Attachment::Ground(x) => PointKin {
                d: x,
                aq: Vector3::zeros(),
                a: Matrix3::identity(),
                arm: Matrix3::zeros(),
            },
            Attachment::Point { body, local } => {
                let f = self.frame(body, s);
                PointKin {
                    d: f.r + f.a * local,
                    aq: f.a * (f.w.cross(&f.w.cross(&local))),
                    arm: -f.a * skew(&local),
                    a: f.a,
                }
            }
            Attachment::Node { body, node } => {
                let f = self.frame(body, s);
                let Body::Flexible(fb) = &self.bodies[body] else {
                    unreachable!("node attachments are checked to name deformable bodies")
                };
                let bj = fb.b(node.get(), &f.z);
                let u = fb.deflection(node.get(), &f.zd);
                PointKin {
                    d: f.r + f.a * bj,
                    aq: f.a * (f.w.cross(&f.w.cross(&bj)) + 2.0 * f.w.cross(&u)),
                    arm: -f.a * skew(&bj),
                    a: f.a,
                }
            }
        }
    }

    /// Adds `sign` times the point's partial velocities $L$ (Eq. 3.17) to `c`: all three
    /// rows from row `r` on, or only the row of `axis` at row `r` (`(r, axis)`); `kin` is the point's
    /// [`Self::point_kinematics`] at the state. Only the point's own body's columns are
    /// touched; each row's are appended to `written` as (row, columns), so that the next
    /// evaluation clears those alone.
    pub(super) fn add_point_rows(
        &self,
        att: &Attachment,
        kin: &PointKin,
        sign: f64,
        c: &mut DMatrix<f64>,
        (r, axis): (usize, Option<usize>),
        written: &mut Vec<(usize, Range<usize>)>,
    ) {
        let axes = axis.map_or(0..3, |a| a..a + 1);
        let first = axes.start;
        let row = |i: usize| r + i - first;
        let (body, node) = match *att {
            Attachment::Ground(_) => return,
            Attachment::Point { body, .. } => (body, None),
            Attachment::Node { body, node } => (body, Some(node)),
        };
        let vo = self.v_off[body];
        for i in axes.clone() {
            written.push((row(i), vo..vo + 6));
            c[(row(i), vo + i)] += sign;
            for k in 0..3 {
                c[(row(i), vo + 3 + k)] += sign * kin.arm[(i, k)];
            }
        }
        let (Some(node), Body::Flexible(fb)) = (node, &self.bodies[body]) else {
            return;
        };
        let psi = &fb.psi_nodes[node.get()];
        for i in axes {
            // Row i of A Ψ_j: over Ψ_j's nonzero columns when they are few (no reduction),
            // else by one product into the row (no temporary).
            match fb.psi_columns(node.get()) {
                Some(columns) => {
                    let a_i = kin.a.row(i);
                    for &col in columns {
                        let at = vo + 6 + col;
                        c[(row(i), at)] += sign * a_i.dot(&psi.column(col).transpose());
                        written.push((row(i), at..at + 1));
                    }
                }
                None => {
                    c.view_mut((row(i), vo + 6), (1, fb.modes())).gemm(
                        sign,
                        &kin.a.row(i),
                        psi,
                        1.0,
                    );
                    written.push((row(i), vo + 6..vo + 6 + fb.modes()));
                }
            }
        }
    }
}
