//! The cantilever variants' views: each variant's modes, its table, the static cases and the layout.

use crate::record::{REFERENCE, method_color};
use crate::scenes::mode_visuals::mode_set;
use crate::{
    models::{CANTILEVER_METHODS as AVAILABLE, CantileverStudy, StaticCase, VariantModes},
    record::{Layout, Visual},
    report::{Cell, Table},
};

/// A variant's full modes (each labelled) and the frequency-error and MAC bars per method.
pub(super) fn variant_visuals(study: &CantileverStudy, variant: &VariantModes) -> Vec<Visual> {
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
pub(super) fn variant_table(variant: &VariantModes) -> Table {
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
pub(super) fn static_visuals(case: &StaticCase) -> Vec<Visual> {
    let peak = case.peak();
    let scale = if peak > 0.0 { 300.0 / peak } else { 1.0 };
    let draw = |pts: &[[f64; 2]]| pts.iter().map(|p| [p[0], -p[1] * scale]).collect();
    let mut visuals = vec![Visual::Polyline2D {
        path: format!("statics/{}/full", case.id),
        points: draw(&case.full_line),
        color: REFERENCE,
        label: None,
        radius: crate::record::LINE,
    }];
    let mut legend = vec![
        (case.text.to_string(), REFERENCE),
        (
            format!(
                "full: peak {peak} mm",
                peak = flexmodes_core::report::readable(peak, 4)
            ),
            REFERENCE,
        ),
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
            radius: crate::record::LINE,
        });
        legend.push((
            format!(
                "{}: error {err}",
                m.id().to_uppercase(),
                err = flexmodes_core::report::readable(err, 2)
            ),
            method_color(m),
        ));
    }
    // The legend: labels without markers in a column under the curves (the curves coincide
    // where the methods are exact, so labels on them would overlap), a row apart wherever
    // the view shows the column at least ~270 pixels tall: 160 of the drawing's units are 29
    // pixels there, a label's box 23 (110 were 24: the boxes touched).
    visuals.push(Visual::Text2D {
        path: format!("statics/{}/legend", case.id),
        points: (0..legend.len())
            .map(|k| [500.0, 400.0 + 160.0 * k as f64])
            .collect(),
        labels: legend.iter().map(|(t, _)| t.clone()).collect(),
        colors: legend.iter().map(|(_, c)| *c).collect(),
    });
    visuals
}

/// Modes per variant beside the charts (frequency error, MAC, statics) and the text.
pub(super) fn layout(statics: &[StaticCase]) -> Layout {
    let tabs_of = |what: &str, name: &str| {
        Layout::Tabs(
            (1..=3)
                // No legend (the scene's text names the colours): errors of either sign and
                // MACs near 1 leave no corner of these charts free of bars.
                .map(|v| Layout::BarChart {
                    name: format!("{name} v{v}"),
                    origin: format!("/metrics/{what}/v{v}"),
                    legend: false,
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
