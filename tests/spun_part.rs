//! A real-size spun part written by CalculiX: the steel bell crank of
//! `assets/generate/corpus.py` (`ccx-bell-crank`: gmsh C3D10, 31 833 DOF, two arms radial to
//! its pivot, K, M and the stiffness spun at 1 000 rad/s about the pivot written by CalculiX
//! 2.20, its prestressed frequencies at 1 000 and 2 000 rad/s by CalculiX). ~2 min to write,
//! ~15 min to run in release on two cores (eight integrations of the full body), so it lives
//! in its own binary, which CI does not build:
//!
//! ```sh
//! python3 assets/generate/corpus.py --out target/parts --only ccx-bell-crank
//! FLEXMODES_SPUN_PART=target/parts/ccx-bell-crank cargo test --release --test spun_part -- \
//!     --ignored --nocapture
//! ```

use std::path::PathBuf;

use flexmodes::{
    Progress,
    body_file::ImportedBody,
    dynamics::DrivenIntegration,
    models::{
        BodyCampbellParameters, DrivenBodyParameters, DrivenRun, body_campbell, driven_body_study,
    },
    reduction::Method,
};

fn part() -> (ImportedBody, serde_json::Value) {
    let dir = PathBuf::from(
        std::env::var("FLEXMODES_SPUN_PART")
            .expect("FLEXMODES_SPUN_PART names the folder corpus.py --only ccx-bell-crank wrote"),
    );
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json")).unwrap())
            .unwrap();
    (body, reference)
}

#[path = "external/checks.rs"]
#[allow(dead_code)]
mod checks;
use checks::ascending;

/// The Campbell table of the whole part, without `--axis-point` (the frame on the preload's
/// axis, the pivot's ring coaxial with it): NR (sparse, Sturm-checked) and CB 20 with its
/// residual vectors within 2e-4 of CalculiX's four lowest prestressed frequencies at Ω₀ and
/// 2Ω₀; every curve carried from rate to rate by a MAC above 0.9.
#[test]
#[ignore = "needs the generated part: FLEXMODES_SPUN_PART=DIR (see the module doc)"]
fn campbell_of_a_real_part_matches_calculix() {
    let (body, reference) = part();
    assert!(body.model.dof_count() >= 30_000);
    let ccx: Vec<Vec<f64>> = serde_json::from_value(reference["spinning_hz"].clone()).unwrap();
    let rates: Vec<f64> = serde_json::from_value(reference["rates_rad_s"].clone()).unwrap();
    let started = std::time::Instant::now();
    let table = body_campbell(
        &body,
        &BodyCampbellParameters {
            drive: "rbe2:pivot".into(),
            axis: [0.0, 0.0, 1.0],
            axis_point: None,
            rates: rates.clone(),
            count: 4,
            models: vec![(Method::CraigBampton, 20)],
            stiffening: true,
            full: true,
            residual_vectors: true,
        },
        &Progress::new(),
    )
    .unwrap();
    assert!(table.stiffened);
    assert!(
        table.axis_point.1.contains("preload"),
        "{:?}",
        table.axis_point
    );
    for curve in &table.curves {
        for (r, expected) in ccx.iter().enumerate() {
            let got = ascending(&curve.hz[r]);
            for (m, &f) in expected.iter().take(4).enumerate() {
                let rel = (got[m] - f).abs() / f;
                println!(
                    "{:?} {} rad/s mode {}: {} against {f} ({rel:.1e})",
                    curve.method,
                    rates[r],
                    m + 1,
                    got[m]
                );
                assert!(
                    rel <= 2e-4,
                    "{:?} rate {} mode {m}: {} {f}",
                    curve.method,
                    rates[r],
                    got[m]
                );
            }
            assert!(curve.mac[r].iter().all(|&c| c > 0.9), "{:?}", curve.mac[r]);
            assert_eq!(curve.unstable[r], 0);
        }
    }
    println!("campbell: {:.1} s", started.elapsed().as_secs_f64());
}

fn driven(
    body: &ImportedBody,
    residual_vectors: bool,
    motion: impl Fn(&mut DrivenBodyParameters),
) -> Vec<DrivenRun> {
    let mut parameters = DrivenBodyParameters {
        drive: "rbe2:pivot".into(),
        residual_vectors,
        integration: DrivenIntegration {
            step: 1e-3,
            end: 1.0,
            spectral_radius: 0.9,
            output_every: 10,
        },
        ..Default::default()
    };
    motion(&mut parameters);
    let methods = [
        Method::CraigBampton,
        Method::ModalTruncation,
        Method::ModeCondensation,
    ];
    driven_body_study(body, &parameters, &methods, &[10], true, &Progress::new())
        .unwrap()
        .runs
}

/// Spun up to 100 and to 1 000 rad/s, shaken, and under gravity: CB, MT and MC with ten
/// fixed-interface modes and the residual vectors within a history error of 1e-3 of the full
/// body; spun up without them, above 1e-2; the a-priori estimate ranks them alike.
#[test]
#[ignore = "needs the generated part: FLEXMODES_SPUN_PART=DIR (see the module doc)"]
fn residual_vectors_make_ten_modes_enough_on_a_real_part() {
    let (body, _) = part();
    type Motion = (&'static str, fn(&mut DrivenBodyParameters));
    let motions: [Motion; 4] = [
        ("spin-up 100", |p| p.rate = 100.0),
        ("spin-up 1000", |p| p.rate = 1000.0),
        ("shake", |p| {
            p.rate = 0.0;
            p.shake = Some(([1.0, 1.0, 0.0], 1e-4, 50.0));
        }),
        ("gravity", |p| {
            p.rate = 100.0;
            p.gravity = Some([0.0, -9.81, 0.0]);
        }),
    ];
    for (name, motion) in motions {
        let with = driven(&body, true, motion);
        for run in &with[1..] {
            let (e, p) = (run.history_error.unwrap(), run.estimate_max().unwrap());
            println!(
                "{name} {} + {} RV: history error {e:.2e}, reaction error {:.2e}, estimate {p:.1e}",
                run.label(),
                run.residual_vectors,
                run.reaction_error.unwrap()
            );
            assert!(e <= 1e-3, "{name} {}: {e}", run.label());
        }
        if name.starts_with("spin-up") {
            let without = driven(&body, false, motion);
            for (a, b) in with[1..].iter().zip(&without[1..]) {
                let (e, p) = (b.history_error.unwrap(), b.estimate_max().unwrap());
                println!(
                    "{name} {} without RV: history error {e:.2e}, estimate {p:.1e}",
                    b.label()
                );
                assert!(e > 1e-2, "{name} {}: {e}", b.label());
                assert!(p > a.estimate_max().unwrap());
            }
        }
    }
}
