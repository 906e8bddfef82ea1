//! Dynamic (geometric, stress) stiffening of a deformable body on a free floating frame
//! (Lin's thesis §1, refs. [16] Kane, Ryan & Banerjee 1987 and [18] Zhang & Huston 1996):
//! the three-dimensional counterpart of [`super::FrameStiffening`], for the bodies of a
//! [`super::System`].
//!
//! A point $\bar s$ of the body (frame axes, §3.3) of a frame with origin acceleration
//! $\ddot r$, angular velocity $\bar\omega$ and angular acceleration $\bar\alpha$ (body axes)
//! carries, per unit mass, the inertia and gravity load
//! $$\bar f(\bar s) = \bar b - \bar\alpha\times\bar s - (\bar\omega\bar\omega^T -
//! |\bar\omega|^2 I)\,\bar s, \qquad \bar b = A^T(g - \ddot r),$$
//! linear in twelve coefficients: the six products $\omega_x^2, \omega_y^2, \omega_z^2,
//! \omega_x\omega_y, \omega_y\omega_z, \omega_z\omega_x$, the three $\alpha_a$ and the three
//! components of the specific force $\bar b$. Each unit case is applied to the body's nodes
//! and solved statically with the body held as its axes hold it: at the anchored
//! coordinates of nodal-fixed axes (Table 4-1), or by inertia relief on mean and principal
//! axes (the load less its rigid-body resultant, $f - MR(R^T M R)^{-1}R^Tf$, so the body is
//! free and no support carries anything). The stresses of case $i$ give
//! $K_{\sigma,i}$ (the elements' geometric stiffness), projected once on the body's basis:
//! $\Psi^T K_{\sigma,i}\Psi$. At every evaluation the modal equations gain
//! $-\sum_i c_i(t)\,K_{\sigma,i}\,z$.
//!
//! Kept: the first-order prestress of the frame's inertia loads and gravity (Wallrapp and
//! Wiedemann 2002's modal stiffening). Left out: the prestress of the joint forces beyond
//! what the supports of the static cases carry, and of the elastic coordinates' own
//! accelerations and Coriolis forces (second order in the deformation).

use faer::{Mat, linalg::solvers::Solve};
use nalgebra::{DMatrix, DVector, Dyn, IsContiguous, Storage, Vector3};

use super::{AxisType, DynamicsError, inertia_invariants::Modal};
use crate::{
    Error, Result,
    error::MatrixLabel,
    fem::{BrickElements, FeModel, RigidMotions},
    linalg::{LinalgError, SparseSymmetric, SymbolicFactor, SymmetricFactor},
    reduction::Basis,
};

/// Unit cases of a free frame: six products of the angular velocity, three angular
/// accelerations, three components of the specific force.
pub const FREE_FRAME_CASES: usize = 12;

/// The cases' names, in their order.
pub const FREE_FRAME_CASE_NAMES: [&str; FREE_FRAME_CASES] = [
    "ω_x²",
    "ω_y²",
    "ω_z²",
    "ω_x ω_y",
    "ω_y ω_z",
    "ω_z ω_x",
    "α_x",
    "α_y",
    "α_z",
    "b_x",
    "b_y",
    "b_z",
];

/// The first angular-acceleration case.
pub const ANGULAR_ACCELERATION_CASES: usize = 6;
/// The first specific-force case.
pub const SPECIFIC_FORCE_CASES: usize = 9;

/// The cases left out: the angular accelerations. Their stiffening term, $\dot{\bar\omega}_a
/// K_{\sigma,\alpha_a} z$, makes the frame's rotation an inertia coupling of the modal
/// equations; taken alone (unsymmetric, or made symmetric as a kinetic energy
/// $\bar\omega_a z^TK_{\sigma,\alpha_a}\dot z$ gives it, without that energy's velocity terms) it
/// made the slab of Lin's Simulation 2 diverge within 0.3 s where the model without it and
/// the nonlinear body stay bounded. On a body turning about a fixed axis they vanish for a
/// straight beam ([`super::FrameStiffening`]'s θ̈ case), and they are absent on mean and
/// principal axes (inertia relief takes a rigid acceleration field whole).
const KEPT_OUT: [usize; 3] = [
    ANGULAR_ACCELERATION_CASES,
    ANGULAR_ACCELERATION_CASES + 1,
    ANGULAR_ACCELERATION_CASES + 2,
];

/// Largest relative residual of the static solves of the unit cases.
const STATIC_TOLERANCE: f64 = 1e-9;

