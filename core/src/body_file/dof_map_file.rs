//! A DOF map of an FE code's matrix output: which node and DOF each equation is. ANSYS
//! `HBMAT` writes it beside the matrix (`.mapping`): a header line `Matrix Eqn Node DOF`, then
//! one line per equation, `equation node label`, labels `UX UY UZ ROTX ROTY ROTZ`.

use super::matrix_bytes::line_error;
use crate::{
    Result,
    error::MatrixLineProblem,
    fem::{DofMap, NodeIndex},
};

/// One line of a DOF map, `number` (1-based) of `path`: its equation (1-based), node, DOF
/// label and the node-major DOF it names (of a body with DOF `names` per node and `node_count`
/// nodes, `dof_count` in all); `None` for a header or blank line.
fn mapped_line<'l>(
    path: &str,
    (number, line): (usize, &'l str),
    (names, node_count, dof_count): (&[&'static str], usize, usize),
) -> Result<Option<(usize, usize, &'l str, usize)>> {
    let error = |line: usize, problem| line_error(path, line, problem);
    let fields: Vec<&str> = line.split_whitespace().collect();
    // The header and blank lines carry no equation.
    let [eq, node, label] = fields[..] else {
        if fields.is_empty() || fields[0].parse::<usize>().is_err() {
            return Ok(None);
        }
        return Err(error(
            number,
            MatrixLineProblem::NotLayout {
                text: line.trim().into(),
                layout: "equation node DOF",
            },
        ));
    };
    let (Ok(eq), Ok(node)) = (eq.parse::<usize>(), node.parse::<usize>()) else {
        return Ok(None);
    };
    let name = match label.to_ascii_uppercase().as_str() {
        "UX" => "x",
        "UY" => "y",
        "UZ" => "z",
        "ROTX" => "θx",
        "ROTY" => "θy",
        "ROTZ" => "θz",
        other => {
            return Err(error(
                number,
                MatrixLineProblem::NotAComponent {
                    node,
                    component: other.into(),
                },
            ));
        }
    };
    let position = names.iter().position(|n| *n == name).ok_or_else(|| {
        error(
            number,
            MatrixLineProblem::DofNotInBody {
                node,
                dof: label.into(),
                body: names.to_vec(),
            },
        )
    })?;
    let Some(index) = NodeIndex::of_number(node).filter(|i| i.get() < node_count) else {
        return Err(error(
            number,
            MatrixLineProblem::NodeNotInBody {
                node,
                count: node_count,
            },
        ));
    };
    if eq == 0 {
        return Err(error(number, MatrixLineProblem::EquationZero));
    }
    // One equation per DOF: a number beyond the body's DOF count names no equation of
    // its matrices (and must not size anything).
    if eq > dof_count {
        return Err(error(
            number,
            MatrixLineProblem::EquationBeyond {
                equation: eq,
                count: dof_count,
            },
        ));
    }
    Ok(Some((
        eq,
        node,
        label,
        index.get() * names.len() + position,
    )))
}

/// The body's DOF of each equation (0-based equation → 0-based node-major DOF), checked: every
/// equation once, labels the body has, and every DOF of the body given an equation.
pub fn parse_dof_map(
    bytes: &[u8],
    path: &str,
    dofs: &DofMap,
    node_count: usize,
) -> Result<Vec<usize>> {
    let error = |line: usize, problem| line_error(path, line, problem);
    let text = std::str::from_utf8(bytes).map_err(|_| error(0, MatrixLineProblem::NotText))?;
    let per = dofs.per_node();
    let names: Vec<&'static str> = dofs.node_dofs().iter().map(|d| d.name()).collect();
    let mut equations: Vec<Option<usize>> = Vec::new();
    let mut taken = vec![None; node_count * per];
    for (number, line) in text.lines().enumerate().map(|(i, l)| (i + 1, l)) {
        let Some((eq, node, label, dof)) =
            mapped_line(path, (number, line), (&names, node_count, taken.len()))?
        else {
            continue;
        };
        if let Some(before) = taken[dof] {
            return Err(error(
                number,
                MatrixLineProblem::DofTwice {
                    node,
                    dof: label.into(),
                    before,
                },
            ));
        }
        taken[dof] = Some(eq);
        if equations.len() < eq {
            equations.resize(eq, None);
        }
        if equations[eq - 1].is_some() {
            return Err(error(
                number,
                MatrixLineProblem::EquationTwice { equation: eq },
            ));
        }
        equations[eq - 1] = Some(dof);
    }
    if let Some(eq) = equations.iter().position(Option::is_none) {
        return Err(error(
            0,
            MatrixLineProblem::EquationUnplaced { equation: eq + 1 },
        ));
    }
    if let Some(dof) = taken.iter().position(Option::is_none) {
        return Err(error(
            0,
            MatrixLineProblem::DofWithoutEquation {
                node: NodeIndex(dof / per).number(),
                dof: names[dof % per],
                left_out: false,
            },
        ));
    }
    Ok(equations.into_iter().map(|e| e.expect("checked")).collect())
}
