//! The body of an export as Exudyn's `FEMinterface` holds it (Zwölfer and Gerstmayr's nodal
//! floating frame of reference with modal reduction, Exudyn's `ObjectFFRFreducedOrder`): node
//! positions, the full mass and stiffness matrices, and a mode basis without rigid-body
//! motions, in Exudyn's coordinate order (node by node, x y z) and node numbering (0-based).
//!
//! The floating frame is attached to the export's first rigid (RBE2) interface: the reduced
//! basis drops that interface's six constraint modes (its ring then never moves in the frame,
//! the frame's rigid motion is the body's), and keeps everything else: the fixed-interface
//! modes and the other interfaces' constraint modes. That is exactly the basis `flexmodes
//! simulate` integrates with the drive at that interface, so the two codes can be compared.
//! The kept basis is checked: no row of the frame's ring may move, and its reduced pencil
//! $(\Psi^TK\Psi, \Psi^TM\Psi)$ must have no zero-energy mode (the frame alone must hold the
//! body), every eigenpair's residual checked.
//!
//! Files, in `exudyn/` of the export folder: `nodes.npy` (n × 3), `mass.mtx` and
//! `stiffness.mtx` (3n × 3n, Matrix Market `coordinate real symmetric`), `modes.npy`
//! (3n × m, `float64`) and `body.json` (units, the frame, node sets and interfaces by 0-based
//! node numbers, the basis' eigenvalues ω² and frequencies); with a body file's `[preload]`,
//! `geometric_stiffness.npy` (m × m): the modal geometric stiffness of the centrifugal
//! prestress per unit rate², $\Psi^TK_{\sigma,1}\Psi$, which a spin Ω about the preload's axis
//! adds as $\Omega^2$ times it (the adapter's `add_stiffening` puts it into Exudyn as a user
//! force). `assets/python/flexmodes_exudyn.py`
//! builds Exudyn's `FEMinterface` and `ObjectFFRFreducedOrderInterface` from them with numpy
//! and scipy only.

use std::path::Path;

use faer::Mat;
use serde_json::{Value, json};

use crate::{
    Result,
    analysis::{zero_energy_below, zero_energy_threshold_hz},
    atomic_file::write_atomically,
    body_file::{
        ImportedBody, lower_entries, mass_lower_entries, write_coordinate_symmetric, write_npy,
    },
    error::{ExportProblem, ReductionError},
    fem::{Direction, FeModel, NodeDof, NodeIndex},
    linalg::{generalized_eigen, hz_from_eigenvalue},
    reduction::{AveragingInterface, Basis, ColumnKind, RigidInterface},
    report::sig_vec,
};

/// The `format` field of `body.json`.
pub const EXUDYN_FORMAT: &str = "flexmodes exudyn body 1";

/// The body of an export for Exudyn, checked and ready to write.
#[derive(Debug, Clone)]
pub struct ExudynBody {
    /// The interface the floating frame is attached to.
    pub frame: String,
    /// The mode basis in Exudyn's order: row `3·node + axis`, one column per kept mode.
    pub modes: Mat<f64>,
    /// Eigenvalues ω² of the kept basis' reduced pencil, (rad/s)², ascending.
    pub eigenvalues: Vec<f64>,
    /// Each eigenpair's relative residual.
    pub residuals: Vec<f64>,
    /// Exudyn's name for the basis: `NormalModes` (fixed-interface modes only) or `HCBmodes`
    /// (with other interfaces' constraint modes).
    pub mode_type: &'static str,
    /// The modal geometric stiffness of the body file's `[preload]` per unit rate² (m × m,
    /// the modes' order), when the export keeps it.
    pub geometric: Option<Mat<f64>>,
    /// For each of Exudyn's coordinates, the body's DOF.
    order: Vec<usize>,
    doc: Value,
}

fn refuse(problem: ExportProblem) -> crate::Error {
    ReductionError::NotExportable {
        to: "Exudyn",
        problem,
    }
    .into()
}

