//! Inertia invariants of a reduced deformable body with a lumped mass matrix, computed once so
//! that the mass matrix, the quadratic-velocity forces and the axis conditions of the
//! floating-frame equations (§3.3, §5.3) never loop over nodes.
//!
//! With $b_j = \bar s_j + \Psi_j z$ and node masses $m_j$, every node sum the equations need
//! is a polynomial of degree two in $z$ whose coefficients are
//!
//! - $m = \sum_j m_j$, $\;c_0 = \sum_j m_j \bar s_j$, $\;P = \sum_j m_j \Psi_j$ (3 × k),
//! - $S = \sum_j m_j \bar s_j \bar s_j^T$ (3 × 3),
//! - $L_c = \sum_j m_j \bar s_j \psi_{jc}^T$ (3 × 3 per mode $c$),
//! - $Q_{cd} = \sum_j m_j \psi_{jc} \psi_{jd}^T$ (3 × 3 per pair of modes),
//!
//! where $\psi_{jc}$ is column $c$ of $\Psi_j$. Cross products need no invariants of their
//! own: $\sum_j m_j\, u_j \times v_j$ is the axial vector of $\sum_j m_j (v_j u_j^T - u_j v_j^T)$.

use std::collections::BTreeMap;

use nalgebra::{DVector, Dyn, Matrix3, Matrix3xX, Storage, Vector, Vector3};

/// A column of modal coordinates, owned or a view into a state vector.
pub type Modal<S> = Vector<f64, Dyn, S>;

/// The vector with $\sum u \times v = \mathrm{axial}(\sum v u^T)$ for any pairs $(u, v)$.
fn axial(m: &Matrix3<f64>) -> Vector3<f64> {
    // (u x v)_x = u_y v_z - u_z v_y = (v u^T)[2,1] - (v u^T)[1,2]
    Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    )
}

/// The invariants of one reduced body (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct InertiaInvariants {
    /// Total mass $m$, kg.
    pub mass: f64,
    /// First moment of the undeformed body about the frame origin, $c_0$, kg m.
    pub first_moment0: Vector3<f64>,
    /// $P = \sum_j m_j \Psi_j$ (3 × k): the translational mean-axis rows (Eq. 4.20).
    pub p_sum: Matrix3xX<f64>,
    /// $S = \sum_j m_j \bar s_j \bar s_j^T$, kg m².
    pub s_outer: Matrix3<f64>,
    /// $L_c$ per mode.
    pub l: Vec<Matrix3<f64>>,
    /// $Q_{cd}$ by rows: for each mode $c$ the modes $d$ with $Q_{cd} \neq 0$ and the
    /// matrix. Without reduction (Ψ = I) a mode couples only with the three of its own node,
    /// so the sums over $(c, d)$ and the storage cost $O(k)$ instead of $O(k^2)$ (a refined
    /// slab of 1 092 DOF would otherwise need 86 MB).
    q: Vec<Vec<(usize, Matrix3<f64>)>>,
    /// The same $Q_{cd}$ stored densely, column by column ($d$, then $c$, then the nine
    /// entries column-major), when most pairs are nonzero (a reduced body's modes move every
    /// node): the sums $\sum_d z_d Q_{cd}$ of every evaluation, for all $c$ at once, are then
    /// $k$ products of a scalar and a contiguous $9k$ vector.
    q_dense: Option<Vec<f64>>,
    /// Otherwise the nonzero entries of each stored $Q_{cd}$, row by row: $(d$, the entry's
    /// index in the column-major 3 × 3, its value$)$. Without reduction each $Q_{cd}$ has one
    /// (a node's mass at one pair of directions): the sums cost a multiply-add per entry, not
    /// a 3 × 3 product per pair.
    q_entries: Vec<Vec<(usize, usize, f64)>>,
    modes: usize,
}

/// Most pairs $Q_{cd}$ nonzero, and at most this many modes: [`InertiaInvariants`] keeps them
/// dense too (at 96 modes, 0.66 MB).
const DENSE_Q_MODES: usize = 96;

