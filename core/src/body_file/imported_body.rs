//! A body read from a body file: its [`FeModel`], named node sets and units, checked.

use super::BodyFileError;
use crate::error::BodySpecProblem;
use std::{collections::BTreeMap, sync::Arc};

use super::{
    BodyLocation, BodySpec, DofOrder, InterfaceKind, InterfaceSpec, Preload, Units,
    csv_table::edges,
    matrix_checks::{check_mass, mass_matrix, rigid_motions_are_null_space, symmetric_matrix},
    spec_matrices::{SpecText, place_equations, read_matrices, read_nodes},
};
use crate::{
    Error, Result,
    fem::{Direction, DofMap, FeModel, NodeDof, RigidMotions},
};

/// A node set tied rigidly to a master node, as a boundary names it.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSet {
    /// The interface's name (the set's, or the body file's interface's).
    pub name: String,
    /// The tied nodes, 1-based.
    pub nodes: Vec<usize>,
    /// The master point the body file gives (`None`: the set's centroid).
    pub master: Option<[f64; 3]>,
    /// Rigid (RBE2: its nodes join the boundary) or averaging (RBE3: they stay free).
    pub kind: InterfaceKind,
    /// RBE3 weights, one per node (`None`: all 1).
    pub weights: Option<Vec<f64>>,
}

/// Largest accepted $|a_{ij} - a_{ji}|$ relative to the largest entry of K or M: exporters
/// that print 7 significant digits stay below it, a wrong matrix does not.
pub const SYMMETRY_TOLERANCE: f64 = 1e-6;

/// A body from a body file: the model every reduction takes, plus what the file names.
#[derive(Debug, Clone)]
pub struct ImportedBody {
    /// The body (node-major DOF, sparse K, lumped or consistent M). Without coordinates its
    /// nodes all sit at the origin and [`Self::has_coordinates`] is false.
    pub model: FeModel,
    /// Named node sets, 1-based node numbers.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Whether the file gave node coordinates (drawing and rigid-body motions need them).
    pub has_coordinates: bool,
    /// Units of the numbers.
    pub units: Units,
    /// The description line of the file.
    pub description: String,
    /// The node set used as interface unless another is given.
    pub default_interface: Option<String>,
    /// Rigid interfaces declared in the body file: name, node set, master point (`None`: the
    /// set's centroid).
    pub interfaces: BTreeMap<String, InterfaceSpec>,
    /// Where it came from.
    pub location: BodyLocation,
    /// The geometric stiffness of a centrifugal load, from the FE code's preloaded stiffness
    /// (`[preload]`), if the file gives one.
    pub preload: Option<Preload>,
}

/// A shared imported body, compared by identity (scene options carry it).
#[derive(Debug, Clone)]
pub struct BodyHandle(pub Arc<ImportedBody>);

impl PartialEq for BodyHandle {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl std::ops::Deref for BodyHandle {
    type Target = ImportedBody;
    fn deref(&self) -> &ImportedBody {
        &self.0
    }
}

fn node_dof(name: &str) -> Option<NodeDof> {
    Some(match name.to_ascii_lowercase().as_str() {
        "x" | "ux" => NodeDof::Translation(Direction::X),
        "y" | "uy" => NodeDof::Translation(Direction::Y),
        "z" | "uz" => NodeDof::Translation(Direction::Z),
        "rx" | "θx" => NodeDof::Rotation(Direction::X),
        "ry" | "θy" => NodeDof::Rotation(Direction::Y),
        "rz" | "θz" => NodeDof::Rotation(Direction::Z),
        _ => return None,
    })
}

/// 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// A body file's bytes as text; bytes that are not UTF-8 are named by their first offset.
fn utf8_text(bytes: Vec<u8>, name: &str) -> Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        SpecText { name, text: "" }.error(
            None,
            BodySpecProblem::NotUtf8 {
                byte: e.utf8_error().valid_up_to(),
            },
        )
    })
}

impl ImportedBody {
    /// The interface used when none is named: the node set the file names
    /// `default_interface`, else its set `interface`, else its first set (1-based node
    /// numbers).
    pub fn default_interface_nodes(&self) -> Result<&[usize]> {
        self.default_interface
            .iter()
            .map(String::as_str)
            .chain(["interface"])
            .find_map(|name| self.node_sets.get(name))
            .or_else(|| self.node_sets.values().next())
            .map(Vec::as_slice)
            .ok_or_else(|| {
                Error::BodyFile(BodyFileError::NoNodeSets {
                    body: (&self.model.name).into(),
                })
            })
    }

