//! The recording of `flexmodes simulate --save`: the body deforming in the turning frame, one
//! lane per model; each output's history per model; online time against history error
//! (log–log) with the Pareto front.

use crate::{
    analysis::{pareto_flags, three_digits},
    fem::FeModel,
    models::{DrivenRun, DrivenStudy},
    record::{Color, Geometry, Layout, LogLogChart, LogLogSeries, RecordingContent, Visual},
    reduction::Method,
    report::Report,
};

use crate::record::method_color;
use crate::scenes::slab::sim_visuals::display_scale;

/// Grey of the undeformed ghost in each lane.
const GHOST: Color = [110, 110, 110, 255];

/// Most samples drawn in the 3-D view (every sample is in the plots).
const DRAWN_SAMPLES: usize = 60;

fn color(run: &DrivenRun) -> Color {
    method_color(run.method.unwrap_or(Method::NoReduction))
}

/// The runs drawn in 3-D: the full body and, per method, its largest model.
fn drawn(study: &DrivenStudy) -> Vec<&DrivenRun> {
    let mut out: Vec<&DrivenRun> = Vec::new();
    for run in &study.runs {
        match out.iter_mut().find(|r| r.method == run.method) {
            Some(r) if run.modes > r.modes => *r = run,
            Some(_) => {}
            None => out.push(run),
        }
    }
    out
}

/// The recording: `text` is the table the CLI prints; `length_unit` the body's (`m`, `mm`).
pub fn recording(
    model: &FeModel,
    study: &DrivenStudy,
    text: &str,
    length_unit: &str,
) -> RecordingContent {
    let (mut visuals, scale) = lanes(model, study);
    let plots = output_plots(study, length_unit, &mut visuals);
    visuals.extend(chart(study));
    // The table's title line is a heading in a terminal, a paragraph in the panel.
    let text = text.strip_prefix("# ").unwrap_or(text);
    let mut report = Report::new("simulate");
    // The runs' table registered, so the explorer draws it as a grid with its ranks.
    report.add_table(crate::scenes::body::body_simulation::runs_table(study));
    report.table = text.to_string();
    let view = if scale != 1.0 {
        format!("turning frame, one lane per model (deflection ×{scale}; grey: undeformed)")
    } else {
        "turning frame, one lane per model (grey: undeformed)".to_string()
    };
    let right = Layout::Vertical(
        vec![
            Layout::Spatial2D {
                name: "history error against online s (log–log)".into(),
                origin: "/bench/error_vs_online".into(),
            },
            Layout::scene_text(),
        ],
        vec![1.0, 1.0],
    );
    let left = Layout::Vertical(
        vec![
            Layout::view3d(&view, "/world/body"),
            Layout::Horizontal(plots, vec![]),
        ],
        vec![1.5, 1.0],
    );
    RecordingContent {
        report,
        markdown: format!(
            "# simulate\n\nLeft: the body in the frame that turns with the drive, one lane per \
             model (the full body and each method's largest model), its deflection magnified; \
             below, each output's largest component over time per model. Right: each reduced \
             model's history error against its online time (log–log), one line per method \
             through its mode counts, the Pareto front in dark grey.\n\n{text}"
        ),
        visuals,
        layout: Layout::Horizontal(vec![left, right], vec![2.0, 1.0]),
        timeline: Some("sim_time".into()),
        y_up: false,
    }
}

