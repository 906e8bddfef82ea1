//! `flexmodes bench slab-modes --sizes 1k,7k,28k,74k,150k`: the offline cost of each reduction
//! against the size of the refined slab, with the fitted growth exponent per method.
//!
//! Timings are wall-clock seconds measured in one run on this machine; they are reported,
//! never asserted.

use crate::reduction::{ReductionRequest, reduce, reduce_interior};
use std::time::Instant;

use serde_json::{Map, Value, json};

use crate::{
    Error, Result,
    fem::{FeModel, SlabParameters, slab},
    linalg::{check_reduction_memory, peak_resident_bytes},
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::Method,
    reduction::{
        COMPLETE_EIGEN_LIMIT, InteriorProblem, ModeCondensationRoute, ModeSelection, SolverPath,
    },
    report::{Report, markdown_table, sig, sig_vec},
};

/// Kept fixed-interface modes of the benchmark work (and the frequencies reported).
pub const BENCH_MODES: usize = 20;

/// The named sizes: DOF in thousands → bricks (the meshes of the SciPy/Exudyn peer script).
const NAMED_SIZES: [(&str, [usize; 3]); 5] = [
    ("1k", [12, 6, 3]),
    ("7k", [24, 12, 6]),
    ("28k", [40, 20, 10]),
    ("74k", [56, 28, 14]),
    ("150k", [72, 36, 18]),
];

/// Parses `1k,7k,28k` or `24x12x6,40x20x10` into meshes, ascending in size.
pub fn parse_sizes(text: &str) -> Result<Vec<[usize; 3]>> {
    let mut out = Vec::new();
    for token in text.split(',').map(str::trim) {
        let bricks = if let Some((_, b)) = NAMED_SIZES.iter().find(|(n, _)| *n == token) {
            *b
        } else {
            let parts: Vec<Option<usize>> = token.split('x').map(|p| p.parse().ok()).collect();
            match parts.as_slice() {
                [Some(a), Some(b), Some(c)] if *a > 0 && *b > 0 && *c > 0 => [*a, *b, *c],
                _ => {
                    return Err(Error::InvalidSize {
                        token: token.into(),
                        named: NAMED_SIZES.map(|(n, _)| n).to_vec(),
                    });
                }
            }
        };
        out.push(bricks);
    }
    out.sort_by_key(|b| b.iter().map(|&n| n + 1).product::<usize>());
    Ok(out)
}

