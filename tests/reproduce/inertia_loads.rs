//! A body's own inertia loads: the residual vectors that carry them into every reduced basis,
//! the a-priori estimate that predicts what a basis without them misses, and the geometry
//! check that keeps rigid rings from being tied to coordinates K was not made from. On bodies
//! CalculiX wrote (assets/bodies/spun-lever, tests/corpus/ccx-block).

use flexmodes::{
    Progress,
    body_file::ImportedBody,
    dynamics::DrivenIntegration,
    models::{DrivenBodyParameters, DrivenRun, driven_body_study, import_summary},
    reduction::Method,
};

const LEVER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bodies/spun-lever");

fn lever() -> ImportedBody {
    ImportedBody::load(&format!("{LEVER}/body.toml")).unwrap()
}

/// The lever driven at its root for 0.2 s (a 0.1 s ramp), CB, MT and MC with two modes.
fn runs(body: &ImportedBody, tweak: impl Fn(&mut DrivenBodyParameters)) -> Vec<DrivenRun> {
    let mut parameters = DrivenBodyParameters {
        drive: "rbe2:root".into(),
        rate: 1000.0,
        ramp: 0.1,
        integration: DrivenIntegration {
            step: 2e-4,
            end: 0.2,
            spectral_radius: 0.9,
            output_every: 10,
        },
        ..Default::default()
    };
    tweak(&mut parameters);
    let methods = [
        Method::CraigBampton,
        Method::ModalTruncation,
        Method::ModeCondensation,
    ];
    driven_body_study(body, &parameters, &methods, &[2], true, &Progress::new())
        .unwrap()
        .runs
}

/// Spun up to 1 000 rad/s, shaken along x and y, and spun slowly under gravity, the lever's
/// reduced models with two fixed-interface modes miss their arm's quasi-static stretch
/// (history error above 1e-2 spun up); with the residual vectors of the twelve unit inertia
/// loads every one is within 1e-3 of the full body. The a-priori estimate (the drive's loads'
/// static share outside the basis) is 1e-6 or less with them and above 1e-2 without, so it
/// ranks the models as their history errors do.
#[test]
fn residual_vectors_carry_the_inertia_loads_of_every_drive() {
    let body = lever();
    type Motion = (&'static str, fn(&mut DrivenBodyParameters));
    let motions: [Motion; 3] = [
        ("spin-up", |_| {}),
        ("shake", |p| {
            p.rate = 0.0;
            p.shake = Some(([1.0, 1.0, 0.0], 1e-4, 200.0));
        }),
        ("gravity", |p| {
            p.rate = 50.0;
            p.gravity = Some([0.0, -9.81, 0.0]);
        }),
    ];
    for (name, motion) in motions {
        let with = runs(&body, motion);
        let without = runs(&body, |p| {
            motion(p);
            p.residual_vectors = false;
        });
        assert!(with[0].method.is_none() && without[0].method.is_none());
        for (a, b) in with[1..].iter().zip(&without[1..]) {
            assert_eq!(a.label(), b.label());
            assert!(
                a.residual_vectors >= 9,
                "{name} {}: {}",
                a.label(),
                a.residual_vectors
            );
            assert_eq!(b.residual_vectors, 0);
            assert_eq!(a.coordinates, b.coordinates + a.residual_vectors);
            let (ea, eb) = (a.history_error.unwrap(), b.history_error.unwrap());
            let (pa, pb) = (a.estimate_max().unwrap(), b.estimate_max().unwrap());
            println!(
                "{name} {}: history error {ea:.2e} with {} RV (estimate {pa:.1e}), {eb:.2e} \
                 without (estimate {pb:.1e})",
                a.label(),
                a.residual_vectors
            );
            assert!(ea <= 1e-3, "{name} {}: {ea}", a.label());
            assert!(pa <= 1e-6 && pb > 1e-2, "{name} {}: {pa} {pb}", a.label());
            assert!(ea < eb, "{name} {}: {ea} {eb}", a.label());
            if name == "spin-up" {
                assert!(eb > 1e-2, "{name} {}: {eb}", a.label());
            }
        }
    }
}

/// CalculiX's block with one node nudged by 1 % of an element's size: its coordinates' rigid
/// motions are not K's null space; `import` names that node first, and a reduction that ties
/// a ring by those coordinates is refused with the defect and the nodes. The block as
/// CalculiX wrote it imports clean and reduces.
#[test]
fn coordinates_that_disagree_with_the_stiffness_are_named() {
    use flexmodes::models::{BodyInterfaces, BodyReducer};
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/corpus/ccx-block");
    let clean = ImportedBody::load(&format!("{dir}/body.toml")).unwrap();
    let (value, text) = import_summary(&clean).unwrap();
    assert!(value["geometry_disagrees"].is_null(), "{value}");
    assert!(!text.contains("WARNING, geometry"), "{text}");

    let scratch = super::scratch::Scratch::new("nudged");
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_file() {
            std::fs::copy(entry.path(), scratch.join(entry.file_name())).unwrap();
        }
    }
    // Node 400 (not on the bore) moved by 0.12 mm, 1 % of the 12 mm mesh.
    let nodes = std::fs::read_to_string(scratch.join("nodes.csv")).unwrap();
    let nudged: Vec<String> = nodes
        .lines()
        .map(
            |line| match line.split(',').collect::<Vec<_>>().as_slice() {
                ["400", x, y, z] => format!("400,{},{y},{z}", x.parse::<f64>().unwrap() + 0.12),
                _ => line.to_string(),
            },
        )
        .collect();
    std::fs::write(scratch.join("nodes.csv"), nudged.join("\n") + "\n").unwrap();
    let body = ImportedBody::load(scratch.join("body.toml").to_str().unwrap()).unwrap();
    let (value, text) = import_summary(&body).unwrap();
    let named = &value["geometry_disagrees"];
    assert!(!named.is_null(), "{value}");
    assert_eq!(named["nodes"][0]["node"], 400, "{named}");
    assert!(
        text.contains("WARNING, geometry") && text.contains("400 ("),
        "{text}"
    );
    let zero = flexmodes::analysis::count_zero_energy_modes(&body.model, 1).unwrap();
    let interfaces = BodyInterfaces::of(&body, &["rbe2:bore".to_string()], None).unwrap();
    let refused = BodyReducer::new(&body.model, interfaces, &zero, 0.0, Progress::new())
        .err()
        .expect("a ring tied by the nudged coordinates is refused");
    let message = refused.to_string();
    assert!(
        message.contains("disagree with the stiffness") && message.contains("400"),
        "{message}"
    );
    let zero = flexmodes::analysis::count_zero_energy_modes(&clean.model, 1).unwrap();
    let interfaces = BodyInterfaces::of(&clean, &["rbe2:bore".to_string()], None).unwrap();
    assert!(BodyReducer::new(&clean.model, interfaces, &zero, 0.0, Progress::new()).is_ok());
}
