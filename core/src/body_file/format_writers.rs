//! The matrices of a body in the FE codes' formats flexmodes reads back: Abaqus matrix input
//! (`node, DOF, node, DOF, value`, the lower triangle) and Nastran DMIG cards (free field, one
//! card per entry, IFO 6). Values in Rust's shortest round-trip form (free field has no
//! column limit), so an import reads back exactly what was written.

use std::fmt::Write as _;

use crate::fem::{FeModel, NodeDof, NodeIndex};

/// Abaqus' and Nastran's component number of a node DOF: 1–3 translations, 4–6 rotations.
fn component(dof: NodeDof) -> usize {
    match dof {
        NodeDof::Translation(d) => d.index() + 1,
        NodeDof::Rotation(d) => d.index() + 4,
    }
}

/// (node, component), both 1-based, of a 0-based node-major DOF.
fn node_component(model: &FeModel, dof: usize) -> (usize, usize) {
    let (node, d) = model.dofs.locate(dof);
    (NodeIndex(node).number(), component(d))
}

/// Abaqus `*MATRIX INPUT` lines of the lower-triangle `entries` (0-based DOF).
pub(super) fn abaqus_text(model: &FeModel, entries: &[(usize, usize, f64)], what: &str) -> String {
    let mut out = format!(
        "** {what} of {}, written by flexmodes convert\n",
        model.name
    );
    for &(i, j, v) in entries {
        let (ni, ci) = node_component(model, i);
        let (nj, cj) = node_component(model, j);
        let _ = writeln!(out, "{ni},{ci}, {nj},{cj}, {v:e}");
    }
    out
}

/// DMIG cards of the symmetric matrix `name` from its lower-triangle `entries`: a header
/// (IFO 6, TIN 2) and one free-field card per entry.
pub(super) fn dmig_text(
    model: &FeModel,
    name: &str,
    entries: &[(usize, usize, f64)],
    what: &str,
) -> String {
    let mut out = format!(
        "$ {what} of {}, written by flexmodes convert\nDMIG,{name},0,6,2,0,,,{}\n",
        model.name,
        model.dof_count()
    );
    for &(i, j, v) in entries {
        let (ni, ci) = node_component(model, i);
        let (nj, cj) = node_component(model, j);
        let _ = writeln!(out, "DMIG,{name},{nj},{cj},,{ni},{ci},{v:e}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::{Direction, DofMap};

    #[test]
    fn components_follow_the_formats_numbering() {
        assert_eq!(component(NodeDof::Translation(Direction::Z)), 3);
        assert_eq!(component(NodeDof::Rotation(Direction::X)), 4);
        let frame = DofMap::frame_3d();
        assert_eq!(frame.node_dofs().len(), 6);
    }
}
