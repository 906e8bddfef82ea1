//! The arguments of the commands on a user's body: `simulate`, `campbell` and `export`, and
//! the small types they share (an X,Y,Z option, an on/off switch, the drive's motion).

use std::path::PathBuf;

use clap::Args;

use crate::reduction::Method;

/// What `simulate` and `campbell` share: a body spun about an axis through its driven
/// interface, with or without its preloaded stiffness.
#[derive(Debug, Args)]
pub(super) struct SpinningBodyArgs {
    /// The body file (TOML), or `builtin:NAME`.
    #[arg(long)]
    pub(super) body: String,
    /// The driven interface, `rbe2:SET` or an rbe2 interface of the body file: its master
    /// follows the frame, its ring clamped in the turning frame.
    #[arg(long)]
    pub(super) drive: String,
    /// Spin axis in body axes, X,Y,Z.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0,0,1",
        allow_hyphen_values = true
    )]
    pub(super) axis: Vec<f64>,
    /// A point of the spin axis, X,Y,Z in the body's length unit (default: the axis the
    /// body's [preload] was spun about when the drive's ring is coaxial with it, else the
    /// drive's master; elsewhere the drive orbits the axis).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(super) axis_point: Option<Vec<f64>>,
    /// Dynamic stiffening from the body's preloaded stiffness (`[preload]` in the body file):
    /// on (default) or off.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub(super) stiffening: OnOff,
    /// Residual vectors of the frame's inertia loads in every reduced basis (the static
    /// responses to its unit linear and angular accelerations and ω_iω_j, the body held at
    /// its interfaces): on (default) or off.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub(super) residual_vectors: OnOff,
}

/// The arguments of `simulate`.
#[derive(Debug, Args)]
pub(super) struct SimulateArgs {
    #[command(flatten)]
    pub(super) spin: SpinningBodyArgs,
    /// Other interfaces the reduced models keep (node sets, `rbe2:SET`), free in the
    /// simulation.
    #[arg(long, value_delimiter = ',')]
    pub(super) boundary: Vec<String>,
    /// Node sets pinned to the carrier (rbe2 rings whose masters keep their place in the
    /// turning frame and turn freely), comma separated.
    #[arg(long, value_delimiter = ',')]
    pub(super) pinned: Vec<String>,
    /// Node sets whose mean displacement is the history, or `node:N` (default: every set but
    /// the drive's and the pinned ones; without such sets, the node farthest from the drive).
    #[arg(long, value_delimiter = ',')]
    pub(super) output: Vec<String>,
    /// Models: nr (the full body) and gr, mt, cb, mc.
    #[arg(long, value_delimiter = ',', default_value = "nr,cb,mc")]
    pub(super) method: Vec<Method>,
    /// Kept fixed-interface modes, one model per count.
    #[arg(long, value_delimiter = ',', default_value = "10")]
    pub(super) modes: Vec<usize>,
    /// The motion: `spin-up` (about --axis through --axis-point, default the drive's
    /// master: elsewhere the drive orbits the axis) or `shake` (a harmonic translation of
    /// the drive along --direction, no turning).
    #[arg(long, value_enum, default_value_t = Motion::SpinUp)]
    pub(super) motion: Motion,
    /// With shake: the direction in ground axes, X,Y,Z.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1,0,0",
        allow_hyphen_values = true
    )]
    pub(super) direction: Vec<f64>,
    /// With shake: the amplitude, m.
    #[arg(long, default_value_t = 1e-3)]
    pub(super) amplitude: f64,
    /// With shake: the frequency, Hz.
    #[arg(long, default_value_t = 50.0)]
    pub(super) frequency: f64,
    /// Steady spin rate, rad/s.
    #[arg(long, default_value_t = 100.0)]
    pub(super) rate: f64,
    /// Ramp time of the spin-up, s.
    #[arg(long, default_value_t = 0.5)]
    pub(super) ramp: f64,
    /// End time, s.
    #[arg(long, default_value_t = 1.0)]
    pub(super) end: f64,
    /// Step of generalized-α, s.
    #[arg(long, default_value_t = 1e-3)]
    pub(super) dt: f64,
    /// Spectral radius at infinite frequency of generalized-α.
    #[arg(long, default_value_t = 0.9)]
    pub(super) rho: f64,
    /// Samples of the history (evenly spaced over the steps).
    #[arg(long, default_value_t = 100)]
    pub(super) samples: usize,
    /// Gravity in ground axes, m/s², X,Y,Z (default: off).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(super) gravity: Option<Vec<f64>>,
    /// Print the results as JSON.
    #[arg(long)]
    pub(super) json: bool,
    /// Also write the recording (the body deforming per model, the histories, the chart)
    /// to this `.rrd`.
    #[arg(long)]
    pub(super) save: Option<PathBuf>,
    /// The axes the histories are seen from: `nodal_fixed` (the drive's frame) or `mean`
    /// (the body's mean axes: the same motion with its rigid part in the mass metric removed).
    #[arg(long, default_value = "nodal_fixed")]
    pub(super) axes: crate::dynamics::AxisKind,
    /// Also run each reduced model with explicit Dormand–Prince steps below its critical
    /// step (predicted from its highest frequency), and check that 3× that step diverges.
    #[arg(long)]
    pub(super) explicit: bool,
}

