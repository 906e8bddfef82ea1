//! What `flexmodes import` (and Python's `Body.summary`) says of a body: its size, mass, zero-energy modes, lowest
//! frequencies and node sets; and the refusal of a mechanism, shared with the `modes` scene.

use serde_json::{Map, Value, json};

use crate::{
    Error, Result,
    analysis::{ZeroEnergyCount, count_zero_energy_modes_by},
    body_file::ImportedBody,
    fem::MassProperties,
    linalg::AmlsStatistics,
    reduction::Eigensolver,
    report::{fmt_hz, residual_note, sig, sig_vec, sig6},
};

/// Elastic free-free modes computed for the summary and the `modes` scene.
pub const FULL_MODES: usize = 10;

/// [`Error::Mechanism`] when the body has more zero-energy modes than a free body's rigid
/// motions.
pub fn refuse_mechanism(
    model: &crate::fem::FeModel,
    full: &crate::analysis::ZeroEnergyCount,
) -> Result<()> {
    let rigid = model.dofs.rigid_body_count();
    if full.zero_modes > rigid {
        return Err(Error::Mechanism {
            body: (&model.name).into(),
            zero_modes: full.zero_modes,
            rigid,
            threshold_hz: full.threshold_hz,
        });
    }
    Ok(())
}

/// "0 (Sturm count: …)": how many eigenvalues below the highest pair the solver skipped, as
/// the inertia of $K - \sigma' M$ counts them, or that the solve was complete.
pub fn missed_note(modes: &crate::linalg::GeneralizedEigen) -> String {
    match modes.sturm {
        Some(c) => format!(
            "{} (Sturm count: {} eigenvalues below {} Hz, {} found)",
            c.missed(),
            c.below,
            sig6(crate::linalg::hz_from_eigenvalue(c.shift)),
            c.found
        ),
        None => "0 (complete dense solve)".into(),
    }
}

/// What `flexmodes import` prints: the body's size, mass, zero-energy modes and lowest
/// frequencies, its node sets; JSON and text. A mechanism is [`Error::Mechanism`].
pub fn import_summary(body: &ImportedBody) -> Result<(Value, String)> {
    import_summary_by(body, Eigensolver::Lanczos)
}

/// [`import_summary`] with the free-free pairs by `solver` (`import --eigensolver`); the
/// summary names the route, and AMLS's reductions and refinement.
pub fn import_summary_by(body: &ImportedBody, solver: Eigensolver) -> Result<(Value, String)> {
    let model = &body.model;
    let (full, amls) = count_zero_energy_modes_by(model, FULL_MODES, solver)?;
    refuse_mechanism(model, &full)?;
    let (mass_kind, mass_nnz) = match &model.m {
        crate::linalg::MassMatrix::Lumped(d) => ("lumped", d.len()),
        crate::linalg::MassMatrix::Consistent(m) => ("consistent", m.nnz()),
    };
    let dof_names: Vec<&'static str> = model.dofs.node_dofs().iter().map(|d| d.name()).collect();
    // How far the coordinates' rigid motions are from K's null space (computed once).
    let defect = (model.rigid_motions == crate::fem::RigidMotions::FromGeometry)
        .then(|| model.rigid_motion_defect());
    // A free body (its zero-energy count a free body's) whose coordinates' rigid motions are
    // not its null space: the coordinates are not the ones its stiffness was made from.
    let geometry = geometry_disagreement(body, full.zero_modes);
    let facts = ImportFacts {
        body,
        full: &full,
        hz: full.elastic_hz(),
        properties: model.mass_properties(),
        amls: amls.as_ref(),
        solver,
        mass_kind,
        mass_nnz,
        dof_names: &dof_names,
        defect,
        geometry: geometry.as_ref(),
    };
    Ok((import_json(&facts), import_text(&facts)))
}

/// What the import found, computed once for its JSON and its text.
struct ImportFacts<'a> {
    body: &'a ImportedBody,
    full: &'a ZeroEnergyCount,
    /// The lowest elastic frequencies, Hz.
    hz: Vec<f64>,
    /// Mass, mass centre and inertia about it.
    properties: MassProperties,
    amls: Option<&'a AmlsStatistics>,
    solver: Eigensolver,
    /// `lumped` or `consistent`, and M's stored entries.
    mass_kind: &'static str,
    mass_nnz: usize,
    dof_names: &'a [&'static str],
    /// How far the coordinates' rigid motions are from K's null space, when K's rigid motions
    /// come from the coordinates.
    defect: Option<f64>,
    /// The coordinates' disagreement with the stiffness, and the nodes where it is largest.
    geometry: Option<&'a (f64, Vec<(usize, f64)>)>,
}

