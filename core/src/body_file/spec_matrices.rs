//! The steps of reading a body file's matrices and nodes: the stiffness and mass files in
//! their format, the nodes (a coordinate table or a count), and where a DOF map places the
//! FE code's equations.

use super::{
    BodyFileError, BodySpec, DofOrder, MatrixFormat,
    abaqus_matrix::parse_abaqus_matrix,
    body_location::BodyLocation,
    calculix_matrix::{calculix_equation_count, parse_calculix_dof_map, parse_calculix_matrix},
    csv_table::read_table,
    dof_map_file::parse_dof_map,
    harwell_boeing::parse_harwell_boeing,
    matrix_checks::check_size_held,
    matrix_market::MatrixMarket,
    nastran_dmig::parse_nastran_dmig,
    nastran_op4::parse_op4,
    parse_matrix_market,
};
use crate::error::{BodySpecProblem, SizeExpectation};
use crate::{Error, Result, error::TableProblem, fem::DofMap};

/// A body file's text and name, for errors that point at its lines.
#[derive(Clone, Copy)]
pub(super) struct SpecText<'a> {
    pub(super) name: &'a str,
    pub(super) text: &'a str,
}

impl SpecText<'_> {
    /// The body file's error at `line` (1-based).
    pub(super) fn error(&self, line: Option<usize>, problem: BodySpecProblem) -> Error {
        Error::BodyFile(BodyFileError::BodyFile {
            path: self.name.into(),
            line,
            problem,
        })
    }

    /// The 1-based line that sets `key`.
    pub(super) fn key_line(&self, key: &str) -> Option<usize> {
        self.text
            .lines()
            .position(|l| l.trim_start().starts_with(key))
            .map(|k| k + 1)
    }
}

/// The stiffness and mass files as read, with their names.
pub(super) struct SpecMatrices {
    pub(super) k_file: MatrixMarket,
    pub(super) k_name: String,
    pub(super) m_file: MatrixMarket,
    pub(super) m_name: String,
}

/// Reads the stiffness and mass files of `spec` in its format; the stiffness must be square.
pub(super) fn read_matrices(
    location: &BodyLocation,
    spec: &BodySpec,
    dofs: &DofMap,
    text: &SpecText<'_>,
) -> Result<SpecMatrices> {
    let matrices = &spec.matrices;
    if !matches!(
        matrices.format,
        MatrixFormat::NastranDmig | MatrixFormat::Op4
    ) && (matrices.stiffness_matrix.is_some() || matrices.mass_matrix.is_some())
    {
        return Err(text.error(
            text.key_line("stiffness_matrix")
                .max(text.key_line("mass_matrix")),
            BodySpecProblem::MatrixNamesNeedFormat,
        ));
    }
    // CalculiX numbers its equations by the lines of its `.dof` file.
    let calculix_equations = if matrices.format == MatrixFormat::Calculix {
        let Some(map_file) = &matrices.dof_map else {
            return Err(text.error(
                text.key_line("format"),
                BodySpecProblem::CalculixNeedsDofMap,
            ));
        };
        let (bytes, map_name) = location.read(Some(map_file))?;
        calculix_equation_count(&bytes, &map_name)?
    } else {
        0
    };
    let parse = |bytes: &[u8], name: &str, dmig: &str| match matrices.format {
        MatrixFormat::Calculix => parse_calculix_matrix(bytes, name, calculix_equations),
        MatrixFormat::MatrixMarket => parse_matrix_market(bytes, name),
        MatrixFormat::HarwellBoeing => parse_harwell_boeing(bytes, name),
        MatrixFormat::Abaqus => parse_abaqus_matrix(bytes, name, dofs),
        MatrixFormat::NastranDmig => parse_nastran_dmig(bytes, name, dmig, dofs),
        MatrixFormat::Op4 => parse_op4(bytes, name, dmig),
    };
    let read = |file: &str, dmig: &str| -> Result<(MatrixMarket, String)> {
        let (bytes, name) = location.read(Some(file))?;
        Ok((parse(&bytes, &name, dmig)?, name))
    };
    let k_dmig = matrices.stiffness_matrix.as_deref().unwrap_or("KAAX");
    let m_dmig = matrices.mass_matrix.as_deref().unwrap_or("MAAX");
    // K and M read side by side when there are threads to spare (each is decompressed and
    // parsed on one core; ~0.5 s each for a 38 k-DOF part); the stiffness's error first.
    let ((k_file, k_name), (m_file, m_name)) = if crate::linalg::threads() > 1 {
        let (k, m) = std::thread::scope(|scope| {
            let m = scope.spawn(|| read(&matrices.mass, m_dmig));
            let k = read(&matrices.stiffness, k_dmig);
            (k, m.join())
        });
        let m = m.unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (k?, m?)
    } else {
        let k = read(&matrices.stiffness, k_dmig)?;
        (k, read(&matrices.mass, m_dmig)?)
    };
    if k_file.rows != k_file.cols {
        return Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
            path: k_name.into(),
            what: "stiffness",
            rows: k_file.rows,
            cols: k_file.cols,
            expected: SizeExpectation::Square,
        }));
    }
    check_size_held(&k_name, k_file.rows, &m_name, m_file.entries.len())?;
    Ok(SpecMatrices {
        k_file,
        k_name,
        m_file,
        m_name,
    })
}

