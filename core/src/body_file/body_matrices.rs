//! A body handed over in memory (Python's `flexmodes.Body`): stiffness and mass as entries,
//! optional node coordinates, node sets and interfaces, checked exactly as a body file is.

use crate::error::{BodySpecProblem, SizeExpectation};
use std::collections::BTreeMap;

use super::{
    BodyFileError, BodyLocation, ImportedBody, InterfaceSpec, MatrixMarket, MatrixMarketFormat,
    Units,
    imported_body::{SetsAndInterfaces, checked_sets, dof_map},
    matrix_checks::{
        check_mass, check_size_held, mass_matrix, rigid_motions_are_null_space, symmetric_matrix,
    },
    spec_matrices::{SpecText, check_node_count},
};
use crate::{
    Error, Result,
    fem::{FeModel, NodeIndex, RigidMotions},
};

/// A sparse matrix as entries: `rows × cols`, `(row, col, value)` 0-based, duplicates summed.
/// A square matrix whose off-diagonal entries all lie in one triangle is read as that
/// triangle of a symmetric matrix; otherwise it must be symmetric (to
/// [`super::SYMMETRY_TOLERANCE`] of its largest entry). A mass may also be a vector
/// (`n × 1` or `1 × n`): lumped.
#[derive(Debug, Clone, PartialEq)]
pub struct MatrixEntries {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// `(row, col, value)`, 0-based.
    pub entries: Vec<(usize, usize, f64)>,
}

/// What [`ImportedBody::from_matrices`] takes.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyMatrices {
    /// The body's name, used in messages.
    pub name: String,
    /// The stiffness, node-major (node 1's DOF, then node 2's, ...), in the force and length
    /// units of [`Self::units`].
    pub stiffness: MatrixEntries,
    /// The mass, same ordering, in the mass unit.
    pub mass: MatrixEntries,
    /// DOF per node, of x, y, z, rx, ry, rz (default: x, y, z).
    pub dofs: Vec<String>,
    /// Node coordinates in the length unit (`None`: unknown; drawing and rigid-body motions
    /// need them).
    pub nodes: Option<Vec<[f64; 3]>>,
    /// Named node sets, 1-based node numbers.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Rigid (RBE2) and averaging (RBE3) interfaces on the node sets.
    pub interfaces: BTreeMap<String, InterfaceSpec>,
    /// The node set used as interface unless another is named.
    pub default_interface: Option<String>,
    /// Units of the numbers.
    pub units: Units,
}

impl Default for BodyMatrices {
    fn default() -> Self {
        Self {
            name: "body".into(),
            stiffness: MatrixEntries {
                rows: 0,
                cols: 0,
                entries: Vec::new(),
            },
            mass: MatrixEntries {
                rows: 0,
                cols: 0,
                entries: Vec::new(),
            },
            dofs: ["x", "y", "z"].map(String::from).to_vec(),
            nodes: None,
            node_sets: BTreeMap::new(),
            interfaces: BTreeMap::new(),
            default_interface: None,
            units: Units::default(),
        }
    }
}

impl MatrixEntries {
    /// The first entry that is not finite, or lies outside the matrix.
    fn check(&self, path: &str) -> Result<()> {
        for (k, &(i, j, v)) in self.entries.iter().enumerate() {
            if i >= self.rows || j >= self.cols {
                return Err(Error::BodyFile(BodyFileError::MatrixIndexOutOfRange {
                    path: path.into(),
                    line: k + 1,
                    row: i + 1,
                    col: j + 1,
                    rows: self.rows,
                    cols: self.cols,
                }));
            }
            if !v.is_finite() {
                return Err(Error::BodyFile(BodyFileError::NonFiniteEntry {
                    path: path.into(),
                    line: k + 1,
                    value: v.to_string().into(),
                }));
            }
        }
        Ok(())
    }

