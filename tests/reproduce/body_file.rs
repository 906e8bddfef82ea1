//! Bodies from body files: the embedded assets, import of the App. B slab against the built-in
//! one, the variety of Matrix Market files exporters write, every malformed input's named
//! error, and the export round trip.

use flexmodes::body_file::BodyFileError;
use std::path::Path;

use faer::Mat;
use flexmodes::{
    analysis::{count_zero_energy_modes, free_free_modes, reduced_modes},
    assets,
    body_file::{
        BodyFileParameters, BodyHandle, ImportedBody, example_bodies, parse_matrix_market,
        write_body, write_files,
    },
    error::CoreError as Error,
    fem::{RigidMotions, SlabParameters, slab},
    linalg::MassMatrix,
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
    scenes::{self, SceneOptions},
};

/// A fresh empty folder, removed when the test passes.
pub(crate) fn scratch(tag: &str) -> crate::scratch::Scratch {
    crate::scratch::Scratch::new(&format!("test-{tag}"))
}

pub(crate) fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// A 2-node bar along x, 1 DOF per node: K = [[k, -k], [-k, k]], lumped masses.
pub(crate) const BAR_BODY: &str = r#"
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
pub(crate) const BAR_K: &str =
    "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 4\n2 1 -4\n2 2 4\n";
pub(crate) const BAR_M: &str = "%%MatrixMarket matrix array real general\n2 1\n1\n1\n";

pub(crate) fn bar(
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
/// K of a chain 1-2-3 in x and y, node-major: springs 2 and 3 in x, 5 and 7 in y.
fn chain_k(i: usize, j: usize) -> f64 {
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
}

/// The chain's masses 1..6, one per DOF in the file's order.
const CHAIN_MASS: &str = "%%MatrixMarket matrix array real general\n6 1\n1\n2\n3\n4\n5\n6\n";

/// The chain's body file with DOF order `order` and the matrix files `k`, `m`.
fn chain_body(order: &str, k: &str, m: &str) -> String {
    format!(
        "name = \"chain\"\ndofs = [\"x\", \"y\"]\ndof_order = \"{order}\"\n[matrices]\n\
         stiffness = \"{k}\"\nmass = \"{m}\"\n[geometry]\nnodes = \"nodes.csv\"\n"
    )
}

#[test]
fn the_formats_exporters_write_all_parse_to_one_body() {
    let (k_full, body) = (chain_k, chain_body);
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
    let mass = CHAIN_MASS;
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
}

#[test]
fn a_dof_major_gzip_compressed_body_reads_as_its_node_major_twin() {
    let (k_full, body) = (chain_k, chain_body);
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
    write(&dir, "m.mtx", CHAIN_MASS);
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
