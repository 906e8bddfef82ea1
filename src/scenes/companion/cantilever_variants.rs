//! `cantilever-variants`: Witteveen (World J. Mech. 2012) §4. Craig–Bampton, Krylov moment
//! matching and balanced truncation, 14 vectors each, built once on a clamped beam structure
//! and then used under boundary conditions changed on the reduced models only. The numbers
//! are [`crate::models::cantilever_study`]'s; this scene draws and tabulates them.

use crate::record::REFERENCE;
use serde_json::{Map, Value, json};

use crate::scenes::companion::cantilever_text::{claims_text, scene_text};
use crate::scenes::companion::cantilever_views::{
    layout, static_visuals, variant_table, variant_visuals,
};
use crate::scenes::{SceneInfo, SceneOptions, SceneOutput};
use crate::{
    Result,
    models::{BAND_HZ, CANTILEVER_METHODS as AVAILABLE, CantileverStudy, cantilever_study},
    record::{Geometry, Visual},
    report::{Cell, Report, Table, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "cantilever-variants",
    recording_cost: 2,
    summary: "Witteveen §4: CB (7+7), Krylov moment matching (2×7) and balanced truncation (14) \
              built once on a clamped beam structure, then with A clamped (variant 2) and A \
              sliding with 250 kg (variant 3): static deflections, frequency errors and MAC",
    sections: "Witteveen 2012 §4",
    controls: crate::scenes::scene_info::SceneControls::methods_only(
        &AVAILABLE,
        "the bases are Witteveen's: the seven I/O DOF, 7 constraint + 7 fixed-interface \
         modes, 2 Krylov blocks, 14 balanced vectors",
    ),
};

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let methods = opts.methods_or(INFO.name, &AVAILABLE, &AVAILABLE)?;
    let study = cantilever_study(&methods)?;
    let (params, frame) = (&study.params, &study.frame);
    let model = &frame.model;

    let mut report = Report::new(INFO.name);
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
            position: model.position(model.node_index(node)?),
            text: name.into(),
            color: [250, 80, 80, 255],
        });
    }

    let dynamics_text = dynamics_section(&study, &mut report, &mut visuals);

    let static_md = statics_section(&study, &mut report, &mut visuals);
    let cal_md = calibration_section(&study, &mut report);

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
    Ok(SceneOutput::new(
        report,
        markdown,
        visuals,
        layout(&study.statics),
    ))
}

/// The dynamics: the full model and each reduced one under each variant (their frequency
/// errors and MACs into the results, their visuals, and one table per variant, returned as
/// markdown).
fn dynamics_section(
    study: &CantileverStudy,
    report: &mut Report,
    visuals: &mut Vec<Visual>,
) -> String {
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
        visuals.extend(variant_visuals(study, variant));
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
    dynamics_text
}

/// The statics: each load case's peak and each model's error against the full model (its
/// results, its visuals and its table, returned as markdown).
fn statics_section(
    study: &CantileverStudy,
    report: &mut Report,
    visuals: &mut Vec<Visual>,
) -> String {
    let mut static_errors: Map<String, Value> = Map::new();
    let mut static_table = Table::new(&["load case", "full peak, mm", "CB", "MM", "BT"]);
    for case in &study.statics {
        let peak = case.peak();
        let mut row = vec![
            Cell::text(case.id.to_uppercase()),
            Cell::number(peak, flexmodes_core::report::readable(peak, 5).to_string()),
        ];
        for m in AVAILABLE {
            match case.error(m) {
                Some(err) => {
                    static_errors
                        .entry(m.id())
                        .or_insert_with(|| Value::Object(Map::new()))
                        .as_object_mut()
                        .map(|o| o.insert(case.id.into(), json!(sig(err))));
                    row.push(Cell::number(
                        err,
                        flexmodes_core::report::readable(err, 3).to_string(),
                    ));
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
    report.add_table(static_table)
}

/// The calibration against Witteveen's printed frequencies and first torsion modes (its
/// results and its table, returned as markdown).
fn calibration_section(study: &CantileverStudy, report: &mut Report) -> String {
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
    report.add_table(cal_table)
}