impl InertiaInvariants {
    /// Bytes held on the heap: $P$, the $L_c$ and the stored $Q_{cd}$ with their indices.
    pub fn heap_bytes(&self) -> usize {
        let entry = std::mem::size_of::<(usize, Matrix3<f64>)>();
        std::mem::size_of::<f64>() * self.p_sum.len()
            + std::mem::size_of::<Matrix3<f64>>() * self.l.len()
            + self.q.iter().map(|row| entry * row.len()).sum::<usize>()
            + self
                .q_dense
                .as_ref()
                .map_or(0, |q| std::mem::size_of::<f64>() * q.len())
    }

    /// Computes the invariants from node masses (kg), undeformed positions in the body frame
    /// (m) and the per-node rows of Ψ.
    pub fn new(masses: &[f64], s_bar: &[Vector3<f64>], psi_nodes: &[Matrix3xX<f64>]) -> Self {
        let k = psi_nodes.first().map_or(0, |p| p.ncols());
        let mut out = Self {
            mass: 0.0,
            first_moment0: Vector3::zeros(),
            p_sum: Matrix3xX::zeros(k),
            s_outer: Matrix3::zeros(),
            l: vec![Matrix3::zeros(); k],
            q: vec![Vec::new(); k],
            q_dense: None,
            q_entries: Vec::new(),
            modes: k,
        };
        // Q_cd for c <= d, accumulated over the nodes whose rows of Ψ have both columns.
        let mut upper: BTreeMap<(usize, usize), Matrix3<f64>> = BTreeMap::new();
        for ((&mj, s), psi) in masses.iter().zip(s_bar).zip(psi_nodes) {
            out.mass += mj;
            out.first_moment0 += s * mj;
            out.s_outer += s * s.transpose() * mj;
            let present: Vec<usize> = (0..k)
                .filter(|&c| psi.column(c).iter().any(|&x| x != 0.0))
                .collect();
            for (i, &c) in present.iter().enumerate() {
                let pc = psi.column(c);
                out.p_sum.column_mut(c).axpy(mj, &pc, 1.0);
                out.l[c] += s * pc.transpose() * mj;
                for &d in &present[i..] {
                    *upper.entry((c, d)).or_insert_with(Matrix3::zeros) +=
                        pc * psi.column(d).transpose() * mj;
                }
            }
        }
        for ((c, d), q) in upper {
            if q.iter().all(|&x| x == 0.0) {
                continue;
            }
            if c != d {
                out.q[d].push((c, q.transpose()));
            }
            out.q[c].push((d, q));
        }
        for row in &mut out.q {
            row.sort_by_key(|&(d, _)| d);
        }
        let pairs: usize = out.q.iter().map(Vec::len).sum();
        if k <= DENSE_Q_MODES && 2 * pairs > k * k {
            let mut dense = vec![0.0; 9 * k * k];
            for (c, row) in out.q.iter().enumerate() {
                for &(d, ref q) in row {
                    dense[9 * (k * d + c)..9 * (k * d + c) + 9].copy_from_slice(q.as_slice());
                }
            }
            out.q_dense = Some(dense);
        } else {
            out.q_entries = out
                .q
                .iter()
                .map(|row| {
                    row.iter()
                        .flat_map(|&(d, ref q)| {
                            q.as_slice()
                                .iter()
                                .enumerate()
                                .filter(|&(_, &x)| x != 0.0)
                                .map(move |(i, &x)| (d, i, x))
                        })
                        .collect()
                })
                .collect();
        }
        out
    }

