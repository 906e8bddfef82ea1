//! The body file: a TOML document naming a body's stiffness and mass (Matrix Market files),
//! its DOF map, node coordinates, wireframe and named node sets.
//!
//! ```toml
//! name = "app-b-slab"
//! description = "Lin (2005) App. B: 4 x 2 x 1 m slab, 12 bricks, lumped mass"
//! dofs = ["x", "y", "z"]        # the DOF of every node, in block order (x y z rx ry rz)
//! dof_order = "node-major"      # or "dof-major": all first DOF, then all second DOF, ...
//! default_interface = "interface"  # the node set reductions use unless told otherwise
//!
//! [units]                       # informational; frequencies are in Hz if they are coherent
//! length = "m"
//! mass = "kg"
//! force = "N"
//!
//! [matrices]
//! stiffness = "k.mtx"           # Matrix Market, coordinate or array, .gz allowed
//! mass = "m.mtx"                # a square matrix, or an n x 1 vector for a lumped mass
//! # format = "harwell-boeing"   # ANSYS HBMAT / SciPy hb_write files instead (or "abaqus")
//! # dof_map = "k.mapping"       # equations -> (node, UX..ROTZ), as ANSYS writes it
//! # format = "calculix"         # CalculiX MATRIXSTORAGE: stiffness = "job.sti",
//! #                             # mass = "job.mas", dof_map = "job.dof" (node.dof lines)
//!
//! [geometry]
//! nodes = "nodes.csv"           # x,y,z per node (or inline [[x, y, z], ...])
//! edges = [[1, 2], [2, 3]]      # optional wireframe, 1-based node pairs (or a CSV file)
//!
//! [node_sets]                   # 1-based node numbers
//! interface = [16, 18, 28, 30]
//! sensors = [8]
//! ```

use std::collections::BTreeMap;

use serde::Deserialize;

/// The whole body file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Body name, used in entity paths (lower case, no spaces recommended).
    pub name: String,
    /// One line shown by `flexmodes import`.
    #[serde(default)]
    pub description: String,
    /// The DOF of every node in block order: `x`, `y`, `z`, `rx`, `ry`, `rz`.
    pub dofs: Vec<String>,
    /// `node-major` (default) or `dof-major`.
    #[serde(default)]
    pub dof_order: DofOrder,
    /// Units the matrices are written in.
    #[serde(default)]
    pub units: Units,
    /// The stiffness and mass files.
    pub matrices: MatrixFiles,
    /// Node coordinates and wireframe.
    #[serde(default)]
    pub geometry: GeometrySpec,
    /// Named node sets (interfaces, sensors), 1-based node numbers.
    #[serde(default)]
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// The node set reductions use when no boundary is given (else `interface`, else the
    /// first set).
    #[serde(default)]
    pub default_interface: Option<String>,
    /// Multipoint interfaces: `[interfaces.NAME]` with `kind`, `node_set` and an optional
    /// `master` point; `--boundary NAME` then means the interface.
    #[serde(default)]
    pub interfaces: BTreeMap<String, InterfaceSpec>,
    /// The stiffness the FE code wrote for the body spinning (`[preload]`: CalculiX's
    /// perturbation step after a static `CENTRIF` step), for dynamic stiffening.
    #[serde(default)]
    pub preload: Option<super::PreloadSpec>,
}

/// A multipoint interface of a body file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// How the set is tied to its master node.
    pub kind: InterfaceKind,
    /// The node set (of `[node_sets]`) it ties.
    pub node_set: String,
    /// The master point in the body's length unit (default: the set's centroid).
    #[serde(default)]
    pub master: Option<[f64; 3]>,
    /// RBE3 only: one positive weight per node of the set, in its order (default: all 1).
    #[serde(default)]
    pub weights: Option<Vec<f64>>,
}

/// How an interface ties its nodes to the master node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InterfaceKind {
    /// Rigid: every node follows the master's rigid motion.
    Rbe2,
    /// Interpolating: the master moves as the nodes' weighted average; adds no stiffness.
    Rbe3,
}

/// Order of the DOF in the matrices.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DofOrder {
    /// All DOF of node 1, then node 2, ... (what most FE codes export).
    #[default]
    NodeMajor,
    /// The first DOF of every node, then the second DOF of every node, ...
    DofMajor,
}

/// Units of the body's numbers (informational: shown, not converted).
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    /// Length unit of the coordinates and translations.
    #[serde(default = "metre")]
    pub length: String,
    /// Mass unit.
    #[serde(default = "kilogram")]
    pub mass: String,
    /// Force unit.
    #[serde(default = "newton")]
    pub force: String,
}