/// The projected geometric stiffness of each unit case of a free frame's loads (`None`: the
/// case stresses nothing).
#[derive(Debug, Clone, PartialEq)]
pub struct FreeFrameStiffening {
    dim: usize,
    cases: [Option<DMatrix<f64>>; FREE_FRAME_CASES],
}

/// The load per unit mass of case `case` at the point `s` (body axes, m): $\partial\bar f /
/// \partial c_i$ of the module's $\bar f$.
pub fn unit_field(case: usize, s: &Vector3<f64>) -> Vector3<f64> {
    let (x, y, z) = (s.x, s.y, s.z);
    match case {
        // −(e_a e_aᵀ − I) s
        0 => Vector3::new(0.0, y, z),
        1 => Vector3::new(x, 0.0, z),
        2 => Vector3::new(x, y, 0.0),
        // −(e_a e_bᵀ + e_b e_aᵀ) s
        3 => -Vector3::new(y, x, 0.0),
        4 => -Vector3::new(0.0, z, y),
        5 => -Vector3::new(z, 0.0, x),
        // −e_a × s
        6..=8 => -Vector3::ith(case - 6, 1.0).cross(s),
        SPECIFIC_FORCE_CASES..FREE_FRAME_CASES => Vector3::ith(case - SPECIFIC_FORCE_CASES, 1.0),
        _ => Vector3::zeros(),
    }
}

/// The coefficients of the unit cases at angular velocity `w`, angular acceleration `alpha`
/// (rad/s, rad/s², body axes) and specific force `b` (m/s², body axes).
pub fn free_frame_coefficients(
    w: &Vector3<f64>,
    alpha: &Vector3<f64>,
    b: &Vector3<f64>,
) -> [f64; FREE_FRAME_CASES] {
    [
        w.x * w.x,
        w.y * w.y,
        w.z * w.z,
        w.x * w.y,
        w.y * w.z,
        w.z * w.x,
        alpha.x,
        alpha.y,
        alpha.z,
        b.x,
        b.y,
        b.z,
    ]
}

/// How the body is held while a unit load case is solved statically.
#[derive(Debug, Clone, PartialEq)]
pub enum CaseSupport {
    /// These DOF (0-based) held at zero; their reactions carry the load's resultant.
    Held(Vec<usize>),
    /// Free, by inertia relief: each load less its rigid-body resultant, on six statically
    /// determinate supports that must then carry nothing.
    Relieved,
}

/// The geometric stiffness (the model's DOF, N/m per unit coefficient) of each unit case in
/// `cases` for the body `model` meshed by `elements`, on a frame with `origin` (model
/// coordinates, m), solved statically held as `support` says: $K_{\sigma}(u_i)$ with
/// $K u_i = M f_i$, $f_i$ the case's [`unit_field`] at the nodes (for a consistent mass the
/// exact load of a linear field, as CalculiX's `CENTRIF` applies it). `None` where the case
/// stresses nothing (a rigid acceleration field relieved whole). Every solve is checked:
/// relative residual at most $10^{-9}$ on the free DOF, and on every DOF when relieved.
pub fn unit_case_stiffnesses(
    model: &FeModel,
    elements: &BrickElements,
    origin: Vector3<f64>,
    support: &CaseSupport,
    cases: &[usize],
) -> Result<Vec<Option<SparseSymmetric>>> {
    let n = model.dof_count();
    let fields = Mat::from_fn(n, cases.len(), |d, c| {
        let p = model.nodes[d / 3];
        unit_field(cases[c], &(Vector3::new(p[0], p[1], p[2]) - origin))[d % 3]
    });
    let mut loads = model.m.mul(fields.as_ref());
    let (held, relieved) = match support {
        CaseSupport::Held(dofs) => (dofs.clone(), false),
        CaseSupport::Relieved => {
            if model.rigid_motions != RigidMotions::FromGeometry {
                return Err(DynamicsError::StiffeningSupport {
                    body: (&model.name).into(),
                    why: "its rigid motions are not known, and mean axes relieve the loads by them",
                }
                .into());
            }
            relieve(model, &mut loads)?;
            (statically_determinate_support(model)?, true)
        }
    };
    let displacements = restrained_solve(model, &held, &loads, relieved)?;
    (0..cases.len())
        .map(|c| {
            let u: Vec<f64> = (0..n).map(|d| displacements[(d, c)]).collect();
            if u.iter().all(|&x| x == 0.0) {
                return Ok(None);
            }
            elements.geometric_stiffness(&model.nodes, &u).map(Some)
        })
        .collect()
}