/// The arguments of `campbell`.
#[derive(Debug, Args)]
pub(super) struct CampbellArgs {
    #[command(flatten)]
    pub(super) spin: SpinningBodyArgs,
    /// Rates, rad/s.
    #[arg(long, value_delimiter = ',', default_value = "0,500,1000,1500,2000")]
    pub(super) rates: Vec<f64>,
    /// Frequencies per rate.
    #[arg(long, default_value_t = 4)]
    pub(super) count: usize,
    /// Models: nr and gr, mt, cb, mc.
    #[arg(long, value_delimiter = ',', default_value = "nr,cb")]
    pub(super) method: Vec<Method>,
    /// Kept modes of the reduced models, one model per count.
    #[arg(long, value_delimiter = ',', default_value = "10")]
    pub(super) modes: Vec<usize>,
    /// Print the table as JSON.
    #[arg(long)]
    pub(super) json: bool,
}

/// An option's three numbers `X,Y,Z` (an axis, a point, a direction), or a usage error naming
/// the option.
pub(super) fn three_numbers(option: &'static str, v: &[f64]) -> crate::Result<[f64; 3]> {
    match v {
        [x, y, z] => Ok([*x, *y, *z]),
        _ => Err(crate::Error::InvalidOption {
            option,
            scene: None,
            reason: format!("takes three numbers X,Y,Z, not {}", v.len()),
        }),
    }
}

/// A switch typed on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(super) enum OnOff {
    /// On.
    On,
    /// Off.
    Off,
}

/// How `simulate --body` drives its interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Motion {
    /// A spin-up about --axis through --axis-point.
    SpinUp,
    /// A harmonic translation along --direction, no turning.
    Shake,
}

/// `flexmodes export`'s arguments.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// The body file (TOML), or `builtin:NAME`.
    #[arg(long)]
    pub(super) body: String,
    /// The reduction: gr, mt, cb, mc.
    #[arg(long)]
    pub(super) method: Method,
    /// Interface: node set names or 1-based nodes, comma separated; `rbe2:SET` ties the
    /// set rigidly to one 6-DOF master node at its centroid (default: the body's default
    /// interface).
    #[arg(long, value_delimiter = ',')]
    pub(super) boundary: Option<Vec<String>>,
    /// Kept fixed-interface normal modes (mt, cb, mc).
    #[arg(long, default_value_t = 10)]
    pub(super) modes: usize,
    /// Destination folder (replaced as a whole once everything is written).
    #[arg(long)]
    pub(super) out: PathBuf,
    /// The format of Ψ: `npy` (binary, numpy.load) or `mtx` (Matrix Market array text).
    #[arg(long, default_value = "npy")]
    pub(super) psi_format: crate::export::PsiFormat,
    /// Reduce the interface to this many characteristic constraint modes (Castanier–Tan–
    /// Pierre; CB and GR on plain node sets).
    #[arg(long, value_name = "N")]
    pub(super) interface_modes: Option<usize>,
    /// Also write the body for Exudyn in `OUT/exudyn/` (nodes, full M and K, the mode
    /// basis without the first rbe2 interface's rigid motions: the floating frame is
    /// attached there); `assets/python/flexmodes_exudyn.py` loads it.
    #[arg(long)]
    pub(super) exudyn: bool,
    /// Print the wall time of each phase on stderr, and the process's peak resident memory.
    #[arg(long)]
    pub(super) timings: bool,
    /// With a body file's `[preload]`: also write its geometric stiffness per unit rate²
    /// projected on Ψ (`kg_r.mtx`, named in model.json): on (default) or off.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub(super) stiffening: OnOff,
    /// Residual vectors of the frame's inertia loads appended to a fixed-interface basis
    /// (GR, MT, CB, MC; named in model.json, carried by the Exudyn export): on (default) or
    /// off.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub(super) residual_vectors: OnOff,
    /// The solver of the fixed-interface pairs (bodies whose interior exceeds 600 DOF) and of
    /// the free-free pairs BH, MM and BT start from: `lanczos` (default) or `amls`
    /// (multi-level substructuring, refined and Sturm-counted; docs/amls.md). model.json
    /// names it.
    #[arg(long, default_value = "lanczos")]
    pub(super) eigensolver: crate::reduction::Eigensolver,
}