    /// `out[c]` $\mathrel{+}= \sum_d v_d Q_{cd}$ for every mode $c$ (`out` holds $k$ matrices):
    /// over the dense columns when kept (one matrix–vector product), else over the stored
    /// pairs with $v_d \neq 0$ in ascending $d$.
    fn add_q_sums<S: Storage<f64, Dyn>>(&self, v: &Modal<S>, out: &mut [Matrix3<f64>]) {
        let k = self.modes;
        match &self.q_dense {
            Some(dense) => {
                // One product of the 9k × k columns with v, on faer's SIMD kernels (the
                // release build's baseline target leaves a plain loop scalar).
                let flat: &mut [f64] = bytemuck::cast_slice_mut(out);
                // v copied to the stack: a view of a state need not be contiguous.
                let mut buffer = [0.0; DENSE_Q_MODES];
                let vs = &mut buffer[..k];
                for (d, x) in vs.iter_mut().enumerate() {
                    *x = v[d];
                }
                faer::linalg::matmul::matmul(
                    faer::MatMut::from_column_major_slice_mut(flat, 9 * k, 1),
                    faer::Accum::Add,
                    faer::MatRef::from_column_major_slice(dense, 9 * k, k),
                    faer::MatRef::from_column_major_slice(&*vs, k, 1),
                    1.0,
                    faer::Par::Seq,
                );
            }
            None => {
                // Per entry of each H_c the same additions in the same ascending d as the
                // 3 × 3 sums, without the zero entries' (exact) additions of nothing.
                for (acc, row) in out.iter_mut().zip(&self.q_entries) {
                    let acc = acc.as_mut_slice();
                    for &(d, i, x) in row {
                        let vd = v[d];
                        if vd != 0.0 {
                            acc[i] += x * vd;
                        }
                    }
                }
            }
        }
    }

    /// Number of modal coordinates k.
    pub fn modes(&self) -> usize {
        self.modes
    }

    /// $Q_{cd}$ (zero when no node moves in both modes).
    pub fn q(&self, c: usize, d: usize) -> Matrix3<f64> {
        self.q[c]
            .iter()
            .find(|&&(e, _)| e == d)
            .map_or_else(Matrix3::zeros, |&(_, q)| q)
    }

    /// First moment about the frame origin, $\sum_j m_j b_j = c_0 + P z$, kg m.
    pub fn first_moment<S: Storage<f64, Dyn>>(&self, z: &Modal<S>) -> Vector3<f64> {
        self.first_moment0 + &self.p_sum * z
    }

    /// $H_c(z) = \sum_j m_j \psi_{jc} b_j^T = L_c^T + \sum_d z_d Q_{cd}$ for every mode $c$.
    pub fn h<S: Storage<f64, Dyn>>(&self, z: &Modal<S>) -> Vec<Matrix3<f64>> {
        let mut out = Vec::with_capacity(self.modes);
        self.h_into(z, &mut out);
        out
    }

    /// [`Self::h`] into `out`, whose storage is reused.
    pub fn h_into<S: Storage<f64, Dyn>>(&self, z: &Modal<S>, out: &mut Vec<Matrix3<f64>>) {
        out.clear();
        out.extend(self.l.iter().map(|l| l.transpose()));
        self.add_q_sums(z, out);
    }

    /// $\sum_j m_j b_j b_j^T = S + \sum_c z_c (L_c + H_c)$, kg m², from $H$ of [`Self::h`].
    pub fn second_moment<S: Storage<f64, Dyn>>(
        &self,
        z: &Modal<S>,
        h: &[Matrix3<f64>],
    ) -> Matrix3<f64> {
        let mut out = self.s_outer;
        for c in 0..self.modes {
            out += (self.l[c] + h[c]) * z[c];
        }
        out
    }

    /// Inertia about the frame origin in body axes,
    /// $\bar J = \sum_j m_j \tilde b_j^T \tilde b_j = \mathrm{tr}(B) I - B$ with $B$ the second
    /// moment, kg m².
    pub fn inertia<S: Storage<f64, Dyn>>(&self, z: &Modal<S>) -> Matrix3<f64> {
        Self::inertia_from(&self.second_moment(z, &self.h(z)))
    }

    /// $\mathrm{tr}(B) I - B$: the inertia from a second moment $B$ of [`Self::second_moment`].
    pub fn inertia_from(second_moment: &Matrix3<f64>) -> Matrix3<f64> {
        Matrix3::identity() * second_moment.trace() - second_moment
    }

