//! Simulations as the scenes run them: kept and weighed in the cache, drawn deflections and
//! lanes, the refined slab with every method, concurrent integrations.

use flexmodes::{Progress, reduction::Method};

/// The explorer's cache integrates only what a request changed, and gives the numbers a fresh
/// run gives.
#[test]
fn a_kept_simulation_is_not_integrated_again() {
    use flexmodes::scenes::{RunCache, SceneOptions, find};
    let run = find("slab-sim1").unwrap().run;
    let cache = RunCache::new();
    let options = |methods: &[Method], modes: usize, cache: &RunCache| SceneOptions {
        methods: Some(methods.to_vec()),
        modes: Some(modes),
        end_time: Some(0.25),
        progress: Progress::new(),
        cache: cache.clone(),
        ..Default::default()
    };
    let integrations = |o: &SceneOptions| o.progress.reading().map_or(0, |r| r.simulations);
    let (nr, cb, gr) = (Method::NoReduction, Method::CraigBampton, Method::Guyan);

    let first = options(&[nr, cb], 6, &cache);
    run(&first).unwrap();
    assert_eq!(integrations(&first), 2);

    let second = options(&[nr, cb, gr], 6, &cache);
    let cached = run(&second).unwrap();
    assert_eq!(integrations(&second), 1, "only GR is new");
    assert_eq!(cache.len(), 3);

    let fresh = run(&options(&[nr, cb, gr], 6, &RunCache::default())).unwrap();
    assert_eq!(
        cached.report.results["rel_rms_error"],
        fresh.report.results["rel_rms_error"]
    );

    // Kept modes change CB's integration, not NR's or GR's.
    let third = options(&[nr, cb, gr], 4, &cache);
    run(&third).unwrap();
    assert_eq!(integrations(&third), 1);
    assert_eq!(cache.len(), 4);
}

/// The cache weighs what it keeps: without reduction the body's dense k × k blocks ($K_{zz}$,
/// $M_{zz}$ and Ψ = I) are at least 3·8·k² bytes; with Craig–Bampton only Ψ (n × 18) and
/// small blocks.
#[test]
fn the_cache_weighs_an_unreduced_integration_by_its_dense_blocks() {
    use flexmodes::scenes::{RunCache, SceneOptions, find};
    let run = find("slab-sim1").unwrap().run;
    let weigh = |m: Method| {
        let cache = RunCache::new();
        run(&SceneOptions {
            methods: Some(vec![m]),
            refine: Some([8, 4, 2]),
            end_time: Some(0.05),
            cache: cache.clone(),
            ..Default::default()
        })
        .unwrap();
        assert_eq!(cache.len(), 1);
        cache.bytes()
    };
    // 9 × 5 × 3 nodes.
    let n = 3 * 9 * 5 * 3;
    let k = n - 6;
    let nr = weigh(Method::NoReduction);
    assert!(nr >= 3 * 8 * k * k, "{nr} bytes for {n} DOF");
    assert!(nr <= 6 * 8 * n * n + (1 << 20), "{nr} bytes for {n} DOF");
    let cb = weigh(Method::CraigBampton);
    assert!(cb >= 8 * n * 12, "{cb}");
    assert!(cb < nr / 10, "{cb} against {nr}");
}