impl FreeFrameStiffening {
    /// The unit cases of `model` (3 DOF per node) meshed by `elements`, on a frame with
    /// `origin` (model coordinates, m) held as `axes` hold it ([`unit_case_stiffnesses`]:
    /// at the anchored coordinates of nodal-fixed axes, relieved on mean and principal axes),
    /// projected on `basis` (the body's, $n \times k$). The angular accelerations' cases
    /// are left out (`KEPT_OUT`).
    pub fn new(
        model: &FeModel,
        elements: &BrickElements,
        axes: &AxisType,
        origin: Vector3<f64>,
        basis: &Basis,
    ) -> Result<Self> {
        let support = match axes {
            AxisType::NodalFixed(nf) => CaseSupport::Held(
                nf.anchored_dofs(model)?
                    .into_iter()
                    .map(|(_, _, d)| d)
                    .collect(),
            ),
            AxisType::Mean | AxisType::Principal => CaseSupport::Relieved,
        };
        let kept: Vec<usize> = (0..FREE_FRAME_CASES)
            .filter(|c| !KEPT_OUT.contains(c))
            .collect();
        let stiffnesses = unit_case_stiffnesses(model, elements, origin, &support, &kept)?;
        let mut cases: [Option<DMatrix<f64>>; FREE_FRAME_CASES] = Default::default();
        for (&case, k_sigma) in kept.iter().zip(stiffnesses) {
            let Some(k_sigma) = k_sigma else { continue };
            let p = basis.project(&k_sigma);
            cases[case] = Some(DMatrix::from_fn(p.nrows(), p.ncols(), |a, b| p[(a, b)]));
        }
        Ok(Self {
            dim: basis.size(),
            cases,
        })
    }

    /// Bytes of the projected matrices.
    pub fn heap_bytes(&self) -> usize {
        self.cases.iter().flatten().map(|k| 8 * k.len()).sum()
    }

    /// Modal coordinates.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Case `i`'s projected matrix.
    pub fn case(&self, i: usize) -> Option<&DMatrix<f64>> {
        self.cases.get(i)?.as_ref()
    }

    /// Adds the frame–modal mass coupling of the acceleration cases to `m_fz` (6 × k: the
    /// translational rows in global axes, then the body-axis rotational rows) of a frame with
    /// rotation `a`: row $a$ of the translations gains $-\sum_i A_{ai}(K_{\sigma,b_i}z)^T$,
    /// row $a$ of the rotations $(K_{\sigma,\alpha_a}z)^T$ (see [`crate::dynamics::System`]'s
    /// use: the same columns enter the modal rows, so the mass matrix stays symmetric).
    /// `scratch` holds $K_{\sigma,i}z$ (k entries), reused.
    pub fn add_mass_coupling<S: Storage<f64, Dyn>>(
        &self,
        a: &nalgebra::Matrix3<f64>,
        z: &Modal<S>,
        m_fz: &mut DMatrix<f64>,
        scratch: &mut DVector<f64>,
    ) {
        let v = scratch;
        for i in 0..3 {
            if let Some(kb) = &self.cases[SPECIFIC_FORCE_CASES + i] {
                v.gemv(1.0, kb, z, 0.0);
                for row in 0..3 {
                    for (c, vc) in v.iter().enumerate() {
                        m_fz[(row, c)] -= a[(row, i)] * vc;
                    }
                }
            }
            if let Some(ka) = &self.cases[ANGULAR_ACCELERATION_CASES + i] {
                v.gemv(1.0, ka, z, 0.0);
                for (c, vc) in v.iter().enumerate() {
                    m_fz[(3 + i, c)] += vc;
                }
            }
        }
    }

    /// `out` $\mathrel{-}= \sum_i c_i K_{\sigma,i} z$.
    pub fn subtract_force<S: Storage<f64, Dyn> + IsContiguous>(
        &self,
        c: &[f64; FREE_FRAME_CASES],
        z: &Modal<S>,
        out: &mut DVector<f64>,
    ) {
        for (i, case) in self.cases.iter().enumerate() {
            if let Some(k) = case
                && c[i] != 0.0
            {
                out.gemv(-c[i], k, z, 1.0);
            }
        }
    }
}

