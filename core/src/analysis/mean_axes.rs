//! Evaluation of a reduced model with mean axes (§8.4, Eqs. 8.30/8.44 and 8.33/8.45):
//! constraint modes from a static problem and normal modes from a constrained eigenproblem,
//! both with the mean-axis conditions as Lagrange multipliers.

use crate::linalg::LinalgError;
use faer::{Mat, MatRef, Side, linalg::solvers::Solve};

use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{generalized_eigen, hz_from_eigenvalue, max_abs, select_rows},
    reduction::{Basis, Partition},
};

/// Constraint and normal modes of a reduced model seen with mean axes.
#[derive(Debug, Clone)]
pub struct MeanAxesEvaluation {
    /// $[\Delta r; \Delta\theta; \Delta z]^c$, one column per boundary DOF.
    pub constraint_solution: Mat<f64>,
    /// Constraint modes as absolute nodal displacements, $[\Delta d]^c$ (Eq. 8.44's solution
    /// mapped by $[\hat I\ \check s\ \Psi]$).
    pub constraint_modes: Mat<f64>,
    /// Non-zero natural frequencies of Eq. (8.45), Hz, ascending.
    pub normal_hz: Vec<f64>,
    /// Normal modes as absolute nodal displacements, one column per frequency.
    pub normal_modes: Mat<f64>,
}

/// The rigid-body columns $[\hat I\ \check s]$ about the mass centre (2-D: 2 + 1 columns,
/// 3-D: 3 + 3).
pub fn rigid_modes_about_mass_centre(model: &FeModel) -> Mat<f64> {
    let c = model.mass_centre();
    let shifted = FeModel {
        nodes: model
            .nodes
            .iter()
            .map(|p| [p[0] - c[0], p[1] - c[1], p[2] - c[2]])
            .collect(),
        ..model.clone()
    };
    shifted.rigid_body_modes()
}

/// The static problem of Eq. (8.44) for the reduced stiffness `k_r`, the mean-axis rows `g`
/// ($P^TM\Psi$) and the boundary rows `q_b` of $Q$: its solution per unit boundary motion
/// (unknowns $(\Delta r, \Delta\theta, \Delta z)$, $\mu$, $\lambda_3$), by a full-pivoting LU
/// whose residual is checked.
fn static_problem(
    k_r: MatRef<'_, f64>,
    g: MatRef<'_, f64>,
    q_b: MatRef<'_, f64>,
) -> Result<Mat<f64>> {
    let (nr, k, nb) = (g.nrows(), k_r.nrows(), q_b.nrows());
    let n = nr + k + nr + nb;
    let mut a = Mat::<f64>::zeros(n, n);
    for i in 0..k {
        for j in 0..k {
            a[(nr + i, nr + j)] = k_r[(i, j)];
        }
        for j in 0..nr {
            a[(nr + i, nr + k + j)] = g[(j, i)];
            a[(nr + k + j, nr + i)] = g[(j, i)];
        }
    }
    for r in 0..nb {
        for c in 0..nr + k {
            a[(c, nr + k + nr + r)] = q_b[(r, c)];
            a[(nr + k + nr + r, c)] = q_b[(r, c)];
        }
    }
    let mut rhs = Mat::<f64>::zeros(n, nb);
    for l in 0..nb {
        rhs[(nr + k + nr + l, l)] = 1.0;
    }
    let lu = a.full_piv_lu();
    let x = lu.solve(&rhs);
    let residual = &a * &x - &rhs;
    let res = max_abs(residual.as_ref());
    if res.is_nan() || res >= 1e-8 * max_abs(a.as_ref()).max(1.0) {
        return Err(Error::Linalg(LinalgError::SingularMatrix {
            matrix: "mean-axis static problem (Eq. 8.44)".into(),
            rcond: None,
        }));
    }
    Ok(x)
}