/// The body's DOF indices node by node, x y z (Exudyn's order); a body whose nodes carry
/// other than the three translations is refused by name.
fn translation_order(model: &FeModel) -> Result<Vec<usize>> {
    let per_node = model.dofs.node_dofs();
    let translations = [Direction::X, Direction::Y, Direction::Z].map(NodeDof::Translation);
    if per_node.len() != 3 || !translations.iter().all(|d| per_node.contains(d)) {
        return Err(refuse(ExportProblem::NotTranslations {
            carried: per_node.iter().map(|d| d.name()).collect(),
        }));
    }
    let nodes = model.node_count();
    Ok((0..nodes)
        .flat_map(|node| {
            translations.map(|d| {
                model
                    .dofs
                    .index(node, d)
                    .expect("checked: x y z translations")
            })
        })
        .collect())
}

/// Refuses a kept basis that moves a node of the frame's ring (beyond 1e-12 of its largest
/// entry): the frame would not be attached to the ring.
fn frame_ring_still(model: &FeModel, frame: &RigidInterface, modes: &Mat<f64>) -> Result<()> {
    let largest = (0..modes.ncols())
        .flat_map(|j| (0..modes.nrows()).map(move |i| (i, j)))
        .fold(0.0f64, |m, (i, j)| m.max(modes[(i, j)].abs()));
    for &node in &frame.nodes {
        for axis in 0..3 {
            // The rows are in Exudyn's order: node by node, x y z.
            let row = 3 * model.node_index(node)?.get() + axis;
            let moved = (0..modes.ncols())
                .map(|j| modes[(row, j)].abs())
                .fold(0.0, f64::max);
            if moved > 1e-12 * largest {
                return Err(refuse(ExportProblem::FrameRingMoves {
                    node,
                    ring: (&frame.name).into(),
                    moved,
                    largest,
                }));
            }
        }
    }
    Ok(())
}

