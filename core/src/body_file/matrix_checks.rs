//! The stiffness and mass of a body file made usable and checked: symmetric storage from a
//! `symmetric` or `general` file, a lumped or consistent mass, positive definiteness located at
//! a DOF, and the rigid motions found in the stiffness's null space.

use super::{BodyFileError, MatrixMarket, SYMMETRY_TOLERANCE};
use crate::error::{MassDefect, SizeExpectation};
use crate::linalg::LinalgError;
use crate::{
    Error, Result,
    fem::FeModel,
    linalg::{MassMatrix, SparseSymmetric, SymbolicFactor, SymmetricFactor},
};

/// Every DOF needs a positive mass, so the mass holds at least one entry per DOF: a stiffness
/// size `n` beyond the mass's `mass_entries` is refused before anything is sized by it (a
/// header or a Python shape of 10¹² DOF with a few entries).
pub(super) fn check_size_held(
    k_name: &str,
    n: usize,
    m_name: &str,
    mass_entries: usize,
) -> Result<()> {
    if n <= mass_entries {
        return Ok(());
    }
    Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
        path: k_name.into(),
        what: "stiffness",
        rows: n,
        cols: n,
        expected: SizeExpectation::MassEntries {
            mass: m_name.into(),
            entries: mass_entries,
        },
    }))
}

/// A symmetric matrix from a file: a `symmetric` file mirrored, a `general` one checked for
/// symmetry (largest defect reported) and symmetrised.
pub(super) fn symmetric_matrix(
    file: &MatrixMarket,
    name: &str,
    what: &'static str,
    to_node_major: &dyn Fn(usize) -> usize,
) -> Result<SparseSymmetric> {
    let n = file.rows;
    let mut entries = Vec::with_capacity(2 * file.entries.len());
    if file.symmetric {
        for &(i, j, v) in &file.entries {
            let (i, j) = (to_node_major(i), to_node_major(j));
            entries.push((i, j, v));
            if i != j {
                entries.push((j, i, v));
            }
        }
        return Ok(SparseSymmetric::from_triplets(n, &entries));
    }
    let stored = SparseSymmetric::from_triplets(n, &file.entries);
    let scale = stored.max_abs();
    let mut worst = (0.0f64, 0, 0);
    let a = stored.as_faer();
    for j in 0..n {
        let rows = a.symbolic().row_idx_of_col_raw(j);
        for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
            let d = (v - stored.get(j, i)).abs();
            if d > worst.0 {
                worst = (d, i, j);
            }
        }
    }
    if scale > 0.0 && worst.0 > SYMMETRY_TOLERANCE * scale {
        return Err(Error::BodyFile(BodyFileError::NotSymmetric {
            path: name.into(),
            what,
            row: worst.1 + 1,
            col: worst.2 + 1,
            asymmetry: worst.0 / scale,
            tolerance: SYMMETRY_TOLERANCE,
        }));
    }
    for &(i, j, v) in &file.entries {
        let (i, j) = (to_node_major(i), to_node_major(j));
        entries.push((i, j, 0.5 * v));
        entries.push((j, i, 0.5 * v));
    }
    Ok(SparseSymmetric::from_triplets(n, &entries))
}

/// The mass: a vector (n × 1 or 1 × n) or a diagonal square matrix becomes lumped, anything
/// else a consistent sparse matrix.
pub(super) fn mass_matrix(
    file: &MatrixMarket,
    name: &str,
    n: usize,
    to_node_major: &dyn Fn(usize) -> usize,
) -> Result<MassMatrix> {
    let vector = (file.rows == n && file.cols == 1) || (file.rows == 1 && file.cols == n);
    if vector {
        let mut d = vec![0.0; n];
        for &(i, j, v) in &file.entries {
            d[to_node_major(i.max(j))] += v;
        }
        return Ok(MassMatrix::Lumped(d));
    }
    if file.rows != n || file.cols != n {
        return Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
            path: name.into(),
            what: "mass",
            rows: file.rows,
            cols: file.cols,
            expected: SizeExpectation::LikeStiffness { n },
        }));
    }
    if file.entries.iter().all(|&(i, j, _)| i == j) {
        let mut d = vec![0.0; n];
        for &(i, _, v) in &file.entries {
            d[to_node_major(i)] += v;
        }
        return Ok(MassMatrix::Lumped(d));
    }
    Ok(MassMatrix::Consistent(symmetric_matrix(
        file,
        name,
        "mass",
        to_node_major,
    )?))
}

/// Relative part of its diagonal within which a consistent mass may be singular (positive
/// semi-definite up to round-off).
pub(super) const SEMI_DEFINITE_MASS: f64 = 1e-10;

/// M must be positive definite, or semi-definite to round-off ([`SEMI_DEFINITE_MASS`]):
/// every lumped entry positive, every diagonal entry positive, a consistent M factorisable.
pub(super) fn check_mass(model: &FeModel, name: &str) -> Result<()> {
    let fail = |dof: usize, defect| {
        Error::BodyFile(BodyFileError::MassNotPositive {
            path: name.into(),
            dof: dof + 1,
            node: model.dof_node(dof).0.number(),
            component: model.dof_node(dof).1.name(),
            defect,
        })
    };
    match &model.m {
        MassMatrix::Lumped(d) => {
            if let Some((dof, v)) = d.iter().enumerate().find(|(_, v)| **v <= 0.0) {
                return Err(fail(dof, MassDefect::Lumped { value: *v }));
            }
        }
        MassMatrix::Consistent(m) => {
            if let Some((dof, v)) = m
                .diagonal()
                .into_iter()
                .enumerate()
                .find(|(_, v)| *v <= 0.0)
            {
                return Err(fail(dof, MassDefect::Diagonal { value: v }));
            }
            let symbolic = SymbolicFactor::analyse(m.as_faer())?;
            if let Err(LinalgError::NonPositivePivot { index, .. }) =
                SymmetricFactor::sparse(m.as_faer(), &symbolic, "mass")
            {
                // A consistent mass integrated with too few points is singular but positive
                // semi-definite (CalculiX's C3D10: one null vector per direction for a whole
                // mesh): M + τ diag(M) is then positive definite for a τ at round-off. The
                // free-free solver needs only K - σM positive definite, which its own
                // factorisation checks.
                let regularised = m.shifted(&MassMatrix::Lumped(m.diagonal()), -SEMI_DEFINITE_MASS);
                if SymmetricFactor::sparse(regularised.as_faer(), &symbolic, "mass").is_err() {
                    return Err(fail(
                        index,
                        MassDefect::Pivot {
                            regularisation: SEMI_DEFINITE_MASS,
                        },
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Whether the rigid motions built from the coordinates are K's null space to round-off:
/// $\max|KR| \le 10^{-9}\,\max|K|\,\max|R|$. True for a free body exported with full
/// precision; false for one restrained before export.
pub(super) fn rigid_motions_are_null_space(model: &FeModel) -> bool {
    model.rigid_motion_defect() <= 1e-9
}
