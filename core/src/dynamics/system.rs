//! The assembled multibody system: $M\dot v + C^T\lambda = Q$, $C\dot v = \gamma$.

use super::DynamicsError;
use crate::error::AttachmentProblem;
use crate::linalg::LinalgError;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3, Vector4};

use super::{
    Attachment, AxisType, Body, Constraint, FlexibleBody, InertiaInvariants,
    constraint_rows::ConstraintRows,
    evaluation_workspace::{BodyBlocks, EvaluationWorkspace},
    free_frame_stiffening::free_frame_coefficients,
    rotation::{l_matrix, rotate_body, skew},
};
use crate::fem::NodeIndex;
use crate::{
    Error, Result,
    linalg::{REDUNDANT_PSD, pinv_solve, reshape, resize},
};

/// Standard gravity, m/s² (App. B, §7.2).
pub const STANDARD_GRAVITY: f64 = 9.80665;
/// Positions $q$ (per body r, p, z) and velocities $v$ (per body $\dot r$, $\bar\omega$, $\dot z$).
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Position coordinates.
    pub q: DVector<f64>,
    /// Velocity coordinates.
    pub v: DVector<f64>,
}

/// Bodies, constraints and loads.
#[derive(Debug, Clone)]
pub struct System {
    /// The bodies.
    pub bodies: Vec<Body>,
    /// The constraints.
    pub constraints: Vec<Constraint>,
    /// Gravity, m/s² (standard gravity 9.80665 in −z, §7.2).
    pub gravity: Vector3<f64>,
    /// Constant global forces on nodes: (body, node, force in N).
    pub nodal_forces: Vec<(usize, NodeIndex, Vector3<f64>)>,
    pub(super) q_off: Vec<usize>,
    pub(super) v_off: Vec<usize>,
}

impl System {
    /// Bytes the bodies hold on the heap, estimated (see [`Body::heap_bytes`]); constraints
    /// and forces are a few hundred bytes each and left out.
    pub fn heap_bytes(&self) -> usize {
        self.bodies.iter().map(Body::heap_bytes).sum()
    }

    /// A system with gravity 9.80665 m/s² in −z.
    pub fn new(bodies: Vec<Body>, constraints: Vec<Constraint>) -> Self {
        let mut q_off = Vec::new();
        let mut v_off = Vec::new();
        let (mut nq, mut nv) = (0, 0);
        for b in &bodies {
            q_off.push(nq);
            v_off.push(nv);
            nq += b.position_count();
            nv += b.velocity_count();
        }
        q_off.push(nq);
        v_off.push(nv);
        Self {
            bodies,
            constraints,
            gravity: Vector3::new(0.0, 0.0, -STANDARD_GRAVITY),
            nodal_forces: Vec::new(),
            q_off,
            v_off,
        }
    }

    /// Number of position coordinates.
    pub fn nq(&self) -> usize {
        *self.q_off.last().unwrap()
    }

    /// Number of velocity coordinates.
    pub fn nv(&self) -> usize {
        *self.v_off.last().unwrap()
    }

    /// Number of constraint rows: the joints' and six per body on mean or principal axes.
    pub fn constraint_rows(&self) -> usize {
        self.constraints.iter().map(Constraint::rows).sum::<usize>()
            + 6 * self.axis_condition_bodies().count()
    }

    /// The deformable bodies whose frame is held by axis conditions (mean or principal axes).
    pub(super) fn axis_condition_bodies(&self) -> impl Iterator<Item = (usize, &FlexibleBody)> {
        self.bodies
            .iter()
            .enumerate()
            .filter_map(|(b, body)| match body {
                Body::Flexible(fb) if !matches!(fb.axes, AxisType::NodalFixed(_)) => {
                    Some((b, &**fb))
                }
                _ => None,
            })
    }

    /// A state with every body at `r`, `A` given per body, at rest, undeformed.
    pub fn state_at(&self, placements: &[(Vector3<f64>, Matrix3<f64>)]) -> State {
        let mut q = DVector::zeros(self.nq());
        for (b, (r, a)) in placements.iter().enumerate() {
            let o = self.q_off[b];
            q.rows_mut(o, 3).copy_from(r);
            q.rows_mut(o + 3, 4)
                .copy_from(&super::euler_parameters_from_matrix(a));
        }
        State {
            q,
            v: DVector::zeros(self.nv()),
        }
    }

