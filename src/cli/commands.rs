//! What each command does: parse, run, map errors to the exit code.

use std::{path::PathBuf, process::ExitCode, time::Instant};

use clap::Parser;

use super::arguments::{Cli, Command, ExportArgs, OptionArgs};
use crate::{
    Error, Progress, Result, TerminalProgress,
    body_file::ImportedBody,
    record::Recorder,
    scenes::{self, SceneId},
};

/// Scenes `record` runs side by side at most (the machines here have two cores).
const RECORD_WORKERS: usize = 2;

/// Parses the arguments (exit 2 on a usage error), runs, and maps errors to exit code 1 with
/// the cause chain on stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", e.cause_chain());
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    let threads: Vec<usize> = cli.threads.iter().map(|&t| usize::from(t)).collect();
    let several = threads.len() > 1;
    // The pool holds the most threads asked for; a bench lowers the count per run.
    crate::linalg::set_threads(threads.iter().copied().max());
    let compares_threads = matches!(
        &cli.command,
        Command::Bench(b) if b.sizes.is_some() && b.scenes.iter().all(|s| *s == SceneId::SlabModes.as_str())
    );
    if several && !compares_threads {
        return Err(Error::InvalidOption {
            option: "--threads",
            scene: None,
            reason: format!(
                "{} thread counts given: only `bench slab-modes --sizes` times several",
                threads.len()
            ),
        });
    }
    match cli.command {
        Command::List { options } => list(options),
        #[cfg(feature = "gui")]
        Command::Gui {
            scene,
            body,
            simulate,
            interval,
            window,
        } => {
            let simulate = simulate.map(|set| crate::gui::SimulationControls {
                end: interval,
                ..crate::gui::SimulationControls::for_drive(&set)
            });
            crate::gui::run_with_body(scene, body.as_deref(), simulate, None, window.into())
        }
        #[cfg(feature = "gui")]
        Command::View { file, window } => crate::gui::run(None, Some(&file), window.into()),
        Command::Bench(args) => super::bench::bench(args, &threads),
        Command::Simulate(arguments) => super::simulate::run(arguments),
        Command::Campbell(arguments) => super::campbell::run(arguments),
        Command::Diff(arguments) => super::diff::run(arguments),
        Command::Serve(arguments) => super::serve::run(arguments),
        Command::Convert {
            body,
            out,
            compress,
            format,
        } => convert(&body, &out, compress, format),
        Command::Import {
            body,
            json,
            eigensolver,
        } => {
            let body = ImportedBody::load(&body)?;
            let (value, text) = crate::models::import_summary_by(&body, eigensolver)?;
            if json {
                println!("{value}");
            } else {
                println!("{text}");
            }
            Ok(())
        }
        Command::Export(args) => export(args),
        Command::Report {
            scene,
            json,
            options,
        } => report(scene, json, options),
        Command::Record {
            scenes: ids,
            all,
            out,
            save,
            timings,
            options,
        } => record(ids, all, (&out, save.as_deref()), timings, options),
    }
}

/// Records `scenes` side by side on the work pool (at most [`RECORD_WORKERS`] at once, the
/// costliest first: [`scenes::SceneId::recording_cost`]), each to `save` or `out/<id>.rrd`,
/// and prints each result table in the order given as soon as it and those before it are
/// done. The first error stops new scenes from starting and is returned once the running ones
/// finish.
fn record_scenes(
    scenes: Vec<scenes::Scene>,
    opts: &scenes::SceneOptions,
    out: &std::path::Path,
    save: Option<&std::path::Path>,
    timings: bool,
) -> Result<()> {
    let count = scenes.len();
    let threads = crate::linalg::threads();
    let workers = threads.clamp(1, RECORD_WORKERS);
    // The threads no other scene uses run a scene's independent integrations (one scene
    // alone on two cores integrates two methods at once; `--all` keeps one per scene).
    let integrations = (threads / workers.min(count).max(1)).max(1);
    let group = TerminalProgress::group();
    let recorder = Recorder::default();
    let started = Instant::now();
    let mut rows = Vec::with_capacity(count);
    // The costliest scenes first (a stable sort: ties in the catalogue's order); the tables
    // are still printed in the catalogue's order.
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(scenes[k].id.recording_cost()));
    crate::work_pool::run_in_order_by(
        &scenes,
        &order,
        workers,
        |k, s| {
            let mut opts = opts.clone();
            opts.progress = Progress::new();
            opts.concurrent_integrations = integrations;
            let _bar = TerminalProgress::start_in(
                Some(&group),
                &opts.progress,
                &format!("recording {} ({} of {count})", s.id, k + 1),
            );
            let computing = Instant::now();
            let output = s.execute(&opts)?;
            let timing = SceneTiming {
                computing_s: computing.elapsed().as_secs_f64(),
                phases: opts.progress.phase_times(),
                writing_s: 0.0,
            };
            let path = save
                .map(std::path::Path::to_path_buf)
                .unwrap_or_else(|| out.join(format!("{}.rrd", s.id)));
            let writing = Instant::now();
            recorder.save(&output, &path)?;
            let timing = SceneTiming {
                writing_s: writing.elapsed().as_secs_f64(),
                ..timing
            };
            Ok::<_, crate::Error>((path, output.report.table, timing))
        },
        |k, (path, table, timing): (PathBuf, String, SceneTiming)| {
            println!("# {} -> {}\n\n{}", scenes[k].id, path.display(), table);
            rows.push((scenes[k].id, timing));
        },
    )?;
    if timings {
        eprint!(
            "{}",
            timing_table(
                &rows,
                workers.min(count),
                integrations,
                started.elapsed().as_secs_f64()
            )
        );
    }
    Ok(())
}