/// `loads` less their rigid-body resultant: $f - MR(R^T M R)^{-1}R^Tf$ with $R$ the model's
/// rigid motions, so that each column is self-equilibrated. A rigid acceleration field is
/// relieved whole: on mean and principal axes the angular accelerations and the specific
/// force stress nothing (the body accelerates freely), only the angular velocity's
/// centrifugal field does.
fn relieve(model: &FeModel, loads: &mut Mat<f64>) -> Result<()> {
    let r = model.rigid_body_modes();
    let mr = model.m.mul(r.as_ref());
    let rmr = r.transpose() * &mr;
    let rf = r.transpose() * &*loads;
    let coefficients = rmr.as_ref().llt(faer::Side::Lower).map(|l| l.solve(&rf));
    let Ok(a) = coefficients else {
        return Err(DynamicsError::StiffeningSupport {
            body: (&model.name).into(),
            why: "the mass of its rigid motions, R^T M R, is not positive definite",
        }
        .into());
    };
    let before: Vec<f64> = (0..loads.ncols())
        .map(|j| loads.col(j).norm_max())
        .collect();
    *loads -= &mr * a;
    // A rigid acceleration field (the angular accelerations, the specific force) is relieved
    // whole: what round-off leaves of it loads nothing.
    for (j, before) in before.into_iter().enumerate() {
        if loads.col(j).norm_max() <= 1e-12 * before {
            loads.col_mut(j).fill(0.0);
        }
    }
    Ok(())
}

/// Six coordinates that hold a free solid statically determinately: all three at the node
/// farthest from the mass centre, two at the node farthest from it, one at the node farthest
/// from the line through both (the directions each holds chosen against that geometry).
fn statically_determinate_support(model: &FeModel) -> Result<Vec<usize>> {
    let p: Vec<Vector3<f64>> = model.nodes.iter().map(|x| Vector3::from(*x)).collect();
    let c = Vector3::from(model.mass_centre());
    let farthest = |from: &dyn Fn(&Vector3<f64>) -> f64| {
        (0..p.len())
            .max_by(|&a, &b| from(&p[a]).total_cmp(&from(&p[b])))
            .unwrap_or(0)
    };
    let a = farthest(&|x| (x - c).norm());
    let b = farthest(&|x| (x - p[a]).norm());
    let axis = (p[b] - p[a]).normalize();
    let c3 = farthest(&|x| (x - p[a]).cross(&axis).norm());
    let normal = (p[c3] - p[a]).cross(&axis);
    let size = (p[b] - p[a]).norm();
    if normal.norm().is_nan() || normal.norm() <= 1e-6 * size * size {
        return Err(DynamicsError::StiffeningSupport {
            body: (&model.name).into(),
            why: "its nodes lie on a line",
        }
        .into());
    }
    let normal = normal.normalize();
    // At b: the two directions least along the axis; at c: the one most along the normal.
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| axis[i].abs().total_cmp(&axis[j].abs()));
    let along_normal = (0..3)
        .max_by(|&i, &j| normal[i].abs().total_cmp(&normal[j].abs()))
        .unwrap_or(2);
    Ok(vec![
        3 * a,
        3 * a + 1,
        3 * a + 2,
        3 * b + order[0],
        3 * b + order[1],
        3 * c3 + along_normal,
    ])
}

/// $u$ with $K_{ff}u_f = f_f$ and $u_h = 0$ at the `held` DOF, for every column of `loads`,
/// its residual checked; when `relieved`, the reactions at the held DOF must vanish too.
fn restrained_solve(
    model: &FeModel,
    held: &[usize],
    loads: &Mat<f64>,
    relieved: bool,
) -> Result<Mat<f64>> {
    let n = model.dof_count();
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let label = MatrixLabel::of_body("stiffness held for the stiffening load cases", &model.name);
    let k_ff = model.k.principal_block(&free);
    let symbolic = SymbolicFactor::analyse(k_ff.as_faer())?;
    let factor = SymmetricFactor::sparse(k_ff.as_faer(), &symbolic, label.clone())?;
    let rhs = Mat::from_fn(free.len(), loads.ncols(), |i, j| loads[(free[i], j)]);
    let x = factor.solve(rhs.as_ref());
    let mut u = Mat::<f64>::zeros(n, loads.ncols());
    for (i, &d) in free.iter().enumerate() {
        for j in 0..loads.ncols() {
            u[(d, j)] = x[(i, j)];
        }
    }
    // Residual on every DOF: the free ones must balance, and relieved loads leave nothing
    // for the supports.
    let ku = model.k.mul(u.as_ref());
    let k_abs_u = model.k.abs_mul(u.as_ref());
    for j in 0..loads.ncols() {
        let scale = (0..n)
            .map(|d| k_abs_u[(d, j)] + loads[(d, j)].abs())
            .fold(0.0f64, f64::max);
        if scale == 0.0 {
            continue;
        }
        let residual = (0..n)
            .filter(|d| relieved || !held.contains(d))
            .map(|d| (ku[(d, j)] - loads[(d, j)]).abs())
            .fold(0.0f64, f64::max)
            / scale;
        if residual.is_nan() || residual > STATIC_TOLERANCE {
            return Err(Error::Linalg(LinalgError::SolveInaccurate {
                matrix: label,
                residual,
                tolerance: STATIC_TOLERANCE,
            }));
        }
    }
    Ok(u)
}

