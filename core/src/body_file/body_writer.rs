//! Writes a body in the body-file format (how the examples in `assets/bodies/` were made).

use std::{collections::BTreeMap, fmt::Write as _, io::Write, path::Path};

use crate::{Error, Result, fem::FeModel, linalg::MassMatrix};

use super::{
    InterfaceKind, InterfaceSpec, MatrixFormat, Units,
    format_writers::{abaqus_text, dmig_text},
    matrix_market::write_coordinate_symmetric_to,
};
use crate::atomic_file::write_atomically;

/// The nonzero entries of `a` on and below its diagonal, `(row, column, value)`, 0-based,
/// column by column.
pub fn lower_entries(a: &crate::linalg::SparseSymmetric) -> Vec<(usize, usize, f64)> {
    let f = a.as_faer();
    let n = f.ncols();
    let mut out = Vec::with_capacity(a.nnz() / 2 + n);
    for j in 0..n {
        let rows = f.symbolic().row_idx_of_col_raw(j);
        for (&i, &v) in rows.iter().zip(f.val_of_col(j)) {
            if i >= j && v != 0.0 {
                out.push((i, j, v));
            }
        }
    }
    out
}

/// The nonzero entries of M on and below its diagonal (a lumped M: its diagonal), as
/// [`lower_entries`].
pub fn mass_lower_entries(m: &MassMatrix) -> Vec<(usize, usize, f64)> {
    match m {
        MassMatrix::Lumped(d) => d
            .iter()
            .enumerate()
            .filter(|(_, v)| **v != 0.0)
            .map(|(i, &v)| (i, i, v))
            .collect(),
        MassMatrix::Consistent(a) => lower_entries(a),
    }
}

/// The files of a body, by name, as bytes (what [`write_body`] puts in the folder).
pub type BodyFiles = BTreeMap<String, Vec<u8>>;

/// What a body file says beside the model's matrices and nodes.
#[derive(Debug, Clone, Default)]
pub struct BodyFileParameters {
    /// Named node sets, 1-based node numbers.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// The node set or interface reductions use unless told otherwise.
    pub default_interface: Option<String>,
    /// One line shown by `flexmodes import`.
    pub description: String,
    /// The units the matrices are in.
    pub units: Units,
    /// Multipoint interfaces (`[interfaces.NAME]`).
    pub interfaces: BTreeMap<String, InterfaceSpec>,
    /// Write the matrices gzip-compressed (`.gz`).
    pub compress: bool,
    /// The matrices' format: Matrix Market (default), Abaqus matrix input or Nastran DMIG
    /// (Harwell–Boeing is read, not written).
    pub format: MatrixFormat,
}

/// The body file and its data files for `model`: `body.toml`, `k.mtx` and `m.mtx` (a vector when
/// M is lumped; both `.mtx.gz` when `compress`), `nodes.csv`, `edges.csv`. Values are
/// written in Rust's shortest round-trip form, so an import reproduces `model` exactly.
pub fn write_body(model: &FeModel, parameters: &BodyFileParameters) -> Result<BodyFiles> {
    let BodyFileParameters {
        description,
        compress,
        format,
        ..
    } = parameters;
    let compress = *compress;
    let unwritable = match format {
        MatrixFormat::Op4 => Some("OP4"),
        MatrixFormat::HarwellBoeing => Some("Harwell-Boeing"),
        MatrixFormat::Calculix => Some("CalculiX matrix storage"),
        _ => None,
    };
    if let Some(format) = unwritable {
        return Err(Error::BodyFile(super::BodyFileError::NotWritable {
            format,
        }));
    }
    let mut files = BodyFiles::new();
    let n = model.dof_count();
    let lower = lower_entries;
    let io = |source| Error::Io {
        path: "(memory)".into(),
        source,
    };
    let mut k = Vec::new();
    write_coordinate_symmetric_to(
        &mut k,
        n,
        &lower(&model.k),
        &format!("stiffness of {} ({description}), N/m", model.name),
    )
    .map_err(io)?;
    let mut store = |name: &str, bytes: Vec<u8>| -> Result<String> {
        if compress {
            let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
            gz.write_all(&bytes).map_err(io)?;
            files.insert(format!("{name}.gz"), gz.finish().map_err(io)?);
            Ok(format!("{name}.gz"))
        } else {
            files.insert(name.into(), bytes);
            Ok(name.into())
        }
    };
    let mass_entries = || mass_lower_entries(&model.m);
    let (k_name, m_name, names) = match format {
        MatrixFormat::Abaqus => {
            let k = abaqus_text(model, &lower(&model.k), "stiffness");
            let m = abaqus_text(model, &mass_entries(), "mass");
            (
                store("k.mtx", k.into_bytes())?,
                store("m.mtx", m.into_bytes())?,
                "",
            )
        }
        MatrixFormat::NastranDmig => {
            let mut cards = dmig_text(model, "KAAX", &lower(&model.k), "stiffness");
            cards.push_str(&dmig_text(model, "MAAX", &mass_entries(), "mass"));
            cards.push_str("ENDDATA\n");
            let name = store("body.pch", cards.into_bytes())?;
            (
                name.clone(),
                name,
                "stiffness_matrix = \"KAAX\"\nmass_matrix = \"MAAX\"\n",
            )
        }
        _ => {
            let k_name = store("k.mtx", k)?;
            (k_name, matrix_market_mass(model, &mut store, io)?, "")
        }
    };
    let format_line = match format {
        MatrixFormat::Abaqus => "format = \"abaqus\"\n",
        MatrixFormat::NastranDmig => "format = \"nastran-dmig\"\n",
        _ => "",
    };
    body_toml(
        model,
        parameters,
        &k_name,
        &m_name,
        &format!("{format_line}{names}"),
        files,
    )
}