/// One scene's wall time in `record --timings`.
struct SceneTiming {
    /// Running the scene (its models and visuals), s.
    computing_s: f64,
    /// The phases the scene named while computing, s each.
    phases: Vec<(String, f64)>,
    /// Encoding and writing its recording, s.
    writing_s: f64,
}

/// The `record --timings` table: every scene's wall time, computing and writing, the phases
/// it named with their shares; the worker threads and the whole run's wall time. With
/// several integrations per scene at once, the phases are those of the first thread (the
/// others report to muted handles), so their shares need not add up.
fn timing_table(
    rows: &[(SceneId, SceneTiming)],
    workers: usize,
    integrations: usize,
    wall_s: f64,
) -> String {
    let concurrent = if integrations > 1 {
        format!(", {integrations} integrations per scene at once (phases: the first thread's)")
    } else {
        String::new()
    };
    let mut out = format!(
        "\nrecord timings: {} scene(s) on {workers} worker thread(s){concurrent}, \
         {wall_s:.2} s wall\n\n\
         | scene | wall s | computing s | writing s | phases (s, share of computing) |\n\
         |---|---|---|---|---|\n",
        rows.len()
    );
    let mut sorted: Vec<&(SceneId, SceneTiming)> = rows.iter().collect();
    sorted.sort_by(|a, b| {
        let total = |t: &SceneTiming| t.computing_s + t.writing_s;
        total(&b.1).total_cmp(&total(&a.1))
    });
    for (id, t) in sorted {
        let named: f64 = t.phases.iter().map(|(_, s)| s).sum();
        let mut phases: Vec<String> = t
            .phases
            .iter()
            .map(|(name, s)| format!("{name} {s:.2} ({:.0} %)", 100.0 * s / t.computing_s))
            .collect();
        if !t.phases.is_empty() && t.computing_s - named > 0.005 {
            let rest = t.computing_s - named;
            phases.insert(
                0,
                format!(
                    "before the first {rest:.2} ({:.0} %)",
                    100.0 * rest / t.computing_s
                ),
            );
        }
        out.push_str(&format!(
            "| {id} | {:.2} | {:.2} | {:.2} | {} |\n",
            t.computing_s + t.writing_s,
            t.computing_s,
            t.writing_s,
            if phases.is_empty() {
                "-".to_string()
            } else {
                phases.join(", ")
            }
        ));
    }
    out
}

/// `flexmodes export`: reduce a body and write the reduced model.
fn export(args: ExportArgs) -> Result<()> {
    let ExportArgs {
        body,
        method,
        boundary,
        modes,
        out,
        psi_format,
        interface_modes,
        exudyn,
        timings,
        stiffening,
        residual_vectors,
        eigensolver,
    } = args;
    let started = Instant::now();
    let body = ImportedBody::load(&body)?;
    let interfaces =
        crate::models::BodyInterfaces::named_or_default(&body, boundary.as_deref(), None)?;
    let boundary = interfaces.boundary;
    let loaded_s = started.elapsed().as_secs_f64();
    let parameters = crate::export::ExportParameters {
        psi_format,
        rigid_interfaces: interfaces.rigid,
        averaging_interfaces: interfaces.averaging,
        interface_modes,
        exudyn,
        stiffening: stiffening == super::arguments::OnOff::On,
        residual_vectors: residual_vectors == super::arguments::OnOff::On,
        eigensolver,
    };
    let summary = crate::export::export(&body, method, &boundary, modes, &out, &parameters)?;
    if timings {
        print_timings(started.elapsed().as_secs_f64(), loaded_s, &summary.timings);
    }
    for i in &parameters.rigid_interfaces {
        println!(
            "rbe2 `{}`: {} nodes tied to a master at ({}) {}",
            i.name,
            i.nodes.len(),
            i.master
                .map(crate::report::sig)
                .map(|x| x.to_string())
                .join(", "),
            body.units.length
        );
    }
    println!(
        "{}: {} of `{}` on {} interface node(s), Ψ {} × {}; wrote {} in {}\n{} \
         zero-energy mode(s); reduced elastic Hz: {} ({})",
        method.id(),
        method.name(),
        body.model.name,
        boundary.len(),
        summary.shape[0],
        summary.shape[1],
        summary.files.join(", "),
        summary.dir.display(),
        summary.zero_energy,
        crate::report::fmt_hz(&summary.hz[..summary.hz.len().min(8)]),
        crate::report::residual_note(
            &summary.hz[..summary.hz.len().min(8)],
            &summary.residuals[..summary.residuals.len().min(8)]
        ),
    );
    // A free body's reduced model should keep its rigid motions (modal truncation alone
    // moves its interface DOF without them).
    let rigid = body.model.dofs.rigid_body_count();
    if body.model.rigid_motions == crate::fem::RigidMotions::FromGeometry
        && method != crate::reduction::Method::ModalTruncation
        && summary.zero_energy < rigid
    {
        println!(
            "WARNING: the reduced model has {} zero-energy mode(s) where the free body has {rigid} \
             rigid motions: its basis does not hold them all, so a floating frame's rigid \
             motion would strain it (check the interface: too few nodes, or coordinates that \
             disagree with the stiffness, which `flexmodes import` names)",
            summary.zero_energy
        );
    }
    if let Some(e) = &summary.exudyn {
        let hz = e.hz();
        println!(
            "Exudyn: {}/exudyn/, the floating frame on `{}`, {} {} (elastic Hz: {} ({}))",
            summary.dir.display(),
            e.frame,
            e.modes.ncols(),
            e.mode_type,
            crate::report::fmt_hz(&hz[..hz.len().min(8)]),
            crate::report::residual_note(
                &hz[..hz.len().min(8)],
                &e.residuals[..e.residuals.len().min(8)]
            ),
        );
    }
    Ok(())
}

