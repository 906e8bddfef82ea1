//! CalculiX's matrix storage (`*FREQUENCY, SOLVER=MATRIXSTORAGE`, CalculiX 2.x): the
//! stiffness in `job.sti`, the mass in `job.mas`, one stored entry per line as
//! `row column value` (1-based equation numbers, the upper triangle, 14 significant digits),
//! and the equations' nodes and DOF in `job.dof`, one line per equation as `node.dof`
//! (`12.3`: node 12, DOF 3; DOF 1–3 the translations, 4–6 the rotations). Optionally
//! gzip-compressed. Every error names the file and the line; nothing is returned half-read.

use super::{
    BodyFileError, MatrixMarket, MatrixMarketFormat,
    matrix_bytes::{entry_value, line_error as error, plain_text},
};
use crate::{
    Error, Result,
    error::MatrixLineProblem,
    fem::{DofMap, NodeIndex},
};

/// Parses a CalculiX `.sti` or `.mas` file named `path` whose equations the DOF map numbers
/// 1 to `equations`: a symmetric matrix of that size in the equations' order.
pub fn parse_calculix_matrix(bytes: &[u8], path: &str, equations: usize) -> Result<MatrixMarket> {
    let text = plain_text(bytes, path)?;
    let mut entries = Vec::new();
    for (number, line) in text.lines().enumerate().map(|(i, l)| (i + 1, l)) {
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        let [row, col, value] = fields[..] else {
            return Err(error(
                path,
                number,
                MatrixLineProblem::NotLayout {
                    text: line.trim().into(),
                    layout: "row column value",
                },
            ));
        };
        let index = |t: &str| {
            t.parse::<usize>().ok().filter(|&i| i > 0).ok_or_else(|| {
                error(
                    path,
                    number,
                    MatrixLineProblem::NotANumber {
                        field: "equation",
                        text: t.into(),
                        expected: "an equation number (1, 2, ...)",
                    },
                )
            })
        };
        let (i, j) = (index(row)?, index(col)?);
        if i > equations || j > equations {
            return Err(Error::BodyFile(BodyFileError::MatrixIndexOutOfRange {
                path: path.into(),
                line: number,
                row: i,
                col: j,
                rows: equations,
                cols: equations,
            }));
        }
        let v = entry_value(value, path, number)?;
        // CalculiX stores the couplings its elements' pattern has, zeros among them.
        if v != 0.0 {
            entries.push((i - 1, j - 1, v));
        }
    }
    if entries.is_empty() {
        return Err(error(path, 0, MatrixLineProblem::NoEntries));
    }
    Ok(MatrixMarket {
        rows: equations,
        cols: equations,
        format: MatrixMarketFormat::Coordinate,
        symmetric: true,
        entries,
    })
}

/// The equations a CalculiX `.dof` file named `path` numbers: its non-blank lines.
pub fn calculix_equation_count(bytes: &[u8], path: &str) -> Result<usize> {
    let text = plain_text(bytes, path)?;
    Ok(text.lines().filter(|l| !l.trim().is_empty()).count())
}

/// Parses a CalculiX `.dof` file named `path`: for each equation (line) its 0-based node-major
/// DOF among `node_count` nodes carrying `dofs`, checked: DOF the body has, each DOF once, and
/// every DOF of the body given an equation.
pub fn parse_calculix_dof_map(
    bytes: &[u8],
    path: &str,
    dofs: &DofMap,
    node_count: usize,
) -> Result<Vec<usize>> {
    let equations = parse_calculix_dof_map_partial(bytes, path, dofs, node_count)?;
    let per = dofs.per_node();
    let mut taken = vec![false; node_count * per];
    equations.iter().for_each(|&d| taken[d] = true);
    if let Some(dof) = taken.iter().position(|t| !t) {
        return Err(error(
            path,
            0,
            MatrixLineProblem::DofWithoutEquation {
                node: NodeIndex(dof / per).number(),
                dof: dofs.node_dofs()[dof % per].name(),
                left_out: true,
            },
        ));
    }
    Ok(equations)
}

