//! Abaqus matrix output (`*MATRIX GENERATE` with `*MATRIX OUTPUT, FORMAT=MATRIX INPUT`): one
//! line per stored entry, `row node, row DOF, column node, column DOF, value`, DOF 1–3 the
//! translations and 4–6 the rotations; lines starting with `*` are keywords or comments. The
//! entries are placed on the body's node-major DOF directly (the format carries its own DOF
//! map). A file holding one triangle is symmetric; one holding both is read whole. Optionally
//! gzip-compressed. Every error names the file and the line; nothing is returned half-read.

use super::{
    MatrixMarket, MatrixMarketFormat,
    matrix_bytes::{entry_value, plain_text},
    node_dof_placement::NodeDofPlacement,
};
use crate::{Result, error::MatrixLineProblem, fem::DofMap};

use super::matrix_bytes::line_error as error;

/// Parses Abaqus matrix-input bytes named `path` for a body whose nodes carry `dofs`; the
/// matrix has a row per DOF of nodes 1 to the largest node the file names.
pub fn parse_abaqus_matrix(bytes: &[u8], path: &str, dofs: &DofMap) -> Result<MatrixMarket> {
    let text = plain_text(bytes, path)?;
    let mut placement = NodeDofPlacement::new(dofs);
    let mut entries = Vec::new();
    let (mut upper, mut lower) = (false, false);
    for (number, line) in text.lines().enumerate().map(|(i, l)| (i + 1, l)) {
        let line = line.trim();
        if line.is_empty() || line.starts_with('*') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [ni, di, nj, dj, value] = fields[..] else {
            return Err(error(
                path,
                number,
                MatrixLineProblem::NotLayout {
                    text: line.into(),
                    layout: "row node, row DOF, column node, column DOF, value",
                },
            ));
        };
        let not_a_number = |field, text: &str, expected| {
            error(
                path,
                number,
                MatrixLineProblem::NotANumber {
                    field,
                    text: text.into(),
                    expected,
                },
            )
        };
        let mut index = |node: &str, dof: &str| -> Result<usize> {
            let node: usize = node
                .parse()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| not_a_number("node", node, "a node number (1, 2, ...)"))?;
            let k: usize = dof
                .parse()
                .map_err(|_| not_a_number("DOF", dof, "a DOF number (1-6)"))?;
            placement
                .index(node, k)
                .map_err(|problem| error(path, number, problem))
        };
        let (i, j) = (index(ni, di)?, index(nj, dj)?);
        let v = entry_value(value, path, number)?;
        upper |= i < j;
        lower |= i > j;
        entries.push((i, j, v));
    }
    if entries.is_empty() {
        return Err(error(path, 0, MatrixLineProblem::NoEntries));
    }
    let n = placement.size();
    Ok(MatrixMarket {
        rows: n,
        cols: n,
        format: MatrixMarketFormat::Coordinate,
        // One triangle stored: mirror it; both: the file is the whole matrix.
        symmetric: !(upper && lower),
        entries,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_NODES: &str = "\
** stiffness of two nodes, lower triangle
*MATRIX INPUT
1,1, 1,1, 4.0
2,1, 1,1, -1.0
2,1, 2,1, 4.0
1,2, 1,2, 4.0
2,2, 1,2, -1.D0
2,2, 2,2, 4.0
1,3, 1,3, 1.0
2,3, 2,3, 1.0
";

    #[test]
    fn reads_a_lower_triangle_onto_node_major_dof() {
        let m = parse_abaqus_matrix(TWO_NODES.as_bytes(), "k.mtx", &DofMap::solid()).unwrap();
        assert_eq!((m.rows, m.cols), (6, 6));
        assert!(m.symmetric);
        assert!(m.entries.contains(&(3, 0, -1.0)) && m.entries.contains(&(4, 1, -1.0)));
    }

    #[test]
    fn names_what_it_cannot_place() {
        let rotation = TWO_NODES.replace("1,3, 1,3, 1.0", "1,4, 1,4, 1.0");
        let e = parse_abaqus_matrix(rotation.as_bytes(), "k.mtx", &DofMap::solid()).unwrap_err();
        assert!(
            e.to_string().contains("k.mtx:9") && e.to_string().contains("node 1"),
            "{e}"
        );
        let temperature = TWO_NODES.replace("2,3, 2,3, 1.0", "2,11, 2,11, 1.0");
        let e = parse_abaqus_matrix(temperature.as_bytes(), "k.mtx", &DofMap::solid()).unwrap_err();
        assert!(e.to_string().contains("k.mtx:10"), "{e}");
        let short = TWO_NODES.replace("2,1, 2,1, 4.0", "2,1, 2,1");
        let e = parse_abaqus_matrix(short.as_bytes(), "k.mtx", &DofMap::solid()).unwrap_err();
        assert!(e.to_string().contains("k.mtx:5"), "{e}");
    }
}
