//! Static correction of a fixed-interface basis for the body's own inertia loads: the
//! residual vectors of the frame's unit inertia loads ([`InertiaLoads`]).
//!
//! A body on a moving frame is loaded by $-Ma(x)$, a combination of twelve unit loads
//! $f_k = M a_k$ (linear and angular accelerations, the products $\omega_i\omega_j$). Their
//! quasi-static response, a spun part's arms stretching under their own centrifugal load,
//! is a shape no low fixed-interface mode need hold: Craig–Bampton with ten modes misses it
//! whole, and its constraint modes cannot help where the interface is clamped. The classic
//! remedy is to add the loads' static responses to the basis: Nastran's residual vectors for
//! inertia loads (RESVEC), Dickens, Nakagawa & Wittbrodt's modal truncation augmentation
//! (1997), the first block of Wilson, Yuan & Dickens' load-dependent Ritz vectors (1982) and
//! of Witteveen's Krylov space (Eq. 21, $P^0R$ with the loads as inputs).
//!
//! With the whole boundary held (Eq. 6.1's partition), the interior response to load $k$ is
//! $x_k = K_{ii}^{-1} f_{k,i}$. Each is made $M_{ii}$-orthogonal to the basis' interior
//! columns $\Phi$ (those zero on the boundary: the fixed-interface modes) and to the vectors
//! kept before it, twice (classical Gram–Schmidt, repeated), and kept when what is left holds
//! more than [`RESIDUAL_VECTOR_DEFLATION`] of its $M_{ii}$-norm; it is appended as
//! $[0;\,x_k]$ with unit $M_{ii}$-norm. Zero on the boundary, the vectors leave a clamped
//! interface clamped, and with the constraint modes they span the static response to every
//! inertia load with any subset of the interfaces held.
//!
//! The a-priori estimate of a basis for a load $f$ is the share of the static response
//! $u = K_{ii}^{-1}f_i$ that its interior columns $\Phi$ miss in the energy norm: with the
//! Ritz approximation $u_r = \Phi(\Phi^TK_{ii}\Phi)^{-1}\Phi^Tf_i$,
//! $$\epsilon = \frac{\|u - u_r\|_{K_{ii}}}{\|u\|_{K_{ii}}},$$
//! 1 when the basis holds nothing of it, round-off when it holds it all.

use faer::{Mat, MatRef};

use super::{Basis, Column, ColumnKind, InteriorProblem};
use crate::{
    Result,
    fem::{InertiaLoadCase, InertiaLoads},
    linalg::MassMatrix,
};

/// Share of its $M_{ii}$-norm a load's static response must keep after orthogonalisation to
/// the basis (and to the vectors before it) to be kept.
pub const RESIDUAL_VECTOR_DEFLATION: f64 = 1e-8;

/// What [`with_inertia_residual_vectors`] added.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidualVectorsAdded {
    /// The loads whose vectors were appended, in column order.
    pub kept: Vec<InertiaLoadCase>,
    /// The loads whose responses the basis (or the vectors before them) already held.
    pub dropped: Vec<InertiaLoadCase>,
}

/// Indices of the basis columns that vanish on every boundary DOF of `problem`.
fn interior_columns(problem: &InteriorProblem, basis: &Basis) -> Vec<usize> {
    let b = &problem.partition.b;
    (0..basis.size())
        .filter(|&j| b.iter().all(|&d| basis.psi[(d, j)] == 0.0))
        .collect()
}

/// The interior rows of the columns `cols` of `basis`.
fn interior_rows(problem: &InteriorProblem, basis: &Basis, cols: &[usize]) -> Mat<f64> {
    let i = &problem.partition.i;
    Mat::from_fn(i.len(), cols.len(), |r, c| basis.psi[(i[r], cols[c])])
}

fn mass_times(m: &MassMatrix, x: MatRef<'_, f64>) -> Mat<f64> {
    m.mul(x)
}