/// An orthonormal basis of the null space of $G = [[0, g], [Q_b]]$ (the mean-axis rows `g` and
/// the boundary rows `q_b`), by an SVD with rank tolerance 1e-10 of the largest singular value.
fn constraint_null_space(g: MatRef<'_, f64>, q_b: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let (nr, k, nb) = (g.nrows(), g.ncols(), q_b.nrows());
    let mut gm = Mat::<f64>::zeros(nr + nb, nr + k);
    for i in 0..nr {
        for j in 0..k {
            gm[(i, nr + j)] = g[(i, j)];
        }
    }
    for r in 0..nb {
        for c in 0..nr + k {
            gm[(nr + r, c)] = q_b[(r, c)];
        }
    }
    let svd = gm.transpose().svd().map_err(|_| {
        Error::Linalg(LinalgError::DecompositionFailed {
            what: "mean-axis constraint SVD".into(),
        })
    })?;
    let s = svd.S().column_vector();
    let tol = 1e-10 * s.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    let rank = s.iter().filter(|v| v.abs() > tol).count();
    let u = svd.U();
    Ok(u.subcols(rank, nr + k - rank).to_owned())
}

/// Eqs. (8.44) and (8.45) for `basis` with the boundary set of `partition`.
pub fn evaluate_with_mean_axes(
    model: &FeModel,
    basis: &Basis,
    partition: &Partition,
) -> Result<MeanAxesEvaluation> {
    let p = rigid_modes_about_mass_centre(model); // [I_hat, s_check]
    let nr = p.ncols();
    let k = basis.size();
    let psi = &basis.psi;
    // Q = [I_hat s psi]: absolute displacements from (dr, dtheta, dz).
    let q = Mat::from_fn(psi.nrows(), nr + k, |i, j| {
        if j < nr { p[(i, j)] } else { psi[(i, j - nr)] }
    });
    let q_b = select_rows(q.as_ref(), &partition.b);
    // Mean-axis rows (Eqs. 8.42, 8.43): P^T M psi dz = 0.
    let g = p.transpose() * model.m.mul(psi.as_ref());
    let k_r = basis.reduced_stiffness(model);
    // Static problem (8.44): unknowns x = (dr, dtheta, dz), mu (nr), lambda3 (nb).
    let x = static_problem(k_r.as_ref(), g.as_ref(), q_b.as_ref())?;
    let constraint_solution = x.subrows(0, nr + k).to_owned();
    let constraint_modes = &q * &constraint_solution;

    // Eigenproblem (8.45) on the null space of the constraints: mean-axis rows and a fixed
    // boundary, G x = 0 with G = [[0, g], [Q_b]].
    let null = constraint_null_space(g.as_ref(), q_b.as_ref())?;
    let mut kx = Mat::<f64>::zeros(nr + k, nr + k);
    for i in 0..k {
        for j in 0..k {
            kx[(nr + i, nr + j)] = k_r[(i, j)];
        }
    }
    let mx = q.transpose() * model.m.mul(q.as_ref());
    let kn = null.transpose() * &kx * &null;
    let mn = null.transpose() * &mx * &null;
    if mn.nrows() == 0 {
        return Ok(MeanAxesEvaluation {
            constraint_solution,
            constraint_modes,
            normal_hz: vec![],
            normal_modes: Mat::zeros(psi.nrows(), 0),
        });
    }
    mn.llt(Side::Lower).map_err(|_| {
        Error::Linalg(LinalgError::NotPositiveDefinite {
            matrix: "constrained mean-axis mass".into(),
        })
    })?;
    let e = generalized_eigen(kn.as_ref(), mn.as_ref(), "mean-axis normal")?;
    let keep: Vec<usize> = (e.zero_energy..e.values.len()).collect();
    let normal_hz = keep
        .iter()
        .map(|&i| hz_from_eigenvalue(e.values[i]))
        .collect();
    let modes = &q * &null * &e.vectors;
    let normal_modes = Mat::from_fn(psi.nrows(), keep.len(), |i, j| modes[(i, keep[j])]);
    Ok(MeanAxesEvaluation {
        constraint_solution,
        constraint_modes,
        normal_hz,
        normal_modes,
    })
}
