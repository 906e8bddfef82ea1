//! Bodies from body files: the embedded assets, import of the App. B slab against the built-in
//! one, the variety of Matrix Market files exporters write, every malformed input's named
//! error, and the export round trip.

use flexmodes::body_file::BodyFileError;
use flexmodes::error::MatrixLineProblem;
use std::path::{Path, PathBuf};

use faer::Mat;
use flexmodes::{
    analysis::{count_zero_energy_modes, free_free_modes, reduced_modes},
    assets,
    body_file::{
        BodyFileParameters, BodyHandle, ImportedBody, example_bodies, parse_matrix_market,
        read_matrix_market, write_body, write_files,
    },
    error::CoreError as Error,
    fem::{RigidMotions, SlabParameters, slab},
    linalg::{MassMatrix, generalized_eigen},
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
    scenes::{self, SceneOptions},
};

/// A fresh empty folder, removed when the test passes.
fn scratch(tag: &str) -> crate::scratch::Scratch {
    crate::scratch::Scratch::new(&format!("test-{tag}"))
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// A 2-node bar along x, 1 DOF per node: K = [[k, -k], [-k, k]], lumped masses.
const BAR_BODY: &str = r#"
name = "bar"
dofs = ["x"]
[matrices]
stiffness = "k.mtx"
mass = "m.mtx"
[geometry]
nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
[node_sets]
left = [1]
"#;
const BAR_K: &str =
    "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 4\n2 1 -4\n2 2 4\n";
const BAR_M: &str = "%%MatrixMarket matrix array real general\n2 1\n1\n1\n";

fn bar(
    dir_tag: &str,
    body: &str,
    k: &str,
    m: &str,
) -> (
    crate::scratch::Scratch,
    flexmodes::error::CoreResult<ImportedBody>,
) {
    let dir = scratch(dir_tag);
    write(&dir, "body.toml", body);
    write(&dir, "k.mtx", k);
    write(&dir, "m.mtx", m);
    let path = dir.join("body.toml");
    let loaded = ImportedBody::load(path.to_str().unwrap());
    (dir, loaded)
}

#[test]
fn every_asset_loads() {
    assert!(
        assets::FILES.len() >= 14,
        "assets listed: {}",
        assets::FILES.len()
    );
    for (path, bytes) in assets::FILES {
        assert!(!bytes.is_empty(), "{path} is empty");
        if path.ends_with(".toml") {
            let text = std::str::from_utf8(bytes).unwrap();
            let _: toml::Table = toml::from_str(text).unwrap_or_else(|e| panic!("{path}: {e}"));
        } else if path.contains(".mtx") {
            let m = parse_matrix_market(bytes, path).unwrap_or_else(|e| panic!("{path}: {e}"));
            assert!(m.rows > 0 && !m.entries.is_empty(), "{path}");
        } else if path.ends_with(".gz") {
            // CalculiX's matrix files, gzipped (read by the body that names them, below).
            assert!(bytes.starts_with(&[0x1f, 0x8b]), "{path} is not gzip");
        } else {
            let text = std::str::from_utf8(bytes).unwrap();
            assert!(text.lines().count() > 1, "{path}");
        }
    }
    let bodies = assets::builtin_bodies();
    assert_eq!(bodies, vec!["app-b-slab", "l-bracket", "spun-lever"]);
    for name in bodies {
        let body = ImportedBody::load(&format!("builtin:{name}")).unwrap();
        assert!(body.has_coordinates, "{name}");
        assert_eq!(
            body.model.rigid_motions,
            RigidMotions::FromGeometry,
            "{name}"
        );
    }
}

#[test]
fn the_example_bodies_are_what_the_generators_write() {
    for (name, files) in example_bodies().unwrap() {
        for (file, bytes) in &files {
            let path = format!("bodies/{name}/{file}");
            let embedded = assets::get(&path).unwrap_or_else(|| panic!("{path} not embedded"));
            if file.ends_with(".gz") {
                let a = parse_matrix_market(embedded, &path).unwrap();
                let b = parse_matrix_market(bytes, &path).unwrap();
                assert_eq!(
                    a, b,
                    "{path}: regenerate with `cargo run --example make_assets`"
                );
            } else {
                assert!(
                    embedded == bytes.as_slice(),
                    "{path} differs from what the generator writes: regenerate with `cargo run \
                     --example make_assets`"
                );
            }
        }
    }
}

#[test]
fn the_imported_app_b_slab_is_the_built_in_one() {
    let built = slab(&SlabParameters::default());
    let imported = ImportedBody::load("builtin:app-b-slab").unwrap();
    let model = &imported.model;
    assert_eq!(model.dof_count(), 90);
    assert_eq!(model.nodes, built.nodes);
    assert_eq!(imported.node_sets["bottom_corners"], vec![16, 18, 28, 30]);
    let a = free_free_modes(&built).unwrap().hz();
    let b = free_free_modes(model).unwrap().hz();
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(&b).enumerate().skip(6) {
        assert!((x - y).abs() <= 1e-12 * x, "mode {k}: {x} vs {y}");
    }
    // And the reductions agree to the last digits too.
    let p = ReductionRequest {
        boundary_nodes: vec![16, 18, 28, 30],
        modes: ModeSelection::Count(6),
        ..Default::default()
    };
    for m in [
        Method::Guyan,
        Method::CraigBampton,
        Method::ModeCondensation,
    ] {
        let fa = reduced_modes(&built, &reduce(&built, &p.with_method(m)).unwrap())
            .unwrap()
            .hz();
        let fb = reduced_modes(model, &reduce(model, &p.with_method(m)).unwrap())
            .unwrap()
            .hz();
        assert_eq!(fa.len(), fb.len());
        for (x, y) in fa.iter().zip(&fb).skip(6) {
            assert!((x - y).abs() <= 1e-11 * x, "{m:?}: {x} vs {y}");
        }
    }
}

/// The same 3-node, 2-DOF-per-node body written the ways exporters write it.
#[test]
fn the_formats_exporters_write_all_parse_to_one_body() {
    // K of a chain 1-2-3 in x and y, node-major: springs 2 and 3 in x, 5 and 7 in y.
    let k_full = |i: usize, j: usize| -> f64 {
        let x = [[2.0, -2.0, 0.0], [-2.0, 5.0, -3.0], [0.0, -3.0, 3.0]];
        let y = [[5.0, -5.0, 0.0], [-5.0, 12.0, -7.0], [0.0, -7.0, 7.0]];
        if i % 2 != j % 2 {
            return 0.0;
        }
        let (a, b) = (i / 2, j / 2);
        if i.is_multiple_of(2) {
            x[a][b]
        } else {
            y[a][b]
        }
    };
    let body = |order: &str, k: &str, m: &str| {
        format!(
            "name = \"chain\"\ndofs = [\"x\", \"y\"]\ndof_order = \"{order}\"\n[matrices]\n\
             stiffness = \"{k}\"\nmass = \"{m}\"\n[geometry]\nnodes = \"nodes.csv\"\n"
        )
    };
    let mut lower = String::new();
    let mut count = 0;
    for j in 0..6 {
        for i in j..6 {
            if k_full(i, j) != 0.0 {
                lower.push_str(&format!("{} {} {:e}\n", i + 1, j + 1, k_full(i, j)));
                count += 1;
            }
        }
    }
    let mut general = String::new();
    let mut gcount = 0;
    for j in 0..6 {
        for i in 0..6 {
            if k_full(i, j) != 0.0 {
                // Fortran exponent style on some entries.
                let v = if (i + j) % 3 == 0 {
                    format!("{:.6E}", k_full(i, j)).replace('E', "D")
                } else {
                    format!("{}", k_full(i, j))
                };
                general.push_str(&format!("  {}\t{}   {v}\n\n", i + 1, j + 1));
                gcount += 1;
            }
        }
    }
    let mut array = String::new();
    for j in 0..6 {
        for i in j..6 {
            array.push_str(&format!("{}\n", k_full(i, j)));
        }
    }
    let variants = [
        (
            "node-major",
            format!(
                "%%MatrixMarket matrix coordinate real symmetric\n% from a test\n6 6 {count}\n{lower}"
            ),
        ),
        (
            "node-major",
            format!(
                "%%MATRIXMARKET MATRIX COORDINATE REAL GENERAL\n%comment\n\n6 6 {gcount}\n% between\n{general}"
            ),
        ),
        (
            "node-major",
            format!("%%MatrixMarket matrix array real symmetric\n6 6\n{array}"),
        ),
        (
            "node-major",
            format!("%%MatrixMarket matrix coordinate integer symmetric\n6 6 {count}\n{lower}"),
        ),
    ];
    let mass = "%%MatrixMarket matrix array real general\n6 1\n1\n2\n3\n4\n5\n6\n";
    let mut reference: Option<Mat<f64>> = None;
    for (n, (order, k)) in variants.iter().enumerate() {
        let dir = scratch("formats");
        write(&dir, "body.toml", &body(order, "k.mtx", "m.mtx"));
        write(&dir, "k.mtx", k);
        write(&dir, "m.mtx", mass);
        write(&dir, "nodes.csv", "# x y\n0 0\n1 0\n2 0\n");
        let b = ImportedBody::load(dir.join("body.toml").to_str().unwrap())
            .unwrap_or_else(|e| panic!("variant {n}: {e}"));
        let kd = b.model.k.to_dense();
        match &reference {
            None => reference = Some(kd),
            Some(r) => {
                assert_eq!(r.nrows(), kd.nrows());
                for i in 0..6 {
                    for j in 0..6 {
                        assert_eq!(r[(i, j)], kd[(i, j)], "variant {n} entry ({i}, {j})");
                    }
                }
            }
        }
    }
    let r = reference.unwrap();
    for i in 0..6 {
        for j in 0..6 {
            assert_eq!(r[(i, j)], k_full(i, j), "({i}, {j})");
        }
    }

    // Dof-major order: all x, then all y; the same body once permuted, gzip-compressed.
    let perm = |i: usize| (i % 3) * 2 + i / 3; // file index -> node-major
    let mut dm = String::new();
    let mut dcount = 0;
    for j in 0..6 {
        for i in j..6 {
            let v = k_full(perm(i), perm(j));
            if v != 0.0 {
                dm.push_str(&format!("{} {} {v}\n", i + 1, j + 1));
                dcount += 1;
            }
        }
    }
    let text = format!("%%MatrixMarket matrix coordinate real symmetric\n6 6 {dcount}\n{dm}");
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    std::io::Write::write_all(&mut gz, text.as_bytes()).unwrap();
    let dir = scratch("dof-major");
    write(&dir, "body.toml", &body("dof-major", "k.mtx.gz", "m.mtx"));
    std::fs::write(dir.join("k.mtx.gz"), gz.finish().unwrap()).unwrap();
    // Lumped masses 1..6 in dof-major order: x of nodes 1-3, then y.
    write(&dir, "m.mtx", mass);
    write(&dir, "nodes.csv", "node,x,y,z\n1,0,0,0\n2,1,0,0\n3,2,0,0\n");
    let b = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    let kd = b.model.k.to_dense();
    for i in 0..6 {
        for j in 0..6 {
            assert_eq!(kd[(i, j)], k_full(i, j), "dof-major ({i}, {j})");
        }
    }
    let MassMatrix::Lumped(d) = &b.model.m else {
        panic!("a vector is a lumped mass")
    };
    assert_eq!(d, &vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
}

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

#[test]
fn a_body_without_coordinates_reduces_but_does_not_draw() {
    let body_text = BAR_BODY.replace(
        "[geometry]\nnodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n",
        "",
    );
    // Three nodes in a chain so an interior remains.
    let k = "%%MatrixMarket matrix coordinate real symmetric\n3 3 5\n1 1 4\n2 1 -4\n2 2 8\n3 2 -4\n3 3 4\n";
    let m = "%%MatrixMarket matrix array real general\n3 1\n1\n1\n1\n";
    let (_, r) = bar("nocoords", &body_text, k, m);
    let body = r.unwrap();
    assert!(!body.has_coordinates);
    assert_eq!(body.model.rigid_motions, RigidMotions::Unknown);
    assert!(matches!(
        body.require_coordinates().unwrap_err(),
        Error::BodyFile(BodyFileError::NoCoordinates { .. })
    ));
    // A free bar along x: one zero-energy mode among its three, counted without coordinates.
    let count = count_zero_energy_modes(&body.model, 2).unwrap();
    assert_eq!(count.zero_modes, 1);
    // ω² of a free 3-mass chain with springs 4: 4 and 12 (rad/s)².
    let hz = count.elastic_hz();
    let expect = [4.0f64.sqrt(), 12.0f64.sqrt()].map(|w| w / (2.0 * std::f64::consts::PI));
    assert_eq!(hz.len(), 2);
    for (a, b) in hz.iter().zip(expect) {
        assert!((a - b).abs() < 1e-12 * b, "{a} vs {b}");
    }
    let opts = SceneOptions {
        body: Some(BodyHandle(std::sync::Arc::new(body))),
        boundary: Some(vec![1]),
        modes: Some(1),
        methods: Some(vec![Method::CraigBampton, Method::Guyan]),
        ..Default::default()
    };
    let out = scenes::find("modes").unwrap().execute(&opts).unwrap();
    assert_eq!(out.report.result("zero_energy_modes").unwrap(), 1);
    assert!(
        out.visuals.iter().all(
            |v| matches!(v, flexmodes::record::Visual::SeriesBars { path, .. }
                if path.starts_with("hz/"))
        ),
        "only the frequency bars are logged without coordinates"
    );
}

#[test]
fn a_mechanism_is_named_with_its_zero_energy_count() {
    // Two slabs side by side, not connected: 12 zero-energy modes.
    let one = slab(&SlabParameters::default());
    let n = one.dof_count();
    let mut two = one.clone();
    let shifted: Vec<[f64; 3]> = one
        .nodes
        .iter()
        .map(|p| [p[0] + 10.0, p[1], p[2]])
        .collect();
    two.nodes.extend(shifted);
    let k1 = one.k.to_dense();
    let mut entries = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if k1[(i, j)] != 0.0 {
                entries.push((i, j, k1[(i, j)]));
                entries.push((i + n, j + n, k1[(i, j)]));
            }
        }
    }
    two.k = flexmodes::linalg::SparseSymmetric::from_triplets(2 * n, &entries);
    let MassMatrix::Lumped(d) = &one.m else {
        panic!()
    };
    two.m = MassMatrix::Lumped([d.as_slice(), d.as_slice()].concat());
    two.edges.clear();
    let files = write_body(
        &two,
        &BodyFileParameters {
            description: "two loose slabs".into(),
            ..Default::default()
        },
    )
    .unwrap();
    let dir = scratch("mechanism");
    write_files(&dir, &files).unwrap();
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    let e = flexmodes::models::import_summary(&body).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Mechanism {
                zero_modes: 12,
                rigid: 6,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn example_bodies_reduce_with_every_method_and_ritz_bounds_hold() {
    for name in ["app-b-slab", "l-bracket"] {
        let body = ImportedBody::load(&format!("builtin:{name}")).unwrap();
        let model = &body.model;
        let boundary = body.default_interface_nodes().unwrap().to_vec();
        let full = count_zero_energy_modes(model, 10).unwrap();
        assert_eq!(full.zero_modes, 6, "{name}");
        let p = ReductionRequest {
            boundary_nodes: boundary.clone(),
            modes: ModeSelection::Count(6),
            ..Default::default()
        };
        for m in [
            Method::Guyan,
            Method::ModalTruncation,
            Method::CraigBampton,
            Method::ModeCondensation,
        ] {
            let basis = reduce(model, &p.with_method(m)).unwrap();
            let red = reduced_modes(model, &basis).unwrap();
            // Rayleigh–Ritz: the k-th reduced eigenvalue bounds the k-th full one from above.
            let count = full.modes.values.len().min(red.values.len());
            assert!(count >= 12, "{name} {m:?}: {count}");
            let scale = full.modes.values[count - 1];
            for k in 0..count {
                assert!(
                    red.values[k] >= full.modes.values[k] - 1e-7 * scale,
                    "{name} {m:?} mode {k}: {} < {}",
                    red.values[k],
                    full.modes.values[k]
                );
            }
        }
    }
}

#[test]
fn export_round_trip_gives_the_same_frequencies() {
    let body = ImportedBody::load("builtin:l-bracket").unwrap();
    let scratch_dir = scratch("export");
    let dir = scratch_dir.join("cb");
    let boundary = body.boundary(&["bolt_hole".into()]).unwrap();
    let summary = flexmodes::export::export(
        &body,
        Method::CraigBampton,
        &boundary,
        8,
        &dir,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(summary.shape, [1314, 24 * 3 + 8]);
    assert_eq!(summary.zero_energy, 6);
    assert_eq!(summary.residuals.len(), summary.hz.len());
    assert!(summary.residuals.iter().all(|&r| r < 1e-8));
    let read = |f: &str| {
        let mm = read_matrix_market(&dir.join(f)).unwrap();
        let mut a = Mat::<f64>::zeros(mm.rows, mm.cols);
        for (i, j, v) in mm.expanded() {
            a[(i, j)] = v;
        }
        a
    };
    let (k, m) = (read("k_r.mtx"), read("m_r.mtx"));
    let (rows, cols, values) =
        flexmodes::body_file::read_npy(&std::fs::read(dir.join("psi.npy")).unwrap()).unwrap();
    assert_eq!(values.len(), rows * cols);
    let psi = Mat::from_fn(rows, cols, |i, j| values[j * rows + i]);
    // In memory, independently of the files.
    let basis = reduce(
        &body.model,
        &ReductionRequest {
            method: Method::CraigBampton,
            boundary_nodes: boundary,
            modes: ModeSelection::Count(8),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(
        (psi.nrows(), psi.ncols()),
        (basis.psi.nrows(), basis.psi.ncols())
    );
    for j in 0..psi.ncols() {
        for i in 0..psi.nrows() {
            assert_eq!(psi[(i, j)], basis.psi[(i, j)], "Ψ is written exactly");
        }
    }
    let from_files = generalized_eigen(k.as_ref(), m.as_ref(), "re-imported")
        .unwrap()
        .hz();
    let in_memory = reduced_modes(&body.model, &basis).unwrap().hz();
    assert_eq!(from_files.len(), in_memory.len());
    for (a, b) in from_files.iter().zip(&in_memory).skip(6) {
        assert!((a - b).abs() <= 1e-12 * b, "{a} vs {b}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("model.json")).unwrap()).unwrap();
    let hz = json["reduced_elastic_hz"].as_array().unwrap();
    assert_eq!(hz.len(), from_files.len() - 6);
    assert!((hz[0].as_f64().unwrap() - from_files[6]).abs() < 1e-6 * from_files[6]);
    assert_eq!(json["columns"].as_array().unwrap().len(), 80);
    // The rigid-body mass matrix: total mass on the translations, M symmetric positive.
    let mass = json["inertia"]["mass"].as_f64().unwrap();
    assert!((mass - body.model.total_mass()).abs() < 1e-12 * mass);
    // A second export replaces the folder as a whole; no temporary folder is left.
    let base_end = body.boundary(&["base_end".into()]).unwrap();
    let text = flexmodes::export::ExportParameters {
        psi_format: flexmodes::export::PsiFormat::MatrixMarket,
        ..Default::default()
    };
    flexmodes::export::export(&body, Method::Guyan, &base_end, 0, &dir, &text).unwrap();
    // Ψ as Matrix Market text when asked, the same numbers.
    let guyan_psi = read("psi.mtx");
    assert_eq!(guyan_psi.ncols(), base_end.len() * 3);
    assert!(!dir.join("psi.npy").exists());
    let leftovers: Vec<_> = std::fs::read_dir(dir.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(leftovers, vec!["cb".to_string()]);
}

#[test]
fn the_app_b_bricks_and_the_plank_set_up_are_read_from_the_assets() {
    let printed = crate::common::asset_rows("thesis/slab-bricks-app-b.txt");
    let bricks = flexmodes::fem::slab_bricks(&SlabParameters::default());
    assert_eq!(printed.len(), 8);
    assert_eq!(bricks.len(), printed.len());
    for (b, row) in bricks.iter().zip(&printed) {
        let one_based: Vec<f64> = b.iter().map(|&n| (n + 1) as f64).collect();
        assert_eq!(&one_based, row);
    }
    let setup = flexmodes::models::plank_setup();
    assert_eq!(setup.hanging_nodes, [3, 15]);
    assert_eq!((setup.force_node, setup.force), (22, 250.0));
    assert_eq!((setup.link_length, setup.link_mass), (2.0, 1.0));
    // The defaults the thesis bodies are built with come from the same files.
    let beam = flexmodes::fem::BeamParameters::default();
    assert_eq!((beam.elements, beam.second_moment), (4, 1.0417e-6));
    let s = SlabParameters::default();
    assert_eq!(
        (s.bricks, s.total_mass, s.poisson_ratio),
        ([4, 2, 1], 62.4, 0.33)
    );
}

/// A body written back (`convert`) keeps its units, node sets and declared interfaces: the
/// flanged hub (mm–t–s) with an rbe2 joint at a given master and an rbe3 ring with weights
/// reads back with the same interfaces, units and matrices.
#[test]
fn a_body_written_back_keeps_its_units_and_interfaces() {
    use flexmodes::body_file::{InterfaceKind, InterfaceSpec, write_imported_body};
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/flange-hub/body.toml");
    let mut body = ImportedBody::load(path.to_str().unwrap()).unwrap();
    let bolt = body.node_sets["bolt_1"].len();
    body.interfaces.insert(
        "joint".into(),
        InterfaceSpec {
            kind: InterfaceKind::Rbe2,
            node_set: "bore".into(),
            master: Some([0.5, -0.25, 20.0]),
            weights: None,
        },
    );
    body.interfaces.insert(
        "sensor".into(),
        InterfaceSpec {
            kind: InterfaceKind::Rbe3,
            node_set: "bolt_1".into(),
            master: None,
            weights: Some((0..bolt).map(|k| 1.0 + 0.125 * k as f64).collect()),
        },
    );
    let dir = scratch("written-back");
    write_files(
        &dir,
        &write_imported_body(&body, true, Default::default()).unwrap(),
    )
    .unwrap();
    let back = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    assert_eq!(back.interfaces, body.interfaces);
    assert_eq!(back.units, body.units);
    assert_eq!(back.node_sets, body.node_sets);
    assert_eq!(back.model.k.nnz(), body.model.k.nnz());
    let (a, b) = (back.model.k.diagonal(), body.model.k.diagonal());
    assert!(
        a.iter().zip(&b).all(|(x, y)| x == y),
        "K written in round-trip form"
    );
}

/// A body handed over in memory (Python's `flexmodes.Body`) is the body its file gives: the
/// L-bracket's K and M as one triangle, as the full symmetric matrix and in any entry order
/// give its frequencies to round-off; each bad input is refused by name with its data.
#[test]
fn a_body_from_matrices_equals_its_body_file_and_is_checked_alike() {
    use flexmodes::body_file::{BodyMatrices, MatrixEntries, lower_entries, mass_lower_entries};
    let file = ImportedBody::load("builtin:l-bracket").unwrap();
    let model = &file.model;
    let n = model.dof_count();
    let k_lower = lower_entries(&model.k);
    let m_lower = mass_lower_entries(&model.m);
    let full = |lower: &[(usize, usize, f64)]| -> Vec<(usize, usize, f64)> {
        let mut out = Vec::new();
        for &(i, j, v) in lower.iter().rev() {
            out.push((j, i, v));
            if i != j {
                out.push((i, j, v));
            }
        }
        out
    };
    let square = |entries: Vec<(usize, usize, f64)>| MatrixEntries {
        rows: n,
        cols: n,
        entries,
    };
    let given = |k: Vec<_>, m: Vec<_>| BodyMatrices {
        name: "bracket".into(),
        stiffness: square(k),
        mass: square(m),
        nodes: Some(model.nodes.clone()),
        node_sets: file.node_sets.clone(),
        default_interface: file.default_interface.clone(),
        ..BodyMatrices::default()
    };
    let reference = count_zero_energy_modes(model, 8).unwrap().elastic_hz();
    for (k, m) in [
        (k_lower.clone(), m_lower.clone()),
        (full(&k_lower), full(&m_lower)),
    ] {
        let body = ImportedBody::from_matrices(given(k, m)).unwrap();
        assert_eq!(body.model.dof_count(), n);
        assert_eq!(body.model.rigid_motions, RigidMotions::FromGeometry);
        assert_eq!(
            body.default_interface_nodes().unwrap(),
            file.default_interface_nodes().unwrap()
        );
        let hz = count_zero_energy_modes(&body.model, 8)
            .unwrap()
            .elastic_hz();
        for (a, b) in hz.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-10 * b, "{a} against {b}");
        }
    }
    let kind = |e: Error| match e {
        Error::BodyFile(b) => b,
        other => panic!("not a body error: {other}"),
    };
    // A NaN, named by its place in the entry list.
    let mut k = k_lower.clone();
    k[9].2 = f64::NAN;
    match kind(ImportedBody::from_matrices(given(k, m_lower.clone())).unwrap_err()) {
        BodyFileError::NonFiniteEntry { line, path, .. } => {
            assert_eq!(line, 10);
            assert_eq!(path, std::path::Path::new("K of bracket"));
        }
        other => panic!("{other}"),
    }
    // Both triangles, not symmetric: the worst entry, 1-based.
    let mut k = full(&k_lower);
    let at = k.iter().position(|&(i, j, _)| i == 40 && j == 3).unwrap();
    k[at].2 += 1e-3 * k_lower.iter().fold(0.0f64, |a, e| a.max(e.2.abs()));
    match kind(ImportedBody::from_matrices(given(k, m_lower.clone())).unwrap_err()) {
        BodyFileError::NotSymmetric { row, col, .. } => {
            assert_eq!((row.min(col), row.max(col)), (4, 41))
        }
        other => panic!("{other}"),
    }
    // A node set past the last node; an index past the matrix.
    let mut sets = given(k_lower.clone(), m_lower.clone());
    sets.node_sets.insert("far".into(), vec![1, n / 3 + 1]);
    match kind(ImportedBody::from_matrices(sets).unwrap_err()) {
        BodyFileError::NodeSetOutOfRange { node, .. } => assert_eq!(node, n / 3 + 1),
        other => panic!("{other}"),
    }
    let mut k = k_lower.clone();
    k.push((n, 0, 1.0));
    assert!(matches!(
        kind(ImportedBody::from_matrices(given(k, m_lower)).unwrap_err()),
        BodyFileError::MatrixIndexOutOfRange { row, .. } if row == n + 1
    ));
}
