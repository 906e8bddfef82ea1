//! The command line (`main.rs` only calls [`main`]).

use std::{io::IsTerminal, path::PathBuf, process::ExitCode};

use clap::{Args, Parser, Subcommand};

use std::sync::Arc;

use crate::{
    Error, Progress, Result, TerminalProgress,
    body_file::{BodyHandle, ImportedBody},
    dynamics::IntegrationScheme,
    record::Recorder,
    reduction::Method,
    scenes::{self, SceneOptions},
};

/// Explorer of model order reduction for restrained deformable bodies.
/// Scenes `record` runs side by side at most (the machines here have two cores).
const RECORD_WORKERS: usize = 2;

/// What `bench --all` measures, in this order.
const BENCH_ALL: [&str; 3] = ["slab-modes", "slab-sim1", "slab-sim2"];

#[derive(Debug, Parser)]
#[command(name = "flexmodes", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List the scenes, one line each.
    List,
    /// Record scenes to Rerun `.rrd` files.
    Record {
        /// Scene ids (see `flexmodes list`).
        scenes: Vec<String>,
        /// Record every scene.
        #[arg(long, conflicts_with = "scenes")]
        all: bool,
        /// Folder to write `<scene>.rrd` into.
        #[arg(long, default_value = "recordings", conflicts_with = "save")]
        out: PathBuf,
        /// Write a single scene to this file.
        #[arg(long)]
        save: Option<PathBuf>,
        #[command(flatten)]
        options: OptionArgs,
    },
    /// Speed against accuracy of every method and kept-mode count: slab-modes (offline cost
    /// against frequency and static error) and the slab simulations (online cost against
    /// node 8's error, stability).
    Bench {
        /// Scenes: slab-modes, slab-sim1, slab-sim2 (default: slab-sim1).
        scenes: Vec<String>,
        /// Every scene bench measures: slab-modes, slab-sim1, slab-sim2.
        #[arg(long, conflicts_with = "scenes")]
        all: bool,
        /// Print one JSON object per scene.
        #[arg(long)]
        json: bool,
        /// Refined meshes to time, `1k,7k,28k,74k,150k` or `NXxNYxNZ,...`: slab-modes'
        /// offline cost, or one simulation's online cost, against DOF.
        #[arg(long)]
        sizes: Option<String>,
        /// Also write the charts to this `.rrd`: with --sizes time against DOF, else error
        /// against cost and against kept modes of one simulation bench.
        #[arg(long)]
        save: Option<PathBuf>,
        /// Integrators to compare, comma separated (default: dp5,gen-alpha).
        #[arg(long, value_delimiter = ',', value_parser = parse_integrator)]
        integrator: Vec<IntegrationScheme>,
        /// Runs of each simulation; the online cost is their median.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=100))]
        repeats: u64,
        /// Simulations on the slab meshed with NX × NY × NZ bricks (App. B is 4,2,1).
        #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_refine, allow_hyphen_values = true)]
        refine: Option<[usize; 3]>,
        /// Time `export --method cb` of this body file as a whole process against SciPy's
        /// CHOLMOD route (the peer script) in the same run.
        #[arg(long, conflicts_with_all = ["scenes", "all", "sizes", "save", "refine"])]
        body: Option<PathBuf>,
        /// With --body: the interface node set.
        #[arg(long, value_delimiter = ',', requires = "body")]
        boundary: Option<Vec<String>>,
        /// With --body: kept fixed-interface modes.
        #[arg(long, default_value_t = 10, requires = "body")]
        modes: usize,
        /// With --body: the SciPy peer script.
        #[arg(
            long,
            default_value = "../shared/bench/peers_body_cb.py",
            requires = "body"
        )]
        peer: PathBuf,
    },
    /// The desktop explorer: the Rerun viewer beside live controls.
    #[cfg(feature = "gui")]
    Gui {
        /// Scene to open (default: the last session's, else beam-modes).
        scene: Option<String>,
        /// Open the `modes` scene on this body file (TOML) or `builtin:NAME`.
        #[arg(long, conflicts_with = "scene")]
        body: Option<String>,
        #[command(flatten)]
        window: WindowArgs,
    },
    /// Open a saved recording in the embedded viewer.
    #[cfg(feature = "gui")]
    View {
        /// The `.rrd` file.
        file: PathBuf,
        #[command(flatten)]
        window: WindowArgs,
    },
    /// Check a body file and print what it holds (DOF, entries, mass, rigid-body modes, lowest
    /// frequencies, node sets).
    Import {
        /// The body file (TOML), or `builtin:NAME` (app-b-slab, l-bracket).
        body: String,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Reduce a body and write Ψ (psi.npy), K_r, M_r (Matrix Market) and model.json to a
    /// folder.
    Export {
        /// The body file (TOML), or `builtin:NAME`.
        #[arg(long)]
        body: String,
        /// The reduction: gr, mt, cb, mc.
        #[arg(long, value_parser = parse_method)]
        method: Method,
        /// Interface: node set names or 1-based nodes, comma separated (default: the set
        /// `interface`, else the body's first set).
        #[arg(long, value_delimiter = ',')]
        boundary: Option<Vec<String>>,
        /// Kept fixed-interface normal modes (mt, cb, mc).
        #[arg(long, default_value_t = 10)]
        modes: usize,
        /// Destination folder (replaced as a whole once everything is written).
        #[arg(long)]
        out: PathBuf,
        /// The format of Ψ: `npy` (binary, numpy.load) or `mtx` (Matrix Market array text).
        #[arg(long, default_value = "npy", value_parser = parse_psi_format)]
        psi_format: crate::export::PsiFormat,
        /// Print the wall time of each phase on stderr.
        #[arg(long)]
        timings: bool,
    },
    /// Print a scene's numeric results (a table, or JSON on stdout).
    Report {
        /// Scene id.
        scene: String,
        /// Print `{"scene", "parameters", "results"}` as JSON.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        options: OptionArgs,
    },
}