/// `flexmodes list`: each scene with its summary, or with the options it takes and their
/// defaults (`--options`).
fn list(options: bool) -> Result<()> {
    let all = scenes::all();
    let width = all.iter().map(|s| s.id.as_str().len()).max().unwrap_or(0);
    for s in all {
        let said = if options {
            s.info.controls.described()
        } else {
            s.info.summary.to_string()
        };
        println!("{:<width$}  {said}", s.id.as_str());
    }
    Ok(())
}

/// `flexmodes convert`: the body written in `format`, then read back and summarised.
fn convert(
    body: &str,
    out: &std::path::Path,
    compress: bool,
    format: crate::body_file::MatrixFormat,
) -> Result<()> {
    let loaded = ImportedBody::load(body)?;
    let files = crate::body_file::write_imported_body(&loaded, compress, format)?;
    crate::body_file::write_files(out, &files)?;
    // What was read, as the written body reads back.
    let written = ImportedBody::load(&out.join("body.toml").display().to_string())?;
    let (_, text) = crate::models::import_summary(&written)?;
    println!(
        "wrote {} ({})\n\n{text}",
        out.display(),
        files.keys().cloned().collect::<Vec<_>>().join(", ")
    );
    Ok(())
}

/// `flexmodes report`: one scene's table, or its report as JSON.
fn report(scene: SceneId, json: bool, options: OptionArgs) -> Result<()> {
    let s = scenes::get(scene);
    let mut opts = options.into_scene_options()?;
    opts.progress = Progress::new();
    let bar = TerminalProgress::start(&opts.progress, s.id.as_str());
    let out = s.execute(&opts)?;
    drop(bar);
    if json {
        println!("{}", out.report.to_json());
    } else {
        println!("# {}\n\n{}", out.report.scene, out.report.table);
    }
    Ok(())
}

/// `flexmodes record`: the scenes named (or all), each to `save` or `out/<id>.rrd`.
fn record(
    ids: Vec<SceneId>,
    all: bool,
    (out, save): (&std::path::Path, Option<&std::path::Path>),
    timings: bool,
    options: OptionArgs,
) -> Result<()> {
    let ids: Vec<SceneId> = if all { scenes::all_ids() } else { ids };
    if ids.is_empty() {
        return Err(Error::InvalidOption {
            option: "SCENES",
            scene: None,
            reason: "name at least one scene or pass --all".into(),
        });
    }
    if save.is_some() && ids.len() != 1 {
        return Err(Error::InvalidOption {
            option: "--save",
            scene: None,
            reason: "--save takes exactly one scene; use --out DIR for several".into(),
        });
    }
    let found = ids.into_iter().map(scenes::get).collect();
    let opts = options.into_scene_options()?;
    if let Some(body) = &opts.body {
        body.require_coordinates()?;
    }
    record_scenes(found, &opts, out, save, timings)
}

/// An export's wall time by phase (of `total` s, reading the body `loaded_s` of them) and the
/// process's peak memory, on standard error.
fn print_timings(total: f64, loaded_s: f64, timings: &[(&'static str, f64)]) {
    eprintln!(
        "wall time by phase, {} thread(s) (--threads):",
        crate::linalg::threads()
    );
    let share = |s: f64| 100.0 * s / total.max(f64::MIN_POSITIVE);
    eprintln!(
        "  read the body: {loaded_s:.3} s ({:.0} %)",
        share(loaded_s)
    );
    for (phase, s) in timings {
        eprintln!("  {phase}: {s:.3} s ({:.0} %)", share(*s));
    }
    eprintln!("  total: {total:.3} s");
    if let Some(peak) = crate::linalg::peak_resident_bytes() {
        eprintln!(
            "peak resident memory (the process's high-water mark, VmHWM): {:.2} GB",
            peak as f64 / 1e9
        );
    }
}
