//! `flexmodes bench slab-modes`: offline cost against accuracy of every reduction method and
//! kept-mode count on the slab (App. B or refined): the reduced model's lowest free-free
//! frequencies and its static sag under gravity, held as in Simulation 1, against the full
//! model's.
//!
//! Timings are wall-clock medians measured in one run on this machine; they are reported,
//! never asserted.

use crate::reduction::ReductionError;
use std::time::Instant;

use serde_json::{Value, json};

use crate::{
    Progress, Result,
    analysis::{
        StaticLoadCase, elastic_hz, full_static_response, lowest_free_free_modes, reduced_hz,
        relative_error, ritz_static_response,
    },
    bench::{MODE_SWEEP, pareto_flags, three_digits},
    dynamics::STANDARD_GRAVITY,
    fem::{SlabParameters, slab},
    models::{default_boundary, held_at_six, reduction_nodes},
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::{Method, ModeSelection, ReductionRequest, reduce},
    report::{markdown_table, sig},
};

/// Elastic free-free frequencies compared with the full model's.
pub const COMPARED_MODES: usize = 6;
/// Repeats of each reduction below this many DOF (the median is reported).
const REPEAT_BELOW_DOFS: usize = 2000;
const REPEATS: usize = 3;

/// One method and kept-mode count.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeBenchPoint {
    /// Method.
    pub method: Method,
    /// Kept normal modes (0 for Guyan).
    pub modes: usize,
    /// Generalised coordinates of the reduced model.
    pub coordinates: usize,
    /// Building the basis, s (median of repeats).
    pub offline_s: f64,
    /// Largest relative error of the lowest [`COMPARED_MODES`] elastic free-free frequencies.
    pub freq_rel_error: f64,
    /// Relative error (2-norm) of the static sag under gravity, held at Simulation 1's six
    /// coordinates.
    pub static_rel_error: f64,
    /// Not dominated in (offline cost, the larger of the two errors).
    pub pareto: bool,
}

impl ModeBenchPoint {
    /// The accuracy the Pareto front is drawn for: the larger of the two errors.
    pub fn error(&self) -> f64 {
        self.freq_rel_error.max(self.static_rel_error)
    }
}

/// Benchmarks the reductions of the slab (`bricks`: a refined mesh) and returns the
/// `bench --json` object, the table and the recording of the charts.
pub fn bench_modes(
    bricks: Option<[usize; 3]>,
    progress: &Progress,
) -> Result<(Value, String, RecordingContent)> {
    let model = match bricks {
        Some(b) => slab(&SlabParameters::refined(b)?),
        None => slab(&SlabParameters::default()),
    };
    let boundary = default_boundary(&model);
    progress.phase("full model: lowest free-free modes and static sag")?;
    let start = Instant::now();
    let full_hz = elastic_hz(&lowest_free_free_modes(&model, COMPARED_MODES)?);
    let reference_eigen_s = start.elapsed().as_secs_f64();
    if full_hz.len() < COMPARED_MODES {
        return Err(ReductionError::TooManyModes {
            requested: COMPARED_MODES,
            available: full_hz.len(),
        }
        .into());
    }
    let case = StaticLoadCase::weight(&model, &held_at_six(&model)?, 2, -STANDARD_GRAVITY);
    let start = Instant::now();
    let full_sag = full_static_response(&model, &case)?;
    let reference_static_s = start.elapsed().as_secs_f64();
    let repeats = if model.dof_count() < REPEAT_BELOW_DOFS {
        REPEATS
    } else {
        1
    };
    let mut cases = vec![(Method::Guyan, 0)];
    for m in [
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ] {
        cases.extend(MODE_SWEEP.map(|k| (m, k)));
    }
    let count = cases.len();
    let mut points = Vec::new();
    for (i, (method, k)) in cases.into_iter().enumerate() {
        progress.phase(&format!("point {} of {count}: {} {k}", i + 1, method.id()))?;
        let params = ReductionRequest {
            boundary_nodes: reduction_nodes(&model, method, &boundary),
            modes: ModeSelection::Count(k),
            ..Default::default()
        };
        let mut times = Vec::new();
        let mut basis = None;
        for _ in 0..repeats {
            let start = Instant::now();
            basis = Some(reduce(&model, &params.with_method(method))?);
            times.push(start.elapsed().as_secs_f64());
        }
        let basis = basis.expect("at least one repeat");
        times.sort_by(f64::total_cmp);
        let hz: Vec<f64> = reduced_hz(&model, &basis)?;
        let compared = hz.len().min(COMPARED_MODES);
        let freq_rel_error = if compared == 0 {
            f64::INFINITY
        } else {
            (0..compared)
                .map(|j| (hz[j] - full_hz[j]).abs() / full_hz[j])
                .fold(0.0f64, f64::max)
        };
        let sag = ritz_static_response(&model, &basis, &case)?;
        points.push(ModeBenchPoint {
            method,
            modes: k,
            coordinates: basis.size(),
            offline_s: times[times.len() / 2],
            freq_rel_error,
            static_rel_error: relative_error(&sag, &full_sag),
            pareto: false,
        });
    }
    // Errors equal to three significant digits count as equal: CB and MC span one space
    // and differ only by round-off, which must not put the slower of the two on the front.
    let flags = pareto_flags(
        &points
            .iter()
            .map(|p| (p.offline_s, three_digits(p.error())))
            .collect::<Vec<_>>(),
    );
    for (p, f) in points.iter_mut().zip(flags) {
        p.pareto = f;
    }
    let rows: Vec<Vec<String>> = points
        .iter()
        .map(|p| {
            vec![
                p.method.id().into(),
                p.modes.to_string(),
                p.coordinates.to_string(),
                crate::report::sig3(p.offline_s),
                crate::report::sig3(p.freq_rel_error),
                crate::report::sig3(p.static_rel_error),
                if p.pareto { "★" } else { "" }.to_string(),
            ]
        })
        .collect();
    let table = format!(
        "The slab with {} DOF held at nodes {boundary:?} (Guyan adds App. B's nodes 5 and 11). \
         Frequency error: the largest relative error of the lowest {COMPARED_MODES} elastic \
         free-free frequencies against the full model's ({} s by the partial eigensolver). \
         Static error: the sag under gravity held at Simulation 1's six coordinates (d16 x y z, \
         d18 x, d28 z, d30 z), Ritz solution in each basis against the full model's sparse \
         solve ({} s), relative 2-norm. Offline s: building the basis, median of {repeats}. \
         ★ marks the Pareto front in (offline s, the larger of the two errors, equal when equal to three significant digits).\n\n{}",
        model.dof_count(),
        flexmodes_core::report::readable(reference_eigen_s, 3),
        flexmodes_core::report::readable(reference_static_s, 3),
        markdown_table(
            &[
                "method",
                "modes",
                "coordinates",
                "offline s",
                "freq. error",
                "static error",
                "Pareto",
            ],
            &rows,
        )
    );
    let json = json!({
        "scene": "slab-modes",
        "dofs": model.dof_count(),
        "reference": {
            "hz": full_hz.iter().map(|&f| sig(f)).collect::<Vec<_>>(),
            "eigen_s": sig(reference_eigen_s),
            "static_s": sig(reference_static_s),
        },
        "points": points.iter().map(|p| json!({
            "method": p.method.id(),
            "modes": p.modes,
            "dofs": p.coordinates,
            "offline_s": sig(p.offline_s),
            "freq_rel_error": sig(p.freq_rel_error),
            "static_rel_error": sig(p.static_rel_error),
            "pareto": p.pareto,
        })).collect::<Vec<_>>(),
    });
    let recording = charts(&points, &table);
    Ok((json, table, recording))
}

