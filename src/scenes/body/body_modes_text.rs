//! The body modes scene's text: the body, its interface and every frequency and residual, and what each method keeps.

use crate::scenes::SceneOptions;
use crate::{body_file::ImportedBody, report::fmt_hz};

/// The tables, lines and sections of the body modes scene's text, already written.
pub(super) struct BodyTables<'a> {
    pub(super) summary: &'a str,
    /// One line per residual check.
    pub(super) residuals: &'a [String],
    /// The methods' notes, one bullet each.
    pub(super) notes: &'a [String],
    pub(super) sweep: &'a str,
    pub(super) influence: &'a str,
    pub(super) response: &'a str,
}

/// The scene's report text: the body and its interface, the methods' table, the full body's
/// and the fixed interface's frequencies, every residual, the notes and the sections.
pub(super) fn body_text(
    body: &ImportedBody,
    boundary: &[usize],
    opts: &SceneOptions,
    kept: usize,
    full: &crate::analysis::ZeroEnergyCount,
    (full_hz, fi_hz): (&[f64], &[f64]),
    tables: &BodyTables,
) -> String {
    let model = &body.model;
    let dofs = model.dof_count();
    let units = &body.units;
    format!(
        "Body `{}` ({}): {dofs} DOF, {} stiffness entries, {} zero-energy mode(s); units {}, \
         {}, {}. Interface {} node(s) {}{}, {kept} kept modes.\n\n{}\nFull body, \
         lowest elastic: {}\n\nFixed-interface: {}\n\nEigen residuals \
         (‖Kφ − λMφ‖/‖Kφ‖ of every printed frequency): {}\n{}{}{}{}",
        model.name,
        body.location.display(),
        model.stiffness_nnz(),
        full.zero_modes,
        units.length,
        units.mass,
        units.force,
        boundary.len(),
        if boundary.len() <= 12 {
            format!("{boundary:?}")
        } else {
            format!(
                "{:?} … {:?}",
                &boundary[..6],
                &boundary[boundary.len() - 3..]
            )
        },
        opts.rigid_interfaces
            .iter()
            .map(|i| format!(
                "; rbe2 `{}`: {} nodes tied to a master at ({})",
                i.name,
                i.nodes.len(),
                i.master.map(flexmodes_core::report::sig6).join(", ")
            ))
            .chain(opts.averaging_interfaces.iter().map(|i| format!(
                "; rbe3 `{}`: {} nodes averaged into a master at ({}), loading it and free",
                i.name,
                i.nodes.len(),
                i.master.map(flexmodes_core::report::sig6).join(", ")
            )))
            .collect::<String>(),
        tables.summary,
        fmt_hz(full_hz),
        fmt_hz(&fi_hz[..fi_hz.len().min(8)]),
        tables.residuals.join("; "),
        tables
            .notes
            .iter()
            .map(|n| format!("\n- {n}"))
            .collect::<String>(),
        tables.sweep,
        tables.influence,
        tables.response,
    )
}

/// The scene's text: what every method keeps and what the columns mean, then the report.
pub(super) fn scene_text(body: &ImportedBody, kept: usize, caption: &str, table: &str) -> String {
    let model = &body.model;
    format!(
        "# modes: {}\n\n{}\n\nEvery method reduces the same body on the same interface: \
         Guyan keeps only the interface (static constraint modes), modal truncation the \
         interface movements and the {kept} lowest fixed-interface modes, Craig–Bampton the \
         constraint modes and those modes, mode condensation the same space in its own \
         coordinates. MacNeal–Rubin keeps free-interface modes and the residual flexibility of the \
         interface DOF; Benfield–Hruda the modes of the body with its interfaces loaded; moment \
         matching Krylov vectors of the interface loads; balanced truncation the dominant \
         vectors of the interface loads' position gramian (each says below what it took). \
         \"max rel. error\" compares each model's six lowest elastic frequencies \
         with the full body's, paired by order; the angle is the largest principal angle between the basis \
         and the full body's zero-energy and six lowest elastic modes (0: contained). \"rigid \
         modes at\" is the highest frequency a reduced model gives its rigid-body motions, \
         which should be zero: round-off in the method's coordinates lifts it. {}\n\n{}",
        model.name, body.description, caption, table
    )
}