/// Window options of `gui` and `view`.
#[cfg(feature = "gui")]
#[derive(Debug, Args, Clone, Default)]
struct WindowArgs {
    /// Save a screenshot to this PNG once the first recording shows, then quit.
    #[arg(long)]
    screenshot: Option<PathBuf>,
    /// Window size in points, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size)]
    window_size: Option<[f32; 2]>,
    /// With --screenshot: toggle this method once the first recording shows, and capture
    /// the recomputed one; `more-modes` or `fewer-modes` presses that button instead.
    #[arg(long, requires = "screenshot")]
    toggle: Option<String>,
    /// With --toggle: toggle that many times (one recomputation each) and print the median
    /// switch latency.
    #[arg(long, requires = "toggle", default_value_t = 1)]
    repeat: u32,
    /// With --toggle: seconds to look at each recording before the next toggle (as a user
    /// would; the explorer anticipates likely requests meanwhile).
    #[arg(long, requires = "toggle", default_value_t = 0.0)]
    pause: f64,
}

#[cfg(feature = "gui")]
fn parse_size(s: &str) -> std::result::Result<[f32; 2], String> {
    let (w, h) = s.split_once('x').ok_or("expected WIDTHxHEIGHT")?;
    Ok([
        w.parse().map_err(|_| "bad width")?,
        h.parse().map_err(|_| "bad height")?,
    ])
}

#[cfg(feature = "gui")]
impl From<WindowArgs> for crate::gui::ViewerOptions {
    fn from(w: WindowArgs) -> Self {
        Self {
            screenshot: w.screenshot,
            window_size: w.window_size,
            toggle: w.toggle,
            repeat: w.repeat,
            pause: std::time::Duration::from_secs_f64(w.pause.max(0.0)),
        }
    }
}

