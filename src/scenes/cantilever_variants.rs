//! `cantilever-variants`: Witteveen (World J. Mech. 2012) §4. Craig–Bampton, Krylov moment
//! matching and balanced truncation, 14 vectors each, built once on a clamped beam structure
//! and then used under boundary conditions changed on the reduced models only. The numbers
//! are [`crate::models::cantilever_study`]'s; this scene draws and tabulates them.

use crate::record::{REFERENCE, method_color};
use serde_json::{Map, Value, json};

use super::{SceneInfo, SceneOptions, SceneOutput, mode_visuals::mode_set};
use crate::{
    Result,
    analysis::{MAC_ACCURATE, ModePair},
    models::{
        BAND_HZ, CANTILEVER_METHODS as AVAILABLE, CantileverStudy, StaticCase, VariantModes,
        WITTEVEEN_INTEREST_HZ as INTEREST_HZ, cantilever_study,
    },
    record::{Geometry, Layout, Visual},
    reduction::Method,
    report::{Cell, Report, Table, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    id: "cantilever-variants",
    summary: "Witteveen §4: CB (7+7), Krylov moment matching (2×7) and balanced truncation (14) \
              built once on a clamped beam structure, then with A clamped (variant 2) and A \
              sliding with 250 kg (variant 3): static deflections, frequency errors and MAC",
    sections: "Witteveen 2012 §4",
    controls: super::scene_info::SceneControls::methods_only(&AVAILABLE),
};

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    opts.check_axes(INFO.id, &[])?;
    if opts.boundary.is_some() || opts.modes.is_some() {
        return Err(crate::Error::InvalidOption {
            scene: INFO.id.into(),
            reason: "--boundary and --modes do not apply: the bases are Witteveen's (the seven \
                     I/O DOF, 7 constraint + 7 fixed-interface modes, 2 Krylov blocks, 14 \
                     balanced vectors)"
                .into(),
        });
    }
    let methods = opts.methods_or(INFO.id, &AVAILABLE, &AVAILABLE)?;
    let study = cantilever_study(&methods)?;
    let (params, frame) = (&study.params, &study.frame);
    let model = &frame.model;

    let mut report = Report::new(INFO.id);
    for (key, value) in [
        ("bottom_length_mm", params.bottom_length),
        ("overhang_length_mm", params.overhang_length),
        ("overhang_root_fraction", params.root_fraction),
        ("band_hz", BAND_HZ),
    ] {
        report.parameters.insert(key.into(), json!(value));
    }
    report
        .parameters
        .insert("dofs".into(), json!(model.dof_count()));

    let mut visuals = vec![Visual::Wireframe {
        path: "structure/undeformed".into(),
        geometry: Geometry::of(model),
        color: REFERENCE,
        label: None,
    }];
    for (name, node) in [("A", frame.a), ("B", frame.b), ("clamp", frame.clamp)] {
        visuals.push(Visual::Label3D {
            path: format!("structure/{}", name.to_lowercase()),
            position: model.nodes[node - 1],
            text: name.into(),
            color: [250, 80, 80, 255],
        });
    }

    // ---- Dynamics: the full model and each reduced one under each variant.
    let (mut hz_all, mut freq_all, mut mac_all) = (Map::new(), Map::new(), Map::new());
    let mut dynamics_text = String::new();
    for variant in &study.variants {
        let key = format!("v{}", variant.variant);
        hz_all.insert(key.clone(), json!(sig_vec(&variant.band_hz)));
        let (mut freq, mut macs) = (Map::new(), Map::new());
        for (m, pairs) in &variant.pairs {
            let errors: Vec<f64> = pairs.iter().map(|p| p.frequency_error).collect();
            freq.insert(m.id().into(), json!(sig_vec(&errors)));
            let mac: Vec<f64> = pairs.iter().map(|p| p.mac).collect();
            macs.insert(m.id().into(), json!(sig_vec(&mac)));
        }
        freq_all.insert(key.clone(), Value::Object(freq));
        mac_all.insert(key, Value::Object(macs));
        visuals.extend(variant_visuals(&study, variant));
        dynamics_text.push_str(&format!(
            "\n### Variant {}: {}\n\n{}",
            variant.variant,
            match variant.variant {
                1 => "clamped at the origin only (the bases' own model)",
                2 => "A clamped as well",
                _ => "A sliding in x only, with 250 kg on it",
            },
            report.add_table(variant_table(variant))
        ));
    }
    report.results.insert("hz".into(), Value::Object(hz_all));
    report
        .results
        .insert("freq_rel_error".into(), Value::Object(freq_all));
    report.results.insert("mac".into(), Value::Object(mac_all));

    // ---- Statics.
    let mut static_errors: Map<String, Value> = Map::new();
    let mut static_table = Table::new(&["load case", "full peak, mm", "CB", "MM", "BT"]);
    for case in &study.statics {
        let peak = case.peak();
        let mut row = vec![
            Cell::text(case.id.to_uppercase()),
            Cell::number(peak, format!("{peak:.4e}")),
        ];
        for m in AVAILABLE {
            match case.error(m) {
                Some(err) => {
                    static_errors
                        .entry(m.id())
                        .or_insert_with(|| Value::Object(Map::new()))
                        .as_object_mut()
                        .map(|o| o.insert(case.id.into(), json!(sig(err))));
                    row.push(Cell::number(err, format!("{err:.2e}")));
                }
                None => row.push(Cell::text("–")),
            }
        }
        static_table.push(row);
        visuals.extend(static_visuals(case));
    }
    report
        .results
        .insert("static_rel_error".into(), Value::Object(static_errors));
    let static_md = report.add_table(static_table);

    // ---- Calibration against the printed frequencies.
    let mut cal = Map::new();
    let mut cal_table = Table::new(&["printed value", "Witteveen, Hz", "ours, Hz", "ratio"]);
    for (what, printed, ours) in study.calibration() {
        cal.insert(what.into(), json!(sig(ours)));
        cal_table.push(vec![
            Cell::text(what),
            Cell::number(printed, format!("{printed}")),
            Cell::number(ours, format!("{ours:.2}")),
            Cell::number(ours / printed, format!("{:.3}", ours / printed)),
        ]);
    }
    for (v, printed) in [(0usize, "mode 7, above 200 Hz"), (1, "mode 3")] {
        let ours = study.variants.get(v).and_then(|x| x.first_torsion);
        cal_table.push(vec![
            Cell::text(format!(
                "variant {}, first torsion of the bottom section",
                v + 1
            )),
            Cell::text(printed),
            Cell::text(ours.map_or("none in the band".into(), |(k, f)| {
                format!("mode {k}, {f:.2}")
            })),
            Cell::text(""),
        ]);
        if let Some((k, _)) = ours {
            cal.insert(format!("v{}_first_torsion_mode", v + 1), json!(k));
        }
    }
    report
        .results
        .insert("calibration".into(), Value::Object(cal));
    report.results.insert(
        "cb_fixed_interface_hz".into(),
        json!(sig_vec(&study.cb_fixed_interface_hz)),
    );
    let cal_md = report.add_table(cal_table);

    // The paper's subspace check: the first three modes against the first three BT vectors.
    let mut subspace_md = String::new();
    if let Some(angles) = &study.subspace_angles_deg {
        report
            .results
            .insert("subspace_angles_deg".into(), json!(sig_vec(angles)));
        subspace_md = format!(
            "Principal angles between the first three modes and the first three BT vectors: \
             {} degrees (Witteveen reports the singular values 2.7, 2.4, 1.7, 0.006, 0.0001, \
             2e-7 of the six vectors side by side: three dimensions dominate).\n",
            angles
                .iter()
                .map(|a| format!("{a:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }

    let claims = claims_text(&study);
    // In the order the tables were added, which the explorer's panel follows.
    report.table = format!(
        "## Dynamics\n{dynamics_text}\n## Statics\n\n{static_md}\n## Calibration\n\n{cal_md}\n\
         {subspace_md}\n## Claims\n\n{claims}"
    );
    let markdown = scene_text(&study, &report.table);
    Ok(SceneOutput {
        report,
        markdown,
        visuals,
        layout: layout(&study.statics),
        timeline: None,
        y_up: false,
    })
}

/// A variant's full modes (each labelled) and the frequency-error and MAC bars per method.
fn variant_visuals(study: &CantileverStudy, variant: &VariantModes) -> Vec<Visual> {
    let model = &study.frame.model;
    let v = variant.variant;
    let shapes: Vec<(Vec<f64>, String)> = variant
        .band_hz
        .iter()
        .enumerate()
        .map(|(k, hz)| {
            (
                (0..model.dof_count())
                    .map(|d| variant.shapes[(d, k)])
                    .collect(),
                format!("{} · {hz:.1} Hz", k + 1),
            )
        })
        .collect();
    let mut visuals = mode_set(model, &format!("v{v}"), &shapes, REFERENCE);
    let count = variant.pairs.len().max(1) as f64;
    let width = 0.8 / count;
    for (s, (m, pairs)) in variant.pairs.iter().enumerate() {
        let abscissa: Vec<f64> = (0..pairs.len())
            .map(|k| (k + 1) as f64 + (s as f64 - 0.5 * (count - 1.0)) * width)
            .collect();
        visuals.push(Visual::SeriesBars {
            path: format!("metrics/freq_error/v{v}/{}", m.id()),
            abscissa: abscissa.clone(),
            values: pairs.iter().map(|p| 100.0 * p.frequency_error).collect(),
            width,
            color: method_color(*m),
        });
        visuals.push(Visual::SeriesBars {
            path: format!("metrics/mac/v{v}/{}", m.id()),
            abscissa,
            values: pairs.iter().map(|p| p.mac).collect(),
            width,
            color: method_color(*m),
        });
    }
    visuals
}

/// A variant's table: each band mode's full frequency, then every method's error and MAC.
fn variant_table(variant: &VariantModes) -> Table {
    let mut header = vec!["mode".to_string(), "full, Hz".to_string()];
    for (m, _) in &variant.pairs {
        header.push(format!("{} error", m.id().to_uppercase()));
        header.push(format!("{} MAC", m.id().to_uppercase()));
    }
    let header_refs: Vec<&str> = header.iter().map(|s| s.as_str()).collect();
    let mut table = Table::new(&header_refs);
    for (k, hz) in variant.band_hz.iter().enumerate() {
        let mut row = vec![
            Cell::text(format!("{}", k + 1)),
            Cell::number(*hz, format!("{hz:.2}")),
        ];
        for (_, pairs) in &variant.pairs {
            let p = &pairs[k];
            row.push(Cell::number(
                p.frequency_error,
                format!("{:+.2} %", 100.0 * p.frequency_error),
            ));
            let flag = if p.accurate() { "" } else { " ✗" };
            row.push(Cell::number(p.mac, format!("{:.3}{flag}", p.mac)));
        }
        table.push(row);
    }
    table
}

/// A load case's deflection lines in a 2-D view (x along the bottom section, mm; the
/// deflection scaled so the full model's peak reads 300 mm high, y pointing down) and a legend.
fn static_visuals(case: &StaticCase) -> Vec<Visual> {
    let peak = case.peak();
    let scale = if peak > 0.0 { 300.0 / peak } else { 1.0 };
    let draw = |pts: &[[f64; 2]]| pts.iter().map(|p| [p[0], -p[1] * scale]).collect();
    let mut visuals = vec![Visual::Polyline2D {
        path: format!("statics/{}/full", case.id),
        points: draw(&case.full_line),
        color: REFERENCE,
        label: None,
    }];
    let mut legend = vec![
        (case.text.to_string(), REFERENCE),
        (format!("full: peak {peak:.3e} mm"), REFERENCE),
    ];
    for m in AVAILABLE {
        let Some((_, line, err)) = case.methods.iter().find(|(mm, _, _)| *mm == m) else {
            continue;
        };
        visuals.push(Visual::Polyline2D {
            path: format!("statics/{}/{}", case.id, m.id()),
            points: draw(line),
            color: method_color(m),
            label: None,
        });
        legend.push((
            format!("{}: error {err:.1e}", m.id().to_uppercase()),
            method_color(m),
        ));
    }
    // The legend: labelled points in a column under the curves (the curves coincide where
    // the methods are exact, so labels on them would overlap).
    visuals.push(Visual::Scatter {
        path: format!("statics/{}/legend", case.id),
        points: (0..legend.len())
            .map(|k| [500.0, 380.0 + 110.0 * k as f64])
            .collect(),
        labels: legend.iter().map(|(t, _)| t.clone()).collect(),
        colors: legend.iter().map(|(_, c)| *c).collect(),
    });
    visuals
}

/// The scene's text above its tables.
fn scene_text(study: &CantileverStudy, tables: &str) -> String {
    let params = &study.params;
    format!(
        "# cantilever-variants\n\n\
         Witteveen, *World J. Mech.* 2 (2012) §4: a beam structure clamped at the origin (N–mm–t \
         units, E = 210 000 N/mm², G = 80 000 N/mm², ρ = 7.8e-9 t/mm³), 12-DOF Euler–Bernoulli \
         frame elements of ≈ {el} mm, lumped mass, {dofs} DOF. His Fig. 1 is missing, so the \
         geometry is ours: a **bottom section** of 100 × 10 mm (100 mm across, y), \
         {l1:.0} mm along x; an **overhanging beam** of 100 × 5 mm, {l2:.0} mm long, rooted at \
         {root:.0} % of the bottom section and pointing {dir} (100 mm side {wide}). \
         **A** is the free end of the bottom section (six I/O DOF), **B** its middle (z). The \
         overhang is the part no I/O DOF sees. Calibrated against the printed frequencies by a \
         grid search over lengths, root and orientation (table below).\n\n\
         **Bases** (14 vectors each, built once on variant 1): **CB** = 7 constraint modes of \
         the I/O DOF + 7 fixed-interface modes; **MM** = block Krylov about s₀ = 0, \
         [K⁻¹B₁, K⁻¹MK⁻¹B₁] by block Arnoldi in the M-inner product with re-orthogonalisation \
         ({deflated} columns deflated); **BT** = the 14 dominant eigenvectors (Euclidean) of the \
         position block of the controllability gramian with D = 1e-4·K, computed exactly in \
         modal coordinates. We use this second-order form because it is what Witteveen ran \
         (SBPOR): a Ritz basis that the changed supports can be applied to; first-order \
         balancing of states (Spanos–Tsuha) gives no displacement basis. \
         **Variants** are applied to the reduced models only: held DOF by the null space of \
         their rows of V, the 250 kg added as m·v·v^T, v the row of V at A's x.\n\n\
         **Measures**: static error = max over the bottom section of |ũ − u| in the direction \
         of interest over max |u|; modes of the full model up to {band} Hz paired with the \
         reduced mode of best MAC (Eq. 43, on all DOF: mm and rad together, as the gramian \
         sees them); frequency error (f̃ − f)/f (Eq. 42); ✗ marks MAC < 0.95.\n\n\
         {tables}",
        el = params.element_length,
        dofs = study.frame.model.dof_count(),
        deflated = study.deflated,
        l1 = params.bottom_length,
        l2 = params.overhang_length,
        root = 100.0 * params.root_fraction,
        dir = match params.direction {
            crate::fem::OverhangDirection::Sideways => "sideways (+y)",
            crate::fem::OverhangDirection::Upwards => "upwards (+z)",
        },
        wide = if params.wide_along_x {
            "along x"
        } else {
            "across x"
        },
        band = BAND_HZ,
    )
}

/// Modes per variant beside the charts (frequency error, MAC, statics) and the text.
fn layout(statics: &[StaticCase]) -> Layout {
    let tabs_of = |what: &str, name: &str| {
        Layout::Tabs(
            (1..=3)
                .map(|v| Layout::BarChart {
                    name: format!("{name} v{v}"),
                    origin: format!("/metrics/{what}/v{v}"),
                    legend: true,
                })
                .collect(),
        )
    };
    Layout::Horizontal(
        vec![
            Layout::Tabs(vec![
                // Short titles: four tabs share a third of a 1280 × 800 window.
                Layout::view3d("v1", "/modes/v1"),
                Layout::view3d("v2", "/modes/v2"),
                Layout::view3d("v3", "/modes/v3"),
                Layout::view3d("beams", "/structure"),
            ]),
            Layout::Vertical(
                vec![
                    tabs_of("freq_error", "Δf %"),
                    tabs_of("mac", "MAC"),
                    Layout::Tabs(
                        statics
                            .iter()
                            .map(|c| Layout::Spatial2D {
                                name: c.id.to_string(),
                                origin: format!("/statics/{}", c.id),
                            })
                            .collect(),
                    ),
                ],
                vec![1.0, 1.0, 1.0],
            ),
            Layout::scene_text(),
        ],
        vec![2.0, 2.0, 2.0],
    )
}

/// The paper's conclusions, each checked on our numbers.
fn claims_text(study: &CantileverStudy) -> String {
    let pairs: Vec<&Vec<(Method, Vec<ModePair>)>> =
        study.variants.iter().map(|v| &v.pairs).collect();
    let full_hz: Vec<&Vec<f64>> = study.variants.iter().map(|v| &v.band_hz).collect();
    let mut out = String::new();
    let static_of = |case: &str, m: Method| {
        study
            .statics
            .iter()
            .find(|c| c.id == case)
            .and_then(|c| c.error(m))
    };
    let verdict = |ok: bool| if ok { "**holds**" } else { "**does not hold**" };
    // Statics: CB and MM exact, BT not.
    for (case, text) in [
        ("lc1", "LC 1: CB and MM accurate, BT not"),
        ("lc2", "LC 2: CB and MM exact, BT highly inaccurate"),
        (
            "v2",
            "variant 2 statics: CB and MM accurate, BT significant errors",
        ),
    ] {
        if let (Some(cb), Some(mm), Some(bt)) = (
            static_of(case, Method::CraigBampton),
            static_of(case, Method::MomentMatching),
            static_of(case, Method::BalancedTruncation),
        ) {
            out.push_str(&format!(
                "- {text}: CB {cb:.1e}, MM {mm:.1e}, BT {bt:.1e} — {}.\n",
                verdict(cb < 1e-8 && mm < 1e-8 && bt > 0.01)
            ));
        }
    }
    let worst_below = |v: usize, m: Method| -> Option<(usize, f64)> {
        let (_, p) = pairs.get(v)?.iter().find(|(mm, _)| *mm == m)?;
        p.iter()
            .enumerate()
            .filter(|(_, q)| q.full_hz <= INTEREST_HZ)
            .map(|(k, q)| (k + 1, q.frequency_error.abs()))
            .fold(None, |b: Option<(usize, f64)>, x| match b {
                Some(y) if y.1 >= x.1 => Some(y),
                _ => Some(x),
            })
    };
    let missed = |v: usize, m: Method| -> Vec<String> {
        pairs
            .get(v)
            .and_then(|ms| ms.iter().find(|(mm, _)| *mm == m))
            .map(|(_, p)| {
                p.iter()
                    .enumerate()
                    .filter(|(_, q)| q.mac < MAC_ACCURATE)
                    .map(|(k, q)| format!("{} ({:.1} Hz, MAC {:.2})", k + 1, q.full_hz, q.mac))
                    .collect()
            })
            .unwrap_or_default()
    };
    for v in 0..pairs.len() {
        let name = v + 1;
        let mut parts = Vec::new();
        for m in AVAILABLE {
            if let Some((k, e)) = worst_below(v, m) {
                let miss = missed(v, m);
                parts.push(format!(
                    "{} worst {:.2} % (mode {k}){}",
                    m.id().to_uppercase(),
                    100.0 * e,
                    if miss.is_empty() {
                        String::new()
                    } else {
                        format!(", MAC < 0.95 on mode {}", miss.join(", "))
                    }
                ));
            }
        }
        out.push_str(&format!(
            "- Variant {name} up to {INTEREST_HZ} Hz ({} modes in the band up to {BAND_HZ} Hz): \
             {}.\n",
            full_hz.get(v).map(|h| h.len()).unwrap_or(0),
            parts.join("; ")
        ));
    }
    // Named claims.
    if let (Some(cb), Some(mm), Some(bt)) = (
        worst_below(0, Method::CraigBampton),
        worst_below(0, Method::MomentMatching),
        worst_below(0, Method::BalancedTruncation),
    ) {
        out.push_str(&format!(
            "- \"Variant 1: BT gives the most accurate results up to 200 Hz\": {}; \"MM has a \
             considerable error on one mode\": its worst is {:.2} % on mode {}.\n",
            verdict(bt.1 <= cb.1 && bt.1 <= mm.1),
            100.0 * mm.1,
            mm.0
        ));
    }
    if let (Some(cb), Some(mm), Some(bt)) = (
        worst_below(1, Method::CraigBampton),
        worst_below(1, Method::MomentMatching),
        worst_below(1, Method::BalancedTruncation),
    ) {
        out.push_str(&format!(
            "- \"Variant 2: CB excellent, MM worse, BT worst\": CB {:.2} %, MM {:.2} %, BT \
             {:.2} % — {}.\n",
            100.0 * cb.1,
            100.0 * mm.1,
            100.0 * bt.1,
            verdict(cb.1 < 0.01 && cb.1 <= mm.1 && mm.1 <= bt.1)
        ));
    }
    let bt_missed: Vec<String> = (0..pairs.len())
        .map(|v| {
            let m = missed(v, Method::BalancedTruncation);
            format!(
                "variant {}: {}",
                v + 1,
                if m.is_empty() {
                    "none".into()
                } else {
                    m.join(", ")
                }
            )
        })
        .collect();
    out.push_str(&format!(
        "- \"BT misses modes the I/O DOF do not see (bottom torsion, the 145 Hz mode)\": BT's \
         modes with MAC < 0.95 — {}.\n",
        bt_missed.join("; ")
    ));
    out
}
