//! `flexmodes bench`: speed against accuracy of every method on the slab simulations, and
//! where explicit integration becomes unstable.
//!
//! Timings are wall-clock ratios measured in one run on this machine; they are reported, never
//! asserted.

use crate::dynamics::{DynamicsError, Simulation, State, System};
use std::time::Instant;

use serde_json::{Map, Value, json};

use super::bench_point::{
    ABOVE_CRITICAL, BELOW_CRITICAL, BenchPoint, LOOSE_ATOL, LOOSE_RTOL, STABILITY_RUN_S,
};
use super::mark_pareto;
use super::simulation_bench_text::{bench_json, bench_text, point_rows};
use crate::{
    Progress, Result,
    analysis::reduced_modes,
    analysis::relative_rms,
    dynamics::{
        AxisType, DEFAULT_SPECTRAL_RADIUS, IntegrationScheme, IntegratorParameters,
        imaginary_stability_limit, simulate,
    },
    error::CoreError,
    fem::{SlabParameters, slab},
    models::{
        PROBE_NODE, Scenario, default_boundary, probe_history, slab_body, slab_node, slab_system,
    },
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::{Method, NodalFixedAxes},
    report::sig,
};

/// Kept-mode counts swept for the methods that keep normal modes.
pub(crate) const MODE_SWEEP: [usize; 4] = [2, 4, 6, 12];

/// The schemes `bench` compares when none is named: the explicit one with adaptive steps and
/// the implicit one with its default step.
pub const BENCH_SCHEMES: [IntegrationScheme; 2] = [
    IntegrationScheme::DormandPrince,
    IntegrationScheme::GeneralizedAlpha {
        spectral_radius: DEFAULT_SPECTRAL_RADIUS,
    },
];

/// The simulation a bench integrates: slab-sim1's or slab-sim2's (slab-sim3 needs its
/// recorded driving tables and is not benchmarked).
pub(crate) fn bench_scenario(scene: &'static str) -> Result<Scenario> {
    match scene {
        "slab-sim1" => Ok(Scenario::HeldAtSix),
        "slab-sim2" => Ok(Scenario::Orbit),
        other => Err(crate::Error::NotBenchable { scene: other }),
    }
}