    /// Reads and checks a body file: `builtin:NAME` or a path.
    pub fn load(location: &str) -> Result<Self> {
        Self::load_from(BodyLocation::parse(location))
    }

    /// Reads and checks the body file at `location`.
    pub fn load_from(location: BodyLocation) -> Result<Self> {
        let (bytes, name) = location.read(None)?;
        let text = utf8_text(bytes, &name)?;
        let spec_text = SpecText {
            name: &name,
            text: &text,
        };
        let spec: BodySpec = toml::from_str(&text).map_err(|e| {
            let line = e.span().map(|s| line_of(&text, s.start));
            spec_text.error(
                line,
                BodySpecProblem::Toml {
                    message: e.message().trim().to_string(),
                },
            )
        })?;
        let dofs = dof_map(&spec.dofs)
            .map_err(|problem| spec_text.error(spec_text.key_line("dofs"), problem))?;
        let mut matrices = read_matrices(&location, &spec, &dofs, &spec_text)?;
        let (nodes, node_count) = read_nodes(&location, &spec, &dofs, &matrices, &name)?;
        place_equations(
            &location,
            &spec,
            &dofs,
            node_count,
            &mut matrices,
            &spec_text,
        )?;
        let per = dofs.per_node();
        let to_node_major = |i: usize| match spec.dof_order {
            DofOrder::NodeMajor => i,
            DofOrder::DofMajor => (i % node_count) * per + i / node_count,
        };
        let k = symmetric_matrix(
            &matrices.k_file,
            &matrices.k_name,
            "stiffness",
            &to_node_major,
        )?;
        let m_name = &matrices.m_name;
        let m = mass_matrix(
            &matrices.m_file,
            m_name,
            matrices.k_file.rows,
            &to_node_major,
        )?;

        let edges = match &spec.geometry.edges {
            None => Vec::new(),
            Some(table) => edges(&location, table, node_count, &name)?,
        };
        let has_coordinates = spec.geometry.nodes.is_some();
        let mut model = FeModel {
            name: spec.name.clone(),
            dofs,
            nodes,
            edges,
            k,
            m,
            rigid_motions: RigidMotions::Unknown,
        };
        check_mass(&model, m_name)?;
        if has_coordinates && rigid_motions_are_null_space(&model) {
            model.rigid_motions = RigidMotions::FromGeometry;
        }

        let interfaces = checked_sets(
            &SetsAndInterfaces {
                node_sets: &spec.node_sets,
                interfaces: &spec.interfaces,
                default_interface: spec.default_interface.as_deref(),
            },
            node_count,
            &spec_text,
        )?;
        let preload = match &spec.preload {
            Some(p) => Some(Preload::read(&model, &location, p)?),
            None => None,
        };
        Ok(Self {
            preload,
            model,
            node_sets: spec.node_sets,
            interfaces,
            has_coordinates,
            units: spec.units,
            description: spec.description,
            default_interface: spec.default_interface,
            location,
        })
    }

    /// The boundary of `spec` with interfaces: an item `rbe2:SET` ties the node set `SET` to
    /// one master node at its centroid (its nodes join the boundary), `rbe3:SET` averages it
    /// into one (its nodes stay free), an item naming an interface of the body file does what
    /// the file says; each is returned as a [`RigidSet`]. Other items are read by [`Self::boundary`]. A node in two items is an
    /// error.
    pub fn boundary_with_interfaces(&self, spec: &[String]) -> Result<(Vec<usize>, Vec<RigidSet>)> {
        let mut plain = Vec::new();
        let mut rigid: Vec<RigidSet> = Vec::new();
        for item in spec {
            let item = item.trim();
            let prefixed = [
                ("rbe2:", InterfaceKind::Rbe2),
                ("rbe3:", InterfaceKind::Rbe3),
            ]
            .into_iter()
            .find_map(|(p, kind)| item.strip_prefix(p).map(|name| (name, kind)));
            if let Some((name, kind)) = prefixed {
                let nodes = self.boundary(&[name.to_string()])?;
                rigid.push(RigidSet {
                    name: name.to_string(),
                    nodes,
                    master: None,
                    kind,
                    weights: None,
                });
            } else if let Some(interface) = self.interfaces.get(item) {
                rigid.push(RigidSet {
                    name: item.to_string(),
                    nodes: self.boundary(std::slice::from_ref(&interface.node_set))?,
                    master: interface.master,
                    kind: interface.kind,
                    weights: interface.weights.clone(),
                });
            } else {
                plain.push(item.to_string());
            }
        }
        let mut nodes = self.boundary(&plain)?;
        let mut averaged: Vec<usize> = Vec::new();
        for set in &rigid {
            for &n in &set.nodes {
                if nodes.contains(&n) || averaged.contains(&n) {
                    return Err(Error::DuplicateNode { node: n });
                }
                match set.kind {
                    InterfaceKind::Rbe2 => nodes.push(n),
                    InterfaceKind::Rbe3 => averaged.push(n),
                }
            }
        }
        Ok((nodes, rigid))
    }

