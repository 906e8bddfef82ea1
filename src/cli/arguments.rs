//! The command line's arguments, as clap parses them.

use std::{path::PathBuf, sync::Arc};

use clap::{Args, Parser, Subcommand};

pub(super) use super::body_arguments::{
    CampbellArgs, ExportArgs, Motion, OnOff, SimulateArgs, SpinningBodyArgs, three_numbers,
};

use crate::{
    Result,
    body_file::{BodyHandle, ImportedBody},
    dynamics::{AxisKind, IntegrationScheme},
    reduction::{Eigensolver, Method},
    scenes::{SceneId, SceneOptions},
};

/// Explorer of model order reduction for restrained deformable bodies.
#[derive(Debug, Parser)]
#[command(name = "flexmodes", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub(super) command: Command,
    /// Threads for the numerics and for independent work (scenes, integrations); large
    /// factorisations, wide solves and large products use them all, small kernels one
    /// (default: the machine's cores). `bench slab-modes --sizes` takes several, `1,2`, and
    /// times every size with each
    #[arg(
        long,
        global = true,
        value_name = "N",
        value_delimiter = ',',
        value_parser = clap::value_parser!(u16).range(1..)
    )]
    pub(super) threads: Vec<u16>,
}

#[derive(Debug, Subcommand)]
pub(super) enum Command {
    /// List the scenes, one line each.
    List {
        /// Instead of the summaries, the options each scene takes, with its defaults.
        #[arg(long)]
        options: bool,
    },
    /// Record scenes to Rerun `.rrd` files.
    Record {
        /// Scene ids (see `flexmodes list`).
        scenes: Vec<SceneId>,
        /// Record every scene.
        #[arg(long, conflicts_with = "scenes")]
        all: bool,
        /// Folder to write `<scene>.rrd` into.
        #[arg(long, default_value = "recordings", conflicts_with = "save")]
        out: PathBuf,
        /// Write a single scene to this file.
        #[arg(long)]
        save: Option<PathBuf>,
        /// Print each scene's wall time on stderr: computing (by phase, where the scene names
        /// them) and writing its recording, with the worker threads used.
        #[arg(long)]
        timings: bool,
        #[command(flatten)]
        options: OptionArgs,
    },
    /// Speed against accuracy of every method and kept-mode count: slab-modes (offline cost
    /// against frequency and static error) and the slab simulations (online cost against
    /// node 8's error, stability).
    Bench(BenchArgs),
    /// The desktop explorer: the Rerun viewer beside live controls.
    #[cfg(feature = "gui")]
    Gui {
        /// Scene to open (default: the last session's, else beam-modes).
        scene: Option<SceneId>,
        /// Open the `modes` scene on this body file (TOML) or `builtin:NAME`.
        #[arg(long, conflicts_with = "scene")]
        body: Option<String>,
        /// With --body: open it driven through this node set (tied rigidly to its master),
        /// spun up as `simulate` spins it.
        #[arg(long, requires = "body")]
        simulate: Option<String>,
        /// With --simulate: the simulated interval, s.
        #[arg(long, requires = "simulate", default_value_t = 1.0)]
        interval: f64,
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
        /// The body file (TOML), or `builtin:NAME` (app-b-slab, l-bracket, spun-lever).
        body: String,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
        /// The free-free pairs' solver: `lanczos` (shift-invert Lanczos; the default, faster
        /// at every size measured on two cores) or `amls` (multi-level substructuring over
        /// the body's nested-dissection tree, refined to the same residual check and
        /// Sturm-counted; docs/amls.md).
        #[arg(long, default_value = "lanczos")]
        eigensolver: Eigensolver,
    },
    /// Write a body read from any supported format (Matrix Market, Harwell–Boeing with a DOF
    /// map, dof-major) as a node-major Matrix Market body file in a folder, and print what was
    /// read.
    Convert {
        /// The body file (TOML), or `builtin:NAME`.
        body: String,
        /// Destination folder (each file written atomically).
        #[arg(long)]
        out: PathBuf,
        /// Compress the matrices (`.gz`).
        #[arg(long)]
        compress: bool,
        /// The matrices' format: matrix-market, abaqus (matrix input lines) or nastran-dmig
        /// (DMIG cards KAAX and MAAX in `body.pch`).
        #[arg(long, default_value = "matrix-market")]
        format: crate::body_file::MatrixFormat,
    },
    /// Reduce a body and write Ψ (psi.npy), K_r, M_r (Matrix Market) and model.json to a
    /// folder.
    Export(ExportArgs),
    /// Simulate a body driven through a rigid interface: the full body (NR, sparse) and
    /// reduced models (gr, mt, cb, mc) run the same spin-up; each model's history and reaction
    /// against the full body's, its offline and online time.
    Simulate(SimulateArgs),
    /// A body spun about an axis through its driven interface: its lowest frequencies at each
    /// rate (the Campbell table), full and reduced, with the dynamic stiffening of its
    /// preloaded stiffness (`[preload]`) or without.
    Campbell(CampbellArgs),
    /// Serve the scenes to browsers on the network: the embedded Rerun web viewer (offline,
    /// gzip) and the recordings over Rerun's data server; prints the URL to share; then reads
    /// teacher commands (`show SCENE [--method …] [--modes N] …`, `list`, `quit`) from the
    /// terminal. Needs the `serve` feature.
    Serve(ServeArgs),
    /// Compare two scene reports, or two folders of them, number by number: a report is
    /// `report --json`'s object (`.json`) or the one a recording holds (`.rrd`). Prints every
    /// number that moved beyond the relative tolerance, key by key, with the wall times left
    /// out, and exits 1 when one did.
    Diff(super::diff::DiffArgs),
    /// Print a scene's numeric results (a table, or JSON on stdout).
    Report {
        /// Scene id.
        scene: SceneId,
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
pub(super) struct WindowArgs {
    /// Save a screenshot to this PNG once the first recording shows, then quit.
    #[arg(long)]
    pub(super) screenshot: Option<PathBuf>,
    /// Window size in points, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size)]
    pub(super) window_size: Option<[f32; 2]>,
    /// The viewer's theme: `light` or `dark` (default: the one last chosen, else the
    /// system's).
    #[arg(long, value_parser = ["light", "dark"])]
    pub(super) theme: Option<String>,
    /// With --screenshot: toggle this method once the first recording shows, and capture
    /// the recomputed one; `more-modes` or `fewer-modes` presses that button instead.
    #[arg(long, requires = "screenshot")]
    pub(super) toggle: Option<String>,
    /// With --toggle: toggle that many times (one recomputation each) and print the median
    /// switch latency.
    #[arg(long, requires = "toggle", default_value_t = 1)]
    pub(super) repeat: u32,
    /// With --toggle: seconds to look at each recording before the next toggle (as a user
    /// would; the explorer anticipates likely requests meanwhile).
    #[arg(long, requires = "toggle", default_value_t = 0.0)]
    pub(super) pause: f64,
    /// With --toggle: save screenshots into this folder at fixed intervals after each
    /// toggle (`switch-SS-FF.png`; the first at the toggle itself).
    #[arg(long, requires = "toggle")]
    pub(super) frames: Option<PathBuf>,
    /// With --frames: milliseconds between two frames.
    #[arg(long, requires = "frames", default_value_t = 150)]
    pub(super) frame_every_ms: u64,
    /// With --frames: frames per toggle.
    #[arg(long, requires = "frames", default_value_t = 20)]
    pub(super) frame_count: u32,
    /// Show each new result as the viewer takes it in, instead of keeping the previous one
    /// on screen until the new one is complete (to see what the atomic switch prevents).
    #[arg(long, hide = true)]
    pub(super) progressive_switch: bool,
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
            light_theme: w.theme.map(|t| t == "light"),
            toggle: w.toggle,
            repeat: w.repeat,
            pause: std::time::Duration::from_secs_f64(w.pause.max(0.0)),
            frames: w.frames.map(|dir| crate::gui::FrameSeries {
                dir,
                every: std::time::Duration::from_millis(w.frame_every_ms),
                count: w.frame_count,
            }),
            atomic: !w.progressive_switch,
        }
    }
}

