//! `model.json`, the reduced model described for another code: the body, method, interface
//! and kept modes, one label per column, the checked frequencies, the inertia invariants of
//! the reduced body and, with a `[preload]`, its geometric stiffness.

use faer::Mat;
use serde_json::json;

use super::ReducedExport;
use crate::{
    body_file::ImportedBody,
    fem::FeModel,
    reduction::{AveragingInterface, Basis, ColumnKind, MASTER_DOF_NAMES, RigidInterface},
    report::sig_vec,
};

impl ReducedExport {
    /// `model.json`: the columns, interfaces, inertia invariants and checked frequencies.
    pub fn document(&self, body: &ImportedBody) -> serde_json::Value {
        let model = &body.model;
        let (method, boundary, modes, parameters) = (
            self.method,
            &self.boundary,
            self.kept_modes,
            &self.parameters,
        );
        let (basis, hz, residuals) = (&self.basis, &self.hz, &self.residuals);
        let (zero_energy, threshold) = (self.zero_energy, self.zero_energy_threshold_hz);
        let (free_free_sturm, exudyn) = (self.free_free_sturm, &self.exudyn);
        let columns = columns_json(model, basis);
        let inertia = if body.has_coordinates {
            Some(inertia_invariants(body, basis))
        } else {
            None
        };
        let doc = json!({
            "format": "flexmodes reduced model 1",
            "body": body.location.display(),
            "body_name": model.name,
            "units": { "length": body.units.length, "mass": body.units.mass, "force": body.units.force },
            "method": method.id(),
            "method_name": method.name(),
            "boundary_nodes": boundary,
            "kept_modes": modes,
            "dofs": model.dof_count(),
            "dof_order": "node-major",
            "dofs_per_node": model.dofs.node_dofs().iter().map(|d| d.name()).collect::<Vec<_>>(),
            "size": basis.size(),
            "columns": columns,
            "interfaces": rigid_json(&parameters.rigid_interfaces, basis),
            // An averaging (RBE3) master is no coordinate of the reduced model: its motion is
            // read as (A Ψ) z and a load on it enters as (A Ψ)ᵀ F (A: the weighted average).
            "averaging_interfaces": averaging_json(&parameters.averaging_interfaces, model, basis),
            // The route of the fixed-interface pairs (sparse path) and of the free-free pairs
            // the load-built methods start from; AMLS's reductions when it made them.
            "eigensolver": parameters.eigensolver.id(),
            "amls_reductions": basis.statistics.amls_reductions,
            "reduced_elastic_hz": sig_vec(hz),
            "reduced_elastic_residuals": sig_vec(residuals),
            "reduced_zero_energy_modes": zero_energy,
            // The body's free-free solve, when the method needed one: modes it skipped below the
            // highest pair, by the Sturm count (0 by construction for a complete dense solve).
            "free_free_missed_modes": free_free_sturm.map(|s| s.map_or(0, |c| c.missed())),
            "free_free_sturm_check": free_free_sturm.flatten().map(|c| json!({
                "shift_hz": crate::linalg::hz_from_eigenvalue(c.shift),
                "eigenvalues_below": c.below,
                "found_below": c.found,
            })),
            "zero_energy_threshold_hz": threshold,
            "files": {
                "psi": parameters.psi_format.file_name(),
                "stiffness": "k_r.mtx",
                "mass": "m_r.mtx",
            },
            "inertia": inertia,
            "stiffening": self.kg_r.as_ref().zip(body.preload.as_ref()).map(|(_, p)| json!({
                "matrix": "kg_r.mtx",
                "per": "rate squared: K_r + rate^2 kg_r in a frame spinning at rate (rad/s) about the axis",
                "axis": [p.load.axis.x, p.load.axis.y, p.load.axis.z],
                "axis_point": p.load.point,
                "preload_rate_rad_s": p.load.rate,
                "held_dofs": p.held.len(),
                "note": "the geometric stiffness of the centrifugal prestress, from the body file's \
                         [preload] (CalculiX's stiffness spun at preload_rate_rad_s less K and the \
                         spin softening); the spin softening rate^2 Psi^T M (I x e~^2) Psi is not \
                         in it: a floating frame's inertia terms make it. It holds for a spin about \
                         this axis with the held DOF clamped, as CalculiX's static step held them",
            })),
            "exudyn": exudyn.as_ref().map(|e| json!({
                "folder": "exudyn",
                "frame": e.frame,
                "modes": e.modes.ncols(),
                "mode_type": e.mode_type,
                "note": "load with assets/python/flexmodes_exudyn.py (numpy, scipy, exudyn)",
            })),
            "inertia_note": if inertia.is_none() {
                "the body file gives no node coordinates, so the rigid-body motions and the inertia \
                 invariants are unknown"
            } else {
                "about the body file's origin; rigid motions R = [translations x y z, small \
                 rotations about x y z] (planar: x, y, rotation about z); mass_matrix = R^T M R, \
                 translation_coupling and rotation_coupling = rows of R^T M Psi"
            },
        });
        doc
    }
}

