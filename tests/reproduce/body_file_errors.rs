//! Every malformed body input's named error: matrix files with their file and line,
//! inconsistent matrices with their data, body files and tables.

use flexmodes::body_file::BodyFileError;
use flexmodes::error::MatrixLineProblem;

use flexmodes::{body_file::ImportedBody, error::CoreError as Error};

use super::body_file::{BAR_BODY, BAR_K, BAR_M, bar, scratch, write};

#[test]
fn malformed_matrix_files_give_named_errors_with_file_and_line() {
    // Header that is not real.
    let (_, r) = bar("hdr", BAR_BODY, &BAR_K.replace("real", "complex"), BAR_M);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MatrixMarketHeader { line: 1, .. })
        ),
        "{e}"
    );
    assert!(e.to_string().contains("k.mtx:1"), "{e}");
    let (_, r) = bar(
        "pattern",
        BAR_BODY,
        &BAR_K.replace("real", "pattern"),
        BAR_M,
    );
    assert!(matches!(
        r.unwrap_err(),
        Error::BodyFile(BodyFileError::MatrixMarketHeader { .. })
    ));

    // A line that does not parse.
    let (_, r) = bar("line", BAR_BODY, &BAR_K.replace("2 1 -4", "2 1 -4x"), BAR_M);
    let e = r.unwrap_err();
    match &e {
        Error::BodyFile(BodyFileError::MatrixLine {
            line: 4,
            problem:
                MatrixLineProblem::NotANumber {
                    field: "value",
                    text,
                    ..
                },
            ..
        }) => assert_eq!(text, "-4x"),
        _ => panic!("{e}"),
    }
    assert!(e.to_string().contains("k.mtx:4"), "{e}");

    // A field of a megabyte (a binary file saved as .mtx): quoted in part, on one line.
    let long = format!("-4{}", "x".repeat(1 << 20));
    let (_, r) = bar(
        "long",
        BAR_BODY,
        &BAR_K.replace("2 1 -4", &format!("2 1 {long}")),
        BAR_M,
    );
    let e = r.unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("k.mtx:4") && message.contains("-4xxx") && message.contains('…'),
        "{message:.300}"
    );
    assert!(
        message.len() < 400,
        "{} bytes: {message:.300}",
        message.len()
    );
}

#[test]
fn matrix_entries_out_of_range_miscounted_or_not_finite_are_named_with_file_and_line() {
    // An index out of range.
    let (_, r) = bar(
        "range",
        BAR_BODY,
        &BAR_K.replace("2 2 4\n", "3 2 4\n"),
        BAR_M,
    );
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MatrixIndexOutOfRange {
                line: 5,
                row: 3,
                col: 2,
                rows: 2,
                ..
            })
        ),
        "{e}"
    );

    // Fewer entries than promised, and more.
    let (_, r) = bar("short", BAR_BODY, &BAR_K.replace("2 2 3", "2 2 4"), BAR_M);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MatrixLine {
                line: 2,
                problem: MatrixLineProblem::EndsEarly {
                    what: "entries",
                    read: 3,
                    expected: 4
                },
                ..
            })
        ),
        "{e}"
    );
    let (_, r) = bar("long", BAR_BODY, &format!("{BAR_K}1 1 1\n"), BAR_M);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MatrixLine {
                line: 6,
                problem: MatrixLineProblem::TooMany { expected: 3, .. },
                ..
            })
        ),
        "{e}"
    );

    // NaN and Inf.
    let (_, r) = bar("nan", BAR_BODY, &BAR_K.replace("2 2 4", "2 2 NaN"), BAR_M);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::NonFiniteEntry { line: 5, .. })
        ),
        "{e}"
    );
    let (_, r) = bar("inf", BAR_BODY, &BAR_K.replace("1 1 4", "1 1 inf"), BAR_M);
    assert!(matches!(
        r.unwrap_err(),
        Error::BodyFile(BodyFileError::NonFiniteEntry { line: 3, .. })
    ));
}

/// Matrices that parse but do not describe the body: sizes, symmetry, a mass that is not
/// positive definite.
#[test]
fn inconsistent_matrices_give_named_errors_with_their_data() {
    // K and M of different sizes.
    let m3 = "%%MatrixMarket matrix array real general\n3 1\n1\n1\n1\n";
    let (_, r) = bar("size", BAR_BODY, BAR_K, m3);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MatrixSizeMismatch {
                rows: 3,
                cols: 1,
                ..
            })
        ),
        "{e}"
    );
    // K not matching the nodes and DOF map.
    let (_, r) = bar(
        "map",
        &BAR_BODY.replace("[\"x\"]", "[\"x\", \"y\"]"),
        BAR_K,
        BAR_M,
    );
    assert!(matches!(
        r.unwrap_err(),
        Error::BodyFile(BodyFileError::MatrixSizeMismatch { .. })
    ));

    // K not symmetric: the largest asymmetry, where.
    let asym =
        "%%MatrixMarket matrix coordinate real general\n2 2 4\n1 1 4\n2 1 -4\n1 2 -3\n2 2 4\n";
    let (_, r) = bar("asym", BAR_BODY, asym, BAR_M);
    let e = r.unwrap_err();
    match &e {
        Error::BodyFile(BodyFileError::NotSymmetric {
            asymmetry,
            row,
            col,
            ..
        }) => {
            assert!((asymmetry - 0.25).abs() < 1e-12, "{e}");
            assert_eq!((row.min(col), row.max(col)), (&1, &2));
        }
        _ => panic!("{e}"),
    }
    // ... while round-off asymmetry is accepted and averaged away.
    let nearly = asym.replace("1 2 -3", "1 2 -4.0000000001");
    let (_, r) = bar("nearly", BAR_BODY, &nearly, BAR_M);
    let k = r.unwrap().model.k.to_dense();
    assert_eq!(k[(0, 1)], k[(1, 0)]);

    // M not positive definite: which DOF.
    let zero_second = "%%MatrixMarket matrix array real general\n2 1\n1\n0\n";
    let (_, r) = bar("mass", BAR_BODY, BAR_K, zero_second);
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MassNotPositive { dof: 2, .. })
        ),
        "{e}"
    );
    assert!(e.to_string().contains("node 2 x"), "{e}");
    let indefinite =
        "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 1\n2 1 2\n2 2 1\n";
    let (_, r) = bar("indef", BAR_BODY, BAR_K, indefinite);
    // The second pivot, 1 - 2²/1 < 0 (faer's 1-based simplicial index mapped to the DOF).
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::MassNotPositive { dof: 2, .. })
        ),
        "{e}"
    );
}

