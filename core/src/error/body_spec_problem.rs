//! What is wrong in a body file (TOML) or a body given in memory
//! ([`super::BodyFileError::BodyFile`], which names the file and, where it can, the line).

/// What is wrong in a body's description, with its data.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum BodySpecProblem {
    /// A body file that is not UTF-8 text from byte `byte` on.
    #[error("not UTF-8 text (byte {byte})")]
    NotUtf8 { byte: usize },
    /// A body file that does not parse as TOML or as a body: the TOML reader's message.
    #[error("{message}")]
    Toml { message: String },
    /// `dofs` lists nothing.
    #[error("`dofs` lists no DOF")]
    NoDofs,
    /// A DOF name that is not x, y, z, rx, ry or rz.
    #[error("unknown DOF `{dof}` (known: x, y, z, rx, ry, rz)")]
    UnknownDof { dof: super::Excerpt },
    /// A DOF listed twice in `dofs`.
    #[error("DOF `{dof}` is listed twice")]
    DofListedTwice { dof: &'static str },
    /// A body in memory asked for a file of its own.
    #[error("a body in memory names no file (asked for `{}`)", asked.as_deref().unwrap_or("its body file"))]
    NoFileInMemory { asked: Option<super::Name> },
    /// A built-in body without the file asked for.
    #[error("no embedded file `{asset}` (built-in bodies: {})", builtin.join(", "))]
    NoEmbeddedFile {
        asset: super::Name,
        builtin: Vec<&'static str>,
    },
    /// A node whose coordinates are NaN or infinite (1-based).
    #[error("node {node} has the coordinates {xyz:?}, which are not finite")]
    NonFiniteCoordinates { node: usize, xyz: [f64; 3] },
    /// `default_interface` names a set `[node_sets]` does not define.
    #[error("`default_interface` names the node set `{set}`, which [node_sets] does not define")]
    DefaultInterfaceUndefined { set: super::Name },
    /// An interface whose node set `[node_sets]` does not define.
    #[error(
        "interface `{interface}` names the node set `{set}`, which [node_sets] does not define"
    )]
    InterfaceSetUndefined {
        interface: super::Name,
        set: super::Name,
    },
    /// Weights on a rigid (RBE2) interface.
    #[error("interface `{interface}`: weights belong to kind \"rbe3\" only")]
    WeightsOnRbe2 { interface: super::Name },
    /// RBE3 weights that are not one positive number per node of the set.
    #[error(
        "interface `{interface}`: {given} weights for the {nodes} nodes of `{set}`; each must be \
         positive"
    )]
    Weights {
        interface: super::Name,
        given: usize,
        nodes: usize,
        set: super::Name,
    },
    /// `stiffness_matrix`/`mass_matrix` with a format that has no named matrices.
    #[error(
        "stiffness_matrix and mass_matrix name DMIG or OP4 matrices: they need format = \
         \"nastran-dmig\" or \"op4\""
    )]
    MatrixNamesNeedFormat,
    /// CalculiX matrices without their `.dof` file.
    #[error(
        "format = \"calculix\" needs dof_map = \"job.dof\" (the equations' nodes and DOF, \
         written beside job.sti and job.mas)"
    )]
    CalculixNeedsDofMap,
    /// A `dof_order` other than node-major beside a DOF map.
    #[error("with a dof_map the map says where each equation goes: leave dof_order node-major")]
    DofOrderWithMap,
    /// A `[preload]` on a body whose nodes do not carry x, y, z alone.
    #[error("a [preload] needs a solid body (dofs = [\"x\", \"y\", \"z\"])")]
    PreloadNeedsSolid,
}