    /// The boundary nodes of `spec`: a node set's name, or 1-based node numbers
    /// (`1,4,5`). Several set names or numbers may be mixed, comma separated.
    pub fn boundary(&self, spec: &[String]) -> Result<Vec<usize>> {
        let mut nodes = Vec::new();
        for item in spec {
            let item = item.trim();
            match item.parse::<usize>() {
                Ok(node) => {
                    self.model.node_index(node)?;
                    nodes.push(node);
                }
                Err(_) => {
                    let set = self.node_sets.get(item).ok_or_else(|| {
                        Error::BodyFile(BodyFileError::UnknownNodeSet {
                            name: item.into(),
                            known: crate::error::Name::all(self.node_sets.keys()),
                        })
                    })?;
                    for &n in set {
                        if !nodes.contains(&n) {
                            nodes.push(n);
                        }
                    }
                }
            }
        }
        Ok(nodes)
    }

    /// Fails with `BodyFileError::NoCoordinates` when the body cannot be drawn.
    pub fn require_coordinates(&self) -> Result<()> {
        if self.has_coordinates {
            Ok(())
        } else {
            Err(Error::BodyFile(BodyFileError::NoCoordinates {
                body: (&self.model.name).into(),
            }))
        }
    }
}

/// A body's node sets, interfaces and default interface, as a body file or a caller gives them.
pub(super) struct SetsAndInterfaces<'a> {
    pub(super) node_sets: &'a BTreeMap<String, Vec<usize>>,
    pub(super) interfaces: &'a BTreeMap<String, InterfaceSpec>,
    pub(super) default_interface: Option<&'a str>,
}

/// Checks the sets against `node_count` nodes and the interfaces against the sets; `text`
/// places an error (the body file, and the line of a key when there is one).
pub(super) fn checked_sets(
    given: &SetsAndInterfaces<'_>,
    node_count: usize,
    text: &SpecText<'_>,
) -> Result<BTreeMap<String, InterfaceSpec>> {
    if let Some(set) = &given.default_interface
        && !given.node_sets.contains_key(*set)
    {
        return Err(text.error(
            text.key_line("default_interface"),
            BodySpecProblem::DefaultInterfaceUndefined { set: (*set).into() },
        ));
    }
    for (set, members) in given.node_sets {
        if let Some(&node) = members.iter().find(|&&x| x == 0 || x > node_count) {
            return Err(Error::BodyFile(BodyFileError::NodeSetOutOfRange {
                path: text.name.into(),
                set: set.into(),
                node,
                count: node_count,
            }));
        }
    }
    let mut interfaces = BTreeMap::new();
    for (iname, interface) in given.interfaces {
        if !given.node_sets.contains_key(&interface.node_set) {
            return Err(text.error(
                text.key_line(iname),
                BodySpecProblem::InterfaceSetUndefined {
                    interface: iname.into(),
                    set: (&interface.node_set).into(),
                },
            ));
        }
        if let Some(w) = &interface.weights {
            let count = given.node_sets[&interface.node_set].len();
            if interface.kind == InterfaceKind::Rbe2 {
                return Err(text.error(
                    text.key_line(iname),
                    BodySpecProblem::WeightsOnRbe2 {
                        interface: iname.into(),
                    },
                ));
            }
            if w.len() != count || w.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(text.error(
                    text.key_line(iname),
                    BodySpecProblem::Weights {
                        interface: iname.into(),
                        given: w.len(),
                        nodes: count,
                        set: (&interface.node_set).into(),
                    },
                ));
            }
        }
        interfaces.insert(iname.clone(), interface.clone());
    }
    Ok(interfaces)
}

/// The per-node DOF a body names (of x, y, z, rx, ry, rz, each once); the problem when they
/// are not.
pub(super) fn dof_map(names: &[String]) -> std::result::Result<DofMap, BodySpecProblem> {
    if names.is_empty() {
        return Err(BodySpecProblem::NoDofs);
    }
    let mut per_node = Vec::new();
    for d in names {
        let dof = node_dof(d).ok_or_else(|| BodySpecProblem::UnknownDof { dof: d.into() })?;
        if per_node.contains(&dof) {
            return Err(BodySpecProblem::DofListedTwice { dof: dof.name() });
        }
        per_node.push(dof);
    }
    Ok(DofMap::new(per_node))
}