/// Runs the benchmark of one simulation scene with each of `schemes` (all of
/// [`BENCH_SCHEMES`] when empty; the explicit scheme, when among them, first: its full-model
/// run is the reference of every error), each integration `repeats` times for the median
/// online cost, and returns the `bench --json` object.
pub fn bench_simulation(
    scene: &'static str,
    schemes: &[IntegrationScheme],
    bricks: Option<[usize; 3]>,
    repeats: usize,
    progress: &Progress,
) -> Result<(Value, String, RecordingContent)> {
    let mut schemes = schemes.to_vec();
    if schemes.is_empty() {
        schemes = BENCH_SCHEMES.to_vec();
    }
    schemes.sort_by_key(|s| !matches!(s, IntegrationScheme::DormandPrince));
    let scenario = bench_scenario(scene)?;
    let model = match bricks {
        Some(b) => slab(&SlabParameters::refined(b)?),
        None => slab(&SlabParameters::default()),
    };
    let boundary = default_boundary(&model);
    let probe = slab_node(&model, PROBE_NODE);
    let axes = AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let t_end = scenario.end_time();
    let mut cases = vec![(Method::NoReduction, 0), (Method::Guyan, 0)];
    for m in [
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ] {
        for k in MODE_SWEEP {
            cases.push((m, k));
        }
    }
    let y_star = imaginary_stability_limit();
    let mut points = Vec::new();
    let mut reference: Option<[Vec<f64>; 3]> = None;
    let mut stability = Map::new();
    let mut stability_rows = Vec::new();
    let count = cases.len();
    for (i, (m, k)) in cases.into_iter().enumerate() {
        progress.phase(&format!(
            "point {} of {count}: {}{}",
            i + 1,
            m.id(),
            if m.keeps_normal_modes() {
                format!(" {k} modes")
            } else {
                String::new()
            }
        ))?;
        let start = Instant::now();
        let body = slab_body(&model, m, axes, &boundary, k)?;
        let offline_s = start.elapsed().as_secs_f64();
        // Highest frequency the integrator has to resolve: the reduced model held by the
        // nodal-fixed frame (its anchors are the determinate supports).
        let hz = reduced_modes(&model, &body.basis)?.hz();
        let highest_hz = hz.last().copied().unwrap_or(0.0);
        let dofs = body.modes();
        let (system, state) = slab_system(&scenario, body)?;
        let runs = scheme_runs(
            &system,
            &state,
            &schemes,
            (t_end, repeats),
            probe,
            (m, &mut reference),
            progress,
        )?;
        let key = if m.keeps_normal_modes() {
            format!("{}_{k}", m.id())
        } else {
            m.id().to_string()
        };
        let omega = 2.0 * std::f64::consts::PI * highest_hz;
        let critical = if omega > 0.0 {
            y_star / omega
        } else {
            f64::INFINITY
        };
        let checks = StabilityChecks::run(
            &system,
            &state,
            critical,
            t_end,
            &schemes,
            (i + 1, count),
            progress,
        )?;
        let (below_ok, above_diverged, implicit_above_bounded) = (
            checks.below_ok,
            checks.above_diverged,
            checks.implicit_above_bounded,
        );
        let mut entry = json!({
            "highest_hz": sig(highest_hz),
            "critical_dt_s": if critical.is_finite() { sig(critical) } else { f64::INFINITY },
            "run_below_ok": below_ok,
            "run_above_diverged": above_diverged,
        });
        if let Some(bounded) = implicit_above_bounded {
            entry["implicit_above_bounded"] = json!(bounded);
        }
        stability.insert(key.clone(), entry);
        stability_rows.push(vec![
            key,
            format!("{highest_hz:.1}"),
            format!(
                "{critical}",
                critical = flexmodes_core::report::readable(critical, 4)
            ),
            if below_ok { "bounded" } else { "DIVERGED" }.to_string(),
            if above_diverged {
                "diverged"
            } else {
                "BOUNDED"
            }
            .to_string(),
            match implicit_above_bounded {
                Some(true) => "bounded",
                Some(false) => "FAILED",
                None => "-",
            }
            .to_string(),
        ]);
        for (scheme, rtol, sim, err, online_wall_s) in runs {
            points.push(BenchPoint {
                method: m,
                modes: k,
                dofs,
                offline_s,
                online_s_per_sim_s: online_wall_s / t_end,
                rel_rms_error: err,
                steps: sim.steps,
                evaluations: sim.evaluations,
                us_per_evaluation: online_wall_s * 1e6 / sim.evaluations.max(1) as f64,
                integrator: scheme,
                rtol,
                pareto: false,
            });
        }
    }
    mark_pareto(&mut points);
    let rows = point_rows(&points);
    let table = bench_text(&schemes, repeats, &rows, &stability_rows, &points);
    let json = bench_json(scene, model.dof_count(), &points, stability);
    let recording = speed_accuracy_charts(scene, &points, &table);
    Ok((json, table, recording))
}

/// One run of a bench point: the scheme, its rtol when it is Dormand–Prince, the simulation,
/// node 8's mean relative RMS error against NR and the median online wall time (s).
type SchemeRun = (IntegrationScheme, Option<f64>, Simulation, f64, f64);