/// `basis` with the residual vectors of `loads` appended (see the module documentation), and
/// which were kept. The basis must come from `problem` (its rows the body's DOF, its boundary
/// the problem's).
pub fn with_inertia_residual_vectors(
    problem: &mut InteriorProblem,
    mut basis: Basis,
    loads: &InertiaLoads,
) -> Result<(Basis, ResidualVectorsAdded)> {
    let i = problem.partition.i.clone();
    let f_i = Mat::from_fn(i.len(), loads.count(), |r, c| loads.matrix[(i[r], c)]);
    let x = problem.static_response(f_i.as_ref())?;
    let m_ii = problem.interior_mass();
    // The interior columns, M_ii-orthonormalised once (Cholesky of their Gram matrix).
    let phi = interior_rows(problem, &basis, &interior_columns(problem, &basis));
    let q = m_orthonormal(m_ii, phi)?;
    let mq = mass_times(m_ii, q.as_ref());
    let mut kept_vectors: Vec<Vec<f64>> = Vec::new();
    let mut kept_mass: Vec<Vec<f64>> = Vec::new();
    let mut added = ResidualVectorsAdded {
        kept: Vec::new(),
        dropped: Vec::new(),
    };
    for (k, &case) in loads.cases.iter().enumerate() {
        let mut v: Vec<f64> = (0..x.nrows()).map(|r| x[(r, k)]).collect();
        let start = m_norm(m_ii, &v);
        if start.is_nan() || start <= 0.0 {
            added.dropped.push(case);
            continue;
        }
        for _ in 0..2 {
            for c in 0..q.ncols() {
                let a: f64 = (0..v.len()).map(|r| mq[(r, c)] * v[r]).sum();
                (0..v.len()).for_each(|r| v[r] -= a * q[(r, c)]);
            }
            for (w, mw) in kept_vectors.iter().zip(&kept_mass) {
                let a: f64 = mw.iter().zip(&v).map(|(p, q)| p * q).sum();
                v.iter_mut().zip(w).for_each(|(v, w)| *v -= a * w);
            }
        }
        let left = m_norm(m_ii, &v);
        if left.is_nan() || left <= RESIDUAL_VECTOR_DEFLATION * start {
            added.dropped.push(case);
            continue;
        }
        v.iter_mut().for_each(|x| *x /= left);
        let mv = mass_times(m_ii, MatRef::from_column_major_slice(&v, v.len(), 1));
        kept_mass.push((0..v.len()).map(|r| mv[(r, 0)]).collect());
        kept_vectors.push(v);
        added.kept.push(case);
    }
    let (n, old) = (basis.psi.nrows(), basis.size());
    let mut psi = Mat::<f64>::zeros(n, old + kept_vectors.len());
    psi.subcols_mut(0, old).copy_from(basis.psi.as_ref());
    for (c, v) in kept_vectors.iter().enumerate() {
        for (r, &d) in i.iter().enumerate() {
            psi[(d, old + c)] = v[r];
        }
    }
    basis.psi = psi;
    basis.columns.extend(added.kept.iter().map(|&load| Column {
        kind: ColumnKind::InertiaResidual { load },
        dof: None,
        label: format!("residual vector {load}"),
    }));
    Ok((basis, added))
}

/// The share of the static response to `load` (a vector on the body's DOF) that the interior
/// columns of `basis` miss in the energy norm (the module's $\epsilon$): 1 for a basis with
/// no interior column, 0 for a load that puts nothing on the interior.
pub fn static_share_outside(
    problem: &mut InteriorProblem,
    basis: &Basis,
    load: &[f64],
) -> Result<f64> {
    let i = problem.partition.i.clone();
    let f = Mat::from_fn(i.len(), 1, |r, _| load[i[r]]);
    let u = problem.static_response(f.as_ref())?;
    let energy: f64 = (0..u.nrows()).map(|r| u[(r, 0)] * f[(r, 0)]).sum();
    if energy.is_nan() || energy <= 0.0 {
        return Ok(0.0);
    }
    let cols = interior_columns(problem, basis);
    if cols.is_empty() {
        return Ok(1.0);
    }
    let phi = interior_rows(problem, basis, &cols);
    let k = problem.interior_stiffness();
    let kphi = k.mul(phi.as_ref());
    let reduced: Mat<f64> = phi.transpose() * &kphi;
    let rhs: Mat<f64> = phi.transpose() * &f;
    let Some(z) = spd_solve(reduced.as_ref(), rhs.as_ref()) else {
        return Ok(f64::NAN);
    };
    let e: Mat<f64> = &u - &phi * &z;
    let ke = k.mul(e.as_ref());
    let missed: f64 = (0..e.nrows()).map(|r| e[(r, 0)] * ke[(r, 0)]).sum();
    Ok((missed.max(0.0) / energy).sqrt().min(1.0))
}

fn m_norm(m: &MassMatrix, v: &[f64]) -> f64 {
    let mv = m.mul(MatRef::from_column_major_slice(v, v.len(), 1));
    v.iter()
        .enumerate()
        .map(|(r, x)| x * mv[(r, 0)])
        .sum::<f64>()
        .max(0.0)
        .sqrt()
}