/// Scene options shared by `record` and `report`.
#[derive(Debug, Args, Clone, Default)]
struct OptionArgs {
    /// Reduction methods, comma separated: nr, gr, mt, cb, mc, eit.
    #[arg(long, value_delimiter = ',', value_parser = parse_method)]
    method: Option<Vec<Method>>,
    /// Kept normal modes.
    #[arg(long)]
    modes: Option<usize>,
    /// Boundary (master, interface) nodes, 1-based, comma separated; with --body also the
    /// names of the body's node sets.
    #[arg(long, value_delimiter = ',')]
    boundary: Option<Vec<String>>,
    /// Factor on the drawn elastic deflections of the simulations (default: automatic, the
    /// largest at ~10 % of the body).
    #[arg(long, value_name = "FACTOR")]
    deformation_scale: Option<f64>,
    /// A body file (TOML) or `builtin:NAME`, for the `modes` scene.
    #[arg(long)]
    body: Option<String>,
    /// Axis type: nodal_fixed, mean, principal.
    #[arg(long)]
    axes: Option<String>,
    /// Simulated interval of the dynamic scenes, s.
    #[arg(long)]
    end_time: Option<f64>,
    /// Time-integration scheme of the simulations: dp5 (explicit Dormand–Prince 5(4), adaptive
    /// steps) or gen-alpha (implicit generalized-α, fixed steps).
    #[arg(long, value_parser = parse_integrator)]
    integrator: Option<IntegrationScheme>,
    /// Fixed step of the simulations, s: dp5 then runs without error control (how a critical
    /// step is checked); gen-alpha's default is 0.001.
    #[arg(long, value_name = "SECONDS")]
    dt: Option<f64>,
    /// Spectral radius ρ∞ of gen-alpha at infinite frequency, in [0, 1] (default 0.8; 1 adds
    /// no numerical damping).
    #[arg(long, value_name = "RHO")]
    rho_inf: Option<f64>,
    /// Bricks of the slab mesh along x, y, z (slab-modes; App. B is 4,2,1).
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_refine, allow_hyphen_values = true)]
    refine: Option<[usize; 3]>,
}

/// `NX,NY,NZ`: three positive brick counts.
fn parse_refine(s: &str) -> std::result::Result<[usize; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected three brick counts NX,NY,NZ, got {} value(s)",
            parts.len()
        ));
    }
    let mut out = [0; 3];
    for (d, p) in parts.iter().enumerate() {
        let axis = ["x", "y", "z"][d];
        out[d] = p
            .parse::<usize>()
            .map_err(|_| format!("brick count along {axis} `{p}` is not a positive integer"))?;
        if out[d] == 0 {
            return Err(format!(
                "brick count along {axis} must be at least 1, got 0"
            ));
        }
    }
    Ok(out)
}

fn parse_integrator(s: &str) -> std::result::Result<IntegrationScheme, String> {
    IntegrationScheme::from_id(s.trim()).ok_or_else(|| {
        format!(
            "unknown integrator `{s}` (known: {})",
            IntegrationScheme::IDS.join(", ")
        )
    })
}

fn parse_psi_format(s: &str) -> std::result::Result<crate::export::PsiFormat, String> {
    match s {
        "npy" => Ok(crate::export::PsiFormat::Npy),
        "mtx" => Ok(crate::export::PsiFormat::MatrixMarket),
        other => Err(format!("unknown Ψ format `{other}` (npy, mtx)")),
    }
}

fn parse_method(s: &str) -> std::result::Result<Method, String> {
    Method::from_id(s.trim()).ok_or_else(|| {
        format!(
            "unknown method `{s}` (known: {})",
            Method::ALL.map(|m| m.id()).join(", ")
        )
    })
}

