//! `flexmodes bench slab-modes --sizes 7k,28k --eigensolver amls,lanczos --pairs 50`: the
//! lowest free-free pairs of each refined slab by each eigensolver in one process, one after
//! the other: wall time, peak resident memory, AMLS's reductions and refinement, and how far
//! apart the solvers' eigenvalues are.
//!
//! Timings are wall-clock seconds measured in one run on this machine; they are reported,
//! never asserted.

use std::time::Instant;

use serde_json::json;

use super::size_bench::SizeBench;
use crate::{
    Result,
    fem::{SlabParameters, slab},
    linalg::{GeneralizedEigen, check_reduction_memory, peak_resident_bytes, reset_peak_resident},
    models::amls_json,
    record::{AMLS, Color, Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::{Eigensolver, Method, free_pairs_by},
    report::{Report, markdown_table, readable, sig},
};

/// One solver's run on one mesh.
struct Run {
    solver: Eigensolver,
    seconds: f64,
    peak: Option<u64>,
    pairs: GeneralizedEigen,
    amls: Option<flexmodes_core::linalg::AmlsStatistics>,
}

/// Times every solver of `solvers` on every mesh of `sizes` for the lowest `elastic` elastic
/// free-free pairs (and the six rigid ones).
pub fn bench_eigensolvers(
    sizes: &[[usize; 3]],
    solvers: &[Eigensolver],
    elastic: usize,
    progress: &dyn Fn(&str),
) -> Result<SizeBench> {
    let wanted = 6 + elastic;
    let mut rows = Vec::new();
    let mut points = Vec::new();
    let mut times: Vec<(Eigensolver, Vec<(f64, f64)>)> =
        solvers.iter().map(|&s| (s, Vec::new())).collect();
    let mut peaks: Vec<(Eigensolver, Vec<(f64, f64)>)> =
        solvers.iter().map(|&s| (s, Vec::new())).collect();
    for &bricks in sizes {
        let params = SlabParameters::refined(bricks)?;
        let dofs = params.dof_count();
        check_reduction_memory(dofs)?;
        progress(&format!("{dofs} DOF ({bricks:?}): assembly"));
        let model = slab(&params);
        let mut runs: Vec<Run> = Vec::new();
        for &solver in solvers {
            progress(&format!(
                "{dofs} DOF: {} pairs by {}",
                wanted,
                solver.name()
            ));
            reset_peak_resident();
            let started = Instant::now();
            let (pairs, amls) = free_pairs_by(&model, wanted, solver)?;
            let seconds = started.elapsed().as_secs_f64();
            runs.push(Run {
                solver,
                seconds,
                peak: peak_resident_bytes(),
                pairs,
                amls,
            });
        }
        // Each solver's time and elastic eigenvalues against Lanczos' (the first solver's
        // when Lanczos is not asked for).
        let reference = runs
            .iter()
            .position(|r| r.solver == Eigensolver::Lanczos)
            .unwrap_or(0);
        let (first, first_s) = (&runs[reference].pairs, runs[reference].seconds);
        for run in &runs {
            let apart = run.pairs.elastic_values_apart(first);
            let worst = run
                .pairs
                .elastic_residuals()
                .into_iter()
                .fold(0.0f64, f64::max);
            let missed = run.pairs.sturm.map_or(0, |s| s.missed());
            let ratio = run.seconds / first_s;
            let gb = run.peak.map(|b| b as f64 / 1e9);
            let amls = run.amls.as_ref();
            rows.push(vec![
                format!("{}×{}×{}", bricks[0], bricks[1], bricks[2]),
                dofs.to_string(),
                run.solver.id().into(),
                readable(run.seconds, 3),
                readable(ratio, 3),
                gb.map_or("–".into(), |g| readable(g, 3)),
                amls.map_or("–".into(), |s| {
                    format!(
                        "{} at {} Hz, {} modes, {} steps",
                        s.reductions,
                        readable(s.cutoff_hz, 3),
                        s.projected,
                        s.iterations
                    )
                }),
                readable(worst, 2),
                missed.to_string(),
                readable(apart, 2),
            ]);
            points.push(json!({
                "bricks": bricks,
                "dofs": dofs,
                "eigensolver": run.solver.id(),
                "seconds": sig(run.seconds),
                "ratio_to_reference": sig(ratio),
                "peak_gb": gb.map(sig),
                "max_residual": sig(worst),
                "sturm_missed": missed,
                "eigenvalues_apart": sig(apart),
                "highest_hz": run.pairs.hz().last().copied().map(sig),
                "amls": amls.map(|s| {
                    let mut v = amls_json(s);
                    v["seconds"] = json!({
                        "reductions": sig(s.seconds[0]),
                        "projected": sig(s.seconds[1]),
                        "refinement": sig(s.seconds[2]),
                        "sturm": sig(s.seconds[3]),
                    });
                    v
                }),
            }));
            if let Some(entry) = times.iter_mut().find(|(s, _)| *s == run.solver) {
                entry.1.push((dofs as f64, run.seconds));
            }
            if let (Some(g), Some(entry)) = (gb, peaks.iter_mut().find(|(s, _)| *s == run.solver)) {
                entry.1.push((dofs as f64, g));
            }
        }
    }
    let threads = crate::linalg::threads();
    let value = json!({
        "scene": "slab-modes",
        "eigensolvers": solvers.iter().map(|s| s.id()).collect::<Vec<_>>(),
        "elastic_pairs": elastic,
        "threads": threads,
        "machine_threads": crate::linalg::machine_threads(),
        "points": points,
    });
    let table = format!(
        "The free refined slab's lowest {wanted} pairs (6 rigid) by each eigensolver, one \
         after the other in one process on {threads} thread(s): wall seconds, the ratio to \
         Lanczos' time on the same mesh (the first solver's without it), the process's peak \
         resident memory during the solve, AMLS's reductions (how many, the last cut-off, the modes kept, refinement \
         steps), the worst elastic residual ‖Kφ − λMφ‖/‖Kφ‖, the modes the Sturm count found \
         missed, and the largest relative difference of the elastic eigenvalues to Lanczos' \
         (the first solver's without it).\n\n{}",
        markdown_table(
            &[
                "mesh",
                "DOF",
                "solver",
                "s",
                "÷ Lanczos",
                "peak GB",
                "AMLS reductions",
                "worst residual",
                "missed",
                "apart",
            ],
            &rows
        )
    );
    let recording = chart(&times, &peaks, &table);
    Ok(SizeBench {
        value,
        table,
        recording,
    })
}

/// The solvers' colours: Lanczos as the full model's (it solves the body itself), AMLS its own.
fn color(solver: Eigensolver) -> Color {
    match solver {
        Eigensolver::Lanczos => method_color(Method::NoReduction),
        Eigensolver::Amls => AMLS,
    }
}

/// Time and peak memory against DOF, log–log, one line per solver.
fn chart(
    times: &[(Eigensolver, Vec<(f64, f64)>)],
    peaks: &[(Eigensolver, Vec<(f64, f64)>)],
    table: &str,
) -> RecordingContent {
    let series = |data: &[(Eigensolver, Vec<(f64, f64)>)]| -> Vec<LogLogSeries> {
        data.iter()
            .map(|(solver, pts)| LogLogSeries {
                id: solver.id().into(),
                label: solver.id().into(),
                color: color(*solver),
                points: pts.clone(),
                line: true,
            })
            .collect()
    };
    let mut visuals = LogLogChart {
        path: "bench/eigen_time".into(),
        x_unit: "DOF".into(),
        y_unit: "time, s".into(),
        series: series(times),
        x_linear: false,
    }
    .visuals();
    visuals.extend(
        LogLogChart {
            path: "bench/eigen_memory".into(),
            x_unit: "DOF".into(),
            y_unit: "peak memory, GB".into(),
            series: series(peaks),
            x_linear: false,
        }
        .visuals(),
    );
    let mut report = Report::new("bench-slab-modes-eigensolvers");
    report.table = table.to_string();
    RecordingContent {
        report,
        markdown: format!("# bench slab-modes --eigensolver\n\n{table}"),
        visuals,
        layout: Layout::bench_charts(
            ("time against DOF", "/bench/eigen_time"),
            ("peak memory against DOF", "/bench/eigen_memory"),
            1.2,
        ),
        timeline: None,
        y_up: false,
    }
}