/// Every scheme at the scenes' settings (Dormand–Prince also at the loose tolerances) on one
/// reduced system, each timed `repeats` times (median); the first NR run becomes `reference`.
fn scheme_runs(
    system: &System,
    state: &State,
    schemes: &[IntegrationScheme],
    timing: (f64, usize),
    probe: usize,
    case: (Method, &mut Option<[Vec<f64>; 3]>),
    progress: &Progress,
) -> Result<Vec<SchemeRun>> {
    let (m, reference) = case;
    let (t_end, repeats) = timing;
    let mut runs = Vec::new();
    // Each scheme at the scenes' settings; Dormand–Prince also at the loose tolerances.
    let defaults = IntegratorParameters::default();
    let settings: Vec<(IntegrationScheme, Option<(f64, f64)>)> = schemes
        .iter()
        .flat_map(|&scheme| match scheme {
            IntegrationScheme::DormandPrince => vec![
                (scheme, Some((defaults.rtol, defaults.atol))),
                (scheme, Some((LOOSE_RTOL, LOOSE_ATOL))),
            ],
            _ => vec![(scheme, None)],
        })
        .collect();
    for (scheme, tolerances) in settings {
        let (rtol, atol) = tolerances.unwrap_or((defaults.rtol, defaults.atol));
        let rtol_reported = tolerances.map(|(r, _)| r);
        let params = IntegratorParameters {
            scheme,
            end_time: t_end,
            rtol,
            atol,
            ..defaults.clone()
        };
        let sim = simulate(system, state, &params, progress)?;
        // The online cost is the median wall time of `repeats` identical runs.
        let mut walls = vec![sim.wall_time_s];
        for _ in 1..repeats.max(1) {
            walls.push(simulate(system, state, &params, progress)?.wall_time_s);
        }
        walls.sort_by(f64::total_cmp);
        let online_wall_s = walls[walls.len() / 2];
        let hist = probe_history(system, &sim, probe);
        if m == Method::NoReduction && reference.is_none() {
            *reference = Some(hist.clone());
        }
        let err = match reference {
            Some(r) => (0..3).map(|d| relative_rms(&hist[d], &r[d])).sum::<f64>() / 3.0,
            None => f64::NAN,
        };
        runs.push((scheme, rtol_reported, sim, err, online_wall_s));
    }
    Ok(runs)
}

/// The stability bound checked: fixed-step runs without error control just below and above
/// the critical step, and the implicit scheme at the step that breaks the explicit one.
struct StabilityChecks {
    below_ok: bool,
    above_diverged: bool,
    implicit_above_bounded: Option<bool>,
}

impl StabilityChecks {
    fn run(
        system: &System,
        state: &State,
        critical: f64,
        t_end: f64,
        schemes: &[IntegrationScheme],
        (point, count): (usize, usize),
        progress: &Progress,
    ) -> Result<Self> {
        // The prediction checked by fixed-step runs without error control.
        let (below_ok, above_diverged) = if critical.is_finite() {
            let fixed = |factor: f64, end_time: f64| {
                simulate(
                    system,
                    state,
                    &IntegratorParameters {
                        end_time,
                        output_interval: end_time / 10.0,
                        fixed_step: Some(factor * critical),
                        ..Default::default()
                    },
                    progress,
                )
            };
            progress.phase(&format!("point {point} of {count}: fixed steps"))?;
            let below = fixed(BELOW_CRITICAL, t_end.min(STABILITY_RUN_S));
            if let Err(CoreError::Cancelled) = below {
                return Err(CoreError::Cancelled.into());
            }
            let above = fixed(ABOVE_CRITICAL, t_end);
            if let Err(CoreError::Cancelled) = above {
                return Err(CoreError::Cancelled.into());
            }
            (
                below.is_ok(),
                matches!(
                    above,
                    Err(CoreError::Dynamics(DynamicsError::Diverged { .. }))
                ),
            )
        } else {
            (true, false)
        };
        // What the implicit scheme does with the step that breaks the explicit one.
        let implicit = schemes
            .iter()
            .copied()
            .find(|s| matches!(s, IntegrationScheme::GeneralizedAlpha { .. }));
        let implicit_above_bounded = match implicit {
            Some(scheme) if critical.is_finite() => {
                progress.phase(&format!("point {point} of {count}: implicit, large step"))?;
                let run = simulate(
                    system,
                    state,
                    &IntegratorParameters {
                        scheme,
                        end_time: t_end,
                        output_interval: ABOVE_CRITICAL * critical,
                        fixed_step: Some(ABOVE_CRITICAL * critical),
                        ..Default::default()
                    },
                    progress,
                );
                if let Err(CoreError::Cancelled) = run {
                    return Err(CoreError::Cancelled.into());
                }
                Some(run.is_ok())
            }
            _ => None,
        };
        Ok(Self {
            below_ok,
            above_diverged,
            implicit_above_bounded,
        })
    }
}

