//! The system's constraint rows $C\dot v = \gamma$ (joints, prescribed nodes, axis
//! conditions), their violation, and the projection of a state onto them.

use nalgebra::{DMatrix, DVector, Matrix3};

use super::{
    Attachment, AxisType, Constraint, FlexibleBody, InertiaInvariants, State, System,
    constraint_rows::{ConstraintRows, Rows},
    evaluation_workspace::EvaluationWorkspace,
    projection_factors::ProjectionFactors,
};
use crate::{
    Result,
    linalg::{reshape, resize},
};

impl System {
    /// Constraint rows at time `t`.
    pub(crate) fn rows(&self, t: f64, s: &State) -> Rows {
        let mut out = Rows::empty();
        self.rows_into(t, s, &mut out);
        out
    }

    /// Per body, the constraint rows that may touch its modal coordinates (a joint at one of
    /// its nodes, its axis conditions), ascending, in the order of [`Self::rows`]: the
    /// system's structure, the same at every instant. The block elimination looks for
    /// nonzero modal entries only there.
    pub(super) fn modal_rows(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.bodies.len()];
        let mut r = 0;
        for c in &self.constraints {
            for attachment in c.attachments() {
                if let Attachment::Node { body, .. } = attachment {
                    let list: &mut Vec<usize> = &mut out[body];
                    // Both ends on one body's nodes: its rows once.
                    let from = list.last().map_or(r, |&last| (last + 1).max(r));
                    list.extend(from..r + c.rows());
                }
            }
            r += c.rows();
        }
        for (body, _) in self.axis_condition_bodies() {
            out[body].extend(r..r + 6);
            r += 6;
        }
        out
    }

    /// [`Self::rows`] into `out`, whose storage is reused.
    pub(crate) fn rows_into(&self, t: f64, s: &State, out: &mut Rows) {
        let nv = self.nv();
        let nr = self.constraint_rows();
        self.clear_jacobian(nr, nv, out);
        for v in [&mut out.gamma, &mut out.target, &mut out.phi] {
            resize(v, nr);
            v.as_mut_slice().fill(0.0);
        }
        out.holonomic.clear();
        out.holonomic.resize(nr, true);
        self.modal_moments_into(s, &mut out.moments);
        let mut r = 0;
        let mut last_node = None;
        for c in &self.constraints {
            match c {
                Constraint::Spherical(a, b) => {
                    let (pa, pb) = (self.point_kinematics(a, s), self.point_kinematics(b, s));
                    let added = &mut out.written.added;
                    self.add_point_rows(a, &pa, 1.0, &mut out.c, (r, None), added);
                    self.add_point_rows(b, &pb, -1.0, &mut out.c, (r, None), added);
                    out.gamma.rows_mut(r, 3).copy_from(&(pb.aq - pa.aq));
                    out.phi.rows_mut(r, 3).copy_from(&(pa.d - pb.d));
                }
                Constraint::PrescribedNode {
                    body,
                    node,
                    axis,
                    motion,
                    x0,
                    v0,
                } => {
                    let at = Attachment::Node {
                        body: *body,
                        node: *node,
                    };
                    // A node prescribed along several axes (consecutive constraints): its
                    // kinematics once.
                    let kin = match &last_node {
                        Some((b, n, kin)) if (b, n) == (body, node) => kin,
                        _ => {
                            &last_node
                                .insert((*body, *node, self.point_kinematics(&at, s)))
                                .2
                        }
                    };
                    let added = &mut out.written.added;
                    self.add_point_rows(&at, kin, 1.0, &mut out.c, (r, Some(*axis)), added);
                    let (x, v, acc) = motion.at(t, *x0, *v0);
                    out.gamma[r] = acc - kin.aq[*axis];
                    out.target[r] = v;
                    out.phi[r] = kin.d[*axis] - x;
                }
            }
            r += c.rows();
        }
        let moments = std::mem::take(&mut out.moments);
        for (body, fb) in self.axis_condition_bodies() {
            self.axis_rows(body, fb, s, &moments[body], r, out);
            r += 6;
        }
        out.moments = moments;
    }

    /// Makes `out.c` an `nr` × `nv` Jacobian that is zero wherever this evaluation does not
    /// write it, and clears `out.written` for it: of a Jacobian of that shape, only the
    /// entries the last evaluation added to, and the axis blocks it overwrote that this one
    /// does not (the same system's are the same blocks); of another shape, all.
    fn clear_jacobian(&self, nr: usize, nv: usize, out: &mut Rows) {
        let first = nr - 6 * self.axis_condition_bodies().count();
        let blocks = || {
            self.axis_condition_bodies()
                .enumerate()
                .map(move |(i, (body, fb))| {
                    let o = self.v_off[body] + 6;
                    (first + 6 * i, o..o + fb.modes())
                })
        };
        let (c, written) = (&mut out.c, &mut out.written);
        if c.shape() == (nr, nv) {
            for (row, columns) in written.added.drain(..) {
                for column in columns {
                    c[(row, column)] = 0.0;
                }
            }
            if !blocks().eq(written.assigned.iter().cloned()) {
                for (row, columns) in written.assigned.drain(..) {
                    c.view_mut((row, columns.start), (6, columns.len()))
                        .fill(0.0);
                }
                written.assigned.extend(blocks());
            }
        } else {
            *c = DMatrix::zeros(nr, nv);
            written.added.clear();
            written.assigned.clear();
            written.assigned.extend(blocks());
        }
    }

    /// The six rows of mean axes (Table 4-2) or principal axes (§4.3) of body `body` from row
    /// `r` on; `h` is the body's $H_c(z)$ at `s`.
    fn axis_rows(
        &self,
        body: usize,
        fb: &FlexibleBody,
        s: &State,
        h: &[Matrix3<f64>],
        r: usize,
        out: &mut Rows,
    ) {
        let f = self.frame(body, s);
        let o = self.v_off[body] + 6;
        let k = fb.modes();
        let inv = &fb.invariants;
        // Translational: sum m_j Psi_j z = 0 (Eq. 4.20), holonomic.
        out.c.view_mut((r, o), (3, k)).copy_from(&inv.p_sum);
        out.phi.rows_mut(r, 3).copy_from(&(&inv.p_sum * f.z));
        if matches!(fb.axes, AxisType::Mean) {
            // Rotational: sum m_j b_j x (Psi_j zdot) = 0 (Eq. 4.15); its acceleration form has
            // no quadratic term for a lumped M (Eq. 4.17).
            InertiaInvariants::rotation_coupling_into(
                h,
                &mut out
                    .c
                    .generic_view_mut((r + 3, o), (nalgebra::U3, nalgebra::Dyn(k))),
            );
            for i in 3..6 {
                out.holonomic[r + i] = false;
            }
        } else {
            // Products of inertia J_xy, J_yz, J_zx = -sum m b_a b_b, held at their undeformed
            // values -S_ab: gradient -(H_c[a,b] + H_c[b,a]), quadratic term
            // -2 sum m (Psi zd)_a (Psi zd)_b.
            let pairs = [(0, 1), (1, 2), (2, 0)];
            let b_z = inv.second_moment(&f.z, h);
            let udot = inv.modal_outer(&f.zd, &f.zd);
            for (i, &(a, b)) in pairs.iter().enumerate() {
                for (c, hc) in h.iter().enumerate() {
                    out.c[(r + 3 + i, o + c)] = -(hc[(a, b)] + hc[(b, a)]);
                }
                out.gamma[r + 3 + i] = 2.0 * udot[(a, b)];
                out.phi[r + 3 + i] = inv.s_outer[(a, b)] - b_z[(a, b)];
            }
        }
    }

    /// Largest position-level and velocity-level constraint violations.
    pub fn violation(&self, t: f64, s: &State) -> (f64, f64) {
        let rows = self.rows(t, s);
        let pos = rows.phi.amax();
        let vel = (&rows.c * &s.v - &rows.target).amax();
        (pos, vel)
    }

    /// Normalises Euler parameters and projects positions, then velocities, onto the
    /// constraint manifold, both in the mass metric. Positions take Gauss–Newton corrections
    /// of least kinetic-energy norm, $\min \tfrac12\Delta q^T M\Delta q$ subject to
    /// $C\Delta q = -\Phi$ (drift). Velocities take the correction of least kinetic energy,
    /// $\min \tfrac12\Delta v^T M\Delta v$ subject to $C(v - \Delta v) = $ target: the
    /// velocity jump constraint impulses cause. Both are the same for every basis of one
    /// space; a Euclidean minimum norm in modal coordinates is not, and made generalized-α's
    /// fixed-step histories of Craig–Bampton and mode condensation differ by 1e-3 where
    /// their models are one (slab-sim3), and Simulation 2's orbit start with velocities the
    /// constraints do not allow.
    ///
    /// The buffers of `ws` are reused: an integration projects after every step. With
    /// [`ProjectionFactors::LastEvaluation`] the velocity correction, and the first position
    /// correction when every row is holonomic (its system is then the evaluation's), solve
    /// with the factors of the last evaluation in `ws` instead of forming and factoring the
    /// system again.
    pub(crate) fn project(
        &self,
        t: f64,
        s: &mut State,
        ws: &mut EvaluationWorkspace,
        factors: ProjectionFactors,
    ) -> Result<()> {
        for b in 0..self.bodies.len() {
            let qo = self.q_off[b];
            let n = s.q.rows(qo + 3, 4).norm();
            s.q.rows_mut(qo + 3, 4).scale_mut(1.0 / n);
        }
        // The rows at the current positions, for the next correction and the velocities.
        self.rows_into(t, s, &mut ws.rows);
        for iteration in 0..3 {
            let rows = &ws.rows;
            let held = rows.holonomic.iter().filter(|&&h| h).count();
            if held == 0 || rows.phi.amax() < 1e-13 {
                break;
            }
            // Every row holonomic: the first correction's system is the last evaluation's.
            let increment = if iteration == 0
                && held == rows.holonomic.len()
                && factors != ProjectionFactors::Fresh
            {
                self.resolve_saddle_point(&rows.phi, &mut ws.saddle)?;
                &mut ws.saddle.x
            } else {
                self.held_correction(s, held, ws)?
            };
            increment.neg_mut();
            self.apply_increment(s, increment);
            self.rows_into(t, s, &mut ws.rows);
        }
        let rows = &ws.rows;
        if rows.c.nrows() > 0 {
            resize(&mut ws.residual, rows.c.nrows());
            rows.c.mul_to(&s.v, &mut ws.residual);
            ws.residual -= &rows.target;
            match factors {
                ProjectionFactors::Fresh => {
                    let all = ConstraintRows {
                        c: &rows.c,
                        g: &ws.residual,
                        modal_rows: &ws.modal_rows,
                    };
                    self.saddle_point(s, &rows.moments, all, false, &mut ws.saddle)?;
                }
                ProjectionFactors::LastEvaluation | ProjectionFactors::LastEvaluationChecked => {
                    self.resolve_saddle_point(&ws.residual, &mut ws.saddle)?;
                }
            }
            s.v -= &ws.saddle.x;
            if factors == ProjectionFactors::LastEvaluationChecked {
                rows.c.mul_to(&s.v, &mut ws.residual);
                ws.residual -= &rows.target;
                let scale = s.v.amax().max(rows.target.amax()).max(1.0);
                if ws.residual.amax() > 1e-12 * scale {
                    let all = ConstraintRows {
                        c: &rows.c,
                        g: &ws.residual,
                        modal_rows: &ws.modal_rows,
                    };
                    self.saddle_point(s, &rows.moments, all, false, &mut ws.saddle)?;
                    s.v -= &ws.saddle.x;
                }
            }
        }
        Ok(())
    }

    /// The position correction of [`Self::project`] by the `held` holonomic rows of
    /// `ws.rows` alone, formed and factored at `s`, into `ws.held_saddle.x`.
    fn held_correction<'w>(
        &self,
        s: &State,
        held: usize,
        ws: &'w mut EvaluationWorkspace,
    ) -> Result<&'w mut DVector<f64>> {
        let rows = &ws.rows;
        let nv = rows.c.ncols();
        reshape(&mut ws.holonomic_c, held, nv);
        resize(&mut ws.holonomic_phi, held);
        // Row i of the full set is row position[i] of the holonomic one.
        ws.position.clear();
        let mut to = 0;
        for (from, &holonomic) in rows.holonomic.iter().enumerate() {
            ws.position.push(to);
            if holonomic {
                ws.holonomic_c.row_mut(to).copy_from(&rows.c.row(from));
                ws.holonomic_phi[to] = rows.phi[from];
                to += 1;
            }
        }
        ws.holonomic_modal_rows
            .resize_with(ws.modal_rows.len(), Vec::new);
        for (held, all) in ws.holonomic_modal_rows.iter_mut().zip(&ws.modal_rows) {
            held.clear();
            held.extend(
                all.iter()
                    .filter(|&&r| rows.holonomic[r])
                    .map(|&r| ws.position[r]),
            );
        }
        let held = ConstraintRows {
            c: &ws.holonomic_c,
            g: &ws.holonomic_phi,
            modal_rows: &ws.holonomic_modal_rows,
        };
        self.saddle_point(s, &rows.moments, held, false, &mut ws.held_saddle)?;
        Ok(&mut ws.held_saddle.x)
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

    use super::*;
    use crate::{
        dynamics::{
            Body, Constraint, RigidBody,
            evaluation_workspace::EvaluationWorkspace,
            test_systems::{reduced_plank, set_in_motion},
        },
        reduction::Method,
    };

    /// The plank reduced by `method` on `axes` and a rod hung from the ground by one end,
    /// its other end joined to plank node `node`; the plank first or second among the
    /// bodies; deformed and moving.
    fn plank_on_a_rod(
        method: Method,
        axes: AxisType,
        node: usize,
        plank_first: bool,
    ) -> (System, State) {
        let (model, body) = reduced_plank(method, axes);
        let node = model.node_index(node).unwrap();
        let origin = body.origin;
        let (p, r) = if plank_first { (0, 1) } else { (1, 0) };
        let mut bodies = vec![
            Body::Flexible(Box::new(body)),
            Body::Rigid(RigidBody::rod("rod", 1.0, 2.0)),
        ];
        let mut placements = vec![
            (origin, Matrix3::identity()),
            (Vector3::new(0.0, 0.0, 3.0), Matrix3::identity()),
        ];
        if !plank_first {
            bodies.swap(0, 1);
            placements.swap(0, 1);
        }
        let end = |sign: f64| Attachment::Point {
            body: r,
            local: Vector3::new(0.5 * sign, 0.0, 0.0),
        };
        let joints = vec![
            Constraint::Spherical(Attachment::Ground(Vector3::new(-0.5, 0.0, 3.0)), end(-1.0)),
            Constraint::Spherical(end(1.0), Attachment::Node { body: p, node }),
        ];
        let system = System::new(bodies, joints);
        let mut state = system.state_at(&placements);
        set_in_motion(&system, &mut state);
        (system, state)
    }

    /// Rows written into buffers an earlier evaluation left (of the same system at another
    /// state, of a system joined at another node, of one whose bodies are in another order:
    /// each of the same shape) are the rows written into new buffers, to the bit.
    #[test]
    fn reused_constraint_rows_equal_fresh_ones() {
        for method in [Method::NoReduction, Method::CraigBampton] {
            let systems = [
                plank_on_a_rod(method, AxisType::Mean, 3, true),
                plank_on_a_rod(method, AxisType::Mean, 15, true),
                plank_on_a_rod(method, AxisType::Mean, 15, false),
            ];
            let shape = systems[0].0.rows(0.0, &systems[0].1).c.shape();
            let mut rows = Rows::empty();
            for (k, (system, state)) in systems.iter().cycle().take(7).enumerate() {
                let mut state = state.clone();
                state.v *= 1.0 + k as f64;
                system.rows_into(0.0, &state, &mut rows);
                let fresh = system.rows(0.0, &state);
                assert_eq!(
                    fresh.c.shape(),
                    shape,
                    "{method:?}: the systems differ in shape"
                );
                assert_eq!(rows.c, fresh.c, "{method:?}, evaluation {k}");
                assert_eq!(rows.gamma, fresh.gamma, "{method:?}, evaluation {k}");
            }
        }
    }

    /// The velocity correction from the factors an evaluation left is a new correction's,
    /// to the bit, at the evaluated state; and a projection with those factors, after a
    /// step that moved the state off its constraints, lands where a projection with its
    /// own lands, to round-off, on the constraints. On principal axes every row is
    /// holonomic, so the first position correction takes the evaluation's factors too; on
    /// mean axes the rotational rows are not, and it forms its own.
    #[test]
    fn a_correction_from_an_evaluations_factors_is_a_new_one() {
        let cases = [Method::NoReduction, Method::CraigBampton]
            .into_iter()
            .flat_map(|m| [(m, AxisType::Mean), (m, AxisType::Principal)]);
        for (method, axes) in cases {
            for plank_first in [true, false] {
                let (system, state) = plank_on_a_rod(method, axes, 15, plank_first);
                let all_held = system.rows(0.0, &state).holonomic.iter().all(|&h| h);
                assert_eq!(
                    all_held,
                    axes == AxisType::Principal,
                    "{method:?}, {axes:?}"
                );
                let mut ws = EvaluationWorkspace::new(&system);
                system.accelerations_in(0.0, &state, &mut ws).unwrap();
                let rows = system.rows(0.0, &state);
                let g = DVector::from_fn(rows.c.nrows(), |i, _| (i as f64 + 1.0).sin());
                system.resolve_saddle_point(&g, &mut ws.saddle).unwrap();
                let mut fresh = EvaluationWorkspace::new(&system);
                let all = ConstraintRows {
                    c: &rows.c,
                    g: &g,
                    modal_rows: &fresh.modal_rows,
                };
                system
                    .saddle_point(&state, &rows.moments, all, false, &mut fresh.saddle)
                    .unwrap();
                assert_eq!(
                    ws.saddle.x, fresh.saddle.x,
                    "{method:?}, {axes:?}, {plank_first}"
                );

                // A step's end: the state off its constraints by drift, evaluated there.
                let mut end = state.clone();
                for _ in 0..10 {
                    system
                        .project(0.0, &mut end, &mut fresh, ProjectionFactors::Fresh)
                        .unwrap();
                }
                assert!(
                    system.violation(0.0, &end).0 < 1e-12,
                    "{:?}",
                    system.violation(0.0, &end)
                );
                for (i, q) in end.q.iter_mut().enumerate() {
                    *q += 1e-9 * ((i % 7) as f64 - 3.0);
                }
                for (i, v) in end.v.iter_mut().enumerate() {
                    *v += 1e-6 * ((i % 5) as f64 - 2.0);
                }
                system.accelerations_in(0.0, &end, &mut ws).unwrap();
                if all_held {
                    // The position correction from the evaluation's factors is the one the
                    // holonomic rows give formed anew, to the bit.
                    let rows = system.rows(0.0, &end);
                    system
                        .resolve_saddle_point(&rows.phi, &mut ws.saddle)
                        .unwrap();
                    fresh.rows = rows;
                    let held = fresh.rows.c.nrows();
                    let own = system.held_correction(&end, held, &mut fresh).unwrap();
                    assert_eq!(&ws.saddle.x, own, "{method:?}, {axes:?}, {plank_first}");
                    assert!(own.amax() > 1e-10, "a correction of {:e}", own.amax());
                }
                let (mut reused, mut own) = (end.clone(), end.clone());
                system
                    .project(0.0, &mut reused, &mut ws, ProjectionFactors::LastEvaluation)
                    .unwrap();
                system
                    .project(0.0, &mut own, &mut fresh, ProjectionFactors::Fresh)
                    .unwrap();
                let gap_q = (&reused.q - &own.q).amax();
                let gap_v = (&reused.v - &own.v).amax() / own.v.amax();
                assert!(
                    gap_q < 1e-13 && gap_v < 1e-12,
                    "{method:?}, {axes:?}: {gap_q:e}, {gap_v:e}"
                );
                let (pos, vel) = system.violation(0.0, &reused);
                let (own_pos, own_vel) = system.violation(0.0, &own);
                assert!(
                    pos < 1e-12 && vel < 1e-12 * own.v.amax() + 2.0 * own_vel,
                    "{method:?}, {axes:?}: |Φ| {pos:e} (own {own_pos:e}), |Cv - target| {vel:e} (own {own_vel:e})"
                );
                // The drift and the velocity error were there, and were corrected.
                let (drift, slip) = system.violation(0.0, &end);
                assert!(drift > 1e-10 && slip > 1e-7, "{drift:e}, {slip:e}");
            }
        }
    }
}
