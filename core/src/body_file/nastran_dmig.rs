//! Nastran DMIG matrices in a bulk-data or punch file (`EXTSEOUT(DMIGPCH)`,
//! `PARAM,EXTOUT,DMIGPCH`, or hand-written): one named matrix picked out of the cards,
//! placed on the body's node-major DOF by the grid and component of every entry (components
//! 1–3 the translations, 4–6 the rotations; grid numbers the body's 1-based node numbers).
//!
//! Cards in small fixed field (8 columns), large field (`DMIG*`, 16 columns, continuations
//! starting `*`) or free field (commas); continuation lines start with `+`, `*` or a blank
//! first field; `$` starts a comment. Reals as Nastran writes them: `1.5E+3`, `1.5D+3`, or the
//! exponent without its letter (`1.5+3`). The header card `DMIG NAME 0 IFO TIN TOUT POLAR
//! blank NCOL` gives the form: IFO 6 symmetric (one triangle; an entry given in both is an
//! error), 1 square (read whole); TIN 1 or 2 (real). Column cards `DMIG NAME GJ CJ blank G1 C1
//! A1 B1 G2 C2 A2 B2 …` give the column's entries, four fields each. Every error names the
//! file and the line; nothing is returned half-read.

use std::collections::{BTreeSet, HashSet};

use super::{
    MatrixMarket, MatrixMarketFormat,
    matrix_bytes::{entry_value, plain_text},
    node_dof_placement::NodeDofPlacement,
};
use crate::{Result, error::MatrixLineProblem, fem::DofMap};

use super::matrix_bytes::line_error as error;

/// One field of a card and the line it stands on.
#[derive(Debug, Clone)]
struct Field {
    text: String,
    line: usize,
}

/// A bulk-data card: its name and data fields (field 2 on), continuations joined.
#[derive(Debug)]
struct Card {
    name: String,
    line: usize,
    fields: Vec<Field>,
}

impl Card {
    fn get(&self, i: usize) -> &str {
        self.fields.get(i).map(|f| f.text.as_str()).unwrap_or("")
    }
    fn line_of(&self, i: usize) -> usize {
        self.fields.get(i).map(|f| f.line).unwrap_or(self.line)
    }
}

/// Cuts `line` into fields of `widths` columns after the first 8.
fn fixed_fields(line: &str, width: usize, count: usize) -> Vec<String> {
    let chars: Vec<char> = line.chars().collect();
    (0..count)
        .map(|k| {
            let from = (8 + k * width).min(chars.len());
            let to = (8 + (k + 1) * width).min(chars.len());
            chars[from..to]
                .iter()
                .collect::<String>()
                .trim()
                .to_string()
        })
        .collect()
}

/// The cards of a bulk-data text.
fn cards(text: &str) -> Vec<Card> {
    let mut out: Vec<Card> = Vec::new();
    for (number, raw) in text.lines().enumerate().map(|(i, l)| (i + 1, l)) {
        let line = raw.split('$').next().unwrap_or("").trim_end();
        if line.trim().is_empty() {
            continue;
        }
        let free = line.contains(',');
        let first = if free {
            line.split(',').next().unwrap_or("").trim().to_string()
        } else {
            line.chars().take(8).collect::<String>().trim().to_string()
        };
        let continuation = first.is_empty() || first.starts_with('+') || first.starts_with('*');
        let large = first.ends_with('*');
        let fields: Vec<String> = if free {
            let mut f: Vec<String> = line
                .split(',')
                .skip(1)
                .map(|s| s.trim().to_string())
                .collect();
            let width = if large { 4 } else { 8 };
            f.truncate(width);
            f.resize(width, String::new());
            f
        } else if large {
            fixed_fields(line, 16, 4)
        } else {
            fixed_fields(line, 8, 8)
        };
        let fields = fields.into_iter().map(|text| Field { text, line: number });
        match (continuation, out.last_mut()) {
            (true, Some(card)) => card.fields.extend(fields),
            (true, None) => {}
            (false, _) => out.push(Card {
                name: first.trim_end_matches('*').to_ascii_uppercase(),
                line: number,
                fields: fields.collect(),
            }),
        }
    }
    out
}

/// Field `i` of `card` (in `path`), which must be an integer; `what` names it.
fn integer_field(path: &str, card: &Card, i: usize, what: &'static str) -> Result<usize> {
    card.get(i).parse().map_err(|_| {
        error(
            path,
            card.line_of(i),
            MatrixLineProblem::NotANumber {
                field: what,
                text: card.get(i).into(),
                expected: "an integer",
            },
        )
    })
}

/// Whether the DMIG matrix of `header` is symmetric (IFO 6) or square (1); complex matrices
/// (TIN 3, 4) and other forms are refused by name.
fn symmetric_kind(header: &Card, path: &str) -> Result<bool> {
    let integer = |card: &Card, i: usize, what| integer_field(path, card, i, what);
    let ifo = integer(header, 2, "IFO")?;
    let tin = integer(header, 3, "TIN")?;
    if !matches!(tin, 1 | 2) {
        return Err(error(
            path,
            header.line_of(3),
            MatrixLineProblem::Unsupported {
                field: "TIN",
                value: tin.to_string().into(),
                needs: "only real matrices (TIN 1 or 2) make a body",
            },
        ));
    }
    Ok(match ifo {
        6 => true,
        1 => false,
        other => {
            return Err(error(
                path,
                header.line_of(2),
                MatrixLineProblem::Unsupported {
                    field: "IFO",
                    value: other.to_string().into(),
                    needs: "a body's matrix is square (1) or symmetric (6)",
                },
            ));
        }
    })
}