/// `flexmodes import --json`.
fn import_json(facts: &ImportFacts<'_>) -> Value {
    let ImportFacts {
        body,
        full,
        ref hz,
        ref properties,
        amls,
        solver,
        mass_kind,
        mass_nnz,
        dof_names,
        defect,
        geometry,
    } = *facts;
    let model = &body.model;
    let sets: Map<String, Value> = body
        .node_sets
        .iter()
        .map(|(k, v)| (k.clone(), json!(v.len())))
        .collect();
    json!({
        "body": body.location.display(),
        "name": model.name,
        "description": body.description,
        "nodes": model.node_count(),
        "dofs_per_node": dof_names,
        "dofs": model.dof_count(),
        "stiffness_nnz": model.stiffness_nnz(),
        "mass": mass_kind,
        "mass_nnz": mass_nnz,
        "total_mass": sig(properties.mass),
        "units": { "length": body.units.length, "mass": body.units.mass, "force": body.units.force },
        "coordinates": body.has_coordinates,
        "size": if body.has_coordinates { Some(sig(model.size())) } else { None },
        "rigid_motions_from_coordinates":
            model.rigid_motions == crate::fem::RigidMotions::FromGeometry,
        "rigid_motion_defect": defect.map(sig),
        "geometry_disagrees": geometry.map(|(d, nodes)| json!({
            "rigid_motion_defect": sig(*d),
            "nodes": nodes.iter().map(|(n, share)| json!({"node": n, "share": sig(*share)}))
                .collect::<Vec<_>>(),
        })),
        "zero_energy_modes": full.zero_modes,
        "zero_energy_threshold_hz": sig(full.threshold_hz),
        "lowest_elastic_hz": sig_vec(hz),
        "lowest_elastic_residuals": sig_vec(&full.elastic_residuals()),
        "missed_modes": full.modes.sturm.map_or(0, |c| c.missed()),
        "eigensolver": solver.id(),
        "amls": amls.map(amls_json),
        "sturm_check": full.modes.sturm.map(|c| json!({
            "shift_hz": sig(crate::linalg::hz_from_eigenvalue(c.shift)),
            "eigenvalues_below": c.below,
            "found_below": c.found,
        })),
        "mass_centre": properties.centre.map(sig),
        "inertia_about_mass_centre": properties.inertia.map(|row| row.map(sig)),
        "node_sets": sets,
    })
}

/// `flexmodes import`'s text.
fn import_text(facts: &ImportFacts<'_>) -> String {
    let (body, full, amls, solver) = (facts.body, facts.full, facts.amls, facts.solver);
    let (mass_kind, mass_nnz, dof_names) = (facts.mass_kind, facts.mass_nnz, facts.dof_names);
    let (defect, geometry) = (facts.defect, facts.geometry);
    let (hz, properties) = (&facts.hz, &facts.properties);
    let model = &body.model;
    let set_text: Vec<String> = body
        .node_sets
        .iter()
        .map(|(k, v)| format!("{k} ({} nodes)", v.len()))
        .collect();
    format!(
        "# {} ({})\n\n{}\n\n- {} nodes × {} DOF ({}) = {} DOF, node-major\n- K: {} stored \
         entries, symmetric\n- M: {mass_kind}, {mass_nnz} entries; total mass {} {}\n- node \
         coordinates: {}\n- zero-energy modes: {} (below {} Hz; a free {} body has {}){}\n\
         - lowest elastic frequencies, Hz: {} ({})\n- eigensolver: {}\n- missed modes: {}\n- mass centre: {}; inertia about it: {}\n\
         - node sets: {}\n- units: {}, {}, {}{}",
        model.name,
        body.location.display(),
        body.description,
        model.node_count(),
        model.dofs.per_node(),
        dof_names.join(" "),
        model.dof_count(),
        model.stiffness_nnz(),
        crate::report::sig6(properties.mass),
        body.units.mass,
        if body.has_coordinates {
            format!(
                "yes, largest extent {} {}",
                crate::report::sig6(model.size()),
                body.units.length
            )
        } else {
            "none (report and export work; drawing does not)".into()
        },
        full.zero_modes,
        crate::report::readable(full.threshold_hz, 3),
        if model.spatial_dim() == 2 {
            "planar"
        } else {
            "spatial"
        },
        model.dofs.rigid_body_count(),
        zero_energy_words(full.zero_modes, defect),
        fmt_hz(hz),
        residual_note(hz, &full.elastic_residuals()),
        route(model.dof_count(), solver, amls),
        missed_note(&full.modes),
        if body.has_coordinates {
            format!(
                "({}) {}",
                properties.centre.map(sig6).join(", "),
                body.units.length
            )
        } else {
            "unknown (no coordinates)".into()
        },
        if body.has_coordinates {
            format!(
                "[{}] {}·{}²",
                properties
                    .inertia
                    .iter()
                    .map(|row| format!("[{}]", row.map(sig6).join(", ")))
                    .collect::<Vec<_>>()
                    .join(", "),
                body.units.mass,
                body.units.length
            )
        } else {
            "unknown".into()
        },
        if set_text.is_empty() {
            "none".into()
        } else {
            set_text.join(", ")
        },
        body.units.length,
        body.units.mass,
        body.units.force,
        geometry.map_or(String::new(), |(d, nodes)| geometry_words(*d, nodes)),
    )
}