/// Arguments of `flexmodes serve`.
#[derive(Debug, Args, Clone)]
pub(super) struct ServeArgs {
    /// Scene ids (default: every scene, unless --file is given).
    pub(super) scenes: Vec<SceneId>,
    /// Serve these `.rrd` files too (each decoded whole first).
    #[arg(long = "file")]
    pub(super) files: Vec<PathBuf>,
    /// The address to listen on: 127.0.0.1 (default) is this machine only; a classroom address
    /// (the teacher's, e.g. 192.168.1.20) lets that network in, 0.0.0.0 every interface.
    /// Anyone who can reach it can watch and load the server.
    #[arg(long, default_value = "127.0.0.1")]
    pub(super) bind: std::net::IpAddr,
    /// The web page's port.
    #[arg(long, default_value_t = 9090)]
    pub(super) port: u16,
    /// The data server's port.
    #[arg(long, default_value_t = 9876)]
    pub(super) grpc_port: u16,
    /// The viewer's theme in the shared URL: dark or light (default: each browser's own).
    #[arg(long, value_enum)]
    pub(super) theme: Option<Theme>,
    /// The token of the teacher's control page (`/control?token=…`), at least 16 URL-safe
    /// characters (default: a random one, printed at start). Without it the page answers 403
    /// and changes nothing.
    #[arg(long, value_name = "TOKEN")]
    pub(super) control_token: Option<String>,
    #[command(flatten)]
    pub(super) options: OptionArgs,
}

