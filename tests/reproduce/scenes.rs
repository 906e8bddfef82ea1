//! Scenes: stable report keys, entity paths, options honoured.

use flexmodes::reduction::{Method, ReductionRequest, reduce};
use flexmodes::{
    analysis::reduced_hz,
    fem::{BeamParameters, beam},
    record::Recorder,
    reduction::{Partition, fixed_interface_modes},
    scenes::{self, SceneOptions},
};

fn run(id: &str, opts: SceneOptions) -> flexmodes::scenes::SceneOutput {
    (scenes::find(id).unwrap().run)(&opts).unwrap()
}

fn paths(out: &flexmodes::scenes::SceneOutput) -> Vec<String> {
    out.visuals.iter().map(|v| v.path().to_string()).collect()
}

/// Each scene's report keys that stay put from release to release.
const STABLE_KEYS: &[(&str, &[&str])] = &[
    (
        "beam-modes",
        &[
            "free_free_hz",
            "guyan_a_hz",
            "guyan_b_hz",
            "guyan_c_hz",
            "fixed_interface_hz",
        ],
    ),
    (
        "slab-modes",
        &[
            "free_free_hz",
            "fixed_interface_hz",
            "reduced_hz.mt",
            "reduced_hz.cb",
            "reduced_hz.mc",
            "reduced_hz.gr",
        ],
    ),
    (
        "beam-profiles",
        &[
            "profile1_error.mt",
            "profile1_error.cb",
            "profile1_error.mc",
            "profile2_error.mt",
            "profile2_error.cb",
            "profile2_error.mc",
        ],
    ),
    ("beam-eitelberg", &["minv_k", "hz"]),
    (
        "slab-mode-sets",
        &[
            "frf_rel_error.cb",
            "frf_rel_error.mr",
            "frf_rel_error.bh",
            "selection.influence",
            "selection.lowest",
        ],
    ),
    (
        "cantilever-variants",
        &[
            "static_rel_error.cb.lc1",
            "static_rel_error.mm.lc2",
            "static_rel_error.bt.v2",
            "freq_rel_error.v1.cb",
            "freq_rel_error.v2.mm",
            "freq_rel_error.v3.bt",
            "mac.v1.bt",
            "mac.v3.cb",
            "hz.v1",
            "hz.v2",
            "hz.v3",
        ],
    ),
    (
        "spin-up",
        &[
            "campbell.published_difference.nr",
            "campbell.published_difference.cb",
            "campbell.lagwise_unstable_from_lambda_without_stiffening",
            "spin_up",
            "first_frequency_rad_s",
        ],
    ),
    (
        "amls",
        &[
            "reference_hz",
            "guyan.max_rel_error",
            "craig_bampton",
            "amls",
            "tree.per_level",
            "refined.sturm_missed",
            "refined.max_residual",
        ],
    ),
];

#[test]
fn every_scene_reports_its_stable_keys_and_logs_its_views() {
    for (id, ks) in STABLE_KEYS {
        let out = run(id, SceneOptions::default());
        for k in *ks {
            assert!(out.report.result(k).is_some(), "{id}: missing {k}");
        }
        let logged = paths(&out);
        for origin in out.layout.origins() {
            let o = origin.trim_start_matches('/');
            assert!(
                o == "scene" || logged.iter().any(|p| p.starts_with(o)),
                "{id}: view origin {origin} has nothing logged"
            );
        }
        assert!(out.markdown.contains(&out.report.table));
        // The explorer's viewer beside its panel at 1 280 × 800 (gui::VIEWER_AREA): the new
        // scene's titles fit as written (the explorer shortens others: tests/gui/).
        if *id == "spin-up" || *id == "amls" {
            let cut = out.layout.cut_titles((950.0, 730.0));
            assert!(cut.is_empty(), "{id}: tab titles cut: {cut:?}");
        }
        let bytes = Recorder::default().encode(&out).unwrap();
        assert!(bytes.len() > 1000, "{id}: {} bytes", bytes.len());
    }
}