/// One lane per drawn model (its undeformed ghost, label and deforming body), and the
/// deflection's display scale.
fn lanes(model: &FeModel, study: &DrivenStudy) -> (Vec<Visual>, f64) {
    let geometry = Geometry::of(model);
    let drawn_runs = drawn(study);
    let largest = study
        .runs
        .iter()
        .flat_map(|r| r.states.iter().map(move |x| (r, x)))
        .map(|(r, x)| {
            r.field_map
                .field(x)
                .chunks_exact(3)
                .map(|u| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    let scale = display_scale(largest, model.size());
    let width = {
        let ys = geometry.nodes.iter().map(|p| p[1]);
        (ys.clone().fold(f64::MIN, f64::max) - ys.fold(f64::MAX, f64::min)).max(0.2 * model.size())
    };
    let top = geometry.nodes.iter().map(|p| p[2]).fold(f64::MIN, f64::max);
    let every = study.times.len().div_ceil(DRAWN_SAMPLES).max(1);
    let mut visuals = Vec::new();
    for (k, run) in drawn_runs.iter().enumerate() {
        let lane = format!(
            "world/body/{}",
            run.label().to_lowercase().replace(' ', "_")
        );
        visuals.push(Visual::Offset {
            path: lane.clone(),
            translation: [0.0, -1.5 * width * k as f64, 0.0],
        });
        visuals.push(Visual::Wireframe {
            path: format!("{lane}/undeformed"),
            geometry: geometry.clone(),
            color: GHOST,
            label: None,
        });
        visuals.push(Visual::Label3D {
            path: format!("{lane}/label"),
            position: [geometry.nodes[0][0], 0.0, top + 0.3 * width],
            text: run.label(),
            color: color(run),
        });
        let (times, positions): (Vec<f64>, Vec<Vec<[f64; 3]>>) = study
            .times
            .iter()
            .zip(&run.states)
            .step_by(every)
            .map(|(&t, x)| {
                let u = run.field_map.field(x);
                let nodes = geometry
                    .nodes
                    .iter()
                    .enumerate()
                    .map(|(j, p)| [0, 1, 2].map(|a| p[a] + scale * u[3 * j + a]))
                    .collect();
                (t, nodes)
            })
            .unzip();
        visuals.push(Visual::Trajectory {
            path: format!("{lane}/deformed"),
            geometry: geometry.clone(),
            times,
            positions,
            color: color(run),
        });
    }
    (visuals, scale)
}

/// Each output's largest component (by the first run) over time, one series per model into
/// `visuals`, and their time-series views.
fn output_plots(study: &DrivenStudy, length_unit: &str, visuals: &mut Vec<Visual>) -> Vec<Layout> {
    let mut plots = Vec::new();
    for (o, name) in study.output_names.iter().enumerate() {
        let Some(first) = study.runs.first() else {
            break;
        };
        let axis = (0..3)
            .max_by(|&a, &b| {
                let amp = |a: usize| {
                    first.outputs[o]
                        .iter()
                        .map(|u| u[a].abs())
                        .fold(0.0, f64::max)
                };
                amp(a).total_cmp(&amp(b))
            })
            .unwrap_or(0);
        let axis_name = ["x", "y", "z"][axis];
        // In the unit whose values read as 1 to 1 000 (nm, not "−0.000 000 01" m).
        let amplitude = study
            .runs
            .iter()
            .flat_map(|r| r.outputs[o].iter().map(|u| u[axis].abs()))
            .fold(0.0, f64::max);
        let (factor, unit) = readable_length(amplitude, length_unit);
        for run in &study.runs {
            visuals.push(Visual::Series {
                path: format!("plots/{name}_{axis_name}/{}", run.label().replace(' ', "_")),
                times: study.times.clone(),
                values: run.outputs[o].iter().map(|u| u[axis] * factor).collect(),
                name: run.label(),
                color: color(run),
            });
        }
        plots.push(Layout::TimeSeries {
            name: format!("{axis_name} of {name}, {unit} (mean, turning frame)"),
            origin: format!("/plots/{name}_{axis_name}"),
        });
    }
    plots
}

/// History error against online time per method, and the Pareto front.
fn chart(study: &DrivenStudy) -> Vec<Visual> {
    let reduced: Vec<&DrivenRun> = study
        .runs
        .iter()
        .filter(|r| r.history_error.is_some())
        .collect();
    if reduced.is_empty() {
        return Vec::new();
    }
    let point = |r: &DrivenRun| (r.cost.online_s, r.history_error.unwrap_or(f64::NAN));
    // One line per method and scheme through its mode counts.
    let mut keys: Vec<(Method, bool)> = Vec::new();
    for r in &reduced {
        if let Some(m) = r.method {
            let key = (m, r.explicit_step.is_some());
            if !keys.contains(&key) {
                keys.push(key);
            }
        }
    }
    let mut series: Vec<LogLogSeries> = keys
        .iter()
        .map(|&(m, explicit)| {
            let mut points: Vec<(f64, f64)> = reduced
                .iter()
                .filter(|r| r.method == Some(m) && r.explicit_step.is_some() == explicit)
                .map(|r| point(r))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let suffix = if explicit { " DP5" } else { "" };
            LogLogSeries {
                id: format!("{}{}", m.id(), suffix.replace(' ', "_").to_lowercase()),
                label: format!("{}{suffix}", m.id().to_uppercase()),
                color: method_color(m),
                points,
                line: true,
            }
        })
        .collect();
    let cost_error: Vec<(f64, f64)> = reduced
        .iter()
        .map(|r| (r.cost.online_s, three_digits(point(r).1)))
        .collect();
    let mut front: Vec<(f64, f64)> = reduced
        .iter()
        .zip(pareto_flags(&cost_error))
        .filter(|(_, on)| *on)
        .map(|(r, _)| point(r))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    series.push(LogLogSeries {
        id: "pareto_front".into(),
        label: "Pareto".into(),
        color: crate::record::PARETO,
        points: front,
        line: true,
    });
    LogLogChart {
        path: "bench/error_vs_online".into(),
        x_unit: "online s".into(),
        y_unit: "history error".into(),
        series,
        x_linear: false,
    }
    .visuals()
}

/// The factor and unit that show lengths of magnitude up to `amplitude` (in `unit`) as
/// numbers from 1 to 1 000: `m` becomes `mm`, `µm` or `nm`, `mm` becomes `µm` or `nm`; any
/// other unit, or an amplitude of 0, keeps its own.
pub fn readable_length(amplitude: f64, unit: &str) -> (f64, String) {
    let prefixes: &[(f64, &str)] = match unit {
        "m" => &[(1.0, "m"), (1e3, "mm"), (1e6, "µm"), (1e9, "nm")],
        "mm" => &[(1.0, "mm"), (1e3, "µm"), (1e6, "nm")],
        _ => &[],
    };
    prefixes
        .iter()
        .find(|(f, _)| amplitude * f >= 1.0)
        .or(prefixes.last().filter(|_| amplitude > 0.0))
        .filter(|_| amplitude > 0.0 && amplitude.is_finite())
        .map_or((1.0, unit.to_string()), |&(f, u)| (f, u.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_are_shown_in_the_unit_that_reads_one_to_a_thousand() {
        let case = |a: f64, unit: &str| {
            let (f, u) = readable_length(a, unit);
            (format!("{}", crate::report::sig(a * f)), u)
        };
        assert_eq!(case(1.3e-8, "m"), ("13".into(), "nm".into()));
        assert_eq!(case(2.5e-5, "m"), ("25".into(), "µm".into()));
        assert_eq!(case(0.004, "m"), ("4".into(), "mm".into()));
        assert_eq!(case(1.5, "m"), ("1.5".into(), "m".into()));
        assert_eq!(case(3e-4, "mm"), ("300".into(), "nm".into()));
        assert_eq!(case(2e-12, "m"), ("0.002".into(), "nm".into()));
        // Another unit, or nothing to scale: as given.
        assert_eq!(case(1e-6, "in"), ("0.000001".into(), "in".into()));
        assert_eq!(readable_length(0.0, "m"), (1.0, "m".into()));
    }
}