/// Builds the Exudyn body of `basis` (see the module): the frame on `rigid[0]`; with
/// `stiffening`, the `[preload]`'s modal geometric stiffness.
pub fn exudyn_body(
    body: &ImportedBody,
    basis: &Basis,
    rigid: &[RigidInterface],
    averaging: &[AveragingInterface],
    stiffening: bool,
) -> Result<ExudynBody> {
    let model = &body.model;
    if !body.has_coordinates {
        return Err(refuse(ExportProblem::NoCoordinates));
    }
    let order = translation_order(model)?;
    let frame = rigid
        .first()
        .ok_or_else(|| refuse(ExportProblem::NoFrameInterface))?;
    let nodes = model.node_count();

    let keep = elastic_columns(basis, frame)?;
    let modes = Mat::from_fn(order.len(), keep.len(), |i, j| {
        basis.psi[(order[i], keep[j])]
    });
    frame_ring_still(model, frame, &modes)?;

    let kept = Basis {
        method: basis.method,
        psi: Mat::from_fn(basis.psi.nrows(), keep.len(), |i, j| {
            basis.psi[(i, keep[j])]
        }),
        columns: keep.iter().map(|&j| basis.columns[j].clone()).collect(),
        statistics: basis.statistics,
    };
    let (k_r, m_r) = (kept.reduced_stiffness(model), kept.reduced_mass(model));
    let geometric = body
        .preload
        .as_ref()
        .filter(|_| stiffening)
        .map(|p| kept.project(&p.rate_squared));
    let eig = generalized_eigen(k_r.as_ref(), m_r.as_ref(), "Exudyn mode basis")?;
    let hz = eig.hz();
    let zero = zero_energy_below(&hz, zero_energy_threshold_hz(model));
    if zero > 0 {
        return Err(refuse(ExportProblem::ZeroEnergyLeft {
            ring: (&frame.name).into(),
            zero,
            lowest_hz: hz[0],
        }));
    }
    let mode_type = mode_type(basis, &keep);
    let (ring_indices, node_sets, interfaces) = numbered_sets(body, frame, (rigid, averaging))?;
    let files = file_names(geometric.is_some());
    let doc = json!({
        "format": EXUDYN_FORMAT,
        "body_name": model.name,
        "body": body.location.display(),
        "units": { "length": body.units.length, "mass": body.units.mass, "force": body.units.force },
        "node_numbering": "0-based (Exudyn's)",
        "coordinate_order": "node by node, x y z (Exudyn's)",
        "nodes": nodes,
        "method": basis.method.id(),
        "frame": {
            "interface": frame.name,
            "kind": "rbe2",
            "master": frame.master,
            "node_numbers": ring_indices,
            "note": "the floating frame's origin and axes are the body's own; the ring never \
                     moves in it (its constraint modes are left out of the basis)",
        },
        "mode_type": mode_type,
        "modes": keep.len(),
        "columns": keep.iter().map(|&j| basis.columns[j].label.clone()).collect::<Vec<_>>(),
        "eigenvalues": eig.values,
        "hz": hz,
        "residuals": sig_vec(&eig.residuals),
        "node_sets": node_sets,
        "interfaces": interfaces,
        "stiffening": body.preload.as_ref().filter(|_| geometric.is_some()).map(|p| json!({
            "matrix": "geometric_stiffness.npy",
            "per": "rate squared: a spin Omega (rad/s) about the axis adds Omega^2 times it to \
                    the modal stiffness",
            "axis": [p.load.axis.x, p.load.axis.y, p.load.axis.z],
            "axis_point": p.load.point,
            "preload_rate_rad_s": p.load.rate,
            "note": "the centrifugal prestress' geometric stiffness, from the body file's \
                     [preload]; the spin softening is the floating frame's own",
        })),
        "files": files,
    });
    Ok(ExudynBody {
        frame: frame.name.clone(),
        modes,
        eigenvalues: eig.values.clone(),
        residuals: eig.residuals.clone(),
        mode_type,
        geometric,
        order,
        doc,
    })
}

/// The basis' columns but the frame ring's six rigid-interface ones: the frame carries the
/// ring, so those are left out; refused when the ring has no six columns or nothing else is
/// left.
fn elastic_columns(basis: &Basis, frame: &RigidInterface) -> Result<Vec<usize>> {
    let keep: Vec<usize> = (0..basis.size())
        .filter(|&j| {
            !matches!(&basis.columns[j].kind,
                ColumnKind::RigidInterface { interface, .. } if *interface == frame.name)
        })
        .collect();
    if keep.len() + 6 != basis.size() {
        return Err(refuse(ExportProblem::NoConstraintModes {
            ring: (&frame.name).into(),
            other: keep.len(),
            columns: basis.size(),
        }));
    }
    if keep.is_empty() {
        return Err(refuse(ExportProblem::NothingElastic {
            ring: (&frame.name).into(),
        }));
    }
    Ok(keep)
}

/// Exudyn's mode type: `NormalModes` when every kept column is a normal mode, else `HCBmodes`.
fn mode_type(basis: &Basis, keep: &[usize]) -> &'static str {
    if keep
        .iter()
        .all(|&j| matches!(basis.columns[j].kind, ColumnKind::Normal { .. }))
    {
        "NormalModes"
    } else {
        "HCBmodes"
    }
}