    /// Offsets of body `b` in q and v.
    pub fn offsets(&self, b: usize) -> (usize, usize) {
        (self.q_off[b], self.v_off[b])
    }

    /// Checks indices of constraints and loads.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, place: AttachmentProblem| {
            Err(DynamicsError::BadAttachment { what, place }.into())
        };
        let node_ok = |b: usize, n: NodeIndex| match self.bodies.get(b) {
            Some(Body::Flexible(f)) => n.get() < f.s_bar.len(),
            _ => false,
        };
        for c in &self.constraints {
            match c {
                Constraint::Spherical(a, b) => {
                    for att in [a, b] {
                        match *att {
                            Attachment::Node { body, node } if !node_ok(body, node) => {
                                return bad(
                                    "joint",
                                    AttachmentProblem::NoSuchNode {
                                        body,
                                        node: node.number(),
                                    },
                                );
                            }
                            Attachment::Point { body, .. }
                                if !matches!(self.bodies.get(body), Some(Body::Rigid(_))) =>
                            {
                                return bad("joint", AttachmentProblem::NotRigid { body });
                            }
                            _ => {}
                        }
                    }
                }
                Constraint::PrescribedNode {
                    body, node, axis, ..
                } => {
                    if !node_ok(*body, *node) || *axis > 2 {
                        return bad(
                            "prescribed motion",
                            AttachmentProblem::NoSuchNodeOrAxis {
                                body: *body,
                                node: node.number(),
                                axis: *axis,
                            },
                        );
                    }
                }
            }
        }
        for &(b, n, _) in &self.nodal_forces {
            if !node_ok(b, n) {
                return bad(
                    "force",
                    AttachmentProblem::NoSuchNode {
                        body: b,
                        node: n.number(),
                    },
                );
            }
        }
        Ok(())
    }

    /// Body `b`'s rows of $M(q)$ and $Q(q, v)$ (Kane's form with body-axis angular
    /// velocities): the frame block, the frame–modal coupling and, when `forces`, the forces
    /// (zero otherwise: the mass-weighted projection and the kinetic energy need only $M$).
    /// The modal block is the body's constant $M_{zz}$. `h` is the body's $H_c(z)$ at `s`
    /// ([`Self::modal_moments`]; empty for a rigid body).
    fn body_blocks(&self, b: usize, s: &State, h: &[Matrix3<f64>], forces: bool) -> BodyBlocks {
        let mut out = BodyBlocks::zeros(self.bodies[b].velocity_count() - 6);
        self.body_blocks_into(b, s, h, forces, &mut out);
        out
    }

    /// [`Self::body_blocks`] into `out`, whose storage is reused.
    pub(super) fn body_blocks_into(
        &self,
        b: usize,
        s: &State,
        h: &[Matrix3<f64>],
        forces: bool,
        out: &mut BodyBlocks,
    ) {
        let f = self.frame(b, s);
        let k = self.bodies[b].velocity_count() - 6;
        reshape(&mut out.m_fz, 6, k);
        resize(&mut out.q, 6 + k);
        resize(&mut out.q_z, k);
        resize(&mut out.a_z, k);
        out.q.as_mut_slice().fill(0.0);
        let m_ff = &mut out.m_ff;
        m_ff.fill(0.0);
        match &self.bodies[b] {
            Body::Rigid(rb) => {
                for i in 0..3 {
                    m_ff[(i, i)] = rb.mass;
                }
                m_ff.fixed_view_mut::<3, 3>(3, 3).copy_from(&rb.inertia);
                if forces {
                    out.q
                        .fixed_rows_mut::<3>(0)
                        .copy_from(&(self.gravity * rb.mass));
                    out.q
                        .fixed_rows_mut::<3>(3)
                        .copy_from(&-f.w.cross(&(rb.inertia * f.w)));
                }
            }
            Body::Flexible(fb) => {
                let inv = &fb.invariants;
                let first = inv.first_moment(&f.z);
                let j_bar = InertiaInvariants::inertia_from(&inv.second_moment(&f.z, h));
                let rw = -f.a * skew(&first);
                for i in 0..3 {
                    m_ff[(i, i)] = inv.mass;
                }
                m_ff.fixed_view_mut::<3, 3>(0, 3).copy_from(&rw);
                m_ff.fixed_view_mut::<3, 3>(3, 0).copy_from(&rw.transpose());
                m_ff.fixed_view_mut::<3, 3>(3, 3).copy_from(&j_bar);
                out.m_fz.rows_mut(0, 3).gemm(1.0, &f.a, &inv.p_sum, 0.0);
                InertiaInvariants::rotation_coupling_into(
                    h,
                    &mut out
                        .m_fz
                        .generic_view_mut((3, 0), (nalgebra::U3, nalgebra::Dyn(k))),
                );
                if let Some(st) = &fb.stiffening {
                    st.add_mass_coupling(&f.a, &f.z, &mut out.m_fz, &mut out.coupling);
                }
                if forces {
                    // Gravity acts on every node: sum m_j A^T g, its moment and modal force.
                    let at = f.a.transpose();
                    let g_local = at * self.gravity;
                    let mut q_r = g_local * inv.mass;
                    let mut q_w = first.cross(&g_local);
                    let q_z = &mut out.q_z;
                    q_z.gemv_tr(1.0, &inv.p_sum, &g_local, 0.0);
                    for &(bb, n, force) in &self.nodal_forces {
                        if bb == b {
                            let local = at * force;
                            q_r += local;
                            q_w += fb.b(n.get(), &f.z).cross(&local);
                            fb.add_nodal_force(n.get(), &local, q_z);
                        }
                    }
                    let a_z = &mut out.a_z;
                    let (ar, aw) =
                        inv.velocity_forces(&f.w, (&f.z, &f.zd), h, &j_bar, a_z, &mut out.coriolis);
                    q_w -= aw;
                    *q_z -= &*a_z;
                    fb.subtract_elastic_force(&f.z, q_z);
                    // Dynamic stiffening by the angular velocity and gravity; the frame
                    // accelerations' part sits in the mass matrix (`add_mass_coupling`).
                    if let Some(st) = &fb.stiffening {
                        let c = free_frame_coefficients(&f.w, &Vector3::zeros(), &g_local);
                        st.subtract_force(&c, &f.z, q_z);
                    }
                    out.q.fixed_rows_mut::<3>(0).copy_from(&(f.a * (q_r - ar)));
                    out.q.fixed_rows_mut::<3>(3).copy_from(&q_w);
                    out.q.rows_mut(6, k).copy_from(q_z);
                }
            }
        }
    }

    /// Every deformable body's $H_c(z) = \sum_j m_j \psi_{jc} b_j^T$ at `s`
    /// ([`InertiaInvariants::h`]), which its mass matrix, forces and axis conditions share;
    /// empty for a rigid body. Computed once per evaluation.
    pub(super) fn modal_moments(&self, s: &State) -> Vec<Vec<Matrix3<f64>>> {
        let mut out = Vec::new();
        self.modal_moments_into(s, &mut out);
        out
    }

    /// [`Self::modal_moments`] into `out`, whose storage is reused.
    pub(super) fn modal_moments_into(&self, s: &State, out: &mut Vec<Vec<Matrix3<f64>>>) {
        out.resize_with(self.bodies.len(), Vec::new);
        for (b, (body, h)) in self.bodies.iter().zip(out.iter_mut()).enumerate() {
            match body {
                Body::Flexible(fb) => {
                    // Only z: the frame's rotation is not needed here.
                    let (qo, k) = (self.q_off[b], fb.modes());
                    fb.invariants.h_into(&s.q.rows(qo + 7, k), h)
                }
                Body::Rigid(_) => h.clear(),
            }
        }
    }

    /// $M(q)$ and $Q(q, v)$, assembled dense: the reference the block elimination of
    /// [`Self::accelerations`] is tested against.
    pub(crate) fn mass_and_forces(&self, s: &State) -> (DMatrix<f64>, DVector<f64>) {
        let nv = self.nv();
        let mut m = DMatrix::zeros(nv, nv);
        let mut q = DVector::zeros(nv);
        let moments = self.modal_moments(s);
        for (b, body) in self.bodies.iter().enumerate() {
            let o = self.v_off[b];
            let blocks = self.body_blocks(b, s, &moments[b], true);
            let k = blocks.m_fz.ncols();
            m.view_mut((o, o), (6, 6)).copy_from(&blocks.m_ff);
            m.view_mut((o, o + 6), (6, k)).copy_from(&blocks.m_fz);
            m.view_mut((o + 6, o), (k, 6))
                .copy_from(&blocks.m_fz.transpose());
            if let Body::Flexible(fb) = body {
                m.view_mut((o + 6, o + 6), (k, k)).copy_from(&fb.m_zz);
            }
            q.rows_mut(o, 6 + k).copy_from(&blocks.q);
        }
        (m, q)
    }

    /// Accelerations $\dot v$ from $M\dot v + C^T\lambda = Q$, $C\dot v = \gamma$.
    ///
    /// Each deformable body's modal block $M_{zz}$ is constant and factored once, so its
    /// modal accelerations are eliminated,
    /// $\ddot z = M_{zz}^{-1}(Q_z - M_{zf}\dot v_f - C_z^T\lambda)$, leaving a symmetric
    /// system in the six frame accelerations per body and the multipliers:
    /// $\begin{bmatrix} M_{ff} - M_{fz}M_{zz}^{-1}M_{zf} & C_f^T - M_{fz}M_{zz}^{-1}C_z^T \\
    /// \cdot & -C_zM_{zz}^{-1}C_z^T \end{bmatrix}
    /// \begin{bmatrix}\dot v_f \\ \lambda\end{bmatrix} =
    /// \begin{bmatrix} Q_f - M_{fz}M_{zz}^{-1}Q_z \\ \gamma - C_zM_{zz}^{-1}Q_z\end{bmatrix}$.
    /// Its size is 6 per body plus the constraint rows, whatever the bodies' modal
    /// coordinates (a full slab of 90 or a plank of 288). Its frame block is singular when Ψ
    /// holds the rigid motions (Eq. 3.38, no reduction on mean axes): the axis conditions
    /// fix that through the multipliers. Every clearly definite frame block (a rigid link, a
    /// body whose Ψ leaves out the rigid motions) is eliminated body by body; what is left is
    /// solved by a scaled symmetric indefinite factorisation, or a pseudo-inverse when
    /// constraints are redundant ([`block_saddle_point_solve`]). Only the constraint rows
    /// that touch a body's modal coordinates enter its elimination.
    pub fn accelerations(&self, t: f64, s: &State) -> Result<DVector<f64>> {
        let mut ws = EvaluationWorkspace::new(self);
        self.accelerations_in(t, s, &mut ws)?;
        Ok(ws.saddle.x)
    }

    /// [`Self::accelerations`] with the buffers of `ws` (sized for this system), into
    /// `ws.saddle.x`: an integration allocates nothing per evaluation.
    pub(super) fn accelerations_in(
        &self,
        t: f64,
        s: &State,
        ws: &mut EvaluationWorkspace,
    ) -> Result<()> {
        ws.evaluations += 1;
        self.rows_into(t, s, &mut ws.rows);
        let rows = &ws.rows;
        let all = ConstraintRows {
            c: &rows.c,
            g: &rows.gamma,
            modal_rows: &ws.modal_rows,
        };
        self.saddle_point(s, &rows.moments, all, true, &mut ws.saddle)
    }

    /// The accelerations of [`Self::accelerations`] from the dense regularised system
    /// $(M + \rho C^TC)\dot v + C^T\mu = Q + \rho C^T\gamma$ (exact because
    /// $C\dot v = \gamma$) with a pseudo-inverse of $C\tilde M^{-1}C^T$: $O(n_v^3)$ per
    /// call, kept as the independent reference the block elimination is tested against.
    pub fn accelerations_dense(&self, t: f64, s: &State) -> Result<DVector<f64>> {
        let (m, q) = self.mass_and_forces(s);
        let rows = self.rows(t, s);
        let scale = m.diagonal().amax().max(1e-12);
        let cn = rows.c.amax().max(1e-12);
        let rho = scale / (cn * cn);
        let mt = &m + rows.c.transpose() * &rows.c * rho;
        let rhs = &q + rows.c.transpose() * &rows.gamma * rho;
        let chol = mt.cholesky().ok_or_else(|| {
            Error::Linalg(LinalgError::SingularMatrix {
                matrix: "regularised system mass".into(),
                rcond: None,
            })
        })?;
        let v0 = chol.solve(&rhs);
        if rows.c.nrows() == 0 {
            return Ok(v0);
        }
        let minv_ct = chol.solve(&rows.c.transpose());
        let schur = &rows.c * &minv_ct;
        let resid = &rows.c * &v0 - &rows.gamma;
        let mu = pinv_solve(&schur, &resid, REDUNDANT_PSD);
        Ok(v0 - minv_ct * mu)
    }

    /// $\dot q$ from $v$ into `qd` (the first $n_q$ rows of the state derivative): $\dot r$,
    /// $\dot p = \tfrac12 L^T\bar\omega$, $\dot z$.
    pub(crate) fn qdot_into(&self, s: &State, qd: &mut nalgebra::DVectorViewMut<'_, f64>) {
        for b in 0..self.bodies.len() {
            let qo = self.q_off[b];
            let f = self.frame(b, s);
            qd.rows_mut(qo, 3).copy_from(&f.rd);
            let pd = l_matrix(&f.p).transpose() * f.w * 0.5;
            qd.rows_mut(qo + 3, 4).copy_from(&pd);
            let k = f.z.len();
            qd.rows_mut(qo + 7, k).copy_from(&f.zd);
        }
    }

    /// Kinetic energy $\tfrac12 v^T M v$, J, body by body from the blocks of $M$ (no
    /// $n_v \times n_v$ matrix).
    pub fn kinetic_energy(&self, s: &State) -> f64 {
        let mut e = 0.0;
        let moments = self.modal_moments(s);
        for (b, body) in self.bodies.iter().enumerate() {
            let blocks = self.body_blocks(b, s, &moments[b], false);
            let o = self.v_off[b];
            let k = blocks.m_fz.ncols();
            let v_f = s.v.fixed_rows::<6>(o);
            e += 0.5 * v_f.dot(&(blocks.m_ff * v_f));
            if let Body::Flexible(fb) = body {
                let zd = s.v.rows(o + 6, k);
                e += v_f.dot(&(&blocks.m_fz * zd)) + 0.5 * zd.dot(&(&fb.m_zz * zd));
            }
        }
        e
    }

    /// Total energy (J): kinetic + strain − work potential of gravity and the constant forces.
    pub fn energy(&self, s: &State) -> f64 {
        let mut e = self.kinetic_energy(s);
        for (b, body) in self.bodies.iter().enumerate() {
            let f = self.frame(b, s);
            match body {
                Body::Rigid(rb) => e -= rb.mass * self.gravity.dot(&f.r),
                Body::Flexible(fb) => {
                    e += 0.5 * f.z.dot(&fb.elastic_force(&f.z));
                    let inv = &fb.invariants;
                    e -= self
                        .gravity
                        .dot(&(f.r * inv.mass + f.a * inv.first_moment(&f.z)));
                }
            }
        }
        for &(b, n, force) in &self.nodal_forces {
            e -= force.dot(&self.node_position(b, n, s));
        }
        e
    }

    /// Moves positions by an increment `dx` in velocity coordinates: translations and modal
    /// coordinates added, each body's orientation turned by the body-axis rotation vector.
    pub(crate) fn apply_increment(&self, s: &mut State, dx: &DVector<f64>) {
        for b in 0..self.bodies.len() {
            let (qo, vo) = (self.q_off[b], self.v_off[b]);
            for i in 0..3 {
                s.q[qo + i] += dx[vo + i];
            }
            let p = Vector4::new(s.q[qo + 3], s.q[qo + 4], s.q[qo + 5], s.q[qo + 6]);
            let th = Vector3::new(dx[vo + 3], dx[vo + 4], dx[vo + 5]);
            s.q.rows_mut(qo + 3, 4).copy_from(&rotate_body(&p, &th));
            let k = self.bodies[b].position_count() - 7;
            for i in 0..k {
                s.q[qo + 7 + i] += dx[vo + 6 + i];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        dynamics::{
            RigidBody,
            test_systems::{reduced_plank, set_in_motion},
        },
        reduction::Method,
    };

    #[test]
    fn kinetic_energy_by_blocks_equals_the_dense_quadratic_form() {
        for method in [Method::NoReduction, Method::CraigBampton] {
            // The reduced plank with a rigid rod beside it, moving and deformed.
            let (_, body) = reduced_plank(method, AxisType::Mean);
            let origin = body.origin;
            let system = System::new(
                vec![
                    Body::Flexible(Box::new(body)),
                    Body::Rigid(RigidBody::rod("rod", 1.0, 2.0)),
                ],
                vec![],
            );
            let mut state = system.state_at(&[
                (origin, Matrix3::identity()),
                (Vector3::new(0.0, 0.0, 3.0), Matrix3::identity()),
            ]);
            set_in_motion(&system, &mut state);
            let (m, _) = system.mass_and_forces(&state);
            let dense = 0.5 * state.v.dot(&(&m * &state.v));
            let blocks = system.kinetic_energy(&state);
            assert!(dense > 0.0);
            assert!(
                (blocks - dense).abs() <= 1e-12 * dense,
                "{method:?}: {blocks} against {dense}"
            );
        }
    }
}