#[test]
fn beam_modes_honours_boundary() {
    let out = run(
        "beam-modes",
        SceneOptions {
            boundary: Some(vec![1, 4, 5]),
            ..Default::default()
        },
    );
    let model = beam(&BeamParameters::default());
    let g = reduced_hz(
        &model,
        &reduce(
            &model,
            &ReductionRequest::of(Method::Guyan).boundary(&[1, 4, 5]),
        )
        .unwrap(),
    )
    .unwrap();
    let fi = fixed_interface_modes(&model, &Partition::new(&model, &[1, 4, 5]).unwrap())
        .unwrap()
        .hz();
    let got_g = out.report.result_vec("guyan_c_hz").unwrap();
    let got_fi = out.report.result_vec("fixed_interface_hz").unwrap();
    assert_eq!(got_g.len(), g.len());
    assert_eq!(got_fi.len(), fi.len());
    for (a, b) in got_g.iter().zip(&g).chain(got_fi.iter().zip(&fi)) {
        assert!((a - b).abs() < 1e-8 * b);
    }
    // The default set (1, 5) has one elastic Guyan (c) frequency; (1, 4, 5) has three.
    assert_eq!(got_g.len(), 3);
}

#[test]
fn slab_modes_honours_boundary_and_modes() {
    let out = run(
        "slab-modes",
        SceneOptions {
            boundary: Some(vec![1, 13, 16, 28]),
            modes: Some(4),
            ..Default::default()
        },
    );
    let size = out.report.result("basis_size.cb").unwrap();
    assert_eq!(size, &serde_json::json!([90, 16]));
    assert_eq!(
        out.report.result("basis_size.gr").unwrap(),
        &serde_json::json!([90, 18])
    );
    let fi = out.report.result_vec("fixed_interface_hz").unwrap();
    assert_eq!(fi.len(), 90 - 12);
    // CB and MC agree, GR is stiffer than CB in its lowest elastic frequency, MT has no
    // rigid-body mode at all.
    let cb = out.report.result_vec("reduced_hz.cb").unwrap();
    let mc = out.report.result_vec("reduced_hz.mc").unwrap();
    let gr = out.report.result_vec("reduced_hz.gr").unwrap();
    assert_eq!(cb.len(), 16 - 6);
    assert_eq!(mc.len(), cb.len());
    for (a, b) in cb.iter().zip(&mc) {
        assert!((a - b).abs() < 1e-6 * a);
    }
    assert!(gr[0] > cb[0], "GR {} Hz, CB {} Hz", gr[0], cb[0]);
    assert_eq!(out.report.result("rigid_body_modes.mt").unwrap(), 0);
    assert_eq!(out.report.result("rigid_body_modes.cb").unwrap(), 6);
}

#[test]
fn slab_modes_shows_rayleigh_ritz_ordering() {
    let out = run("slab-modes", SceneOptions::default());
    let full = out.report.result_vec("free_free_hz").unwrap();
    for m in ["cb", "mc", "gr"] {
        let r = out.report.result_vec(&format!("reduced_hz.{m}")).unwrap();
        assert_eq!(r.len(), 18 - 6, "{m}");
        assert!(full.len() > r.len());
        for (k, (a, b)) in r.iter().zip(&full).enumerate() {
            assert!(a >= &(b * (1.0 - 1e-9)), "{m} mode {k}: {a} below full {b}");
        }
    }
    // Guyan is the stiffest of the 18-coordinate models in its first elastic mode.
    let g = out.report.result_vec("reduced_hz.gr").unwrap()[0];
    let c = out.report.result_vec("reduced_hz.cb").unwrap()[0];
    assert!(g > c);
}

#[test]
fn method_filter_restricts_what_is_logged() {
    let out = run(
        "beam-modes",
        SceneOptions {
            methods: Some(vec![flexmodes::reduction::Method::CraigBampton]),
            ..Default::default()
        },
    );
    let p = paths(&out);
    assert!(p.iter().any(|p| p.starts_with("modes/craig_bampton/")));
    assert!(!p.iter().any(|p| p.starts_with("modes/mode_condensation/")));
    assert!(p.iter().any(|p| p.starts_with("modes/free_free/")));
}