/// The nodes' coordinates (zero without a coordinate table) and their count, which must
/// account for the stiffness' DOF. `name` is the body file's.
pub(super) fn read_nodes(
    location: &BodyLocation,
    spec: &BodySpec,
    dofs: &DofMap,
    matrices: &SpecMatrices,
    name: &str,
) -> Result<(Vec<[f64; 3]>, usize)> {
    let n = matrices.k_file.rows;
    let per = dofs.per_node();
    let coordinates = match &spec.geometry.nodes {
        Some(table) => Some(read_table(location, table, "nodes", name)?),
        None => None,
    };
    let node_count = match &coordinates {
        Some((rows, _)) => rows.len(),
        None => {
            if !n.is_multiple_of(per) {
                return Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
                    path: matrices.k_name.clone().into(),
                    what: "stiffness",
                    rows: n,
                    cols: n,
                    expected: SizeExpectation::WholeNodes {
                        per,
                        body_file: name.into(),
                    },
                }));
            }
            n / per
        }
    };
    check_node_count(&matrices.k_name, n, node_count, &spec.dofs)?;
    let Some((rows, table_name)) = coordinates else {
        return Ok((vec![[0.0; 3]; node_count], node_count));
    };
    let mut out = Vec::with_capacity(rows.len());
    for (k, (line, row)) in rows.into_iter().enumerate() {
        let xyz: &[f64] = match row.len() {
            2 | 3 => &row,
            4 if row[0] == (k + 1) as f64 => &row[1..],
            4 => {
                return Err(Error::BodyFile(BodyFileError::TableLine {
                    path: table_name.into(),
                    line,
                    problem: TableProblem::NodeNumberOutOfOrder {
                        expected: k + 1,
                        found: row[0],
                    },
                }));
            }
            c => {
                return Err(Error::BodyFile(BodyFileError::TableLine {
                    path: table_name.into(),
                    line,
                    problem: TableProblem::CoordinateCount { values: c },
                }));
            }
        };
        out.push([xyz[0], xyz[1], xyz.get(2).copied().unwrap_or(0.0)]);
    }
    Ok((out, node_count))
}

/// With a DOF map, the FE code's equations moved to the body's node-major DOF in both
/// matrices (each must have as many rows as the map has equations).
pub(super) fn place_equations(
    location: &BodyLocation,
    spec: &BodySpec,
    dofs: &DofMap,
    node_count: usize,
    matrices: &mut SpecMatrices,
    text: &SpecText<'_>,
) -> Result<()> {
    let Some(map_file) = &spec.matrices.dof_map else {
        return Ok(());
    };
    if spec.dof_order != DofOrder::NodeMajor {
        return Err(text.error(text.key_line("dof_order"), BodySpecProblem::DofOrderWithMap));
    }
    let (bytes, map_name) = location.read(Some(map_file))?;
    let equations = if spec.matrices.format == MatrixFormat::Calculix {
        parse_calculix_dof_map(&bytes, &map_name, dofs, node_count)?
    } else {
        parse_dof_map(&bytes, &map_name, dofs, node_count)?
    };
    for (file, name) in [
        (&mut matrices.k_file, &matrices.k_name),
        (&mut matrices.m_file, &matrices.m_name),
    ] {
        if file.rows != equations.len() {
            return Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
                path: name.clone().into(),
                what: "matrix",
                rows: file.rows,
                cols: file.cols,
                expected: SizeExpectation::DofMapEquations {
                    map: map_name.into(),
                    equations: equations.len(),
                },
            }));
        }
        let square = file.cols == file.rows;
        for entry in &mut file.entries {
            entry.0 = equations[entry.0];
            if square {
                entry.1 = equations[entry.1];
            }
        }
    }
    Ok(())
}

/// `node_count` nodes of the DOF `dofs` names must make the stiffness' `n` DOF.
pub(super) fn check_node_count(
    k_name: &str,
    n: usize,
    node_count: usize,
    dofs: &[String],
) -> Result<()> {
    let per = dofs.len();
    if node_count * per == n {
        return Ok(());
    }
    Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
        path: k_name.into(),
        what: "stiffness",
        rows: n,
        cols: n,
        expected: SizeExpectation::NodesTimesDof {
            nodes: node_count,
            dofs: crate::error::Name::all(dofs),
        },
    }))
}