/// What the zero-energy count says of the body: restrained before export, or the coordinates'
/// rigid motions and how closely K holds them (`defect`).
fn zero_energy_words(zero_modes: usize, defect: Option<f64>) -> String {
    if zero_modes == 0 {
        " — the body was restrained before export".to_string()
    } else if let Some(defect) = defect {
        format!(
            "; they are the rigid motions of the node coordinates (K R = {defect} of \
             |K||R|{})",
            if defect > 1e-13 {
                ": the matrices' own precision, which every residual check allows for"
            } else {
                ""
            },
            defect = crate::report::readable(defect, 2)
        )
    } else {
        String::new()
    }
}

/// Nodes named when the coordinates disagree with the stiffness.
const GEOMETRY_NODES_NAMED: usize = 12;

/// The rigid-motion defect and the nodes where it is largest, for a body with coordinates
/// that K's free-free modes show to be free (`zero_modes` a free body's count) but whose
/// coordinates' rigid motions are not K's null space (their defect above 1e-9).
pub fn geometry_disagreement(
    body: &ImportedBody,
    zero_modes: usize,
) -> Option<(f64, Vec<(usize, f64)>)> {
    let model = &body.model;
    let free = zero_modes == model.dofs.rigid_body_count();
    if !(body.has_coordinates && free && model.rigid_motions == crate::fem::RigidMotions::Unknown) {
        return None;
    }
    let defect = model.rigid_motion_defect();
    Some((
        defect,
        model.rigid_motion_residual_nodes(GEOMETRY_NODES_NAMED),
    ))
}

/// The import summary's warning of [`geometry_disagreement`].
fn geometry_words(defect: f64, nodes: &[(usize, f64)]) -> String {
    format!(
        "\n- WARNING, geometry: the node coordinates' rigid motions are not K's null space \
         (K R = {} of |K||R|, where the matrices' precision leaves below 1e-9), though K has \
         a free body's zero-energy modes: the coordinates are not those K was made from. \
         K R is largest at node(s) {}. Usually the FE code moved them: CalculiX repositions \
         mid-side nodes of distorted quadratic elements, and its .frd holds the coordinates it \
         used. Interfaces built from these coordinates (rbe2, rbe3, rigid rings) carry energy \
         in rigid motion, and the reduced models' zero-energy modes are not rigid.",
        crate::report::readable(defect, 2),
        nodes
            .iter()
            .map(|(n, share)| format!("{n} ({})", crate::report::readable(*share, 2)))
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// An AMLS solve's counts as every JSON output gives them (`import`, the `amls` scene, the
/// eigensolver bench): reductions, the last cut-off, the modes kept, refinement steps, the
/// wanted eigenvalues' error before refinement and the worst residual after.
pub fn amls_json(s: &AmlsStatistics) -> Value {
    json!({
        "reductions": s.reductions,
        "cutoff_hz": sig(s.cutoff_hz),
        "projected": s.projected,
        "iterations": s.iterations,
        "unrefined_value_error": sig(s.unrefined_value_error),
        "max_residual": sig(s.max_residual),
    })
}

/// Which route made the pairs, as the summary says it.
fn route(dofs: usize, solver: Eigensolver, amls: Option<&AmlsStatistics>) -> String {
    match amls {
        Some(s) => format!(
            "{}: {} reduction(s), the last at {} Hz keeping {} modes (worst wanted eigenvalue \
             {} high before refinement), {} refinement step(s) to a worst residual of {}",
            solver.name(),
            s.reductions,
            crate::report::readable(s.cutoff_hz, 3),
            s.projected,
            crate::report::readable(s.unrefined_value_error, 2),
            s.iterations,
            crate::report::readable(s.max_residual, 2),
        ),
        None if dofs <= crate::reduction::DENSE_INTERIOR_LIMIT => {
            "the complete dense eigenproblem (a small body)".into()
        }
        None => solver.name().into(),
    }
}