/// Least-squares slope of log y against log x (None with fewer than two positive points).
pub fn growth_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let (mx, my) = (
        logs.iter().map(|p| p.0).sum::<f64>() / n,
        logs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The benchmark's results: JSON, the markdown table and the recording's content.
pub struct SizeBench {
    /// The `--json` object.
    pub value: Value,
    /// The markdown table.
    pub table: String,
    /// Log–log offline time against DOF per method, for `--save`.
    pub recording: RecordingContent,
}

/// One run's wall times of every method on one mesh.
struct Measured {
    phases: crate::reduction::ReductionStatistics,
    hz: Vec<f64>,
    cb_s: f64,
    mt_s: f64,
    mc_kept_s: f64,
    mc_complete_s: Option<f64>,
    gr_s: f64,
}

impl Measured {
    /// Each time the median of `runs` (phases too), the frequencies of the first.
    fn median(mut runs: Vec<Measured>) -> Measured {
        let median = |values: Vec<f64>| -> f64 {
            let mut v = values;
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let pick = |f: &dyn Fn(&Measured) -> f64| median(runs.iter().map(f).collect());
        let mut phases = runs[0].phases;
        phases.factorization_s = pick(&|m| m.phases.factorization_s);
        phases.constraint_modes_s = pick(&|m| m.phases.constraint_modes_s);
        phases.eigen_s = pick(&|m| m.phases.eigen_s);
        let cb_s = pick(&|m| m.cb_s);
        let mt_s = pick(&|m| m.mt_s);
        let mc_kept_s = pick(&|m| m.mc_kept_s);
        let gr_s = pick(&|m| m.gr_s);
        let mc_complete_s = runs[0]
            .mc_complete_s
            .map(|_| pick(&|m| m.mc_complete_s.unwrap_or(f64::NAN)));
        let first = runs.swap_remove(0);
        Measured {
            phases,
            hz: first.hz,
            cb_s,
            mt_s,
            mc_kept_s,
            mc_complete_s,
            gr_s,
        }
    }
}

/// Times CB (its phases), MT and MC on CB's factor and modes, MC's complete route where it
/// applies, and Guyan on `model` held at `corners`.
fn measure(model: &FeModel, corners: &[usize], progress: &dyn Fn(&str)) -> Result<Measured> {
    let dofs = model.dof_count();
    progress(&format!("{dofs} DOF: Craig-Bampton"));
    let started = Instant::now();
    let mut problem = InteriorProblem::new(model, corners, SolverPath::Auto)?;
    let cb = reduce_interior(
        &mut problem,
        &ReductionRequest::of(Method::CraigBampton).modes(ModeSelection::Count(BENCH_MODES)),
    )?;
    let cb_s = started.elapsed().as_secs_f64();
    let phases = cb.statistics;
    let hz = cb.normal_hz();
    let started = Instant::now();
    reduce_interior(
        &mut problem,
        &ReductionRequest::of(Method::ModalTruncation).modes(ModeSelection::Count(BENCH_MODES)),
    )?;
    // MT reuses CB's factor and modes: its own cost is the basis assembly on top.
    let mt_s = phases.factorization_s + phases.eigen_s + started.elapsed().as_secs_f64();
    let started = Instant::now();
    reduce_interior(
        &mut problem,
        &ReductionRequest::of(Method::ModeCondensation)
            .modes(ModeSelection::Count(BENCH_MODES))
            .route(ModeCondensationRoute::KeptModes),
    )?;
    let mc_kept_s = cb_s + started.elapsed().as_secs_f64();
    let interior = problem.interior_dofs();
    drop(problem);
    let mc_complete_s = if interior <= COMPLETE_EIGEN_LIMIT {
        progress(&format!("{dofs} DOF: mode condensation, complete route"));
        let started = Instant::now();
        reduce(
            model,
            &ReductionRequest::of(Method::ModeCondensation)
                .boundary(corners)
                .modes(ModeSelection::Count(BENCH_MODES))
                .solver(SolverPath::Auto)
                .route(ModeCondensationRoute::Complete),
        )?;
        Some(started.elapsed().as_secs_f64())
    } else {
        None
    };
    progress(&format!("{dofs} DOF: Guyan"));
    let started = Instant::now();
    reduce(
        model,
        &ReductionRequest::of(Method::Guyan)
            .boundary(corners)
            .solver(SolverPath::Auto),
    )?;
    let gr_s = started.elapsed().as_secs_f64();
    Ok(Measured {
        phases,
        hz,
        cb_s,
        mt_s,
        mc_kept_s,
        mc_complete_s,
        gr_s,
    })
}

/// Runs every size with each thread count of `threads` (none: the count in use), `repeats`
/// times (each time the median); returns the JSON object, a markdown table and the recording.
pub fn bench_sizes(
    sizes: &[[usize; 3]],
    threads: &[usize],
    repeats: usize,
    progress: &dyn Fn(&str),
) -> Result<SizeBench> {
    let mut points = Vec::new();
    let mut rows = Vec::new();
    let mut series: Map<String, Value> = Map::new();
    let mut totals: std::collections::BTreeMap<String, Vec<(f64, f64)>> = Default::default();
    let before = crate::linalg::threads();
    let counts = if threads.is_empty() {
        vec![before]
    } else {
        threads.to_vec()
    };
    let several = counts.len() > 1;
    for &bricks in sizes {
        let params = SlabParameters::refined(bricks)?;
        let dofs = params.dof_count();
        check_reduction_memory(dofs)?;
        progress(&format!("{dofs} DOF ({bricks:?}): assembly"));
        let started = Instant::now();
        let model = slab(&params);
        let assembly_s = started.elapsed().as_secs_f64();
        let corners = params.bottom_corners();
        // One assembly per mesh; each thread count times the same model.
        for &wanted in &counts {
            let threads = crate::linalg::use_threads(wanted);
            progress(&format!("{dofs} DOF, {threads} thread(s)"));
            let runs = (0..repeats.max(1))
                .map(|_| measure(&model, &corners, progress))
                .collect::<Result<Vec<_>>>()?;
            let m = Measured::median(runs);
            let peak = peak_resident_bytes();
            for (id, s) in [
                ("gr", Some(m.gr_s)),
                ("mt", Some(m.mt_s)),
                ("cb", Some(m.cb_s)),
                ("mc", Some(m.mc_kept_s)),
                ("mc_complete", m.mc_complete_s),
            ] {
                if let Some(s) = s {
                    let key = if several {
                        format!("{id}_{threads}t")
                    } else {
                        id.to_string()
                    };
                    totals.entry(key).or_default().push((dofs as f64, s));
                }
            }
            let (row, point) = size_entry(bricks, threads, &model, assembly_s, &m, peak);
            rows.push(row);
            points.push(point);
        }
    }
    crate::linalg::use_threads(before);
    let mut exponents = Map::new();
    for (id, pts) in &totals {
        series.insert(
            id.clone(),
            json!(pts.iter().map(|p| [p.0, sig(p.1)]).collect::<Vec<_>>()),
        );
        exponents.insert(id.clone(), json!(growth_exponent(pts).map(sig)));
    }
    let value = json!({
        "scene": "slab-modes",
        "modes": BENCH_MODES,
        "boundary": "four bottom corners (12 DOF)",
        "threads": counts,
        "machine_threads": crate::linalg::machine_threads(),
        "repeats": repeats.max(1),
        "points": points,
        "offline_s_against_dofs": series,
        "growth_exponent": exponents,
    });
    let table = format!(
        "Refined slab, Craig-Bampton with the four bottom corners (12 DOF) and {BENCH_MODES} kept \
         fixed-interface modes; wall seconds, the median of {} run(s) per size and thread \
         count (`--repeats`). MT and MC reuse CB's factor and \
         modes (their times include CB's shared phases); MC complete is the thesis' route \
         (complete dense interior eigenproblem, up to {COMPLETE_EIGEN_LIMIT} interior DOF). \
         Peak memory is the process's peak so far (sizes run ascending). Threads: what the \
         kernels may use (`--threads`; this machine has {}); a factorisation of more than \
         {} flops and products of more than {} use them all, smaller kernels one. \
         Series keys `cb_2t`: CB with 2 threads.\n\n{}\nGrowth exponents p (offline s grows as DOF^p): \
         {}\n",
        repeats.max(1),
        crate::linalg::machine_threads(),
        flexmodes_core::report::readable(crate::linalg::PARALLEL_FACTOR_FLOPS, 1),
        flexmodes_core::report::readable(crate::linalg::PARALLEL_FLOPS, 1),
        markdown_table(
            &[
                "mesh",
                "DOF",
                "threads",
                "nnz K",
                "nnz L",
                "assembly",
                "factor",
                "constraint",
                "eigen",
                "CB",
                "GR",
                "MT",
                "MC",
                "MC complete",
                "peak MB",
            ],
            &rows
        ),
        exponents
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let recording = log_log_chart(&totals, &exponents, table.clone());
    Ok(SizeBench {
        value,
        table,
        recording,
    })
}

/// One size and thread count's table row and JSON point.
fn size_entry(
    bricks: [usize; 3],
    threads: usize,
    model: &FeModel,
    assembly_s: f64,
    m: &Measured,
    peak: Option<u64>,
) -> (Vec<String>, Value) {
    let dofs = model.dof_count();
    let row = vec![
        format!("{}×{}×{}", bricks[0], bricks[1], bricks[2]),
        dofs.to_string(),
        threads.to_string(),
        model.stiffness_nnz().to_string(),
        m.phases.factor_nnz.to_string(),
        format!("{assembly_s:.3}"),
        format!("{:.3}", m.phases.factorization_s),
        format!("{:.3}", m.phases.constraint_modes_s),
        format!("{:.3}", m.phases.eigen_s),
        format!("{:.3}", m.cb_s),
        format!("{:.3}", m.gr_s),
        format!("{:.3}", m.mt_s),
        format!("{:.3}", m.mc_kept_s),
        m.mc_complete_s.map_or("—".into(), |s| format!("{s:.3}")),
        peak.map_or("?".into(), |b| format!("{:.0}", b as f64 / 1e6)),
    ];
    let point = json!({
        "bricks": bricks,
        "dofs": dofs,
        "threads": threads,
        "nnz": model.stiffness_nnz(),
        "factor_nnz": m.phases.factor_nnz,
        "factor_flops": m.phases.factor_flops,
        "timing_s": {
            "assembly": sig(assembly_s),
            "factorization": sig(m.phases.factorization_s),
            "constraint_modes": sig(m.phases.constraint_modes_s),
            "eigen": sig(m.phases.eigen_s),
            "reduction": sig(m.cb_s),
        },
        "offline_s": {
            "gr": sig(m.gr_s), "mt": sig(m.mt_s), "cb": sig(m.cb_s), "mc": sig(m.mc_kept_s),
            "mc_complete": m.mc_complete_s.map(sig),
        },
        "eigen_block_solves": m.phases.eigen_block_solves,
        "eigen_max_residual": m.phases.eigen_max_residual,
        "peak_memory_bytes": peak,
        "fixed_interface_hz": sig_vec(&m.hz),
    });
    (row, point)
}

/// Log–log chart of offline time against DOF: x = log₁₀ DOF, y = log₁₀ s (drawn upward), one
/// polyline per method labelled with its growth exponent, decade ticks labelled on the axes.
fn log_log_chart(
    totals: &std::collections::BTreeMap<String, Vec<(f64, f64)>>,
    exponents: &Map<String, Value>,
    table: String,
) -> RecordingContent {
    let series = totals
        .iter()
        .map(|(id, pts)| {
            // `cb` or, comparing thread counts, `cb_2t`.
            let (method, threads) = match id.rsplit_once('_').and_then(|(m, t)| {
                let count = t.strip_suffix('t')?.parse::<usize>().ok()?;
                Some((m, count))
            }) {
                Some((m, count)) => (m, Some(count)),
                None => (id.as_str(), None),
            };
            let base = match method {
                "gr" => method_color(Method::Guyan),
                "mt" => method_color(Method::ModalTruncation),
                "cb" => method_color(Method::CraigBampton),
                "mc" => method_color(Method::ModeCondensation),
                _ => [150, 150, 150, 255],
            };
            // More threads, darker.
            let shade = 1.0 / (threads.unwrap_or(1) as f64).sqrt();
            let color = [
                (base[0] as f64 * shade) as u8,
                (base[1] as f64 * shade) as u8,
                (base[2] as f64 * shade) as u8,
                base[3],
            ];
            let exponent = exponents
                .get(id)
                .and_then(Value::as_f64)
                .map_or("—".into(), |p| format!("{p:.2}"));
            let method_name = method.replace('_', " ").to_uppercase();
            let name = match threads {
                Some(t) => format!("{method_name}, {t} thread(s)"),
                None => method_name,
            };
            // Only the largest mesh is labelled (method and exponent); the table has every
            // value.
            LogLogSeries {
                id: id.clone(),
                // The viewer's font has no ∝: said in ASCII.
                label: format!("{name}: s ~ DOF^{exponent}"),
                color,
                points: pts.clone(),
                line: true,
            }
        })
        .collect();
    let visuals = LogLogChart {
        path: "bench/offline_time".into(),
        x_unit: "DOF".into(),
        y_unit: "offline time, s".into(),
        series,
        x_linear: false,
    }
    .visuals();
    let mut report = Report::new("bench-slab-modes");
    report.table = table.clone();
    RecordingContent {
        report,
        markdown: format!("# bench slab-modes --sizes\n\n{table}"),
        visuals,
        layout: Layout::Horizontal(
            vec![
                Layout::Spatial2D {
                    name: "offline time against DOF (log–log)".into(),
                    origin: "/bench/offline_time".into(),
                },
                Layout::Text {
                    name: "table".into(),
                    origin: "/scene".into(),
                },
            ],
            vec![2.0, 1.0],
        ),
        timeline: None,
        y_up: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_by_name_and_by_bricks_and_a_bad_token_names_the_sizes() {
        assert_eq!(
            parse_sizes("7k,4x2x1").unwrap(),
            vec![[4, 2, 1], [24, 12, 6]],
            "ascending in size"
        );
        for bad in ["9k", "4x2", "0x2x1"] {
            match parse_sizes(bad) {
                Err(Error::InvalidSize { token, named }) => {
                    assert_eq!(token, bad);
                    assert_eq!(named, ["1k", "7k", "28k", "74k", "150k"]);
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
    }
}