#[test]
fn result_tables_rank_errors_from_their_numbers() {
    let out = run("beam-profiles", SceneOptions::default());
    let table = &out.report.tables[0];
    assert_eq!(table.rows.len(), 3, "MT, CB, MC");
    assert_eq!(table.lower_is_better, vec![1, 2]);
    let method = |r: usize| table.rows[r][0].text.clone();
    for column in [1, 2] {
        let (best, worst) = table.best_and_worst(column).unwrap();
        // Profile errors of §7.1: MT 0.1569 the worst, CB = MC the best: both, as they print
        // alike.
        let methods = |rows: &[usize]| rows.iter().map(|&r| method(r)).collect::<Vec<_>>();
        assert_eq!(methods(&worst), ["MT"]);
        assert_eq!(methods(&best), ["CB", "MC"]);
        let value = |r: usize| table.rows[r][column].value.unwrap();
        assert!(value(worst[0]) > 1.5 * value(best[0]));
    }
    // The method column is not ranked, and the markdown shows the same cells.
    assert!(table.best_and_worst(0).is_none());
    assert!(out.report.table.contains(&table.markdown()));
}

/// A view that shows a subset says so: the L-bracket's bolt hole has 72 boundary DOF, of which
/// the constraint-mode tab draws 24.
#[test]
fn a_view_of_a_subset_says_how_many_of_how_many() {
    fn names(l: &flexmodes::record::Layout, out: &mut Vec<String>) {
        use flexmodes::record::Layout;
        match l {
            Layout::Horizontal(items, _) | Layout::Vertical(items, _) | Layout::Tabs(items) => {
                items.iter().for_each(|i| names(i, out))
            }
            Layout::Spatial3D { name, .. } => out.push(name.clone()),
            _ => {}
        }
    }
    let out = run("modes", SceneOptions::default());
    let mut tabs = Vec::new();
    names(&out.layout, &mut tabs);
    assert!(tabs.contains(&"guyan_c (24 of 72)".to_string()), "{tabs:?}");
    let slab = run("slab-modes", SceneOptions::default());
    let mut tabs = Vec::new();
    names(&slab.layout, &mut tabs);
    assert!(tabs.contains(&"guyan_c".to_string()), "{tabs:?}");
}

/// The `amls` scene's text says, at each cut-off, AMLS has fewer coordinates and a larger
/// error than Craig–Bampton on the root separator, Guyan the largest error of all, and
/// AMLS refined equal to Lanczos with no mode missed: each is checked on its numbers.
#[test]
fn the_amls_ladder_says_what_its_numbers_show() {
    let out = run("amls", SceneOptions::default());
    let r = |k: &str| out.report.result(k).unwrap().clone();
    let points = |k: &str| -> Vec<(f64, f64)> {
        r(k).as_array()
            .unwrap()
            .iter()
            .map(|p| {
                (
                    p["coordinates"].as_f64().unwrap(),
                    p["max_rel_error"].as_f64().unwrap(),
                )
            })
            .collect()
    };
    let (cb, amls) = (points("craig_bampton"), points("amls"));
    assert_eq!(cb.len(), amls.len());
    assert!(cb.len() >= 3);
    let guyan = r("guyan.max_rel_error").as_f64().unwrap();
    for ((c_n, c_e), (a_n, a_e)) in cb.iter().zip(&amls) {
        assert!(a_n < c_n && a_e > c_e, "AMLS {a_n} {a_e}, CB {c_n} {c_e}");
        assert!(guyan > *a_e && guyan > *c_e);
    }
    assert_eq!(r("refined.sturm_missed").as_u64(), Some(0));
    assert!(r("refined.max_residual").as_f64().unwrap() <= 1e-8);
    assert!(r("refined.eigenvalues_apart").as_f64().unwrap() <= 1e-10);
    // Every DOF of the body sits in one part of the tree.
    let per_level = r("tree.per_level");
    let unknowns: u64 = per_level
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["unknowns"].as_u64().unwrap())
        .sum();
    assert_eq!(Some(unknowns), out.report.parameters["dof"].as_u64());
}