#[test]
fn the_drawn_deflection_is_automatic_or_as_asked() {
    let scene = flexmodes::scenes::find("slab-sim1").unwrap();
    let run = |scale: Option<f64>| {
        scene.execute(&flexmodes::scenes::SceneOptions {
            methods: Some(vec![Method::CraigBampton]),
            end_time: Some(0.2),
            deformation_scale: scale,
            ..Default::default()
        })
    };
    let auto = run(None).unwrap();
    let f = auto.report.results["deformation_scale"].as_f64().unwrap();
    // 1, 2 or 5 times a power of ten, at least 1.
    let mantissa = f / 10f64.powf(f.log10().floor());
    assert!(
        f >= 1.0 && [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
        "{f}"
    );
    let asked = run(Some(7.0)).unwrap();
    assert_eq!(asked.report.results["deformation_scale"], 7.0);
    assert!(matches!(
        run(Some(-1.0)).unwrap_err(),
        flexmodes::Error::InvalidOption { .. }
    ));
}

#[test]
fn a_refined_slab_simulation_runs_every_method_and_cb_stays_close_to_the_full_model() {
    let options = flexmodes::scenes::SceneOptions {
        refine: Some([8, 4, 2]),
        end_time: Some(0.3),
        ..Default::default()
    };
    let output = (flexmodes::scenes::find("slab-sim1").unwrap().run)(&options).unwrap();
    let report = &output.report;
    assert_eq!(report.parameters["dofs"], 405);
    assert_eq!(report.parameters["bricks"], serde_json::json!([8, 4, 2]));
    let errors = report.results["rel_rms_error"].as_object().unwrap();
    assert_eq!(errors.len(), 5);
    for d in ["xi", "eta", "zeta"] {
        let cb = errors["cb"][d].as_f64().unwrap();
        let mc = errors["mc"][d].as_f64().unwrap();
        let mt = errors["mt"][d].as_f64().unwrap();
        assert!(cb < 0.1, "{d}: CB {cb}");
        assert!((cb - mc).abs() <= 1e-4, "{d}: CB {cb}, MC {mc}");
        // Modal truncation cannot follow the supports (§7.2): far worse than CB.
        assert!(mt > 5.0 * cb, "{d}: MT {mt}, CB {cb}");
    }
}

#[test]
fn bodies_of_different_methods_are_drawn_in_lanes_that_do_not_overlap() {
    use flexmodes::record::Visual;
    let options = flexmodes::scenes::SceneOptions {
        methods: Some(vec![
            Method::NoReduction,
            Method::CraigBampton,
            Method::Guyan,
        ]),
        end_time: Some(0.2),
        ..Default::default()
    };
    let out = flexmodes::scenes::find("slab-sim1")
        .unwrap()
        .execute(&options)
        .unwrap();
    let offset = |lane: &str| {
        out.visuals.iter().find_map(|v| match v {
            Visual::Offset { path, translation } if path == lane => Some(*translation),
            _ => None,
        })
    };
    // The y extent of each lane's body over the whole run, shifted by its lane's offset.
    let mut extents = Vec::new();
    for m in ["nr", "cb", "gr"] {
        let lane = format!("world/slab/{m}");
        let shift = offset(&lane).unwrap_or_else(|| panic!("no offset for {lane}"));
        let mut first_frames: Option<Vec<[f64; 3]>> = None;
        for part in ["nodal_fixed", "undeformed_ghost"] {
            let path = format!("{lane}/{part}");
            // Node positions per time: logged for the deflected body, a rigid outline moved
            // by its frame's placement (rotation columns) for the ghost.
            let positions: Vec<Vec<[f64; 3]>> = out
                .visuals
                .iter()
                .find_map(|v| match v {
                    Visual::Trajectory {
                        path: p, positions, ..
                    } if *p == path => Some(positions.clone()),
                    Visual::RigidTrajectory {
                        path: p,
                        geometry,
                        translations,
                        rotations,
                        ..
                    } if *p == path => {
                        assert_eq!(translations.len(), rotations.len());
                        Some(
                            translations
                                .iter()
                                .zip(rotations)
                                .map(|(t, r)| {
                                    geometry
                                        .nodes
                                        .iter()
                                        .map(|x| {
                                            [0, 1, 2].map(|i| {
                                                t[i] + (0..3).map(|c| r[c][i] * x[c]).sum::<f64>()
                                            })
                                        })
                                        .collect()
                                })
                                .collect(),
                        )
                    }
                    _ => None,
                })
                .unwrap_or_else(|| panic!("no trajectory {path}"));
            assert!(!positions.is_empty());
            // At the start the slab is undeformed: the ghost, placed by its frame alone, lies
            // on the body drawn from every node's position.
            if let Some(body) = &first_frames {
                let ghost: &Vec<[f64; 3]> = &positions[0];
                assert_eq!(ghost.len(), Vec::len(body));
                for (g, b) in ghost.iter().zip(body) {
                    let gap = (0..3).map(|i| (g[i] - b[i]).abs()).fold(0.0, f64::max);
                    assert!(gap < 1e-9, "{path}: ghost {g:?}, body {b:?}");
                }
            }
            first_frames = Some(positions[0].clone());
            let ys = positions.iter().flatten().map(|p| p[1] + shift[1]);
            let lo = ys.clone().fold(f64::MAX, f64::min);
            let hi = ys.fold(f64::MIN, f64::max);
            extents.push((m, lo, hi));
        }
        assert!(
            out.visuals
                .iter()
                .any(|v| v.path() == format!("{lane}/label")),
            "{lane} has no label"
        );
    }
    for (i, a) in extents.iter().enumerate() {
        for b in &extents[i + 1..] {
            if a.0 != b.0 {
                assert!(a.2 < b.1 || b.2 < a.1, "lanes {a:?} and {b:?} overlap");
            }
        }
    }
}

/// The explorer integrates a scene's methods on several threads: the same errors, in the same
/// order, as one after the other; the scene text says so.
#[test]
fn concurrent_integrations_give_the_serial_results() {
    use flexmodes::scenes::{SceneOptions, find};
    let scene = find("slab-sim1").unwrap();
    let methods = vec![
        Method::NoReduction,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::Guyan,
    ];
    let options = |threads: usize| SceneOptions {
        methods: Some(methods.clone()),
        end_time: Some(0.2),
        concurrent_integrations: threads,
        ..Default::default()
    };
    let serial = scene.execute(&options(1)).unwrap();
    let concurrent = scene.execute(&options(3)).unwrap();
    let errors = |o: &flexmodes::scenes::SceneOutput| o.report.results["rel_rms_error"].clone();
    assert_eq!(errors(&serial).as_object().unwrap().len(), methods.len());
    assert_eq!(errors(&serial), errors(&concurrent));
    assert_eq!(
        serial.report.parameters["methods"],
        concurrent.report.parameters["methods"]
    );
    assert!(concurrent.markdown.contains("ran up to 3 at a time"));
    assert!(!serial.markdown.contains("at a time"));
}
