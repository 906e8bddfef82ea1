//! The `modes` scene's interface response: each model's magnitude error against the full
//! body over `--band`, tabulated, and every response charted (semi-log: |H| of the first
//! channel against frequency).

use serde_json::{Map, Value, json};

use crate::{
    Result,
    analysis::FrequencyResponse,
    models::InterfaceResponse,
    record::{Layout, LogLogChart, LogLogSeries, Visual},
    reduction::Method,
    report::{Cell, Table, sig},
};

use crate::record::{REFERENCE, method_color};

/// The table, JSON, chart visuals, the chart's view and a sentence for the text, comparing
/// each method's response (from [`InterfaceResponse::of_model`]) with the full body's.
pub fn response_table(
    response: &InterfaceResponse,
    models: &[(Method, FrequencyResponse)],
) -> Result<(Table, Value, Vec<Visual>, Layout, String)> {
    let mut table = Table::new(&["model", "FRF error over the band"]).rank_lower(&[1]);
    let mut errors = Map::new();
    let magnitude = |h: &FrequencyResponse| -> Vec<(f64, f64)> {
        h.hz.iter().copied().zip(h.magnitude(0, 0)).collect()
    };
    let mut series = vec![LogLogSeries {
        id: "full".into(),
        label: "full".into(),
        color: REFERENCE,
        points: magnitude(&response.full),
        line: true,
    }];
    for (method, h) in models {
        let e = h.relative_magnitude_error(&response.full)?;
        let id = method.id();
        errors.insert(id.into(), json!(sig(e)));
        table.push(vec![
            Cell::text(id.to_uppercase()),
            Cell::number(e, flexmodes_core::report::readable(e, 3).to_string()),
        ]);
        series.push(LogLogSeries {
            id: id.into(),
            label: id.to_uppercase(),
            color: method_color(*method),
            points: magnitude(h),
            line: true,
        });
    }
    let visuals = LogLogChart {
        path: "charts/interface_response".into(),
        x_unit: "Hz".into(),
        y_unit: format!("|H| {}", response.loads.labels[0]),
        series,
        x_linear: true,
    }
    .visuals();
    let view = Layout::Spatial2D {
        name: "interface response |H₁₁| against Hz".into(),
        origin: "/charts/interface_response".into(),
    };
    let json = json!({
        "hz": response.full.hz.iter().map(|&f| sig(f)).collect::<Vec<_>>(),
        "full_s": sig(response.full_s),
        "rel_error": Value::Object(errors),
    });
    let text = format!("FRF error: {}.", response.describe());
    Ok((table, json, visuals, view, text))
}