/// Each column of the basis: its label, kind, DOF (1-based, with its node) and frequency.
fn columns_json(model: &FeModel, basis: &Basis) -> Vec<serde_json::Value> {
    basis
        .columns
        .iter()
        .map(|c| {
            json!({
                "label": c.label,
                "kind": kind_name(&c.kind),
                "dof": c.dof.map(|d| {
                    let (node, dof) = model.dof_node(d);
                    json!({ "node": node.number(), "dof": dof.name(), "index": d + 1 })
                }),
                "hz": match c.kind {
                    ColumnKind::Normal { hz }
                    | ColumnKind::FreeInterface { hz }
                    | ColumnKind::Loaded { hz } => Some(hz),
                    _ => None,
                },
            })
        })
        .collect()
}

/// Each rigid (RBE2) interface: its master, its six columns (1-based) and its tied nodes.
fn rigid_json(rigid: &[RigidInterface], basis: &Basis) -> Vec<serde_json::Value> {
    rigid
        .iter()
        .map(|i| {
            let first = basis.columns.iter().position(|c| {
                matches!(
                    &c.kind,
                    ColumnKind::RigidInterface { interface, .. } if *interface == i.name
                )
            });
            json!({
                "name": i.name,
                "kind": "rbe2",
                "master": i.master,
                "master_dofs": MASTER_DOF_NAMES,
                "columns": first.map(|f| (f + 1..=f + 6).collect::<Vec<_>>()),
                "tied_nodes": i.nodes,
            })
        })
        .collect()
}

/// Each averaging (RBE3) interface: its master is no coordinate of the reduced model, its
/// motion is read as $(A\Psi)z$ and a load on it enters as $(A\Psi)^TF$ ($A$: the weighted
/// average).
fn averaging_json(
    averaging: &[AveragingInterface],
    model: &FeModel,
    basis: &Basis,
) -> Vec<serde_json::Value> {
    averaging
        .iter()
        .map(|i| {
            let a_psi = i.averaging_matrix(model).map(|a| a * &basis.psi).map(|m| {
                (0..6)
                    .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<_>>())
                    .collect::<Vec<_>>()
            });
            json!({
                "name": i.name,
                "kind": "rbe3",
                "master": i.master,
                "master_dofs": MASTER_DOF_NAMES,
                "averaged_nodes": i.nodes,
                "weights": i.weights,
                "master_motion": a_psi.ok(),
            })
        })
        .collect()
}

fn kind_name(k: &ColumnKind) -> &'static str {
    match k {
        ColumnKind::Nodal => "nodal",
        ColumnKind::BoundaryMovement => "boundary_movement",
        ColumnKind::Constraint => "constraint",
        ColumnKind::CondensedBoundary => "condensed_boundary",
        ColumnKind::EitelbergBoundary => "eitelberg_boundary",
        ColumnKind::Normal { .. } => "normal",
        ColumnKind::FreeInterface { .. } => "free_interface",
        ColumnKind::Residual => "residual",
        ColumnKind::Loaded { .. } => "loaded",
        ColumnKind::Krylov { .. } => "krylov",
        ColumnKind::Balanced { .. } => "balanced",
        ColumnKind::InertiaResidual { .. } => "inertia_residual",
        ColumnKind::RigidInterface { .. } => "rigid_interface",
        ColumnKind::CharacteristicConstraint { .. } => "characteristic_constraint",
    }
}

/// $R^TMR$ and $R^TM\Psi$ about the body file's origin.
fn inertia_invariants(body: &ImportedBody, basis: &Basis) -> serde_json::Value {
    let model = &body.model;
    let r = model.rigid_body_modes();
    let mr = model.m.mul(r.as_ref());
    let rmr: Mat<f64> = r.transpose() * &mr;
    let coupling: Mat<f64> = mr.transpose() * &basis.psi;
    let rows = |a: &Mat<f64>, from: usize, to: usize| -> Vec<Vec<f64>> {
        (from..to)
            .map(|i| (0..a.ncols()).map(|j| a[(i, j)]).collect())
            .collect()
    };
    let count = r.ncols();
    let translations = model.spatial_dim();
    let properties = model.mass_properties();
    json!({
        "mass": properties.mass,
        "mass_centre": properties.centre,
        "inertia_about_centre": properties.inertia,
        "mass_matrix": rows(&rmr, 0, count),
        "translation_coupling": rows(&coupling, 0, translations),
        "rotation_coupling": rows(&coupling, translations, count),
    })
}