/// [`parse_calculix_dof_map`] of a run that held some DOF (a static step's boundary
/// conditions leave them out of the equations): every check but the last.
pub fn parse_calculix_dof_map_partial(
    bytes: &[u8],
    path: &str,
    dofs: &DofMap,
    node_count: usize,
) -> Result<Vec<usize>> {
    let text = plain_text(bytes, path)?;
    let per = dofs.per_node();
    let names: Vec<&'static str> = dofs.node_dofs().iter().map(|d| d.name()).collect();
    let mut taken: Vec<Option<usize>> = vec![None; node_count * per];
    let mut equations = Vec::new();
    for (number, line) in text.lines().enumerate().map(|(i, l)| (i + 1, l)) {
        let field = line.trim();
        if field.is_empty() {
            continue;
        }
        let parsed = field
            .split_once('.')
            .and_then(|(n, d)| Some((n.parse::<usize>().ok()?, d.parse::<usize>().ok()?)));
        let Some((node, component)) = parsed else {
            return Err(error(
                path,
                number,
                MatrixLineProblem::NotLayout {
                    text: field.into(),
                    layout: "node.dof",
                },
            ));
        };
        let name = match component {
            1 => "x",
            2 => "y",
            3 => "z",
            4 => "θx",
            5 => "θy",
            6 => "θz",
            other => {
                return Err(error(
                    path,
                    number,
                    MatrixLineProblem::NotAComponent {
                        node,
                        component: other.to_string().into(),
                    },
                ));
            }
        };
        let position = names.iter().position(|n| *n == name).ok_or_else(|| {
            error(
                path,
                number,
                MatrixLineProblem::DofNotInBody {
                    node,
                    dof: component.to_string().into(),
                    body: names.clone(),
                },
            )
        })?;
        let Some(index) = NodeIndex::of_number(node).filter(|i| i.get() < node_count) else {
            return Err(error(
                path,
                number,
                MatrixLineProblem::NodeNotInBody {
                    node,
                    count: node_count,
                },
            ));
        };
        let dof = index.get() * per + position;
        let equation = equations.len() + 1;
        if let Some(before) = taken[dof] {
            return Err(error(
                path,
                number,
                MatrixLineProblem::DofTwice {
                    node,
                    dof: component.to_string().into(),
                    before,
                },
            ));
        }
        taken[dof] = Some(equation);
        equations.push(dof);
    }
    Ok(equations)
}

#[cfg(test)]
mod tests {
    use super::*;

    const STI: &str = "1 1  4.0000000000000e+00\n1 2 -1.0000000000000e+00\n2 2  4.0\n3 3 1\n\
                       4 4 1\n5 5 1\n6 6 1\n";
    const DOF: &str = "1.1\n1.2\n2.1\n1.3\n2.2\n2.3\n";

    #[test]
    fn reads_an_upper_triangle_and_places_the_equations() {
        let map = parse_calculix_dof_map(DOF.as_bytes(), "job.dof", &DofMap::solid(), 2).unwrap();
        assert_eq!(map, vec![0, 1, 3, 2, 4, 5]);
        let m = parse_calculix_matrix(STI.as_bytes(), "job.sti", 6).unwrap();
        assert!(m.symmetric);
        assert_eq!((m.rows, m.cols), (6, 6));
        assert!(m.entries.contains(&(0, 1, -1.0)));
    }

    #[test]
    fn names_the_file_and_line_of_what_it_cannot_read() {
        let e = parse_calculix_matrix(STI.replace("4.0\n", "4.x\n").as_bytes(), "job.sti", 6)
            .unwrap_err();
        assert!(e.to_string().contains("job.sti:3"), "{e}");
        let e = parse_calculix_matrix(STI.as_bytes(), "job.sti", 5).unwrap_err();
        assert!(e.to_string().contains("job.sti:7"), "{e}");
        let e = parse_calculix_matrix("1 1\n".as_bytes(), "job.sti", 5).unwrap_err();
        assert!(e.to_string().contains("job.sti:1"), "{e}");
        let e = parse_calculix_dof_map(
            DOF.replace("2.1", "3.1").as_bytes(),
            "job.dof",
            &DofMap::solid(),
            2,
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("job.dof:3") && e.to_string().contains("node 3"),
            "{e}"
        );
        let e = parse_calculix_dof_map(
            DOF.replace("2.3", "2.5").as_bytes(),
            "job.dof",
            &DofMap::solid(),
            2,
        )
        .unwrap_err();
        assert!(e.to_string().contains("job.dof:6"), "{e}");
        let e = parse_calculix_dof_map(
            DOF.replace("2.3\n", "").as_bytes(),
            "job.dof",
            &DofMap::solid(),
            2,
        )
        .unwrap_err();
        assert!(e.to_string().contains("node 2 DOF `z`"), "{e}");
    }
}
