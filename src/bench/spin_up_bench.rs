//! `flexmodes bench spin-up`: what dynamic stiffening costs online, measured in one run: Kane
//! et al.'s beam spun up below its first bending frequency (both models stable) by NR and CB
//! with and without the geometric stiffness of the frame's loads, medians of `repeats`
//! runs, and NR against CB at the scene's rates with stiffening. One thread: the models are
//! dense and small.

use serde_json::{Value, json};

use crate::{
    Progress, Result,
    models::{SpinUpModels, SpinUpParameters, model_label},
    record::{Layout, RecordingContent},
    report::{Cell, Report, Table},
};

/// A steady rate below the first bending frequency (3.80 rad/s), rad/s: the unstiffened
/// models stay bounded, so both run the whole interval.
pub const STABLE_RATE: f64 = 3.0;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs the bench: the table, its JSON, and a recording of the table.
pub fn bench_spin_up(
    repeats: usize,
    progress: &Progress,
) -> Result<(Value, String, RecordingContent)> {
    let parameters = SpinUpParameters::default();
    let models = SpinUpModels::new(&parameters)?;
    let repeats = repeats.max(1);
    let steps = (parameters.integration.end / parameters.integration.step).round();
    let mut table = Table::new(&[
        "ω_s, rad/s",
        "model",
        "online with stiffening, s",
        "without, s",
        "with / without",
        "µs per step with",
    ]);
    let mut rows = Vec::new();
    let timed = |rate: f64, modes: usize, stiffening: bool| -> Result<f64> {
        let mut times = Vec::with_capacity(repeats);
        for _ in 0..repeats {
            times.push(models.run(rate, modes, stiffening, progress)?.online_s);
        }
        Ok(median(times))
    };
    for modes in [0, models.reduced_modes()] {
        let with = timed(STABLE_RATE, modes, true)?;
        let without = timed(STABLE_RATE, modes, false)?;
        let label = model_label(modes, true);
        table.push(vec![
            Cell::text(format!("{STABLE_RATE}")),
            Cell::text(label.clone()),
            Cell::number(with, format!("{with:.4}")),
            Cell::number(without, format!("{without:.4}")),
            Cell::number(with / without, format!("{:.2}", with / without)),
            Cell::number(with / steps * 1e6, format!("{:.1}", with / steps * 1e6)),
        ]);
        rows.push(json!({"rate": STABLE_RATE, "model": label, "with_s": with,
                         "without_s": without, "ratio": with / without}));
    }
    let mut speedups = Vec::new();
    for &rate in &parameters.rates {
        let nr = timed(rate, 0, true)?;
        let cb = timed(rate, models.reduced_modes(), true)?;
        speedups.push(json!({"rate": rate, "nr_s": nr, "cb_s": cb, "nr_over_cb": nr / cb}));
    }
    let speed_text: Vec<String> = speedups
        .iter()
        .map(|s| {
            format!(
                "ω_s = {} rad/s: NR {:.4} s, CB {} {:.4} s, {:.0}×",
                s["rate"],
                s["nr_s"].as_f64().unwrap_or(0.0),
                models.reduced_modes(),
                s["cb_s"].as_f64().unwrap_or(0.0),
                s["nr_over_cb"].as_f64().unwrap_or(0.0)
            )
        })
        .collect();
    let text = format!(
        "{}\nMedians of {repeats} runs of {steps} generalized-α steps, one thread. With \
         stiffening, NR against CB at the scene's rates: {}.\n",
        table.markdown(),
        speed_text.join("; ")
    );
    let value = json!({"bench": "spin-up", "repeats": repeats, "threads": 1,
                       "stiffening_cost": rows, "speedup": speedups});
    let mut report = Report::new("bench spin-up");
    report.table = text.clone();
    let recording = RecordingContent {
        report,
        markdown: format!("# bench spin-up\n\n{text}"),
        visuals: Vec::new(),
        layout: Layout::scene_text(),
        timeline: None,
        y_up: true,
    };
    Ok((value, text, recording))
}