impl OptionArgs {
    /// The scene options: the body file loaded and checked, set names resolved to nodes.
    fn into_scene_options(self) -> Result<SceneOptions> {
        let body = match &self.body {
            Some(b) => Some(BodyHandle(Arc::new(ImportedBody::load(b)?))),
            None => None,
        };
        let boundary = match (&self.boundary, &body) {
            (None, _) => None,
            (Some(items), Some(body)) => Some(body.boundary(items)?),
            (Some(items), None) => Some(parse_nodes(items)?),
        };
        let integrator = match (self.integrator, self.rho_inf) {
            (Some(IntegrationScheme::GeneralizedAlpha { .. }) | None, Some(rho)) => {
                Some(IntegrationScheme::GeneralizedAlpha {
                    spectral_radius: rho,
                })
            }
            (Some(IntegrationScheme::DormandPrince), Some(_)) => {
                use clap::CommandFactory;
                Cli::command()
                    .error(
                        clap::error::ErrorKind::ArgumentConflict,
                        "--rho-inf is a parameter of --integrator gen-alpha, not of dp5",
                    )
                    .exit()
            }
            (scheme, None) => scheme,
        };
        Ok(SceneOptions {
            methods: self.method,
            modes: self.modes,
            boundary,
            axes: self.axes,
            end_time: self.end_time,
            integrator,
            dt: self.dt,
            refine: self.refine,
            deformation_scale: self.deformation_scale,
            body,
            ..Default::default()
        })
    }
}

/// 1-based node numbers; a name is a node set, which needs a body file: without one, a usage
/// error (exit 2) as any other malformed option.
fn parse_nodes(items: &[String]) -> Result<Vec<usize>> {
    let mut nodes = Vec::with_capacity(items.len());
    for s in items {
        match s.trim().parse::<usize>() {
            Ok(n) => nodes.push(n),
            Err(_) => {
                use clap::CommandFactory;
                Cli::command()
                    .error(
                        clap::error::ErrorKind::ValueValidation,
                        format!(
                            "--boundary `{s}` is not a node number (node set names need --body)"
                        ),
                    )
                    .exit()
            }
        }
    }
    Ok(nodes)
}

/// Parses the arguments (exit 2 on a usage error), runs, and maps errors to exit code 1 with
/// the cause chain on stderr.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let mut msg = format!("error: {e}");
            let mut src = std::error::Error::source(&e);
            while let Some(s) = src {
                msg.push_str(&format!(": {s}"));
                src = s.source();
            }
            eprintln!("{msg}");
            ExitCode::from(1)
        }
    }
}

fn progress(msg: &str) {
    if std::io::stderr().is_terminal() {
        eprintln!("{msg}");
    }
}