#[cfg(test)]
mod tests {
    use nalgebra::{DVector, Matrix3, Vector3};

    use super::*;
    use crate::{
        dynamics::{
            Attachment, Body, Constraint, FlexibleBody, RigidBody, System,
            test_systems::set_in_motion,
        },
        fem::{Direction, SlabParameters, plank, slab},
        reduction::{
            Method, ModeSelection, NodalFixedAxes, ReductionRequest, TableConfiguration, reduce,
        },
    };

    /// A slender bar spun about z through its mass centre carries the axial force
    /// $N(x) = \rho A\Omega^2(L^2/4 - x^2)/2$; on the field $v_y = x^2$ the geometric
    /// stiffness' energy is $\int N v'^2 dx = \rho A \Omega^2 L^5 / 60$ (closed form, per
    /// unit $\Omega^2$). The bricks (Poisson's ratio 0, lumped masses, inertia relief on
    /// mean axes) converge to it as $h^2$: 4.9 %, 1.2 %, 0.31 % at 10, 20, 40 bricks.
    #[test]
    fn a_spun_bar_stiffens_by_its_centrifugal_tension() {
        let (length, mass) = (10.0f64, 12.0);
        let closed = mass / length * length.powi(5) / 60.0;
        let mut errors = Vec::new();
        for n in [10, 20, 40] {
            let p = SlabParameters {
                size: [length, 0.2, 0.2],
                bricks: [n, 1, 1],
                youngs_modulus: 2.0e11,
                poisson_ratio: 0.0,
                total_mass: mass,
                consistent_mass: false,
            };
            let model = slab(&p);
            let centre = Vector3::from(model.mass_centre());
            let dofs = model.dof_count();
            let cases = unit_case_stiffnesses(
                &model,
                &BrickElements::of_slab(&p),
                centre,
                &CaseSupport::Relieved,
                &[0, 2],
            )
            .unwrap();
            let energy_of = |k: &SparseSymmetric, v: &DVector<f64>| -> f64 {
                let kv = k.mul(faer::MatRef::from_column_major_slice(
                    v.as_slice(),
                    v.len(),
                    1,
                ));
                (0..v.len()).map(|i| v[i] * kv[(i, 0)]).sum()
            };
            let v = DVector::from_fn(dofs, |d, _| {
                if d % 3 == 1 {
                    let x = model.nodes[d / 3][0] - centre.x;
                    x * x
                } else {
                    0.0
                }
            });
            let k = cases[1].as_ref().expect("ω_z² stresses the bar");
            let energy = energy_of(k, &v);
            errors.push((energy - closed).abs() / closed);
            // Spin about the bar's own axis stresses it only across: far less energy.
            let along = cases[0].as_ref().map_or(0.0, |k| energy_of(k, &v).abs());
            assert!(
                along < 1e-3 * closed,
                "spin about x: {along} against {closed}"
            );
        }
        assert!(
            errors[2] < 0.005 && errors[1] < 0.3 * errors[0] && errors[2] < 0.3 * errors[1],
            "relative errors at 10, 20, 40 bricks: {errors:?}"
        );
    }

    /// The twelve unit fields add up to the inertia and gravity load of the module
    /// documentation at an arbitrary frame state.
    #[test]
    fn unit_fields_sum_to_the_frame_load() {
        let (w, alpha, b) = (
            Vector3::new(0.3, -1.2, 2.0),
            Vector3::new(-0.7, 0.4, 1.1),
            Vector3::new(0.2, 9.0, -3.0),
        );
        let s = Vector3::new(1.5, -0.4, 0.9);
        let c = free_frame_coefficients(&w, &alpha, &b);
        let sum = (0..FREE_FRAME_CASES).fold(Vector3::zeros(), |f, i| f + unit_field(i, &s) * c[i]);
        let expected = b - alpha.cross(&s) - w.cross(&w.cross(&s));
        assert!((sum - expected).norm() < 1e-14 * expected.norm());
    }

