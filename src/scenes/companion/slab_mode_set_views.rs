//! The slab mode sets' views: the kept sets, the frequency series and the layout.

use crate::record::{REFERENCE, method_color};
use crate::scenes::mode_visuals::mode_set;
use crate::{
    analysis::FrequencyResponse,
    models::DualSpinStudy,
    record::{Color, Geometry, Layout, LogLogChart, LogLogSeries, Visual},
};

/// The two rotor selections: report key and label.
pub(super) const SELECTIONS: [(&str, &str); 2] =
    [("influence", "by influence"), ("lowest", "lowest")];

/// The assembly, its modes, the FRF charts and the influence bars.
pub(super) fn visuals(study: &DualSpinStudy) -> Vec<Visual> {
    let ds = &study.ds;
    let mut visuals = vec![Visual::Wireframe {
        path: "assembly/undeformed".into(),
        geometry: Geometry::of(&ds.assembly),
        color: REFERENCE,
        label: None,
    }];
    for (path, node, text) in [
        ("assembly/motor", ds.hub, "motor: torque about z at the hub"),
        (
            "assembly/platform",
            ds.platform,
            "platform (40 kg): sensors θz, θx",
        ),
        ("assembly/ground", ds.ground, "ground"),
    ] {
        visuals.push(Visual::Label3D {
            path: path.into(),
            position: ds.assembly.nodes[node],
            text: text.into(),
            color: [250, 80, 80, 255],
        });
    }
    let shapes: Vec<(Vec<f64>, String)> = study
        .shapes
        .iter()
        .enumerate()
        .map(|(j, (u, hz))| (u.clone(), format!("{} · {hz:.2} Hz", j + 1)))
        .collect();
    visuals.extend(mode_set(&ds.assembly, "assembly", &shapes, REFERENCE));
    let reference = &study.reference;
    let mut set_series = vec![series("full", "full", REFERENCE, reference, 0)];
    let mut roll_series = vec![series("full", "full", REFERENCE, reference, 1)];
    for set in &study.sets {
        let (m, up) = (set.method, set.method.id().to_uppercase());
        set_series.push(series(m.id(), &up, method_color(m), &set.frf, 0));
        roll_series.push(series(m.id(), &up, method_color(m), &set.frf, 1));
    }
    let mut sel_series = vec![series("full", "full", REFERENCE, reference, 0)];
    for ((id, label), (chosen, color)) in SELECTIONS.iter().zip(
        study
            .selections
            .iter()
            .zip([KEPT_COLOR, [220, 60, 60, 255]]),
    ) {
        sel_series.push(series(id, label, color, &chosen.frf, 0));
    }
    for (path, s) in [
        ("frf/sets_yaw", set_series),
        ("frf/sets_roll", roll_series),
        ("frf/selection_yaw", sel_series),
    ] {
        visuals.extend(
            LogLogChart {
                path: path.into(),
                x_unit: "Hz".into(),
                y_unit: "rad/(N m)".into(),
                series: s,
                x_linear: true,
            }
            .visuals(),
        );
    }
    let ranking = &study.ranking;
    let rigid = ranking.modes.rigid;
    let top = ranking.sigma[rigid..]
        .iter()
        .fold(0.0f64, |a, &b| a.max(b))
        .max(f64::MIN_POSITIVE);
    for (id, pick, color) in [
        ("kept", true, KEPT_COLOR),
        ("dropped", false, [150, 150, 150, 255]),
    ] {
        let idx: Vec<usize> = (rigid..ranking.modes.mode_count())
            .filter(|i| ranking.influence.contains(i) == pick)
            .collect();
        visuals.push(Visual::SeriesBars {
            path: format!("influence/{id}"),
            abscissa: idx.iter().map(|&i| (i - rigid + 1) as f64).collect(),
            values: idx
                .iter()
                .map(|&i| (ranking.sigma[i] / top).max(1e-12).log10() + 12.0)
                .collect(),
            width: 0.8,
            color,
        });
    }
    visuals
}

/// The colour of the rotor modes kept by influence.
pub(super) const KEPT_COLOR: Color = [60, 130, 240, 255];

/// The assembly and its modes beside the FRF charts, the influence bars and the text.
pub(super) fn layout() -> Layout {
    Layout::Horizontal(
        vec![
            Layout::Tabs(vec![
                Layout::view3d("assembly", "/assembly"),
                Layout::view3d("modes", "/modes/assembly"),
            ]),
            Layout::Vertical(
                vec![
                    Layout::Tabs(vec![
                        Layout::Spatial2D {
                            name: "θz FRF: sets".into(),
                            origin: "/frf/sets_yaw".into(),
                        },
                        Layout::Spatial2D {
                            name: "θx FRF: sets".into(),
                            origin: "/frf/sets_roll".into(),
                        },
                    ]),
                    Layout::Spatial2D {
                        name: "θz FRF: influence".into(),
                        origin: "/frf/selection_yaw".into(),
                    },
                    Layout::BarChart {
                        name: "rotor σ (blue kept)".into(),
                        origin: "/influence".into(),
                        legend: true,
                    },
                ],
                vec![1.2, 1.2, 0.8],
            ),
            Layout::scene_text(),
        ],
        vec![2.0, 2.2, 1.8],
    )
}

/// A chart series: |G| of channel (output r, the only input) against frequency.
pub(super) fn series(
    id: &str,
    label: &str,
    color: Color,
    frf: &FrequencyResponse,
    output: usize,
) -> LogLogSeries {
    LogLogSeries {
        id: id.into(),
        label: label.into(),
        color,
        points: frf
            .hz
            .iter()
            .copied()
            .zip(frf.magnitude(output, 0))
            .collect(),
        line: true,
    }
}