/// Scene options shared by `record` and `report`.
#[derive(Debug, Args, Clone, Default)]
pub(super) struct OptionArgs {
    /// Reduction methods, comma separated: nr, gr, mt, cb, mc, eit.
    #[arg(long, value_delimiter = ',')]
    pub(super) method: Option<Vec<Method>>,
    /// Kept normal modes.
    #[arg(long)]
    pub(super) modes: Option<usize>,
    /// Boundary (master, interface) nodes, 1-based, comma separated; with --body also the
    /// names of the body's node sets.
    #[arg(long, value_delimiter = ',')]
    pub(super) boundary: Option<Vec<String>>,
    /// Factor on the drawn elastic deflections of the simulations (default: automatic, the
    /// largest at ~10 % of the body).
    #[arg(long, value_name = "FACTOR")]
    pub(super) deformation_scale: Option<f64>,
    /// A body file (TOML) or `builtin:NAME`, for the `modes` scene.
    #[arg(long)]
    pub(super) body: Option<String>,
    /// Axis type: nodal_fixed, mean, principal.
    #[arg(long)]
    pub(super) axes: Option<AxisKind>,
    /// Reduce the interface to N characteristic constraint modes (Castanier–Tan–Pierre;
    /// `modes --body` only).
    #[arg(long, value_name = "N")]
    pub(super) interface_modes: Option<usize>,
    /// Compare each model's interface response with the full body's from 0 to this
    /// frequency, Hz (`modes --body` only).
    #[arg(long, value_name = "HZ")]
    pub(super) band: Option<f64>,
    /// Simulated interval of the dynamic scenes, s.
    #[arg(long)]
    pub(super) end_time: Option<f64>,
    /// Time-integration scheme of the simulations: dp5 (explicit Dormand–Prince 5(4), adaptive
    /// steps) or gen-alpha (implicit generalized-α, fixed steps).
    #[arg(long)]
    pub(super) integrator: Option<IntegrationScheme>,
    /// Fixed step of the simulations, s: dp5 then runs without error control (how a critical
    /// step is checked); gen-alpha's default is 0.001.
    #[arg(long, value_name = "SECONDS")]
    pub(super) dt: Option<f64>,
    /// Spectral radius ρ∞ of gen-alpha at infinite frequency, in [0, 1] (default 0.8; 1 adds
    /// no numerical damping).
    #[arg(long, value_name = "RHO")]
    pub(super) rho_inf: Option<f64>,
    /// Bricks of the slab mesh along x, y, z (slab-modes; App. B is 4,2,1).
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_refine, allow_hyphen_values = true)]
    pub(super) refine: Option<[usize; 3]>,
    /// Dynamic (geometric) stiffening of the slab simulations' floating frame: on or off
    /// (default off, Lin's thesis' model, which leaves it out).
    #[arg(long, value_enum)]
    pub(super) stiffening: Option<super::body_arguments::OnOff>,
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

impl OptionArgs {
    /// The scene options: the body file loaded and checked, set names resolved to nodes.
    pub(super) fn into_scene_options(self) -> Result<SceneOptions> {
        let body = match &self.body {
            Some(b) => Some(BodyHandle(Arc::new(ImportedBody::load(b)?))),
            None => None,
        };
        let (boundary, rigid_interfaces, averaging_interfaces) = match (&self.boundary, &body) {
            (None, _) => (None, Vec::new(), Vec::new()),
            (Some(items), Some(body)) => {
                let i = crate::models::BodyInterfaces::of(body, items, None)?;
                (Some(i.boundary), i.rigid, i.averaging)
            }
            (Some(items), None) => (Some(parse_nodes(items)?), Vec::new(), Vec::new()),
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
            rigid_interfaces,
            averaging_interfaces,
            interface_modes: self.interface_modes,
            band_hz: self.band,
            axes: self.axes,
            end_time: self.end_time,
            integrator,
            dt: self.dt,
            refine: self.refine,
            deformation_scale: self.deformation_scale,
            body,
            stiffening: self
                .stiffening
                .map(|s| s == super::body_arguments::OnOff::On),
            ..Default::default()
        })
    }
}

/// 1-based node numbers; a name is a node set, which needs a body file: without one, a usage
/// error (exit 2) as any other malformed option.
pub(super) fn parse_nodes(items: &[String]) -> Result<Vec<usize>> {
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

/// The viewer's theme in `serve`'s shared URL.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Theme {
    Dark,
    Light,
}