/// A body file's own mistakes: node sets, missing files, TOML, DOF names, set names.
#[test]
fn malformed_body_files_give_named_errors() {
    // A node set naming a missing node.
    let (_, r) = bar(
        "set",
        &BAR_BODY.replace("left = [1]", "left = [1, 3]"),
        BAR_K,
        BAR_M,
    );
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::NodeSetOutOfRange {
                node: 3,
                count: 2,
                ..
            })
        ),
        "{e}"
    );

    // A missing file, a TOML error with its line, an unknown DOF name.
    let (_, r) = bar(
        "missing",
        &BAR_BODY.replace("m.mtx", "nothere.mtx"),
        BAR_K,
        BAR_M,
    );
    let e = r.unwrap_err();
    assert!(
        matches!(e, Error::Io { ref path, .. } if path.ends_with("nothere.mtx")),
        "{e}"
    );
    let (_, r) = bar(
        "toml",
        &BAR_BODY.replace("[matrices]", "[matrices\n"),
        BAR_K,
        BAR_M,
    );
    let e = r.unwrap_err();
    assert!(
        matches!(
            e,
            Error::BodyFile(BodyFileError::BodyFile { line: Some(4), .. })
        ),
        "{e}"
    );
    let (_, r) = bar("dof", &BAR_BODY.replace("[\"x\"]", "[\"q\"]"), BAR_K, BAR_M);
    assert!(matches!(
        r.unwrap_err(),
        Error::BodyFile(BodyFileError::BodyFile { .. })
    ));
    let (_, r) = bar(
        "unknown-key",
        &format!("{BAR_BODY}\n[extra]\na = 1\n"),
        BAR_K,
        BAR_M,
    );
    assert!(matches!(
        r.unwrap_err(),
        Error::BodyFile(BodyFileError::BodyFile { .. })
    ));

    // A set name that is not defined, given as boundary.
    let (_, r) = bar("ok", BAR_BODY, BAR_K, BAR_M);
    let body = r.unwrap();
    let e = body.boundary(&["right".into()]).unwrap_err();
    assert!(
        matches!(e, Error::BodyFile(BodyFileError::UnknownNodeSet { .. })),
        "{e}"
    );
    assert_eq!(
        body.boundary(&["left".into(), "2".into()]).unwrap(),
        vec![1, 2]
    );
}

/// A node or edge table's bad line is named by file, line and what is wrong there, as data.
#[test]
fn bad_table_lines_are_named_with_their_data() {
    use flexmodes::error::TableProblem;
    let tabled = BAR_BODY.replace(
        "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]",
        "nodes = \"nodes.csv\"\nedges = \"edges.csv\"",
    );
    let cases: [(&str, &str, usize, TableProblem); 5] = [
        (
            "x,y,z\n0,0,0\n1,0,zero\n",
            "1 2\n",
            3,
            TableProblem::NotNumbers {
                text: "1,0,zero".into(),
            },
        ),
        (
            "1,0,0,0\n3,1,0,0\n",
            "1 2\n",
            2,
            TableProblem::NodeNumberOutOfOrder {
                expected: 2,
                found: 3.0,
            },
        ),
        (
            "0\n1\n",
            "1 2\n",
            1,
            TableProblem::CoordinateCount { values: 1 },
        ),
        ("0,0,0\n1,0,0\n", "1 2\n2\n", 2, TableProblem::EdgeTooShort),
        (
            "0,0,0\n1,0,0\n",
            "1 3\n",
            1,
            TableProblem::NodeOutOfRange { node: 3, count: 2 },
        ),
    ];
    for (i, (nodes, edges, line, problem)) in cases.into_iter().enumerate() {
        let dir = scratch(&format!("table-{i}"));
        write(&dir, "body.toml", &tabled);
        write(&dir, "k.mtx", BAR_K);
        write(&dir, "m.mtx", BAR_M);
        write(&dir, "nodes.csv", nodes);
        write(&dir, "edges.csv", edges);
        let e = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap_err();
        let file = if i < 3 { "nodes.csv" } else { "edges.csv" };
        match &e {
            Error::BodyFile(BodyFileError::TableLine {
                path,
                line: found_line,
                problem: found,
            }) => {
                assert!(path.ends_with(file), "{e}");
                assert_eq!((*found_line, found), (line, &problem), "{e}");
            }
            other => panic!("case {i}: not a table line: {other}"),
        }
        assert!(e.to_string().contains(&format!("{file}:{line}: ")), "{e}");
    }
}