fn run(cli: Cli) -> Result<()> {
    crate::linalg::use_sequential_kernels();
    match cli.command {
        Command::List => {
            for s in scenes::all() {
                println!("{:<16} {}", s.info.id, s.info.summary);
            }
            Ok(())
        }
        #[cfg(feature = "gui")]
        Command::Gui {
            scene,
            body,
            window,
        } => {
            if let Some(s) = &scene {
                scenes::find(s)?;
            }
            crate::gui::run_with_body(scene.as_deref(), body.as_deref(), None, window.into())
        }
        #[cfg(feature = "gui")]
        Command::View { file, window } => crate::gui::run(None, Some(&file), window.into()),
        Command::Bench {
            body: Some(body),
            boundary,
            modes,
            peer,
            repeats,
            json,
            ..
        } => {
            let boundary = match boundary {
                Some(b) => b,
                None => {
                    let loaded = ImportedBody::load(&body.display().to_string())?;
                    let nodes = scenes::body_modes::default_boundary(&loaded)?;
                    // The peer takes a set name: the body's default interface.
                    let name = loaded
                        .node_sets
                        .iter()
                        .find(|(_, v)| **v == nodes)
                        .map(|(k, _)| k.clone())
                        .ok_or_else(|| Error::InvalidOption {
                            scene: "bench".into(),
                            reason: "name the interface node set with --boundary".into(),
                        })?;
                    vec![name]
                }
            };
            let (value, text) =
                crate::bench_export::run(&crate::bench_export::ExportBenchParameters {
                    body,
                    boundary,
                    modes,
                    repeats: repeats as usize,
                    peer,
                })?;
            if json {
                println!("{value}");
            } else {
                println!("{text}");
            }
            Ok(())
        }
        Command::Bench {
            scenes: ids,
            json,
            sizes: Some(sizes),
            save,
            ..
        } => {
            let simulation = match ids.as_slice() {
                [id] if id == "slab-sim1" || id == "slab-sim2" => Some(id.clone()),
                _ if ids.iter().all(|id| id == "slab-modes") => None,
                _ => {
                    return Err(Error::InvalidOption {
                        scene: ids.join(","),
                        reason: "--sizes times slab-modes, or one of slab-sim1 and slab-sim2"
                            .into(),
                    });
                }
            };
            let meshes = crate::bench_sizes::parse_sizes(&sizes)?;
            let bench = match &simulation {
                Some(id) => {
                    let handle = Progress::new();
                    let bar = TerminalProgress::start(&handle, &format!("bench {id} --sizes"));
                    let bench = crate::bench_sim_sizes::bench_sim_sizes(id, &meshes, &handle)?;
                    drop(bar);
                    bench
                }
                None => crate::bench_sizes::bench_sizes(&meshes, &|s| progress(s))?,
            };
            let title = simulation.as_deref().unwrap_or("slab-modes");
            if let Some(path) = &save {
                Recorder::default().save(&bench.recording, path)?;
                progress(&format!("wrote {}", path.display()));
            }
            if json {
                println!("{}", bench.value);
            } else {
                println!("# bench {title} --sizes {sizes}\n\n{}", bench.table);
            }
            Ok(())
        }
        Command::Bench {
            scenes: ids,
            all,
            json,
            sizes: None,
            save,
            integrator,
            refine,
            repeats,
            ..
        } => {
            let ids = if all {
                BENCH_ALL.iter().map(|s| s.to_string()).collect()
            } else {
                ids
            };
            if !integrator.is_empty() && !ids.is_empty() && ids.iter().all(|id| id == "slab-modes")
            {
                return Err(Error::InvalidOption {
                    scene: "slab-modes".into(),
                    reason: "--integrator applies to the simulation benches only".into(),
                });
            }
            if save.is_some() && ids.len() > 1 {
                return Err(Error::InvalidOption {
                    scene: ids.join(","),
                    reason: "--save writes the charts of one simulation bench: name one scene"
                        .into(),
                });
            }
            let ids = if ids.is_empty() {
                vec!["slab-sim1".to_string()]
            } else {
                ids
            };
            for id in &ids {
                scenes::find(id)?;
            }
            let count = ids.len();
            for (k, id) in ids.into_iter().enumerate() {
                let handle = Progress::new();
                let bar =
                    TerminalProgress::start(&handle, &format!("bench {id} ({} of {count})", k + 1));
                let (value, table, recording) = if id == "slab-modes" {
                    crate::bench_modes::bench_modes(refine, &handle)?
                } else {
                    crate::bench::bench(&id, &integrator, refine, repeats as usize, &handle)?
                };
                drop(bar);
                if let Some(path) = &save {
                    Recorder::default().save(&recording, path)?;
                }
                if json {
                    println!("{value}");
                } else {
                    println!("# bench {id}\n\n{table}");
                }
            }
            Ok(())
        }
        Command::Import { body, json } => {
            let body = ImportedBody::load(&body)?;
            let (value, text) = scenes::body_modes::import_summary(&body)?;
            if json {
                println!("{value}");
            } else {
                println!("{text}");
            }
            Ok(())
        }
        Command::Export {
            body,
            method,
            boundary,
            modes,
            out,
            psi_format,
            timings,
        } => {
            let started = std::time::Instant::now();
            let body = ImportedBody::load(&body)?;
            let boundary = match boundary {
                Some(items) => body.boundary(&items)?,
                None => scenes::body_modes::default_boundary(&body)?,
            };
            let loaded_s = started.elapsed().as_secs_f64();
            let parameters = crate::export::ExportParameters { psi_format };
            let summary =
                crate::export::export(&body, method, &boundary, modes, &out, &parameters)?;
            if timings {
                eprintln!("read the body: {loaded_s:.3} s");
                for (phase, s) in &summary.timings {
                    eprintln!("{phase}: {s:.3} s");
                }
                eprintln!("total: {:.3} s", started.elapsed().as_secs_f64());
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
            Ok(())
        }
        Command::Report {
            scene,
            json,
            options,
        } => {
            let s = scenes::find(&scene)?;
            let mut opts = options.into_scene_options()?;
            opts.progress = Progress::new();
            let bar = TerminalProgress::start(&opts.progress, s.info.id);
            let out = s.execute(&opts)?;
            drop(bar);
            if json {
                println!("{}", out.report.to_json());
            } else {
                println!("# {}\n\n{}", out.report.scene, out.report.table);
            }
            Ok(())
        }
        Command::Record {
            scenes: ids,
            all,
            out,
            save,
            options,
        } => {
            let ids: Vec<String> = if all {
                scenes::all()
                    .iter()
                    .map(|s| s.info.id.to_string())
                    .collect()
            } else {
                ids
            };
            if ids.is_empty() {
                return Err(Error::InvalidOption {
                    scene: "-".into(),
                    reason: "name at least one scene or pass --all".into(),
                });
            }
            if save.is_some() && ids.len() != 1 {
                return Err(Error::InvalidOption {
                    scene: ids.join(","),
                    reason: "--save takes exactly one scene; use --out DIR for several".into(),
                });
            }
            // Resolve every id first, so a typo fails before anything is written.
            let found = ids
                .iter()
                .map(|id| scenes::find(id))
                .collect::<Result<Vec<_>>>()?;
            let opts = options.into_scene_options()?;
            if let Some(body) = &opts.body {
                body.require_coordinates()?;
            }
            record_scenes(found, &opts, &out, save.as_deref())
        }
    }
}

/// Records `scenes` side by side on the machine's cores (at most [`RECORD_WORKERS`]), each
/// to `save` or `out/<id>.rrd`, and prints each result table in the order given as soon as
/// it and those before it are done. The first error stops new scenes from starting and is
/// returned once the running ones finish.
fn record_scenes(
    scenes: Vec<scenes::Scene>,
    opts: &scenes::SceneOptions,
    out: &std::path::Path,
    save: Option<&std::path::Path>,
) -> Result<()> {
    use std::sync::{
        atomic::{AtomicBool, AtomicUsize, Ordering},
        mpsc,
    };
    let count = scenes.len();
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, RECORD_WORKERS)
        .min(count);
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let group = TerminalProgress::group();
    let (sender, receiver) = mpsc::channel::<(usize, Result<(PathBuf, String)>)>();
    let recorder = Recorder::default();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let sender = sender.clone();
            let (next, failed, group, recorder, scenes) =
                (&next, &failed, &group, &recorder, &scenes);
            scope.spawn(move || {
                loop {
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    if k >= count || failed.load(Ordering::SeqCst) {
                        break;
                    }
                    let s = &scenes[k];
                    let mut opts = opts.clone();
                    opts.progress = Progress::new();
                    let bar = TerminalProgress::start_in(
                        Some(group),
                        &opts.progress,
                        &format!("recording {} ({} of {count})", s.info.id, k + 1),
                    );
                    let result = s.execute(&opts).and_then(|output| {
                        let path = save
                            .map(std::path::Path::to_path_buf)
                            .unwrap_or_else(|| out.join(format!("{}.rrd", s.info.id)));
                        recorder.save(&output, &path)?;
                        Ok((path, output.report.table))
                    });
                    drop(bar);
                    if result.is_err() {
                        failed.store(true, Ordering::SeqCst);
                    }
                    if sender.send((k, result)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(sender);
        // Print in order: hold what finishes early until those before it are printed.
        let mut pending: Vec<Option<(PathBuf, String)>> = vec![None; count];
        let mut printed = 0;
        let mut first_error: Option<(usize, Error)> = None;
        for (k, result) in receiver {
            match result {
                Ok(done) => pending[k] = Some(done),
                Err(e) => {
                    if first_error.as_ref().is_none_or(|(j, _)| k < *j) {
                        first_error = Some((k, e));
                    }
                }
            }
            while printed < count {
                let Some((path, table)) = pending[printed].take() else {
                    break;
                };
                println!(
                    "# {} -> {}\n\n{}",
                    scenes[printed].info.id,
                    path.display(),
                    table
                );
                printed += 1;
            }
        }
        match first_error {
            Some((_, e)) => Err(e),
            None => Ok(()),
        }
    })
}