/// M as Matrix Market (a vector when lumped), stored by `store`.
fn matrix_market_mass(
    model: &FeModel,
    store: &mut impl FnMut(&str, Vec<u8>) -> Result<String>,
    io: impl Fn(std::io::Error) -> Error + Copy,
) -> Result<String> {
    let n = model.dof_count();
    let mut m = Vec::new();
    match &model.m {
        MassMatrix::Lumped(d) => {
            writeln!(m, "%%MatrixMarket matrix array real general").map_err(io)?;
            writeln!(m, "% lumped mass of {}, kg, one entry per DOF", model.name).map_err(io)?;
            writeln!(m, "{n} 1").map_err(io)?;
            for v in d {
                writeln!(m, "{v:e}").map_err(io)?;
            }
        }
        MassMatrix::Consistent(a) => {
            write_coordinate_symmetric_to(
                &mut m,
                n,
                &lower_entries(a),
                &format!("consistent mass of {}, kg", model.name),
            )
            .map_err(io)?;
        }
    }
    store("m.mtx", m)
}

/// `body.toml`, `nodes.csv` and `edges.csv` added to `files` (the matrices already in).
fn body_toml(
    model: &FeModel,
    parameters: &BodyFileParameters,
    k_name: &str,
    m_name: &str,
    matrix_keys: &str,
    mut files: BodyFiles,
) -> Result<BodyFiles> {
    let BodyFileParameters {
        node_sets,
        default_interface,
        description,
        units,
        interfaces,
        ..
    } = parameters;
    let mut nodes = String::from("x,y,z\n");
    for p in &model.nodes {
        let _ = writeln!(nodes, "{:e},{:e},{:e}", p[0], p[1], p[2]);
    }
    files.insert("nodes.csv".into(), nodes.into_bytes());
    let mut edges = String::from("node_a,node_b\n");
    for e in &model.edges {
        let _ = writeln!(edges, "{},{}", e[0] + 1, e[1] + 1);
    }
    files.insert("edges.csv".into(), edges.into_bytes());

    let dofs: Vec<String> = model
        .dofs
        .node_dofs()
        .iter()
        .map(|d| format!("\"{}\"", d.name().replace('θ', "r")))
        .collect();
    let mut toml = format!(
        "# flexmodes body file (see docs/bodies.md in flexmodes)\n\
         name = \"{}\"\n\
         description = \"{}\"\n\
         dofs = [{}]\n\
         dof_order = \"node-major\"\n{}\n\
         [units]\nlength = \"{}\"\nmass = \"{}\"\nforce = \"{}\"\n\n\
         [matrices]\n{matrix_keys}stiffness = \"{k_name}\"\nmass = \"{m_name}\"\n\n\
         [geometry]\nnodes = \"nodes.csv\"\nedges = \"edges.csv\"\n\n\
         [node_sets]\n",
        model.name,
        description.replace('"', "'"),
        dofs.join(", "),
        default_interface
            .as_ref()
            .map(|s| format!("default_interface = \"{s}\"\n"))
            .unwrap_or_default(),
        units.length,
        units.mass,
        units.force,
    );
    for (set, members) in node_sets {
        let list: Vec<String> = members.iter().map(|m| m.to_string()).collect();
        let _ = writeln!(toml, "{set} = [{}]", list.join(", "));
    }
    for (name, spec) in interfaces {
        let kind = match spec.kind {
            InterfaceKind::Rbe2 => "rbe2",
            InterfaceKind::Rbe3 => "rbe3",
        };
        let _ = write!(
            toml,
            "\n[interfaces.{name}]\nkind = \"{kind}\"\nnode_set = \"{}\"\n",
            spec.node_set
        );
        if let Some(m) = spec.master {
            let _ = writeln!(toml, "master = [{:e}, {:e}, {:e}]", m[0], m[1], m[2]);
        }
        if let Some(w) = &spec.weights {
            let list: Vec<String> = w.iter().map(|x| format!("{x:e}")).collect();
            let _ = writeln!(toml, "weights = [{}]", list.join(", "));
        }
    }
    files.insert("body.toml".into(), toml.into_bytes());
    Ok(files)
}