fn metre() -> String {
    "m".into()
}
fn kilogram() -> String {
    "kg".into()
}
fn newton() -> String {
    "N".into()
}

impl Units {
    /// Metres per length unit (m, cm, mm, in, ft); another unit is an error naming it.
    pub fn metres_per_length(&self) -> crate::Result<f64> {
        Ok(match self.length.as_str() {
            "m" => 1.0,
            "cm" => 1e-2,
            "mm" => 1e-3,
            "in" => 0.0254,
            "ft" => 0.3048,
            other => {
                return Err(super::BodyFileError::UnknownLengthUnit { unit: other.into() }.into());
            }
        })
    }
}

impl Default for Units {
    fn default() -> Self {
        Self {
            length: metre(),
            mass: kilogram(),
            force: newton(),
        }
    }
}

/// The matrix files, relative to the body file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MatrixFiles {
    /// Stiffness K.
    pub stiffness: String,
    /// Mass M: square, or a vector (n × 1 or 1 × n) of a lumped mass.
    pub mass: String,
    /// The files' format: `matrix-market` (default), `harwell-boeing` (ANSYS `HBMAT`, SciPy
    /// `hb_write`), `abaqus` (`*MATRIX OUTPUT, FORMAT=MATRIX INPUT`), `calculix`
    /// (`*FREQUENCY, SOLVER=MATRIXSTORAGE`: `.sti`, `.mas` and the `.dof` map) or `nastran-dmig`
    /// (DMIG cards; the matrices by name, [`Self::stiffness_matrix`] and [`Self::mass_matrix`]).
    #[serde(default)]
    pub format: MatrixFormat,
    /// A DOF map (ANSYS `HBMAT`'s `.mapping`: lines `equation node DOF`, DOF `UX UY UZ ROTX
    /// ROTY ROTZ`): the matrices' equations in the FE code's own order, placed on the body's
    /// nodes and DOF.
    #[serde(default)]
    pub dof_map: Option<String>,
    /// With `nastran-dmig` or `op4`: the stiffness matrix's name in the file (default `KAAX`,
    /// the name `EXTSEOUT(DMIGPCH)` punches).
    #[serde(default)]
    pub stiffness_matrix: Option<String>,
    /// With `nastran-dmig` or `op4`: the mass matrix's name (default `MAAX`).
    #[serde(default)]
    pub mass_matrix: Option<String>,
}

/// The format of the matrix files.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MatrixFormat {
    /// NIST Matrix Market (`.mtx`, optionally gzip).
    #[default]
    MatrixMarket,
    /// Harwell–Boeing, real assembled (`RSA`, `RUA`; optionally gzip).
    HarwellBoeing,
    /// Abaqus matrix output (`FORMAT=MATRIX INPUT`: node, DOF, node, DOF, value per line).
    Abaqus,
    /// Nastran DMIG cards in a bulk-data or punch file (grid, component per entry).
    NastranDmig,
    /// Nastran OUTPUT4 (binary or ASCII; the matrices by name, placed by `dof_map`).
    Op4,
    /// CalculiX's matrix storage (`*FREQUENCY, SOLVER=MATRIXSTORAGE`): `job.sti` and
    /// `job.mas` (`row column value`, upper triangle), placed by `dof_map = "job.dof"`.
    Calculix,
}

impl MatrixFormat {
    /// The ids a body file's `format` and `convert --format` take.
    pub const IDS: [&'static str; 4] =
        ["matrix-market", "harwell-boeing", "abaqus", "nastran-dmig"];
}

impl std::str::FromStr for MatrixFormat {
    type Err = crate::error::UnknownId;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "matrix-market" => Ok(Self::MatrixMarket),
            "harwell-boeing" => Ok(Self::HarwellBoeing),
            "abaqus" => Ok(Self::Abaqus),
            "nastran-dmig" => Ok(Self::NastranDmig),
            "op4" => Ok(Self::Op4),
            "calculix" => Ok(Self::Calculix),
            other => Err(crate::error::UnknownId::new(
                "matrix format",
                other,
                &Self::IDS,
            )),
        }
    }
}

/// Node coordinates and wireframe, each inline or as a CSV file.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySpec {
    /// Node coordinates: a CSV file (`x,y[,z]` per line, optionally a leading node number) or
    /// inline `[[x, y, z], ...]`.
    pub nodes: Option<TableOrFile<f64>>,
    /// Wireframe edges as 1-based node pairs, or faces as 1-based node cycles: a CSV file or
    /// inline lists.
    pub edges: Option<TableOrFile<usize>>,
}

/// Rows of numbers given inline or as a CSV file.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum TableOrFile<T> {
    /// A file name relative to the body file.
    File(String),
    /// Inline rows.
    Inline(Vec<Vec<T>>),
}