/// The recording of a simulation bench: error against online cost (log–log), one line per
/// method and integrator through its kept-mode counts and the Pareto front in dark grey; error
/// against kept modes per method (explicit scheme); the table beside them. The reference
/// (error 0) has no place on a log axis and is left out of the charts.
fn speed_accuracy_charts(scene: &str, points: &[BenchPoint], table: &str) -> RecordingContent {
    let by_method = by_method(points);
    let cost_series = cost_series(points, &by_method);
    let mode_series = mode_series(&by_method);
    let mut visuals = LogLogChart {
        path: "bench/error_vs_cost".into(),
        x_unit: "online s per simulated s".into(),
        y_unit: "node 8 rel. RMS error".into(),
        series: cost_series,
        x_linear: false,
    }
    .visuals();
    visuals.extend(
        LogLogChart {
            path: "bench/error_vs_modes".into(),
            x_unit: "kept modes".into(),
            y_unit: "node 8 rel. RMS error".into(),
            series: mode_series,
            x_linear: false,
        }
        .visuals(),
    );
    let mut report = crate::report::Report::new(&format!("bench-{scene}"));
    report.table = table.to_string();
    RecordingContent {
        report,
        markdown: format!(
            "# bench {scene}\n\nLeft: node 8's relative RMS error against the online cost \
             (wall seconds per simulated second), log–log; one line per method and \
             integrator through 2, 4, 6, 12 kept modes (gen-alpha in the paler shade, \
             Dormand–Prince at rtol {LOOSE_RTOL} in the darker one), the \
             Pareto front in dark grey. Right: error against kept modes (Dormand–Prince).\n\n\
             {table}",
            LOOSE_RTOL = flexmodes_core::report::readable(LOOSE_RTOL, 1)
        ),
        visuals,
        layout: Layout::bench_charts(
            (
                "error against online cost (log–log)",
                "/bench/error_vs_cost",
            ),
            (
                "error against kept modes 2–12 (log–log)",
                "/bench/error_vs_modes",
            ),
            1.5,
        ),
        timeline: None,
        y_up: false,
    }
}

/// The bench's points grouped by method and integrator, in their order.
type ByMethod<'a> = Vec<((Method, String), Vec<&'a BenchPoint>)>;

fn by_method(points: &[BenchPoint]) -> ByMethod<'_> {
    let mut by_method: Vec<((Method, String), Vec<&BenchPoint>)> = Vec::new();
    for p in points {
        let key = (p.method, p.integrator_label());
        match by_method.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(p),
            None => by_method.push((key, vec![p])),
        }
    }
    by_method
}