    /// As a Matrix Market file would give it: one triangle of a symmetric matrix when every
    /// off-diagonal entry lies on one side.
    fn into_matrix_market(self) -> MatrixMarket {
        let square = self.rows == self.cols;
        let lower = self.entries.iter().all(|&(i, j, _)| i >= j);
        let upper = self.entries.iter().all(|&(i, j, _)| i <= j);
        let symmetric = square && (lower || upper);
        MatrixMarket {
            rows: self.rows,
            cols: self.cols,
            format: MatrixMarketFormat::Coordinate,
            symmetric,
            entries: self.entries,
        }
    }
}

impl ImportedBody {
    /// A body from matrices in memory, checked as [`ImportedBody::load`] checks a body
    /// file: square symmetric stiffness, positive (semi-)definite mass located at a DOF,
    /// nodes that divide the DOF, node sets within the nodes, interfaces on defined sets, and
    /// the rigid motions found in the stiffness's null space when coordinates are given. An
    /// error names the matrix (`K of NAME`, `M of NAME`) and, for an entry, its position in
    /// the entry list as the line.
    pub fn from_matrices(body: BodyMatrices) -> Result<Self> {
        let k_name = format!("K of {}", body.name);
        let m_name = format!("M of {}", body.name);
        let body_error = |problem| {
            Error::BodyFile(BodyFileError::BodyFile {
                path: format!("<{} in memory>", body.name).into(),
                line: None,
                problem,
            })
        };
        let dofs = dof_map(&body.dofs).map_err(body_error)?;
        let per = dofs.per_node();
        body.stiffness.check(&k_name)?;
        body.mass.check(&m_name)?;
        let n = body.stiffness.rows;
        if body.stiffness.cols != n || n == 0 {
            return Err(Error::BodyFile(BodyFileError::MatrixSizeMismatch {
                path: k_name.into(),
                what: "stiffness",
                rows: n,
                cols: body.stiffness.cols,
                expected: SizeExpectation::Square,
            }));
        }
        check_size_held(&k_name, n, &m_name, body.mass.entries.len())?;
        let node_count = match &body.nodes {
            Some(nodes) => nodes.len(),
            None => n / per,
        };
        check_node_count(&k_name, n, node_count, &body.dofs)?;
        if let Some((node, xyz)) = body
            .nodes
            .iter()
            .flatten()
            .enumerate()
            .find(|(_, xyz)| xyz.iter().any(|x| !x.is_finite()))
        {
            return Err(body_error(BodySpecProblem::NonFiniteCoordinates {
                node: NodeIndex(node).number(),
                xyz: *xyz,
            }));
        }
        let interfaces = checked_sets(
            &SetsAndInterfaces {
                node_sets: &body.node_sets,
                interfaces: &body.interfaces,
                default_interface: body.default_interface.as_deref(),
            },
            node_count,
            &SpecText {
                name: &format!("<{} in memory>", body.name),
                text: "",
            },
        )?;
        let node_major = |i: usize| i;
        let k = symmetric_matrix(
            &body.stiffness.into_matrix_market(),
            &k_name,
            "stiffness",
            &node_major,
        )?;
        let m = mass_matrix(&body.mass.into_matrix_market(), &m_name, n, &node_major)?;
        let has_coordinates = body.nodes.is_some();
        let mut model = FeModel {
            name: body.name.clone(),
            dofs,
            nodes: body.nodes.unwrap_or_else(|| vec![[0.0; 3]; node_count]),
            edges: Vec::new(),
            k,
            m,
            rigid_motions: RigidMotions::Unknown,
        };
        check_mass(&model, &m_name)?;
        if has_coordinates && rigid_motions_are_null_space(&model) {
            model.rigid_motions = RigidMotions::FromGeometry;
        }
        Ok(Self {
            model,
            node_sets: body.node_sets,
            interfaces,
            has_coordinates,
            units: body.units,
            description: format!("{} (in memory)", body.name),
            default_interface: body.default_interface,
            location: BodyLocation::Memory(body.name),
            preload: None,
        })
    }
}