/// $\Phi L^{-T}$ with $LL^T = \Phi^T M\Phi$: the same span, $M$-orthonormal (`phi` with no
/// column: itself).
fn m_orthonormal(m: &MassMatrix, phi: Mat<f64>) -> Result<Mat<f64>> {
    if phi.ncols() == 0 {
        return Ok(phi);
    }
    let mphi = m.mul(phi.as_ref());
    let gram: Mat<f64> = phi.transpose() * &mphi;
    let k = gram.ncols();
    let g = Mat::from_fn(k, k, |a, b| 0.5 * (gram[(a, b)] + gram[(b, a)]));
    let llt = g
        .llt(faer::Side::Lower)
        .map_err(|_| crate::error::LinalgError::SingularMatrix {
            matrix: "mass Gram matrix of a basis' interior columns".into(),
            rcond: None,
        })?;
    // Φ L^{-T}: solve L Y^T = Φ^T.
    let l = llt.L();
    let mut yt = phi.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, yt.as_mut(), faer::Par::Seq);
    Ok(yt.transpose().to_owned())
}

/// $A^{-1}b$ for a small symmetric positive definite $A$, `None` when it is not.
fn spd_solve(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Option<Mat<f64>> {
    let n = a.ncols();
    let s = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let llt = s.llt(faer::Side::Lower).ok()?;
    Some(faer::linalg::solvers::Solve::solve(&llt, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        fem::{SlabParameters, slab},
        reduction::{Method, ModeSelection, SolverPath, reduce_interior},
    };

    /// On the App. B slab clamped at its four bottom corners, Craig–Bampton with two modes
    /// misses a large share of the centrifugal and gravity responses; with the residual
    /// vectors it misses none of any of the twelve loads (to round-off), the added columns are
    /// zero on the boundary and $M$-orthonormal to each other and to the normal modes. On a
    /// denser slab (sparse path) the same holds.
    #[test]
    fn residual_vectors_hold_every_inertia_load_and_leave_the_boundary_still() {
        for (bricks, tol) in [([4, 2, 1], 1e-6), ([8, 4, 2], 1e-6)] {
            let parameters = SlabParameters::refined(bricks).unwrap();
            let model = slab(&parameters);
            let corners = parameters.bottom_corners();
            let mut problem = InteriorProblem::new(&model, &corners, SolverPath::Auto).unwrap();
            let cb = reduce_interior(
                &mut problem,
                &crate::reduction::ReductionRequest::of(Method::CraigBampton)
                    .modes(ModeSelection::Count(2)),
            )
            .unwrap();
            let loads = InertiaLoads::of(&model);
            let before: Vec<f64> = (0..loads.count())
                .map(|k| {
                    let f: Vec<f64> = (0..model.dof_count())
                        .map(|i| loads.matrix[(i, k)])
                        .collect();
                    static_share_outside(&mut problem, &cb, &f).unwrap()
                })
                .collect();
            assert!(
                before.iter().cloned().fold(0.0, f64::max) > 0.1,
                "{before:?}"
            );
            let old = cb.size();
            let (rv, added) = with_inertia_residual_vectors(&mut problem, cb, &loads).unwrap();
            assert_eq!(added.kept.len() + added.dropped.len(), 12);
            assert_eq!(rv.size(), old + added.kept.len());
            assert!(added.kept.len() >= 9, "{added:?}");
            for (k, share) in before.iter().enumerate() {
                let f: Vec<f64> = (0..model.dof_count())
                    .map(|i| loads.matrix[(i, k)])
                    .collect();
                let after = static_share_outside(&mut problem, &rv, &f).unwrap();
                assert!(after <= tol, "load {k}: {after:e} (before {share:e})");
            }
            let b = problem.partition.b.clone();
            for j in old..rv.size() {
                assert!(b.iter().all(|&d| rv.psi[(d, j)] == 0.0));
            }
            // Mass-orthonormal among the interior columns.
            let interior: Vec<usize> = (0..rv.size())
                .filter(|&j| b.iter().all(|&d| rv.psi[(d, j)] == 0.0))
                .collect();
            let cols = Mat::from_fn(model.dof_count(), interior.len(), |r, c| {
                rv.psi[(r, interior[c])]
            });
            let g: Mat<f64> = cols.transpose() * model.m.mul(cols.as_ref());
            for a in 0..g.nrows() {
                for c in 0..g.ncols() {
                    let want = if a == c { 1.0 } else { 0.0 };
                    assert!((g[(a, c)] - want).abs() <= 1e-10, "{a} {c} {}", g[(a, c)]);
                }
            }
        }
    }
}