#[cfg(feature = "serve")]
impl Theme {
    /// As the web viewer's URL takes it.
    pub fn id(self) -> &'static str {
        match self {
            Theme::Dark => "dark",
            Theme::Light => "light",
        }
    }
}

/// `flexmodes bench`'s arguments.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Scenes: slab-modes, slab-sim1, slab-sim2 (default: slab-sim1).
    pub(super) scenes: Vec<String>,
    /// Every scene bench measures: slab-modes, slab-sim1, slab-sim2.
    #[arg(long, conflicts_with = "scenes")]
    pub(super) all: bool,
    /// Print one JSON object per scene.
    #[arg(long)]
    pub(super) json: bool,
    /// Refined meshes to time, `1k,7k,28k,74k,150k` or `NXxNYxNZ,...`: slab-modes'
    /// offline cost, or one simulation's online cost, against DOF.
    #[arg(long)]
    pub(super) sizes: Option<String>,
    /// Also write the charts to this `.rrd`: with --sizes time against DOF, else error
    /// against cost and against kept modes of one simulation bench.
    #[arg(long)]
    pub(super) save: Option<PathBuf>,
    /// Integrators to compare, comma separated (default: dp5,gen-alpha).
    #[arg(long, value_delimiter = ',')]
    pub(super) integrator: Vec<IntegrationScheme>,
    /// Runs of each simulation or export (default 3), or of each size and thread count
    /// with --sizes (default 1); the median is reported.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100))]
    pub(super) repeats: Option<u64>,
    /// Simulations on the slab meshed with NX × NY × NZ bricks (App. B is 4,2,1).
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_refine, allow_hyphen_values = true)]
    pub(super) refine: Option<[usize; 3]>,
    /// A body file: with no scene, time `export --method cb` of it as a whole process
    /// against SciPy's CHOLMOD route (the peer script) in the same run; with the scene
    /// `modes`, chart every method and kept-mode count on it (offline time, peak memory,
    /// frequency error, Pareto front, mode-count advice); with `simulate` (and --drive),
    /// time the full body's driven spin-up per step against CB's.
    #[arg(long, conflicts_with_all = ["all", "sizes", "refine"])]
    pub(super) body: Option<PathBuf>,
    /// With --body: the interface (node set names, node numbers, `rbe2:SET`).
    #[arg(long, value_delimiter = ',', requires = "body")]
    pub(super) boundary: Option<Vec<String>>,
    /// With --body: kept modes (export: one count, default 10; modes: the counts to
    /// chart, default 4,8,16,32).
    #[arg(long, value_delimiter = ',', requires = "body")]
    pub(super) modes: Vec<usize>,
    /// With `modes --body`: methods to chart (default: all eight).
    #[arg(long, value_delimiter = ',', requires = "body")]
    pub(super) method: Vec<Method>,
    /// With `modes --body`: top of the frequency band, Hz; every full-body mode up to it
    /// is compared (default: the lowest six elastic modes).
    #[arg(long, value_name = "HZ", requires = "body")]
    pub(super) band: Option<f64>,
    /// With `modes --body`: the relative frequency error the advice asks of a model.
    #[arg(long, default_value_t = 0.01, requires = "body")]
    pub(super) tolerance: f64,
    /// With `modes --body`: reduce the interface to N characteristic constraint modes.
    #[arg(long, value_name = "N", requires = "body")]
    pub(super) interface_modes: Option<usize>,
    /// With `simulate --body`: the driven interface (`rbe2:SET`).
    #[arg(long, requires = "body")]
    pub(super) drive: Option<String>,
    /// With `simulate --body`: the same part meshed finer, each timed like --body to chart
    /// the full body's cost against DOF.
    #[arg(long, value_delimiter = ',', requires = "drive")]
    pub(super) larger: Vec<PathBuf>,
    /// With `slab-modes --sizes`: time the free slab's lowest free-free pairs by these
    /// eigensolvers instead of the reductions (`amls,lanczos`), each after the other in one
    /// process, with its peak memory.
    #[arg(long, value_delimiter = ',', requires = "sizes")]
    pub(super) eigensolver: Vec<Eigensolver>,
    /// With --eigensolver: the elastic pairs asked of each (default 50).
    #[arg(long, requires = "eigensolver")]
    pub(super) pairs: Option<usize>,
    /// With --body: the SciPy peer script.
    #[arg(
        long,
        default_value = "../shared/bench/peers_body_cb.py",
        requires = "body"
    )]
    pub(super) peer: PathBuf,
}