/// Error against online cost: one line per method and integrator (the scenes' dp5 in the
/// method's colour, gen-alpha paler, loose dp5 darker), one label per method, and the Pareto
/// front.
fn cost_series(points: &[BenchPoint], by_method: &ByMethod<'_>) -> Vec<LogLogSeries> {
    // The scenes' dp5 in the method's colour, gen-alpha paler, loose dp5 darker.
    let shade = |c: crate::record::Color, integrator: &str| match integrator {
        "dp5" => c,
        "gen-alpha" => [c[0] / 2 + 60, c[1] / 2 + 60, c[2] / 2 + 60, 255],
        _ => [c[0] / 2, c[1] / 2, c[2] / 2, 255],
    };
    // One label per method, on its first line the chart can draw: the explicit one, or for
    // the reference (error 0 at the scenes' tolerance, off the log axis) the loose one.
    let drawable = |p: &&BenchPoint| p.rel_rms_error > 0.0 && p.online_s_per_sim_s > 0.0;
    let labelled: Vec<usize> = by_method
        .iter()
        .enumerate()
        .filter(|(k, ((m, _), pts))| {
            pts.iter().any(drawable)
                && !by_method[..*k]
                    .iter()
                    .any(|((m2, _), p2)| m2 == m && p2.iter().any(drawable))
        })
        .map(|(k, _)| k)
        .collect();
    let mut cost_series: Vec<LogLogSeries> = by_method
        .iter()
        .enumerate()
        .map(|(k, ((m, integrator), pts))| LogLogSeries {
            id: format!(
                "{}_{}",
                m.id(),
                integrator.replace(['-', ' '], "_").replace('.', "")
            ),
            label: if labelled.contains(&k) {
                m.id().to_uppercase()
            } else {
                String::new()
            },
            color: shade(method_color(*m), integrator),
            points: pts
                .iter()
                .map(|p| (p.online_s_per_sim_s, p.rel_rms_error))
                .collect(),
            line: true,
        })
        .collect();
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.pareto)
        .map(|p| (p.online_s_per_sim_s, p.rel_rms_error))
        .collect();
    // Most expensive first: the front's line runs from the reference to the cheapest
    // non-dominated point.
    front.sort_by(|a, b| b.0.total_cmp(&a.0));
    cost_series.push(LogLogSeries {
        id: "pareto_front".into(),
        label: "Pareto".into(),
        color: crate::record::PARETO,
        points: front,
        line: true,
    });
    cost_series
}

/// Error against kept modes, per method (Dormand–Prince).
fn mode_series(by_method: &ByMethod<'_>) -> Vec<LogLogSeries> {
    by_method
        .iter()
        .filter(|((m, integrator), _)| m.keeps_normal_modes() && *integrator == "dp5")
        .map(|((m, _), pts)| LogLogSeries {
            id: m.id().into(),
            label: m.id().to_uppercase(),
            color: method_color(*m),
            points: pts
                .iter()
                .map(|p| (p.modes as f64, p.rel_rms_error))
                .collect(),
            line: true,
        })
        .collect()
}

#[cfg(test)]
mod chart_tests {
    use super::*;

    /// The bench's charts of every method under the three integrator settings at four kept
    /// mode counts keep their text off the data and apart (`record::chart_text_clashes`).
    #[test]
    fn the_speed_accuracy_charts_keep_their_text_off_the_data() {
        let methods = [
            Method::NoReduction,
            Method::Guyan,
            Method::ModalTruncation,
            Method::CraigBampton,
            Method::ModeCondensation,
        ];
        let mut points = Vec::new();
        for (i, &method) in methods.iter().enumerate() {
            for (integrator, rtol) in [
                (
                    IntegrationScheme::DormandPrince,
                    Some(IntegratorParameters::default().rtol),
                ),
                (IntegrationScheme::DormandPrince, Some(LOOSE_RTOL)),
                (
                    IntegrationScheme::GeneralizedAlpha {
                        spectral_radius: DEFAULT_SPECTRAL_RADIUS,
                    },
                    None,
                ),
            ] {
                for modes in [2, 4, 6, 12] {
                    points.push(BenchPoint {
                        method,
                        modes,
                        dofs: 6 + modes,
                        offline_s: 1e-3,
                        online_s_per_sim_s: 0.01 * (1 + i + modes) as f64,
                        rel_rms_error: if i == 0 { 0.0 } else { 0.5 / modes as f64 },
                        steps: 100,
                        evaluations: 600,
                        us_per_evaluation: 5.0,
                        integrator,
                        rtol,
                        pareto: modes == 12,
                    });
                }
            }
        }
        let content = speed_accuracy_charts("slab-sim1", &points, "");
        assert_eq!(crate::record::chart_count(&content.visuals), 2);
        let clashes = crate::record::chart_text_clashes(&content.visuals);
        assert!(clashes.is_empty(), "{clashes:?}");
    }
}