    /// A stiffened plank on a rod, moving and deformed under gravity: the block elimination
    /// gives the accelerations of the dense system, whose mass matrix stays symmetric and
    /// holds the specific force's coupling $-\sum_i A_{ai}K_{\sigma,b_i}z$ in its modal rows
    /// and translational columns; the stiffening changes the accelerations by far more than
    /// the tolerance.
    #[test]
    fn stiffened_accelerations_solve_the_dense_system() {
        // Nodal-fixed axes: origin node 8, ξ through node 14, node 23 on the ξη plane, held
        // there, so the frame's accelerations stress the plank (on mean axes they do not).
        let axes = AxisType::NodalFixed(NodalFixedAxes {
            origin: 8,
            axis_node: 14,
            plane_node: 23,
            configuration: TableConfiguration::new(Direction::X, Direction::Y),
        });
        for method in [Method::CraigBampton, Method::NoReduction] {
            let model = plank(&SlabParameters::default());
            let basis = reduce(
                &model,
                &ReductionRequest {
                    method,
                    boundary_nodes: vec![8, 14, 23, 15],
                    modes: ModeSelection::Count(6),
                    ..Default::default()
                },
            )
            .unwrap();
            let body = FlexibleBody::new(model.clone(), basis, axes).unwrap();
            let plain = body.clone();
            let body = body
                .with_stiffening(&BrickElements::of_slab(&SlabParameters::default()))
                .unwrap();
            let st = body.stiffening.clone().unwrap();
            assert!(st.case(SPECIFIC_FORCE_CASES).is_some());
            let node = model.node_index(15).unwrap();
            let origin = body.origin;
            let end = |sign: f64| Attachment::Point {
                body: 1,
                local: Vector3::new(0.5 * sign, 0.0, 0.0),
            };
            let joints = vec![
                Constraint::Spherical(Attachment::Ground(Vector3::new(-0.5, 0.0, 3.0)), end(-1.0)),
                Constraint::Spherical(end(1.0), Attachment::Node { body: 0, node }),
            ];
            let placements = [
                (origin, Matrix3::identity()),
                (Vector3::new(0.0, 0.0, 3.0), Matrix3::identity()),
            ];
            let rod = Body::Rigid(RigidBody::rod("rod", 1.0, 2.0));
            let system = System::new(
                vec![Body::Flexible(Box::new(body)), rod.clone()],
                joints.clone(),
            );
            let mut state = system.state_at(&placements);
            set_in_motion(&system, &mut state);
            let (qo, vo) = system.offsets(0);
            let k = st.dim();
            let blocks = system.accelerations(0.0, &state).unwrap();
            let dense = system.accelerations_dense(0.0, &state).unwrap();
            let scale = dense.amax();
            let error = (&blocks - &dense).amax() / scale;
            let (m, _) = system.mass_and_forces(&state);
            let asymmetry = (&m - m.transpose()).amax() / m.amax();
            let unstiffened = System::new(vec![Body::Flexible(Box::new(plain)), rod], joints);
            let (m_plain, _) = unstiffened.mass_and_forces(&state);
            let a = system.frame(0, &state).a;
            let z = state.q.rows(qo + 7, k).into_owned();
            let mut coupling_error = 0.0f64;
            let mut coupling = 0.0f64;
            for axis in 0..3 {
                let mut expected = DVector::zeros(k);
                for i in 0..3 {
                    if let Some(kb) = st.case(SPECIFIC_FORCE_CASES + i) {
                        expected -= kb * &z * a[(axis, i)];
                    }
                }
                let added =
                    m.view((vo + 6, vo + axis), (k, 1)) - m_plain.view((vo + 6, vo + axis), (k, 1));
                coupling_error = coupling_error.max((added - &expected).amax());
                coupling = coupling.max(expected.amax());
            }
            let plain_accelerations = unstiffened.accelerations(0.0, &state).unwrap();
            let stiffening = (&plain_accelerations - &dense).amax() / scale;
            assert!(
                error < 1e-9
                    && asymmetry < 1e-13
                    && coupling > 0.0
                    && coupling_error < 1e-12 * coupling
                    && stiffening > 1e3 * error,
                "{method:?}: blocks against dense {error:.1e}, asymmetry {asymmetry:.1e}, \
                 coupling {coupling:.1e} off by {coupling_error:.1e}, stiffening {stiffening:.1e}"
            );
        }
    }
}