/// Writes `files` into the folder `dir` (created if missing), each file atomically.
pub fn write_files(dir: &Path, files: &BodyFiles) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    for (name, bytes) in files {
        write_atomically(&dir.join(name), |w| w.write_all(bytes))?;
    }
    Ok(())
}

/// The example bodies of `assets/bodies/`, as [`write_body`] makes them: the App. B slab
/// (`app-b-slab`) and the L-bracket (`l-bracket`, stiffness gzip-compressed).
pub fn example_bodies() -> Result<Vec<(&'static str, BodyFiles)>> {
    let slab = crate::fem::slab(&crate::fem::SlabParameters::default());
    let slab_sets = BTreeMap::from([
        ("bottom_corners".to_string(), vec![16, 18, 28, 30]),
        ("guyan_extra".to_string(), vec![5, 11]),
        ("top_centre".to_string(), vec![8]),
    ]);
    let (bracket, bracket_sets) = crate::fem::l_bracket(&crate::fem::LBracketParameters::default());
    Ok(vec![
        (
            "app-b-slab",
            write_body(
                &slab,
                &BodyFileParameters {
                    node_sets: slab_sets,
                    default_interface: Some("bottom_corners".into()),
                    description: "Lin (2005) App. B slab: 4 x 2 x 1 m, 8 trilinear bricks, E = \
                                  0.2e6 Pa, nu = 0.33, 62.4 kg lumped"
                        .into(),
                    ..Default::default()
                },
            )?,
        ),
        (
            "l-bracket",
            write_body(
                &bracket,
                &BodyFileParameters {
                    node_sets: bracket_sets,
                    default_interface: Some("bolt_hole".into()),
                    description: "steel L-bracket, 60 x 30 x 10 mm base with a 10 x 10 mm bolt \
                                  hole, upright 40 mm above the base (50 mm overall), 5 mm \
                                  trilinear bricks, consistent mass"
                        .into(),
                    compress: true,
                    ..Default::default()
                },
            )?,
        ),
    ])
}

/// The body file and data files of an imported body as [`write_body`] writes them (node-major
/// Matrix Market, whatever format it was read from), with its units, node sets, default
/// interface and declared interfaces: what `flexmodes convert` writes. A body without node
/// coordinates is refused (its nodes would be written as if it had them).
pub fn write_imported_body(
    body: &super::ImportedBody,
    compress: bool,
    format: MatrixFormat,
) -> Result<BodyFiles> {
    body.require_coordinates()?;
    write_body(
        &body.model,
        &BodyFileParameters {
            node_sets: body.node_sets.clone(),
            default_interface: body.default_interface.clone(),
            description: body.description.clone(),
            units: body.units.clone(),
            interfaces: body.interfaces.clone(),
            compress,
            format,
        },
    )
}