/// Frequency error (bright) and static error (pale) against kept modes, per method that
/// keeps normal modes.
fn convergence_series(points: &[ModeBenchPoint], methods: &[Method]) -> Vec<LogLogSeries> {
    let of = |m: Method| points.iter().filter(move |p| p.method == m);
    methods
        .iter()
        .filter(|m| m.keeps_normal_modes())
        .flat_map(|&m| {
            let c = method_color(m);
            [
                LogLogSeries {
                    id: format!("{}_freq", m.id()),
                    label: format!("{} freq.", m.id().to_uppercase()),
                    color: c,
                    points: of(m).map(|p| (p.modes as f64, p.freq_rel_error)).collect(),
                    line: true,
                },
                LogLogSeries {
                    id: format!("{}_static", m.id()),
                    label: format!("{} static", m.id().to_uppercase()),
                    color: [c[0] / 2 + 60, c[1] / 2 + 60, c[2] / 2 + 60, 255],
                    points: of(m)
                        .map(|p| (p.modes as f64, p.static_rel_error))
                        .collect(),
                    line: true,
                },
            ]
        })
        .collect()
}

/// Error against offline cost (log–log) per method through its kept-mode counts with the
/// Pareto front, and frequency and static error against kept modes.
fn charts(points: &[ModeBenchPoint], table: &str) -> RecordingContent {
    let mut methods: Vec<Method> = Vec::new();
    for p in points {
        if !methods.contains(&p.method) {
            methods.push(p.method);
        }
    }
    let of = |m: Method| points.iter().filter(move |p| p.method == m);
    let mut cost: Vec<LogLogSeries> = methods
        .iter()
        .map(|&m| LogLogSeries {
            id: m.id().into(),
            label: m.id().to_uppercase(),
            color: method_color(m),
            points: of(m).map(|p| (p.offline_s, p.error())).collect(),
            line: true,
        })
        .collect();
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.pareto)
        .map(|p| (p.offline_s, p.error()))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    cost.push(LogLogSeries {
        id: "pareto_front".into(),
        label: "Pareto".into(),
        color: crate::record::PARETO,
        points: front,
        line: true,
    });
    let convergence = convergence_series(points, &methods);
    let mut visuals = LogLogChart {
        path: "bench/error_vs_offline".into(),
        x_unit: "offline time, s".into(),
        y_unit: "larger of freq. and static rel. error".into(),
        series: cost,
        x_linear: false,
    }
    .visuals();
    visuals.extend(
        LogLogChart {
            path: "bench/error_vs_modes".into(),
            x_unit: "kept modes".into(),
            y_unit: "rel. error".into(),
            series: convergence,
            x_linear: false,
        }
        .visuals(),
    );
    let mut report = crate::report::Report::new("bench-slab-modes");
    report.table = table.to_string();
    RecordingContent {
        report,
        markdown: format!(
            "# bench slab-modes\n\nLeft: the larger of frequency and static error against \
             the offline cost of building the basis (log–log), one line per method through \
             2, 4, 6, 12 kept modes, the Pareto front in dark grey. Right: frequency error \
             (bright) and static error (pale) against kept modes. Craig–Bampton and mode \
             condensation span one space, so their errors coincide; on App. B's 90 DOF every \
             reduction takes about a millisecond and the cost axis is mostly timer noise — \
             `--refine` makes the costs differ. The table gives the numbers.\n\n{table}"
        ),
        visuals,
        layout: Layout::bench_charts(
            (
                "error against offline s (log–log)",
                "/bench/error_vs_offline",
            ),
            (
                "error against kept modes (log–log)",
                "/bench/error_vs_modes",
            ),
            1.2,
        ),
        timeline: None,
        y_up: false,
    }
}