/// The frame ring's node numbers, and every node set and interface with its node numbers,
/// 0-based as Exudyn numbers nodes.
fn numbered_sets(
    body: &ImportedBody,
    frame: &RigidInterface,
    (rigid, averaging): (&[RigidInterface], &[AveragingInterface]),
) -> Result<(Vec<usize>, Vec<Value>, Vec<Value>)> {
    let model = &body.model;
    let zero_based = |nodes: &[usize]| -> Result<Vec<usize>> {
        nodes
            .iter()
            .map(|&n| model.node_index(n).map(NodeIndex::get))
            .collect()
    };
    let ring_indices = zero_based(&frame.nodes)?;
    let node_sets = body
        .node_sets
        .iter()
        .map(|(name, nodes)| Ok(json!({ "name": name, "node_numbers": zero_based(nodes)? })))
        .collect::<Result<Vec<_>>>()?;
    let interfaces = rigid
        .iter()
        .map(|i| {
            Ok(json!({
                "name": i.name, "kind": "rbe2", "master": i.master,
                "node_numbers": zero_based(&i.nodes)?,
            }))
        })
        .chain(averaging.iter().map(|i| {
            Ok(json!({
                "name": i.name, "kind": "rbe3", "master": i.master,
                "node_numbers": zero_based(&i.nodes)?, "weights": i.weights,
            }))
        }))
        .collect::<Result<Vec<_>>>()?;
    Ok((ring_indices, node_sets, interfaces))
}

/// The files of the Exudyn body, the geometric stiffness' with `stiffening`.
fn file_names(stiffening: bool) -> Value {
    let mut files = json!({
        "nodes": "nodes.npy",
        "mass": "mass.mtx",
        "stiffness": "stiffness.mtx",
        "modes": "modes.npy",
    });
    if stiffening {
        files["geometric_stiffness"] = json!("geometric_stiffness.npy");
    }
    files
}

impl ExudynBody {
    /// [`Self::eigenvalues`] as frequencies, Hz.
    pub fn hz(&self) -> Vec<f64> {
        self.eigenvalues
            .iter()
            .map(|&l| hz_from_eigenvalue(l))
            .collect()
    }

    /// Writes the files into `dir` (created; each file atomically) and returns their names
    /// relative to `dir`'s parent.
    pub fn write(&self, body: &ImportedBody, dir: &Path) -> Result<Vec<String>> {
        let model = &body.model;
        std::fs::create_dir_all(dir).map_err(|source| crate::Error::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let mut position = vec![0; self.order.len()];
        for (p, &dof) in self.order.iter().enumerate() {
            position[dof] = p;
        }
        let permuted = |entries: Vec<(usize, usize, f64)>| -> Vec<(usize, usize, f64)> {
            let mut out: Vec<_> = entries
                .into_iter()
                .map(|(i, j, v)| {
                    let (a, b) = (position[i], position[j]);
                    (a.max(b), a.min(b), v)
                })
                .collect();
            out.sort_by_key(|&(i, j, _)| (j, i));
            out
        };
        let n = self.order.len();
        let nodes = Mat::from_fn(model.node_count(), 3, |i, j| model.nodes[i][j]);
        write_npy(&dir.join("nodes.npy"), nodes.as_ref())?;
        let mass = mass_lower_entries(&model.m);
        let units = &body.units;
        write_coordinate_symmetric(
            &dir.join("mass.mtx"),
            n,
            &permuted(mass),
            &format!(
                "mass of {} in {}; Exudyn's order: node by node, x y z",
                model.name, units.mass
            ),
        )?;
        write_coordinate_symmetric(
            &dir.join("stiffness.mtx"),
            n,
            &permuted(lower_entries(&model.k)),
            &format!(
                "stiffness of {} in {}/{}; Exudyn's order: node by node, x y z",
                model.name, units.force, units.length
            ),
        )?;
        write_npy(&dir.join("modes.npy"), self.modes.as_ref())?;
        let mut written = vec!["nodes.npy", "mass.mtx", "stiffness.mtx", "modes.npy"];
        if let Some(g) = &self.geometric {
            write_npy(&dir.join("geometric_stiffness.npy"), g.as_ref())?;
            written.push("geometric_stiffness.npy");
        }
        let text = serde_json::to_string_pretty(&self.doc).expect("JSON of plain values");
        write_atomically(&dir.join("body.json"), |w| w.write_all(text.as_bytes()))?;
        written.push("body.json");
        Ok(written.iter().map(|f| format!("exudyn/{f}")).collect())
    }
}