/// Parses the DMIG matrix `matrix` of the bulk-data bytes named `path` for a body whose nodes
/// carry `dofs`; the matrix has a row per DOF of nodes 1 to the largest grid the entries name.
pub fn parse_nastran_dmig(
    bytes: &[u8],
    path: &str,
    matrix: &str,
    dofs: &DofMap,
) -> Result<MatrixMarket> {
    let text = plain_text(bytes, path)?;
    let all = cards(&text);
    let wanted = matrix.to_ascii_uppercase();
    let ours: Vec<&Card> = all
        .iter()
        .filter(|c| c.name == "DMIG" && c.get(0).to_ascii_uppercase() == wanted)
        .collect();
    let header = ours.iter().find(|c| c.get(1) == "0").ok_or_else(|| {
        let names: BTreeSet<String> = all
            .iter()
            .filter(|c| c.name == "DMIG")
            .map(|c| c.get(0).to_ascii_uppercase())
            .collect();
        error(
            path,
            0,
            MatrixLineProblem::NoSuchMatrix {
                format: "DMIG",
                wanted: (&wanted).into(),
                found: crate::error::Name::all(names),
            },
        )
    })?;
    let integer = |card: &Card, i: usize, what| integer_field(path, card, i, what);
    let symmetric = symmetric_kind(header, path)?;
    let mut placement = NodeDofPlacement::new(dofs);
    let mut entries = Vec::new();
    let mut seen = HashSet::new();
    for card in ours.iter().filter(|c| c.get(1) != "0") {
        let grid = |i: usize, placement: &mut NodeDofPlacement| -> Result<usize> {
            let node = integer(card, i, "grid")?;
            let component: usize = if card.get(i + 1).is_empty() {
                0
            } else {
                integer(card, i + 1, "component")?
            };
            placement
                .index(node, component)
                .map_err(|problem| error(path, card.line_of(i), problem))
        };
        let j = grid(1, &mut placement)?;
        let mut k = 4;
        while k < card.fields.len() {
            if card.get(k).is_empty() && card.get(k + 2).is_empty() {
                k += 4;
                continue;
            }
            let i = grid(k, &mut placement)?;
            let line = card.line_of(k + 2);
            let text = card.get(k + 2);
            let v = entry_value(text, path, line)?;
            let key = if symmetric {
                (i.max(j), i.min(j))
            } else {
                (i, j)
            };
            if !seen.insert(key) {
                return Err(error(
                    path,
                    line,
                    MatrixLineProblem::EntryTwice {
                        row: key.0 + 1,
                        col: key.1 + 1,
                        symmetric,
                    },
                ));
            }
            entries.push((i, j, v));
            k += 4;
        }
    }
    if entries.is_empty() {
        return Err(error(
            path,
            header.line,
            MatrixLineProblem::MatrixEmpty {
                matrix: wanted.into(),
            },
        ));
    }
    let n = placement.size();
    Ok(MatrixMarket {
        rows: n,
        cols: n,
        format: MatrixMarketFormat::Coordinate,
        symmetric,
        entries,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two nodes, x only in small field, y in large field, z in free field: K symmetric.
    const BULK: &str = "\
$ a hand-written punch file
DMIG        KAAX       0       6       2       0                       6
DMIG        KAAX       1       1               1       1      4.
+              2       1    -1.0
DMIG        KAAX       2       1               2       1    4.+0
DMIG*               KAAX               1               2
*                      1               2         4.0D+00
*                      2               2        -1.0D+00
DMIG*               KAAX               2               2
*                      2               2         4.0D+00
DMIG,KAAX,1,3,,1,3,1.0
DMIG,KAAX,2,3,,2,3,1.5
DMIG        MAAX       0       6       2       0                       6
DMIG        MAAX       1       1               1       1     1.0
";

    #[test]
    fn reads_every_field_format() {
        let m = parse_nastran_dmig(BULK.as_bytes(), "k.pch", "kaax", &DofMap::solid()).unwrap();
        assert_eq!((m.rows, m.cols, m.symmetric), (6, 6, true));
        let mut e = m.entries.clone();
        e.sort_by_key(|a| (a.0, a.1));
        assert_eq!(
            e,
            vec![
                (0, 0, 4.0),
                (1, 1, 4.0),
                (2, 2, 1.0),
                (3, 0, -1.0),
                (3, 3, 4.0),
                (4, 1, -1.0),
                (4, 4, 4.0),
                (5, 5, 1.5)
            ]
        );
    }

    #[test]
    fn names_the_line_of_what_is_wrong() {
        let dofs = DofMap::solid();
        let cases = [
            (
                BULK.replace("1    4.+0", "1    4.+x"),
                "k.pch:5:",
                "not a real",
            ),
            (
                BULK.replace(",2,3,,2,3,1.5", ",2,3,,2,4,1.5"),
                "k.pch:12:",
                "θx",
            ),
            (
                BULK.replace(",2,3,,2,3,1.5", ",1,1,,2,1,1.5"),
                "k.pch:12:",
                "twice",
            ),
            (
                BULK.replace(
                    "KAAX       0       6       2",
                    "KAAX       0       6       3",
                ),
                "k.pch:2:",
                "real",
            ),
        ];
        for (text, line, says) in cases {
            let e = parse_nastran_dmig(text.as_bytes(), "k.pch", "KAAX", &dofs).unwrap_err();
            let s = e.to_string();
            assert!(s.contains(line) && s.contains(says), "{s}");
        }
        let e = parse_nastran_dmig(BULK.as_bytes(), "k.pch", "KGG", &dofs).unwrap_err();
        assert!(e.to_string().contains("KAAX, MAAX"), "{e}");
    }
}