    /// $\sum_j m_j \tilde b_j \Psi_j$ (3 × k): the rotation–deformation coupling of the mass
    /// matrix and the rotational mean-axis rows (Eq. 4.15). Column $d$ is
    /// $\sum_j m_j b_j \times \psi_{jd}$, the axial vector of $H_d$.
    pub fn rotation_coupling(&self, h: &[Matrix3<f64>]) -> Matrix3xX<f64> {
        let mut out = Matrix3xX::zeros(self.modes);
        Self::rotation_coupling_into(h, &mut out.as_view_mut());
        out
    }

    /// [`Self::rotation_coupling`] into a 3 × k view (rows of a larger matrix).
    pub fn rotation_coupling_into(
        h: &[Matrix3<f64>],
        out: &mut nalgebra::MatrixViewMut<'_, f64, nalgebra::U3, Dyn, nalgebra::U1, Dyn>,
    ) {
        for (d, hd) in h.iter().enumerate() {
            out.set_column(d, &axial(hd));
        }
    }

    /// $\sum_j m_j (\Psi_j a)(\Psi_j b)^T = \sum_{cd} a_c b_d Q_{cd}$.
    pub fn modal_outer<S: Storage<f64, Dyn>, T: Storage<f64, Dyn>>(
        &self,
        a: &Modal<S>,
        b: &Modal<T>,
    ) -> Matrix3<f64> {
        let mut out = Matrix3::zeros();
        for c in 0..self.modes {
            if a[c] == 0.0 {
                continue;
            }
            for &(d, ref q) in &self.q[c] {
                if b[d] != 0.0 {
                    out += q * (a[c] * b[d]);
                }
            }
        }
        out
    }

    /// The velocity-dependent inertia forces of the floating-frame equations for frame angular
    /// velocity $\bar\omega$ (body axes, rad/s), deformation $z$ and its rate $\dot z$, as
    /// $(\sum_j m_j\alpha_j,\ \sum_j m_j\, b_j\times\alpha_j,\ \sum_j m_j \Psi_j^T\alpha_j)$ with
    /// $\alpha_j = \bar\omega\times(\bar\omega\times b_j) + 2\bar\omega\times\Psi_j\dot z$
    /// (body axes; the generalised forces subtract them). `h` and `inertia` are those of the
    /// same `z` ([`Self::h`], [`Self::inertia_from`]), which the mass matrix needs too. The
    /// modal forces are written into `modal` (k entries); the other two are returned.
    /// `coriolis` is scratch ($\sum_d \dot z_d Q_{cd}$ per mode), reused.
    pub fn velocity_forces<S: Storage<f64, Dyn>, T: Storage<f64, Dyn>>(
        &self,
        w: &Vector3<f64>,
        (z, zd): (&Modal<S>, &Modal<T>),
        h: &[Matrix3<f64>],
        inertia: &Matrix3<f64>,
        modal: &mut DVector<f64>,
        coriolis: &mut Vec<Matrix3<f64>>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let first = self.first_moment(z);
        let u_sum = &self.p_sum * zd;
        let translational = w.cross(&w.cross(&first)) + 2.0 * w.cross(&u_sum);
        // sum m b x (w x (w x b)) = w x (J w); sum m b x (w x u) = w tr(G) - G w with
        // G = sum m u b^T = sum_c zd_c H_c.
        let mut g = Matrix3::zeros();
        for (c, hc) in h.iter().enumerate() {
            g += hc * zd[c];
        }
        let rotational = w.cross(&(inertia * w)) + 2.0 * (w * g.trace() - g * w);
        // psi_c . (w x (w x b)) = w^T (psi_c b^T) w - |w|^2 psi_c . b, summed over nodes:
        // w^T H_c w - |w|^2 tr H_c. And psi_c . (w x u) = w . (u x psi_c), summed:
        // w . axial(sum m psi_c u^T) = w . axial(sum_d zd_d Q_cd).
        let w2 = w.norm_squared();
        coriolis.clear();
        coriolis.resize(self.modes, Matrix3::zeros());
        self.add_q_sums(zd, coriolis);
        for (c, qc) in coriolis.iter().enumerate() {
            let centrifugal = (w.transpose() * h[c] * w)[0] - w2 * h[c].trace();
            modal[c] = centrifugal + 2.0 * w.dot(&axial(qc));
        }
        (translational, rotational)
    }
}
