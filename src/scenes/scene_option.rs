//! The one table of which options each scene takes: every option a scene can be run with,
//! how a user names it, whether it was given, and whether a scene's controls offer it. The
//! registry refuses what a scene does not offer before it runs; the command line, the
//! explorer's panel, the classroom's control page and `flexmodes list` read the same table.

use crate::scenes::{SceneControls, SceneOptions};
use crate::{dynamics::AxisKind, reduction::Method as ReductionMethod};

/// An option a scene may be run with, as the command line names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SceneOption {
    /// `--method`: which methods to compute and show.
    Method,
    /// `--modes`: kept normal modes.
    Modes,
    /// `--boundary`: boundary (master) nodes, or a body's node sets.
    Boundary,
    /// `--axes`: the floating frame's axes.
    Axes,
    /// `--end-time`: the simulated interval.
    EndTime,
    /// `--integrator`, `--dt` and `--rho-inf`: the time integration.
    Integrator,
    /// `--deformation-scale`: the drawn deflections' factor.
    DeformationScale,
    /// `--refine`: the slab's mesh.
    Refine,
    /// `--stiffening`: the floating frame's dynamic stiffening.
    Stiffening,
    /// `--body`: a body from a body file.
    Body,
    /// `--band`: interface responses compared up to a frequency.
    Band,
    /// `--interface-modes`: characteristic constraint modes of the interface.
    InterfaceModes,
    /// `simulate`: the body driven through one of its interfaces.
    Simulate,
}

impl SceneOption {
    /// Every option, in the order the command line's help lists them.
    pub const ALL: [SceneOption; 13] = [
        SceneOption::Method,
        SceneOption::Modes,
        SceneOption::Boundary,
        SceneOption::Axes,
        SceneOption::EndTime,
        SceneOption::Integrator,
        SceneOption::DeformationScale,
        SceneOption::Refine,
        SceneOption::Stiffening,
        SceneOption::Body,
        SceneOption::Band,
        SceneOption::InterfaceModes,
        SceneOption::Simulate,
    ];

    /// The option as a user types it (`--end-time`; `simulate` is a command).
    pub const fn flag(self) -> &'static str {
        match self {
            SceneOption::Method => "--method",
            SceneOption::Modes => "--modes",
            SceneOption::Boundary => "--boundary",
            SceneOption::Axes => "--axes",
            SceneOption::EndTime => "--end-time",
            SceneOption::Integrator => "--integrator",
            SceneOption::DeformationScale => "--deformation-scale",
            SceneOption::Refine => "--refine",
            SceneOption::Stiffening => "--stiffening",
            SceneOption::Body => "--body",
            SceneOption::Band => "--band",
            SceneOption::InterfaceModes => "--interface-modes",
            SceneOption::Simulate => "simulate",
        }
    }

    /// What the option's value looks like, as a form shows it beside the field (the method
    /// and axis ids from their own lists).
    pub fn hint(self) -> String {
        let ids = |ids: Vec<&str>| ids.join(",");
        match self {
            SceneOption::Method => format!(
                "{} (comma separated)",
                ids(ReductionMethod::ALL.iter().map(|m| m.id()).collect())
            ),
            SceneOption::Axes => format!(
                "one of {}",
                ids(AxisKind::ALL.iter().map(|a| a.id()).collect())
            ),
            other => other.fixed_hint().into(),
        }
    }

    /// The hint of an option whose values are not a list of ids.
    const fn fixed_hint(self) -> &'static str {
        match self {
            SceneOption::Method | SceneOption::Axes => "",
            SceneOption::Modes => "kept normal modes",
            SceneOption::Boundary => "nodes or node sets, comma separated",
            SceneOption::EndTime => "simulated seconds",
            SceneOption::Integrator => "dp5 or gen-alpha",
            SceneOption::DeformationScale => "factor on drawn deflections (0: none)",
            SceneOption::Refine => "NX,NY,NZ",
            SceneOption::Stiffening => "on or off",
            SceneOption::Body => "a body file or builtin:NAME",
            SceneOption::Band => "highest compared frequency, Hz",
            SceneOption::InterfaceModes => "characteristic constraint modes kept",
            SceneOption::Simulate => "a drive through one interface",
        }
    }

    /// Whether `options` set it (rather than leaving the scene's default).
    pub fn given(self, options: &SceneOptions) -> bool {
        match self {
            SceneOption::Method => options.methods.is_some(),
            SceneOption::Modes => options.modes.is_some(),
            SceneOption::Boundary => {
                options.boundary.is_some()
                    || !options.rigid_interfaces.is_empty()
                    || !options.averaging_interfaces.is_empty()
            }
            SceneOption::Axes => options.axes.is_some(),
            SceneOption::EndTime => options.end_time.is_some(),
            SceneOption::Integrator => options.integrator.is_some() || options.dt.is_some(),
            SceneOption::DeformationScale => options.deformation_scale.is_some(),
            SceneOption::Refine => options.refine.is_some(),
            SceneOption::Stiffening => options.stiffening.is_some(),
            SceneOption::Body => options.body.is_some(),
            SceneOption::Band => options.band_hz.is_some(),
            SceneOption::InterfaceModes => options.interface_modes.is_some(),
            SceneOption::Simulate => options.simulation.is_some(),
        }
    }

    /// Whether a scene with `controls` takes it: the table itself.
    pub fn offered_by(self, controls: &SceneControls) -> bool {
        let simulates = controls.end_time.is_some();
        match self {
            SceneOption::Method => !controls.methods.is_empty(),
            SceneOption::Modes => controls.modes.is_some(),
            SceneOption::Boundary => !controls.boundary.is_empty() || controls.body,
            SceneOption::Axes => !controls.axes.is_empty(),
            SceneOption::EndTime | SceneOption::Integrator | SceneOption::DeformationScale => {
                simulates
            }
            SceneOption::Refine => controls.refine.is_some(),
            SceneOption::Stiffening => controls.stiffening,
            SceneOption::Body
            | SceneOption::Band
            | SceneOption::InterfaceModes
            | SceneOption::Simulate => controls.body,
        }
    }
}

impl std::fmt::Display for SceneOption {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.flag())
    }
}
